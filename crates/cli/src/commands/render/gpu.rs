//! `--device auto|gpu|cpu` for `render` and `bench render`: which back end runs the scene
//! (crate cuticle-gpu's [`Backend`] choice, the one both the CLI and the window use), the GPU
//! render, and what render.json records about the device.

use anyhow::{Result, bail};
use cuticle_gpu::{Backend, Choice, GpuDevice, GpuRenderer};
use cuticle_render::{Image, Method, Renderer, Scene, Timings};
use serde_json::{Value, json};

/// Resolves `--device` for `method` before any work: the brute force and the path tracer run
/// on the CPU only.
pub fn choose(choice: Choice, method: Method) -> Result<Backend> {
    match (method, choice) {
        (Method::Srbf, choice) => Ok(Backend::choose(choice)?),
        (_, Choice::Gpu) => {
            bail!("--method {method:?} runs on the CPU only: use --device cpu or auto")
        }
        (_, _) => Ok(Backend::Cpu),
    }
}

/// One GPU frame as `render` reports it.
pub struct GpuRendered {
    pub image: Image,
    pub visible_points: usize,
    pub coverage: f64,
    /// The visibility buffer drawn (for coverage.exr).
    pub visibility: cuticle_render::frame::draw::Coverage,
    pub timings: Timings,
    pub device: Value,
}

/// The scene on the GPU: prepare (drawing and shadows), shade, resolve, and the visibility
/// buffer read back.
pub fn render(device: &GpuDevice, cpu: &Renderer, scene: &Scene) -> Result<GpuRendered> {
    let gpu = GpuRenderer::new(device, cpu);
    let (image, frame) = gpu.render(scene)?;
    let visibility = gpu.coverage(&frame);
    Ok(GpuRendered {
        visible_points: frame.visible_count(),
        coverage: visibility.covered_fraction(),
        visibility,
        timings: frame.timings(),
        device: json!({
            "name": "gpu",
            "adapter": device.summary,
            "passes": frame.passes(),
            "upload_seconds": frame.upload_seconds(),
            "gpu_seconds": frame.gpu_seconds(),
            "stages_on_cpu": ["background"],
        }),
        image,
    })
}

/// render.json's `"device"` for the CPU renderer.
pub fn cpu_json() -> Value {
    json!({ "name": "cpu" })
}
