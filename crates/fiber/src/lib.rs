//! Hair fiber scattering: the shared fiber frame and lat-long grid, the special functions and
//! Fresnel factors the models share, and the models themselves — [`Marschner2003`],
//! [`DEon2011`] and [`NonSeparable`] — each able to evaluate S (DESIGN.md §3), importance-sample
//! it and report the sampling pdf.

pub mod frame;
pub mod latlong;

pub use frame::{FiberAngles, FiberFrame, wrap_pi};
pub use latlong::{LatLongGrid, LatLongImage};
