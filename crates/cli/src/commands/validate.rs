//! `cuticle validate`: every simulated configuration of a sweep against each model (issue 3):
//! `validation.csv` (every configuration, model and lobe), `validation.md` (summary tables and
//! the per-lobe verdict), `error_vs_theta_i.svg`, comparison sheets like d'Eon et al. 2014 Figure 7
//! in `sheets/`, and `validate.json`. With `--noise`, a second sweep of the same configurations
//! with another seed, the models are compared with the mean of the two runs and every figure
//! gets its noise floor and noise-corrected residual (`cuticle_validate::noise`, issue 14).
//! With `--moments`, `moments.csv` holds each lobe's mean, width and skew in θ per bright φ
//! column for the simulation and every model (`cuticle_validate::moments`).

use crate::latlong_io::{png_bytes_with_white, read_exr, white_point};
use crate::output::OutDir;
use crate::progress::bar;
use crate::svg_plot::{Series, line_plot};
use anyhow::{Context, Result, bail};
use cuticle_fiber::ranges;
use cuticle_fiber::{FiberAngles, LatLongImage, Lobe};
use cuticle_validate::compare::{figures_of, with_noise};
use cuticle_validate::models::FiberModels;
use cuticle_validate::moments::column_moments;
use cuticle_validate::noise::{mean_of, seed_to_seed_l1};
use cuticle_validate::peak::bright_columns;
use cuticle_validate::sheet::{abs_difference, stack, total};
use cuticle_validate::summary::{mean_median, non_finite};
use cuticle_validate::sweep_dir::FILES;
use cuticle_validate::sweep_dir::fiber_order;
use cuticle_validate::{ModelId, Row, SimConfig, csv, images_of, list_configs, markdown};
use serde_json::json;
use std::path::PathBuf;
use std::time::Instant;

#[derive(clap::Args)]
pub struct Args {
    /// A sweep folder (one subfolder per configuration) or one configuration's folder.
    #[arg(long)]
    sim: PathBuf,
    /// A second sweep of the same configurations (same parameters and paths, another --seed):
    /// its runs give each figure's noise floor, and the models are compared with the mean of
    /// the two.
    #[arg(long)]
    noise: Option<PathBuf>,
    /// Models to compare, comma-separated: nonseparable, nonseparable-paper, deon2011, marschner.
    #[arg(
        long,
        default_value = "nonseparable,nonseparable-paper,deon2011,marschner"
    )]
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
    /// Also write `moments.csv`: the mean, standard deviation and skewness in θ of R, TT and
    /// TRT over every bright φ column, for the simulation and each model.
    #[arg(long)]
    moments: bool,
    /// Output folder.
    #[arg(long, default_value = "out/validation")]
    out: PathBuf,
}

pub fn run(args: Args) -> Result<()> {
    let models = cuticle_validate::parse_models(&args.models)?;
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
    let twins = args
        .noise
        .as_deref()
        .map(|dir| noise_twins(&configs, dir))
        .transpose()?;
    let mut out = OutDir::create(&args.out, "validate")?;
    let sheet_set = sheet_indices(configs.len(), args.sheets);
    let start = Instant::now();
    let progress = bar(configs.len() as u64, "validate");
    let mut rows_of: Vec<Vec<Row>> = vec![Vec::new(); configs.len()];
    let mut moments_of: Vec<String> = vec![String::new(); configs.len()];
    let mut fiber_models = FiberModels::default();
    for i in fiber_order(&configs) {
        let config = &configs[i];
        let first = read_lobes(config)?;
        let (sim, noise) = match &twins {
            Some(t) => {
                let second = read_lobes(&t[i])?;
                (
                    mean_of(&first, &second),
                    Some(seed_to_seed_l1(&first, &second)),
                )
            }
            None => (first, None),
        };
        let params = config.fiber_params();
        let mut rendered = Vec::new();
        for &kind in &models {
            let images = images_of(fiber_models.get(kind, &params)?, config, sim[0].grid);
            let mut figures = figures_of(kind, &images, &sim);
            if let Some(n) = &noise {
                figures = with_noise(figures, n);
            }
            for lobe in Lobe::ALL {
                rows_of[i].push(Row::new(config, kind, lobe, figures.lobes[lobe.index()]));
            }
            if args.moments {
                moments_of[i] += &moment_rows(config, kind.name(), &images, &sim);
            }
            rendered.push((kind, images));
        }
        if args.moments {
            moments_of[i] += &moment_rows(config, "sim", &sim, &sim);
        }
        if sheet_set.contains(&i) {
            write_sheet(&mut out, config, &sim, &rendered, &mut fiber_models, &args)?;
        }
        progress.inc(1);
    }
    let rows = rows_of.concat();
    progress.finish_and_clear();
    let seconds = start.elapsed().as_secs_f64();

    out.write("validation.csv", csv(&rows).as_bytes())?;
    if args.moments {
        let table = format!("{MOMENTS_HEADER}\n{}", moments_of.concat());
        out.write("moments.csv", table.as_bytes())?;
    }
    let noise_note = args.noise.as_ref().map_or(String::new(), |n| {
        format!(
            " Second runs for the noise floor from `{}`; figures against the mean of the two.",
            n.display()
        )
    });
    let header = format!(
        "# Validation against the Monte Carlo ground truth\n\n{} configurations from `{}`, models {}.{noise_note}\n",
        configs.len(),
        args.sim.display(),
        args.models
    );
    out.write("validation.md", markdown(&rows, &header).as_bytes())?;
    out.write("error_vs_theta_i.svg", error_plot(&rows).as_bytes())?;
    out.finish(record(&args, &configs, &rows, seconds))?;
    print_summary(&rows, configs.len(), seconds, &args);
    let bad = non_finite(&rows);
    if let Some(first) = bad.first() {
        bail!(
            "{} lobe image(s) of the models are not finite (NaN or infinite), first {} {} {}; \
             the report in {} marks them NaN",
            bad.len(),
            first.config,
            first.model,
            first.lobe,
            args.out.display()
        );
    }
    Ok(())
}

