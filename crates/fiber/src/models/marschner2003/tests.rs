use super::*;
use crate::geometry::bravais::azimuthal_deflection;
use crate::geometry::bravais::{eta_double_prime, eta_prime};
use crate::geometry::frame::{FiberAngles, wrap_pi};
use crate::lobe::Lobe;
use crate::math::GaussLegendre;
use crate::model::FiberModel;
use crate::optics::fresnel::fresnel_oblique;
use crate::params::FiberParams;
use crate::testing::{check_weights, chi2_test};
use glam::DVec3;
use proptest::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI};

fn model(params: MarschnerParams) -> Marschner2003 {
    Marschner2003::new(params).expect("valid parameters")
}

/// ∫ₐᵇ f by `panels` panels of a 16-point Gauss–Legendre rule.
fn composite(a: f64, b: f64, panels: usize, mut f: impl FnMut(f64) -> f64) -> f64 {
    let rule = GaussLegendre::cached(16);
    let h = (b - a) / panels as f64;
    (0..panels)
        .map(|k| rule.integrate(a + k as f64 * h, a + (k + 1) as f64 * h, &mut f))
        .sum()
}

/// ∫ S_lobe dω_o over the sphere (channel x), θ_o restricted to [lo, hi]; φ runs from
/// the back (φ_o − φ_i = −π, where N has a kink) round to the back.
fn lobe_energy(m: &Marschner2003, wi: FiberAngles, lobe: Lobe, lo: f64, hi: f64) -> f64 {
    composite(lo, hi, 16, |theta_o| {
        theta_o.cos()
            * composite(wi.phi - PI, wi.phi + PI, 8, |phi| {
                m.eval(wi, FiberAngles::new(theta_o, wrap_pi(phi)))[lobe].x
            })
    })
}

/// ½ ∫ F(η′, η″, asin h) dh = ∫₀^{π/2} F cos γ dγ at inclination θ.
fn fresnel_integral(eta: f64, theta: f64) -> f64 {
    let (ep, epp) = (eta_prime(eta, theta), eta_double_prime(eta, theta));
    composite(0.0, FRAC_PI_2, 8, |g| fresnel_oblique(ep, epp, g) * g.cos())
}

/// ∫ S_R dω / (½ ∫ F dh) − 1 for an unshifted R lobe of width β_R at θ_i.
fn r_energy_error(beta_r: f64, theta_i: f64) -> f64 {
    let params = MarschnerParams {
        alpha_r: 0.0,
        beta_r,
        ..Default::default()
    };
    let wi = FiberAngles::new(theta_i, 0.4);
    let reach = 10.0 * 2.0 * beta_r;
    let got = lobe_energy(
        &model(params),
        wi,
        Lobe::R,
        -theta_i - reach,
        -theta_i + reach,
    );
    got / fresnel_integral(params.eta, theta_i) - 1.0
}

#[test]
fn r_lobe_energy_is_the_fresnel_integral() {
    // Narrow and unshifted, the R lobe is the smooth cylinder's reflection blurred along
    // the specular cone: its energy is ½ ∫ F dh up to the O(β²) of cos²θ_o / cos²θ_d,
    // predicted β_R² (2 tan²θ_i − 3 sec²θ_i) to second order.
    let predicted =
        |beta: f64, t: f64| beta * beta * (2.0 * t.tan().powi(2) - 3.0 / t.cos().powi(2));
    let mut worst: f64 = 0.0;
    for &theta_i in &[0.0, 0.3, -0.6, 0.9] {
        let err = r_energy_error(0.1f64.to_radians(), theta_i);
        worst = worst.max(err.abs());
        assert!(err.abs() < 5e-5, "θ_i {theta_i}: relative error {err}");
        let beta = 1f64.to_radians();
        let wide = r_energy_error(beta, theta_i);
        let ratio = wide / predicted(beta, theta_i);
        assert!(
            (0.5..1.5).contains(&ratio),
            "θ_i {theta_i}: {wide} vs {ratio}"
        );
        eprintln!(
            "θ_i {theta_i}: error at β_R = 1° {wide:.3e}, predicted {:.3e}",
            predicted(beta, theta_i)
        );
    }
    eprintln!("R lobe energy vs Fresnel integral at β_R = 0.1°: worst relative error {worst:.2e}");
}

