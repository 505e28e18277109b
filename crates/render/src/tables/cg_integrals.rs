//! The precomputed tables of Xu et al. 2011 §5, built once and independent of every hair parameter:
//! - 𝒞_k(λ′, δ) = ∫ |cos^k((δ − φ′)/2)| g^c(φ′; 0, λ′) dφ′, k = 0…6 (eq. 14), stored divided by
//!   Z(λ′) = ∫ g^c(φ′; 0, λ′) dφ′ (so each entry is a weighted mean of |cos^k|, smooth in ln λ′),
//!   with ln Z beside it; λ′ ∈ [0.001, 10] logarithmically (128 nodes) × δ ∈ [0, π] (65 nodes,
//!   the paper's 64 over the half circle doubled by the symmetry 𝒞_k(λ′, −δ) = 𝒞_k(λ′, δ));
//! - ℋ_k^TT(η, θ_d) = ∫_{−1}^{1} (1 − F)² h^k dh and ℋ_k^TRT(η, θ_d) = ∫_{−1}^{1} (1 − F)² F h^k
//!   dh, k = 0, 2, 4 (eqs. 19, 23), η ∈ [1, 10] logarithmically (128 nodes) × θ_d ∈ [0, 1.5] (64);
//! - N_R's Fresnel factor as a quintic in cos γ ([`r_fresnel`]; Xu et al. 2011 eq. 13 has
//!   Schlick's), over the same (η, θ_d) grid.

use crate::fresnel::oblique;
use crate::srbf::circular_gaussian as cg;
use crate::tables::grid::{Cell, Grid2};
use crate::tables::r_fresnel::{self, TERMS};
use cuticle_fiber::math::GaussLegendre;
use std::f64::consts::PI;

/// Range of λ′ the 𝒞_k table covers (Xu et al. 2011 §5).
pub const LAMBDA_RANGE: (f64, f64) = (0.001, 10.0);
/// Range of η the ℋ tables cover (Xu et al. 2011 §5).
pub const ETA_RANGE: (f64, f64) = (1.0, 10.0);
/// Largest θ_d the ℋ tables hold; beyond, the edge value is used (cos θ_d < 0.071).
pub const THETA_D_MAX: f64 = 1.5;

/// All tables of §5.
#[derive(Clone, Debug)]
pub struct Tables {
    /// [ĉ_0 … ĉ_6, ln Z] over (ln λ′, δ).
    cosine: Grid2<8>,
    /// [ℋ_0, ℋ_2, ℋ_4] of TT over (ln η, θ_d).
    h_tt: Grid2<3>,
    /// [ℋ_0, ℋ_2, ℋ_4] of TRT over (ln η, θ_d).
    h_trt: Grid2<3>,
    /// [a₀ … a₅] of N_R's Fresnel quintic over (ln η, θ_d).
    r_fresnel: Grid2<TERMS>,
}

impl Tables {
    /// Builds every table (a fraction of a second on two cores).
    pub fn build() -> Self {
        let (l0, l1) = (LAMBDA_RANGE.0.ln(), LAMBDA_RANGE.1.ln());
        let cosine = Grid2::build((128, l0, l1), (65, 0.0, PI), |ln_l, delta| {
            cosine_entry(ln_l.exp(), delta)
        });
        let (e0, e1) = (ETA_RANGE.0.ln(), ETA_RANGE.1.ln());
        let h_tt = Grid2::build((128, e0, e1), (64, 0.0, THETA_D_MAX), |ln_eta, td| {
            fresnel_moments(ln_eta.exp(), td, |f| (1.0 - f) * (1.0 - f))
        });
        let h_trt = Grid2::build((128, e0, e1), (64, 0.0, THETA_D_MAX), |ln_eta, td| {
            fresnel_moments(ln_eta.exp(), td, |f| (1.0 - f) * (1.0 - f) * f)
        });
        let r_fresnel = Grid2::build((128, e0, e1), (64, 0.0, THETA_D_MAX), |ln_eta, td| {
            r_fresnel::coefficients(ln_eta.exp(), td)
        });
        Self {
            cosine,
            h_tt,
            h_trt,
            r_fresnel,
        }
    }

