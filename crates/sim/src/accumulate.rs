//! Tallies of exiting weight per lobe and pixel, and of lost weight, in 32.32 fixed point.
//!
//! Integer addition is associative, so the merged tally is bit-identical however the rays were
//! split between threads. One unit is 2⁻³² of a ray's weight: the rounding per path is below
//! 1.2·10⁻¹⁰, and a pixel holds 4·10⁹ rays' worth of weight (a 10⁹-ray run, the most
//! [`crate::SimParams`] accepts, puts a few 10⁷ into its brightest R pixel).

use cuticle_fiber::{LatLongGrid, LatLongImage};
use glam::DVec3;

/// Lobes by number of internal segments p: R, TT, TRT, TRRT, and p ≥ 4 in "rest".
pub const LOBES: usize = 5;

const ONE: f64 = 4_294_967_296.0;

/// Why a path's weight, or part of it, did not leave the fiber.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Loss {
    Shadowing,
    BackFacing,
    Cutoff,
}

/// Lost weight per kind, summed in floating point over one chunk of rays (always in the same
/// order, so still deterministic) and then added to a [`Tally`] once.
#[derive(Clone, Copy, Debug, Default)]
pub struct LossSums([DVec3; 3]);

impl LossSums {
    #[inline]
    pub fn add(&mut self, why: Loss, w: DVec3) {
        self.0[why as usize] += w;
    }
}

/// Fixed-point sums for one group of rays.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Tally {
    grid: LatLongGrid,
    /// `[lobe][pixel][channel]`, flattened.
    exits: Vec<u64>,
    /// `[loss kind][channel]`; signed, because an importance-sampling weight above 1 records a
    /// negative shadowing loss (the estimator stays unbiased).
    losses: [[i128; 3]; 3],
}

/// Nearest fixed-point value of a weight ≥ 0 (a cast truncates; `round` is a library call on
/// the baseline x86-64 target).
#[inline]
fn to_unsigned(x: f64) -> u64 {
    (x * ONE + 0.5) as i64 as u64
}

/// Nearest fixed-point value of a signed weight.
#[inline]
fn to_signed(x: f64) -> i128 {
    (x * ONE + 0.5f64.copysign(x)) as i64 as i128
}

impl Tally {
    pub fn new(grid: LatLongGrid) -> Self {
        Self {
            grid,
            exits: vec![0; LOBES * grid.len() * 3],
            losses: [[0; 3]; 3],
        }
    }

    /// Records RGB weight `w` leaving in lobe `p` (≥ 4 goes to "rest") into pixel `pixel`.
    #[inline]
    pub fn exit(&mut self, p: usize, pixel: usize, w: DVec3) {
        let base = (p.min(LOBES - 1) * self.grid.len() + pixel) * 3;
        let cell = &mut self.exits[base..base + 3];
        for (c, v) in cell.iter_mut().zip(w.to_array()) {
            *c = c.wrapping_add(to_unsigned(v));
        }
    }

    /// Records RGB weight `w` lost for `why`.
    #[inline]
    pub fn lose(&mut self, why: Loss, w: DVec3) {
        let row = &mut self.losses[why as usize];
        for (c, v) in row.iter_mut().zip(w.to_array()) {
            *c += to_signed(v);
        }
    }

    /// Records a chunk's summed losses.
    pub fn lose_all(&mut self, sums: &LossSums) {
        for why in [Loss::Shadowing, Loss::BackFacing, Loss::Cutoff] {
            self.lose(why, sums.0[why as usize]);
        }
    }

    /// Adds another tally of the same grid.
    pub fn merge(mut self, other: Tally) -> Tally {
        for (a, b) in self.exits.iter_mut().zip(&other.exits) {
            *a = a.wrapping_add(*b);
        }
        for (ra, rb) in self.losses.iter_mut().zip(&other.losses) {
            for (a, b) in ra.iter_mut().zip(rb) {
                *a += b;
            }
        }
        self
    }

    /// Weight lost for `why`, per ray traced.
    pub fn lost(&self, why: Loss, rays: u64) -> DVec3 {
        let l = self.losses[why as usize];
        DVec3::new(l[0] as f64, l[1] as f64, l[2] as f64) / (ONE * rays as f64)
    }

    /// The lobe images in S (sr⁻¹): weight per ray traced, divided by each pixel's solid angle
    /// (docs/conventions.md §3–4), so that `LatLongImage::energy` is the lobe's share of the power.
    pub fn images(&self, rays: u64) -> [LatLongImage; LOBES] {
        std::array::from_fn(|p| self.image(p, rays))
    }

    fn image(&self, p: usize, rays: u64) -> LatLongImage {
        let g = self.grid;
        let mut img = LatLongImage::zeros(g);
        let lobe = &self.exits[p * g.len() * 3..(p + 1) * g.len() * 3];
        for (k, row) in img.pixels.chunks_mut(g.width).enumerate() {
            let norm = 1.0 / (ONE * rays as f64 * g.pixel_solid_angle(k));
            for (j, px) in row.iter_mut().enumerate() {
                let c = &lobe[(k * g.width + j) * 3..][..3];
                *px = DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64) * norm;
            }
        }
        img
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn images_hold_weight_per_ray_over_solid_angle() {
        let g = LatLongGrid::new(8, 4);
        let mut t = Tally::new(g);
        t.exit(1, 9, DVec3::new(0.5, 1.0, 0.25));
        t.exit(7, 0, DVec3::splat(1.0));
        let more = {
            let mut m = Tally::new(g);
            m.lose(Loss::Shadowing, DVec3::splat(0.5));
            m.lose(Loss::Shadowing, DVec3::splat(-0.25));
            m
        };
        let t = t.merge(more);
        let imgs = t.images(2);
        assert!((imgs[1].energy() - DVec3::new(0.25, 0.5, 0.125)).length() < 1e-9);
        assert!((imgs[4].energy() - DVec3::splat(0.5)).length() < 1e-9);
        assert_eq!(imgs[0].energy(), DVec3::ZERO);
        assert!((t.lost(Loss::Shadowing, 2) - DVec3::splat(0.125)).length() < 1e-9);
    }
}
