//! Random numbers: one `Pcg64Mcg` stream per chunk of rays, seeded from (seed, chunk index), so
//! that results do not depend on which thread traces which chunk.

use glam::DVec2;
use rand_core::Rng;
use rand_pcg::Pcg64Mcg;

/// A uniform sampler on [0, 1).
pub struct Sampler(Pcg64Mcg);

/// SplitMix64's finaliser (Steele, Lea & Flood 2014), used to spread (seed, chunk) over the
/// generator's 128-bit state.
fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

impl Sampler {
    /// The stream of chunk `chunk` under `seed`: the SplitMix64 sequence of `seed` read at
    /// positions 2·chunk + 1 and 2·chunk + 2 gives the high and low halves of the state.
    pub fn for_chunk(seed: u64, chunk: u64) -> Self {
        const GAMMA: u64 = 0x9e37_79b9_7f4a_7c15;
        let at = |k: u64| mix64(seed.wrapping_add(k.wrapping_mul(GAMMA)));
        let hi = at(2 * chunk + 1) as u128;
        let lo = at(2 * chunk + 2) as u128;
        Self(Pcg64Mcg::new((hi << 64) | lo))
    }

    /// A uniform double on [0, 1) with 53 random bits.
    #[inline]
    pub fn uniform(&mut self) -> f64 {
        (self.0.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// Two uniforms on [0, 1) from one 64-bit draw, 32 bits each: enough for a Fresnel choice,
    /// and for a Beckmann ξ₁, whose largest value then caps tan θ_m at 4.7 β, cutting off a
    /// share e^−22 ≈ 2·10⁻¹⁰ of the distribution.
    #[inline]
    pub fn pair(&mut self) -> (f64, f64) {
        const UNIT: f64 = 1.0 / (1u64 << 32) as f64;
        let bits = self.0.next_u64();
        (
            (bits >> 32) as f64 * UNIT,
            (bits & 0xffff_ffff) as f64 * UNIT,
        )
    }

    /// A point uniform in the unit disk (not at its centre), by rejection from the square; its
    /// two coordinates share one 64-bit draw (32 bits each, ample for an azimuth).
    #[inline]
    pub fn disk(&mut self) -> DVec2 {
        const HALF: f64 = 1.0 / (1u64 << 31) as f64;
        loop {
            let bits = self.0.next_u64();
            let x = (bits >> 32) as f64 * HALF - 1.0;
            let y = (bits & 0xffff_ffff) as f64 * HALF - 1.0;
            let p = DVec2::new(x, y);
            let r2 = p.length_squared();
            if r2 <= 1.0 && r2 > 1e-300 {
                return p;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn streams_differ_by_chunk_and_repeat_by_seed() {
        let first = |seed, chunk| Sampler::for_chunk(seed, chunk).uniform();
        assert_eq!(first(7, 3), first(7, 3));
        assert_ne!(first(7, 3), first(7, 4));
        assert_ne!(first(7, 3), first(8, 3));
        let mut s = Sampler::for_chunk(1, 0);
        let mean = (0..100_000).map(|_| s.uniform()).sum::<f64>() / 100_000.0;
        assert!((mean - 0.5).abs() < 0.005);
        let n = 100_000;
        let pts: Vec<DVec2> = (0..n).map(|_| s.disk()).collect();
        assert!(pts.iter().all(|p| p.length_squared() <= 1.0));
        let inner = pts.iter().filter(|p| p.length_squared() < 0.25).count() as f64 / n as f64;
        let upper = pts.iter().filter(|p| p.y > 0.0).count() as f64 / n as f64;
        assert!((inner - 0.25).abs() < 0.006 && (upper - 0.5).abs() < 0.006);
        let pairs: Vec<(f64, f64)> = (0..n).map(|_| s.pair()).collect();
        let below = |f: fn(&(f64, f64)) -> f64| {
            pairs.iter().filter(|p| f(p) < 0.3).count() as f64 / n as f64
        };
        assert!((below(|p| p.0) - 0.3).abs() < 0.006 && (below(|p| p.1) - 0.3).abs() < 0.006);
        assert!(pairs.iter().all(|p| p.0 < 1.0 && p.1 < 1.0));
    }
}
