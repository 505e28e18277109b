//! SRBF single scattering (Xu et al. 2011 eq. 11) against the exact Marschner 2003 model of the
//! fiber crate — the model `--method brute` and the path tracer render — under one SRBF light,
//! mode by mode. The reference integrates the model against the SRBF itself,
//! L_o = ∫ S_p(ω→ω_o) G(ω) cos θ / cos θ_o dω / ∫ G dω, G = exp(2(ω·ξ − 1)/λ²), by quadrature in
//! polar coordinates about the light's centre ξ, so a narrow light is the directional light's
//! limit and a wide one is compared with the same blur the SRBF path applies.

use cuticle_fiber::{FiberAngles, FiberModel, Marschner2003};
use cuticle_render::Renderer;
use cuticle_render::scene::hair::HairParams;
use cuticle_render::srbf::single_scattering::{LocalLight, ShadingFiber, modes};
use glam::DVec3;
use std::f64::consts::PI;

/// Per lobe, the model's L_o under a unit-power SRBF light of bandwidth λ at (θ_j, 0).
fn exact(model: &Marschner2003, theta_j: f64, lambda: f64, ao: FiberAngles) -> [DVec3; 3] {
    let xi = FiberAngles::new(theta_j, 0.0).to_dir();
    let t1 = xi.any_orthonormal_vector();
    let t2 = xi.cross(t1);
    let reach = (6.0 * lambda).min(PI);
    let rule = cuticle_fiber::math::GaussLegendre::cached(24);
    let (panels, around) = (6, 256);
    let mut sum = [DVec3::ZERO; 3];
    let mut z = 0.0;
    for panel in 0..panels {
        let a = reach * panel as f64 / panels as f64;
        let step = reach / panels as f64;
        for (x, w) in rule.nodes.iter().zip(&rule.weights) {
            let psi = a + 0.5 * step * (x + 1.0);
            let g = (2.0 * (psi.cos() - 1.0) / (lambda * lambda)).exp();
            let weight = 0.5 * step * w * psi.sin() * g * 2.0 * PI / around as f64;
            for k in 0..around {
                let chi = 2.0 * PI * (k as f64 + 0.5) / around as f64;
                let dir = psi.cos() * xi + psi.sin() * (chi.cos() * t1 + chi.sin() * t2);
                let ai = FiberAngles::from_dir(dir);
                z += weight;
                let s = model.eval(ai, ao).0;
                let f = weight * ai.theta.cos() / ao.theta.cos();
                for p in 0..3 {
                    sum[p] += s[p] * f;
                }
            }
        }
    }
    sum.map(|v| v / z)
}

struct Sweep {
    /// Worst |srbf − exact| per mode over the sweep, relative to the mode's largest exact value
    /// over the sweep.
    worst: [f64; 3],
    /// Worst ratio of the summed modes, srbf / exact, where the total is at least a tenth of
    /// the sweep's largest.
    total: (f64, f64),
}

/// θ_o, θ_i pairs: at the R peak (θ_i = 2α_R − θ_o), the slab test's view, and off-peak; φ from
/// front to back.
fn sweep(lambda: f64) -> Sweep {
    let r = Renderer::new();
    let fiber = HairParams::default().fiber(None);
    let lobes = r.lobe_table(&fiber);
    let lobes = lobes.for_fiber(&r.tables, &fiber);
    let shading = ShadingFiber {
        params: &fiber,
        lobes: &lobes,
    };
    let model = Marschner2003::new(fiber).unwrap();
    let peak = 2.0 * fiber.alpha_r;
    let mut error = [0.0f64; 3];
    let mut peak_mode = [0.0f64; 3];
    let mut total = (f64::INFINITY, 0.0f64);
    for (theta_o, theta_i) in [(0.0, peak), (0.4, peak - 0.4), (-0.2, 0.3), (0.2, 0.2)] {
        let phis = [0.0, 0.4, 0.9, 1.5, 2.2, 2.8, PI];
        let rows: Vec<([DVec3; 3], [DVec3; 3])> = phis
            .iter()
            .map(|&phi| {
                let light = LocalLight {
                    theta: theta_i,
                    phi: 0.0,
                    bandwidth: lambda,
                    radiance: DVec3::ONE,
                };
                let unit = 1.0 / cuticle_render::srbf::dual_scattering::srbf_integral(lambda);
                let srbf = modes(&r.tables, shading, theta_o, phi, &light, 4).map(|m| m * unit);
                let want = exact(&model, theta_i, lambda, FiberAngles::new(theta_o, phi));
                (srbf, want)
            })
            .collect();
        let sum = |m: &[DVec3; 3]| m[0] + m[1] + m[2];
        let largest = rows
            .iter()
            .map(|(_, e)| sum(e).max_element())
            .fold(0.0, f64::max);
        for (s, e) in &rows {
            for p in 0..3 {
                error[p] = error[p].max((s[p] - e[p]).abs().max_element());
                peak_mode[p] = peak_mode[p].max(e[p].max_element());
            }
            let (ts, te) = (sum(s), sum(e));
            for c in 0..3 {
                if te[c] >= 0.1 * largest {
                    let ratio = ts[c] / te[c];
                    total = (total.0.min(ratio), total.1.max(ratio));
                }
            }
        }
    }
    Sweep {
        worst: std::array::from_fn(|p| error[p] / peak_mode[p]),
        total,
    }
}

