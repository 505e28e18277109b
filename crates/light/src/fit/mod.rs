//! Fitting an environment map with J SRBF lights (Xu et al. 2011 eq. 1): minimise the
//! solid-angle-weighted squared error Σ_p Δω_p ‖L(ω_p) − Σ_j L_j G(ω_p; ω_j, λ_j)‖² over the
//! sphere, as Tsai & Shih (2006) and Ren et al. (2010) do.
//!
//! 1. The map is area-averaged down to `fit_width × fit_width/2`, and the cells hiding the most
//!    detail (a compact sun, sharp edges) are split down to single pixels within a budget of
//!    [`FitOptions::refine_samples`] extra samples ([`adaptive_target`]), so that the error the
//!    fit minimises is close to the full map's.
//! 2. Initial centres and bandwidths from spherical k-means of the energy ([`init`]), coefficients
//!    from non-negative least squares ([`coefficients`]).
//! 3. Lights that NNLS left dark are moved to where the fit falls shortest ([`revive`]), before
//!    and after the refinement (a few rounds).
//! 4. Projected Levenberg–Marquardt on all centres, bandwidths and coefficients together
//!    ([`levenberg_marquardt`]), bandwidths kept in [`FitOptions::min_bandwidth`] (by default
//!    0.6 of the finest sample's height, where a lobe's energy still matches the pixel it fits)
//!    to [`FitOptions::max_bandwidth`].
//! 5. The relative L2 error is reported on the fit grid and on the full map.

mod adaptive_target;
mod cache;
mod cells;
mod coefficients;
mod init;
mod levenberg_marquardt;
mod linalg;
mod model;
mod nnls;
mod normal_equations;
mod params;
mod revive;
mod target;

use crate::srbf::sharpness_of;
use crate::{EnvMap, LightError, SrbfLight, relative_l2_error};
use glam::DVec3;
use serde::{Deserialize, Serialize};
use std::time::Instant;

pub use cache::{FitCache, FitSource, fit_srbf_cached, key as fit_cache_key};

/// Settings of [`fit_srbf`]; `Default` is the project's choice.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FitOptions {
    /// J, the number of SRBF lights.
    pub lights: usize,
    /// Width of the downsampled map the fit works on (height is width/2 for a 2:1 map).
    pub fit_width: usize,
    /// Extra samples the adaptive target may spend resolving detail below the fit grid
    /// (0: the plain downsampled map).
    pub refine_samples: usize,
    /// Spherical k-means iterations of the initialisation.
    pub kmeans_iterations: usize,
    /// Most Levenberg–Marquardt iterations, all rounds together.
    pub max_iterations: usize,
    /// Rounds of reviving dead lights and refining again.
    pub revive_rounds: usize,
    /// Relative error decrease below which an iteration counts as stalled (three in a row stop).
    pub tolerance: f64,
    /// Narrowest bandwidth λ, radians; `None` for 0.6 × the finest sample's height π/H (H the
    /// map's height when `refine_samples` > 0, else the fit grid's).
    pub min_bandwidth: Option<f64>,
    /// Widest bandwidth λ.
    pub max_bandwidth: f64,
}

impl Default for FitOptions {
    fn default() -> Self {
        Self {
            lights: 40,
            fit_width: 128,
            refine_samples: 4096,
            kmeans_iterations: 20,
            max_iterations: 100,
            revive_rounds: 3,
            tolerance: 1e-3,
            min_bandwidth: None,
            max_bandwidth: 4.0,
        }
    }
}

/// What a fit made and measured.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct FitReport {
    /// The lights, most powerful first; always `lights` of them, and any the fit found no use
    /// for (a smooth map needs fewer) come last with a zero coefficient.
    pub lights: Vec<SrbfLight>,
    /// Relative L2 error on the full-resolution map (see [`relative_l2_error`]).
    pub relative_l2: f64,
    /// Relative L2 error on the fit grid, after the initialisation and at the end.
    pub relative_l2_fit_initial: f64,
    pub relative_l2_fit: f64,
    pub fit_width: usize,
    pub fit_height: usize,
    /// Samples the fit worked on (the fit grid plus the refined cells).
    pub fit_samples: usize,
    /// The bandwidth bounds used, λ_min and λ_max.
    pub bandwidth_range: [f64; 2],
    pub iterations: usize,
    /// ∫ L dω of the map and of the fit, per channel.
    pub map_integral: DVec3,
    pub fit_integral: DVec3,
    /// Wall time of the fit (downsampling to final error), seconds.
    pub seconds: f64,
}

/// Progress events of a fit, for a progress bar.
#[derive(Clone, Copy, Debug)]
pub enum FitProgress {
    Initialised {
        relative_l2: f64,
    },
    Iteration {
        iteration: usize,
        max_iterations: usize,
        relative_l2: f64,
    },
    Done,
}

/// Fits `options.lights` SRBF lights to `map` (rotation included).
pub fn fit_srbf(map: &EnvMap, options: &FitOptions) -> Result<FitReport, LightError> {
    fit_srbf_with_progress(map, options, &mut |_| {})
}

