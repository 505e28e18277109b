//! [`GroomParams`]: every control of a procedural groom, and their valid ranges.

use super::head::Head;
use crate::appearance::Appearance;
use crate::error::ParamsError;
use cuticle_range::{CountRange, End, Range};
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

/// The counts' ranges ([`GroomParams::validate`]; `max_points` lies in min_points..=1024).
pub const STRANDS: CountRange = CountRange {
    name: "strands",
    min: 0,
    max: MAX_STRANDS as u64,
};
pub const MIN_POINTS: CountRange = CountRange {
    name: "min_points",
    min: 2,
    max: MAX_POINTS_PER_STRAND as u64,
};
pub const CLUMP_SIZE: CountRange = CountRange {
    name: "clump_size",
    min: 1,
    max: MAX_STRANDS as u64,
};
/// Lengths, thicknesses and radii (each under its own name).
pub const POSITIVE: Range = Range {
    name: "length",
    min: End::Open(0.0),
    max: End::Closed(f32::MAX as f64),
    unit: "",
};
/// Variations, gravity, lift, volume and amplitudes (each under its own name).
pub const NON_NEGATIVE: Range = Range {
    name: "gravity",
    min: End::Closed(0.0),
    max: End::Closed(f32::MAX as f64),
    unit: "",
};
pub const CLUMPING: Range = Range {
    name: "clumping",
    min: End::Closed(0.0),
    max: End::Closed(1.0),
    unit: "",
};

impl GroomParams {
    /// Checks every control is within its range.
    pub fn validate(&self) -> Result<(), ParamsError> {
        STRANDS.check_usize(self.strands)?;
        MIN_POINTS.check_usize(self.min_points)?;
        let max_points = CountRange {
            name: "max_points",
            min: self.min_points as u64,
            ..MIN_POINTS
        };
        max_points.check_usize(self.max_points)?;
        CLUMP_SIZE.check_usize(self.clump_size)?;
        let positive = [
            ("length", self.length),
            ("wavelength", self.wavelength),
            ("curl_pitch", self.curl_pitch),
            ("root_thickness", self.root_thickness),
            ("tip_thickness", self.tip_thickness),
            ("clump_radius", self.clump_radius),
        ]
        .into_iter()
        .chain(self.head.radii.iter().map(|&r| ("head radius", r)));
        for (name, value) in positive {
            POSITIVE.named(name).check(value.into())?;
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
            NON_NEGATIVE.named(name).check(value.into())?;
        }
        CLUMPING.check(self.clumping.into())?;
        if !self.appearance.is_physical() {
            return Err(ParamsError::Unphysical);
        }
        Ok(())
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
                matches!(&err, ParamsError::Range(e) if e.name == name),
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
        assert_eq!(err, ParamsError::Unphysical);
    }
}
