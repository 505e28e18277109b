//! The SRBF hair renderer of Xu et al. 2011, *Interactive Hair Rendering and Appearance Editing
//! under Environment Lighting* (Xu et al. 2011), on the CPU, with its brute-force reference.
//!
//! # Units and convention
//! The fiber crate's S is docs/conventions.md §3's: S = Σ_p ½ M_p N_p cos θ_o / cos²θ_d (power
//! fraction per steradian). The radiance a fiber shows, averaged across its projected width, is
//! L_o = (1/cos θ_o) ∫ S L_i cos θ_i dω_i = ∫ ½ M_p N_p / cos²θ_d L_i cos θ_i dω_i,
//! i.e. Marschner's L̄ = D ∫ S_M L_i cos θ_i dω_i divided by the width D, with his unit-integral
//! M_p(θ_h) taken as the density ½ M_p in θ_o that conserves energy (the fiber crate's module
//! documentation). Xu et al. 2011's eq. 2 is this with L_i = Σ_j L_j G_j; ½ M_p(θ_h) as a function
//! of θ_i is the unit normal density of mean 2α_p − θ_o and deviation 2β_p (Xu et al. 2011 eq. 7).
//! Pixels hold L_o times coverage plus the background for the rest.
//!
//! # The rooms
//! - [`scene`]: what a render is of — groom, environment and its SRBF fit, camera
//!   ([`scene::camera`]), hair parameters ([`scene::hair`]) — from a TOML file and/or flags.
//! - [`frame`]: the frame's stages and their timings ([`frame::renderer`]): drawing
//!   ([`frame::draw`]), shadows ([`frame::shadows`]), the fiber frame at each point, shading,
//!   resolve.
//! - [`tables`]: the precomputed functions shading reads, built once or when a hair parameter
//!   changes.
//! - [`srbf`]: the fast path, Xu et al. 2011's shading against SRBF lights: single scattering
//!   and dual scattering.
//! - [`brute`]: the reference twins of [`srbf`]'s files, with matching names, from the exact
//!   functions against the map as directional lights (`--method brute`).
//! - [`preview`]: what a live window's quick first frame after an edit leaves out.
//! - [`compare`]: two renders against each other over the hair (`cuticle compare`).
//! - [`angles`], [`fresnel`]: the small fiber optics both paths share; [`mod@bench`]: the paper's
//!   workload timed.

pub mod angles;
pub mod bench;
pub mod brute;
pub mod compare;
pub mod frame;
pub mod fresnel;
pub mod preview;
pub mod scene;
pub mod srbf;
pub mod tables;

pub use frame::progress::Progress;
pub use frame::renderer::{Image, Prepared, Renderer, TableBuilds, Timings, WorldLight};
pub use frame::reshade::Shaded;
pub use frame::shadows::ShadowOptions;
pub use scene::camera::Camera;
pub use scene::hair::HairParams;
pub use scene::{Lobes, Method, Scene, SceneError, SceneSpec};
