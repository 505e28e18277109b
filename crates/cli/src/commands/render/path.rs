//! `cuticle render --method path`: the path tracer (crate cuticle-trace) on the scene the SRBF
//! renderer reads (same groom, camera, environment and image size); and `cuticle bench trace`,
//! its rays and samples per second.
//!
//! With `--model marschner` (the default) every strand has exactly the scene's hair parameters
//! (`HairParams::fiber`, as `--method srbf|brute` shade); the other models take the fiber flags
//! (`--beta`, `--alpha-deg`, `--mu-a` or melanin; η from the scene; `--beta-m`, `--beta-n` for
//! Chiang 2016) for every strand.

use super::record::check_finite;
use crate::commands::fiber_args::model_parser;
use crate::output::OutDir;
use crate::progress::bar;
use anyhow::{Context, Result, bail};
use cuticle_fiber::ranges::BETA;
use cuticle_fiber::spec::absorption;
use cuticle_fiber::{BuildOptions, FiberModel, FiberParams, ModelId};
use cuticle_light::ToneMap;
use cuticle_render::{Image, Scene, SceneSpec};
use cuticle_trace::{
    Accel, MAX_DEPTH, PathOptions, SPP, StrandModels, Strategy, TraceImage, TraceOptions,
};
use glam::DVec3;
use serde_json::{Value, json};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The path tracer's flags of `cuticle render` (used with `--method path`).
#[derive(clap::Args, Clone, Debug)]
pub struct PathArgs {
    /// Samples per pixel (--method path).
    #[arg(long, default_value_t = TraceOptions::default().spp)]
    pub spp: u32,
    /// Seed of the path tracer's random numbers.
    #[arg(long, default_value_t = TraceOptions::default().seed)]
    pub seed: u64,
    /// Most scattering events of a path.
    #[arg(long, default_value_t = TraceOptions::default().path.max_depth)]
    pub max_depth: u32,
    /// Fiber model of the path tracer; marschner takes the scene's hair parameters.
    #[arg(long, value_parser = model_parser(), default_value = "marschner")]
    pub model: ModelId,
    /// Longitudinal roughness β of d'Eon 2011 / non-separable (Beckmann), in (0, 1]
    /// [default: 0.04].
    #[arg(long, allow_negative_numbers = true)]
    pub beta: Option<f64>,
    /// Scale tilt α, degrees (d'Eon 2011, non-separable, Chiang 2016) [default: -2].
    #[arg(long, allow_negative_numbers = true)]
    pub alpha_deg: Option<f64>,
    /// Eumelanin concentration, instead of --mu-a (models other than marschner).
    #[arg(long, allow_negative_numbers = true)]
    pub eumelanin: Option<f64>,
    /// Pheomelanin concentration, instead of --mu-a.
    #[arg(long, allow_negative_numbers = true)]
    pub pheomelanin: Option<f64>,
    /// Chiang 2016's longitudinal roughness β_m, in (0, 1] [default: 0.3].
    #[arg(long, allow_negative_numbers = true)]
    pub beta_m: Option<f64>,
    /// Chiang 2016's azimuthal roughness β_n, in (0, 1] [default: 0.3].
    #[arg(long, allow_negative_numbers = true)]
    pub beta_n: Option<f64>,
}

impl PathArgs {
    fn beta(&self) -> f64 {
        self.beta.unwrap_or(0.04)
    }

    fn alpha_deg(&self) -> f64 {
        self.alpha_deg.unwrap_or(-2.0)
    }

    fn beta_m(&self) -> f64 {
        self.beta_m.unwrap_or(0.3)
    }

    fn beta_n(&self) -> f64 {
        self.beta_n.unwrap_or(0.3)
    }

    /// The fiber flags given, by name: what the model chosen must use, or the run is refused
    /// (issue 57 #9: `--eumelanin 8` with `--model marschner` once changed nothing).
    fn given(&self) -> Vec<(&'static str, bool)> {
        vec![
            ("--beta", self.beta.is_some()),
            ("--alpha-deg", self.alpha_deg.is_some()),
            ("--eumelanin", self.eumelanin.is_some()),
            ("--pheomelanin", self.pheomelanin.is_some()),
            ("--beta-m", self.beta_m.is_some()),
            ("--beta-n", self.beta_n.is_some()),
        ]
    }