#[test]
fn energy_factor_of_the_cos2_normalisation() {
    // E(θ_i) = ∫ ½ M_R(θ_h) cos²θ_o / cos²θ_d dθ_o for the default lobe.
    let m = model(MarschnerParams::default());
    let lobe = m.lobes[0];
    for &(theta_i, lo, hi) in &[(0.0, 0.89, 0.91), (-0.6, 1.05, 1.07), (0.6, 0.71, 0.74)] {
        let e = composite(-FRAC_PI_2, FRAC_PI_2, 64, |theta_o| {
            let theta_d = 0.5 * (theta_o - theta_i);
            0.5 * lobe.eval(0.5 * (theta_i + theta_o)) * theta_o.cos().powi(2)
                / theta_d.cos().powi(2)
        });
        eprintln!("E_R(θ_i = {theta_i}) = {e:.4}");
        assert!((lo..hi).contains(&e), "θ_i {theta_i}: {e}");
    }
}

/// max over γ ∈ [−π/2, π/2] of |Φ̂(p, γ) − Φ(p, sin γ)|.
fn cubic_error(p: u32, eta_prime: f64) -> f64 {
    let d = CubicDeflection::new(p, eta_prime);
    (0..=4000)
        .map(|k| {
            let g = -FRAC_PI_2 + PI * k as f64 / 4000.0;
            (d.phi(g) - azimuthal_deflection(p, g.sin(), eta_prime)).abs()
        })
        .fold(0.0, f64::max)
}

#[test]
fn cubic_deflection_tracks_the_exact_one() {
    // R is exact; TT and TRT err by 2p |γ̂_t − γ_t|, least near η′ = 2 and most for η′
    // near 1. Human hair (η = 1.55) has η′ ≥ 1.55 at every inclination.
    let etas = [1.55, 1.7, 2.0, 2.5, 3.0, 5.0, 20.0];
    let worst = |p| etas.iter().map(|&e| cubic_error(p, e)).fold(0.0, f64::max);
    let (r, tt, trt) = (worst(0), worst(1), worst(2));
    eprintln!(
        "max |Φ̂ − Φ| for η′ ≥ 1.55: R {r:.1e}, TT {tt:.4}, TRT {trt:.4}; at η′ = 1.4: \
         TT {:.4}, TRT {:.4}",
        cubic_error(1, 1.4),
        cubic_error(2, 1.4)
    );
    assert!(r < 1e-12);
    assert!(tt < 0.02 && trt < 0.04, "TT {tt} TRT {trt}");
}

/// Roots of Φ̂(p, ·) ≡ φ found by sign changes of the wrapped difference on a dense grid.
fn dense_root_count(d: &CubicDeflection, phi: f64) -> usize {
    let n = 8_000;
    let f = |k: usize| wrap_pi(d.phi(-FRAC_PI_2 + PI * k as f64 / n as f64) - phi);
    (0..n)
        .filter(|&k| {
            let (a, b) = (f(k), f(k + 1));
            (a <= 0.0) != (b <= 0.0) && (a - b).abs() < 1.0
        })
        .count()
}

