//! Validation of the fiber models against the Monte Carlo ground truth of `cuticle-sim`
//! (d'Eon et al. 2014 §2.1 and Figure 7).
//!
//! For a simulated configuration and a model: [`pixel_integral`] renders the model's lobe images
//! on the simulation's lat-long grid, each pixel the mean of S over the pixel (not S at its
//! centre); [`metrics`] compares them lobe by lobe (relative L1 error, energy difference, error
//! in θ of the lobe's peak, [`peak`]); [`summary`] aggregates the figures of a whole sweep into
//! the tables of `validation.md`, and [`sheet`] stacks images into Figure 7-like sheets.
//! Given two simulations of each configuration with different seeds, [`noise`] measures the
//! noise floor every figure sits on; [`moments`] gives a lobe's mean, width and skew in θ per
//! φ column, to say how a model's lobe differs where it does.
//!
//! ```no_run
//! use cuticle_validate::{ModelId, SimConfig, compare_config};
//! let dir = std::path::Path::new("out/sweep-small/ti0.75_a-2_b0.04_mu0_eta1.55");
//! let config = SimConfig::read(dir).unwrap();
//! # let sim_images: [cuticle_fiber::LatLongImage; 5] = unimplemented!();
//! let figures = compare_config(&config, ModelId::NonSeparable, &sim_images).unwrap();
//! println!("R error {:?}", figures.lobes[0].relative_l1);
//! ```

pub mod compare;
pub mod error;
pub mod metrics;
pub mod models;
pub mod moments;
pub mod noise;
pub mod peak;
pub mod pixel_integral;
pub mod sheet;
pub mod summary;
pub mod summary_verdict;
pub mod sweep_dir;

pub use compare::{ConfigFigures, compare_config, images_of, model_images};
pub use cuticle_fiber::ModelId;
pub use error::ValidateError;
pub use metrics::{LobeFigures, lobe_figures};
pub use models::{build_model, parse_models};
pub use pixel_integral::{PixelRule, integrate_lobes};
pub use summary::{Row, csv, markdown};
pub use sweep_dir::{SimConfig, list_configs};
