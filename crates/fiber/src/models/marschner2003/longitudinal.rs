//! The longitudinal lobes M_p: unit-integral Gaussians in θ_h.

use crate::math::{exp_fast, exp_lanes, normal_quantile_fast};
use std::f64::consts::{FRAC_PI_2, PI};
use wide::f64x4;

/// M_p: a unit-integral Gaussian in θ_h (Marschner 2003's practical model, Table 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct GaussianLobe {
    pub(super) alpha: f64,
    pub(super) beta: f64,
}

impl GaussianLobe {
    /// M_p(θ_h): the reference [`GaussianLanes::eval`] is measured against.
    #[cfg(test)]
    pub(super) fn eval(&self, theta_h: f64) -> f64 {
        crate::math::normal_pdf_fast((theta_h - self.alpha) / self.beta) / self.beta
    }

    /// θ_o = 2θ_h − θ_i with θ_h from M_p by inversion, or `None` beyond ±π/2.
    pub(super) fn sample(&self, theta_i: f64, u: f64) -> Option<f64> {
        let theta_h = self.alpha + self.beta * normal_quantile_fast(u);
        let theta_o = 2.0 * theta_h - theta_i;
        (theta_o.abs() <= FRAC_PI_2).then_some(theta_o)
    }

    /// Roughly the share of M_p that lands inside θ_o ∈ [−π/2, π/2] (a logistic stand-in for
    /// the normal distribution function, within 2e-4): it only steers lobe choice. The
    /// logistic ½(1 + tanh z) is written 1 / (1 + e^{−2z}), through [`exp_fast`].
    pub(super) fn approximate_mass(&self, theta_i: f64) -> f64 {
        let cdf = |theta_h: f64| {
            let x = (theta_h - self.alpha) / self.beta;
            let z = (2.0 / PI).sqrt() * (x + 0.044715 * x * x * x);
            1.0 / (1.0 + exp_fast(-2.0 * z))
        };
        (cdf(0.5 * (theta_i + FRAC_PI_2)) - cdf(0.5 * (theta_i - FRAC_PI_2))).max(0.0)
    }
}

/// The three M_p at one θ_h in SIMD lanes, for evaluation: one [`exp_lanes`] for the three
/// Gaussians where [`GaussianLobe::eval`] takes three exponentials (within 7.4e-9 relative of
/// them, the bound of `exp_lanes`; `lanes_match_the_lobes`). The fourth lane is empty.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct GaussianLanes {
    alpha: f64x4,
    inv_beta: f64x4,
    /// 1 / (√(2π) β), 0 in the empty lane.
    norm: f64x4,
}

impl GaussianLanes {
    pub(super) fn new(lobes: &[GaussianLobe; 3]) -> Self {
        let lane = |f: &dyn Fn(&GaussianLobe) -> f64| {
            f64x4::from([f(&lobes[0]), f(&lobes[1]), f(&lobes[2]), 0.0])
        };
        Self {
            alpha: lane(&|l| l.alpha),
            inv_beta: lane(&|l| 1.0 / l.beta),
            norm: lane(&|l| 1.0 / ((2.0 * PI).sqrt() * l.beta)),
        }
    }

    /// [M_R, M_TT, M_TRT] at θ_h.
    #[inline]
    pub(super) fn eval(&self, theta_h: f64) -> [f64; 3] {
        let x = (f64x4::splat(theta_h) - self.alpha) * self.inv_beta;
        let [r, tt, trt, _] = (exp_lanes(x * x * f64x4::splat(-0.5)) * self.norm).to_array();
        [r, tt, trt]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The lanes against the scalar lobes over θ_h ∈ [−π/2, π/2], for narrow and wide lobes:
    /// within exp_lanes' 7.4e-9 relative (plus rounding) wherever M is above 1e-300.
    #[test]
    fn lanes_match_the_lobes() {
        for (alpha, beta) in [(-0.09, 0.09), (0.05, 0.02), (0.12, 0.35)] {
            let lobes = [
                GaussianLobe { alpha, beta },
                GaussianLobe {
                    alpha: -0.5 * alpha,
                    beta: 0.5 * beta,
                },
                GaussianLobe {
                    alpha: -1.5 * alpha,
                    beta: 2.0 * beta,
                },
            ];
            let lanes = GaussianLanes::new(&lobes);
            let mut worst: f64 = 0.0;
            for k in 0..=4000 {
                let theta_h = -FRAC_PI_2 + PI * k as f64 / 4000.0;
                for (lane, lobe) in lanes.eval(theta_h).iter().zip(&lobes) {
                    let want = lobe.eval(theta_h);
                    if want > 1e-300 {
                        worst = worst.max((lane / want - 1.0).abs());
                    } else {
                        assert!(*lane < 1e-290, "θ_h {theta_h}: {lane} against {want}");
                    }
                }
            }
            assert!(worst < 1e-8, "α {alpha} β {beta}: {worst:e}");
        }
    }
}