    /// The first fiber flag given that `model` does not take.
    fn unused_flag(&self) -> Option<&'static str> {
        let takes: &[&str] = match self.model {
            ModelId::Marschner => &[],
            ModelId::DEon2011 | ModelId::NonSeparable | ModelId::NonSeparablePaper => {
                &["--beta", "--alpha-deg", "--eumelanin", "--pheomelanin"]
            }
            ModelId::Chiang2016 => &[
                "--alpha-deg",
                "--eumelanin",
                "--pheomelanin",
                "--beta-m",
                "--beta-n",
            ],
        };
        self.given()
            .into_iter()
            .find(|(flag, given)| *given && !takes.contains(flag))
            .map(|(flag, _)| flag)
    }

    /// Refuses the path tracer's flags on a render by another method, which would ignore them.
    pub fn check_unused(&self, method: &str) -> Result<()> {
        let flag = if self.model != ModelId::Marschner {
            Some("--model")
        } else {
            self.given().into_iter().find(|(_, g)| *g).map(|(f, _)| f)
        };
        match flag {
            Some(flag) => bail!("{flag} is for --method path; --method {method} does not use it"),
            None => Ok(()),
        }
    }

    pub(crate) fn options(&self) -> Result<TraceOptions> {
        Ok(TraceOptions::checked(
            self.spp.into(),
            self.seed,
            self.max_depth.into(),
        )?)
    }

    /// The fiber parameters of the non-Marschner models: η from the scene, absorption from
    /// the scene's `--mu-a`, else melanin, else the scene's default μ_a.
    fn fiber(&self, spec: &SceneSpec, beta: f64) -> Result<FiberParams> {
        let hair = &spec.hair;
        let mu_a = absorption(
            hair.mu_a,
            self.eumelanin,
            self.pheomelanin,
            DVec3::from_array(hair.default_mu_a),
        )?;
        let params = FiberParams {
            eta: hair.eta,
            beta,
            alpha: self.alpha_deg().to_radians(),
            mu_a,
        };
        params.validate()?;
        Ok(params)
    }

    /// The model's flags checked against the scene's hair before anything is loaded.
    pub(crate) fn check(&self, spec: &SceneSpec) -> Result<()> {
        let model = self.model.name();
        if let Some(flag) = self.unused_flag() {
            bail!(
                "{flag} does not apply to --model {model}{}",
                if self.model == ModelId::Marschner {
                    " (it takes the scene's hair parameters: --mu-a, --eta, ...)"
                } else {
                    ""
                }
            );
        }
        if self.model != ModelId::Marschner
            && let Some(sidecar) = &spec.strand_absorption
        {
            // Only Marschner 2003 takes a strand's own absorption (StrandModels::marschner).
            bail!(
                "the scene's strand_absorption {sidecar} applies to --model marschner only; \
                 --model {model} gives every strand one absorption"
            );
        }
        match self.model {
            ModelId::Marschner => Ok(()),
            ModelId::Chiang2016 => {
                self.fiber(spec, BETA.named("beta_m").check(self.beta_m())?)?;
                BETA.named("beta_n").check(self.beta_n())?;
                Ok(())
            }
            _ => self.fiber(spec, self.beta()).map(|_| ()),
        }
    }

    /// Chiang 2016's parameters as `--model chiang2016` renders them (β in the params is β_m),
    /// and β_n: what `cuticle export` hands pbrt-v4 and Mitsuba 3.
    pub(crate) fn chiang(&self, spec: &SceneSpec) -> Result<(FiberParams, f64)> {
        let beta_m = BETA.named("beta_m").check(self.beta_m())?;
        let beta_n = BETA.named("beta_n").check(self.beta_n())?;
        Ok((self.fiber(spec, beta_m)?, beta_n))
    }

    fn models(&self, scene: &Scene) -> Result<StrandModels> {
        let strands = scene.groom.strand_count();
        let one = |m: Box<dyn FiberModel>| Ok(StrandModels::uniform(m, strands));
        let (beta, beta_n) = match self.model {
            ModelId::Marschner => {
                return StrandModels::marschner(scene).context("Marschner 2003 parameters");
            }
            ModelId::Chiang2016 => (
                BETA.named("beta_m").check(self.beta_m())?,
                Some(self.beta_n()),
            ),
            _ => (self.beta(), None),
        };
        let options = BuildOptions {
            beta_n,
            ..BuildOptions::default()
        };
        one(self
            .model
            .build(&self.fiber(&scene.spec, beta)?, &options)?)
    }

    pub(crate) fn json(&self, scene: &Scene) -> Result<Value> {
        let fiber = match self.model {
            ModelId::Marschner => Value::Null,
            ModelId::Chiang2016 => {
                let p = self.fiber(&scene.spec, self.beta_m())?;
                json!({"beta_m": self.beta_m(), "beta_n": self.beta_n(), "alpha_deg": self.alpha_deg(), "eta": p.eta, "mu_a": p.mu_a.to_array()})
            }
            _ => {
                let p = self.fiber(&scene.spec, self.beta())?;
                json!({"beta": self.beta(), "alpha_deg": self.alpha_deg(), "eta": p.eta, "mu_a": p.mu_a.to_array()})
            }
        };
        Ok(json!({
            "model": self.model.name(),
            "spp": self.spp,
            "seed": self.seed,
            "max_depth": self.max_depth,
            "strategy": Strategy::Mis,
            "fiber": fiber,
        }))
    }
}

