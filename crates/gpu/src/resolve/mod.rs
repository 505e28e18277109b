//! Stage 5 on the GPU: subsamples averaged into pixels (`resolve.wgsl`, frame/renderer.rs's
//! `Renderer::resolve`).

use bytemuck::{Pod, Zeroable};

/// resolve.wgsl's `ResolveParams`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct ResolveParams {
    pub width: u32,
    pub height: u32,
    pub ss: u32,
    pub _pad: u32,
}

/// Invocations per workgroup along each image axis (resolve.wgsl's `@workgroup_size`).
pub const TILE: u32 = 8;

/// The compiled pass.
pub fn pipeline(device: &wgpu::Device) -> wgpu::ComputePipeline {
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("resolve"),
        source: wgpu::ShaderSource::Wgsl(include_str!("resolve.wgsl").into()),
    });
    crate::buffers::compute_pipeline(device, &module, "resolve")
}
