//! One configuration against one model: the model's pixel-integrated lobe images and the
//! figures of every lobe.

use crate::error::ValidateError;
use crate::metrics::{LobeFigures, lobe_figures};
use crate::models::build_model;
use crate::pixel_integral::{PixelRule, integrate_lobes};
use crate::sweep_dir::SimConfig;
use cuticle_fiber::ModelId;
use cuticle_fiber::{FiberModel, LatLongImage};

/// The figures of one (configuration, model) pair, lobes in the order R, TT, TRT, TRRT, rest.
#[derive(Clone, Debug)]
pub struct ConfigFigures {
    pub model: ModelId,
    pub lobes: [LobeFigures; 5],
}

/// `kind`'s five lobe images for `config` on `grid`, by the default [`PixelRule`].
pub fn model_images(
    config: &SimConfig,
    kind: ModelId,
    grid: cuticle_fiber::LatLongGrid,
) -> Result<[LatLongImage; 5], ValidateError> {
    let model = build_model(kind, &config.fiber_params())?;
    Ok(images_of(model.as_ref(), config, grid))
}

/// `model`'s five lobe images for `config` on `grid`, by the default [`PixelRule`]: the model
/// must be the one for `config`'s fiber ([`crate::models::FiberModels`] keeps it).
pub fn images_of(
    model: &dyn FiberModel,
    config: &SimConfig,
    grid: cuticle_fiber::LatLongGrid,
) -> [LatLongImage; 5] {
    let params = config.fiber_params();
    let rule = PixelRule::for_fiber(params.eta, params.alpha, params.beta);
    integrate_lobes(model, config.theta_i, grid, &rule)
}

/// The figures of `kind` against the simulated lobe images `sim` of `config`.
pub fn compare_config(
    config: &SimConfig,
    kind: ModelId,
    sim: &[LatLongImage; 5],
) -> Result<ConfigFigures, ValidateError> {
    let images = model_images(config, kind, sim[0].grid)?;
    Ok(figures_of(kind, &images, sim))
}

/// The same figures with each lobe's seed-to-seed L1 beside them ([`crate::noise`]).
pub fn with_noise(mut figures: ConfigFigures, seed_to_seed: &[Option<f64>; 5]) -> ConfigFigures {
    for (f, s) in figures.lobes.iter_mut().zip(seed_to_seed) {
        f.seed_to_seed_l1 = *s;
    }
    figures
}

/// The figures of already rendered model images against `sim`.
pub fn figures_of(
    kind: ModelId,
    model: &[LatLongImage; 5],
    sim: &[LatLongImage; 5],
) -> ConfigFigures {
    ConfigFigures {
        model: kind,
        lobes: std::array::from_fn(|p| lobe_figures(&model[p], &sim[p])),
    }
}
