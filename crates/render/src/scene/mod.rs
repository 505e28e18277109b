//! A scene: groom, environment and its SRBF fit, camera, hair parameters and image settings,
//! from a TOML file and/or flags ([`SceneSpec`]), loaded into memory ([`Scene`]).
//!
//! Spaces: the groom's (+z up, as procedural grooms and cyHair models) is world space; the
//! light crate's directions are +y up, turned into world space by [`light_to_world`].

pub mod camera;
pub mod hair;
pub mod headroom;
pub mod memory;
pub mod overrides;
pub mod resample;

use crate::frame::shadows::ShadowOptions;
use crate::scene::camera::Camera;
use crate::scene::hair::HairParams;
use cuticle_fiber::ranges::{CountRange, End, Range, RangeError};
use cuticle_groom::Groom;
use cuticle_groom::procedural::{GroomParams, Preset, generate};
use cuticle_light::{
    EnvMap, FitCache, FitOptions, FitSource, MAX_LIGHTS, MAX_RADIANCE, SrbfLight, fit_srbf_cached,
    load_or_default,
};
use glam::{DVec3, Vec3};
use serde::{Deserialize, Deserializer, Serialize};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Which shading integrates the lights.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Method {
    /// Circular Gaussians against SRBF lights (Xu et al. 2011).
    Srbf,
    /// The exact Marschner 2003 model against the environment as directional lights.
    Brute,
    /// The path tracer (crate cuticle-trace, `cuticle render --method path`); the SRBF
    /// [`crate::Renderer`] does not render it ([`crate::Renderer::accepts`]).
    Path,
}

/// Everything a render needs, as a user writes it (TOML keys = these field names).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SceneSpec {
    /// A preset name (straight, wavy, curly) or a `.hair` file.
    pub groom: String,
    /// Strands of a preset groom.
    pub strands: usize,
    /// Whether the loaded groom gets the points it is shaded at ([`resample::shading_points`]);
    /// false for a groom file that holds them already, as a look saved by `cuticle view` does
    /// (the tips' step reads maps of the groom, so it would not add the same points twice).
    pub shading_points: bool,
    /// A per-strand absorption file laid over the groom's own (the JSON sidecar
    /// `cuticle view` saves with a painted groom: [`cuticle_groom::strand_absorption`]).
    pub strand_absorption: Option<String>,
    /// `default` (the procedural sky), `constant:R,G,B` (or `constant:V`, a uniform
    /// environment for tests) or an .hdr/.exr lat-long map.
    pub env: String,
    /// Rotation of the environment about the up axis, degrees.
    pub env_rotate_deg: f64,
    /// Number J of SRBF lights to fit.
    pub lights: usize,
    pub width: usize,
    pub height: usize,
    /// The camera; `None` frames the groom.
    pub camera: Option<Camera>,
    pub hair: HairParams,
    pub method: Method,
    /// Segments m of the linear quadrature (Xu et al. 2011 §4.2.2).
    pub quadrature: usize,
    /// Whether to add dual-scattering multiple scattering.
    pub multiple: bool,
    /// Which single-scattering lobes shade (a debug view; all by default).
    pub lobes: Lobes,
    /// Subsamples per pixel along each axis.
    pub supersampling: usize,
    pub shadows: ShadowOptions,
    /// n of the brute force's 6 × n × n directional lights.
    pub brute_grid: usize,
}

impl Default for SceneSpec {
    fn default() -> Self {
        Self {
            groom: "straight".into(),
            strands: Preset::DEFAULT_STRANDS,
            shading_points: true,
            strand_absorption: None,
            env: "default".into(),
            env_rotate_deg: 0.0,
            lights: 40,
            width: 720,
            height: 480,
            camera: None,
            hair: HairParams::default(),
            method: Method::Srbf,
            quadrature: 4,
            multiple: true,
            lobes: Lobes::ALL,
            supersampling: 3,
            shadows: ShadowOptions::default(),
            brute_grid: 16,
        }
    }
}

/// The single-scattering lobes that shade (Marschner et al. 2003's R, TT, TRT): a lobe off
/// contributes zero, so the three alone sum to all three. A debug view of the SRBF and brute
/// methods' single scattering (the path tracer's bounces are not split by lobe); multiple
/// scattering has its own switch ([`SceneSpec::multiple`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Lobes {
    pub r: bool,
    pub tt: bool,
    pub trt: bool,
}

impl Lobes {
    pub const ALL: Self = Self {
        r: true,
        tt: true,
        trt: true,
    };

    /// As a mask over [R, TT, TRT].
    pub fn mask(&self) -> [bool; 3] {
        [self.r, self.tt, self.trt]
    }

