//! A path tracer of grooms under environment light: the ground truth of the renderers, and the
//! fiber crate's models at work on real hair (`cuticle render --method path`).
//!
//! The pipeline, one file a step:
//! 1. [`tubes`]: each strand as a chain of mitred round tubes of the strand's width; a hit
//!    gives the fiber frame (tangent u, offset h) of docs/conventions.md §2;
//! 2. [`accel`]: the tubes in a BVH (obvhs's CWBVH);
//! 3. [`env_sampling`]: a 2D CDF over the lat-long map for environment importance sampling;
//! 4. [`models`]: the fiber model of each strand (Marschner 2003 from the scene's hair
//!    parameters, as the SRBF renderer shades, or any model of the fiber crate);
//! 5. [`path`]: the estimator of one camera sample, with its weights derived: environment and
//!    BCSDF sampling with multiple importance sampling, Russian roulette, a depth limit;
//! 6. [`render`]: progressive passes, seeded per pixel-sample so the image is the same on any
//!    number of threads, with each pixel's standard error.
//!
//! The scene (groom, environment, camera, image size) is the render crate's [`Scene`], read as
//! the SRBF renderer reads it, so `--method srbf|brute|path` render the same picture.

pub mod accel;
pub mod env_sampling;
pub mod models;
pub mod path;
pub mod render;
pub mod tubes;

pub use accel::Accel;
pub use models::StrandModels;
pub use path::{PathOptions, Strategy};
pub use render::{MAX_DEPTH, SPP, TraceImage, TraceOptions, TraceStats, render, render_with};

#[doc(no_inline)]
pub use cuticle_render::Scene;
