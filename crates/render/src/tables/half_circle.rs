//! Integrals over a half circle, for the inner integrals of multiple scattering (Xu et al. 2011
//! eq. 28): 𝒩^G_t(δ, θ_d) = (1/π) ∫_{δ−π/2}^{δ+π/2} N_t(θ_d, φ) dφ. With N_R = Σ_k C_k |cos^k(φ/2)|
//! (eq. 13) and N_TT, N_TRT sums of weighted circular Gaussians (eqs. 16, 20), this needs only
//! - W_k(δ) = ∫_{δ−π/2}^{δ+π/2} |cos^k(φ/2)| dφ, k = 0…6, over δ ∈ [0, π] (129 nodes), and
//! - P(λ, δ) = ∫_{δ−π/2}^{δ+π/2} g^c(φ; 0, λ) dφ / ∫ g^c(φ; 0, λ) dφ, the share of a circular
//!   Gaussian inside the half circle centred δ away, over ln λ ∈ [ln 10⁻³, ln 20] (96) × δ (129),
//!
//! both even in δ and independent of every hair parameter, so built once with the other tables.

use crate::srbf::circular_gaussian as cg;
use crate::tables::grid::Grid2;
use std::f64::consts::PI;

const DELTA_NODES: usize = 129;
const LAMBDA_NODES: usize = 96;
const LAMBDA_MIN: f64 = 1e-3;
const LAMBDA_MAX: f64 = 20.0;
/// Midpoint samples over the half circle when building.
const SAMPLES: usize = 2048;

/// The half-circle tables.
#[derive(Clone, Debug)]
pub struct HalfCircle {
    cosines: Grid2<7>,
    share: Grid2<1>,
}

impl Default for HalfCircle {
    fn default() -> Self {
        Self::build()
    }
}

/// ∫ over [δ − π/2, δ + π/2] of f, by the midpoint rule.
fn half_integral(delta: f64, f: impl Fn(f64) -> f64) -> f64 {
    let d = PI / SAMPLES as f64;
    (0..SAMPLES)
        .map(|i| f(delta - 0.5 * PI + (i as f64 + 0.5) * d))
        .sum::<f64>()
        * d
}

impl HalfCircle {
    pub fn build() -> Self {
        let cosines = Grid2::build((DELTA_NODES, 0.0, PI), (2, 0.0, 1.0), |delta, _| {
            std::array::from_fn(|k| {
                half_integral(delta, |phi| (0.5 * phi).cos().abs().powi(k as i32))
            })
        });
        let share = Grid2::build(
            (LAMBDA_NODES, LAMBDA_MIN.ln(), LAMBDA_MAX.ln()),
            (DELTA_NODES, 0.0, PI),
            |ln_lambda, delta| {
                let lambda = ln_lambda.exp();
                let inside = half_integral(delta, |phi| cg::eval(phi, 0.0, lambda));
                [(inside / cg::integral(lambda)).clamp(0.0, 1.0)]
            },
        );
        Self { cosines, share }
    }

    /// The grids as stored: W_k over (|δ|, a constant axis) and P over (ln λ, |δ|).
    pub fn grids(&self) -> (&Grid2<7>, &Grid2<1>) {
        (&self.cosines, &self.share)
    }

    /// W_k(δ), k = 0…6.
    pub fn cosines(&self, delta: f64) -> [f64; 7] {
        self.cosines
            .lookup(crate::angles::wrap_pi(delta).abs(), 0.0)
    }

    /// P(λ, δ): the share of g^c(·; μ, λ) inside the half circle centred μ + δ.
    pub fn share(&self, lambda: f64, delta: f64) -> f64 {
        self.shares(lambda, [delta])[0]
    }

    /// [`Self::share`] of one λ at several δ, its logarithm and cell found once.
    pub fn shares<const N: usize>(&self, lambda: f64, deltas: [f64; N]) -> [f64; N] {
        let cell = self.share.cell_x(lambda.clamp(LAMBDA_MIN, LAMBDA_MAX).ln());
        deltas.map(|delta| {
            let d = self.share.cell_y(crate::angles::wrap_pi(delta).abs());
            self.share.lookup_cells(cell, d)[0]
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shares_and_cosines_match_their_integrals() {
        let t = HalfCircle::build();
        // A wide Gaussian is nearly uniform: half of it lies in any half circle.
        assert!((t.share(19.0, 1.0) - 0.5).abs() < 0.01);
        // A narrow one is all inside when centred, none when opposite.
        assert!(t.share(0.01, 0.0) > 0.999 && t.share(0.01, PI) < 1e-3);
        // W_0 = π; W_2(0) = ∫_{−π/2}^{π/2} cos²(φ/2) = π/2 + 1.
        assert!((t.cosines(0.7)[0] - PI).abs() < 1e-6);
        assert!((t.cosines(0.0)[2] - (0.5 * PI + 1.0)).abs() < 1e-4);
        // Off-node against a direct integral.
        let (lambda, delta) = (0.37, 1.234);
        let want = half_integral(delta, |phi| cg::eval(phi, 0.0, lambda)) / cg::integral(lambda);
        assert!((t.share(lambda, delta) - want).abs() < 5e-3);
    }
}
