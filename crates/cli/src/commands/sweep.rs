//! `cuticle sweep`: the ground-truth simulation over a grid of configurations (d'Eon et al. 2014
//! §2.1's suite, the `small` subset, or a JSON file), resumable and shardable.
//!
//! Each configuration goes to `OUT/<name>/` (e.g. `ti0.75_a-2_b0.04_mu0.25_eta1.55`) with
//! `R.exr` … `rest.exr`, `total.exr`, `azimuthal.csv` (and PNGs with `--png`) and `sim.json`:
//! the set `cuticle sim` writes, staged beside the folder and swapped in whole, so a
//! configuration is complete exactly when its `sim.json` exists. A resumed run skips complete
//! configurations, redoes any that a killed run left without `sim.json`, and refuses a folder
//! whose configurations were made with other `--rays`, `--seed` or `--png`.
//! `--shard K/N` runs the configurations whose index i (in the grid's order) has
//! i mod N = K − 1, so the N jobs of an array share one output folder without overlap.
//! The folder must be a sweep's, and each configuration is run by one process at a time
//! ([`super::sweep_folder`]): a second run that shares any is refused before it starts.

use crate::commands::sim::write_result;
use crate::commands::sweep_folder::{ConfigLocks, check_is_sweep};
use crate::output::write_json_atomic;
use crate::progress::bar;
use anyhow::{Context, Result, bail};
use cuticle_fiber::LatLongGrid;
use cuticle_sim::{Shard, Sweep, SweepConfig, SweepSummary, grid};
use serde_json::json;
use std::path::{Path, PathBuf};

#[derive(clap::Args)]
pub struct Args {
    /// Output folder: one subfolder per configuration.
    #[arg(long)]
    out: PathBuf,
    /// `paper` (15,400 configurations), `small` (120), or a JSON file listing configurations:
    /// [{"theta_i": 0.5, "alpha_deg": -2, "beta": 0.04, "eta": 1.55, "mu_a": 0.25 or [r,g,b]}, …].
    #[arg(long, default_value = "paper")]
    grid: String,
    /// Paths per configuration.
    #[arg(long, default_value_t = 10_000_000)]
    rays: u64,
    /// Random seed, shared by every configuration.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Run only shard K of N (1-based): configurations with index mod N = K - 1.
    #[arg(long, default_value = "1/1")]
    shard: Shard,
    /// Stop after this many configurations (the rest stay for a later run).
    #[arg(long)]
    limit: Option<usize>,
    /// Also write a tone-mapped PNG beside each EXR.
    #[arg(long)]
    png: bool,
}

/// The largest grid file read: about 100,000 configurations.
const MAX_GRID_FILE: u64 = 16 << 20;

fn configs(grid_arg: &str) -> Result<Vec<SweepConfig>> {
    match grid_arg {
        "paper" => Ok(grid::paper()),
        "small" => Ok(grid::small()),
        file => {
            let size = std::fs::metadata(file)
                .with_context(|| format!("cannot read grid file {file}"))?
                .len();
            if size > MAX_GRID_FILE {
                bail!(
                    "grid file {file} is {size} bytes; a grid file holds at most {MAX_GRID_FILE}"
                );
            }
            let text = cuticle_light::file::read_regular_text(Path::new(file), MAX_GRID_FILE)
                .with_context(|| format!("cannot read grid file {file}"))?;
            Ok(grid::from_json(&text)?)
        }
    }
}

pub fn run(args: Args) -> Result<()> {
    let all = configs(&args.grid)?;
    let sweep = Sweep::new(
        &all,
        args.shard,
        &args.out,
        args.rays,
        args.seed,
        LatLongGrid::default(),
    )?;
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("cannot create output folder {}", args.out.display()))?;
    check_is_sweep(&args.out)?;
    let _locks = ConfigLocks::take(&args.out, sweep.configs.iter().map(|(_, c)| c))?;
    sweep.check_settings()?;
    check_png(&sweep, args.png)?;
    let progress = bar(sweep.configs.len() as u64, "sweep");
    progress.set_position(sweep.complete_count() as u64);
    progress.reset_eta();
    let png = args.png;
    let write = move |dir: &Path, r: &cuticle_sim::SimResult| {
        write_result(dir, r, png).map_err(|e| format!("{e:#}"))
    };
    let ran = std::cell::Cell::new(0usize);
    let stop = || args.limit.is_some_and(|n| ran.get() >= n);
    let summary = sweep.run(&write, &stop, &mut |c, _| {
        ran.set(ran.get() + 1);
        progress.inc(1);
        progress.set_message(c.dir_name());
    })?;
    progress.finish_and_clear();
    write_json_atomic(
        &args.out.join(record_name(args.shard)),
        &record(&args, &summary),
    )?;
    println!(
        "{} configurations in shard {}/{}: {} already complete, {} simulated ({:.1} s, {:.1} M paths/s), {} left -> {}",
        summary.total,
        args.shard.k,
        args.shard.n,
        summary.skipped,
        summary.ran,
        summary.seconds,
        summary.rays as f64 / summary.seconds.max(1e-9) / 1e6,
        summary.remaining,
        args.out.display()
    );
    Ok(())
}

/// Refuses to resume into complete configurations written with the other `--png` setting.
fn check_png(sweep: &Sweep, png: bool) -> Result<()> {
    for (_, config) in &sweep.configs {
        let dir = sweep.dir(config);
        if sweep.is_complete(config) && dir.join("total.png").is_file() != png {
            bail!(
                "{} was made {} --png; resume with the settings it was made with, or write to another folder",
                dir.display(),
                if png { "without" } else { "with" }
            );
        }
    }
    Ok(())
}

/// `sweep.json`, or `sweep-K-of-N.json` for a shard, so shards sharing a folder do not collide.
fn record_name(shard: Shard) -> String {
    if shard == Shard::ALL {
        "sweep.json".into()
    } else {
        format!("sweep-{}-of-{}.json", shard.k, shard.n)
    }
}

fn record(args: &Args, s: &SweepSummary) -> serde_json::Value {
    json!({
        "params": {
            "grid": args.grid,
            "rays": args.rays,
            "seed": args.seed,
            "shard": format!("{}/{}", args.shard.k, args.shard.n),
            "limit": args.limit,
            "png": args.png,
        },
        "configs": s.total,
        "skipped": s.skipped,
        "ran": s.ran,
        "remaining": s.remaining,
        "seconds": s.seconds,
        "rays": s.rays,
    })
}