/// `moments.csv`'s columns.
const MOMENTS_HEADER: &str =
    "config,source,lobe,phi,energy,mean_theta,std_dev_theta,skewness_theta";

/// `images`' column moments of R, TT and TRT over the bright columns of `sim`, as CSV rows
/// labelled `source` ([`cuticle_validate::moments`]).
fn moment_rows(
    config: &SimConfig,
    source: &str,
    images: &[LatLongImage; 5],
    sim: &[LatLongImage; 5],
) -> String {
    let mut rows = String::new();
    for lobe in [Lobe::R, Lobe::TT, Lobe::TRT] {
        let p = lobe.index();
        for (j, _) in bright_columns(&sim[p]) {
            if let Some(m) = column_moments(&images[p], j) {
                rows += &format!(
                    "{},{source},{},{:.6},{:.6e},{:.6},{:.6},{:.4}\n",
                    config.name,
                    lobe.name(),
                    images[p].grid.phi_center(j),
                    m.energy,
                    m.mean,
                    m.std_dev,
                    m.skewness
                );
            }
        }
    }
    rows
}

/// For every configuration, its second run under `dir`: the same folder name, the same
/// parameters and number of paths, and a different seed (else the floor would be zero).
fn noise_twins(configs: &[SimConfig], dir: &std::path::Path) -> Result<Vec<SimConfig>> {
    let others = list_configs(dir).with_context(|| format!("--noise {}", dir.display()))?;
    configs
        .iter()
        .map(|c| {
            let Some(twin) = others.iter().find(|o| o.name == c.name) else {
                bail!(
                    "--noise {} has no configuration {} (run the same sweep with another --seed)",
                    dir.display(),
                    c.name
                );
            };
            if c.grid != twin.grid {
                bail!(
                    "--noise: {} is on a {}x{} grid, {} on {}x{}: the second run needs the same grid",
                    twin.dir.display(),
                    twin.grid[0],
                    twin.grid[1],
                    c.dir.display(),
                    c.grid[0],
                    c.grid[1]
                );
            }
            if !c.same_setup(twin) {
                bail!(
                    "--noise: {} differs from {} in its parameters or number of paths",
                    twin.dir.display(),
                    c.dir.display()
                );
            }
            if c.seed.is_none() || c.seed == twin.seed {
                bail!(
                    "--noise: {} and {} share the seed {:?}: the second run needs another --seed",
                    c.dir.display(),
                    twin.dir.display(),
                    c.seed
                );
            }
            Ok(twin.clone())
        })
        .collect()
}

