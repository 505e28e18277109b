//! `cuticle validate`: every simulated configuration of a sweep against each model (issue 3):
//! `validation.csv` (every configuration, model and lobe), `validation.md` (summary tables and
//! the per-lobe verdict), `error_vs_theta_i.svg`, comparison sheets like d'Eon et al. 2014 Figure 7 in
//! `sheets/`, and `validate.json`.

use crate::latlong_io::{png_bytes_with_white, read_exr, white_point};
use crate::output::OutDir;
use crate::progress::bar;
use crate::svg_plot::{Series, line_plot};
use anyhow::{Context, Result, bail};
use cuticle_fiber::ranges;
use cuticle_fiber::{FiberAngles, LatLongImage, Lobe};
use cuticle_validate::compare::figures_of;
use cuticle_validate::sheet::{abs_difference, stack, total};
use cuticle_validate::summary::mean_median;
use cuticle_validate::sweep_dir::FILES;
use cuticle_validate::{ModelKind, Row, SimConfig, csv, list_configs, markdown, model_images};
use serde_json::json;
use std::path::PathBuf;
use std::time::Instant;

#[derive(clap::Args)]
pub struct Args {
    /// A sweep folder (one subfolder per configuration) or one configuration's folder.
    #[arg(long)]
    sim: PathBuf,
    /// Models to compare, comma-separated: nonseparable, deon2011, marschner.
    #[arg(long, default_value = "nonseparable,deon2011,marschner")]
    models: String,
    /// Only configurations whose folder name contains this text (e.g. `_a-4_` or `ti1.3_`).
    #[arg(long)]
    filter: Option<String>,
    /// Comparison sheets for this many configurations, spread evenly over the list.
    #[arg(long, default_value_t = 4)]
    sheets: usize,
    /// Importance samples of the non-separable model in each sheet's "sampled" panel.
    #[arg(long, default_value_t = 1_000_000)]
    sheet_samples: u64,
    /// Output folder.
    #[arg(long, default_value = "out/validation")]
    out: PathBuf,
}

pub fn run(args: Args) -> Result<()> {
    let models = ModelKind::parse_list(&args.models)?;
    ranges::SAMPLES
        .named("sheet_samples")
        .check(args.sheet_samples)?;
    let mut configs = list_configs(&args.sim)?;
    if let Some(f) = &args.filter {
        configs.retain(|c| c.name.contains(f.as_str()));
        if configs.is_empty() {
            bail!(
                "no configuration under {} matches --filter {f}",
                args.sim.display()
            );
        }
    }
    let mut out = OutDir::create(&args.out, "validate")?;
    let sheet_set = sheet_indices(configs.len(), args.sheets);
    let start = Instant::now();
    let progress = bar(configs.len() as u64, "validate");
    let mut rows = Vec::new();
    for (i, config) in configs.iter().enumerate() {
        let sim = read_lobes(config)?;
        let mut rendered = Vec::new();
        for &kind in &models {
            let images = model_images(config, kind, sim[0].grid)?;
            let figures = figures_of(kind, &images, &sim);
            for lobe in Lobe::ALL {
                rows.push(Row::new(config, kind, lobe, figures.lobes[lobe.index()]));
            }
            rendered.push((kind, images));
        }
        if sheet_set.contains(&i) {
            write_sheet(&mut out, config, &sim, &rendered, &args)?;
        }
        progress.inc(1);
    }
    progress.finish_and_clear();
    let seconds = start.elapsed().as_secs_f64();

    out.write("validation.csv", csv(&rows).as_bytes())?;
    let header = format!(
        "# Validation against the Monte Carlo ground truth\n\n{} configurations from `{}`, models {}.\n",
        configs.len(),
        args.sim.display(),
        args.models
    );
    out.write("validation.md", markdown(&rows, &header).as_bytes())?;
    out.write("error_vs_theta_i.svg", error_plot(&rows).as_bytes())?;
    out.finish(record(&args, &configs, &rows, seconds))?;
    print_summary(&rows, configs.len(), seconds, &args);
    Ok(())
}

/// The simulation's five lobe images, read with the rest of the configuration's set (`total`,
/// `azimuthal.csv`) and checked against each other and `sim.json` before anything relies on
/// them.
fn read_lobes(config: &SimConfig) -> Result<[LatLongImage; 5]> {
    let read = |name: &str| read_exr(&config.dir.join(format!("{name}.exr")));
    let [r, tt, trt, trrt, rest, total] = FILES.map(read);
    let images = [r?, tt?, trt?, trrt?, rest?, total?];
    let csv_path = config.dir.join("azimuthal.csv");
    let csv = std::fs::read_to_string(&csv_path)
        .with_context(|| format!("cannot read {}", csv_path.display()))?;
    config.check_set(&images, &csv)?;
    let [r, tt, trt, trrt, rest, _] = images;
    Ok([r, tt, trt, trrt, rest])
}

