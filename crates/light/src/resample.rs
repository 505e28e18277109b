//! Downsampling a lat-long map: each new pixel is the solid-angle-weighted mean of the old pixels
//! it covers (fractional overlaps included), so ∫ L dω over any new pixel is kept exactly.

use crate::EnvMap;
use glam::DVec3;
use rayon::prelude::*;
use std::f64::consts::PI;

/// Overlap weights of each output cell with the input cells: `(input index, weight)` lists.
type Overlaps = Vec<Vec<(usize, f64)>>;

impl EnvMap {
    /// This map area-averaged down to `width × height` (each no larger than now); rotation kept.
    pub fn downsample(&self, width: usize, height: usize) -> EnvMap {
        assert!(
            (1..=self.width()).contains(&width) && (1..=self.height()).contains(&height),
            "downsample to {width}x{height} from {}x{}",
            self.width(),
            self.height()
        );
        let columns = column_overlaps(self.width(), width);
        let rows = row_overlaps(self.height(), height);
        let narrow: Vec<Vec<DVec3>> = (0..self.height())
            .into_par_iter()
            .map(|row| self.row_resampled(row, &columns))
            .collect();
        let pixels = (0..height)
            .into_par_iter()
            .flat_map_iter(|out_row| {
                let row_weights = &rows[out_row];
                let narrow = &narrow;
                (0..width).map(move |column| {
                    let sum: DVec3 = row_weights
                        .iter()
                        .map(|&(row, w)| narrow[row][column] * w)
                        .sum();
                    sum.as_vec3()
                })
            })
            .collect();
        EnvMap::new(width, height, pixels)
            .with_rotation(self.rotation())
            .with_clamped_negatives(self.clamped_negatives())
    }

    fn row_resampled(&self, row: usize, columns: &Overlaps) -> Vec<DVec3> {
        let line = &self.pixels()[row * self.width()..(row + 1) * self.width()];
        columns
            .iter()
            .map(|cell| {
                cell.iter()
                    .map(|&(c, w)| line[c].as_dvec3() * w)
                    .sum::<DVec3>()
            })
            .collect()
    }
}

/// Column overlaps: all columns have the same solid angle per unit φ, so weights are the overlap
/// lengths in φ, normalised to sum to 1.
fn column_overlaps(from: usize, to: usize) -> Overlaps {
    overlaps(from, to, |x| x)
}

/// Row overlaps weighted by solid angle: the part of input row k inside an output row counts
/// sin θ_top − sin θ_bottom of that part (docs/conventions.md §4 pixel solid angle).
fn row_overlaps(from: usize, to: usize) -> Overlaps {
    overlaps(from, to, |y| -(PI / 2.0 - PI * y).sin())
}

/// For each of `to` equal cells over [0, 1], the input cells of `from` it overlaps, each weighted
/// by the measure `m(b) − m(a)` of the overlap [a, b], normalised to sum to 1.
fn overlaps(from: usize, to: usize, measure: impl Fn(f64) -> f64) -> Overlaps {
    (0..to)
        .map(|cell| {
            let (lo, hi) = (cell as f64 / to as f64, (cell + 1) as f64 / to as f64);
            let first = (lo * from as f64).floor() as usize;
            let last = ((hi * from as f64).ceil() as usize).min(from);
            let mut list: Vec<(usize, f64)> = (first..last)
                .filter_map(|i| {
                    let a = lo.max(i as f64 / from as f64);
                    let b = hi.min((i + 1) as f64 / from as f64);
                    (b > a).then(|| (i, measure(b) - measure(a)))
                })
                .collect();
            let total: f64 = list.iter().map(|&(_, w)| w).sum();
            list.iter_mut().for_each(|(_, w)| *w /= total);
            list
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn test_map(width: usize, height: usize) -> EnvMap {
        EnvMap::from_fn(width, height, |d| {
            Vec3::new(
                (3.0 * d.x).sin() as f32 + 1.5,
                (d.y * d.y * 4.0) as f32,
                (1.0 + d.z) as f32,
            )
        })
    }

    #[test]
    fn downsampling_keeps_the_integral() {
        let map = test_map(120, 60);
        for &(w, h) in &[(60, 30), (32, 16), (7, 3), (120, 60)] {
            let small = map.downsample(w, h);
            let diff = (small.integral() - map.integral()).abs().max_element();
            assert!(
                diff < 1e-4 * map.integral().max_element(),
                "{w}x{h}: {diff}"
            );
        }
    }

    #[test]
    fn integer_factor_downsample_is_the_weighted_block_mean() {
        let map = test_map(16, 8);
        let small = map.downsample(8, 4);
        let (c, r) = (3, 0);
        let mut sum = DVec3::ZERO;
        let mut weight = 0.0;
        for row in 2 * r..2 * r + 2 {
            for column in 2 * c..2 * c + 2 {
                sum += map.pixel(column, row).as_dvec3() * map.solid_angle(row);
                weight += map.solid_angle(row);
            }
        }
        let expected = (sum / weight).as_vec3();
        assert!(small.pixel(c, r).abs_diff_eq(expected, 1e-5));
        assert!(!small.pixel(c, r).abs_diff_eq(map.pixel(2 * c, 2 * r), 1e-3));
    }
}
