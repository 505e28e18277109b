//! Stage 4 on the GPU: L_o at every visible point, one invocation each. The WGSL is the CPU's
//! shading code in f32, file for file under the names of the files it ports:
//! 1. `bindings.wgsl`: the pass's inputs ([`ShadeParams`], tables, strands, points, shadows,
//!    lights) and its output (a colour per groom point);
//! 2. `grid.wgsl` (tables/grid.rs), `angles.wgsl` (angles.rs, fresnel.rs, the fiber frame),
//!    `circular_gaussian.wgsl`, `quadrature.wgsl`, `cg_lobes.wgsl` (with taylor.rs),
//!    `lobe_table.wgsl`: what both scatterings read;
//! 3. `single_scattering.wgsl` (srbf/single_scattering.rs), with the quadrature's integrands;
//! 4. `forward_scattering.wgsl` (with the averages of tables/back_scattering.rs) and
//!    `dual_scattering.wgsl` (srbf/dual_scattering.rs, function for function);
//! 5. `shade.wgsl`: the entry point, frame/renderer.rs's `SrbfFrame::shade`.
//!
//! Precision: f32 throughout. The one rewrite is the exponent of a product of circular
//! Gaussians, κ − κ₁ − κ₂ = 2κ₁κ₂(c − 1)/(κ + κ₁ + κ₂), which f32 would lose for sharp lobes.

use crate::tables::{GridDesc, slot};
use bytemuck::{Pod, Zeroable};

/// The WGSL of the pass, in the order above.
pub const SOURCE: [&str; 11] = [
    include_str!("bindings.wgsl"),
    include_str!("grid.wgsl"),
    include_str!("angles.wgsl"),
    include_str!("circular_gaussian.wgsl"),
    include_str!("quadrature.wgsl"),
    include_str!("cg_lobes.wgsl"),
    include_str!("lobe_table.wgsl"),
    include_str!("single_scattering.wgsl"),
    include_str!("forward_scattering.wgsl"),
    include_str!("dual_scattering.wgsl"),
    include_str!("shade.wgsl"),
];

/// Invocations per workgroup (shade.wgsl's `@workgroup_size`).
pub const WORKGROUP: u32 = 64;

/// The frame's uniform (bindings.wgsl's `Params`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct ShadeParams {
    pub eye: [f32; 3],
    pub visible: u32,
    pub eta: f32,
    pub alpha_r: f32,
    pub beta_r: f32,
    pub eccentricity: f32,
    pub caustic_bandwidth: f32,
    pub caustic_fade: f32,
    pub d_b: f32,
    pub cutoff: f32,
    pub lights: u32,
    pub m: u32,
    pub multiple: u32,
    pub sigma_scale: f32,
    pub min_z: f32,
    /// Bit t set: single-scattering lobe t (R, TT, TRT) shades ([`lobe_bits`]).
    pub lobes: u32,
    pub _pad: [f32; 2],
    pub grids: [GridDesc; slot::COUNT],
}

/// A visible point (bindings.wgsl's `Point`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct PointRecord {
    pub position: [f32; 3],
    pub strand: u32,
    pub tangent: [f32; 3],
    pub index: u32,
}

/// A light (bindings.wgsl's `Light`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct LightRecord {
    pub direction: [f32; 3],
    pub bandwidth: f32,
    pub radiance: [f32; 3],
    pub _pad: f32,
}

/// The compiled pass.
pub fn pipeline(device: &wgpu::Device) -> wgpu::ComputePipeline {
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("shade"),
        source: wgpu::ShaderSource::Wgsl(SOURCE.concat().into()),
    });
    device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("shade"),
        layout: None,
        module: &module,
        entry_point: Some("shade"),
        compilation_options: Default::default(),
        cache: None,
    })
}

/// Workgroups for `points` invocations, as (x, y) within the 65,535 a dimension allows
/// (shade.wgsl folds y back into the point index).
pub fn workgroups(points: usize) -> (u32, u32) {
    let groups = (points as u32).div_ceil(WORKGROUP);
    let x = groups.clamp(1, 65_535);
    (x, groups.div_ceil(x))
}

/// The scene's lobe mask as `ShadeParams::lobes`: bit t for lobe t of [R, TT, TRT].
pub fn lobe_bits(lobes: cuticle_render::Lobes) -> u32 {
    lobes
        .mask()
        .iter()
        .enumerate()
        .map(|(t, &on)| u32::from(on) << t)
        .sum()
}
