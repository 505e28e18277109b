//! Times building the non-separable model's tables at one scale tilt and roughness, the cost a
//! renderer or `cuticle validate` pays once per fiber before its first evaluation, for
//! profilers and BENCHMARKS.md:
//! `cargo run --release -p cuticle-fiber --example tabulate_nonseparable -- ALPHA_DEG BETA`
//! (η 1.55, grey μ_a 0.25). "model" is the constructor, which builds TT's rough azimuth
//! (`rough_deflection::RoughTtTable`); "tables" is `tabulated()`; the rough mirror of R is
//! built on the first evaluation and timed apart.
use cuticle_fiber::{FiberAngles, FiberModel, FiberParams, NonSeparable};
use glam::DVec3;
use std::process::ExitCode;
use std::time::Instant;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let parsed: Option<Vec<f64>> = args.iter().map(|a| a.parse().ok()).collect();
    let Some([alpha_deg, beta]) = parsed.as_deref().and_then(|v| <[f64; 2]>::try_from(v).ok())
    else {
        eprintln!("usage: tabulate_nonseparable ALPHA_DEG BETA (e.g. -2 0.04)");
        return ExitCode::FAILURE;
    };
    let params = FiberParams {
        eta: 1.55,
        beta,
        alpha: alpha_deg.to_radians(),
        mu_a: DVec3::splat(0.25),
    };
    let built = Instant::now();
    let model = match NonSeparable::new(params) {
        Ok(m) => m,
        Err(e) => {
            eprintln!("tabulate_nonseparable: {e}");
            return ExitCode::FAILURE;
        }
    };
    let construct = built.elapsed().as_secs_f64();
    let start = Instant::now();
    let model = model.tabulated();
    let tables = start.elapsed().as_secs_f64();
    let wi = FiberAngles::from_dir(DVec3::new(0.3, 0.9, 0.1).normalize());
    let wo = FiberAngles::from_dir(DVec3::new(-0.2, -0.5, 0.7).normalize());
    let s = model.eval(wi, wo).total().x;
    let first = start.elapsed().as_secs_f64() - tables;
    println!(
        "α {alpha_deg}° β {beta}: model {construct:.2} s, tables {tables:.2} s, first evaluation \
         {first:.2} s (S {s:.6e})"
    );
    ExitCode::SUCCESS
}
