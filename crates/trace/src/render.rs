//! The progressive image: passes of one sample per pixel, each pixel-sample's generator seeded
//! from (seed, pixel, sample index) alone, and each pixel's sums accumulated in sample order,
//! so the image is the same bit for bit on any number of threads. Per pixel the mean and its
//! standard error √(s² / n) from the sample variance s² (0 below two samples).

use crate::accel::Accel;
use crate::env_sampling::EnvSampler;
use crate::models::StrandModels;
use crate::path::{PathOptions, World};
use cuticle_fiber::ranges::{CountRange, RangeError};
use cuticle_render::{Image, Progress, Scene};
use glam::DVec3;
use rand_core::SeedableRng;
use rand_pcg::Pcg64Mcg;
use rayon::prelude::*;
use serde::Serialize;
use std::time::Instant;

/// Samples per pixel of one path-traced image ([`TraceOptions::spp`]).
pub const SPP: CountRange = CountRange {
    name: "spp",
    min: 1,
    max: 1 << 20,
};

/// Most scattering events of one path ([`PathOptions::max_depth`]).
pub const MAX_DEPTH: CountRange = CountRange {
    name: "max_depth",
    min: 1,
    max: 100_000,
};

/// What a render is asked for.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct TraceOptions {
    /// Samples per pixel.
    pub spp: u32,
    pub seed: u64,
    pub path: PathOptions,
}

impl TraceOptions {
    /// `spp` and `max_depth` checked against [`SPP`] and [`MAX_DEPTH`], the other path
    /// options their defaults (what `cuticle render --method path` and the Python bindings
    /// take).
    pub fn checked(spp: u64, seed: u64, max_depth: u64) -> Result<Self, RangeError> {
        Ok(Self {
            spp: SPP.check(spp)? as u32,
            seed,
            path: PathOptions {
                max_depth: MAX_DEPTH.check(max_depth)? as u32,
                ..PathOptions::default()
            },
        })
    }
}

impl Default for TraceOptions {
    fn default() -> Self {
        Self {
            spp: 64,
            seed: 0,
            path: PathOptions::default(),
        }
    }
}

/// A finished render: the mean image, its standard error, and what it cost.
#[derive(Clone, Debug)]
pub struct TraceImage {
    pub image: Image,
    /// Per pixel and channel: the standard error of the mean.
    pub standard_error: Vec<DVec3>,
    /// Per pixel: the fraction of its camera rays that met hair (`cuticle compare`'s mask).
    pub coverage: Vec<f64>,
    pub spp: u32,
    pub stats: TraceStats,
}

/// Counts and seconds of a render.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct TraceStats {
    /// Ray–groom queries: camera, continuation and shadow rays.
    pub rays: u64,
    /// Pixel samples (paths).
    pub samples: u64,
    /// BVH build, including the tubes.
    pub build_seconds: f64,
    /// Path tracing.
    pub trace_seconds: f64,
    pub tubes: usize,
}

impl TraceStats {
    pub fn rays_per_second(&self) -> f64 {
        self.rays as f64 / self.trace_seconds.max(1e-12)
    }

    pub fn samples_per_second(&self) -> f64 {
        self.samples as f64 / self.trace_seconds.max(1e-12)
    }
}

/// Running sums of one pixel.
#[derive(Clone, Copy, Debug, Default)]
struct Accumulator {
    sum: DVec3,
    sum_sq: DVec3,
    hits: u32,
}

/// Renders `scene` with `models`, calling `progress(samples per pixel done, total)` after each
/// pass. Camera, image size and environment are the scene's, as the SRBF renderer reads them.
pub fn render(
    scene: &Scene,
    models: &StrandModels,
    options: &TraceOptions,
    progress: Progress,
) -> TraceImage {
    let accel = Accel::build(&scene.groom);
    render_with(scene, &accel, models, options, progress)
}

/// [`render`] with the BVH already built.
pub fn render_with(
    scene: &Scene,
    accel: &Accel,
    models: &StrandModels,
    options: &TraceOptions,
    progress: Progress,
) -> TraceImage {
    let (width, height) = (scene.spec.width, scene.spec.height);
    let view = scene.camera.view(width, height);
    let sampler = EnvSampler::new(&scene.env);
    let world = World {
        accel,
        env: &scene.env,
        sampler: &sampler,
        models,
    };
    let start = Instant::now();
    let mut acc = vec![Accumulator::default(); width * height];
    let mut rays = 0u64;
    for pass in 0..options.spp {
        rays += acc
            .par_chunks_mut(width.max(1))
            .enumerate()
            .map(|(y, row)| {
                let mut rays = 0u64;
                for (x, a) in row.iter_mut().enumerate() {
                    let pixel = (y * width + x) as u64;
                    let mut rng = Pcg64Mcg::seed_from_u64(sample_seed(options.seed, pixel, pass));
                    let (jx, jy) = (
                        crate::path::uniform(&mut rng),
                        crate::path::uniform(&mut rng),
                    );
                    let dir = view.ray(x as f64 + jx, y as f64 + jy);
                    let s = world.camera_sample(view.eye, dir, &options.path, &mut rng);
                    a.sum += s.radiance;
                    a.sum_sq += s.radiance * s.radiance;
                    a.hits += u32::from(s.hit);
                    rays += s.rays;
                }
                rays
            })
            .sum::<u64>();
        progress(pass as usize + 1, options.spp as usize);
    }
    let n = options.spp.max(1) as f64;
    let image = Image {
        width,
        height,
        pixels: acc.iter().map(|a| a.sum / n).collect(),
    };
    let standard_error = acc
        .iter()
        .map(|a| {
            if options.spp < 2 {
                return DVec3::ZERO;
            }
            let mean = a.sum / n;
            let variance = ((a.sum_sq - mean * mean * n) / (n - 1.0)).max(DVec3::ZERO);
            (variance / n).map(f64::sqrt)
        })
        .collect();
    TraceImage {
        image,
        standard_error,
        coverage: acc.iter().map(|a| a.hits as f64 / n).collect(),
        spp: options.spp,
        stats: TraceStats {
            rays,
            samples: options.spp as u64 * (width * height) as u64,
            build_seconds: accel.build_seconds,
            trace_seconds: start.elapsed().as_secs_f64(),
            tubes: accel.tube_count(),
        },
    }
}

/// The seed of one pixel-sample's generator: SplitMix64 (Steele et al. 2014) of the three
/// numbers chained, so neighbouring pixels and samples get unrelated streams.
pub fn sample_seed(seed: u64, pixel: u64, sample: u32) -> u64 {
    splitmix64(splitmix64(splitmix64(seed) ^ pixel) ^ sample as u64)
}

fn splitmix64(x: u64) -> u64 {
    let mut z = x.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}
