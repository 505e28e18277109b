//! A cuticle scene handed to two production path tracers: pbrt-v4 ([`pbrt`]) and Mitsuba 3
//! ([`mitsuba`]), so the look made here can be rendered, and checked, there
//! (`cuticle export --format pbrt|mitsuba`).
//!
//! The pipeline, one file a step:
//! 1. the scene is the path tracer's ([`Scene`], loaded as `render --method path` loads it:
//!    the groom with its shading points, the environment with its rotation, the camera, the
//!    image size) and the hair is Chiang et al. 2016's ([`HairLook`]: β_m, β_n, α, η, and σ_a
//!    per strand or for all), the one model both renderers ship;
//! 2. [`strands`]: each strand as the polyline the path tracer draws (repeated points dropped,
//!    as the trace crate's tubes drop them), its diameter per point, and the strands grouped by
//!    absorption so each group gets one material;
//! 3. [`env`]: the environment resampled onto each renderer's own parameterisation (Mitsuba's
//!    lat-long grid, pbrt-v4's equal-area octahedral square), so a direction receives the
//!    radiance cuticle gives it, whatever the conventions;
//! 4. [`pbrt`] and [`mitsuba`]: the scene files, each module's documentation the mapping of
//!    every quantity with its source.
//!
//! An [`Export`] is the files' names and bytes; the caller writes them (the command line writes
//! them as one set, with its record).

pub mod env;
pub mod mitsuba;
pub mod pbrt;
pub mod strands;

use cuticle_render::Scene;
use glam::DVec3;
use serde::Serialize;

/// Which renderer the scene is written for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Format {
    /// pbrt-v4's scene description (`scene.pbrt`).
    Pbrt,
    /// Mitsuba 3's XML scene (`scene.xml`).
    Mitsuba,
}

/// Chiang et al. 2016's parameters as cuticle's `--model chiang2016` takes them.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ChiangHair {
    /// Longitudinal roughness β_m in (0, 1].
    pub beta_m: f64,
    /// Azimuthal roughness β_n in (0, 1].
    pub beta_n: f64,
    /// Scale tilt α, degrees (cuticle's sign: the R cone at −θ_i + 2α).
    pub alpha_deg: f64,
    /// Index of refraction η of the fiber (the medium outside is 1).
    pub eta: f64,
}

/// Absorption σ_a per unit radius (docs/conventions.md §5), for every strand or each its own.
#[derive(Clone, Debug, PartialEq)]
pub enum Absorption {
    Uniform(DVec3),
    /// One value per strand of the groom.
    PerStrand(Vec<DVec3>),
}

/// The hair's look: the fiber model's parameters and each strand's absorption.
#[derive(Clone, Debug, PartialEq)]
pub struct HairLook {
    pub fiber: ChiangHair,
    pub sigma_a: Absorption,
}

/// How the exported scene is rendered: the path tracer's own settings.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct RenderSettings {
    /// Samples per pixel.
    pub spp: u32,
    pub seed: u64,
    /// Most scattering events of a path (cuticle's `--max-depth`).
    pub max_depth: u32,
}

/// One file of an export, named relative to the export's folder.
#[derive(Clone, Debug, PartialEq)]
pub struct ExportFile {
    pub name: String,
    pub bytes: Vec<u8>,
}

/// What an export wrote, for the record.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Summary {
    pub format: Format,
    /// The file to hand the renderer.
    pub scene_file: String,
    /// The image the renderer writes.
    pub image_file: String,
    /// Strands written, and strands left out for having fewer than two distinct points.
    pub strands: usize,
    pub skipped_strands: usize,
    /// Control points written (after repeated points were dropped).
    pub points: usize,
    /// Distinct absorptions, each one material.
    pub materials: usize,
    /// The environment image: its file and size in pixels.
    pub env_file: String,
    pub env_width: usize,
    pub env_height: usize,
}

impl Summary {
    /// The record of a format that writes `names` (scene, image, environment), with `strands`
    /// and an environment image of `env_size` (width, height) pixels.
    fn of(
        format: Format,
        [scene_file, image_file, env_file]: [&str; 3],
        strands: &strands::Grouped,
        (env_width, env_height): (usize, usize),
    ) -> Self {
        Self {
            format,
            scene_file: scene_file.into(),
            image_file: image_file.into(),
            strands: strands.strand_count(),
            skipped_strands: strands.skipped,
            points: strands.point_count(),
            materials: strands.groups.len(),
            env_file: env_file.into(),
            env_width,
            env_height,
        }
    }
}

/// A scene written for one renderer.
#[derive(Clone, Debug, PartialEq)]
pub struct Export {
    pub files: Vec<ExportFile>,
    pub summary: Summary,
}

/// Why a scene cannot be exported.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    #[error("the groom has no strand of two distinct points: nothing to export")]
    NoStrands,
    #[error("{0}")]
    Invalid(String),
    #[error("environment image: {0}")]
    Encode(#[from] cuticle_light::LightError),
}