/// The simulation's five lobe images, read with the rest of the configuration's set (`total`,
/// `azimuthal.csv`) and checked against each other and `sim.json` before anything relies on
/// them.
fn read_lobes(config: &SimConfig) -> Result<[LatLongImage; 5]> {
    let read = |name: &str| read_exr(&config.dir.join(format!("{name}.exr")));
    let [r, tt, trt, trrt, rest, total] = FILES.map(read);
    let images = [r?, tt?, trt?, trrt?, rest?, total?];
    let csv_path = config.dir.join("azimuthal.csv");
    let csv = cuticle_light::file::read_regular_text(&csv_path, cuticle_light::file::MAX_TEXT_FILE)
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
    rendered: &[(ModelId, [LatLongImage; 5])],
    fiber_models: &mut FiberModels,
    args: &Args,
) -> Result<()> {
    let find = |k: ModelId| {
        rendered
            .iter()
            .find(|(m, _)| *m == k)
            .map(|(_, i)| total(i))
    };
    let Some(evaluated) = find(ModelId::NonSeparable) else {
        return Ok(());
    };
    let sim_total = total(sim);
    let model = fiber_models.get(ModelId::NonSeparable, &config.fiber_params())?;
    let sampled = crate::commands::lobes::sample_histogram(
        model,
        FiberAngles::new(config.theta_i, 0.0),
        sim_total.grid,
        args.sheet_samples,
        1,
    )
    .image;
    let difference = abs_difference(&evaluated, &sim_total);
    let mut panels = vec![&sim_total, &sampled, &evaluated, &difference];
    let deon = find(ModelId::DEon2011);
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
    const COLORS: [&str; 4] = ["#1f77b4", "#ff7f0e", "#d62728", "#2ca02c"];
    let names: Vec<&'static str> = ModelId::ALL
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
            "sim": args.sim, "noise": args.noise, "models": args.models, "filter": args.filter,
            "sheets": args.sheets, "sheet_samples": args.sheet_samples, "moments": args.moments,
        },
        "configurations": configs.len(),
        "seconds": seconds,
        "summary": summary_json(rows),
        "results": rows,
    })
}

/// Per model and lobe: mean and median relative L1, and where there is a noise floor its
/// median and the median residual.
fn summary_json(rows: &[Row]) -> serde_json::Value {
    use cuticle_validate::summary::{counted_floor, counted_l1, counted_residual};
    let mut out = serde_json::Map::new();
    for kind in ModelId::ALL {
        let mut lobes = serde_json::Map::new();
        for lobe in Lobe::ALL {
            let of = || {
                rows.iter()
                    .filter(|r| r.model == kind.name() && r.lobe == lobe.name())
            };
            let Some((mean, median)) = mean_median(of().map(counted_l1)) else {
                continue;
            };
            let mut v = json!({"mean_relative_l1": mean, "median_relative_l1": median});
            if let Some((_, floor)) = mean_median(of().map(counted_floor)) {
                v["median_noise_floor"] = json!(floor);
                v["median_residual_l1"] =
                    json!(mean_median(of().map(counted_residual)).map(|m| m.1));
            }
            lobes.insert(lobe.name().into(), v);
        }
        if !lobes.is_empty() {
            out.insert(kind.name().into(), lobes.into());
        }
    }
    out.into()
}

/// The summary on stdout: per lobe, the mean relative L1 of each model; with a noise floor,
/// medians: the seed-to-seed L1 and the floor, then each model's L1 and residual.
fn print_summary(rows: &[Row], n: usize, seconds: f64, args: &Args) {
    use cuticle_validate::summary::{counted_floor, counted_l1, counted_residual, has_noise};
    println!(
        "validated {n} configurations in {seconds:.1} s -> {}",
        args.out.display()
    );
    let median = |v: Vec<Option<f64>>| mean_median(v).map(|m| m.1);
    let fmt = |v: Option<f64>| v.map_or_else(|| "–".to_string(), |x| format!("{x:.3}"));
    let noise = has_noise(rows);
    if noise {
        println!("  medians per lobe: seed-to-seed L1, noise floor; each model's L1 (residual)");
    }
    for lobe in ["R", "TT", "TRT"] {
        let of = |m: &str| -> Vec<&Row> {
            rows.iter()
                .filter(|r| r.model == m && r.lobe == lobe)
                .collect()
        };
        let mut parts = Vec::new();
        if noise {
            let any = of(ModelId::ALL[0].name());
            let floor = median(any.iter().map(|r| counted_floor(r)).collect());
            parts.push(format!(
                "seed-to-seed {} floor {}",
                fmt(floor.map(|f| 2.0 * f)),
                fmt(floor)
            ));
        }
        for kind in ModelId::ALL {
            let sel = of(kind.name());
            if sel.is_empty() {
                continue;
            }
            parts.push(if noise {
                format!(
                    "{} {} ({})",
                    kind.name(),
                    fmt(median(sel.iter().map(|r| counted_l1(r)).collect())),
                    fmt(median(sel.iter().map(|r| counted_residual(r)).collect()))
                )
            } else {
                format!(
                    "{} {}",
                    kind.name(),
                    fmt(mean_median(sel.iter().map(|r| counted_l1(r))).map(|m| m.0))
                )
            });
        }
        let what = if noise { "" } else { "mean relative L1: " };
        println!("  {lobe:4} {what}{}", parts.join(" | "));
    }
}