/// [`fit_srbf`], reporting progress to `progress`.
pub fn fit_srbf_with_progress(
    map: &EnvMap,
    options: &FitOptions,
    progress: &mut dyn FnMut(FitProgress),
) -> Result<FitReport, LightError> {
    validate(options)?;
    let start = Instant::now();
    let (fit_width, fit_height) = fit_grid(map, options.fit_width);
    let mut adaptive =
        adaptive_target::AdaptiveTarget::new(map, fit_width, fit_height, options.refine_samples);
    let finest = if options.refine_samples > 0 {
        map.height()
    } else {
        fit_height
    };
    let bandwidth_range = [
        options.min_bandwidth.unwrap_or(
            (0.6 * std::f64::consts::PI / finest as f64).max(crate::srbf::MIN_BANDWIDTH),
        ),
        options.max_bandwidth,
    ];
    let kappa_range = (
        sharpness_of(bandwidth_range[1]),
        sharpness_of(bandwidth_range[0]),
    );
    let mut params = init::kmeans_init(
        adaptive.target(),
        options.lights,
        options.kmeans_iterations,
        kappa_range,
    );
    coefficients::solve_coefficients(adaptive.target(), &mut params);
    let initial = adaptive
        .target()
        .relative(model::sum_squared_error(adaptive.target(), &params));
    progress(FitProgress::Initialised {
        relative_l2: initial,
    });
    let outcome = refine_and_revive(&mut adaptive, params, options, kappa_range, progress);
    let target = adaptive.target();
    let lights = outcome.params.to_sorted_lights();
    // What a fit writes, `validate_lights` (every lights file's reader) accepts.
    crate::srbf::validate_lights(&lights)?;
    let relative_l2 = relative_l2_error(map, &lights);
    progress(FitProgress::Done);
    Ok(FitReport {
        relative_l2,
        relative_l2_fit_initial: initial,
        relative_l2_fit: target.relative(outcome.sse),
        fit_width,
        fit_height,
        fit_samples: target.len(),
        bandwidth_range,
        iterations: outcome.iterations,
        map_integral: map.integral(),
        fit_integral: lights.iter().map(|l| l.integral()).sum(),
        lights,
        seconds: start.elapsed().as_secs_f64(),
    })
}

/// Alternates Levenberg–Marquardt with freeing duplicate lights and reviving dark ones (with fresh
/// NNLS coefficients), for at most `revive_rounds` + 1 refinements sharing `max_iterations`. A
/// round that ends worse than the one before is undone.
fn refine_and_revive(
    adaptive: &mut adaptive_target::AdaptiveTarget,
    params: params::Params,
    options: &FitOptions,
    kappa_range: (f64, f64),
    progress: &mut dyn FnMut(FitProgress),
) -> levenberg_marquardt::LmOutcome {
    let mut best = levenberg_marquardt::LmOutcome {
        sse: model::sum_squared_error(adaptive.target(), &params),
        params,
        iterations: 0,
    };
    for round in 0..=options.revive_rounds {
        let mut params = best.params.clone();
        let detailed = adaptive.refine_detail(adaptive_target::DETAIL_SHARE * best.sse);
        let freed = revive::merge_duplicates(&mut params);
        let revived = revive::revive_dead_lights(adaptive.target(), &mut params, kappa_range);
        let resolved = adaptive.resolve_lobes(&params.lobes());
        if freed + revived > 0 || resolved || detailed {
            coefficients::solve_coefficients(adaptive.target(), &mut params);
        } else if round > 0 {
            break;
        }
        let done = best.iterations;
        let settings = levenberg_marquardt::LmSettings {
            max_iterations: options.max_iterations - done,
            tolerance: options.tolerance,
            kappa_range,
        };
        let norm2 = adaptive.target().norm2;
        let relative = |sse: f64| {
            if norm2 > 0.0 {
                (sse / norm2).sqrt()
            } else {
                sse.sqrt()
            }
        };
        let outcome = levenberg_marquardt::refine(adaptive, params, &settings, &mut |i, sse| {
            progress(FitProgress::Iteration {
                iteration: done + i,
                max_iterations: options.max_iterations,
                relative_l2: relative(sse),
            })
        });
        let iterations = done + outcome.iterations;
        let previous = model::sum_squared_error(adaptive.target(), &best.params);
        if outcome.sse < previous || round == 0 {
            best = levenberg_marquardt::LmOutcome {
                iterations,
                ..outcome
            };
        } else {
            best.sse = previous;
            best.iterations = iterations;
            break;
        }
        if best.iterations >= options.max_iterations {
            break;
        }
    }
    best
}

/// The fit grid: `width` columns (at most the map's), rows in proportion.
fn fit_grid(map: &EnvMap, width: usize) -> (usize, usize) {
    let width = width.min(map.width());
    let height = ((width * map.height()) as f64 / map.width() as f64).round() as usize;
    (width, height.clamp(1, map.height()))
}

/// Most Levenberg–Marquardt iterations a fit may be asked for (it converges in tens).
pub const MAX_ITERATIONS: usize = 10_000;

fn validate(options: &FitOptions) -> Result<(), LightError> {
    let bad = |message: &str| Err(LightError::FitOptions(message.to_string()));
    if options.lights == 0 || options.lights > crate::MAX_LIGHTS {
        return Err(LightError::LightCount(options.lights));
    }
    if options.max_iterations > MAX_ITERATIONS {
        return bad("at most 10000 Levenberg–Marquardt iterations");
    }
    if options.fit_width < 8 {
        return bad("the fit grid must be at least 8 pixels wide");
    }
    let bandwidth = |name, b| crate::srbf::BANDWIDTH.named(name).check(b);
    let range_fault = options
        .min_bandwidth
        .map_or(Ok(0.0), |b| bandwidth("min_bandwidth", b))
        .and_then(|_| bandwidth("max_bandwidth", options.max_bandwidth));
    if let Err(e) = range_fault {
        return bad(&e.to_string());
    }
    if options.max_bandwidth < options.min_bandwidth.unwrap_or(0.0) {
        return bad("min_bandwidth must not exceed max_bandwidth");
    }
    if options.tolerance.is_nan() || options.tolerance < 0.0 {
        return bad("the tolerance must be ≥ 0");
    }
    Ok(())
}