/// `n` indices spread evenly over `len`.
fn sheet_indices(len: usize, n: usize) -> Vec<usize> {
    let n = n.min(len);
    (0..n).map(|s| (2 * s + 1) * len / (2 * n)).collect()
}

/// `sheets/<config>.png`: simulation | sampled | evaluated | |difference| | d'Eon 2011 (totals,
/// top to bottom, one white point taken from the simulation), as d'Eon et al. 2014 Figure 7.
fn write_sheet(
    out: &mut OutDir,
    config: &SimConfig,
    sim: &[LatLongImage; 5],
    rendered: &[(ModelKind, [LatLongImage; 5])],
    args: &Args,
) -> Result<()> {
    let find = |k: ModelKind| {
        rendered
            .iter()
            .find(|(m, _)| *m == k)
            .map(|(_, i)| total(i))
    };
    let Some(evaluated) = find(ModelKind::NonSeparable) else {
        return Ok(());
    };
    let sim_total = total(sim);
    let model = ModelKind::NonSeparable.build(&config.fiber_params())?;
    let sampled = crate::commands::lobes::sample_histogram(
        model.as_ref(),
        FiberAngles::new(config.theta_i, 0.0),
        sim_total.grid,
        args.sheet_samples,
        1,
    )
    .image;
    let difference = abs_difference(&evaluated, &sim_total);
    let mut panels = vec![&sim_total, &sampled, &evaluated, &difference];
    let deon = find(ModelKind::DEon2011);
    panels.extend(deon.as_ref());
    let png = png_bytes_with_white(&stack(&panels), white_point(&sim_total))?;
    out.write(&format!("sheets/{}.png", config.name), &png)?;
    Ok(())
}

/// Mean relative L1 of R, TT and TRT against θ_i, one curve per model.
fn error_plot(rows: &[Row]) -> String {
    let mut thetas: Vec<f64> = rows.iter().map(|r| r.theta_i).collect();
    thetas.sort_by(f64::total_cmp);
    thetas.dedup();
    const COLORS: [&str; 3] = ["#1f77b4", "#d62728", "#2ca02c"];
    let names: Vec<&'static str> = ModelKind::ALL
        .iter()
        .map(|m| m.name())
        .filter(|n| rows.iter().any(|r| r.model == *n))
        .collect();
    let series: Vec<Series> = names
        .iter()
        .zip(COLORS)
        .map(|(name, color)| Series {
            name,
            color,
            values: thetas
                .iter()
                .map(|t| {
                    mean_median(
                        rows.iter()
                            .filter(|r| r.model == *name && r.theta_i == *t)
                            .filter(|r| ["R", "TT", "TRT"].contains(&r.lobe))
                            .map(cuticle_validate::summary::counted_l1),
                    )
                    .map_or(f64::NAN, |v| v.0)
                })
                .collect(),
        })
        .collect();
    line_plot(
        "mean relative L1 error of R, TT, TRT against the simulation",
        "theta_i (radians)",
        &thetas,
        &series,
    )
}

fn record(args: &Args, configs: &[SimConfig], rows: &[Row], seconds: f64) -> serde_json::Value {
    json!({
        "params": {
            "sim": args.sim, "models": args.models, "filter": args.filter,
            "sheets": args.sheets, "sheet_samples": args.sheet_samples,
        },
        "configurations": configs.len(),
        "seconds": seconds,
        "summary": summary_json(rows),
        "results": rows,
    })
}

/// Mean and median relative L1 per model and lobe.
fn summary_json(rows: &[Row]) -> serde_json::Value {
    let mut out = serde_json::Map::new();
    for kind in ModelKind::ALL {
        let mut lobes = serde_json::Map::new();
        for lobe in Lobe::ALL {
            let v = mean_median(
                rows.iter()
                    .filter(|r| r.model == kind.name() && r.lobe == lobe.name())
                    .map(cuticle_validate::summary::counted_l1),
            );
            if let Some((mean, median)) = v {
                lobes.insert(
                    lobe.name().into(),
                    json!({"mean_relative_l1": mean, "median_relative_l1": median}),
                );
            }
        }
        if !lobes.is_empty() {
            out.insert(kind.name().into(), lobes.into());
        }
    }
    out.into()
}

fn print_summary(rows: &[Row], n: usize, seconds: f64, args: &Args) {
    println!(
        "validated {n} configurations in {seconds:.1} s -> {}",
        args.out.display()
    );
    for kind in ModelKind::ALL {
        let parts: Vec<String> = ["R", "TT", "TRT"]
            .iter()
            .filter_map(|l| {
                let v = mean_median(
                    rows.iter()
                        .filter(|r| r.model == kind.name() && r.lobe == *l)
                        .map(cuticle_validate::summary::counted_l1),
                )?;
                Some(format!("{l} {:.3}", v.0))
            })
            .collect();
        if !parts.is_empty() {
            println!(
                "  {:13} mean relative L1: {}",
                kind.name(),
                parts.join(", ")
            );
        }
    }
}
