//! Importance sampling of a lat-long environment map: a 2D CDF over its pixels (rows by their
//! power, then a column within the row), a direction uniform in solid angle within the chosen
//! pixel. Directions are the light crate's (+y up, rotation applied, as [`EnvMap::radiance`]).
//!
//! The map is looked up bilinearly, so a pixel's radiance reaches into its neighbours: each
//! pixel is weighted by the largest channel mean of itself and its eight neighbours, so the
//! density is positive wherever the looked-up radiance is (an environment-only estimator stays
//! unbiased), and is piecewise constant in solid angle: pdf(ω) = w_k / Σ_j w_j Δω_j.

use cuticle_light::{EnvMap, direction_from_angles, direction_to_angles};
use glam::DVec3;
use std::f64::consts::PI;

/// A sampler of an environment map's directions; empty for a black map.
#[derive(Clone, Debug)]
pub struct EnvSampler {
    width: usize,
    height: usize,
    rotation: f64,
    /// Per pixel: its weight w_k.
    weight: Vec<f64>,
    /// Cumulative row probabilities (height + 1 entries, last 1).
    row_cdf: Vec<f64>,
    /// Per row, cumulative column probabilities (width + 1 entries each).
    column_cdf: Vec<f64>,
    /// Σ_j w_j Δω_j; 0 for a black map.
    total: f64,
}

/// A sampled direction with its density per steradian.
#[derive(Clone, Copy, Debug)]
pub struct EnvSample {
    pub direction: DVec3,
    pub pdf: f64,
}

impl EnvSampler {
    pub fn new(map: &EnvMap) -> Self {
        let (w, h) = (map.width(), map.height());
        let mean = |c: usize, r: usize| {
            let p = map.pixel(c, r);
            (p.x as f64 + p.y as f64 + p.z as f64) / 3.0
        };
        let weight: Vec<f64> = (0..w * h)
            .map(|k| {
                let (c, r) = (k % w, k / w);
                let rows = r.saturating_sub(1)..=(r + 1).min(h - 1);
                rows.flat_map(|rr| [w - 1, 0, 1].map(|dc| mean((c + dc) % w, rr)))
                    .fold(0.0, f64::max)
            })
            .collect();
        let mut row_power = Vec::with_capacity(h);
        let mut column_cdf = Vec::with_capacity(h * (w + 1));
        for r in 0..h {
            let row = &weight[r * w..(r + 1) * w];
            let sum: f64 = row.iter().sum();
            row_power.push(sum * map.solid_angle(r));
            column_cdf.extend(cumulative(row, sum));
        }
        let total: f64 = row_power.iter().sum();
        Self {
            width: w,
            height: h,
            rotation: map.rotation(),
            weight,
            row_cdf: cumulative(&row_power, total),
            column_cdf,
            total,
        }
    }

    /// Whether the map carries no light (nothing to sample).
    pub fn is_black(&self) -> bool {
        !(self.total > 0.0 && self.total.is_finite())
    }

    /// A direction from two uniform numbers, or `None` for a black map.
    pub fn sample(&self, u: [f64; 2]) -> Option<EnvSample> {
        if self.is_black() {
            return None;
        }
        let row = find(&self.row_cdf, u[0]);
        let cdf = &self.column_cdf[row * (self.width + 1)..(row + 1) * (self.width + 1)];
        let (column, u_phi) = {
            let c = find(cdf, u[1]);
            let span = cdf[c + 1] - cdf[c];
            (c, ((u[1] - cdf[c]) / span).clamp(0.0, 1.0))
        };
        // Within the pixel, uniform in solid angle: φ uniform, sin θ uniform.
        let span_r = self.row_cdf[row + 1] - self.row_cdf[row];
        let u_theta = ((u[0] - self.row_cdf[row]) / span_r).clamp(0.0, 1.0);
        let (top, bottom) = (self.theta_edge(row), self.theta_edge(row + 1));
        let sin_theta = top.sin() + u_theta * (bottom.sin() - top.sin());
        let phi = -PI + 2.0 * PI * (column as f64 + u_phi) / self.width as f64 + self.rotation;
        let direction = direction_from_angles(sin_theta.clamp(-1.0, 1.0).asin(), phi);
        Some(EnvSample {
            direction,
            pdf: self.weight[row * self.width + column] / self.total,
        })
    }

