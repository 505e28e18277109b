//! [`GroomParams`]: every control of a procedural groom, and their valid ranges.

use super::head::Head;
use crate::appearance::Appearance;
use crate::error::ParamsError;
use serde::{Deserialize, Serialize};

/// Controls of a procedural groom. Lengths are in centimetres.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct GroomParams {
    pub seed: u64,
    pub strands: usize,
    /// Points per strand, drawn uniformly from `min_points..=max_points`.
    pub min_points: usize,
    pub max_points: usize,
    pub head: Head,
    /// Mean strand length (of the centreline, before waves and curls).
    pub length: f32,
    /// Relative standard deviation of the strand length.
    pub length_variation: f32,
    /// Curvature toward −z per centimetre of strand: 0 stands straight out, 0.3 falls soon.
    pub gravity: f32,
    /// How far the root leaves the scalp's tangent plane (0 flat, 1 along the normal).
    pub lift: f32,
    /// Largest height above the scalp a strand settles at, giving the hairdo volume.
    pub volume: f32,
    /// Average number of strands that share a clump.
    pub clump_size: usize,
    /// Radius of a clump's footprint on the scalp.
    pub clump_radius: f32,
    /// How far tips are pulled onto their clump's guide (0 none, 1 all the way).
    pub clumping: f32,
    pub wave_amplitude: f32,
    pub wavelength: f32,
    pub curl_radius: f32,
    /// Distance along the strand of one turn of a curl.
    pub curl_pitch: f32,
    /// Fiber diameter at the root; it tapers to `tip_thickness` over the last fifth.
    pub root_thickness: f32,
    pub tip_thickness: f32,
    /// Each strand's appearance: this, with its absorption varied.
    pub appearance: Appearance,
    /// Relative standard deviation of absorption (μ_a or melanin) between clumps and strands.
    pub absorption_variation: f32,
}

/// Most strands a procedural groom may have.
pub const MAX_STRANDS: usize = 2_000_000;
/// Most points a procedural strand may have.
pub const MAX_POINTS_PER_STRAND: usize = 1024;

impl GroomParams {
    /// Checks every control is within its range.
    pub fn validate(&self) -> Result<(), ParamsError> {
        let counts = [
            (
                "strands",
                self.strands,
                self.strands <= MAX_STRANDS,
                "at most 2,000,000",
            ),
            (
                "min_points",
                self.min_points,
                self.min_points >= 2,
                "at least 2",
            ),
            (
                "max_points",
                self.max_points,
                (self.min_points..=MAX_POINTS_PER_STRAND).contains(&self.max_points),
                "between min_points and 1024",
            ),
            (
                "clump_size",
                self.clump_size,
                self.clump_size >= 1,
                "at least 1",
            ),
        ];
        for (name, value, ok, rule) in counts {
            require(name, value as f64, ok, rule)?;
        }
        let positive = [
            ("length", self.length),
            ("wavelength", self.wavelength),
            ("curl_pitch", self.curl_pitch),
            ("root_thickness", self.root_thickness),
            ("tip_thickness", self.tip_thickness),
            ("clump_radius", self.clump_radius),
        ];
        for (name, value) in positive {
            require(
                name,
                value.into(),
                value.is_finite() && value > 0.0,
                "positive",
            )?;
        }
        for (name, value) in self.head.radii.iter().map(|&r| ("head radius", r)) {
            require(
                name,
                value.into(),
                value.is_finite() && value > 0.0,
                "positive",
            )?;
        }
        let non_negative = [
            ("length_variation", self.length_variation),
            ("gravity", self.gravity),
            ("lift", self.lift),
            ("volume", self.volume),
            ("wave_amplitude", self.wave_amplitude),
            ("curl_radius", self.curl_radius),
            ("absorption_variation", self.absorption_variation),
        ];
        for (name, value) in non_negative {
            require(
                name,
                value.into(),
                value.is_finite() && value >= 0.0,
                "zero or more",
            )?;
        }
        let clumping = self.clumping;
        require(
            "clumping",
            clumping.into(),
            (0.0..=1.0).contains(&clumping),
            "within [0, 1]",
        )?;
        let physical = self.appearance.is_physical();
        require(
            "appearance",
            f64::NAN,
            physical,
            "physical (β > 0, η > 1, absorption ≥ 0)",
        )
    }
}

fn require(
    name: &'static str,
    value: f64,
    ok: bool,
    rule: &'static str,
) -> Result<(), ParamsError> {
    if ok {
        Ok(())
    } else {
        Err(ParamsError::OutOfRange { name, rule, value })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::procedural::Preset;

    #[test]
    fn presets_are_valid() {
        for preset in Preset::ALL {
            assert_eq!(preset.params().validate(), Ok(()), "{preset}");
        }
    }

    #[test]
    fn out_of_range_controls_are_named() {
        let base = Preset::Straight.params();
        let cases = [
            (
                "min_points",
                GroomParams {
                    min_points: 1,
                    ..base.clone()
                },
            ),
            (
                "max_points",
                GroomParams {
                    max_points: 10,
                    ..base.clone()
                },
            ),
            (
                "length",
                GroomParams {
                    length: 0.0,
                    ..base.clone()
                },
            ),
            (
                "wavelength",
                GroomParams {
                    wavelength: f32::NAN,
                    ..base.clone()
                },
            ),
            (
                "gravity",
                GroomParams {
                    gravity: -1.0,
                    ..base.clone()
                },
            ),
            (
                "clumping",
                GroomParams {
                    clumping: 1.5,
                    ..base.clone()
                },
            ),
            (
                "strands",
                GroomParams {
                    strands: MAX_STRANDS + 1,
                    ..base.clone()
                },
            ),
            (
                "head radius",
                GroomParams {
                    head: Head {
                        radii: [1.0, 0.0, 1.0],
                    },
                    ..base.clone()
                },
            ),
        ];
        for (name, params) in cases {
            let err = params.validate().unwrap_err();
            assert!(
                matches!(err, ParamsError::OutOfRange { name: n, .. } if n == name),
                "{err}"
            );
        }
        let eta = Appearance {
            eta: 0.5,
            ..base.appearance
        };
        let err = GroomParams {
            appearance: eta,
            ..base
        }
        .validate()
        .unwrap_err();
        assert!(matches!(
            err,
            ParamsError::OutOfRange {
                name: "appearance",
                ..
            }
        ));
    }
}
