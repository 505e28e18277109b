//! A lobe's shape in θ, column by column: the mean, standard deviation and skewness of θ_o over
//! each φ column, weighted by the light in each pixel (S times the pixel's solid angle, channel
//! mean). Where a model's lobe and the simulation's differ, these say how: a mean that sits
//! beside the simulated one, a width, or a skew the model's symmetric lobe cannot carry
//! (docs/departures/19-tt-sine-lobe.md). `cuticle validate --moments` writes them
//! for every bright column ([`crate::peak::bright_columns`]) of R, TT and TRT.
//!
//! A pixel spreads the light it holds over its height Δθ, which adds Δθ²/12 to the variance
//! of its centres (Sheppard's correction, taken out here) and nothing to the third moment.

use cuticle_fiber::LatLongImage;
use cuticle_fiber::lobe::channel_mean;

/// The moments of θ_o over one φ column.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ColumnMoments {
    /// ∫ S dω over the column (channel mean).
    pub energy: f64,
    /// Mean θ_o, radians.
    pub mean: f64,
    /// Standard deviation of θ_o, radians, without the pixels' own height.
    pub std_dev: f64,
    /// Third central moment over the cube of the standard deviation.
    pub skewness: f64,
}

/// The moments of column `j`; `None` where the column holds no light, or where the lobe is
/// narrower than the pixels can tell (the corrected variance not positive).
pub fn column_moments(img: &LatLongImage, j: usize) -> Option<ColumnMoments> {
    let g = img.grid;
    let weight = |k: usize| channel_mean(img.at(j, k)) * g.pixel_solid_angle(k);
    let energy: f64 = (0..g.height).map(weight).sum();
    if !energy.is_finite() || energy <= 0.0 {
        return None;
    }
    let mean = (0..g.height)
        .map(|k| weight(k) * g.theta_center(k))
        .sum::<f64>()
        / energy;
    let central = |n: i32| {
        (0..g.height)
            .map(|k| weight(k) * (g.theta_center(k) - mean).powi(n))
            .sum::<f64>()
            / energy
    };
    let row_height = g.theta_top(0) - g.theta_top(1);
    let variance = central(2) - row_height * row_height / 12.0;
    if variance.is_nan() || variance <= 0.0 {
        return None;
    }
    Some(ColumnMoments {
        energy,
        mean,
        std_dev: variance.sqrt(),
        skewness: central(3) / variance.powf(1.5),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use cuticle_fiber::LatLongGrid;
    use glam::DVec3;
    use std::f64::consts::{PI, SQRT_2};

    /// A column holding, in each pixel, the mass of a split normal (two half-Gaussians of
    /// deviations s1 below and s2 above `mode`), divided by the pixel's solid angle.
    fn split_normal_column(mode: f64, s1: f64, s2: f64) -> LatLongImage {
        let g = LatLongGrid::new(4, 400);
        let cdf = |x: f64| {
            let phi = |z: f64| 0.5 * cuticle_fiber::math::erfc(-z / SQRT_2);
            let t = s1 + s2;
            if x < mode {
                2.0 * s1 / t * phi((x - mode) / s1)
            } else {
                s1 / t + 2.0 * s2 / t * (phi((x - mode) / s2) - 0.5)
            }
        };
        let mut img = LatLongImage::zeros(g);
        let dth = PI / g.height as f64;
        for k in 0..g.height {
            let top = g.theta_top(k);
            let mass = cdf(top) - cdf(top - dth);
            img.pixels[k * g.width + 1] = DVec3::splat(mass / g.pixel_solid_angle(k));
        }
        img
    }

    #[test]
    fn moments_of_a_gaussian_column() {
        // Two pixels wide (σ = 2Δθ): Sheppard's correction matters at this width.
        let sigma = 2.0 * PI / 400.0;
        let m = column_moments(&split_normal_column(-0.6, sigma, sigma), 1).unwrap();
        assert!((m.energy - 1.0).abs() < 1e-9, "{m:?}");
        assert!((m.mean + 0.6).abs() < 1e-6, "{m:?}");
        assert!((m.std_dev / sigma - 1.0).abs() < 2e-3, "{m:?}");
        assert!(m.skewness.abs() < 1e-3, "{m:?}");
        assert_eq!(
            column_moments(&split_normal_column(-0.6, sigma, sigma), 0),
            None
        );
    }

    #[test]
    fn moments_of_a_skewed_column() {
        // A split normal's mean, variance and skewness in closed form.
        let (mode, s1, s2) = (0.3, 0.08, 0.04);
        let k = (2.0 / PI).sqrt();
        let d = s2 - s1;
        let mean = mode + k * d;
        let variance = (1.0 - 2.0 / PI) * d * d + s1 * s2;
        let skewness = k * d * ((4.0 / PI - 1.0) * d * d + s1 * s2) / variance.powf(1.5);
        let m = column_moments(&split_normal_column(mode, s1, s2), 1).unwrap();
        assert!((m.mean - mean).abs() < 1e-5, "{m:?} vs {mean}");
        assert!((m.std_dev / variance.sqrt() - 1.0).abs() < 1e-3, "{m:?}");
        assert!((m.skewness - skewness).abs() < 0.01, "{m:?} vs {skewness}");
        assert!(skewness < -0.2);
    }
}