    /// The sum of the lobes that are on.
    pub fn sum(&self, modes: [DVec3; 3]) -> DVec3 {
        modes
            .iter()
            .zip(self.mask())
            .filter(|(_, on)| *on)
            .map(|(m, _)| *m)
            .sum()
    }
}

impl Default for Lobes {
    fn default() -> Self {
        Self::ALL
    }
}

/// Why a scene cannot be loaded.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    #[error("cannot read scene file {path}: {source}")]
    Read {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    /// One line: where in the file, and what is wrong there.
    #[error("scene file {path}{at}: {message}")]
    Toml {
        path: PathBuf,
        at: String,
        message: String,
    },
    #[error("groom: {0}")]
    Groom(String),
    #[error("environment: {0}")]
    Light(#[from] cuticle_light::LightError),
    #[error("hair parameter {0}")]
    Hair(RangeError),
    #[error("scene {0}")]
    Range(#[from] RangeError),
    #[error("{0}")]
    Invalid(String),
    #[error(transparent)]
    Memory(#[from] memory::MemoryError),
}

/// Image width and height, pixels.
pub const SIZE: CountRange = CountRange {
    name: "width/height",
    min: 1,
    max: 16384,
};
/// Subsamples per pixel along each axis.
pub const SUPERSAMPLING: CountRange = CountRange {
    name: "supersampling",
    min: 1,
    max: 8,
};
/// Segments m of the linear quadrature (Xu et al. 2011 §4.2.2).
pub const QUADRATURE: CountRange = CountRange {
    name: "quadrature",
    min: 2,
    max: crate::srbf::quadrature::MAX_SEGMENTS as u64,
};
/// n of the brute force's 6 n² directional lights.
pub const BRUTE_GRID: CountRange = CountRange {
    name: "brute_grid",
    min: 1,
    max: 64,
};
/// Strands of a preset groom (the groom crate makes empty ones too; a scene renders hair).
pub const STRANDS: CountRange = CountRange {
    min: 1,
    ..cuticle_groom::procedural::STRANDS
};
/// Number J of SRBF lights fitted to the map (or read from a lights file).
pub const LIGHTS: CountRange = CountRange {
    name: "lights",
    min: 1,
    max: MAX_LIGHTS as u64,
};
/// Texels along each side of an opacity map.
pub const SHADOW_RESOLUTION: CountRange = CountRange {
    name: "shadows.resolution",
    min: 8,
    max: 4096,
};
/// The opacity maps' optical-depth multiplier (1 physical, 0 no shadows).
pub const SHADOW_DENSITY: Range = Range {
    name: "shadows.density",
    min: End::Closed(0.0),
    max: End::Closed(1000.0),
    unit: "",
};
/// The transmittance below which a light adds no direct light.
pub const SHADOW_CUTOFF: Range = Range {
    name: "shadows.cutoff",
    min: End::Closed(0.0),
    max: End::Closed(0.01),
    unit: "",
};
/// Bandwidth of the sub-lights wide SRBF lights are split into (20 and up: none split).
pub const SHADOW_SPLIT_BANDWIDTH: Range = Range {
    name: "shadows.split_bandwidth",
    min: End::Closed(0.25),
    max: End::Closed(1000.0),
    unit: "",
};
/// Bandwidth of the cells lights are merged in for multiple scattering (0: none merged).
pub const SHADOW_MERGE_BANDWIDTH: Range = Range {
    name: "shadows.merge_bandwidth",
    min: End::Closed(0.0),
    max: End::Closed(4.0),
    unit: "",
};
/// Rotation of the environment about the up axis, degrees.
pub const ENV_ROTATE_DEG: Range = Range {
    name: "env_rotate_deg",
    min: End::Closed(-360.0),
    max: End::Closed(360.0),
    unit: " degrees",
};

/// `[a, b, c]` and nothing else: serde's fixed-size arrays read the first three numbers of a
/// longer list and drop the rest without a word.
pub fn exactly_three<'de, D: Deserializer<'de>>(d: D) -> Result<[f64; 3], D::Error> {
    let values = Vec::<f64>::deserialize(d)?;
    <[f64; 3]>::try_from(values.as_slice()).map_err(|_| {
        serde::de::Error::invalid_length(values.len(), &"three numbers [r, g, b] or [x, y, z]")
    })
}

/// [`exactly_three`] for an optional key.
pub fn maybe_three<'de, D: Deserializer<'de>>(d: D) -> Result<Option<[f64; 3]>, D::Error> {
    exactly_three(d).map(Some)
}

impl SceneSpec {
    /// Reads a TOML scene file; missing keys keep their defaults.
    pub fn from_toml_file(path: &Path) -> Result<Self, SceneError> {
        let text = cuticle_light::file::read_regular_text(path, cuticle_light::file::MAX_TEXT_FILE)
            .map_err(|source| SceneError::Read {
                path: path.into(),
                source,
            })?;
        toml::from_str(&text).map_err(|e| SceneError::Toml {
            path: path.into(),
            at: e
                .span()
                .map(|span| line_and_column(&text, span.start))
                .unwrap_or_default(),
            message: e.message().trim().replace('\n', "; "),
        })
    }

    /// Checks every number against its range, each named by its scene key.
    pub fn validate(&self) -> Result<(), SceneError> {
        self.hair.validate().map_err(SceneError::Hair)?;
        SIZE.named("width").check_usize(self.width)?;
        SIZE.named("height").check_usize(self.height)?;
        QUADRATURE.check_usize(self.quadrature)?;
        SUPERSAMPLING.check_usize(self.supersampling)?;
        BRUTE_GRID.check_usize(self.brute_grid)?;
        SHADOW_RESOLUTION.check_usize(self.shadows.resolution)?;
        SHADOW_DENSITY.check(self.shadows.density)?;
        SHADOW_CUTOFF.check(self.shadows.cutoff)?;
        SHADOW_SPLIT_BANDWIDTH.check(self.shadows.split_bandwidth)?;
        SHADOW_MERGE_BANDWIDTH.check(self.shadows.merge_bandwidth)?;
        LIGHTS.check_usize(self.lights)?;
        if self.groom.parse::<Preset>().is_ok() {
            STRANDS.check_usize(self.strands)?;
        }
        ENV_ROTATE_DEG.check(self.env_rotate_deg)?;
        if self.lobes != Lobes::ALL && self.method == Method::Path {
            return Err(SceneError::Invalid(
                "lobes (per-lobe debug views) apply to the srbf and brute methods, not path".into(),
            ));
        }
        if let Some(camera) = &self.camera {
            camera.validate()?;
        }
        Ok(())
    }
}

/// ` line L column C` of byte `offset` in `text` (1-based).
fn line_and_column(text: &str, offset: usize) -> String {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    format!(" line {line} column {column}")
}

/// A loaded scene.
#[derive(Clone, Debug)]
pub struct Scene {
    pub spec: SceneSpec,
    pub groom: Groom,
    pub env: EnvMap,
    /// SRBF lights (light-crate space, +y up).
    pub lights: Vec<SrbfLight>,
    pub camera: Camera,
    /// Seconds spent fitting the SRBF lights (0 when read from a file).
    pub fit_seconds: f64,
    /// Relative L2 error of the fit, when fitted.
    pub fit_error: Option<f64>,
    /// Whether the lights were fitted now or read from the fit cache
    /// ([`cuticle_light::FitCache`]); `None` when given (a lights file) or not needed.
    pub fit_source: Option<FitSource>,
}

impl Scene {
    /// Loads the groom (its long segments split for shading, [`resample`]) and environment
    /// and fits the lights, unless `lights` are given (read by the caller from a `lights.json`
    /// of `cuticle env fit`).
    pub fn load(spec: SceneSpec, lights: Option<Vec<SrbfLight>>) -> Result<Self, SceneError> {
        spec.validate()?;
        if let Some(lights) = &lights {
            cuticle_light::validate_lights(lights)?;
        }
        Self::load_lit(spec, lights)
    }

    /// As [`Scene::load`], without SRBF lights: for the path tracer, which samples the map
    /// itself (`--method path`).
    pub fn load_without_lights(spec: SceneSpec) -> Result<Self, SceneError> {
        spec.validate()?;
        Self::load_lit(spec, Some(Vec::new()))
    }

    fn load_lit(spec: SceneSpec, lights: Option<Vec<SrbfLight>>) -> Result<Self, SceneError> {
        let mut groom = load_groom(&spec.groom, spec.strands)?;
        if spec.shading_points {
            groom = resample::shading_points(groom);
        }
        if let Some(path) = &spec.strand_absorption {
            groom = groom
                .with_strand_absorption(path)
                .map_err(|e| SceneError::Groom(format!("strand absorption {path}: {e}")))?;
        }
        validate_strands(&spec, &groom)?;
        let env = load_env(&spec.env)?.with_rotation(spec.env_rotate_deg.to_radians());
        let start = Instant::now();
        let mut fit_source = None;
        let (lights, fit_error) = match lights {
            Some(lights) => (lights, None),
            None => {
                let options = FitOptions {
                    lights: spec.lights,
                    ..FitOptions::default()
                };
                let cache = FitCache::from_env();
                let (report, source) =
                    fit_srbf_cached(&env, &options, cache.as_ref(), &mut |_| {})?;
                fit_source = Some(source);
                (report.lights, Some(report.relative_l2))
            }
        };
        let mut scene = Self::assemble(
            spec,
            groom,
            env,
            lights,
            start.elapsed().as_secs_f64(),
            fit_error,
        );
        scene.fit_source = fit_source;
        Ok(scene)
    }

    /// A scene from parts already in memory (tests, benchmarks).
    pub fn from_parts(spec: SceneSpec, groom: Groom, env: EnvMap, lights: Vec<SrbfLight>) -> Self {
        Self::assemble(spec, groom, env, lights, 0.0, None)
    }

    fn assemble(
        spec: SceneSpec,
        groom: Groom,
        env: EnvMap,
        lights: Vec<SrbfLight>,
        fit_seconds: f64,
        fit_error: Option<f64>,
    ) -> Self {
        let camera = spec.camera.unwrap_or_else(|| {
            if groom.point_count() == 0 {
                Camera::framing(Vec3::splat(-10.0), Vec3::splat(10.0), true)
            } else {
                let b = groom.bounds();
                Camera::framing(b.min, b.max, true)
            }
        });
        Self {
            spec,
            groom,
            env,
            lights,
            camera,
            fit_seconds,
            fit_error,
            fit_source: None,
        }
    }

    /// Environment radiance arriving from world direction `dir`.
    pub fn env_radiance(&self, dir: DVec3) -> DVec3 {
        self.env.radiance(world_to_light(dir).as_vec3()).as_dvec3()
    }
}

/// Every strand's own absorption (from the groom's appearance) within the fiber's ranges, so
/// shading never meets parameters the exact model refuses.
fn validate_strands(spec: &SceneSpec, groom: &Groom) -> Result<(), SceneError> {
    if spec.hair.mu_a.is_some() {
        return Ok(());
    }
    for (s, appearance) in groom.appearance().iter().enumerate() {
        spec.hair
            .fiber(Some(appearance))
            .validate()
            .map_err(|e| SceneError::Groom(format!("strand {s}'s absorption: {e}")))?;
    }
    Ok(())
}

/// The environment a scene names: `constant:R,G,B` (or `constant:V`) is a uniform map of that
/// radiance (each channel finite and ≥ 0); anything else goes to the light crate's
/// [`load_or_default`].
pub fn load_env(spec: &str) -> Result<EnvMap, SceneError> {
    let Some(values) = spec.strip_prefix("constant:") else {
        return Ok(load_or_default(spec)?);
    };
    let bad = || {
        SceneError::Invalid(format!(
            "environment {spec}: constant takes one radiance or R,G,B, each finite and in \
             [0, {MAX_RADIANCE:e}]"
        ))
    };
    let parsed: Vec<f32> = values
        .split(',')
        .map(|v| v.trim().parse::<f32>().map_err(|_| bad()))
        .collect::<Result<_, _>>()?;
    let rgb = match parsed.as_slice() {
        [v] => Vec3::splat(*v),
        [r, g, b] => Vec3::new(*r, *g, *b),
        _ => return Err(bad()),
    };
    if !(rgb.is_finite() && rgb.min_element() >= 0.0 && rgb.max_element() <= MAX_RADIANCE as f32) {
        return Err(bad());
    }
    Ok(EnvMap::new(16, 8, vec![rgb; 16 * 8]))
}

/// A preset name, or a groom file: `.hair` or USD (`.usda`, `.usdc`, `.usdz`), by
/// [`Groom::read`].
pub fn load_groom(spec: &str, strands: usize) -> Result<Groom, SceneError> {
    match spec.parse::<Preset>() {
        Ok(preset) => {
            let params = GroomParams {
                strands,
                ..preset.params()
            };
            generate(&params).map_err(|e| SceneError::Groom(e.to_string()))
        }
        Err(_) => Groom::read(spec).map_err(|e| SceneError::Groom(format!("{spec}: {e}"))),
    }
}

/// Light-crate direction (+y up) → world (+z up): (x, y, z) ↦ (x, −z, y).
pub fn light_to_world(d: DVec3) -> DVec3 {
    DVec3::new(d.x, -d.z, d.y)
}

/// World direction → light-crate direction, the inverse of [`light_to_world`].
pub fn world_to_light(d: DVec3) -> DVec3 {
    DVec3::new(d.x, d.z, -d.y)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn constant_environments_parse_and_bad_ones_are_refused() {
        let env = load_env("constant:0.5,1,2").unwrap();
        assert_eq!(env.radiance(Vec3::Y), Vec3::new(0.5, 1.0, 2.0));
        assert_eq!(load_env("constant:1").unwrap().radiance(Vec3::X), Vec3::ONE);
        for bad in [
            "constant:",
            "constant:1,2",
            "constant:-1",
            "constant:nan",
            "constant:a,b,c",
        ] {
            assert!(
                matches!(load_env(bad), Err(SceneError::Invalid(_))),
                "{bad}"
            );
        }
    }
}
