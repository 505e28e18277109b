//! The physical parameters every model shares, and their validation.

use glam::DVec3;
use serde::Serialize;
use thiserror::Error;

/// A fiber: relative index η, surface roughness β (Beckmann, as the simulator uses it), scale
/// tilt α (radians) and interior absorption μ_a per unit radius (RGB).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct FiberParams {
    pub eta: f64,
    pub beta: f64,
    pub alpha: f64,
    pub mu_a: DVec3,
}

impl Default for FiberParams {
    /// Human hair in air: η = 1.55, β = 0.04, α = −2°, a light brown μ_a.
    fn default() -> Self {
        Self {
            eta: 1.55,
            beta: 0.04,
            alpha: (-2.0f64).to_radians(),
            mu_a: DVec3::new(0.12, 0.25, 0.5),
        }
    }
}

/// Why a parameter set cannot describe a fiber.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum ParamError {
    #[error("{name} must be a finite number, got {value}")]
    NotFinite { name: &'static str, value: f64 },
    #[error("eta must be greater than 1 (a fiber denser than its surroundings), got {0}")]
    EtaTooSmall(f64),
    #[error("beta (roughness) must be positive and at most {max}, got {value}")]
    BetaOutOfRange { value: f64, max: f64 },
    #[error("alpha (scale tilt) must lie within ±{max_deg} degrees, got {value_deg} degrees")]
    AlphaOutOfRange { value_deg: f64, max_deg: f64 },
    #[error("mu_a (absorption) must be non-negative and at most {max}, got {value}")]
    AbsorptionOutOfRange { value: f64, max: f64 },
}

/// Largest roughness the models are meant for (and tested to).
pub const MAX_BETA: f64 = 1.0;
/// Largest scale tilt, in degrees.
pub const MAX_ALPHA_DEG: f64 = 20.0;
/// Largest absorption per unit radius (beyond it every internal lobe is black to f64).
pub const MAX_MU_A: f64 = 1000.0;

impl FiberParams {
    /// Checks every field, returning the first fault in a sentence a user understands.
    pub fn validate(&self) -> Result<(), ParamError> {
        let finite = |name, value: f64| {
            if value.is_finite() {
                Ok(())
            } else {
                Err(ParamError::NotFinite { name, value })
            }
        };
        finite("eta", self.eta)?;
        finite("beta", self.beta)?;
        finite("alpha", self.alpha)?;
        for c in self.mu_a.to_array() {
            finite("mu_a", c)?;
        }
        if self.eta <= 1.0 {
            return Err(ParamError::EtaTooSmall(self.eta));
        }
        if !(self.beta > 0.0 && self.beta <= MAX_BETA) {
            return Err(ParamError::BetaOutOfRange {
                value: self.beta,
                max: MAX_BETA,
            });
        }
        if self.alpha.to_degrees().abs() > MAX_ALPHA_DEG {
            return Err(ParamError::AlphaOutOfRange {
                value_deg: self.alpha.to_degrees(),
                max_deg: MAX_ALPHA_DEG,
            });
        }
        for c in self.mu_a.to_array() {
            if !(0.0..=MAX_MU_A).contains(&c) {
                return Err(ParamError::AbsorptionOutOfRange {
                    value: c,
                    max: MAX_MU_A,
                });
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_valid_and_each_fault_is_named() {
        assert_eq!(FiberParams::default().validate(), Ok(()));
        let p = FiberParams {
            beta: -0.1,
            ..Default::default()
        };
        assert!(matches!(
            p.validate(),
            Err(ParamError::BetaOutOfRange { .. })
        ));
        let p = FiberParams {
            eta: 1.0,
            ..Default::default()
        };
        assert_eq!(p.validate(), Err(ParamError::EtaTooSmall(1.0)));
        let p = FiberParams {
            mu_a: DVec3::new(0.1, f64::NAN, 0.0),
            ..Default::default()
        };
        assert!(matches!(
            p.validate(),
            Err(ParamError::NotFinite { name: "mu_a", .. })
        ));
        let p = FiberParams {
            alpha: 0.5,
            ..Default::default()
        };
        assert!(matches!(
            p.validate(),
            Err(ParamError::AlphaOutOfRange { .. })
        ));
    }
}
