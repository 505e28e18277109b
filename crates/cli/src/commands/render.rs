//! `cuticle render`: the hair renderer of Xu et al. 2011 (crate cuticle-render) on a scene from
//! flags and/or a TOML file: `image.png` (tone-mapped), `image.exr` (linear), `coverage.exr` (each
//! pixel's hair coverage, the mask `cuticle compare` reads) and `render.json` with
//! every parameter and the seconds of each stage; and `cuticle bench render`, the renderer's
//! benchmark ([`cuticle_render::bench`]) with its `bench.json`.

use crate::commands::device;
use crate::output::OutDir;
use crate::progress::bar;
use anyhow::{Context, Result};
use cuticle_fiber::ranges::CountRange;
use cuticle_gpu::{Backend, Choice};
use cuticle_light::{SrbfLight, ToneMap};
use cuticle_render::bench::{BenchReport, Edit};
use cuticle_render::scene::overrides::SceneOverrides;
use cuticle_render::{Image, Method, Renderer, Scene, SceneSpec, Timings};
use glam::DVec3;
use serde_json::{Value, json};
use std::path::{Path, PathBuf};

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
    path: crate::commands::trace::PathArgs,
}

/// The scene flags `render` and `view` share.
#[derive(clap::Args, Clone, Debug)]
pub struct SceneArgs {
    /// A TOML scene file (keys as in SceneSpec); flags override it.
    #[arg(long)]
    scene: Option<PathBuf>,
    /// A groom preset (straight, wavy, curly), a .hair file or a USD groom (.usda, .usdc, .usdz).
    #[arg(long)]
    groom: Option<String>,
    /// Strands of a preset groom.
    #[arg(long)]
    strands: Option<usize>,
    /// `default` (procedural sky), `constant:R,G,B` (uniform) or an .hdr/.exr lat-long map.
    #[arg(long)]
    env: Option<String>,
    /// Number J of SRBF lights to fit, or a lights.json from `cuticle env fit`.
    #[arg(long)]
    lights: Option<String>,
    /// srbf (Xu et al. 2011), brute (exact model, 6 n² directional lights) or path (the path
    /// tracer, flags --spp, --seed, --max-depth, --model and the fiber flags).
    #[arg(long, value_parser = ["srbf", "brute", "path"])]
    method: Option<String>,
    /// Segments m of the linear quadrature.
    #[arg(long)]
    quadrature: Option<usize>,
    /// Single scattering only.
    #[arg(long)]
    no_multiple: bool,
    #[arg(long)]
    width: Option<usize>,
    #[arg(long)]
    height: Option<usize>,
    /// Subsamples per pixel along each axis.
    #[arg(long)]
    supersampling: Option<usize>,
    /// n of the brute force's 6 n² lights.
    #[arg(long)]
    brute_grid: Option<usize>,
    /// Index of refraction η.
    #[arg(long, allow_negative_numbers = true)]
    eta: Option<f64>,
    /// Longitudinal shift α_R, degrees.
    #[arg(long, allow_negative_numbers = true)]
    alpha_r_deg: Option<f64>,
    /// Longitudinal width β_R, degrees.
    #[arg(long, allow_negative_numbers = true)]
    beta_r_deg: Option<f64>,
    /// Absorption μ_a per unit radius for every strand: one value or r,g,b.
    #[arg(long, allow_negative_numbers = true)]
    mu_a: Option<String>,
    /// Eccentricity a.
    #[arg(long, allow_negative_numbers = true)]
    eccentricity: Option<f64>,
    /// TRT caustic width w_c, degrees.
    #[arg(long, allow_negative_numbers = true)]
    caustic_width_deg: Option<f64>,
}

impl SceneArgs {
    /// The `--method` given, if any.
    pub(crate) fn method(&self) -> Option<&str> {
        self.method.as_deref()
    }