    /// 𝒞_k(λ′, δ) for k = 0…6 (Xu et al. 2011 eq. 14), λ′ clamped to [`LAMBDA_RANGE`].
    pub fn cosine(&self, lambda: f64, delta: f64) -> [f64; 7] {
        let v = self.cosine_normalised(lambda, delta);
        let z = v[7].exp();
        std::array::from_fn(|k| v[k] * z)
    }

    /// [𝒞_0/Z … 𝒞_6/Z, ln Z] at (λ′, δ).
    pub fn cosine_normalised(&self, lambda: f64, delta: f64) -> [f64; 8] {
        let l = lambda.clamp(LAMBDA_RANGE.0, LAMBDA_RANGE.1).ln();
        let d = crate::angles::wrap_pi(delta).abs();
        self.cosine.lookup(l, d)
    }

    /// [ℋ_0, ℋ_2, ℋ_4] of TT at (η, θ_d) (Xu et al. 2011 eq. 19).
    pub fn h_tt(&self, eta: f64, theta_d: f64) -> [f64; 3] {
        self.h_tt
            .lookup(eta.clamp(ETA_RANGE.0, ETA_RANGE.1).ln(), theta_d.abs())
    }

    /// [ℋ_0, ℋ_2, ℋ_4] of TRT at (η, θ_d) (Xu et al. 2011 eq. 23).
    pub fn h_trt(&self, eta: f64, theta_d: f64) -> [f64; 3] {
        self.h_trt
            .lookup(eta.clamp(ETA_RANGE.0, ETA_RANGE.1).ln(), theta_d.abs())
    }

    /// [a₀ … a₅] of N_R's Fresnel factor F ≈ Σ a_n cosⁿγ at (η, θ_d) ([`r_fresnel`]).
    pub fn r_fresnel(&self, eta: f64, theta_d: f64) -> [f64; TERMS] {
        self.r_fresnel_in(self.fresnel_row(eta), theta_d)
    }

    /// Where η lies in the Fresnel table, for [`Self::r_fresnel_in`]: found once for the
    /// quadrature samples of a window, which share η.
    pub fn fresnel_row(&self, eta: f64) -> FresnelRow {
        FresnelRow(
            self.r_fresnel
                .cell_x(eta.clamp(ETA_RANGE.0, ETA_RANGE.1).ln()),
        )
    }

    /// [`Self::r_fresnel`] at η's row: the same values.
    pub fn r_fresnel_in(&self, row: FresnelRow, theta_d: f64) -> [f64; TERMS] {
        self.r_fresnel
            .lookup_cells(row.0, self.r_fresnel.cell_y(theta_d.abs()))
    }

    /// The grids as stored, for a back end that uploads them.
    pub fn grids(&self) -> StoredGrids<'_> {
        StoredGrids {
            cosine: &self.cosine,
            h_tt: &self.h_tt,
            h_trt: &self.h_trt,
            r_fresnel: &self.r_fresnel,
        }
    }

    /// Number of table entries (for reports).
    pub fn entries(&self) -> usize {
        self.cosine.len() + self.h_tt.len() + self.h_trt.len() + self.r_fresnel.len()
    }
}

/// An index of refraction's place in the Fresnel table ([`Tables::fresnel_row`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FresnelRow(Cell);

/// [`Tables`]' grids as stored.
pub struct StoredGrids<'a> {
    /// [𝒞_0/Z … 𝒞_6/Z, ln Z] over (ln λ′, δ).
    pub cosine: &'a Grid2<8>,
    /// ℋ^TT over (ln η, θ_d).
    pub h_tt: &'a Grid2<3>,
    /// ℋ^TRT over (ln η, θ_d).
    pub h_trt: &'a Grid2<3>,
    /// N_R's Fresnel quintic over (ln η, θ_d).
    pub r_fresnel: &'a Grid2<TERMS>,
}