#[test]
fn every_root_is_found() {
    let mut checked = 0;
    for &eta_prime in &[1.05, 1.3, 1.55, 1.8, 2.0, 2.5, 10.0] {
        for p in 0..3u32 {
            let d = CubicDeflection::new(p, eta_prime);
            // Values where the count changes: folds and the edge rays at γ = ±π/2.
            let special: Vec<f64> = [d.phi(FRAC_PI_2), d.phi(-FRAC_PI_2)]
                .into_iter()
                .chain(d.fold().into_iter().flat_map(|g| [d.phi(g), d.phi(-g)]))
                .map(wrap_pi)
                .collect();
            for k in 0..360 {
                let phi = wrap_pi(-PI + (k as f64 + 0.37) * PI / 180.0);
                if special.iter().any(|s| wrap_pi(phi - s).abs() < 1e-3) {
                    continue;
                }
                let roots = d.roots(phi);
                for &g in roots.as_slice() {
                    assert!(
                        wrap_pi(d.phi(g) - phi).abs() < 1e-12,
                        "p {p} η′ {eta_prime} φ {phi}: root {g}"
                    );
                }
                assert_eq!(
                    roots.as_slice().len(),
                    dense_root_count(&d, phi),
                    "p {p} η′ {eta_prime} φ {phi}"
                );
                checked += 1;
            }
        }
    }
    assert!(checked > 7_000);
}

/// The density by the general root search, as [`CubicDeflection::offset_density`] had it.
fn density_by_roots(d: &CubicDeflection, phi: f64) -> f64 {
    d.roots(phi)
        .as_slice()
        .iter()
        .map(|&g| d.inverse_spread(g))
        .sum()
}

#[test]
fn falling_root_density_matches_the_root_search() {
    // R at every η′, TT above η′ = 2/√3 (where Φ̂ falls), TT below and TRT through roots.
    let mut fast = 0;
    for &eta_prime in &[1.05, 1.16, 1.2, 1.55, 1.8, 2.0, 3.0, 10.0, 1e6] {
        for p in 0..3u32 {
            let d = CubicDeflection::new(p, eta_prime);
            fast += usize::from(d.falls());
            for k in 0..=2000 {
                let phi = wrap_pi(-PI + (k as f64 + 0.29) * PI / 1000.0);
                let (got, want) = (d.offset_density(phi), density_by_roots(&d, phi));
                assert!(
                    (got - want).abs() <= 1e-12 * want.max(1e-3),
                    "p {p} η′ {eta_prime} φ {phi}: {got} vs {want}"
                );
            }
        }
    }
    // R at all nine η′, TT at the eight above 2/√3 and TRT at the three above 2 take the
    // fast path.
    assert_eq!(fast, 20);
}

#[test]
fn n_r_in_closed_form_is_the_root_search() {
    let mu_a = DVec3::new(0.2, 0.3, 0.5);
    for &eta in &[1.2, 1.55, 2.4] {
        for i in 0..=60 {
            let theta_d = -1.5 + 3.0 * i as f64 / 60.0;
            let interface = Interface::new(eta, theta_d, mu_a);
            for k in 0..=200 {
                let phi = wrap_pi(-PI + (k as f64 + 0.13) * PI / 100.0);
                let (got, want) = (n_r(eta, theta_d, phi), azimuthal(0, &interface, phi).x);
                assert!(
                    (got - want).abs() <= 1e-13 * want.max(1e-3),
                    "η {eta} θ_d {theta_d} φ {phi}: {got} vs {want}"
                );
            }
        }
    }
}

/// Relative L1 of the tabulated model's S (each lobe, channel sums) against the exact one
/// over random direction pairs.
fn tabulated_error(params: MarschnerParams, pairs: usize) -> [f64; 3] {
    let exact = model(params);
    let fast = model(params).tabulated();
    assert!(fast.table().is_some());
    let mut rng = <rand_pcg::Pcg64Mcg as rand_core::SeedableRng>::seed_from_u64(3);
    let (mut diff, mut total) = ([0.0; 3], [0.0; 3]);
    for _ in 0..pairs {
        let u = crate::testing::uniform4(&mut rng);
        let wi = FiberAngles::new((2.0 * u[0] - 1.0).asin(), PI * (2.0 * u[1] - 1.0));
        let wo = FiberAngles::new((2.0 * u[2] - 1.0).asin(), PI * (2.0 * u[3] - 1.0));
        let (a, b) = (fast.eval(wi, wo), exact.eval(wi, wo));
        for p in 0..3 {
            diff[p] += (a.0[p] - b.0[p]).abs().element_sum();
            total[p] += b.0[p].element_sum();
        }
    }
    std::array::from_fn(|p| diff[p] / total[p])
}

