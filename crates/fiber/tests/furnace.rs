//! White furnace (issue 2): with μ_a = 0, α = 0 and η = 1.55, d'Eon 2011 integrates to 1 within
//! 0.5 % over θ_i ∈ {0, 0.5, 1.0, 1.4} × β ∈ {0.01, 0.04, 0.15, 0.3}, and so does the
//! non-separable model except at rough grazing settings.
//!
//! There the paper's non-separable TT lobe is not exactly normalised: its M depends on φ
//! (through the offset h that φ selects) while its N depends on θ_o (through η′(θ_d)), so ∫∫ M N
//! is Ā only to second order. That coupling is what makes d'Eon et al. 2014's fixed-point
//! sampling necessary; it costs up to 1.04 % of the energy (β = 0.3, θ_i = 1.0; 0.6 % at
//! β = 0.15, θ_i = 1.2, measured with `cuticle furnace --model nonseparable-paper`), and the
//! test holds it to that. The default form reads N_TT at one θ_d whatever θ_o
//! (docs/departures/21-tt-column-covariance.md), so its TT integrates to A(1, h)'s energy exactly.
//! The grid runs on the tabulated fast path (whose error against direct quadrature the table's
//! own tests bound); one configuration also runs on direct quadrature.
//!
//! The paper's non-separable form is the one held white: the default form takes the Fresnel
//! factors of the rough surface (issue 14), whose micro-surface shadows a little and whose
//! long paths are cut, and integrates to those energies instead.
//!
//! With tilted scales the fiber is no longer white (issue 14): the tilted non-separable model
//! integrates, lobe by lobe, to the energies its A(p, h) gives (`NonSeparable::lobe_energies`:
//! 1 minus what the scales remove, R's off the rough surface), and the furnace finds them;
//! `tilted_scales_lose_what_the_budget_says` prints how much is lost.

use cuticle_fiber::furnace::{FurnaceRule, albedo};
use cuticle_fiber::models::nonseparable::Scales;
use cuticle_fiber::{DEon2011, FiberModel, FiberParams, NonSeparable};
use glam::DVec3;

const THETAS: [f64; 4] = [0.0, 0.5, 1.0, 1.4];
const BETAS: [f64; 4] = [0.01, 0.04, 0.15, 0.3];

fn lossless(beta: f64) -> FiberParams {
    FiberParams {
        eta: 1.55,
        beta,
        alpha: 0.0,
        mu_a: DVec3::ZERO,
    }
}

fn check(model: &dyn FiberModel, beta: f64, thetas: &[f64]) {
    check_within(model, beta, thetas, 0.005);
}

fn check_within(model: &dyn FiberModel, beta: f64, thetas: &[f64], tolerance: f64) {
    check_budget(model, beta, thetas, tolerance, 1, |_| 1.0);
}

/// The albedo at each θ_i is `budget(θ_i)` within `tolerance`, by the rule at `resolution`.
fn check_budget(
    model: &dyn FiberModel,
    beta: f64,
    thetas: &[f64],
    tolerance: f64,
    resolution: usize,
    budget: impl Fn(f64) -> f64,
) {
    for &theta_i in thetas {
        let est = albedo(
            model,
            theta_i,
            FurnaceRule {
                beta,
                max_shift: 0.0,
                resolution,
            },
        );
        let a = est.albedo.x;
        // The rule must be sharp enough to judge 0.5 %, and the albedo then within it.
        assert!(
            est.error_estimate.x < 0.001,
            "{} β {beta} θ_i {theta_i}: {est:?}",
            model.name()
        );
        let want = budget(theta_i);
        assert!(
            (a - want).abs() < tolerance,
            "{} β {beta} θ_i {theta_i}: albedo {a}, budget {want}",
            model.name()
        );
    }
}

#[test]
fn deon2011_conserves_energy() {
    for beta in BETAS {
        check(
            &DEon2011::new(lossless(beta)).unwrap().tabulated(),
            beta,
            &THETAS,
        );
    }
}

/// The paper's form: A(p, h) is d'Eon 2011's, which loses nothing.
#[test]
fn nonseparable_conserves_energy() {
    for beta in BETAS {
        let model = NonSeparable::paper(lossless(beta)).unwrap().tabulated();
        if beta <= 0.04 {
            check(&model, beta, &THETAS);
        } else {
            check(&model, beta, &THETAS[..2]);
            check_within(&model, beta, &THETAS[2..], 0.0125);
        }
    }
}

