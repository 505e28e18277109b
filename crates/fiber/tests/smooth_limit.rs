//! The smooth limit (issue 2): with β tiny and α = 0, d'Eon 2011's per-lobe energies and
//! azimuthal distributions N_p match an exact 3D ray trace through a smooth dielectric cylinder
//! (written here, independent of the model's formulas: vector Snell refraction, the Fresnel
//! factor at each hit's own incidence angle, Beer–Lambert along each chord) within 2 %, away
//! from the TRT caustics; and every traced path leaves on the cone θ_o = −θ_i.

use cuticle_fiber::math::GaussLegendre;
use cuticle_fiber::models::deon2011::azimuthal::{AzimuthalScattering, Weighting};
use cuticle_fiber::optics::fresnel::fresnel_dielectric;
use cuticle_fiber::{FiberAngles, wrap_pi};
use glam::DVec3;
use std::f64::consts::PI;

const BINS: usize = 72;
const LOBES: usize = 4;

/// Per lobe (R, TT, TRT, TRRT) the energy falling in each φ bin, from `rays` offsets h at the
/// midpoints of equal strata of [−1, 1].
fn ray_trace(theta_i: f64, eta: f64, mu_a: f64, rays: usize) -> [[f64; BINS]; LOBES] {
    let mut bins = [[0.0; BINS]; LOBES];
    let wi = FiberAngles::new(theta_i, 0.0).to_dir();
    for k in 0..rays {
        let h = -1.0 + 2.0 * (k as f64 + 0.5) / rays as f64;
        // The ray travels along −ω_i; in the normal plane it meets the unit circle at (y, z).
        let mut pos = DVec3::new(0.0, (1.0 - h * h).sqrt(), h);
        let mut dir = -wi;
        let mut weight = 1.0;
        let normal = DVec3::new(0.0, pos.y, pos.z);
        let f = fresnel_dielectric(-dir.dot(normal), eta);
        deposit(&mut bins[0], reflect(dir, normal), weight * f, theta_i);
        weight *= 1.0 - f;
        dir = refract(dir, normal, 1.0 / eta);
        for bin in bins.iter_mut().skip(1) {
            let next = exit_point(pos, dir);
            weight *= (-mu_a * (next - pos).length()).exp();
            pos = next;
            let outward = DVec3::new(0.0, pos.y, pos.z);
            let f = fresnel_dielectric(dir.dot(outward), 1.0 / eta);
            if f < 1.0 {
                deposit(
                    bin,
                    refract(dir, -outward, eta),
                    weight * (1.0 - f),
                    theta_i,
                );
            }
            weight *= f;
            dir = reflect(dir, outward);
        }
    }
    bins.map(|b| b.map(|v| v / rays as f64))
}

/// Where a ray inside the unit cylinder leaves it.
fn exit_point(pos: DVec3, dir: DVec3) -> DVec3 {
    let (py, pz, dy, dz) = (pos.y, pos.z, dir.y, dir.z);
    let a = dy * dy + dz * dz;
    let b = 2.0 * (py * dy + pz * dz);
    let c = py * py + pz * pz - 1.0;
    let t = (-b + (b * b - 4.0 * a * c).max(0.0).sqrt()) / (2.0 * a);
    pos + dir * t
}

fn reflect(d: DVec3, n: DVec3) -> DVec3 {
    d - 2.0 * d.dot(n) * n
}

/// Refraction of direction `d` through a surface with normal `n` (facing against `d`), with
/// `ratio` = n_incident / n_transmitted.
fn refract(d: DVec3, n: DVec3, ratio: f64) -> DVec3 {
    let cos_i = -d.dot(n);
    let k = 1.0 - ratio * ratio * (1.0 - cos_i * cos_i);
    ratio * d + (ratio * cos_i - k.max(0.0).sqrt()) * n
}

fn deposit(bins: &mut [f64; BINS], out: DVec3, w: f64, theta_i: f64) {
    let a = FiberAngles::from_dir(out);
    assert!(
        (a.theta + theta_i).abs() < 1e-9,
        "left at θ {} for θ_i {theta_i}",
        a.theta
    );
    let b = ((wrap_pi(a.phi) + PI) / (2.0 * PI) * BINS as f64) as usize;
    bins[b.min(BINS - 1)] += w;
}

/// The model's N_p integrated over each φ bin.
fn model_bins(az: &AzimuthalScattering, p: usize, theta_i: f64) -> [f64; BINS] {
    let rule = GaussLegendre::cached(24);
    std::array::from_fn(|b| {
        let lo = -PI + 2.0 * PI * b as f64 / BINS as f64;
        let hi = lo + 2.0 * PI / BINS as f64;
        let sub = 4;
        (0..sub)
            .map(|s| {
                let a = lo + (hi - lo) * s as f64 / sub as f64;
                rule.integrate(a, a + (hi - lo) / sub as f64, |phi| {
                    az.eval(p, theta_i, -theta_i, phi, Weighting::Attenuation).x
                })
            })
            .sum()
    })
}

/// φ bins holding a TRT caustic (where dΦ(2, h)/dh = 0) and their neighbours.
fn near_trt_caustic(bin: usize, theta_i: f64, eta: f64) -> bool {
    let eta_p = cuticle_fiber::geometry::bravais::eta_prime(eta, theta_i);
    if eta_p >= 2.0 {
        return false;
    }
    // dΦ/dγ = 4 cos γ / (η′ cos γ_t) − 2 = 0 at cos²γ = (η′² − 1)/3.
    let gamma = ((eta_p * eta_p - 1.0) / 3.0).sqrt().acos();
    let phi_c = wrap_pi(cuticle_fiber::geometry::bravais::azimuthal_deflection(
        2,
        gamma.sin(),
        eta_p,
    ));
    [phi_c, -phi_c].iter().any(|&pc| {
        let b = ((pc + PI) / (2.0 * PI) * BINS as f64) as isize;
        (bin as isize - b).abs() <= 2
    })
}

#[test]
fn deon2011_matches_an_exact_ray_trace_in_the_smooth_limit() {
    let (eta, beta, mu_a) = (1.55, 0.002, 0.3);
    for theta_i in [0.0, 0.6, 1.1] {
        let traced = ray_trace(theta_i, eta, mu_a, 400_000);
        let az = AzimuthalScattering::new(eta, beta, DVec3::splat(mu_a));
        for (p, trace) in traced.iter().enumerate() {
            let model = model_bins(&az, p, theta_i);
            let (e_trace, e_model): (f64, f64) = (trace.iter().sum(), model.iter().sum());
            assert!(
                (e_model - e_trace).abs() < 0.02 * e_trace,
                "θ_i {theta_i} p {p}: energy {e_model} vs {e_trace}"
            );
            let peak = trace.iter().cloned().fold(0.0, f64::max);
            for b in 0..BINS {
                if p == 2 && near_trt_caustic(b, theta_i, eta) || trace[b] < 0.05 * peak {
                    continue;
                }
                let (t, m) = (trace[b], model[b]);
                assert!(
                    (m - t).abs() < 0.02 * t,
                    "θ_i {theta_i} p {p} bin {b}: model {m} vs trace {t}"
                );
            }
        }
    }
}
