//! Hair fiber scattering: the fiber frame and angles, the numerics and optics the models share,
//! and the models themselves, each able to evaluate S (docs/conventions.md §3),
//! importance-sample it and report the sampling pdf through [`FiberModel`].
//!
//! The rooms, lowest first (each uses only the ones above it):
//! - [`math`]: special functions by family, quadrature, Blinn's cubic, vMF, table helpers;
//! - [`geometry`]: the fiber frame, the lat-long grid, Bravais' refraction, Nusselt rotations;
//! - [`optics`]: Fresnel, melanin absorption, d'Eon 2011's attenuation, Beckmann, the rough
//!   interface;
//! - [`lobes`]: longitudinal lobes, the wrapped Gaussian, skewed sine lobes;
//! - [`models`]: one folder per model — [`Marschner2003`], [`DEon2011`] (with its azimuthal
//!   table), [`Chiang2016`] (near-field in h, [`FiberModel::eval_at`]) and [`NonSeparable`]
//!   (whose tilted and rough scales are its own rooms, which d'Eon 2011 does not see);
//! - [`registry`]: every model by name ([`ModelId`]), built tabulated or direct; [`spec`], a
//!   named model with its parameters checked ([`ModelSpec`]); [`furnace`], the white-furnace
//!   integrator.
//!
//! Adding a model: its folder under `models/` implementing [`FiberModel`] (and
//! [`FiberModel::tabulate`] if it has a fast path), its `pub mod` line in `models/mod.rs`, its
//! variant of [`ModelId`] and its one line in the registry (`registry.rs`). The command line,
//! the validation, the path tracer and the benches then offer it by its name.
//!
//! ```
//! use cuticle_fiber::{DEon2011, FiberAngles, FiberModel, FiberParams};
//! let model = DEon2011::new(FiberParams::default()).unwrap();
//! let wi = FiberAngles::new(0.5, 0.0);
//! let s = model.eval(wi, FiberAngles::new(-0.5, 0.3));
//! assert!(s.total().min_element() > 0.0);
//! let sample = model.sample(wi, [0.3, 0.6, 0.2, 0.9]).unwrap();
//! assert!(sample.pdf > 0.0);
//! ```

pub mod furnace;
pub mod geometry;
pub mod lobe;
pub mod lobes;
pub mod math;
pub mod model;
pub mod models;
pub mod optics;
pub mod params;
pub mod ranges;
pub mod registry;
pub mod spec;
#[cfg(test)]
pub(crate) mod testing;

pub use geometry::frame::{FiberAngles, FiberFrame, wrap_pi};
pub use geometry::latlong::{LatLongGrid, LatLongImage};
pub use lobe::{Lobe, LobeValues};
pub use model::{FiberModel, FiberSample};
pub use models::chiang2016::Chiang2016;
pub use models::deon2011::DEon2011;
pub use models::marschner2003::Marschner2003;
pub use models::nonseparable::NonSeparable;
pub use params::{FiberParams, ParamError};
pub use ranges::{Range, RangeError};
pub use registry::{BuildOptions, ModelId, Tabulation};
pub use spec::{ModelSpec, SpecError};
