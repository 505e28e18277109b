//! Per-strand appearance: what a fiber scattering model needs to shade one strand.
//!
//! Units follow docs/conventions.md §5: μ_a per unit fiber radius, β (longitudinal roughness)
//! unitless, the scale tilt α in degrees, η the index of refraction of the fiber.

use serde::{Deserialize, Serialize};

/// How a strand absorbs light inside the fiber.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Absorption {
    /// Absorption coefficient μ_a per unit fiber radius, RGB (the CLI's `--mu-a`).
    #[serde(rename = "mu_a", alias = "sigma_a")]
    MuA([f32; 3]),
    /// Pigment concentrations, turned into μ_a by the fiber crate's melanin model.
    Melanin { eumelanin: f32, pheomelanin: f32 },
}

/// The scattering parameters of one strand.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Appearance {
    /// Absorption, or `None` to let the renderer use its global setting.
    pub absorption: Option<Absorption>,
    /// Longitudinal roughness β.
    pub beta: f32,
    /// Scale tilt α in degrees.
    pub alpha_deg: f32,
    /// Index of refraction η.
    pub eta: f32,
}

impl Appearance {
    /// Longitudinal roughness of human hair in the literature's usual range.
    pub const DEFAULT_BETA: f32 = 0.3;
    /// Cuticle scale tilt of human hair, in degrees.
    pub const DEFAULT_ALPHA_DEG: f32 = 2.0;
    /// Index of refraction of keratin.
    pub const DEFAULT_ETA: f32 = 1.55;

    /// This appearance with melanin absorption.
    pub fn with_melanin(self, eumelanin: f32, pheomelanin: f32) -> Self {
        Self {
            absorption: Some(Absorption::Melanin {
                eumelanin,
                pheomelanin,
            }),
            ..self
        }
    }

    /// This appearance with an explicit μ_a (per unit radius, RGB).
    pub fn with_mu_a(self, mu_a: [f32; 3]) -> Self {
        Self {
            absorption: Some(Absorption::MuA(mu_a)),
            ..self
        }
    }

    /// This appearance with its absorption (μ_a or both concentrations) multiplied by `factor`.
    pub fn with_absorption_scaled(self, factor: f32) -> Self {
        let absorption = self.absorption.map(|a| match a {
            Absorption::MuA(s) => Absorption::MuA(s.map(|c| c * factor)),
            Absorption::Melanin {
                eumelanin,
                pheomelanin,
            } => Absorption::Melanin {
                eumelanin: eumelanin * factor,
                pheomelanin: pheomelanin * factor,
            },
        });
        Self { absorption, ..self }
    }

    /// Whether every number is finite and in its physical range (β > 0, η > 1, μ_a and
    /// concentrations ≥ 0).
    pub fn is_physical(&self) -> bool {
        let absorption_ok = match self.absorption {
            None => true,
            Some(Absorption::MuA(s)) => s.iter().all(|c| c.is_finite() && *c >= 0.0),
            Some(Absorption::Melanin {
                eumelanin,
                pheomelanin,
            }) => [eumelanin, pheomelanin]
                .iter()
                .all(|c| c.is_finite() && *c >= 0.0),
        };
        absorption_ok
            && self.beta.is_finite()
            && self.beta > 0.0
            && self.alpha_deg.is_finite()
            && self.eta.is_finite()
            && self.eta > 1.0
    }
}

impl Default for Appearance {
    fn default() -> Self {
        Self {
            absorption: None,
            beta: Self::DEFAULT_BETA,
            alpha_deg: Self::DEFAULT_ALPHA_DEG,
            eta: Self::DEFAULT_ETA,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scaling_absorption_scales_every_channel_or_pigment() {
        let melanin = Appearance::default()
            .with_melanin(1.0, 0.5)
            .with_absorption_scaled(2.0);
        let expected = Absorption::Melanin {
            eumelanin: 2.0,
            pheomelanin: 1.0,
        };
        assert_eq!(melanin.absorption, Some(expected));
        let sigma = Appearance::default()
            .with_mu_a([0.1, 0.2, 0.4])
            .with_absorption_scaled(0.5);
        assert_eq!(sigma.absorption, Some(Absorption::MuA([0.05, 0.1, 0.2])));
        assert_eq!(
            Appearance::default().with_absorption_scaled(3.0).absorption,
            None
        );
    }

    #[test]
    fn unphysical_values_are_flagged() {
        assert!(Appearance::default().is_physical());
        assert!(
            !Appearance {
                eta: 0.9,
                ..Appearance::default()
            }
            .is_physical()
        );
        assert!(
            !Appearance {
                beta: 0.0,
                ..Appearance::default()
            }
            .is_physical()
        );
        assert!(
            !Appearance::default()
                .with_mu_a([0.1, -1.0, 0.0])
                .is_physical()
        );
        assert!(
            !Appearance::default()
                .with_melanin(f32::NAN, 0.0)
                .is_physical()
        );
    }
}
