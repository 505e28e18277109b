//! The inputs of one simulation, and their validation.

use cuticle_fiber::LatLongGrid;
use cuticle_fiber::ranges::{self, CountRange};
use thiserror::Error;

/// The most paths one simulation traces (the fixed-point tallies' headroom, see `accumulate`).
pub const MAX_RAYS: u64 = ranges::SAMPLES.max;

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

impl From<cuticle_fiber::RangeError> for SimError {
    fn from(e: cuticle_fiber::RangeError) -> Self {
        SimError::InvalidParam(e.to_string())
    }
}

/// The number of paths, within [`MAX_RAYS`].
pub const RAYS: CountRange = CountRange {
    name: "rays",
    min: 1,
    max: MAX_RAYS,
};

impl SimParams {
    /// Checks every parameter against the ranges every model shares
    /// ([`cuticle_fiber::ranges`]): θ_i, α, β, η and μ_a, 0 < rays ≤ [`MAX_RAYS`], and a
    /// non-empty grid.
    pub fn validate(&self) -> Result<(), SimError> {
        ranges::THETA_I.check(self.theta_i)?;
        ranges::ALPHA_DEG.check_radians(self.alpha)?;
        ranges::BETA.check(self.beta)?;
        ranges::ETA.check(self.eta)?;
        ranges::MU_A.check_all(&self.mu_a)?;
        RAYS.check(self.rays)?;
        if self.grid.is_empty() {
            return Err(SimError::InvalidParam(
                "the lat-long grid must not be empty".into(),
            ));
        }
        Ok(())
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
            SimParams {
                beta: 100.0,
                ..Default::default()
            },
            SimParams {
                eta: 1e300,
                ..Default::default()
            },
        ];
        for p in bad {
            assert!(p.validate().is_err(), "{p:?} should be rejected");
        }
    }
}
