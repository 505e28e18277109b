//! The inputs of one simulation, and their validation.

use cuticle_fiber::LatLongGrid;
use std::f64::consts::FRAC_PI_2;
use thiserror::Error;

/// The most paths one simulation traces (the fixed-point tallies' headroom, see `accumulate`).
pub const MAX_RAYS: u64 = 1_000_000_000;

/// One configuration of the rough fiber and the light (d'Eon et al. 2014 §2.1).
#[derive(Clone, Debug, PartialEq)]
pub struct SimParams {
    /// Incident inclination θ_i in radians, |θ_i| < π/2 (φ_i = 0).
    pub theta_i: f64,
    /// Scale tilt α in radians; positive tilts the outward normal toward +u (see [`crate::scale`]).
    pub alpha: f64,
    /// Beckmann roughness β > 0.
    pub beta: f64,
    /// Relative index of refraction η = η_fiber/η_outside > 1.
    pub eta: f64,
    /// Interior absorption coefficient per unit radius, RGB, ≥ 0.
    pub mu_a: [f64; 3],
    /// Number of paths traced, > 0.
    pub rays: u64,
    /// Seed of the random streams; a seed gives bit-identical results on any thread count.
    pub seed: u64,
    /// The lat-long grid of the lobe images.
    pub grid: LatLongGrid,
}

impl Default for SimParams {
    /// Human hair in air at moderate roughness, 10 million paths (the default).
    fn default() -> Self {
        Self {
            theta_i: 0.5,
            alpha: 0.0,
            beta: 0.04,
            eta: 1.55,
            mu_a: [0.0; 3],
            rays: 10_000_000,
            seed: 1,
            grid: LatLongGrid::default(),
        }
    }
}

/// Why a simulation or a sweep could not run.
#[derive(Debug, Error)]
pub enum SimError {
    #[error("invalid parameter: {0}")]
    InvalidParam(String),
}

fn check(ok: bool, what: impl FnOnce() -> String) -> Result<(), SimError> {
    if ok {
        Ok(())
    } else {
        Err(SimError::InvalidParam(what()))
    }
}

impl SimParams {
    /// Checks every parameter: finite numbers, β > 0, η > 1, μ_a ≥ 0, |θ_i| < π/2, |α| < π/4,
    /// 0 < rays ≤ [`MAX_RAYS`] and a non-empty grid.
    pub fn validate(&self) -> Result<(), SimError> {
        let t = self.theta_i;
        check(t.is_finite() && t.abs() < FRAC_PI_2, || {
            format!("theta_i must be finite with |theta_i| < pi/2 (got {t})")
        })?;
        let a = self.alpha;
        check(a.is_finite() && a.abs() < FRAC_PI_2 / 2.0, || {
            format!(
                "alpha must be finite with |alpha| < 45 degrees (got {} degrees)",
                a.to_degrees()
            )
        })?;
        let b = self.beta;
        check(b.is_finite() && b > 0.0, || {
            format!("beta must be finite and > 0 (got {b})")
        })?;
        let e = self.eta;
        check(e.is_finite() && e > 1.0, || {
            format!("eta must be finite and > 1 (got {e})")
        })?;
        let mu = self.mu_a;
        check(mu.iter().all(|m| m.is_finite() && *m >= 0.0), || {
            format!("mu_a must be finite and >= 0 (got {mu:?})")
        })?;
        check(self.rays > 0 && self.rays <= MAX_RAYS, || {
            format!("rays must be between 1 and {MAX_RAYS} (got {})", self.rays)
        })?;
        check(!self.grid.is_empty(), || {
            "the lat-long grid must not be empty".to_string()
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rejects_each_bad_parameter() {
        assert!(SimParams::default().validate().is_ok());
        let bad = [
            SimParams {
                beta: 0.0,
                ..Default::default()
            },
            SimParams {
                beta: f64::NAN,
                ..Default::default()
            },
            SimParams {
                eta: 1.0,
                ..Default::default()
            },
            SimParams {
                eta: f64::INFINITY,
                ..Default::default()
            },
            SimParams {
                theta_i: 1.6,
                ..Default::default()
            },
            SimParams {
                mu_a: [0.0, -1.0, 0.0],
                ..Default::default()
            },
            SimParams {
                rays: 0,
                ..Default::default()
            },
            SimParams {
                alpha: 1.0,
                ..Default::default()
            },
        ];
        for p in bad {
            assert!(p.validate().is_err(), "{p:?} should be rejected");
        }
    }
}