/// Loads the scene without an SRBF fit (the path tracer samples the map itself), once what
/// it needs in memory is known to fit.
pub(crate) fn load(mut spec: SceneSpec) -> Result<Scene> {
    spec.method = cuticle_render::Method::Path;
    super::scene_args::load_within_memory(spec, None)
}

/// `cuticle render --method path`.
pub fn run(args: &PathArgs, spec: SceneSpec, out: &Path) -> Result<()> {
    let options = args.options()?;
    if !spec.multiple {
        // Once ignored: the path tracer traced every order and said nothing.
        bail!(
            "--no-multiple (scene key multiple = false) is for --method srbf and brute; the \
             path tracer's single scattering is --max-depth 1"
        );
    }
    args.check(&spec)?;
    let scene = load(spec)?;
    let models = args.models(&scene)?;
    let params = args.json(&scene)?;
    eprintln!(
        "path tracing {} strands ({} points) at {}x{}, {} spp, model {}",
        scene.groom.strand_count(),
        scene.groom.point_count(),
        scene.spec.width,
        scene.spec.height,
        options.spp,
        models.name()
    );
    // The folder is checked before the work, not after it.
    let mut out_dir = OutDir::create(out, "render")?;
    let progress = bar(options.spp as u64, "trace");
    let report = |done: usize, _total: usize| progress.set_position(done as u64);
    let traced = cuticle_trace::render(&scene, &models, &options, &report);
    progress.finish_and_clear();
    check_finite(&traced.image, "an image")?;
    let error = standard_error_image(&traced);
    check_finite(&error, "a standard error")?;
    let tone = ToneMap::for_map(&scene.env);
    out_dir.write("image.png", &traced.image.png_bytes(tone)?)?;
    out_dir.write("image.exr", &traced.image.exr_bytes()?)?;
    out_dir.write("standard_error.exr", &error.exr_bytes()?)?;
    out_dir.write("coverage.exr", &coverage_exr(&traced)?)?;
    out_dir.finish(record(&scene, params, &traced)?)?;
    let s = &traced.stats;
    println!(
        "{}: {} spp in {:.2} s ({:.3} spp/s, {:.2} M rays/s, {} rays; BVH of {} tubes {:.2} s); mean standard error {:.4}",
        out.display(),
        traced.spp,
        s.trace_seconds,
        traced.spp as f64 / s.trace_seconds.max(1e-12),
        s.rays_per_second() / 1e6,
        s.rays,
        s.tubes,
        s.build_seconds,
        mean_standard_error(&traced)
    );
    Ok(())
}

fn mean_standard_error(t: &TraceImage) -> f64 {
    let n = t.standard_error.len().max(1) as f64;
    t.standard_error
        .iter()
        .map(|e| (e.x + e.y + e.z) / 3.0)
        .sum::<f64>()
        / n
}

/// render.json of a path-traced image.
fn record(scene: &Scene, path: Value, t: &TraceImage) -> Result<Value> {
    let s = &t.stats;
    Ok(json!({
        "params": serde_json::to_value(&scene.spec)?,
        "method": "path",
        "path": path,
        "strands": scene.groom.strand_count(),
        "points": scene.groom.point_count(),
        "tubes": s.tubes,
        "spp": t.spp,
        "samples": s.samples,
        "rays": s.rays,
        "samples_per_second": s.samples_per_second(),
        "spp_per_second": t.spp as f64 / s.trace_seconds.max(1e-12),
        "rays_per_second": s.rays_per_second(),
        "threads": rayon::current_num_threads(),
        "mean_standard_error": mean_standard_error(t),
        "seconds": {"bvh": s.build_seconds, "trace": s.trace_seconds},
    }))
}

/// The per-pixel standard error of the mean, linear RGB.
fn standard_error_image(t: &TraceImage) -> Image {
    Image {
        width: t.image.width,
        height: t.image.height,
        pixels: t.standard_error.clone(),
    }
}

/// Each pixel's coverage (the fraction of its camera rays that met hair) in all three channels,
/// as the SRBF renderer's coverage.exr.
fn coverage_exr(t: &TraceImage) -> Result<Vec<u8>> {
    let coverage = Image {
        width: t.image.width,
        height: t.image.height,
        pixels: t.coverage.iter().map(|&c| DVec3::splat(c)).collect(),
    };
    Ok(coverage.exr_bytes()?)
}

