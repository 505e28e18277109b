//! `cuticle render`: a scene from flags and/or a TOML file ([`scene_args`]) rendered by one
//! method on one device, and the output set: `image.png` (tone-mapped), `image.exr` (linear),
//! `coverage.exr` (each pixel's hair coverage, the mask `cuticle compare` reads) and
//! `render.json` with every parameter and the seconds of each stage ([`record`]).
//! - `--method srbf|brute`: Xu et al. 2011's renderer (crate cuticle-render) and its reference,
//!   on the CPU or, for srbf, the GPU ([`gpu`]);
//! - `--method path`: the path tracer ([`path`]);
//! - `cuticle bench render|trace`: their benchmarks ([`bench`]).

pub mod bench;
pub mod gpu;
pub mod path;
pub mod record;
pub mod scene_args;

pub use bench::{Bench, bench};
pub use scene_args::{SceneArgs, spec_from};

use crate::output::OutDir;
use crate::progress::bar;
use anyhow::Result;
use cuticle_gpu::{Backend, Choice};
use cuticle_light::ToneMap;
use cuticle_render::{Method, Renderer};
use record::{check_finite, coverage_image, multiple_json, seconds_json};
use scene_args::load_within_memory;
use serde_json::json;
use std::path::PathBuf;

#[derive(clap::Args, Clone, Debug)]
pub struct Args {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Output folder.
    #[arg(long, default_value = "out/render")]
    out: PathBuf,
    /// auto (a hardware GPU where one exists, else the CPU), gpu (any adapter, a software one
    /// included) or cpu.
    #[arg(long, default_value = "auto")]
    device: Choice,
    #[command(flatten)]
    path: path::PathArgs,
}

pub fn run(args: Args) -> Result<()> {
    let (spec, lights) = spec_from(&args.scene)?;
    if spec.method == Method::Path {
        if lights.is_some() {
            // Issue 57 #9: the file was read, then ignored.
            anyhow::bail!(
                "--lights FILE is for --method srbf and brute; the path tracer samples the \
                 environment map itself (give --env)"
            );
        }
        gpu::choose(args.device, spec.method)?;
        return path::run(&args.path, spec, &args.out);
    }
    args.path.check_unused(if spec.method == Method::Brute {
        "brute"
    } else {
        "srbf"
    })?;
    let scene = load_within_memory(spec, lights)?;
    Renderer::accepts(&scene)?;
    // The device is probed only once the scene is known to be good: bad input fails fast.
    let backend = gpu::choose(args.device, scene.spec.method)?;
    let mut out = OutDir::create(&args.out, "render")?;
    let renderer = Renderer::new();
    eprintln!(
        "rendering {} strands ({} points) under {} SRBF lights ({} shaded) at {}x{}, method {:?}, on {}",
        scene.groom.strand_count(),
        scene.groom.point_count(),
        scene.lights.len(),
        scene.shaded_lights(),
        scene.spec.width,
        scene.spec.height,
        scene.spec.method,
        match &backend {
            Backend::Cpu => "the CPU".to_string(),
            Backend::Gpu(d) => format!("{} ({})", d.summary.name, d.summary.kind),
        }
    );
    let (image, visible_points, coverage, visibility, timings, device_json) = match &backend {
        Backend::Cpu => {
            let progress = bar(0, "shade");
            let report = |done: usize, total: usize| {
                progress.set_length(total as u64);
                progress.set_position(done as u64);
            };
            let (image, prepared, timings) = renderer.render_with_progress(&scene, &report);
            progress.finish_and_clear();
            let cov = prepared.coverage.covered_fraction();
            let n = prepared.points.len();
            (image, n, cov, prepared.coverage, timings, gpu::cpu_json())
        }
        Backend::Gpu(d) => {
            let r = gpu::render(d, &renderer, &scene)?;
            (
                r.image,
                r.visible_points,
                r.coverage,
                r.visibility,
                r.timings,
                r.device,
            )
        }
    };
    check_finite(&image, "an image")?;
    let tone = ToneMap::for_map(&scene.env);
    out.write("image.png", &image.png_bytes(tone)?)?;
    out.write("image.exr", &image.exr_bytes()?)?;
    out.write("coverage.exr", &coverage_image(&visibility).exr_bytes()?)?;
    let record = json!({
        "params": serde_json::to_value(&scene.spec)?,
        "strands": scene.groom.strand_count(),
        "points": scene.groom.point_count(),
        "lights": scene.lights.len(),
        "shaded_lights": scene.shaded_lights(),
        "srbf_fit_relative_l2": scene.fit_error,
        "srbf_fit_source": scene.fit_source,
        "visible_points": visible_points,
        "coverage": coverage,
        "device": device_json,
        "multiple_scattering": multiple_json(&scene),
        "seconds": seconds_json(&timings),
    });
    out.finish(record)?;
    println!(
        "{}: {} visible points shaded in {:.2} s; frame {:.2} s (drawing {:.2}, shadows {:.2}, shading {:.2}, resolve {:.2}; tables {:.2}, fit {:.2})",
        args.out.display(),
        visible_points,
        timings.shading,
        timings.drawing + timings.shadows + timings.shading + timings.resolve,
        timings.drawing,
        timings.shadows,
        timings.shading,
        timings.resolve,
        timings.tables,
        timings.srbf_fit
    );
    Ok(())
}
