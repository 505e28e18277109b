//! Named starting points for procedural grooms.

use super::head::Head;
use super::params::GroomParams;
use crate::appearance::Appearance;
use crate::error::ParamsError;
use std::fmt;
use std::str::FromStr;

/// A hairstyle whose controls are set to look right together.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Preset {
    /// Shoulder-length straight brown hair, combed back from a centre parting: the project's
    /// built-in scene groom.
    #[default]
    Straight,
    /// Longer hair with soft waves, coherent within each clump.
    Wavy,
    /// Shorter springy hair in tight curls, with more volume.
    Curly,
}

impl Preset {
    pub const ALL: [Preset; 3] = [Preset::Straight, Preset::Wavy, Preset::Curly];
    /// Strands of every preset unless asked otherwise.
    pub const DEFAULT_STRANDS: usize = 10_000;
    /// Seed of every preset unless asked otherwise.
    pub const DEFAULT_SEED: u64 = 1;

    pub fn name(self) -> &'static str {
        match self {
            Preset::Straight => "straight",
            Preset::Wavy => "wavy",
            Preset::Curly => "curly",
        }
    }

    /// This preset's controls, with the default strand count and seed.
    pub fn params(self) -> GroomParams {
        let base = straight();
        match self {
            Preset::Straight => base,
            Preset::Wavy => GroomParams {
                min_points: 24,
                max_points: 32,
                length: 30.0,
                gravity: 0.3,
                clumping: 0.5,
                clump_size: 60,
                clump_radius: 0.8,
                wave_amplitude: 0.7,
                wavelength: 8.0,
                appearance: base.appearance.with_melanin(0.6, 0.3),
                ..base
            },
            Preset::Curly => GroomParams {
                min_points: 48,
                max_points: 64,
                length: 17.0,
                gravity: 0.18,
                lift: 0.4,
                volume: 3.0,
                clump_size: 30,
                clump_radius: 0.5,
                clumping: 0.6,
                curl_radius: 0.7,
                curl_pitch: 2.4,
                appearance: base.appearance.with_melanin(3.0, 0.2),
                ..base
            },
        }
    }
}

/// The default scene groom's controls.
fn straight() -> GroomParams {
    GroomParams {
        seed: Preset::DEFAULT_SEED,
        strands: Preset::DEFAULT_STRANDS,
        min_points: 20,
        max_points: 30,
        head: Head::default(),
        length: 26.0,
        length_variation: 0.08,
        gravity: 0.25,
        lift: 0.3,
        volume: 1.2,
        clump_size: 40,
        clump_radius: 0.6,
        clumping: 0.3,
        wave_amplitude: 0.0,
        wavelength: 8.0,
        curl_radius: 0.0,
        curl_pitch: 3.0,
        root_thickness: 0.03,
        tip_thickness: 0.015,
        appearance: Appearance::default().with_melanin(1.3, 0.2),
        absorption_variation: 0.12,
    }
}

impl fmt::Display for Preset {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Preset {
    type Err = ParamsError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Preset::ALL
            .into_iter()
            .find(|p| p.name().eq_ignore_ascii_case(s))
            .ok_or_else(|| ParamsError::UnknownPreset(s.to_string()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_parse_back_to_their_preset() {
        for preset in Preset::ALL {
            assert_eq!(preset.name().parse::<Preset>(), Ok(preset));
        }
        assert_eq!("CURLY".parse::<Preset>(), Ok(Preset::Curly));
        assert_eq!(
            "afro".parse::<Preset>(),
            Err(ParamsError::UnknownPreset("afro".into()))
        );
    }

    #[test]
    fn the_default_preset_is_the_scene_groom() {
        let p = Preset::default().params();
        assert_eq!(Preset::default(), Preset::Straight);
        assert_eq!((p.strands, p.min_points, p.max_points), (10_000, 20, 30));
    }
}
