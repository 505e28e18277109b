//! The per-pixel rule conserves each model's energy: the lobe images' ∫ S dω agree with
//! `furnace::albedo`, an independent graded quadrature, to 0.3 % of the lobe (or 2e-4
//! absolute for faint lobes), where S at pixel centres misses narrow lobes by far more.

use cuticle_fiber::furnace::{FurnaceRule, albedo};
use cuticle_fiber::lobe::channel_mean;
use cuticle_fiber::{FiberParams, LatLongGrid, Lobe};
use cuticle_validate::{ModelId, PixelRule, build_model, integrate_lobes};
use glam::DVec3;

const REL_TOL: f64 = 3e-3;
const ABS_TOL: f64 = 2e-4;

fn fiber(beta: f64, alpha_deg: f64) -> FiberParams {
    FiberParams {
        eta: 1.55,
        beta,
        alpha: alpha_deg.to_radians(),
        mu_a: DVec3::splat(0.25),
    }
}

/// Largest |image energy − furnace energy| beyond tolerance, per lobe, as (lobe, image, furnace).
fn energy_mismatches(
    kind: ModelId,
    params: &FiberParams,
    theta_i: f64,
    rule: &PixelRule,
) -> Vec<(Lobe, f64, f64)> {
    let model = build_model(kind, params).unwrap();
    let images = integrate_lobes(model.as_ref(), theta_i, LatLongGrid::default(), rule);
    let reference = albedo(
        model.as_ref(),
        theta_i,
        FurnaceRule {
            beta: params.beta,
            max_shift: 6.0 * params.alpha.abs(),
            resolution: 1,
        },
    );
    Lobe::ALL
        .into_iter()
        .map(|l| {
            (
                l,
                channel_mean(images[l.index()].energy()),
                channel_mean(reference.per_lobe[l]),
            )
        })
        .filter(|(_, a, b)| (a - b).abs() > (REL_TOL * b.abs()).max(ABS_TOL))
        .collect()
}

#[test]
fn pixel_integral_conserves_energy() {
    // The models this test was written for; Chiang 2016 has its own furnace tests.
    for kind in [
        ModelId::NonSeparable,
        ModelId::NonSeparablePaper,
        ModelId::DEon2011,
        ModelId::Marschner,
    ] {
        for (beta, alpha_deg, theta_i) in [(0.02, 4.0, 0.25), (0.02, -4.0, 1.1), (0.08, 2.0, 0.75)]
        {
            let p = fiber(beta, alpha_deg);
            let rule = PixelRule::for_fiber(p.eta, p.alpha, p.beta);
            let bad = energy_mismatches(kind, &p, theta_i, &rule);
            assert!(
                bad.is_empty(),
                "{} β {beta} α {alpha_deg} θ_i {theta_i}: {bad:?}",
                kind.name()
            );
        }
    }
}

#[test]
fn centre_sampling_does_not_conserve_narrow_lobes() {
    let p = fiber(0.02, 0.0);
    let bad = energy_mismatches(ModelId::DEon2011, &p, 0.25, &PixelRule::centre());
    assert!(
        !bad.is_empty(),
        "point sampling happened to conserve energy: the test above proves nothing"
    );
}
