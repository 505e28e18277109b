//! The precomputed functions shading reads.
//! - Built once per process, independent of every hair parameter: [`cg_integrals`] (Xu et al.
//!   2011 §5's 𝒞_k and ℋ_k, with N_R's Fresnel quintic from [`r_fresnel`]), [`half_circle`]
//!   (half-circle integrals of circular Gaussians),
//!   [`spread`] (the normalisation of a light's spread in inclination).
//! - Rebuilt when a hair parameter changes and kept across absorption edits by [`last_built`]:
//!   [`lobe_table`] (the TT/TRT circular Gaussians over θ_d × absorption) and
//!   [`back_scattering`] (Zinke et al. 2008's averages), both on the shared
//!   [`absorption_axis`].
//! - Their storage: [`grid`], a regular 2D grid with bilinear lookup.

pub mod absorption_axis;
pub mod back_scattering;
pub mod cg_integrals;
pub mod grid;
pub mod half_circle;
pub mod last_built;
pub mod lobe_table;
pub mod r_fresnel;
pub mod spread;