#[test]
fn tabulated_model_follows_the_exact_one() {
    // The table's own bounds (table.rs) carried to S over uniformly random pairs, circular
    // and elliptical (TRT exact off the table); R is exact to rounding in closed form.
    for params in [
        MarschnerParams::default(),
        MarschnerParams {
            eta: 1.8,
            mu_a: DVec3::new(0.05, 0.6, 3.0),
            caustic_width: 12f64.to_radians(),
            eccentricity: 0.9,
            ..Default::default()
        },
    ] {
        let [r, tt, trt] = tabulated_error(params, 200_000);
        eprintln!("tabulated S, relative L1: R {r:.2e} TT {tt:.2e} TRT {trt:.2e}");
        assert!(r < 1e-12 && tt < 2e-3 && trt < 3e-3, "{r} {tt} {trt}");
    }
}

#[test]
fn tabulated_model_samples_its_own_eval() {
    let m = model(MarschnerParams::default()).tabulated();
    let wi = FiberAngles::new(0.45, -0.3);
    check_weights(&m, wi, 20_000, 8, 0.0).unwrap();
    chi2_test(&m, wi, 1 << 19, 41, (32, 64), 1).unwrap();
}

#[test]
fn lobe_choice_reads_its_nodes() {
    // Between nodes the lobe choice interpolates; at a node it is what it tabulates, and it
    // always sums to 1.
    let params = MarschnerParams::default();
    let m = model(params);
    for k in [0, 1, 77, 128, 255, 256] {
        let theta_i = -FRAC_PI_2 + PI * k as f64 / 256.0;
        let want = sampling::lobe_weights(&params, &m.lobes, theta_i);
        let got = m.lobe_probabilities(theta_i);
        for p in 0..3 {
            assert!(
                (got[p] - want[p]).abs() < 1e-14,
                "θ_i {theta_i}: {got:?} {want:?}"
            );
        }
        assert!((got.iter().sum::<f64>() - 1.0).abs() < 1e-14);
    }
}

/// ∫ N dφ over the circle, from the back (φ = −π) round to the back; fine panels, since
/// N has kinks where a polarisation turns totally reflecting (η″ < 1 at large θ_d).
fn integral_over_phi(n: impl Fn(f64) -> DVec3) -> DVec3 {
    let c = |k: usize| composite(-PI, PI, 2048, |phi| n(phi)[k]);
    DVec3::new(c(0), c(1), c(2))
}

/// ½ ∫ A(p, h) dh.
fn mean_attenuation(interface: &Interface, p: u32) -> DVec3 {
    let c = |k: usize| {
        composite(0.0, FRAC_PI_2, 512, |g| {
            interface.attenuation(p, g)[k] * g.cos()
        })
    };
    DVec3::new(c(0), c(1), c(2))
}

#[test]
fn azimuthal_functions_integrate_to_the_mean_attenuation() {
    // Σ over roots of A / |2 dΦ̂/dh| is a change of variables from h to φ: whatever the
    // cubic's error, ∫ N_p dφ = ½ ∫ A dh when every root and its Jacobian are right.
    // (TRT without folds, η′ ≥ 2, so that N_P has no integrable singularity to resolve.)
    let mu_a = DVec3::new(0.0, 0.4, 1.5);
    for &(p, eta, theta_d) in &[
        (0, 1.55, 0.3),
        (1, 1.55, 0.0),
        (1, 1.3, -0.7),
        (2, 2.3, 0.2),
        (2, 1.55, 1.1),
    ] {
        let interface = Interface::new(eta, theta_d, mu_a);
        assert!(p < 2 || interface.deflection(2).fold().is_none());
        let got = integral_over_phi(|phi| azimuthal(p, &interface, phi));
        let want = mean_attenuation(&interface, p);
        assert!(
            (got - want).abs().max_element() < 1e-5 * want.max_element(),
            "p {p} η {eta}: {got} vs {want}"
        );
    }
}

