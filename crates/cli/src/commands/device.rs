//! `--device auto|gpu|cpu` for `render` and `bench render`: which renderer runs the scene
//! (crate cuticle-gpu's choice), the GPU render and benchmark, and what render.json and
//! bench.json record about the device.

use anyhow::{Result, bail};
use cuticle_gpu::bench::GpuBenchReport;
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

/// The GPU benchmark.
pub fn bench(
    device: &GpuDevice,
    cpu: &Renderer,
    scene: &Scene,
    frames: usize,
) -> Result<GpuBenchReport> {
    let gpu = GpuRenderer::new(device, cpu);
    Ok(cuticle_gpu::bench::run(&gpu, scene, frames)?)
}

/// bench.json's `"seconds"` and `"device"` of a GPU run.
pub fn bench_json(device: &GpuDevice, r: &GpuBenchReport) -> Value {
    json!({
        "device": { "name": "gpu", "adapter": device.summary, "stages_on_cpu": ["background"] },
        "frames": r.frames,
        "visible_points": r.visible_points,
        "seconds": {
            "full_frame": {
                "drawing": r.full.drawing,
                "shadows": r.full.shadows,
                "upload": r.upload,
                "shading": r.full.shading,
                "resolve": r.full.resolve,
                "frame": r.full_frame,
                "gpu_timestamps": r.full_gpu,
            },
            "rerender": {
                "shading": r.rerender.shading,
                "resolve": r.rerender.resolve,
                "frame": r.rerender_frame,
                "gpu_timestamps": r.rerender_gpu,
            },
        },
    })
}

/// The GPU benchmark's summary line.
pub fn print_bench(device: &GpuDevice, r: &GpuBenchReport) {
    let f = &r.full;
    let stamps = match (r.full_gpu, r.rerender_gpu) {
        (Some(f), Some(g)) => format!(
            "GPU timestamps: full frame drawing {:.4} s, shadows {:.4} s, shading {:.4} s, resolve {:.4} s; re-render shading {:.4} s, resolve {:.4} s",
            f.drawing, f.shadows, f.shading, f.resolve, g.shading, g.resolve
        ),
        _ => "no timestamp queries on this adapter".to_string(),
    };
    println!(
        "{} ({}): median of {} frames, {} visible points: full frame {:.3} s (drawing {:.3}, upload {:.3}, shadows {:.3}, shading {:.3}, resolve {:.3}); {}; {stamps}",
        device.summary.name,
        device.summary.kind,
        r.frames,
        r.visible_points,
        r.full_frame,
        f.drawing,
        r.upload,
        f.shadows,
        f.shading,
        f.resolve,
        crate::commands::render::rerender_summary(r.rerender_frame, &r.rerender),
    );
}
