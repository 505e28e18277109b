//! What the tests that hold the tilted non-separable model against the simulator share: a
//! lossless fiber of index [`ETA`], simulated on a grid, and the model pixel-integrated on it.
//! Not every test uses every helper.
#![allow(dead_code)]

use cuticle_fiber::{FiberParams, LatLongGrid, LatLongImage, NonSeparable};
use cuticle_sim::{SimParams, SimResult, simulate};
use cuticle_validate::{PixelRule, integrate_lobes};
use glam::DVec3;

/// The fiber's index of refraction.
pub const ETA: f64 = 1.55;

/// The tilted non-separable model of the lossless fiber with scale tilt α and roughness β.
pub fn model(alpha: f64, beta: f64) -> NonSeparable {
    let params = FiberParams {
        eta: ETA,
        beta,
        alpha,
        mu_a: DVec3::ZERO,
    };
    NonSeparable::new(params).unwrap()
}

/// The simulator's lobes of that fiber, `paths` paths on `grid` from `seed`.
pub fn simulated(
    theta_i: f64,
    alpha: f64,
    beta: f64,
    grid: LatLongGrid,
    paths: u64,
    seed: u64,
) -> SimResult {
    let params = SimParams {
        theta_i,
        alpha,
        beta,
        eta: ETA,
        mu_a: [0.0; 3],
        rays: paths,
        seed,
        grid,
    };
    simulate(&params, &|_, _| {}).unwrap()
}

/// The tabulated `model`'s lobes at θ_i, pixel-integrated on `grid` as the validation
/// integrates them.
pub fn model_images(model: &NonSeparable, theta_i: f64, grid: LatLongGrid) -> [LatLongImage; 5] {
    let params = model.params();
    integrate_lobes(
        model,
        theta_i,
        grid,
        &PixelRule::for_fiber(params.eta, params.alpha, params.beta),
    )
}
