//! `cuticle furnace`: the albedo ∫ S dω_o of a fiber model over a grid of θ_i (and of β when
//! asked), by the deterministic quadrature of `cuticle_fiber::furnace`, beside the albedo the
//! model's A(p, h) says it must have: 1 for a lossless fiber, less with absorption, and less
//! for the tilted non-separable model by what its tilted scales remove (issue 14).

use crate::commands::fiber_args::FiberArgs;
use crate::output::OutDir;
use anyhow::{Result, bail};
use cuticle_fiber::furnace::{FurnaceRule, albedo};
use cuticle_fiber::lobe::channel_mean;
use cuticle_fiber::models::nonseparable::scales::attenuation::{
    Surface, TiltedAttenuation, energy_budget,
};
use cuticle_fiber::ranges;
use cuticle_fiber::{ModelId, NonSeparable};
use rayon::prelude::*;
use serde_json::json;
use std::path::PathBuf;
use std::time::Instant;

#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    fiber: FiberArgs,
    /// Incident inclinations θ_i, radians, comma-separated.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "0,0.25,0.5,0.75,1,1.2,1.4",
        allow_negative_numbers = true
    )]
    theta_i: Vec<f64>,
    /// Roughnesses β to sweep, comma-separated (default: --beta alone).
    #[arg(long, value_delimiter = ',', allow_negative_numbers = true)]
    betas: Vec<f64>,
    /// Output folder.
    #[arg(long, default_value = "out/furnace")]
    out: PathBuf,
}

/// Most (θ_i, β) pairs one run integrates.
const MAX_CASES: usize = 1000;

pub fn run(args: Args) -> Result<()> {
    for &t in &args.theta_i {
        ranges::THETA_I.check(t)?;
    }
    if args.theta_i.len() * args.betas.len().max(1) > MAX_CASES {
        bail!(
            "at most {MAX_CASES} (theta_i, beta) pairs, got {}",
            args.theta_i.len() * args.betas.len().max(1)
        );
    }
    let betas = if args.betas.is_empty() {
        vec![args.fiber.beta]
    } else {
        args.betas.clone()
    };
    let cases: Vec<(f64, f64)> = betas
        .iter()
        .flat_map(|&b| args.theta_i.iter().map(move |&t| (b, t)))
        .collect();
    let models = betas
        .iter()
        .map(|&beta| {
            FiberArgs {
                beta,
                ..args.fiber.clone()
            }
            .model()
        })
        .collect::<Result<Vec<_>>>()?;
    let out = OutDir::create(&args.out, "furnace")?;
    let start = Instant::now();
    let progress = crate::progress::bar(cases.len() as u64, "furnace");
    let results: Vec<_> = cases
        .par_iter()
        .map(|&(beta, theta_i)| {
            let model = &models[betas.iter().position(|&b| b == beta).unwrap_or(0)];
            let rule = FurnaceRule::for_fiber(beta, args.fiber.alpha_deg);
            let est = albedo(model.as_ref(), theta_i, rule);
            progress.inc(1);
            (beta, theta_i, est)
        })
        .collect();
    progress.finish_and_clear();
    println!(
        "{:>8} {:>8} {:>10} {:>10} {:>10} {:>10}",
        "beta", "theta_i", "albedo", "± rule", "expected", "lost"
    );
    let budgets: Vec<Option<TiltedAttenuation>> = results
        .iter()
        .map(|(_, theta_i, _)| budget(&args.fiber, *theta_i))
        .collect();
    for ((beta, theta_i, est), b) in results.iter().zip(&budgets) {
        let (expected, lost) = b.as_ref().map_or(("–".into(), "–".into()), |b| {
            (
                format!("{:.5}", channel_mean(b.lobes.total())),
                format!("{:.5}", channel_mean(b.lost())),
            )
        });
        println!(
            "{beta:>8.4} {theta_i:>8.3} {:>10.5} {:>10.1e} {expected:>10} {lost:>10}",
            channel_mean(est.albedo),
            channel_mean(est.error_estimate)
        );
    }
    let record = json!({
        "params": args.fiber.json(None)?,
        "results": results.iter().zip(&budgets).map(|((beta, theta_i, est), b)| json!({
            "theta_i": theta_i,
            "beta": beta,
            "albedo": channel_mean(est.albedo),
            "albedo_rgb": est.albedo.to_array(),
            "error_estimate": channel_mean(est.error_estimate),
            "evaluations": est.evaluations,
            "expected_albedo": b.as_ref().map(|b| channel_mean(b.lobes.total())),
            "lost_to_scales": b.as_ref().map(|b| channel_mean(b.lost())),
        })).collect::<Vec<_>>(),
        "seconds": start.elapsed().as_secs_f64(),
    });
    let record = out.finish(record)?;
    println!("-> {}", record.display());
    Ok(())
}

/// ½ ∫ Σ_p A(p, h) dh and the losses for the models built on A(p, h): d'Eon 2011 and the
/// paper's non-separable form on the smooth untilted fiber's, the tilted form its own (tilted
/// scales, rough Fresnel factors); none for Marschner 2003 and Chiang 2016 (their own
/// attenuation, with no stated budget).
fn budget(fiber: &FiberArgs, theta_i: f64) -> Option<TiltedAttenuation> {
    let p = fiber.params().ok()?;
    match fiber.model {
        ModelId::Marschner | ModelId::Chiang2016 => None,
        ModelId::NonSeparable => Some(NonSeparable::new(p).ok()?.energy_budget(theta_i)),
        ModelId::DEon2011 | ModelId::NonSeparablePaper => {
            Some(energy_budget(theta_i, Surface::smooth(p.eta, 0.0), p.mu_a))
        }
    }
}