    /// The density per steradian with which [`EnvSampler::sample`] draws `direction`.
    pub fn pdf(&self, direction: DVec3) -> f64 {
        if self.is_black() {
            return 0.0;
        }
        let (theta, phi) = direction_to_angles(direction.normalize());
        let x = ((phi - self.rotation + PI) / (2.0 * PI)).rem_euclid(1.0) * self.width as f64;
        let y = (0.5 * PI - theta) / PI * self.height as f64;
        let column = (x as usize).min(self.width - 1);
        let row = (y.max(0.0) as usize).min(self.height - 1);
        self.weight[row * self.width + column] / self.total
    }

    fn theta_edge(&self, row: usize) -> f64 {
        0.5 * PI - PI * row as f64 / self.height as f64
    }
}

/// The cumulative sums of `values / total`, starting at 0 and ending at exactly 1.
fn cumulative(values: &[f64], total: f64) -> Vec<f64> {
    let mut out = Vec::with_capacity(values.len() + 1);
    let mut acc = 0.0;
    out.push(0.0);
    for v in values {
        acc += if total > 0.0 { v / total } else { 0.0 };
        out.push(acc);
    }
    let n = out.len();
    out[n - 1] = 1.0;
    out
}

/// The interval k with cdf[k] ≤ u < cdf[k + 1] and a positive width.
fn find(cdf: &[f64], u: f64) -> usize {
    let k = cdf.partition_point(|&c| c <= u).saturating_sub(1);
    let mut k = k.min(cdf.len() - 2);
    while cdf[k + 1] <= cdf[k] && k > 0 {
        k -= 1;
    }
    while cdf[k + 1] <= cdf[k] && k + 2 < cdf.len() {
        k += 1;
    }
    k
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn map_with_sun() -> EnvMap {
        EnvMap::from_fn(64, 32, |d| {
            let sun = (d.dot(DVec3::new(0.6, 0.7, 0.3).normalize()) - 0.97).max(0.0) * 400.0;
            Vec3::splat(0.1 + sun as f32) + Vec3::new(d.y.max(0.0) as f32, 0.0, 0.0)
        })
        .with_rotation(0.8)
    }

    /// Samples report the density `pdf` gives them, the density integrates to 1, and
    /// ∫ L dω estimated as the mean of L / pdf over samples matches the map's integral.
    #[test]
    fn density_is_consistent_and_estimates_the_integral() {
        let map = map_with_sun();
        let s = EnvSampler::new(&map);
        let n = 200_000;
        let mut sum = DVec3::ZERO;
        let mut state = 7u64;
        let mut next = move || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..n {
            let e = s.sample([next(), next()]).unwrap();
            let pdf = s.pdf(e.direction);
            assert!((pdf - e.pdf).abs() <= 1e-9 * pdf, "{pdf} vs {}", e.pdf);
            sum += map.radiance(e.direction.as_vec3()).as_dvec3() / e.pdf;
        }
        let estimate = sum / n as f64;
        let exact = map.integral();
        assert!(
            (estimate - exact).abs().max_element() < 0.01 * exact.max_element(),
            "{estimate} vs {exact}"
        );
        let mass: f64 = map.iter().map(|p| s.pdf(p.direction) * p.solid_angle).sum();
        assert!((mass - 1.0).abs() < 1e-9, "{mass}");
    }

    #[test]
    fn a_constant_map_is_sampled_uniformly_and_a_black_one_not_at_all() {
        let s = EnvSampler::new(&EnvMap::new(8, 4, vec![Vec3::ONE; 32]));
        let e = s.sample([0.3, 0.9]).unwrap();
        assert!((e.pdf - 1.0 / (4.0 * PI)).abs() < 1e-12);
        let black = EnvSampler::new(&EnvMap::new(8, 4, vec![Vec3::ZERO; 32]));
        assert!(black.is_black() && black.sample([0.5, 0.5]).is_none());
        assert_eq!(black.pdf(DVec3::Y), 0.0);
    }
}
