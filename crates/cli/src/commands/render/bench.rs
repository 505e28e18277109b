//! `cuticle bench render`: the renderer on the paper's workload ([`cuticle_render::bench`],
//! or the GPU's [`cuticle_gpu::bench`]), medians of full frames and of each edit's re-render,
//! with its `bench.json`; `cuticle bench trace` is the path tracer's ([`super::path`]).

use super::gpu;
use super::record::seconds_json;
use super::scene_args::load_within_memory;
use crate::output::OutDir;
use anyhow::Result;
use cuticle_fiber::ranges::CountRange;
use cuticle_gpu::bench::GpuBenchReport;
use cuticle_gpu::{Backend, Choice, GpuDevice, GpuRenderer};
use cuticle_render::bench::{BenchReport, Edit};
use cuticle_render::{Renderer, Scene, SceneSpec, Timings};
use serde_json::{Value, json};
use std::path::PathBuf;

/// `cuticle bench`: what to benchmark.
#[derive(clap::Subcommand, Clone, Debug)]
pub enum Bench {
    /// The renderer on the paper's workload (default groom, 40 SRBF lights, 720x480, single and
    /// multiple scattering): medians of full frames and of re-renders after an absorption edit.
    Render(BenchArgs),
    /// The path tracer: BVH build time, ray casting and path tracing rays/s and spp/s
    /// (default: straight.hair at 360x240 under the procedural sky).
    Trace(super::path::TraceBenchArgs),
}

#[derive(clap::Args, Clone, Debug)]
pub struct BenchArgs {
    /// Strands of the default groom.
    #[arg(long)]
    strands: Option<usize>,
    #[arg(long)]
    width: Option<usize>,
    #[arg(long)]
    height: Option<usize>,
    /// Frames timed for each median (1 to 1000).
    #[arg(long, default_value_t = 3)]
    frames: usize,
    /// auto (a hardware GPU where one exists, else the CPU), gpu or cpu.
    #[arg(long, default_value = "auto")]
    device: Choice,
    /// Output folder.
    #[arg(long, default_value = "out/bench-render")]
    out: PathBuf,
}

pub fn bench(command: Bench) -> Result<()> {
    let args = match command {
        Bench::Render(args) => args,
        Bench::Trace(args) => return super::path::bench(&args),
    };
    let mut spec = SceneSpec::default();
    args.strands.into_iter().for_each(|v| spec.strands = v);
    args.width.into_iter().for_each(|v| spec.width = v);
    args.height.into_iter().for_each(|v| spec.height = v);
    FRAMES.check_usize(args.frames)?;
    let scene = load_within_memory(spec, None)?;
    let backend = gpu::choose(args.device, scene.spec.method)?;
    let out = OutDir::create(&args.out, "bench")?;
    let renderer = Renderer::new();
    eprintln!(
        "bench: {} strands, {} SRBF lights, {}x{}, {} frames",
        scene.groom.strand_count(),
        scene.lights.len(),
        scene.spec.width,
        scene.spec.height,
        args.frames
    );
    if let Backend::Gpu(d) = &backend {
        let report = gpu_bench(d, &renderer, &scene, args.frames)?;
        let mut record = gpu_bench_json(d, &report);
        record["params"] = serde_json::to_value(&scene.spec)?;
        record["strands"] = json!(scene.groom.strand_count());
        record["points"] = json!(scene.groom.point_count());
        record["lights"] = json!(scene.lights.len());
        record["shaded_lights"] = json!(scene.shaded_lights());
        record["seconds"]["tables"] = json!(renderer.table_seconds);
        record["seconds"]["srbf_fit"] = json!(scene.fit_seconds);
        out.finish(record)?;
        print_gpu_bench(d, &report);
        return Ok(());
    }
    let report = cuticle_render::bench::run(&renderer, &scene, args.frames);
    out.finish(bench_json(&scene, &renderer, &report)?)?;
    print_bench(&report);
    Ok(())
}

/// Frames one benchmark times.
const FRAMES: CountRange = CountRange {
    name: "frames",
    min: 1,
    max: 1000,
};

/// bench.json: the scene's parameters and the median seconds.
fn bench_json(scene: &Scene, renderer: &Renderer, report: &BenchReport) -> Result<Value> {
    let edits: serde_json::Map<String, Value> = report
        .edits
        .iter()
        .map(|e| {
            let name = serde_json::to_value(e.edit).map(|v| v.as_str().unwrap_or("").to_owned());
            Ok((
                name?,
                json!({ "stages": seconds_json(&e.timings), "frame": e.frame }),
            ))
        })
        .collect::<Result<_>>()?;
    Ok(json!({
        "params": serde_json::to_value(&scene.spec)?,
        "strands": scene.groom.strand_count(),
        "points": scene.groom.point_count(),
        "lights": scene.lights.len(),
        "shaded_lights": scene.shaded_lights(),
        "device": gpu::cpu_json(),
        "frames": report.frames,
        "visible_points": report.visible_points,
        "seconds": {
            "tables": renderer.table_seconds,
            "srbf_fit": scene.fit_seconds,
            "full_frame": seconds_json(&report.full),
            "frame": report.full_frame,
            "edits": edits,
        },
    }))
}

fn print_bench(r: &BenchReport) {
    let f = &r.full;
    println!(
        "median of {} frames, {} visible points: full frame {:.3} s (drawing {:.3}, shadows {:.3}, shading {:.3}, resolve {:.3}); tables {:.2} s once",
        r.frames,
        r.visible_points,
        r.full_frame,
        f.drawing,
        f.shadows,
        f.shading,
        f.resolve,
        f.tables
    );
    let absorption = r.edit(Edit::Absorption);
    println!(
        "{}",
        rerender_summary(absorption.frame, &absorption.timings)
    );
    for e in r.edits.iter().filter(|e| e.edit != Edit::Absorption) {
        let t = &e.timings;
        println!(
            "re-render after {} {:.3} s (drawing {:.3}, shadows {:.3}, shading {:.3}, resolve {:.3})",
            edit_name(e.edit),
            e.frame,
            t.drawing,
            t.shadows,
            t.shading,
            t.resolve
        );
    }
}

/// How the benchmark's printout names an edit.
fn edit_name(edit: Edit) -> &'static str {
    match edit {
        Edit::Absorption => "an absorption edit",
        Edit::Roughness => "a beta_R/alpha_R edit",
        Edit::Eta => "an eta edit",
        Edit::Camera => "a camera orbit",
    }
}

/// The re-render after an absorption edit, as both devices' benchmarks print it.
fn rerender_summary(frame: f64, t: &Timings) -> String {
    format!(
        "re-render after an absorption edit {frame:.4} s (shading {:.4}, resolve {:.4}), {:.1} frames/s",
        t.shading,
        t.resolve,
        1.0 / frame.max(1e-9)
    )
}

/// The GPU benchmark.
fn gpu_bench(
    device: &GpuDevice,
    cpu: &Renderer,
    scene: &Scene,
    frames: usize,
) -> Result<GpuBenchReport> {
    let gpu = GpuRenderer::new(device, cpu);
    Ok(cuticle_gpu::bench::run(&gpu, scene, frames)?)
}

/// bench.json's `"seconds"` and `"device"` of a GPU run.
fn gpu_bench_json(device: &GpuDevice, r: &GpuBenchReport) -> Value {
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
fn print_gpu_bench(device: &GpuDevice, r: &GpuBenchReport) {
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
        rerender_summary(r.rerender_frame, &r.rerender),
    );
}
