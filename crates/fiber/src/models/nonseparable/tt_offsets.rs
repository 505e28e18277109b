//! TT's offset h(φ), the root of Φ(1, h) = φ that places TT's cone and width (d'Eon et al.
//! 2014 §2.4), tabulated once per model and polished by Newton's method: the fast twin of
//! [`tt_offset`], which solves from a linear first guess at every call.
//!
//! 1. The table holds γ = asin h over the ratio η/η′ ∈ [0, 1] (η′ ≥ η grows with the
//!    inclination; 0 is η′ = ∞) and |φ| ∈ [0, π]: Φ(1, −γ) = 2π − Φ(1, γ), so h(−φ) = −h(φ).
//!    Where φ lies inside TT's gap, |φ| ≤ 2 asin(1/η′), the offset is clamped to the edge, as
//!    [`tt_offset`] clamps it.
//! 2. A lookup interpolates γ bilinearly and takes two Newton steps on Φ(1, γ) − |φ|, which
//!    square its error twice; a step past the edge is clamped there.
//!
//! Within 1e-12 of [`tt_offset`] over θ_i and φ (`matches_the_solve`).

use crate::geometry::frame::wrap_pi;
use crate::math::{asin_fast, sin_cos_quadrant};
use crate::models::nonseparable::cones::tt_offset;
use std::f64::consts::{FRAC_PI_2, PI};

/// Nodes along η/η′.
const RATIO_NODES: usize = 64;
/// Nodes along |φ| ∈ [0, π].
const PHI_NODES: usize = 257;
/// Newton steps after the interpolated guess.
const POLISH_STEPS: usize = 2;

/// γ = asin h of TT's offset on the (η/η′, |φ|) grid of one η.
#[derive(Clone, Debug)]
pub struct TtOffsets {
    eta: f64,
    /// [ratio][φ] → γ.
    gamma: Vec<f64>,
}

impl TtOffsets {
    /// The table for index η, each node solved by [`tt_offset`].
    pub fn build(eta: f64) -> Self {
        let mut gamma = Vec::with_capacity(RATIO_NODES * PHI_NODES);
        for i in 0..RATIO_NODES {
            let ratio = i as f64 / (RATIO_NODES - 1) as f64;
            let eta_prime = if ratio > 0.0 {
                eta / ratio
            } else {
                f64::INFINITY
            };
            for j in 0..PHI_NODES {
                let phi = PI * j as f64 / (PHI_NODES - 1) as f64;
                gamma.push(tt_offset(phi, eta_prime).clamp(-1.0, 1.0).asin());
            }
        }
        Self { eta, gamma }
    }

    /// The offset h whose TT path leaves at azimuth φ for the Bravais index η′ (≥ η, the
    /// table's own), as [`tt_offset`] gives it.
    pub fn offset(&self, phi: f64, eta_prime: f64) -> f64 {
        let target = wrap_pi(phi);
        let a = target.abs();
        let ratio = (self.eta / eta_prime).clamp(0.0, 1.0);
        let mut gamma = self.interpolate(ratio, a);
        let inv_eta_prime = ratio / self.eta;
        for _ in 0..POLISH_STEPS {
            // Φ(1, γ) − |φ| and dΦ/dγ = 2 cos γ / (η′ cos γ_t) − 2, as in [`tt_offset`].
            let (sg, cg) = sin_cos_quadrant(gamma);
            let st = sg * inv_eta_prime;
            let ct = (1.0 - st * st).max(1e-300).sqrt();
            let miss = 2.0 * asin_fast(st) - 2.0 * gamma + PI - a;
            let slope = 2.0 * cg * inv_eta_prime / ct - 2.0;
            gamma = (gamma - miss / slope).clamp(-FRAC_PI_2, FRAC_PI_2);
        }
        let h = sin_cos_quadrant(gamma).0;
        if target < 0.0 { -h } else { h }
    }

    /// γ at (η/η′, |φ|) by bilinear interpolation.
    fn interpolate(&self, ratio: f64, a: f64) -> f64 {
        let (i, fi) = cell(ratio, RATIO_NODES);
        let (j, fj) = cell(a / PI, PHI_NODES);
        let row = |i: usize| {
            let g = &self.gamma[i * PHI_NODES + j..i * PHI_NODES + j + 2];
            g[0] + fj * (g[1] - g[0])
        };
        let (lo, hi) = (row(i), row(i + 1));
        lo + fi * (hi - lo)
    }
}

/// The lower node and the fraction toward the next of t ∈ [0, 1] on n nodes.
fn cell(t: f64, n: usize) -> (usize, f64) {
    let x = t.clamp(0.0, 1.0) * (n - 1) as f64;
    let i = (x as usize).min(n - 2);
    (i, x - i as f64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::bravais::eta_prime;

    /// Over inclinations to grazing and every azimuth (TT's gap, its edge and the back
    /// included), for the indices of hair and beyond.
    #[test]
    fn matches_the_solve() {
        let mut worst: f64 = 0.0;
        for &eta in &[1.33, 1.55, 1.9] {
            let table = TtOffsets::build(eta);
            for k in 0..=300 {
                let theta = -1.55 + 3.1 * k as f64 / 300.0;
                let eta_p = eta_prime(eta, theta);
                for m in 0..=997 {
                    let phi = -PI + 2.0 * PI * m as f64 / 997.0;
                    let (fast, exact) = (table.offset(phi, eta_p), tt_offset(phi, eta_p));
                    worst = worst.max((fast - exact).abs());
                }
            }
        }
        eprintln!("TtOffsets within {worst:.1e} of tt_offset");
        assert!(worst < 1e-12, "{worst}");
    }
}
