//! Random numbers for procedural grooms. Every strand and every clump draws from its own
//! generator, seeded from the groom's seed and its index, so the result does not depend on
//! how the work is split across threads.

use rand_core::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;
use std::f32::consts::TAU;

/// Which family of objects a generator belongs to, so clump 3 and strand 3 differ.
#[derive(Clone, Copy, Debug)]
pub enum Stream {
    Clump = 1,
    Strand = 2,
}

/// A generator with the few distributions the groom needs.
pub struct Random(Pcg64Mcg);

impl Random {
    /// The generator of object `index` of `stream` in the groom seeded with `seed`.
    pub fn for_object(seed: u64, stream: Stream, index: usize) -> Self {
        let key = mix(mix(seed) ^ (stream as u64).wrapping_mul(0xa076_1d64_78bd_642f))
            ^ (index as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15);
        Self(Pcg64Mcg::seed_from_u64(mix(key)))
    }

    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f32 {
        (self.0.next_u64() >> 40) as f32 * (1.0 / (1u64 << 24) as f32)
    }

    /// Uniform in [lo, hi).
    pub fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.unit()
    }

    /// Uniform integer in [lo, hi] (inclusive).
    pub fn int_inclusive(&mut self, lo: usize, hi: usize) -> usize {
        let span = (hi - lo) as u64 + 1;
        lo + (self.0.next_u64() % span) as usize
    }

    /// Standard normal (Box–Muller).
    pub fn normal(&mut self) -> f32 {
        let u1 = 1.0 - self.unit();
        let u2 = self.unit();
        (-2.0 * u1.ln()).sqrt() * (TAU * u2).cos()
    }

    /// Uniform angle in [0, 2π).
    pub fn angle(&mut self) -> f32 {
        TAU * self.unit()
    }
}

/// SplitMix64's finaliser: spreads every input bit over the output.
fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn objects_get_distinct_reproducible_streams() {
        let draw = |seed, stream, index| Random::for_object(seed, stream, index).0.next_u64();
        assert_eq!(draw(5, Stream::Strand, 9), draw(5, Stream::Strand, 9));
        assert_ne!(draw(5, Stream::Strand, 9), draw(5, Stream::Strand, 10));
        assert_ne!(draw(5, Stream::Strand, 9), draw(5, Stream::Clump, 9));
        assert_ne!(draw(5, Stream::Strand, 9), draw(6, Stream::Strand, 9));
    }

    #[test]
    fn distributions_have_their_moments() {
        let rng = &mut Random::for_object(1, Stream::Strand, 0);
        let n = 20_000;
        let units: Vec<f32> = (0..n).map(|_| rng.unit()).collect();
        assert!(units.iter().all(|u| (0.0..1.0).contains(u)));
        let mean = units.iter().sum::<f32>() / n as f32;
        assert!((mean - 0.5).abs() < 0.01, "{mean}");
        let normals: Vec<f32> = (0..n).map(|_| rng.normal()).collect();
        let mean = normals.iter().sum::<f32>() / n as f32;
        let var = normals.iter().map(|x| (x - mean).powi(2)).sum::<f32>() / n as f32;
        assert!(
            mean.abs() < 0.03 && (var - 1.0).abs() < 0.05,
            "{mean} {var}"
        );
        let ints: Vec<usize> = (0..n).map(|_| rng.int_inclusive(20, 30)).collect();
        assert_eq!(
            (ints.iter().min(), ints.iter().max()),
            (Some(&20), Some(&30))
        );
    }
}
