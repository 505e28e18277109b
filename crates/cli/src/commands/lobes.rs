//! `cuticle lobes`: a fiber model's lobes as lat-long images (docs/conventions.md §4), and with
//! `--samples` the histogram of its importance samples beside them, like d'Eon et al. 2014 Figure
//! 7.
//!
//! Each pixel (and so each row of `azimuthal.csv`) is the mean of S over the pixel, integrated
//! on the white furnace's θ panels (`cuticle_fiber::furnace`) cut at the rows' edges, as the
//! simulator's histograms and `validate` are: a lobe narrower than a row is neither missed nor
//! overstated, and the images' energy (`energy_of_images` in lobes.json) is the furnace's
//! (`energy`) within [`IMAGE_ENERGY_TOLERANCE`] at every β the command takes.

use crate::commands::fiber_args::FiberArgs;
use crate::latlong_io::{LOBE_FILES, png_bytes_with_white, white_point, write_images};
use crate::output::OutDir;
use crate::progress::bar;
use crate::svg_plot::{Series, line_plot};
use anyhow::Result;
use cuticle_fiber::geometry::latlong::index_of_dir;
use cuticle_fiber::lobe::channel_mean;
use cuticle_fiber::ranges;
use cuticle_fiber::{FiberAngles, FiberModel, LatLongGrid, LatLongImage, Lobe};
use cuticle_validate::pixel_integral::{lobe_grid, lobe_images, total};
use glam::DVec3;
use rand_core::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;
use rayon::prelude::*;
use serde_json::json;
use std::path::PathBuf;
use std::time::Instant;

#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    fiber: FiberArgs,
    /// Incident inclination θ_i, radians, in (−π/2, π/2).
    #[arg(long, default_value_t = 0.5, allow_negative_numbers = true)]
    theta_i: f64,
    /// Importance samples to histogram beside the evaluated lobes (0: none).
    #[arg(long, default_value_t = 0)]
    samples: u64,
    /// Seed of the importance samples.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Image width (height is width / 4).
    #[arg(long, default_value_t = 400)]
    width: usize,
    /// Output folder.
    #[arg(long, default_value = "out/lobes")]
    out: PathBuf,
}

/// Samples per independent random stream: fixed, so a seed gives the same histogram on any
/// number of threads.
const CHUNK: u64 = 1 << 14;

pub fn run(args: Args) -> Result<()> {
    ranges::THETA_I.check(args.theta_i)?;
    let grid = lobe_grid(args.width)?;
    if args.samples > 0 {
        ranges::SAMPLES.check(args.samples)?;
    }
    let model = args.fiber.model()?;
    let wi = FiberAngles::new(args.theta_i, 0.0);
    let mut out = OutDir::create(&args.out, "lobes")?;

    let rule =
        cuticle_fiber::furnace::FurnaceRule::for_fiber(args.fiber.beta, args.fiber.alpha_deg);
    let start = Instant::now();
    let lobes = lobe_images(model.as_ref(), args.theta_i, grid, rule);
    let eval_seconds = start.elapsed().as_secs_f64();
    let total = total(&lobes);
    let mut named: Vec<(&str, &LatLongImage)> =
        LOBE_FILES.iter().copied().zip(lobes.iter()).collect();
    named.push(("total", &total));
    write_images(&mut out, &named, true)?;

    let energy = cuticle_fiber::furnace::albedo(model.as_ref(), args.theta_i, rule);
    let mut record = json!({
        "params": args.fiber.json(Some(args.theta_i))?,
        "energy": energy_json(|l| channel_mean(energy.per_lobe[l]), channel_mean(energy.albedo)),
        "energy_error_estimate": channel_mean(energy.error_estimate),
        "energy_of_images_bound": IMAGE_ENERGY_TOLERANCE * channel_mean(energy.albedo)
            + IMAGE_ENERGY_ESTIMATES * channel_mean(energy.error_estimate),
        "energy_of_images": energy_json(|l| channel_mean(lobes[l.index()].energy()), channel_mean(total.energy())),
        "width": grid.width, "height": grid.height,
        "seconds": { "evaluate": eval_seconds },
    });

    if args.samples > 0 {
        let start = Instant::now();
        let histogram = sample_histogram(model.as_ref(), wi, grid, args.samples, args.seed);
        record["seconds"]["sample"] = json!(start.elapsed().as_secs_f64());
        record["samples"] = json!(args.samples);
        record["mean_iterations"] = json!(histogram.mean_iterations);
        write_comparison(&mut out, &total, &histogram.image)?;
        record["sampled_energy"] = json!(channel_mean(histogram.image.energy()));
        record["relative_l1_sampled_vs_evaluated"] = json!(relative_l1(&histogram.image, &total));
    }
    out.finish(record)?;
    println!(
        "{} at theta_i {:.3}: energy R {:.4} TT {:.4} TRT {:.4} TRRT {:.4} rest {:.4} total {:.4} -> {}",
        model.name(),
        args.theta_i,
        channel_mean(energy.per_lobe[Lobe::R]),
        channel_mean(energy.per_lobe[Lobe::TT]),
        channel_mean(energy.per_lobe[Lobe::TRT]),
        channel_mean(energy.per_lobe[Lobe::TRRT]),
        channel_mean(energy.per_lobe[Lobe::Rest]),
        channel_mean(energy.albedo),
        args.out.display()
    );
    Ok(())
}