/// Writes `scene` with the hair `look` for `format`, rendered with `settings`.
pub fn export(
    scene: &Scene,
    look: &HairLook,
    settings: &RenderSettings,
    format: Format,
) -> Result<Export, ExportError> {
    check_look(scene, look)?;
    match format {
        Format::Pbrt => pbrt::export(scene, look, settings),
        Format::Mitsuba => mitsuba::export(scene, look, settings),
    }
}

/// The look's numbers are ones both renderers take: finite roughness in (0, 1], η > 1 (Mitsuba
/// refuses equal indices), finite non-negative σ_a, one σ_a per strand.
fn check_look(scene: &Scene, look: &HairLook) -> Result<(), ExportError> {
    let f = &look.fiber;
    let bad = |what: String| Err(ExportError::Invalid(what));
    for (name, beta) in [("beta_m", f.beta_m), ("beta_n", f.beta_n)] {
        if !(beta > 0.0 && beta <= 1.0) {
            return bad(format!("{name} {beta} is outside (0, 1]"));
        }
    }
    if !(f.eta > 1.0 && f.eta.is_finite()) {
        return bad(format!("eta {} must be finite and above 1", f.eta));
    }
    if f.alpha_deg.is_nan() || f.alpha_deg.abs() >= 90.0 {
        return bad(format!("alpha {} degrees is not a scale tilt", f.alpha_deg));
    }
    let values: &[DVec3] = match &look.sigma_a {
        Absorption::Uniform(s) => std::slice::from_ref(s),
        Absorption::PerStrand(v) if v.len() != scene.groom.strand_count() => {
            return bad(format!(
                "{} absorptions for {} strands",
                v.len(),
                scene.groom.strand_count()
            ));
        }
        Absorption::PerStrand(v) => v,
    };
    match values
        .iter()
        .find(|s| !(s.is_finite() && s.min_element() >= 0.0))
    {
        Some(s) => bad(format!("sigma_a {s} must be finite and non-negative")),
        None => Ok(()),
    }
}

/// A number as both scene formats read it back to the same f64: Rust's shortest round-trip
/// decimal (never an exponent).
pub(crate) fn num(x: f64) -> String {
    let s = format!("{x}");
    if s == "-0" { "0".into() } else { s }
}

/// Three numbers separated by `sep`.
pub(crate) fn triple(v: DVec3, sep: &str) -> String {
    [v.x, v.y, v.z].map(num).join(sep)
}

#[cfg(test)]
mod tests {
    use super::*;
    use cuticle_light::EnvMap;
    use cuticle_render::SceneSpec;
    use glam::Vec3;

    fn scene() -> Scene {
        let groom = cuticle_render::scene::load_groom("straight", 3).unwrap();
        let env = EnvMap::new(4, 2, vec![Vec3::ONE; 8]);
        Scene::from_parts(SceneSpec::default(), groom, env, Vec::new())
    }

    fn look() -> HairLook {
        HairLook {
            fiber: ChiangHair {
                beta_m: 0.3,
                beta_n: 0.3,
                alpha_deg: 2.0,
                eta: 1.55,
            },
            sigma_a: Absorption::Uniform(DVec3::new(0.2, 0.4, 0.8)),
        }
    }

    const SETTINGS: RenderSettings = RenderSettings {
        spp: 4,
        seed: 0,
        max_depth: 8,
    };

    /// A look a renderer would refuse or misread is refused before anything is written, naming
    /// the value.
    #[test]
    fn impossible_looks_are_refused() {
        type Spoil = (&'static str, fn(&mut HairLook));
        let cases: [Spoil; 8] = [
            ("beta_m", |l| l.fiber.beta_m = 0.0),
            ("beta_n", |l| l.fiber.beta_n = 1.5),
            ("beta_m", |l| l.fiber.beta_m = f64::NAN),
            ("eta", |l| l.fiber.eta = 1.0),
            ("alpha", |l| l.fiber.alpha_deg = f64::NAN),
            ("sigma_a", |l| {
                l.sigma_a = Absorption::Uniform(DVec3::splat(-1.0))
            }),
            ("sigma_a", |l| {
                l.sigma_a = Absorption::Uniform(DVec3::new(0.0, f64::INFINITY, 0.0))
            }),
            ("2 absorptions for 3 strands", |l| {
                l.sigma_a = Absorption::PerStrand(vec![DVec3::ONE; 2])
            }),
        ];
        let scene = scene();
        for (needle, spoil) in cases {
            let mut bad = look();
            spoil(&mut bad);
            for format in [Format::Pbrt, Format::Mitsuba] {
                let e = export(&scene, &bad, &SETTINGS, format)
                    .unwrap_err()
                    .to_string();
                assert!(e.contains(needle), "{needle}: {e}");
            }
        }
        assert!(export(&scene, &look(), &SETTINGS, Format::Mitsuba).is_ok());
    }

    /// Numbers are written so they read back to the same value, with no exponent and no "-0".
    #[test]
    fn numbers_round_trip() {
        for x in [0.1, -2.5, 1e-9, 123456.789, 1.0 / 3.0] {
            let s = num(x);
            assert!(!s.contains('e'), "{s}");
            assert_eq!(s.parse::<f64>().unwrap(), x);
        }
        assert_eq!(num(-0.0), "0");
    }
}
