//! The parallel simulation: rays in fixed-size chunks, one random stream per chunk, tallies
//! merged exactly (fixed point), so the result is bit-identical on any number of threads.

use crate::accumulate::{LOBES, Loss, LossSums, Tally};
use crate::params::{SimError, SimParams};
use crate::path::Fiber;
use crate::rng::Sampler;
use cuticle_fiber::LatLongImage;
use glam::DVec3;
use rayon::prelude::*;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Instant;

/// Rays per chunk (and per random stream). Part of the definition of a seed's result.
pub const CHUNK: u64 = 1 << 16;

/// Lobe names in the order of [`SimResult::lobes`] (docs/conventions.md §5).
pub const LOBE_NAMES: [&str; LOBES] = ["R", "TT", "TRT", "TRRT", "rest"];

/// The outcome of [`simulate`]. Energies and losses are fractions of the intercepted power, RGB.
#[derive(Clone, Debug)]
pub struct SimResult {
    pub params: SimParams,
    /// S in sr⁻¹ per lobe: R, TT, TRT, TRRT, rest (p ≥ 4), in the order of [`LOBE_NAMES`].
    pub lobes: [LatLongImage; LOBES],
    /// ∫ S dω of each lobe.
    pub energy: [DVec3; LOBES],
    /// Shadowing and masking by the micro-surface, and rays sent to the wrong side of the macro
    /// surface. An unbiased estimate: single paths may record negative loss (weights above 1).
    pub lost_shadowing: DVec3,
    /// Rays that met the back of a tilted scale.
    pub lost_backfacing: DVec3,
    /// Paths still inside after [`crate::path::MAX_EVENTS`] surface events.
    pub lost_cutoff: DVec3,
    /// Wall time of the tracing, in seconds.
    pub seconds: f64,
    /// Paths traced.
    pub rays: u64,
}

impl SimResult {
    /// The sum of the lobes.
    pub fn total(&self) -> LatLongImage {
        let mut t = LatLongImage::zeros(self.params.grid);
        self.lobes.iter().for_each(|l| t.add(l));
        t
    }

    /// The albedo ∫ S dω over all lobes.
    pub fn albedo(&self) -> DVec3 {
        self.energy.iter().sum()
    }

    /// Power absorbed inside the fiber: what neither left nor was lost at the surface, at
    /// least 0. The difference of sums leaves a residue of about 1e-13 where nothing is
    /// absorbed (μ_a = 0), negative as often as not (issue 57 #13): no fiber absorbs less than
    /// nothing.
    pub fn absorbed(&self) -> DVec3 {
        let rest = DVec3::ONE
            - self.albedo()
            - self.lost_shadowing
            - self.lost_backfacing
            - self.lost_cutoff;
        rest.max(DVec3::ZERO)
    }

    /// Paths per second of wall time.
    pub fn paths_per_second(&self) -> f64 {
        self.rays as f64 / self.seconds.max(1e-12)
    }
}

/// Traces `params.rays` paths on the current rayon pool. `progress(done, total)` is called,
/// from worker threads, after each chunk of rays.
pub fn simulate(
    params: &SimParams,
    progress: &(dyn Fn(u64, u64) + Sync),
) -> Result<SimResult, SimError> {
    params.validate()?;
    let start = Instant::now();
    let tally = trace_all(params, progress);
    let seconds = start.elapsed().as_secs_f64();
    let rays = params.rays;
    let lobes = tally.images(rays);
    Ok(SimResult {
        params: params.clone(),
        energy: std::array::from_fn(|p| lobes[p].energy()),
        lobes,
        lost_shadowing: tally.lost(Loss::Shadowing, rays),
        lost_backfacing: tally.lost(Loss::BackFacing, rays),
        lost_cutoff: tally.lost(Loss::Cutoff, rays),
        seconds,
        rays,
    })
}

fn trace_all(params: &SimParams, progress: &(dyn Fn(u64, u64) + Sync)) -> Tally {
    let fiber = Fiber::new(params);
    let chunks = params.rays.div_ceil(CHUNK) as usize;
    let done = AtomicU64::new(0);
    let grid = params.grid;
    // A few pieces per thread balance the load; more would only add tallies to zero and merge.
    let min_len = (chunks / (4 * rayon::current_num_threads())).max(1);
    (0..chunks)
        .into_par_iter()
        .with_min_len(min_len)
        .fold(
            || Tally::new(grid),
            |mut tally, c| {
                let n = trace_chunk(&fiber, params, c as u64, &mut tally);
                progress(done.fetch_add(n, Ordering::Relaxed) + n, params.rays);
                tally
            },
        )
        .reduce(|| Tally::new(grid), Tally::merge)
}

/// Traces chunk `c` through the widest of [`trace_chunk_baseline`]'s builds this CPU runs.
/// They give the same bits (`trace_chunk_avx2_gives_the_baseline_bits`): Rust never fuses a
/// multiply and an add unasked, and the sim asks for no fused operation.
fn trace_chunk(fiber: &Fiber, params: &SimParams, c: u64, tally: &mut Tally) -> u64 {
    #[cfg(target_arch = "x86_64")]
    if has_avx2() {
        // SAFETY: the CPU has every feature `trace_chunk_avx2` is compiled for.
        return unsafe { trace_chunk_avx2(fiber, params, c, tally) };
    }
    trace_chunk_baseline(fiber, params, c, tally)
}