#[test]
fn glint_energy_against_the_caustics_it_replaces() {
    // With k_G = 0.5 each glint carries the ½ A Δh of the offsets it stands for; the
    // removal takes away a band of N_P around each caustic. Measured for the record.
    let interface = Interface::new(1.55, 0.0, DVec3::new(0.2, 0.3, 0.5));
    let params = MarschnerParams::default();
    let trt = integral_over_phi(|phi| azimuthal_trt(&interface, &params, phi)).x;
    let want = mean_attenuation(&interface, 2).x;
    eprintln!(
        "∫ N_TRT dφ / ½ ∫ A dh at η′ = 1.55, defaults: {:.3}",
        trt / want
    );
    assert!((0.5..0.6).contains(&(trt / want)));
}

#[test]
fn trt_roots_switch_across_the_caustic() {
    // η′ = 1.8: three roots inside the caustic, one beyond it.
    let d = CubicDeflection::new(2, 1.8);
    let phi_c = wrap_pi(d.phi(d.fold().unwrap()));
    assert_eq!(d.roots(phi_c - 1e-4).as_slice().len(), 3);
    assert_eq!(d.roots(phi_c + 1e-4).as_slice().len(), 1);
    assert_eq!(d.roots(-phi_c - 1e-4).as_slice().len(), 1);
    // η′ = 1.55: the caustic lies beyond the edge ray 4c − π, so between them two roots
    // remain, and none beyond the caustic.
    let d = CubicDeflection::new(2, 1.55);
    let phi_c = wrap_pi(d.phi(d.fold().unwrap()));
    let edge = wrap_pi(d.phi(FRAC_PI_2)).abs();
    assert!(edge < phi_c);
    assert_eq!(d.roots(edge - 1e-4).as_slice().len(), 3);
    assert_eq!(d.roots(phi_c - 1e-4).as_slice().len(), 2);
    assert_eq!(d.roots(phi_c + 1e-4).as_slice().len(), 0);
}

#[test]
fn caustic_fold_of_the_cubic_against_the_exact_one() {
    // The paper's h_c = √((4 − η′²)/3) is where the exact dΦ/dh vanishes; the cubic's
    // fold stays close to it.
    let (mut dh, mut dphi) = (0.0f64, 0.0f64);
    for k in 0..=80 {
        let eta_prime = 1.55 + 0.45 * k as f64 / 80.0 - 1e-9;
        let c = Caustic::new(eta_prime, &MarschnerParams::default());
        let h_exact = ((4.0 - eta_prime * eta_prime) / 3.0).sqrt();
        let phi_exact = wrap_pi(azimuthal_deflection(2, h_exact, eta_prime));
        dh = dh.max((c.gamma_c.sin() - h_exact).abs());
        dphi = dphi.max((c.phi_c - phi_exact).abs());
    }
    eprintln!("cubic vs exact caustic, η′ ∈ [1.55, 2): |Δh_c| ≤ {dh:.4}, |Δφ_c| ≤ {dphi:.4}");
    assert!(dh < 0.02 && dphi < 0.035);
}

fn n_trt(eta_prime: f64, phi: f64) -> DVec3 {
    let interface = Interface::new(eta_prime, 0.0, DVec3::new(0.2, 0.3, 0.5));
    azimuthal_trt(&interface, &MarschnerParams::default(), phi)
}

#[test]
fn glint_is_finite_and_continuous() {
    for &eta_prime in &[1.3, 1.55, 1.8, 1.99] {
        let c = Caustic::new(eta_prime, &MarschnerParams::default());
        assert_eq!(c.t, 1.0);
        let at = n_trt(eta_prime, c.phi_c);
        assert!(at.is_finite() && at.min_element() >= 0.0);
        // Steps of 1e-6 across ±0.05 of the caustic: no jump above 1e-3 of the peak.
        let values: Vec<f64> = (-50_000..=50_000)
            .map(|k| n_trt(eta_prime, c.phi_c + k as f64 * 1e-6).x)
            .collect();
        let peak = values.iter().copied().fold(0.0, f64::max);
        let jump = values
            .windows(2)
            .map(|w| (w[1] - w[0]).abs())
            .fold(0.0, f64::max);
        assert!(values.iter().all(|v| v.is_finite()));
        assert!(
            jump < 1e-3 * peak,
            "η′ {eta_prime}: jump {jump} peak {peak}"
        );
    }
    // Continuous as the caustics merge at η′ = 2 and the glint fades.
    for &phi in &[0.0, 0.05, 0.3, -1.0] {
        let (below, above) = (n_trt(2.0 - 1e-7, phi), n_trt(2.0 + 1e-7, phi));
        assert!((below - above).abs().max_element() < 1e-4 * below.max_element().max(1e-3));
    }
    assert_eq!(Caustic::new(2.0 + 0.3, &MarschnerParams::default()).t, 0.0);
}

