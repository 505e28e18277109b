//! A scene: groom, environment and its SRBF fit, camera, hair parameters and image settings,
//! from a TOML file and/or flags ([`SceneSpec`]), loaded into memory ([`Scene`]).
//!
//! Spaces: the groom's (+z up, as procedural grooms and cyHair models) is world space; the
//! light crate's directions are +y up, turned into world space by [`light_to_world`].

pub mod camera;
pub mod hair;
pub mod resample;

use crate::frame::shadow::ShadowOptions;
use crate::scene::camera::Camera;
use crate::scene::hair::HairParams;
use cuticle_groom::Groom;
use cuticle_groom::procedural::{GroomParams, Preset, generate};
use cuticle_light::{EnvMap, FitOptions, SrbfLight, fit_srbf, load_or_default};
use glam::{DVec3, Vec3};
use serde::{Deserialize, Serialize};
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
            supersampling: 3,
            shadows: ShadowOptions::default(),
            brute_grid: 16,
        }
    }
}

/// Why a scene cannot be loaded.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    #[error("cannot read scene file {path}: {source}")]
    Read {
        path: PathBuf,
        source: std::io::Error,
    },
    #[error("scene file {path}: {source}")]
    Toml {
        path: PathBuf,
        source: toml::de::Error,
    },
    #[error("groom: {0}")]
    Groom(String),
    #[error("environment: {0}")]
    Light(#[from] cuticle_light::LightError),
    #[error(transparent)]
    Hair(#[from] crate::scene::hair::HairParamError),
    #[error("{0}")]
    Invalid(String),
}

impl SceneSpec {
    /// Reads a TOML scene file; missing keys keep their defaults.
    pub fn from_toml_file(path: &Path) -> Result<Self, SceneError> {
        let text = std::fs::read_to_string(path).map_err(|source| SceneError::Read {
            path: path.into(),
            source,
        })?;
        toml::from_str(&text).map_err(|source| SceneError::Toml {
            path: path.into(),
            source,
        })
    }

    /// Checks the numbers that are not checked where they are used.
    pub fn validate(&self) -> Result<(), SceneError> {
        self.hair.validate()?;
        let bad = |m: &str| Err(SceneError::Invalid(m.into()));
        if self.width == 0 || self.height == 0 || self.width > 16384 || self.height > 16384 {
            return bad("width and height must lie in 1..=16384");
        }
        if !(2..=crate::srbf::quadrature::MAX_SEGMENTS).contains(&self.quadrature) {
            return bad("quadrature (segments m) must lie in 2..=256");
        }
        if !(1..=8).contains(&self.supersampling) {
            return bad("supersampling must lie in 1..=8");
        }
        if !(1..=64).contains(&self.brute_grid) {
            return bad("brute_grid must lie in 1..=64");
        }
        if !(8..=4096).contains(&self.shadows.resolution)
            || self.shadows.density.is_nan()
            || self.shadows.density < 0.0
        {
            return bad("shadow resolution must lie in 8..=4096 and density be ≥ 0");
        }
        if !(0.0..=0.01).contains(&self.shadows.cutoff) {
            return bad("shadow cutoff must lie in [0, 0.01]");
        }
        if self.lights == 0 {
            return bad("lights must be at least 1");
        }
        Ok(())
    }
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
}

impl Scene {
    /// Loads the groom (its long segments split for shading, [`resample`]) and environment
    /// and fits the lights, unless `lights` are given (read by the caller from a `lights.json`
    /// of `cuticle env fit`).
    pub fn load(spec: SceneSpec, lights: Option<Vec<SrbfLight>>) -> Result<Self, SceneError> {
        spec.validate()?;
        let groom = resample::split_long_segments(load_groom(&spec.groom, spec.strands)?);
        let env = load_env(&spec.env)?.with_rotation(spec.env_rotate_deg.to_radians());
        let start = Instant::now();
        let (lights, fit_error) = match lights {
            Some(lights) => (lights, None),
            None => {
                let report = fit_srbf(
                    &env,
                    &FitOptions {
                        lights: spec.lights,
                        ..FitOptions::default()
                    },
                )?;
                (report.lights, Some(report.relative_l2))
            }
        };
        Ok(Self::assemble(
            spec,
            groom,
            env,
            lights,
            start.elapsed().as_secs_f64(),
            fit_error,
        ))
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
        }
    }

    /// Environment radiance arriving from world direction `dir`.
    pub fn env_radiance(&self, dir: DVec3) -> DVec3 {
        self.env.radiance(world_to_light(dir).as_vec3()).as_dvec3()
    }
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
            "environment {spec}: constant takes one radiance or R,G,B, each finite and >= 0"
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
    if !(rgb.is_finite() && rgb.min_element() >= 0.0) {
        return Err(bad());
    }
    Ok(EnvMap::new(16, 8, vec![rgb; 16 * 8]))
}

/// A preset name or a `.hair` path.
pub fn load_groom(spec: &str, strands: usize) -> Result<Groom, SceneError> {
    match spec.parse::<Preset>() {
        Ok(preset) => {
            let params = GroomParams {
                strands,
                ..preset.params()
            };
            generate(&params).map_err(|e| SceneError::Groom(e.to_string()))
        }
        Err(_) => Groom::read_hair(spec).map_err(|e| SceneError::Groom(format!("{spec}: {e}"))),
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
