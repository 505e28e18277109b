//! Marschner 2003 Table 1: the parameters, their defaults and their checks.

use crate::lobe::Lobe;
use crate::ranges::{self, RangeError};
use glam::DVec3;

/// The parameters of Marschner 2003 (its Table 1), angles in radians.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct MarschnerParams {
    /// Index of refraction η.
    pub eta: f64,
    /// Longitudinal shift of the R lobe α_R (the paper: −10° to −5°).
    pub alpha_r: f64,
    /// Longitudinal width (standard deviation) of the R lobe β_R (the paper: 5° to 10°).
    pub beta_r: f64,
    /// Absorption μ_a per unit radius, RGB (the paper: μ_a from 0.2 to ∞).
    pub mu_a: DVec3,
    /// Eccentricity a of the cross section, 1 for a circle (the paper: 0.85 to 1).
    pub eccentricity: f64,
    /// Azimuthal width w_c of the TRT caustic glint (the paper: 10° to 25°).
    pub caustic_width: f64,
    /// Glint scale factor k_G (the paper: 0.5 to 5).
    pub glint_scale: f64,
    /// Fade range Δη′ over which the glint vanishes once the caustics merge (0.2 to 0.4).
    pub caustic_fade: f64,
    /// Caustic intensity limit Δh_M (0.5).
    pub caustic_limit: f64,
}

/// Table 1's α_R, β_R and w_c in degrees, as [`MarschnerParams::default`] takes them and as a
/// user types them.
pub const DEFAULT_ALPHA_R_DEG: f64 = -7.5;
/// See [`DEFAULT_ALPHA_R_DEG`].
pub const DEFAULT_BETA_R_DEG: f64 = 7.5;
/// See [`DEFAULT_ALPHA_R_DEG`].
pub const DEFAULT_CAUSTIC_WIDTH_DEG: f64 = 17.5;

impl Default for MarschnerParams {
    /// Marschner 2003 Table 1: η = 1.55, the middle of each range given as a range
    /// (α_R = −7.5°, β_R = 7.5°, w_c = 17.5°, Δη′ = 0.3), Δh_M = 0.5, a circular fiber, and
    /// k_G = 0.5, the low end of its range and the scale at which a glint carries the energy
    /// of the offsets Δh it replaces (k_G A Δh per caustic against ½ A Δh, twice). μ_a is a
    /// light brown starting at the table's smallest μ_a.
    fn default() -> Self {
        Self {
            eta: 1.55,
            alpha_r: DEFAULT_ALPHA_R_DEG.to_radians(),
            beta_r: DEFAULT_BETA_R_DEG.to_radians(),
            mu_a: DVec3::new(0.2, 0.3, 0.5),
            eccentricity: 1.0,
            caustic_width: DEFAULT_CAUSTIC_WIDTH_DEG.to_radians(),
            glint_scale: 0.5,
            caustic_fade: 0.3,
            caustic_limit: 0.5,
        }
    }
}

/// Why a parameter set cannot describe a Marschner fiber: the parameter (named as a scene
/// key, angles in degrees), its value and its range.
pub type MarschnerError = RangeError;

impl MarschnerParams {
    /// The three lobes Marschner 2003 models, in the order of [`Self::longitudinal`].
    pub const LOBES: [Lobe; 3] = [Lobe::R, Lobe::TT, Lobe::TRT];

    /// (α_p, β_p) of M_R, M_TT, M_TRT from α_R, β_R (Marschner 2003 Table 1: α_TT = −α_R/2,
    /// α_TRT = −3α_R/2, β_TT = β_R/2, β_TRT = 2β_R).
    pub fn longitudinal(&self) -> [(f64, f64); 3] {
        let (a, b) = (self.alpha_r, self.beta_r);
        [(a, b), (-0.5 * a, 0.5 * b), (-1.5 * a, 2.0 * b)]
    }

    /// Checks every field against its range ([`crate::ranges`]), returning the first fault.
    pub fn validate(&self) -> Result<(), MarschnerError> {
        ranges::ETA.check(self.eta)?;
        ranges::ALPHA_R_DEG.check_radians(self.alpha_r)?;
        ranges::BETA_R_DEG.check_radians(self.beta_r)?;
        ranges::MU_A.check_all(&self.mu_a.to_array())?;
        ranges::ECCENTRICITY.check(self.eccentricity)?;
        ranges::CAUSTIC_WIDTH_DEG.check_radians(self.caustic_width)?;
        ranges::GLINT_SCALE.check(self.glint_scale)?;
        ranges::CAUSTIC_FADE.check(self.caustic_fade)?;
        ranges::CAUSTIC_LIMIT.check(self.caustic_limit)?;
        Ok(())
    }
}