fn energy_json(per_lobe: impl Fn(Lobe) -> f64, total: f64) -> serde_json::Value {
    let mut v = serde_json::Map::new();
    for lobe in Lobe::ALL {
        v.insert(lobe.name().to_string(), json!(per_lobe(lobe)));
    }
    v.insert("total".into(), json!(total));
    v.into()
}

/// How far each lobe's image energy may sit from the furnace's: this share of the total
/// (channel means; the φ rules differ, three points a column here, uniform panels there) plus
/// [`IMAGE_ENERGY_ESTIMATES`] times the furnace's error estimate (at the smallest β with a
/// tilt the furnace's finest panels are capped wider than a lobe, and its fine-against-coarse
/// estimate is all either integral is known to). lobes.json states the bound as
/// `energy_of_images_bound`; tests/fiber_commands.rs holds every model to it from the smallest
/// β to the largest.
pub const IMAGE_ENERGY_TOLERANCE: f64 = 2e-3;
/// See [`IMAGE_ENERGY_TOLERANCE`].
pub const IMAGE_ENERGY_ESTIMATES: f64 = 4.0;

/// The histogram of importance samples, in the units of S: Σ weight / (N · pixel solid angle).
pub struct SampleHistogram {
    pub image: LatLongImage,
    pub mean_iterations: f64,
}

pub fn sample_histogram(
    model: &dyn FiberModel,
    wi: FiberAngles,
    grid: LatLongGrid,
    n: u64,
    seed: u64,
) -> SampleHistogram {
    let chunks = n.div_ceil(CHUNK);
    let progress = bar(chunks, "sample");
    let mut image = LatLongImage::zeros(grid);
    let mut iterations = 0;
    // Chunks in batches, each batch's images summed in chunk order: memory stays a batch of
    // images whatever n is, and the sum is the same on any number of threads.
    let batch = rayon::current_num_threads() as u64;
    for first in (0..chunks).step_by(batch as usize) {
        let partial: Vec<(Vec<DVec3>, u64)> = (first..(first + batch).min(chunks))
            .into_par_iter()
            .map(|c| {
                let histogram = sample_chunk(model, wi, grid, n, seed, c);
                progress.inc(1);
                histogram
            })
            .collect();
        for (pixels, it) in &partial {
            image
                .pixels
                .iter_mut()
                .zip(pixels)
                .for_each(|(a, b)| *a += *b);
            iterations += it;
        }
    }
    progress.finish_and_clear();
    for k in 0..grid.height {
        let scale = 1.0 / (n as f64 * grid.pixel_solid_angle(k));
        image.pixels[k * grid.width..(k + 1) * grid.width]
            .iter_mut()
            .for_each(|p| *p *= scale);
    }
    SampleHistogram {
        image,
        mean_iterations: iterations as f64 / n as f64,
    }
}

