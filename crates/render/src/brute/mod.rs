//! The reference (`--method brute`): the exact Marschner 2003 model against the environment as
//! 6 n² directional lights, each file the twin of the SRBF file of the same name.
//! - [`single_scattering`]: the lights and their direct light, the twin of
//!   [`crate::srbf::single_scattering`];
//! - [`dual_scattering`]: the same dual-scattering terms from the exact functions, the twin of
//!   [`crate::srbf::dual_scattering`];
//! - [`exact_azimuthal`]: the exact N_p the circular Gaussians of [`crate::srbf::cg_lobes`]
//!   approximate; [`half_circle`]: their half-circle averages, the twin of
//!   [`crate::tables::half_circle`].

pub mod dual_scattering;
pub mod exact_azimuthal;
pub mod half_circle;
pub mod single_scattering;
