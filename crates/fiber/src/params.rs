//! The physical parameters every model shares, and their validation.

use crate::ranges::{self, RangeError};
use glam::DVec3;
use serde::Serialize;

/// A fiber: relative index η, surface roughness β (Beckmann, as the simulator uses it), scale
/// tilt α (radians) and interior absorption μ_a per unit radius (RGB).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct FiberParams {
    pub eta: f64,
    pub beta: f64,
    pub alpha: f64,
    pub mu_a: DVec3,
}

/// The default scale tilt α, degrees ([`FiberParams::default`]'s, as the command line types it).
pub const DEFAULT_ALPHA_DEG: f64 = -2.0;

impl Default for FiberParams {
    /// Human hair in air: η = 1.55, β = 0.04, α = −2°, a light brown μ_a.
    fn default() -> Self {
        Self {
            eta: 1.55,
            beta: 0.04,
            alpha: DEFAULT_ALPHA_DEG.to_radians(),
            mu_a: DVec3::new(0.12, 0.25, 0.5),
        }
    }
}

/// Why a parameter set cannot describe a fiber: the parameter, its value and its range.
pub type ParamError = RangeError;

impl FiberParams {
    /// Checks every field against its range ([`crate::ranges`]), returning the first fault in a
    /// sentence a user understands.
    pub fn validate(&self) -> Result<(), ParamError> {
        ranges::ETA.check(self.eta)?;
        ranges::BETA.check(self.beta)?;
        ranges::ALPHA_DEG.check_radians(self.alpha)?;
        ranges::MU_A.check_all(&self.mu_a.to_array())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_valid_and_each_fault_is_named() {
        assert_eq!(FiberParams::default().validate(), Ok(()));
        let fault = |p: FiberParams| p.validate().unwrap_err();
        let p = FiberParams::default();
        assert_eq!(fault(FiberParams { beta: -0.1, ..p }).name, "beta");
        assert_eq!(fault(FiberParams { eta: 1.0, ..p }).name, "eta");
        assert_eq!(fault(FiberParams { eta: 1e160, ..p }).name, "eta");
        let nan = fault(FiberParams {
            mu_a: DVec3::new(0.1, f64::NAN, 0.0),
            ..p
        });
        assert_eq!(nan.name, "mu_a");
        assert!(
            nan.value.is_nan(),
            "the NaN is named, not a neighbour: {nan}"
        );
        let alpha = fault(FiberParams { alpha: 0.5, ..p });
        assert_eq!(alpha.name, "alpha_deg");
        assert!((alpha.value - 0.5f64.to_degrees()).abs() < 1e-12);
    }
}