/// The summed weights of chunk `c`'s samples per pixel, and their fixed-point iterations.
fn sample_chunk(
    model: &dyn FiberModel,
    wi: FiberAngles,
    grid: LatLongGrid,
    n: u64,
    seed: u64,
    c: u64,
) -> (Vec<DVec3>, u64) {
    let mut rng = Pcg64Mcg::seed_from_u64(seed ^ c.wrapping_mul(0x9E37_79B9_7F4A_7C15));
    let mut pixels = vec![DVec3::ZERO; grid.len()];
    let mut iterations = 0;
    for _ in 0..CHUNK.min(n - c * CHUNK) {
        let u = std::array::from_fn(|_| uniform(&mut rng));
        if let Some(s) = model.sample(wi, u) {
            pixels[index_of_dir(&grid, s.wo.to_dir())] += s.weight;
            iterations += s.iterations as u64;
        }
    }
    (pixels, iterations)
}

fn uniform(rng: &mut Pcg64Mcg) -> f64 {
    (rng.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

/// Σ |a − b| / Σ |b| over pixels, weighted by solid angle (channel mean).
fn relative_l1(a: &LatLongImage, b: &LatLongImage) -> f64 {
    let g = a.grid;
    let (mut num, mut den) = (0.0, 0.0);
    for k in 0..g.height {
        let w = g.pixel_solid_angle(k);
        for j in 0..g.width {
            num += w * channel_mean((a.at(j, k) - b.at(j, k)).abs());
            den += w * channel_mean(b.at(j, k).abs());
        }
    }
    if den > 0.0 { num / den } else { 0.0 }
}

/// `sampled_total.exr/png`, `compare.png` (evaluated | sampled | |difference| stacked, one white
/// point), and `azimuthal.svg` (evaluated and sampled densities in φ).
fn write_comparison(
    out: &mut OutDir,
    evaluated: &LatLongImage,
    sampled: &LatLongImage,
) -> Result<()> {
    let mut difference = LatLongImage::zeros(evaluated.grid);
    for ((d, a), b) in difference
        .pixels
        .iter_mut()
        .zip(&evaluated.pixels)
        .zip(&sampled.pixels)
    {
        *d = (*a - *b).abs();
    }
    out.write("sampled_total.exr", &crate::latlong_io::exr_bytes(sampled)?)?;
    let white = white_point(evaluated);
    out.write("sampled_total.png", &png_bytes_with_white(sampled, white)?)?;
    let mut sheet = LatLongImage::zeros(LatLongGrid::new(
        evaluated.grid.width,
        3 * evaluated.grid.height,
    ));
    for (i, img) in [evaluated, sampled, &difference].into_iter().enumerate() {
        let n = img.pixels.len();
        sheet.pixels[i * n..(i + 1) * n].copy_from_slice(&img.pixels);
    }
    out.write("compare.png", &png_bytes_with_white(&sheet, white)?)?;
    let g = evaluated.grid;
    let phis: Vec<f64> = (0..g.width).map(|j| g.phi_center(j)).collect();
    let series = [
        Series {
            name: "evaluated",
            color: "#1f77b4",
            values: evaluated
                .azimuthal()
                .into_iter()
                .map(channel_mean)
                .collect(),
        },
        Series {
            name: "sampled",
            color: "#d62728",
            values: sampled.azimuthal().into_iter().map(channel_mean).collect(),
        },
    ];
    out.write(
        "azimuthal.svg",
        line_plot(
            "density in phi (sr^-1 integrated over theta)",
            "phi (radians)",
            &phis,
            &series,
        )
        .as_bytes(),
    )?;
    Ok(())
}