/// Whether this CPU has the features of [`trace_chunk_avx2`] (x86-64-v3 less FMA).
#[cfg(target_arch = "x86_64")]
fn has_avx2() -> bool {
    use std::arch::is_x86_feature_detected as has;
    has!("avx2") && has!("bmi1") && has!("bmi2") && has!("lzcnt") && has!("popcnt")
}

/// [`trace_chunk_baseline`] compiled for AVX2: three-operand VEX arithmetic, `roundsd`, `mulx`
/// (the project builds for baseline x86-64, SSE2 only). Everything the path loop calls is
/// inlined into it and compiled alike, but for the C library's `exp`, which picks its own.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,bmi1,bmi2,lzcnt,popcnt")]
fn trace_chunk_avx2(fiber: &Fiber, params: &SimParams, c: u64, tally: &mut Tally) -> u64 {
    trace_chunk_baseline(fiber, params, c, tally)
}

/// Traces chunk `c`: its rays' offsets are stratified, h_k = −1 + 2(k + ξ_k)/n for ray k of n,
/// which keeps h uniform on [−1, 1] and lowers the variance of each lobe's energy.
#[inline(always)]
fn trace_chunk_baseline(fiber: &Fiber, params: &SimParams, c: u64, tally: &mut Tally) -> u64 {
    let first = c * CHUNK;
    let n = CHUNK.min(params.rays - first);
    let mut rng = Sampler::for_chunk(params.seed, c);
    let scale = 2.0 / n as f64;
    let mut lost = LossSums::default();
    for k in 0..n {
        let h = -1.0 + (k as f64 + rng.uniform()) * scale;
        fiber.trace(h, &mut rng, tally, &mut lost);
    }
    tally.lose_all(&lost);
    n
}

#[cfg(test)]
mod tests {
    use super::*;
    use cuticle_fiber::LatLongGrid;

    /// A clear fiber whose tallies add up to a hair over 1, as sums of f64 do.
    #[test]
    fn absorbed_is_never_negative() {
        let params = SimParams {
            mu_a: [0.0; 3],
            ..SimParams::default()
        };
        let grid = params.grid;
        let third = DVec3::splat(1.0 / 3.0 + 1e-16);
        let result = SimResult {
            params,
            lobes: std::array::from_fn(|_| LatLongImage::zeros(grid)),
            energy: [third, third, third, DVec3::ZERO, DVec3::ZERO],
            lost_shadowing: DVec3::splat(1e-13),
            lost_backfacing: DVec3::ZERO,
            lost_cutoff: DVec3::ZERO,
            seconds: 1.0,
            rays: 1,
        };
        assert_eq!(result.absorbed(), DVec3::ZERO);
        let absorbing = SimResult {
            energy: [DVec3::splat(0.1); LOBES],
            lost_shadowing: DVec3::ZERO,
            ..result
        };
        assert!(
            (absorbing.absorbed() - DVec3::splat(0.5))
                .abs()
                .max_element()
                < 1e-12
        );
    }

    /// The AVX2 build of the path loop against the baseline one, chunk by chunk, on
    /// configurations that take every branch (tilted scales, rough, coloured and grey
    /// absorption, TIR trapping): the tallies must agree to the bit, or a seed's result would
    /// depend on the CPU.
    #[test]
    #[cfg(target_arch = "x86_64")]
    fn trace_chunk_avx2_gives_the_baseline_bits() {
        if !has_avx2() {
            // trace_chunk never takes the AVX2 copy here, so there is nothing to compare.
            eprintln!("no AVX2 on this CPU: the baseline copy is the only one run");
            return;
        }
        // Steep, rough, coloured; and the typical configuration, grey (one exponential).
        for (theta_i, alpha_deg, beta, mu_a) in [
            (1.2, -3.0f64, 0.3, [0.1, 0.5, 2.0]),
            (0.75, -2.0, 0.04, [0.25; 3]),
        ] {
            let params = SimParams {
                theta_i,
                alpha: alpha_deg.to_radians(),
                beta,
                eta: 1.55,
                mu_a,
                rays: 2 * CHUNK,
                seed: 11,
                grid: LatLongGrid::new(90, 45),
            };
            let fiber = Fiber::new(&params);
            for c in 0..2 {
                let mut wide = Tally::new(params.grid);
                let mut base = Tally::new(params.grid);
                // SAFETY: has_avx2() returned true above.
                unsafe { trace_chunk_avx2(&fiber, &params, c, &mut wide) };
                trace_chunk_baseline(&fiber, &params, c, &mut base);
                assert!(
                    wide == base,
                    "θ_i {theta_i} chunk {c}: the AVX2 build's tally differs"
                );
            }
        }
    }
}
