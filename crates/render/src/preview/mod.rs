//! Preview quality: the quick frame a live window shows first after an edit. Shading costs per
//! visible point × light × quadrature segment, and an edit of a parameter the back-scattering
//! tables depend on rebuilds them before it shades, so a preview scene
//! ([`preview_scene`]) cuts
//! - the pixels (`scale` times fewer along each axis, the caller's choice) and subsamples (one);
//! - the lights: the scene's lights, the wide ones split ([`crate::frame::sub_lights`]) at
//!   [`PREVIEW_SPLIT_BANDWIDTH`], merged into [`PREVIEW_LIGHTS`] carrying the same energy
//!   ([`merged_lights`]), and not split again;
//! - the linear quadrature to at most [`PREVIEW_QUADRATURE`] segments (Xu et al. 2011 §4.2.2);
//!
//! and a preview renderer ([`crate::Renderer::for_preview`]) builds its back-scattering tables
//! on a [`PREVIEW_TABLE_NODES`]² grid instead of the full one.

pub mod merged_lights;

use crate::frame::sub_lights::split_wide;
use crate::scene::Scene;

/// Lights a preview shades with.
pub const PREVIEW_LIGHTS: usize = 8;
/// Largest number of quadrature segments a preview integrates with.
pub const PREVIEW_QUADRATURE: usize = 2;
/// Nodes along each axis of a preview renderer's back-scattering tables.
pub const PREVIEW_TABLE_NODES: usize = 16;

/// The sub-lights' width of the split that is merged into a preview's lights: the pieces the
/// clusters are made of, kept at what the merge was measured with (BENCHMARKS.md "The window"),
/// whatever the full frame's [`crate::ShadowOptions::split_bandwidth`] (finer pieces make no better
/// eight lights).
pub const PREVIEW_SPLIT_BANDWIDTH: f64 = 0.5;

/// The split bandwidth of a preview scene: the largest a scene accepts
/// ([`crate::scene::SHADOW_SPLIT_BANDWIDTH`]), above any light's bandwidth, so none is split.
pub const NO_SPLIT: f64 = 1000.0;

/// The scene at preview quality: `scale` times fewer pixels along each axis, one subsample,
/// the frame's lights merged into [`PREVIEW_LIGHTS`] (and split no further) and a coarser
/// quadrature.
pub fn preview_scene(scene: &Scene, scale: usize) -> Scene {
    let mut s = scene.clone();
    let scale = scale.max(1);
    s.spec.width = scene.spec.width.div_ceil(scale).max(1);
    s.spec.height = scene.spec.height.div_ceil(scale).max(1);
    s.spec.supersampling = 1;
    s.spec.quadrature = scene.spec.quadrature.min(PREVIEW_QUADRATURE);
    s.lights = preview_lights(scene);
    s.spec.shadows.split_bandwidth = NO_SPLIT;
    s
}

/// The scene's lights (wide ones split at [`PREVIEW_SPLIT_BANDWIDTH`]) merged into
/// [`PREVIEW_LIGHTS`].
pub fn preview_lights(scene: &Scene) -> Vec<cuticle_light::SrbfLight> {
    let split = split_wide(&scene.lights, PREVIEW_SPLIT_BANDWIDTH);
    merged_lights::merge_lights(&split, PREVIEW_LIGHTS)
}