/// [𝒞_0/Z … 𝒞_6/Z, ln Z] by composite Gauss–Legendre over the Gaussian's support, split at the
/// kink of |cos((δ − φ′)/2)| at φ′ = δ − π.
pub fn cosine_entry(lambda: f64, delta: f64) -> [f64; 8] {
    let reach = (12.0 * lambda).min(PI);
    let kink = delta - PI;
    let mut cuts = vec![-reach, reach];
    if kink > -reach && kink < reach {
        cuts.push(kink);
    }
    cuts.sort_by(f64::total_cmp);
    let rule = GaussLegendre::cached(16);
    let mut sums = [0.0; 7];
    for w in cuts.windows(2) {
        let panels = 16;
        let step = (w[1] - w[0]) / panels as f64;
        for p in 0..panels {
            let a = w[0] + p as f64 * step;
            for (k, sum) in sums.iter_mut().enumerate() {
                *sum += rule.integrate(a, a + step, |x| {
                    ((delta - x) * 0.5).cos().abs().powi(k as i32) * cg::eval(x, 0.0, lambda)
                });
            }
        }
    }
    let z = sums[0];
    let mut out = [0.0; 8];
    for k in 0..7 {
        out[k] = sums[k] / z;
    }
    out[7] = z.ln();
    out
}

/// [∫ w(F) h^k dh] for k = 0, 2, 4 over h ∈ [−1, 1] (F is even in h).
pub fn fresnel_moments(eta: f64, theta_d: f64, w: impl Fn(f64) -> f64) -> [f64; 3] {
    let rule = GaussLegendre::cached(32);
    let mut out = [0.0; 3];
    for (a, b) in [(0.0, 0.8), (0.8, 0.97), (0.97, 1.0)] {
        for (i, k) in [0, 2, 4].into_iter().enumerate() {
            out[i] += 2.0 * rule.integrate(a, b, |h| w(oblique(eta, theta_d, h)) * h.powi(k));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::OnceLock;

    fn tables() -> &'static Tables {
        static T: OnceLock<Tables> = OnceLock::new();
        T.get_or_init(Tables::build)
    }

    /// Brute Riemann sum of 𝒞_k with 200,000 points over the circle.
    fn direct(k: i32, lambda: f64, delta: f64) -> f64 {
        let n = 200_000;
        let dx = 2.0 * PI / n as f64;
        (0..n)
            .map(|i| {
                let x = -PI + (i as f64 + 0.5) * dx;
                ((delta - x) * 0.5).cos().abs().powi(k) * cg::eval(x, 0.0, lambda) * dx
            })
            .sum()
    }

    /// 𝒞_k lookups (between nodes) against direct integration: within 1 % of 𝒞_0 (relative to
    /// the lobe's total weight Z, which is what multiplies the polynomial's coefficients).
    #[test]
    fn cosine_lookup_matches_direct_integration() {
        let t = tables();
        for &lambda in &[0.0173, 0.123, 0.77, 3.1] {
            for &delta in &[0.0, 0.9, 2.2, 3.0, -1.3] {
                let c = t.cosine(lambda, delta);
                let z = direct(0, lambda, delta);
                for k in 0..7 {
                    let d = direct(k, lambda, delta);
                    assert!(
                        (c[k as usize] - d).abs() < 0.01 * z,
                        "k={k} λ={lambda} δ={delta}: {} vs {d}",
                        c[k as usize]
                    );
                }
            }
        }
    }

    /// ℋ tables between nodes against fresh integration, to 0.5 %; ℋ_0^TT ≤ 2 and TRT ≤ TT.
    #[test]
    fn fresnel_tables_match_integration() {
        let t = tables();
        for &(eta, td) in &[(1.55, 0.3), (1.33, 1.1), (2.7, 0.05)] {
            let tt = fresnel_moments(eta, td, |f| (1.0 - f) * (1.0 - f));
            let trt = fresnel_moments(eta, td, |f| (1.0 - f) * (1.0 - f) * f);
            let (lt, lr) = (t.h_tt(eta, td), t.h_trt(eta, td));
            for k in 0..3 {
                assert!((lt[k] / tt[k] - 1.0).abs() < 5e-3, "TT {eta} {td} {k}");
                assert!((lr[k] / trt[k] - 1.0).abs() < 5e-3, "TRT {eta} {td} {k}");
                assert!(lr[k] < lt[k]);
            }
            assert!(lt[0] <= 2.0);
        }
    }
}
