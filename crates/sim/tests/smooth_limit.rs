//! The smooth limit: at β = 0.0025 and α = 0 the simulator must reproduce the exact
//! smooth-cylinder energies, A(p, h) averaged over h (Marschner 2003 with the exact 3D Fresnel and
//! docs/conventions.md §8's T = exp(−2 μ_a cos γ_t / cos θ_t)), and put every lobe at θ_o = −θ_i.

use cuticle_sim::{SimParams, SimResult, simulate};
use glam::DVec3;

/// Unpolarised Fresnel reflectance by the s/p equations (Born & Wolf §1.5), independent of the
/// crate's Walter form.
fn fresnel(cos_i: f64, eta: f64) -> f64 {
    let sin_t = (1.0 - cos_i * cos_i).max(0.0).sqrt() / eta;
    let cos_t = (1.0 - sin_t * sin_t).sqrt();
    let rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    let rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    0.5 * (rs * rs + rp * rp)
}

/// The exact per-lobe energies [R, TT, TRT, TRRT, rest] of a smooth cylinder, channel by
/// channel: ½∫A(p, h) dh by the midpoint rule with `n` nodes. A(0, h) = F and
/// A(p, h) = (1 − F)² F^(p−1) T^p, with F at the 3D incidence cosine cos θ_i cos γ_i (the same at
/// every internal event) and T = exp(−2 μ_a cos γ_t / cos θ_t), γ_t from Bravais' η'.
fn smooth_energies(theta_i: f64, eta: f64, mu_a: f64, n: usize) -> [f64; 5] {
    let sin_theta_t = theta_i.sin() / eta;
    let cos_theta_t = (1.0 - sin_theta_t * sin_theta_t).sqrt();
    let eta_p = (eta * eta - theta_i.sin().powi(2)).sqrt() / theta_i.cos();
    let mut e = [0.0; 5];
    for k in 0..n {
        let h = -1.0 + 2.0 * (k as f64 + 0.5) / n as f64;
        let f = fresnel(theta_i.cos() * (1.0 - h * h).sqrt(), eta);
        let cos_gamma_t = (1.0 - (h / eta_p).powi(2)).sqrt();
        let t = (-2.0 * mu_a * cos_gamma_t / cos_theta_t).exp();
        let tt = (1.0 - f) * (1.0 - f);
        let a = [
            f,
            tt * t,
            tt * f * t * t,
            tt * f * f * t * t * t,
            tt * f.powi(3) * t.powi(4) / (1.0 - f * t),
        ];
        for (ep, ap) in e.iter_mut().zip(a) {
            *ep += ap / n as f64;
        }
    }
    e
}

fn run(theta_i: f64, beta: f64, mu_a: [f64; 3]) -> SimResult {
    let params = SimParams {
        theta_i,
        alpha: 0.0,
        beta,
        eta: 1.55,
        mu_a,
        rays: 16_000_000,
        seed: 11,
        ..Default::default()
    };
    simulate(&params, &|_, _| {}).unwrap()
}

/// Relative error of the simulated energy against the exact one.
fn rel(got: f64, want: f64) -> f64 {
    (got - want) / want
}

/// The simulated energies of lobes R, TT, TRT, TRRT, rest and of p ≥ 2 together, channel `c`,
/// with their exact values.
fn compare(r: &SimResult, c: usize) -> Vec<(&'static str, f64, f64)> {
    let p = &r.params;
    let want = smooth_energies(p.theta_i, p.eta, p.mu_a[c], 400_000);
    let got: Vec<f64> = r.energy.iter().map(|e| e[c]).collect();
    let mut rows: Vec<_> = ["R", "TT", "TRT", "TRRT", "rest"]
        .into_iter()
        .zip(got.iter().copied().zip(want))
        .map(|(n, (g, w))| (n, g, w))
        .collect();
    rows.push(("p>=2", got[2..].iter().sum(), want[2..].iter().sum()));
    rows
}

