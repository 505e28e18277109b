//! The longitudinal lobes M_p: unit-integral Gaussians in θ_h.

use crate::special::{exp_fast, normal_pdf_fast, normal_quantile_fast};
use std::f64::consts::{FRAC_PI_2, PI};

/// M_p: a unit-integral Gaussian in θ_h (Marschner 2003's practical model, Table 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct GaussianLobe {
    pub(super) alpha: f64,
    pub(super) beta: f64,
}

impl GaussianLobe {
    /// M_p(θ_h).
    pub(super) fn eval(&self, theta_h: f64) -> f64 {
        normal_pdf_fast((theta_h - self.alpha) / self.beta) / self.beta
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
