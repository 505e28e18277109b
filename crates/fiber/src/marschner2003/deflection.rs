//! The cubic deflection Φ̂(p, γ) and its roots γ_i.

use super::MIN_SLOPE;
use crate::cubic::Cubic;
use crate::special::{asin_fast, cos_quadrant};
use std::f64::consts::{FRAC_PI_2, PI};

/// Φ̂(p, γ) = (6pc/π − 2)γ − (8pc/π³)γ³ + pπ with c = asin(1/η′) (Marschner 2003's cubic
/// approximation, Marschner et al. 2003 "Finding γ_i"):
/// the exact Φ = 2pγ_t − 2γ + pπ with γ_t replaced by the cubic through γ_t(0) = 0,
/// γ_t(±π/2) = ±c and dγ_t/dγ(±π/2) = 0.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CubicDeflection {
    p: u32,
    /// Coefficient of γ.
    a: f64,
    /// Coefficient of −γ³.
    b: f64,
}

/// Up to six roots γ_i: three per branch φ + 2πk, and Φ̂'s range spans less than 4π.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct GammaRoots {
    values: [f64; 6],
    len: usize,
}

impl GammaRoots {
    pub fn as_slice(&self) -> &[f64] {
        &self.values[..self.len]
    }
}

impl CubicDeflection {
    pub fn new(p: u32, eta_prime: f64) -> Self {
        Self::with_critical_angle(p, Self::critical_angle(eta_prime))
    }

    /// c = asin(1/η′), the one transcendental a deflection needs, shared by the lobes.
    pub fn critical_angle(eta_prime: f64) -> f64 {
        asin_fast((1.0 / eta_prime).clamp(-1.0, 1.0))
    }

    /// The deflection of lobe p given c = [`CubicDeflection::critical_angle`].
    pub fn with_critical_angle(p: u32, c: f64) -> Self {
        let pc = p as f64 * c;
        Self {
            p,
            a: 6.0 * pc / PI - 2.0,
            b: 8.0 * pc / PI.powi(3),
        }
    }

    /// Φ̂(p, γ), unwrapped.
    pub fn phi(&self, gamma: f64) -> f64 {
        (self.a - self.b * gamma * gamma) * gamma + self.p as f64 * PI
    }

    /// dΦ̂/dγ.
    pub fn slope(&self, gamma: f64) -> f64 {
        self.a - 3.0 * self.b * gamma * gamma
    }

    /// d²Φ̂/dγ².
    pub(super) fn curvature(&self, gamma: f64) -> f64 {
        -6.0 * self.b * gamma
    }

    /// The positive γ where dΦ̂/dγ = 0 (the caustic), if Φ̂ has a fold inside (−π/2, π/2).
    pub fn fold(&self) -> Option<f64> {
        let g = (self.a / (3.0 * self.b)).sqrt();
        (self.a > 0.0 && self.b > 0.0 && g < FRAC_PI_2).then_some(g)
    }

    /// The smallest and largest Φ̂ over [−π/2, π/2].
    pub(super) fn range(&self) -> (f64, f64) {
        let ends = [self.phi(-FRAC_PI_2), self.phi(FRAC_PI_2)];
        let folds = self.fold().map(|g| [self.phi(-g), self.phi(g)]);
        ends.into_iter()
            .chain(folds.into_iter().flatten())
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
                (lo.min(x), hi.max(x))
            })
    }

    /// Every γ ∈ [−π/2, π/2] with Φ̂(p, γ) = φ + 2πk for some integer k.
    pub fn roots(&self, phi: f64) -> GammaRoots {
        let (lo, hi) = self.range();
        let k_min = ((lo - phi) / (2.0 * PI)).ceil() as i64;
        let k_max = ((hi - phi) / (2.0 * PI)).floor() as i64;
        let mut out = GammaRoots::default();
        for k in k_min..=k_max {
            let target = phi + 2.0 * PI * k as f64;
            let cubic = Cubic([self.p as f64 * PI - target, self.a, 0.0, -self.b]);
            for &g in cubic.roots_in(-FRAC_PI_2, FRAC_PI_2).as_slice() {
                if out.len < out.values.len() {
                    out.values[out.len] = g;
                    out.len += 1;
                }
            }
        }
        out
    }

    /// 1/|2 dΦ̂/dh| = cos γ / (2 |dΦ̂/dγ|), the density in φ of the offsets near γ.
    pub(super) fn inverse_spread(&self, gamma: f64) -> f64 {
        cos_quadrant(gamma).max(0.0) / (2.0 * self.slope(gamma).abs().max(MIN_SLOPE))
    }
}