/// At β = 0.0025 (the paper's smoothest fiber), R, TT and all of p ≥ 2 together are within
/// 0.5 % of the exact smooth values (measured: within 0.1 %; statistical σ ≤ 0.1 % at 16 M rays).
///
/// The separate high-order lobes are not: even this little roughness moves ~0.1 % of the power
/// from TT, TRT and TRRT into p ≥ 4, because rays entering near grazing meet the inside of the
/// surface near the critical angle, where Fresnel is steepest and a 0.14° micro-tilt can turn a
/// transmission into total internal reflection. Measured at θ_i = 1: TRT −0.6 %, TRRT −2.4 %,
/// rest +14 %, shrinking with β (rest +1.4 % at β = 0.0005, statistical at 10⁻⁴; see
/// `high_order_lobes_converge_as_roughness_vanishes`). Those lobes are held to 1 %, 4 % and 20 %.
/// In an absorbing fiber the power moved to longer paths is partly absorbed, so p ≥ 2 together
/// drops like TRT; and the more the fiber absorbs, the more its TRT comes from the short chords
/// of near-grazing rays, where the effect lives (measured: TRT and p ≥ 2 −0.7 % at μ_a = 0.12 and
/// 0.5, −1.0 % at μ_a = 2; TRRT −3.1 % at μ_a = 2). There TRT and p ≥ 2 are held to 1.5 % and
/// TRRT to 5 %.
fn check_paper_smooth(r: &SimResult) {
    for c in 0..3 {
        for (name, got, want) in compare(r, c) {
            let mu = r.params.mu_a[c];
            let bound = match name {
                "TRT" | "p>=2" if mu > 0.0 => 0.015,
                "TRRT" if mu > 0.0 => 0.05,
                "TRT" => 0.01,
                "TRRT" => 0.04,
                "rest" => 0.20,
                _ => 0.005,
            };
            assert!(
                rel(got, want).abs() <= bound,
                "θ_i {} μ_a {mu} {name}: simulated {got:.6}, exact {want:.6}",
                r.params.theta_i
            );
        }
    }
}

/// Each of R, TT, TRT, TRRT has its energy-weighted mean θ within a quarter of a row (0.45°)
/// of −θ_i, and 99 % of its energy in the row holding −θ_i and its neighbours.
fn check_cone(r: &SimResult, theta_i: f64) {
    let g = r.params.grid;
    let want_row = g.pixel_of(-theta_i, 0.0).1;
    for (p, img) in r.lobes.iter().take(4).enumerate() {
        let row_energy: Vec<f64> = (0..g.height)
            .map(|k| (0..g.width).map(|j| img.at(j, k)).sum::<DVec3>().x * g.pixel_solid_angle(k))
            .collect();
        let total: f64 = row_energy.iter().sum();
        let mean: f64 = row_energy
            .iter()
            .enumerate()
            .map(|(k, e)| e * g.theta_center(k))
            .sum::<f64>()
            / total;
        let near: f64 = row_energy[want_row - 1..=want_row + 1].iter().sum();
        let quarter_row = std::f64::consts::PI / g.height as f64 / 4.0;
        assert!(
            (mean + theta_i).abs() < quarter_row + (g.theta_center(want_row) + theta_i).abs(),
            "lobe {p}: mean θ {mean}"
        );
        assert!(
            near > 0.99 * total,
            "lobe {p}: {near} of {total} near θ_o = −θ_i"
        );
    }
}

#[test]
fn clear_fiber_matches_fresnel_and_bravais() {
    for theta_i in [0.3, 1.0] {
        let r = run(theta_i, 0.0025, [0.0; 3]);
        check_paper_smooth(&r);
        check_cone(&r, theta_i);
    }
}

#[test]
fn absorbing_fiber_matches_beer_lambert_along_the_chords() {
    let r = run(0.6, 0.0025, [0.12, 0.5, 2.0]);
    check_paper_smooth(&r);
    check_cone(&r, 0.6);
}

/// At β = 10⁻⁴ every lobe is within 0.5 % of exact, except TRRT and rest, held to 1 % and 2 %
/// (about 3σ of their statistical error at 16 M rays: 0.3 % and 0.5 %).
#[test]
fn high_order_lobes_converge_as_roughness_vanishes() {
    let r = run(1.0, 1e-4, [0.0; 3]);
    for (name, got, want) in compare(&r, 0) {
        let bound = match name {
            "TRRT" => 0.01,
            "rest" => 0.02,
            _ => 0.005,
        };
        assert!(
            rel(got, want).abs() <= bound,
            "{name}: simulated {got:.6}, exact {want:.6}"
        );
    }
}
