//! Hair fiber scattering: the shared fiber frame and lat-long grid, the special functions and
//! Fresnel factors the models share, and the models themselves — [`Marschner2003`],
//! [`DEon2011`], [`NonSeparable`] and [`Chiang2016`] (near-field in h, [`FiberModel::eval_at`]) — each able to evaluate S (docs/conventions.md §3), importance-sample
//! it and report the sampling pdf through [`FiberModel`]. [`table::AzimuthalTable`] is the fast
//! path for the azimuthal terms of the last two, [`furnace`] the white-furnace integrator.
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

pub mod absorption;
pub mod attenuation;
pub mod azimuthal;
pub mod beckmann;
pub mod bravais;
pub mod chiang2016;
pub mod cubic;
pub mod deon2011;
pub mod frame;
pub mod fresnel;
pub mod furnace;
pub mod latlong;
pub mod lobe;
pub mod longitudinal;
pub mod marschner2003;
pub mod model;
pub mod nonseparable;
pub mod nusselt;
pub mod params;
pub mod ranges;
pub mod rough_deflection;
pub mod rough_interface;
pub mod rough_trt;
pub mod sine_lobe;
pub mod special;
pub mod table;
#[cfg(test)]
pub(crate) mod testing;
pub mod tilted_attenuation;
pub mod tilted_deflection;
pub mod tilted_mirror;
pub mod vmf;

pub use chiang2016::Chiang2016;
pub use deon2011::DEon2011;
pub use frame::{FiberAngles, FiberFrame, wrap_pi};
pub use latlong::{LatLongGrid, LatLongImage};
pub use lobe::{Lobe, LobeValues};
pub use marschner2003::Marschner2003;
pub use model::{FiberModel, FiberSample};
pub use nonseparable::NonSeparable;
pub use params::{FiberParams, ParamError};
pub use ranges::{Range, RangeError};
