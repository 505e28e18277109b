//! Hair scattering parameters: the global set a scene carries (Marschner 2003's Table 1, as
//! Xu et al. 2011 edits them), and the per-strand values shading reads, taking each strand's
//! absorption from the groom's [`Appearance`] unless the scene overrides it.
//!
//! The groom's β and α (pbrt-style roughness and a tilt in degrees) are not Marschner's β_R and
//! α_R; the renderer takes the longitudinal lobes from the global parameters and only the
//! absorption (μ_a or melanin) per strand.

use cuticle_fiber::models::marschner2003::{
    DEFAULT_ALPHA_R_DEG, DEFAULT_BETA_R_DEG, DEFAULT_CAUSTIC_WIDTH_DEG, MarschnerParams,
};
use cuticle_fiber::optics::absorption::mu_a_from_melanin;
use cuticle_fiber::ranges::{self, End, Range, RangeError};
use cuticle_groom::{Absorption, Appearance};
use glam::DVec3;
use serde::{Deserialize, Serialize};
use std::f64::consts::SQRT_2;

/// The editable parameters of the hair (angles in degrees, as a user types them).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct HairParams {
    /// Index of refraction η.
    pub eta: f64,
    /// Longitudinal shift α_R, degrees (α_TT = −α_R/2, α_TRT = −3α_R/2).
    pub alpha_r_deg: f64,
    /// Longitudinal width β_R, degrees (β_TT = β_R/2, β_TRT = 2β_R).
    pub beta_r_deg: f64,
    /// Absorption μ_a per unit radius for every strand; `None` takes each strand's own.
    #[serde(deserialize_with = "crate::scene::maybe_three")]
    pub mu_a: Option<[f64; 3]>,
    /// μ_a of strands whose appearance carries none.
    #[serde(deserialize_with = "crate::scene::exactly_three")]
    pub default_mu_a: [f64; 3],
    /// Eccentricity a (1 for a circular fiber; Xu et al. 2011 eq. 24).
    pub eccentricity: f64,
    /// Azimutal width w_c of the TRT caustics, degrees (a standard deviation, as Marschner's).
    pub caustic_width_deg: f64,
    /// Δη′ over which the TRT caustics fade once they merge (Xu et al. 2011 §4.2.4).
    pub caustic_fade: f64,
    /// d_b, the weight of local backward multiple scattering (Xu et al. 2011 eq. 4; 0.6–0.8).
    pub d_b: f64,
}

impl Default for HairParams {
    fn default() -> Self {
        let m = MarschnerParams::default();
        Self {
            eta: m.eta,
            alpha_r_deg: DEFAULT_ALPHA_R_DEG,
            beta_r_deg: DEFAULT_BETA_R_DEG,
            mu_a: None,
            default_mu_a: [0.3, 0.5, 0.9],
            eccentricity: 1.0,
            caustic_width_deg: DEFAULT_CAUSTIC_WIDTH_DEG,
            caustic_fade: m.caustic_fade,
            d_b: 0.6,
        }
    }
}

/// d_b, the weight of local backward multiple scattering (Xu et al. 2011 eq. 4).
pub const D_B: Range = Range {
    name: "d_b",
    min: End::Closed(0.0),
    max: End::Closed(1.0),
    unit: "",
};

impl HairParams {
    /// Checks every field against the ranges the model and tables cover: the fiber's through
    /// [`MarschnerParams::validate`], the one check every consumer of these parameters shares
    /// (the SRBF path, the brute force and the exact model), and `d_b`. Each fault names its
    /// scene key (`hair.` keys, flags of the same name) and value.
    pub fn validate(&self) -> Result<(), RangeError> {
        if let Some(mu) = self.mu_a {
            ranges::MU_A.check_all(&mu)?;
        }
        ranges::MU_A
            .named("default_mu_a")
            .check_all(&self.default_mu_a)?;
        self.fiber(None).validate()?;
        D_B.check(self.d_b)?;
        Ok(())
    }

    /// The shading parameters of a strand with this appearance: the exact model's parameters,
    /// which both the circular-Gaussian path and the brute-force reference read.
    pub fn fiber(&self, appearance: Option<&Appearance>) -> MarschnerParams {
        let own = appearance.and_then(|a| a.absorption).map(mu_a_of);
        let mu_a = match self.mu_a {
            Some(m) => DVec3::from_array(m),
            None => own.unwrap_or(DVec3::from_array(self.default_mu_a)),
        };
        MarschnerParams {
            eta: self.eta,
            alpha_r: self.alpha_r_deg.to_radians(),
            beta_r: self.beta_r_deg.to_radians(),
            mu_a,
            eccentricity: self.eccentricity,
            caustic_width: self.caustic_width_deg.to_radians(),
            caustic_fade: self.caustic_fade,
            ..MarschnerParams::default()
        }
    }
}

/// μ_a per unit radius of a strand's absorption: given, or from melanin through the fiber
/// crate's mapping.
pub fn mu_a_of(absorption: Absorption) -> DVec3 {
    match absorption {
        Absorption::MuA(s) => DVec3::new(s[0] as f64, s[1] as f64, s[2] as f64),
        Absorption::Melanin {
            eumelanin,
            pheomelanin,
        } => mu_a_from_melanin(eumelanin as f64, pheomelanin as f64),
    }
}

/// λ₁ of the TRT caustic Gaussians: a circular Gaussian exp(−x²/λ²) has deviation λ/√2, so
/// Marschner's glint of deviation w_c is λ₁ = √2 w_c (Xu et al. 2011 sets λ₁ = w_c in its own
/// bandwidth convention).
pub fn caustic_bandwidth(fiber: &MarschnerParams) -> f64 {
    SQRT_2 * fiber.caustic_width
}
