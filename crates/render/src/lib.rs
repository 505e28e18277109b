//! The SRBF hair renderer of Xu et al. 2011, *Interactive Hair Rendering and Appearance Editing
//! under Environment Lighting* (Xu et al. 2011), on the CPU, with its brute-force reference.
//!
//! # Units and convention
//! The fiber crate's S is docs/conventions.md §3's: S = Σ_p ½ M_p N_p cos θ_o / cos²θ_d (power fraction per
//! steradian). The radiance a fiber shows, averaged across its projected width, is
//! L_o = (1/cos θ_o) ∫ S L_i cos θ_i dω_i = ∫ ½ M_p N_p / cos²θ_d L_i cos θ_i dω_i,
//! i.e. Marschner's L̄ = D ∫ S_M L_i cos θ_i dω_i divided by the width D, with his unit-integral
//! M_p(θ_h) taken as the density ½ M_p in θ_o that conserves energy (the fiber crate's module
//! documentation). Xu et al. 2011's eq. 2 is this with L_i = Σ_j L_j G_j; ½ M_p(θ_h) as a function
//! of θ_i is the unit normal density of mean 2α_p − θ_o and deviation 2β_p (Xu et al. 2011 eq. 7).
//! Pixels hold L_o times coverage plus the background for the rest.
//!
//! # Where things are
//! - The frame: [`renderer`] (stages and their timings), [`scene`], [`camera`], [`raster`]
//!   (supersampled strands), [`shadow`] (deep opacity maps filtered per light).
//! - Built once: [`tables`] (Xu et al. 2011 §5's 𝒞_k and ℋ_k), [`half_circle`], [`spread`].
//! - Rebuilt when a hair parameter changes, kept across absorption edits ([`last_built`]):
//!   [`lobe_table`] (the TT/TRT circular Gaussians of [`cg_lobes`] over θ_d × absorption),
//!   [`back_scattering_tables`] (Zinke's averages), both on the shared [`absorption_axis`].
//! - Shading: [`single_scattering`] (eq. 11 with [`quadrature`] and [`circular_gaussian`]),
//!   [`dual_scattering`] with [`forward_scattering`].
//! - The reference: [`brute`] and [`brute_multiple`] from the exact functions
//!   ([`exact_azimuthal`], [`exact_half_circle`]).

pub mod absorption_axis;
pub mod angles;
pub mod back_scattering_tables;
pub mod bench;
pub mod brute;
pub mod brute_multiple;
pub mod camera;
pub mod cg_lobes;
pub mod circular_gaussian;
pub mod dual_scattering;
pub mod exact_azimuthal;
pub mod exact_half_circle;
pub mod fiber_frames;
pub mod forward_scattering;
pub mod fresnel;
pub mod grid;
pub mod hair;
pub mod half_circle;
pub mod last_built;
pub mod lobe_table;
pub mod progress;
pub mod quadrature;
pub mod raster;
pub mod renderer;
pub mod scene;
pub mod shadow;
pub mod single_scattering;
pub mod spread;
pub mod tables;
pub mod taylor;

pub use camera::Camera;
pub use hair::HairParams;
pub use progress::Progress;
pub use renderer::{Image, Prepared, Renderer, Timings};
pub use scene::{Method, Scene, SceneError, SceneSpec};
pub use shadow::ShadowOptions;