#[test]
fn eccentricity_one_is_circular_and_other_values_change_trt_only() {
    // Xu et al. 2011 eq. 24 at η = 1.55, a = 0.9: η*₁ = 1.341, η*₂ = 1.80802.
    assert!((eta_star(1.55, 0.9, 0.0) - 1.341).abs() < 1e-12);
    assert!((eta_star(1.55, 0.9, PI) - (1.1 / 0.81 + 0.45)).abs() < 1e-12);
    assert_eq!(eta_star(1.55, 1.0, 0.7), 1.55);
    let circ = model(MarschnerParams::default());
    let ellip = model(MarschnerParams {
        eccentricity: 0.9,
        ..Default::default()
    });
    let mut trt_changed = 0;
    for k in 0..200 {
        let x = k as f64;
        let wi = FiberAngles::new(0.3 * (0.7 * x).sin(), wrap_pi(0.37 * x));
        let wo = FiberAngles::new(-0.25 + 0.2 * (1.3 * x).cos(), wrap_pi(1.11 * x));
        let (a, b) = (circ.eval(wi, wo), ellip.eval(wi, wo));
        assert_eq!(a[Lobe::R], b[Lobe::R]);
        assert_eq!(a[Lobe::TT], b[Lobe::TT]);
        if (a[Lobe::TRT] - b[Lobe::TRT]).abs().max_element() > 1e-6 * a[Lobe::TRT].max_element() {
            trt_changed += 1;
        }
        // The circle depends on φ_o − φ_i only.
        let shift = |w: FiberAngles| FiberAngles::new(w.theta, wrap_pi(w.phi + 1.0));
        let rotated = circ.eval(shift(wi), shift(wo));
        assert!(
            (rotated.total() - a.total()).abs().max_element()
                < 1e-9 * a.total().max_element().max(1e-12)
        );
    }
    assert!(trt_changed > 150, "{trt_changed}");
}

#[test]
fn reciprocal_in_marschners_units() {
    // Marschner's S (= ours / cos θ_o) is symmetric in ω_i and ω_o: exactly, elliptical, and
    // from the table (symmetric in θ_d and φ).
    let elliptical = model(MarschnerParams {
        eccentricity: 0.9,
        ..Default::default()
    });
    for m in [elliptical, model(MarschnerParams::default()).tabulated()] {
        for k in 0..300 {
            let x = k as f64;
            let a = FiberAngles::new(1.2 * (0.7 * x).sin(), wrap_pi(0.37 * x));
            let b = FiberAngles::new(1.3 * (1.3 * x).cos(), wrap_pi(1.11 * x + 0.5));
            let ab = m.eval(a, b).total() / b.theta.cos();
            let ba = m.eval(b, a).total() / a.theta.cos();
            assert!(
                (ab - ba).abs().max_element() <= 1e-9 * ab.max_element().max(1e-300),
                "{ab} {ba}"
            );
        }
    }
}