fn check(s: &Sweep, bounds: [f64; 3], total: (f64, f64), what: &str) {
    eprintln!("{what}: worst per mode {:?}, total {:?}", s.worst, s.total);
    for (p, name) in ["R", "TT", "TRT"].iter().enumerate() {
        assert!(
            s.worst[p] <= bounds[p],
            "{what}: {name} errs by {:.3} of its peak (bound {})",
            s.worst[p],
            bounds[p]
        );
    }
    assert!(
        s.total.0 >= total.0 && s.total.1 <= total.1,
        "{what}: srbf / exact over the modes {:?}, bounds {total:?}",
        s.total
    );
}

/// A narrow light (λ = 0.05, the slab test's stand-in for a directional light), per mode, worst
/// error relative to the mode's peak over four views × seven azimuths (at the R peak, off it,
/// the slab test's view, and a forward view): TRT within 8 % (measured 4.6 %; carrying Xu et al.
/// 2011's bare ∫ N_P instead of the model's caustic-treated N_TRT gave 64 %), TT within 8 %
/// (measured 5.9 %: one circular Gaussian at π for the cubic deflection's N_TT), R within 3 %
/// (measured 0.7 % with the model's own Fresnel fitted per (η, θ_d), tables/r_fresnel.rs;
/// Schlick's polynomial, Xu et al. 2011 eq. 13, was 15.5 % low at φ ≈ 1.5–2.2). The modes'
/// sum, where it is at least a tenth of its sweep's largest: 0.88–1.07 of the model (measured
/// 0.93–1.02; 0.79–1.09 with Schlick's R, 1.16 with the bare ∫ N_P).
#[test]
fn narrow_light_matches_the_exact_model_per_mode() {
    let s = sweep(0.05);
    check(&s, [0.03, 0.08, 0.08], (0.88, 1.07), "λ = 0.05");
}

/// A wide light (λ = 0.3), the same sweep: TRT within 5 % (measured 2.5 %; 76 % with the bare
/// ∫ N_P), TT within 8 % (3.4 %), R within 3 % (1.4 %; 16.9 % with Schlick's); the sum
/// 0.90–1.05 (measured 0.95–1.02; 0.85–1.01 with Schlick's R, 1.16 with the bare ∫ N_P).
#[test]
fn wide_light_matches_the_exact_model_per_mode() {
    let s = sweep(0.3);
    check(&s, [0.03, 0.08, 0.05], (0.90, 1.05), "λ = 0.3");
}

/// A narrow light (λ = 0.01, a sun of the fitted default sky) beside a fiber seen from the
/// front (θ_o = 0, θ_i = 0.3, φ = 1, 1.25, 1.5 about TT's deflection limit φ ≈ 1.40, below
/// which the model's N_TT is 0): the modes' sum at φ = 1 within 0.75–1.3 of the exact model's,
/// and summed over the three azimuths at most 2.5× it per channel (measured 1.25× at φ = 1,
/// 2.3× summed in red: the pair still leaks a little just inside the limit). Xu et al. 2011 eq.
/// 16's single TT Gaussian gave 2.05× at φ = 1 and 5.3× at φ = 1.5 (its tail past the limit).
#[test]
fn a_light_beside_the_fiber_sees_no_tt_past_its_limit() {
    let r = Renderer::new();
    let fiber = HairParams::default().fiber(None);
    let lobes = r.lobe_table(&fiber);
    let lobes = lobes.for_fiber(&r.tables, &fiber);
    let shading = ShadingFiber {
        params: &fiber,
        lobes: &lobes,
    };
    let model = Marschner2003::new(fiber).unwrap();
    let lambda = 0.01;
    let unit = 1.0 / cuticle_render::srbf::dual_scattering::srbf_integral(lambda);
    let light = LocalLight {
        theta: 0.3,
        phi: 0.0,
        bandwidth: lambda,
        radiance: DVec3::ONE,
    };
    let (mut got, mut want) = (DVec3::ZERO, DVec3::ZERO);
    for phi in [1.0, 1.25, 1.5] {
        let ao = FiberAngles::new(0.0, phi);
        let srbf: DVec3 = modes(&r.tables, shading, ao.theta, phi, &light, 4)
            .iter()
            .map(|m| *m * unit)
            .sum();
        let exact: DVec3 = exact(&model, 0.3, lambda, ao).iter().sum();
        eprintln!("φ {phi}: srbf / exact {}", srbf / exact);
        if phi == 1.0 {
            let ratio = srbf / exact;
            assert!(
                ratio.min_element() >= 0.75 && ratio.max_element() <= 1.3,
                "φ {phi}: srbf / exact {ratio}"
            );
        }
        got += srbf;
        want += exact;
    }
    eprintln!("over the three azimuths: srbf / exact {}", got / want);
    assert!(
        (got / want).max_element() <= 2.5,
        "over the three azimuths: srbf / exact {}",
        got / want
    );
}
