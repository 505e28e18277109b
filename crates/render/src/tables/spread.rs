//! The normalisation of a light spread in inclination: dual scattering distributes a light's
//! energy over incident directions as g^u(θ; θ_j, σ) s(φ) / Z (Zinke et al. 2008's spread
//! function ψ_f, Xu et al. 2011 eq. 5), with Z making ∫ g^u s dω / Z = 1 (dω = cos θ dθ dφ, ∫ s dφ
//! = 1). Zinke and Xu et al. 2011 write Z = cos θ_j, its narrow limit; for a wide spread near the
//! fiber's axis (a sky straight above hanging hair) cos θ_j → 0 while the spread still reaches
//! inclinations with cos θ > 0, and the narrow limit overstates the light (tests/multiple.rs
//! measures both against the brute force; the figures are in BENCHMARKS.md). This table holds
//! the exact Z(θ_j, σ) = ∫_{−π/2}^{π/2} N(θ; θ_j, σ) cos θ dθ over the
//! same interval the shading integrals cover; Z(θ_j, 0) = cos θ_j.

use crate::tables::grid::Grid2;
use cuticle_fiber::math::GaussLegendre;
use std::f64::consts::{FRAC_PI_2, PI};

/// Largest deviation σ tabulated; wider spreads read the edge.
const MU_A_MAX: f64 = 4.0;
/// Nodes along each axis.
const NODES: usize = 129;
/// Smallest Z returned (the narrow limit's old floor on cos θ_j).
pub const MIN_Z: f64 = 1e-4;

/// Z(|θ_j|, σ) on a grid (Z is even in θ_j).
#[derive(Clone, Debug)]
pub struct SpreadNormalisation {
    grid: Grid2<1>,
}

impl Default for SpreadNormalisation {
    fn default() -> Self {
        Self::build()
    }
}

impl SpreadNormalisation {
    pub fn build() -> Self {
        Self {
            grid: Grid2::build(
                (NODES, 0.0, FRAC_PI_2),
                (NODES, 0.0, MU_A_MAX),
                |mu, sigma| [exact(mu, sigma)],
            ),
        }
    }

    /// The grid as stored: Z over (|θ_j|, σ), before the floor [`MIN_Z`].
    pub fn grid(&self) -> &Grid2<1> {
        &self.grid
    }

    /// Z(θ_j, σ), at least 1e-4; σ beyond 4 reads σ = 4, where the spread is nearly flat
    /// over the interval.
    pub fn at(&self, theta_j: f64, sigma: f64) -> f64 {
        self.grid.lookup(theta_j.abs(), sigma)[0].max(MIN_Z)
    }
}

/// ∫_{−π/2}^{π/2} N(θ; μ, σ) cos θ dθ by 16 Gauss–Legendre panels of 16 points.
fn exact(mu: f64, sigma: f64) -> f64 {
    if sigma <= 0.0 {
        return mu.cos();
    }
    let rule = GaussLegendre::cached(16);
    let panels = 16;
    let width = PI / panels as f64;
    (0..panels)
        .map(|k| {
            let a = -FRAC_PI_2 + k as f64 * width;
            rule.integrate(a, a + width, |x| {
                let z = (x - mu) / sigma;
                (-0.5 * z * z).exp() / (sigma * (2.0 * PI).sqrt()) * x.cos()
            })
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Narrow spreads give cos θ_j·e^{−σ²/2} (the untruncated closed form, exact while the
    /// spread stays inside ±π/2); at the axis Z stays positive where cos θ_j vanishes; the
    /// table interpolates the integral between nodes within 2e-4 (h²/8 of the σ spacing is
    /// 1.2e-4).
    #[test]
    fn normalisation_has_its_limits_and_interpolates() {
        let z = SpreadNormalisation::build();
        for &(mu, sigma) in &[(0.0f64, 0.05f64), (0.7, 0.1), (-1.0, 0.08)] {
            let want = f64::cos(mu) * (-0.5 * sigma * sigma).exp();
            assert!((z.at(mu, sigma) - want).abs() < 2e-4, "{mu} {sigma}");
        }
        assert!(z.at(FRAC_PI_2, 0.0) <= MIN_Z);
        let pole = z.at(FRAC_PI_2, 0.5);
        assert!(pole > 0.1, "{pole}");
        for i in 0..50 {
            let (mu, sigma) = (-1.5 + 0.0613 * i as f64, 0.013 + 0.0791 * i as f64);
            let want = exact(mu.abs(), sigma).max(MIN_Z);
            assert!((z.at(mu, sigma) - want).abs() < 2e-4, "{mu} {sigma}");
        }
    }
}