#[test]
fn sampling_matches_pdf_chi2() {
    let cases: [(f64, MarschnerParams); 6] = [
        (0.0, MarschnerParams::default()),
        (0.6, MarschnerParams::default()),
        (
            -1.0,
            MarschnerParams {
                beta_r: 10f64.to_radians(),
                alpha_r: -5f64.to_radians(),
                mu_a: DVec3::ZERO,
                ..Default::default()
            },
        ),
        (
            1.3,
            MarschnerParams {
                beta_r: 5f64.to_radians(),
                alpha_r: -10f64.to_radians(),
                mu_a: DVec3::splat(2.0),
                ..Default::default()
            },
        ),
        (
            -0.4,
            MarschnerParams {
                beta_r: 2f64.to_radians(),
                alpha_r: 0.0,
                eta: 1.3,
                glint_scale: 3.0,
                ..Default::default()
            },
        ),
        (
            0.3,
            MarschnerParams {
                beta_r: 0.5,
                alpha_r: 10f64.to_radians(),
                eccentricity: 0.85,
                ..Default::default()
            },
        ),
    ];
    let start = std::time::Instant::now();
    for (n, (theta_i, params)) in cases.iter().enumerate() {
        let m = model(*params);
        let wi = FiberAngles::new(*theta_i, 0.25);
        let p = chi2_test(&m, wi, 1 << 19, 17 + n as u64, (32, 64), cases.len());
        eprintln!("χ² case {n} (θ_i = {theta_i}): {p:?}");
        p.unwrap();
        check_weights(&m, wi, 20_000, 99 + n as u64, 1e-4).unwrap();
    }
    eprintln!("χ² cases took {:?}", start.elapsed());
}

#[test]
fn samples_carry_exactly_the_eval_and_pdf_they_report() {
    // sample finds S and pdf together (one root search for R and TT): the arithmetic of eval
    // and pdf, so the same bits, circular or elliptical.
    for eccentricity in [1.0, 0.9] {
        let m = model(MarschnerParams {
            eccentricity,
            ..Default::default()
        });
        check_weights(&m, FiberAngles::new(0.45, -0.3), 20_000, 8, 0.0).unwrap();
    }
}

#[test]
fn weights_average_to_the_integral_of_s() {
    // The estimator Σ weight / draws (a rejected draw counts 0) is unbiased only if the
    // sampling covers every direction where S > 0: compare it with quadrature of S.
    let m = model(MarschnerParams {
        mu_a: DVec3::new(0.1, 0.3, 0.9),
        ..Default::default()
    });
    let wi = FiberAngles::new(0.3, 0.0);
    let integral = composite(-FRAC_PI_2, FRAC_PI_2, 24, |theta_o| {
        theta_o.cos()
            * composite(-PI, PI, 24, |phi| {
                m.eval(wi, FiberAngles::new(theta_o, phi)).total().y
            })
    });
    let mut rng = <rand_pcg::Pcg64Mcg as rand_core::SeedableRng>::seed_from_u64(5);
    let n = 1 << 18;
    let (mut sum, mut sum2) = (0.0, 0.0);
    for _ in 0..n {
        let w = m
            .sample(wi, crate::testing::uniform4(&mut rng))
            .map_or(0.0, |s| s.weight.y);
        sum += w;
        sum2 += w * w;
    }
    let mean = sum / n as f64;
    let sigma = ((sum2 / n as f64 - mean * mean) / n as f64).sqrt();
    eprintln!("Σ w / n = {mean:.5} ± {sigma:.5}, ∫ S dω = {integral:.5}");
    assert!((mean - integral).abs() < 4.0 * sigma + 1e-3 * integral);
}

#[test]
fn parameters_are_validated_field_by_field() {
    assert!(MarschnerParams::default().validate().is_ok());
    let bad = |f: fn(&mut MarschnerParams)| {
        let mut p = MarschnerParams::default();
        f(&mut p);
        p.validate().unwrap_err()
    };
    for (name, f) in [
        (
            "eta",
            (|p: &mut MarschnerParams| p.eta = 1.0) as fn(&mut MarschnerParams),
        ),
        ("beta_r_deg", |p| p.beta_r = f64::NAN),
        ("mu_a", |p| p.mu_a.y = -1.0),
        ("alpha_r_deg", |p| p.alpha_r = 1.0),
        ("beta_r_deg", |p| p.beta_r = 0.0),
        ("eccentricity", |p| p.eccentricity = 0.5),
        ("eccentricity", |p| p.eccentricity = 1.42),
        ("caustic_width_deg", |p| p.caustic_width = 0.0),
        ("glint_scale", |p| p.glint_scale = -1.0),
        ("caustic_fade", |p| p.caustic_fade = 0.0),
        ("caustic_limit", |p| p.caustic_limit = 3.0),
    ] {
        let err = bad(f);
        assert_eq!(err.name, name, "{err}");
        assert!(err.to_string().starts_with(name));
    }
}

