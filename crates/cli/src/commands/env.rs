//! `cuticle env fit`: approximate an environment map by J SRBF lights (Xu et al. 2011 eq. 1) and
//! write `lights.json` (what the renderer reads), `fit.png` (the map and its reconstruction side by
//! side) and `env.json` (every parameter and figure, docs/conventions.md §5).

use crate::output::OutDir;
use crate::progress::bar;
use anyhow::Result;
use cuticle_fiber::ranges::CountRange;
use cuticle_light::{
    EnvMap, FitOptions, FitProgress, FitReport, comparison_image, fit_srbf_with_progress,
    load_or_default,
};
use cuticle_render::scene::ENV_ROTATE_DEG;
use serde_json::{Value, json};
use std::path::PathBuf;
use std::time::Instant;

#[derive(clap::Args)]
pub struct Args {
    #[command(subcommand)]
    command: EnvCommand,
}

#[derive(clap::Subcommand)]
enum EnvCommand {
    /// Fit J SRBF lights to an environment map: lights.json, fit.png, env.json.
    Fit(FitArgs),
}

#[derive(clap::Args)]
struct FitArgs {
    /// Lat-long environment map (.hdr or .exr), or `default` for the procedural sky.
    #[arg(long, default_value = "default")]
    env: String,
    /// Number of SRBF lights J.
    #[arg(long, default_value_t = FitOptions::default().lights)]
    lights: usize,
    /// Rotation about the up axis (+y), degrees: content at azimuth φ moves to φ + D.
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    rotate_deg: f64,
    /// Width of the coarse grid the fit works on (refined adaptively where needed).
    #[arg(long, default_value_t = FitOptions::default().fit_width)]
    fit_width: usize,
    /// Most Levenberg–Marquardt iterations.
    #[arg(long, default_value_t = FitOptions::default().max_iterations)]
    max_iterations: usize,
    /// Width of each of the two panels of fit.png.
    #[arg(long, default_value_t = 512)]
    preview_width: usize,
    /// Output folder.
    #[arg(long)]
    out: PathBuf,
}

pub fn run(args: Args) -> Result<()> {
    match args.command {
        EnvCommand::Fit(args) => fit(&args),
    }
}

/// Width of each panel of fit.png: 8192 × 4096 panels take 200 MB.
const PREVIEW_WIDTH: CountRange = CountRange {
    name: "preview_width",
    min: 2,
    max: 8192,
};

fn fit(args: &FitArgs) -> Result<()> {
    ENV_ROTATE_DEG.named("rotate_deg").check(args.rotate_deg)?;
    PREVIEW_WIDTH.check_usize(args.preview_width)?;
    let mut out = OutDir::create(&args.out, "env")?;
    let start = Instant::now();
    let map = load_or_default(&args.env)?.with_rotation(args.rotate_deg.to_radians());
    let load_seconds = start.elapsed().as_secs_f64();
    let options = FitOptions {
        lights: args.lights,
        fit_width: args.fit_width,
        max_iterations: args.max_iterations,
        ..FitOptions::default()
    };
    let report = fit_with_bar(&map, &options)?;
    let params = params_json(args, &options);
    out.write_json("lights.json", &lights_json(&report, &params))?;
    out.write("fit.png", &preview_png(&map, &report, args.preview_width)?)?;
    out.finish(env_json(&map, &report, &params, load_seconds, start))?;
    println!(
        "{} SRBF lights fitted to {} ({}x{}) in {:.2} s: relative L2 error {:.4} on the full map; \
         wrote lights.json, fit.png, env.json to {}",
        report.lights.len(),
        args.env,
        map.width(),
        map.height(),
        report.seconds,
        report.relative_l2,
        args.out.display()
    );
    Ok(())
}

/// The fit with a progress bar over its Levenberg–Marquardt iterations.
fn fit_with_bar(map: &EnvMap, options: &FitOptions) -> Result<FitReport> {
    let progress = bar(options.max_iterations as u64, "fit");
    let report = fit_srbf_with_progress(map, options, &mut |event| match event {
        FitProgress::Initialised { relative_l2 } => {
            progress.set_message(format!("fit {relative_l2:.4}"))
        }
        FitProgress::Iteration {
            iteration,
            relative_l2,
            ..
        } => {
            progress.set_position(iteration as u64);
            progress.set_message(format!("fit {relative_l2:.4}"));
        }
        FitProgress::Done => progress.finish_and_clear(),
    });
    progress.finish_and_clear();
    Ok(report?)
}

fn params_json(args: &FitArgs, options: &FitOptions) -> Value {
    json!({
        "env": args.env,
        "lights": args.lights,
        "rotate_deg": args.rotate_deg,
        "preview_width": args.preview_width,
        "fit": options,
    })
}

/// What the renderer reads: each light's centre, bandwidth and coefficient, with the convention.
fn lights_json(report: &FitReport, params: &Value) -> Value {
    let lights: Vec<Value> = report
        .lights
        .iter()
        .map(|l| {
            json!({
                "direction": l.direction.to_array(),
                "bandwidth": l.bandwidth,
                "sharpness": l.sharpness(),
                "coefficient": l.coefficient.to_array(),
            })
        })
        .collect();
    json!({
        "convention": "world +y up; radiance(w) = sum_j coefficient_j * exp(2 (w . direction_j - 1) / bandwidth_j^2) \
                       (Xu et al. 2011 eq. 1), evaluate as exp(-sharpness_j |w - direction_j|^2 / 2)",
        "lights": lights,
        "relative_l2": report.relative_l2,
        "seconds": report.seconds,
        "params": params,
    })
}

fn env_json(
    map: &EnvMap,
    report: &FitReport,
    params: &Value,
    load_seconds: f64,
    start: Instant,
) -> Value {
    json!({
        "params": params,
        "map": {
            "width": map.width(),
            "height": map.height(),
            "rotation_rad": map.rotation(),
            "clamped_negatives": map.clamped_negatives(),
        },
        "relative_l2": report.relative_l2,
        "relative_l2_fit": report.relative_l2_fit,
        "relative_l2_fit_initial": report.relative_l2_fit_initial,
        "fit_width": report.fit_width,
        "fit_height": report.fit_height,
        "fit_samples": report.fit_samples,
        "bandwidth_range": report.bandwidth_range,
        "iterations": report.iterations,
        "map_integral": report.map_integral.to_array(),
        "fit_integral": report.fit_integral.to_array(),
        "lights": report.lights.len(),
        "seconds": report.seconds,
        "load_seconds": load_seconds,
        "total_seconds": start.elapsed().as_secs_f64(),
    })
}

/// fit.png: the map (left) and its reconstruction (right), tone-mapped alike.
fn preview_png(map: &EnvMap, report: &FitReport, width: usize) -> Result<Vec<u8>> {
    let image = comparison_image(map, &report.lights, width);
    let (w, h) = (image.width() as usize, image.height() as usize);
    Ok(cuticle_light::image_file::png_bytes(
        w,
        h,
        image.into_raw(),
    )?)
}