    /// The `--lights` given (a count or a file), if any.
    pub(crate) fn lights(&self) -> Option<&str> {
        self.lights.as_deref()
    }
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
        device::choose(args.device, spec.method)?;
        return crate::commands::trace::run(&args.path, spec, &args.out);
    }
    args.path.check_unused(if spec.method == Method::Brute {
        "brute"
    } else {
        "srbf"
    })?;
    let scene = load_within_memory(spec, lights)?;
    Renderer::accepts(&scene)?;
    // The device is probed only once the scene is known to be good: bad input fails fast.
    let backend = device::choose(args.device, scene.spec.method)?;
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
            (
                image,
                n,
                cov,
                prepared.coverage,
                timings,
                device::cpu_json(),
            )
        }
        Backend::Gpu(d) => {
            let r = device::render(d, &renderer, &scene)?;
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

/// `cuticle bench`: what to benchmark.
#[derive(clap::Subcommand, Clone, Debug)]
pub enum Bench {
    /// The renderer on the paper's workload (default groom, 40 SRBF lights, 720x480, single and
    /// multiple scattering): medians of full frames and of re-renders after an absorption edit.
    Render(BenchArgs),
    /// The path tracer: BVH build time, ray casting and path tracing rays/s and spp/s
    /// (default: straight.hair at 360x240 under the procedural sky).
    Trace(crate::commands::trace::TraceBenchArgs),
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
        Bench::Trace(args) => return crate::commands::trace::bench(&args),
    };
    let mut spec = SceneSpec::default();
    args.strands.into_iter().for_each(|v| spec.strands = v);
    args.width.into_iter().for_each(|v| spec.width = v);
    args.height.into_iter().for_each(|v| spec.height = v);
    FRAMES.check_usize(args.frames)?;
    let scene = load_within_memory(spec, None)?;
    let backend = device::choose(args.device, scene.spec.method)?;
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
        let report = device::bench(d, &renderer, &scene, args.frames)?;
        let mut record = device::bench_json(d, &report);
        record["params"] = serde_json::to_value(&scene.spec)?;
        record["strands"] = json!(scene.groom.strand_count());
        record["points"] = json!(scene.groom.point_count());
        record["lights"] = json!(scene.lights.len());
        record["shaded_lights"] = json!(scene.shaded_lights());
        record["seconds"]["tables"] = json!(renderer.table_seconds);
        record["seconds"]["srbf_fit"] = json!(scene.fit_seconds);
        out.finish(record)?;
        device::print_bench(d, &report);
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

/// The scene, loaded once what it needs in memory is known to fit
/// ([`cuticle_render::scene::headroom::load_within_memory`]).
pub fn load_within_memory(spec: SceneSpec, lights: Option<Vec<SrbfLight>>) -> Result<Scene> {
    Ok(cuticle_render::scene::headroom::load_within_memory(
        spec, lights,
    )?)
}

/// Refuses to write an image holding a pixel that is not a finite 32-bit float
/// ([`Image::check_finite`]); `what` names the image in the message.
pub(crate) fn check_finite(image: &Image, what: &str) -> Result<()> {
    Ok(image.check_finite(what)?)
}

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
        "device": device::cpu_json(),
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
pub fn rerender_summary(frame: f64, t: &Timings) -> String {
    format!(
        "re-render after an absorption edit {frame:.4} s (shading {:.4}, resolve {:.4}), {:.1} frames/s",
        t.shading,
        t.resolve,
        1.0 / frame.max(1e-9)
    )
}

/// The scene file (if any) with the flags laid over it ([`SceneOverrides`]), and lights read
/// from a file.
pub fn spec_from(args: &SceneArgs) -> Result<(SceneSpec, Option<Vec<SrbfLight>>)> {
    let spec = match &args.scene {
        Some(path) => SceneSpec::from_toml_file(path)?,
        None => SceneSpec::default(),
    };
    let (lights, light_file) = match &args.lights {
        None => (None, None),
        Some(s) => match s.parse::<usize>() {
            Ok(n) => (Some(n), None),
            Err(_) => (None, Some(read_lights(Path::new(s))?)),
        },
    };
    let overrides = SceneOverrides {
        groom: args.groom.clone(),
        strands: args.strands,
        env: args.env.clone(),
        lights,
        method: args
            .method
            .as_deref()
            .map(str::parse)
            .transpose()
            .map_err(anyhow::Error::msg)?,
        quadrature: args.quadrature,
        multiple: args.no_multiple.then_some(false),
        width: args.width,
        height: args.height,
        supersampling: args.supersampling,
        brute_grid: args.brute_grid,
        eta: args.eta,
        alpha_r_deg: args.alpha_r_deg,
        beta_r_deg: args.beta_r_deg,
        mu_a: args.mu_a.as_deref().map(parse_rgb).transpose()?,
        eccentricity: args.eccentricity,
        caustic_width_deg: args.caustic_width_deg,
    };
    Ok((overrides.apply(spec), light_file))
}

fn parse_rgb(s: &str) -> Result<[f64; 3]> {
    let v: Vec<f64> = s
        .split(',')
        .map(|x| x.trim().parse::<f64>())
        .collect::<std::result::Result<_, _>>()
        .with_context(|| format!("--mu-a takes one number or r,g,b, got {s}"))?;
    match v.as_slice() {
        [x] => Ok([*x; 3]),
        [r, g, b] => Ok([*r, *g, *b]),
        _ => anyhow::bail!("--mu-a takes one number or r,g,b, got {s}"),
    }
}

/// The largest lights file read (512 lights take under 200 kB).
const MAX_LIGHTS_FILE: u64 = 4 << 20;

/// The `"lights"` array of a lights.json written by `cuticle env fit`, each light checked.
fn read_lights(path: &Path) -> Result<Vec<SrbfLight>> {
    let size = std::fs::metadata(path)
        .with_context(|| format!("cannot read {}", path.display()))?
        .len();
    if size > MAX_LIGHTS_FILE {
        anyhow::bail!(
            "{} is {size} bytes, more than a lights file of {} lights takes",
            path.display(),
            cuticle_light::MAX_LIGHTS
        );
    }
    let text = cuticle_light::file::read_regular_text(path, MAX_LIGHTS_FILE)
        .with_context(|| format!("cannot read {}", path.display()))?;
    let value: Value =
        serde_json::from_str(&text).with_context(|| format!("{} is not JSON", path.display()))?;
    let lights = value
        .get("lights")
        .cloned()
        .with_context(|| format!("{} has no \"lights\" array", path.display()))?;
    let lights: Vec<SrbfLight> = serde_json::from_value(lights)
        .with_context(|| format!("{}: \"lights\" is not a list of lights", path.display()))?;
    cuticle_light::validate_lights(&lights).with_context(|| path.display().to_string())?;
    Ok(lights)
}

/// Whether and how multiple scattering was rendered.
fn multiple_json(scene: &Scene) -> Value {
    let terms = match scene.spec.method {
        Method::Srbf => "circular-Gaussian fits against SRBF windows (Xu et al. 2011 eqs. 27-31)",
        Method::Brute => {
            "exact azimuthal functions and Marschner lobes per directional light, integrated numerically"
        }
        Method::Path => "every path, by path tracing",
    };
    json!({
        "enabled": scene.spec.multiple,
        "model": "dual scattering (Zinke et al. 2008; Xu et al. 2011 section 4.3)",
        "terms": terms,
        "d_b": scene.spec.hair.d_b,
        "d_f": cuticle_render::srbf::forward_scattering::DENSITY_FACTOR,
    })
}

/// Seconds per stage as render.json records them.
pub fn seconds_json(t: &Timings) -> Value {
    json!({
        "tables": t.tables,
        "srbf_fit": t.srbf_fit,
        "drawing": t.drawing,
        "shadows": t.shadows,
        "shading": t.shading,
        "resolve": t.resolve,
        "frame": t.drawing + t.shadows + t.shading + t.resolve,
    })
}

/// Each pixel's hair coverage (the fraction of its subsamples a strand covers) in all three
/// channels: the mask `cuticle compare` averages over.
fn coverage_image(coverage: &cuticle_render::frame::draw::Coverage) -> Image {
    let (width, height) = (coverage.width, coverage.height);
    Image {
        width,
        height,
        pixels: (0..width * height)
            .map(|k| DVec3::splat(coverage.pixel_fraction(k % width, k / width)))
            .collect(),
    }
}