/// `cuticle bench trace`'s flags.
#[derive(clap::Args, Clone, Debug)]
pub struct TraceBenchArgs {
    /// A groom preset, a .hair file or a USD groom (.usda, .usdc, .usdz).
    #[arg(long, default_value = "../shared/data/hair/straight.hair")]
    pub groom: String,
    /// Environment: default, constant:R,G,B or an .hdr/.exr map.
    #[arg(long, default_value = "default")]
    pub env: String,
    #[arg(long, default_value_t = 360)]
    pub width: usize,
    #[arg(long, default_value_t = 240)]
    pub height: usize,
    /// Samples per pixel of the path-traced part.
    #[arg(long, default_value_t = 4)]
    pub spp: u32,
    #[arg(long, default_value_t = TraceOptions::default().path.max_depth)]
    pub max_depth: u32,
    /// Output folder.
    #[arg(long, default_value = "out/bench-trace")]
    pub out: PathBuf,
}

/// `cuticle bench trace`: the BVH's build time, ray casting alone (camera rays, then rays in
/// random directions from the hits: the ray–groom intersections per second), and the path
/// tracer (Marschner 2003 at the scene's defaults, MIS, depth 64): rays and spp per second.
pub fn bench(args: &TraceBenchArgs) -> Result<()> {
    let spec = SceneSpec {
        groom: args.groom.clone(),
        env: args.env.clone(),
        width: args.width,
        height: args.height,
        ..SceneSpec::default()
    };
    let options = TraceOptions {
        spp: SPP.check(args.spp.into())? as u32,
        seed: 1,
        path: PathOptions {
            max_depth: MAX_DEPTH.check(args.max_depth.into())? as u32,
            ..PathOptions::default()
        },
    };
    let scene = load(spec)?;
    let out = OutDir::create(&args.out, "bench")?;
    let accel = Accel::build(&scene.groom);
    let casting = cast_rays(&scene, &accel);
    let models = StrandModels::marschner(&scene)?;
    let traced = cuticle_trace::render_with(&scene, &accel, &models, &options, &|_, _| {});
    let s = &traced.stats;
    let threads = rayon::current_num_threads();
    let record = json!({
        "groom": args.groom, "env": args.env, "width": args.width, "height": args.height,
        "strands": scene.groom.strand_count(), "tubes": accel.tube_count(), "threads": threads,
        "bvh_seconds": accel.build_seconds,
        "ray_casting": {"rays": casting.0, "seconds": casting.1, "rays_per_second": casting.0 as f64 / casting.1},
        "path": {"spp": traced.spp, "max_depth": options.path.max_depth, "rays": s.rays, "seconds": s.trace_seconds,
                 "rays_per_second": s.rays_per_second(), "spp_per_second": traced.spp as f64 / s.trace_seconds},
    });
    out.finish(record)?;
    println!(
        "{} tubes, BVH {:.3} s; ray casting {:.2} M rays/s ({:.2} M per thread, {threads} threads); path tracing {:.2} M rays/s, {:.3} spp/s ({:.2} s per spp)",
        accel.tube_count(),
        accel.build_seconds,
        casting.0 as f64 / casting.1 / 1e6,
        casting.0 as f64 / casting.1 / 1e6 / threads as f64,
        s.rays_per_second() / 1e6,
        traced.spp as f64 / s.trace_seconds,
        s.trace_seconds / traced.spp as f64
    );
    Ok(())
}

/// Camera rays through every pixel centre, and from each hit one ray in a fixed pseudo-random
/// direction, four times over: (rays, seconds).
fn cast_rays(scene: &Scene, accel: &Accel) -> (u64, f64) {
    use rayon::prelude::*;
    let (w, h) = (scene.spec.width, scene.spec.height);
    let view = scene.camera.view(w, h);
    let start = Instant::now();
    let rays: u64 = (0..4 * w * h)
        .into_par_iter()
        .map(|k| {
            let p = k % (w * h);
            let d = view.ray((p % w) as f64 + 0.5, (p / w) as f64 + 0.5);
            let Some(hit) = accel.closest(view.eye, d) else {
                return 1;
            };
            let f = accel.frame(hit, view.eye, d);
            let x = (k as f64 * 0.618_034).fract() * std::f64::consts::TAU;
            let z = ((k as f64 * 0.754_878).fract() * 2.0 - 1.0).clamp(-1.0, 1.0);
            let r = (1.0 - z * z).sqrt();
            let dir = DVec3::new(r * x.cos(), r * x.sin(), z);
            std::hint::black_box(accel.closest(f.on_axis, dir));
            2
        })
        .sum();
    (rays, start.elapsed().as_secs_f64())
}