/// The default form on flat scales: its rough Fresnel factors lose what the micro-surface
/// shadows and what stays trapped, so it integrates to its lobes' energies
/// (`NonSeparable::lobe_energies`), whose sum is below 1 at grazing incidence; each lobe
/// within 0.0025 and the whole within 0.005 (measured: each lobe within 0.0012, R's columns
/// at β = 0.3, θ_i = 1.0 and 1.4; the sum within 0.0013 there and 0.0010 at β = 0.04,
/// θ_i = 1.4). At β = 0.04 the
/// rule runs at twice its resolution: R's columns near |φ| = π, where the reflecting offsets
/// graze, are down to 0.0017 rad wide at θ_i = 1.4 (docs/departures/18-r-column-lobe.md), which
/// the default rule's finest panels (0.275 β) do not resolve.
#[test]
fn rough_nonseparable_integrates_to_its_lobe_energies() {
    for beta in [0.04, 0.3] {
        let model = NonSeparable::new(lossless(beta)).unwrap().tabulated();
        let resolution = if beta <= 0.04 { 2 } else { 1 };
        let rule = FurnaceRule {
            beta,
            max_shift: 0.0,
            resolution,
        };
        for theta_i in THETAS {
            check_lobes(&model, theta_i, rule, [0.0025, 0.005]);
        }
    }
    // Measurably lossy where the rough exit traps light: not a white furnace in disguise.
    let rough = NonSeparable::new(lossless(0.3)).unwrap();
    assert!(rough.energy_budget(1.4).lost().x > 0.02);
}

/// The furnace's albedo at θ_i against `NonSeparable::lobe_energies`: each lobe within
/// `tolerance[0]`, their sum within `tolerance[1]`, with the rule sharp enough to judge it.
fn check_lobes(model: &NonSeparable, theta_i: f64, rule: FurnaceRule, tolerance: [f64; 2]) {
    let est = albedo(model, theta_i, rule);
    let want = model.lobe_energies(theta_i);
    let label = format!(
        "α {:.3} β {} θ_i {theta_i}",
        model.params().alpha,
        rule.beta
    );
    println!(
        "{label}: albedo {:.4}, lobes' energies {:.4}",
        est.albedo.x,
        want.total().x
    );
    assert!(est.error_estimate.x < 0.005, "{label}: {est:?}");
    for (p, (got, want)) in est.per_lobe.0.iter().zip(want.0).enumerate() {
        assert!(
            (got.x - want.x).abs() < tolerance[0],
            "{label}: lobe {p} integrates to {}, its energy is {}",
            got.x,
            want.x
        );
    }
    assert!(
        (est.albedo.x - want.total().x).abs() < tolerance[1],
        "{label}: albedo {}, lobes' energies {}",
        est.albedo.x,
        want.total().x
    );
}

#[test]
fn direct_quadrature_conserves_energy_too() {
    check(&DEon2011::new(lossless(0.15)).unwrap(), 0.15, &[0.5]);
    // The paper's form, the white one: the default's rough A(p, h) follows micro-normal
    // directions event by event, which by direct quadrature (A at every node of every N_p)
    // costs minutes here; its tabulated twin is held to its budget above.
    check(&NonSeparable::paper(lossless(0.15)).unwrap(), 0.15, &[1.0]);
}

/// The furnace of the tilted model finds each lobe's energy (`NonSeparable::lobe_energies`)
/// within 0.005 of the incident power over θ_i ∈ {−0.25, 0.75, 1.1, 1.3} × α ∈ {±2°, ±4°} at
/// β = 0.04, and the losses are large where the simulator says they are; the paper's form
/// stays white (to 1 %). Measured: every lobe within 0.0009 but TT at α = +4°, where the
/// table's interpolation in θ_i meets a TT that dies between θ_i = 0.75 and 1.1 (0.0043 at
/// 1.1, 0.0017 at 0.75). The rule's own error reaches 0.0034 at θ_i 1.3: R's N has an edge in
/// φ where the tilted scales start to hide the reflection, which the rule's φ panels resolve
/// slowly.
#[test]
fn tilted_scales_lose_what_the_budget_says() {
    let beta = 0.04;
    println!("  α     θ_i   lost (budget)");
    for alpha_deg in [-4.0, -2.0, 2.0, 4.0] {
        let params = FiberParams {
            alpha: f64::to_radians(alpha_deg),
            ..lossless(beta)
        };
        let model = NonSeparable::new(params).unwrap().tabulated();
        let rule = FurnaceRule {
            beta,
            max_shift: 6.0 * params.alpha.abs(),
            resolution: 1,
        };
        for theta_i in [-0.25, 0.75, 1.1, 1.3] {
            let lost = model.energy_budget(theta_i).lost().x;
            println!("{alpha_deg:+.0}° {theta_i:+.2}   {lost:.4}");
            check_lobes(&model, theta_i, rule, [0.005, 0.005]);
        }
        if alpha_deg == 2.0 {
            assert!(model.energy_budget(1.1).lost().x > 0.4);
            let paper = NonSeparable::with_scales(params, Scales::Paper)
                .unwrap()
                .tabulated();
            let white = albedo(&paper, 1.1, rule).albedo.x;
            // Measured 1.0056: the pole cone and the M–N coupling, no loss.
            assert!((white - 1.0).abs() < 0.01, "paper: {white}");
        }
    }
}