#[test]
fn from_fiber_maps_the_shared_parameters() {
    let fiber = FiberParams::default();
    let m = Marschner2003::from_fiber(&fiber).unwrap();
    assert_eq!(m.params().eta, fiber.eta);
    assert_eq!(m.params().mu_a, fiber.mu_a);
    // The R lobe's cone and width in θ_o are d'Eon 2011's.
    let deon = crate::DEon2011::new(fiber).unwrap();
    for &theta_i in &[-0.7, 0.0, 0.4] {
        let cone = deon.longitudinal(0, theta_i);
        let lobe = m.lobes[0];
        assert!((-theta_i + 2.0 * lobe.alpha - cone.theta_cone).abs() < 1e-15);
        assert!((2.0 * lobe.beta - cone.v.sqrt()).abs() < 1e-15);
    }
    let extreme = FiberParams {
        alpha: 20f64.to_radians(),
        beta: 1.0,
        ..fiber
    };
    assert!(Marschner2003::from_fiber(&extreme).is_ok());
    let bad = FiberParams { eta: 0.9, ..fiber };
    assert!(matches!(
        Marschner2003::from_fiber(&bad),
        Err(e) if e.name == "eta"
    ));
}

/// eval, pdf and a sample at one pair are finite and non-negative, the sample inside the domain.
fn check_finite(
    m: &Marschner2003,
    wi: FiberAngles,
    wo: FiberAngles,
    u: [f64; 4],
) -> Result<(), TestCaseError> {
    for v in m.eval(wi, wo).0 {
        prop_assert!(v.is_finite() && v.min_element() >= 0.0, "eval {v}");
    }
    let pdf = m.pdf(wi, wo);
    prop_assert!(pdf.is_finite() && pdf >= 0.0, "pdf {pdf}");
    if let Some(s) = m.sample(wi, u) {
        prop_assert!(
            s.weight.is_finite() && s.weight.min_element() >= 0.0,
            "weight {}",
            s.weight
        );
        prop_assert!(s.pdf.is_finite() && s.pdf > 0.0);
        prop_assert!(s.wo.theta.abs() <= FRAC_PI_2 && s.wo.phi.abs() <= PI);
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]
    /// Exact and tabulated (half the cases: a table per case), circular and elliptical.
    #[test]
    fn finite_and_non_negative_everywhere(
        theta_i in -FRAC_PI_2..=FRAC_PI_2,
        theta_o in -FRAC_PI_2..=FRAC_PI_2,
        phi_i in -PI..=PI,
        phi_o in -PI..=PI,
        beta_r in 0.001f64..=1.0,
        eta in 1.01f64..=3.0,
        mu_a in 0.0f64..=100.0,
        alpha_deg in -10.0f64..=10.0,
        eccentricity in 0.75f64..=1.3,
        caustic_deg in 0.3f64..=60.0,
        tabulated: bool,
        u in prop::array::uniform4(0.0f64..1.0),
    ) {
        let m = model(MarschnerParams {
            eta,
            beta_r,
            alpha_r: alpha_deg.to_radians(),
            mu_a: DVec3::new(mu_a, 0.5 * mu_a, 0.0),
            eccentricity,
            caustic_width: caustic_deg.to_radians(),
            ..Default::default()
        });
        let m = if tabulated { m.tabulated() } else { m };
        prop_assert_eq!(m.table().is_some(), tabulated);
        check_finite(&m, FiberAngles::new(theta_i, phi_i), FiberAngles::new(theta_o, phi_o), u)?;
    }
}
