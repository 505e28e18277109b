//! `cuticle sim`: one Monte Carlo ground-truth simulation of a rough fiber (d'Eon et al. 2014
//! §2.1), its lobe images, `azimuthal.csv` and `sim.json` (docs/conventions.md §5).

use crate::latlong_io::{LOBE_FILES, write_images};
use crate::output::OutDir;
use crate::progress::bar;
use anyhow::Result;
use cuticle_fiber::LatLongImage;
use cuticle_sim::{LOBE_NAMES, SimParams, SimResult, sim_json, simulate};
use std::path::{Path, PathBuf};

#[derive(clap::Args)]
pub struct Args {
    /// Incident inclination θ_i, radians.
    #[arg(long, default_value_t = SimParams::default().theta_i, allow_negative_numbers = true)]
    theta_i: f64,
    /// Scale tilt α, degrees (positive tilts the surface normal toward +u, the fiber tangent).
    #[arg(long, default_value_t = SimParams::default().alpha.to_degrees(), allow_negative_numbers = true)]
    alpha_deg: f64,
    /// Beckmann roughness β > 0.
    #[arg(long, default_value_t = SimParams::default().beta, allow_negative_numbers = true)]
    beta: f64,
    /// Relative index of refraction η > 1.
    #[arg(long, default_value_t = SimParams::default().eta, allow_negative_numbers = true)]
    eta: f64,
    /// Interior absorption per unit radius: one value or r,g,b.
    #[arg(long, default_value = "0", value_parser = parse_mu_a, allow_negative_numbers = true)]
    mu_a: [f64; 3],
    /// Paths to trace.
    #[arg(long, default_value_t = SimParams::default().rays)]
    rays: u64,
    /// Random seed; a seed gives the same images on any number of threads.
    #[arg(long, default_value_t = SimParams::default().seed)]
    seed: u64,
    /// Output folder.
    #[arg(long)]
    out: PathBuf,
}

/// `--mu-a`: `v` (grey) or `r,g,b`.
pub fn parse_mu_a(s: &str) -> Result<[f64; 3], String> {
    let values: Vec<f64> = s
        .split(',')
        .map(|v| {
            v.trim()
                .parse::<f64>()
                .map_err(|_| format!("not a number: {v:?}"))
        })
        .collect::<Result<_, _>>()?;
    match values[..] {
        [v] => Ok([v; 3]),
        [r, g, b] => Ok([r, g, b]),
        _ => Err(format!("expected one value or r,g,b (got {s:?})")),
    }
}

impl Args {
    fn params(&self) -> SimParams {
        SimParams {
            theta_i: self.theta_i,
            alpha: self.alpha_deg.to_radians(),
            beta: self.beta,
            eta: self.eta,
            mu_a: self.mu_a,
            rays: self.rays,
            seed: self.seed,
            ..Default::default()
        }
    }
}

/// The lobes and their sum, named as their files.
pub fn named_images(result: &SimResult) -> Vec<(&'static str, LatLongImage)> {
    let mut images: Vec<_> = LOBE_NAMES
        .iter()
        .copied()
        .zip(result.lobes.iter().cloned())
        .collect();
    images.push((LOBE_FILES[5], result.total()));
    images
}

/// Writes a result's whole set into `dir`: lobe images (EXR, and PNG when `png`),
/// `azimuthal.csv`, and `sim.json` last, swapped in at once (what `sim` writes, and each
/// configuration of a sweep).
pub fn write_result(dir: &Path, result: &SimResult, png: bool) -> Result<()> {
    let mut out = OutDir::create(dir, "sim")?;
    write_into(&mut out, result, png)?;
    out.finish(sim_json(result))?;
    Ok(())
}

fn write_into(out: &mut OutDir, result: &SimResult, png: bool) -> Result<()> {
    let images = named_images(result);
    let refs: Vec<(&str, &LatLongImage)> = images.iter().map(|(n, i)| (*n, i)).collect();
    write_images(out, &refs, png)?;
    Ok(())
}

pub fn run(args: Args) -> Result<()> {
    let params = args.params();
    params.validate()?;
    let mut out = OutDir::create(&args.out, "sim")?;
    let progress = bar(params.rays, "sim");
    let result = simulate(&params, &|done, _| {
        progress.set_position(done.max(progress.position()))
    })?;
    progress.finish_and_clear();
    write_into(&mut out, &result, true)?;
    out.finish(sim_json(&result))?;
    print_summary(&result, &args.out);
    Ok(())
}

fn print_summary(r: &SimResult, out: &std::path::Path) {
    let mean = |v: glam::DVec3| (v.x + v.y + v.z) / 3.0;
    let lobes: Vec<String> = LOBE_NAMES
        .iter()
        .zip(&r.energy)
        .map(|(n, e)| format!("{n} {:.4}", mean(*e)))
        .collect();
    println!(
        "energy  {}  total {:.4}",
        lobes.join("  "),
        mean(r.albedo())
    );
    println!(
        "lost    shadowing {:.4}  back-facing {:.4}  cut off {:.2e}",
        mean(r.lost_shadowing),
        mean(r.lost_backfacing),
        mean(r.lost_cutoff)
    );
    println!(
        "{} paths in {:.2} s ({:.1} M paths/s) -> {}",
        r.rays,
        r.seconds,
        r.paths_per_second() / 1e6,
        out.display()
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mu_a_takes_one_or_three_values() {
        assert_eq!(parse_mu_a("0.25"), Ok([0.25; 3]));
        assert_eq!(parse_mu_a("0.1, 0.2,0.3"), Ok([0.1, 0.2, 0.3]));
        assert!(parse_mu_a("0.1,0.2").is_err());
        assert!(parse_mu_a("red").is_err());
    }
}
