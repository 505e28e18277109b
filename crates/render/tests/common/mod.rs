//! Helpers shared by the renderer's integration tests.

use cuticle_groom::procedural::{GroomParams, Preset, generate};
use cuticle_groom::{Groom, GroomParts};
use cuticle_light::{EnvMap, SrbfLight, evaluate_lights};
use cuticle_render::{Renderer, Scene, SceneSpec, ShadowOptions};
use glam::Vec3;
use std::sync::OnceLock;

/// One renderer (its parameter-independent tables) for every test in a binary.
#[allow(dead_code)] // not every test binary uses it
pub fn renderer() -> &'static Renderer {
    static R: OnceLock<Renderer> = OnceLock::new();
    R.get_or_init(Renderer::new)
}

/// Segments per strand of [`block`].
#[allow(dead_code)] // not every test binary uses it
pub const SEGMENTS: usize = 15;

/// 40 × 40 strands 0.22 apart (jittered), hanging from z = 10, 5 to 10 units long (the hair
/// thins toward the bottom, as where a groom's strands end at different lengths); segments
/// just short enough for `split_long_segments` to keep them whole, as in straight.hair.
#[allow(dead_code)] // not every test binary uses it
pub fn block() -> Groom {
    let mut positions = Vec::new();
    let mut strand_offsets = vec![0];
    let jitter = |k: u32| (k.wrapping_mul(2_654_435_761) >> 8) as f32 / (1u32 << 24) as f32 - 0.5;
    for i in 0..40u32 {
        for j in 0..40u32 {
            let x = (i as f32 - 19.5) * 0.22 + 0.18 * jitter(i * 40 + j);
            let y = (j as f32 - 19.5) * 0.22 + 0.18 * jitter(i * 40 + j + 7919);
            let length = 7.5 + 5.0 * jitter(i * 40 + j + 104_729);
            for k in 0..=SEGMENTS {
                let z = 10.0 - length * k as f32 / SEGMENTS as f32;
                positions.push(Vec3::new(x, y, z));
            }
            strand_offsets.push(positions.len() as u32);
        }
    }
    Groom::from_parts(GroomParts {
        thickness: vec![0.25; positions.len()],
        positions,
        strand_offsets,
        ..GroomParts::default()
    })
    .unwrap()
}

/// A tiny scene of the default groom's kind: 200 strands, 48 × 32 at 2 × 2 subsamples, a key
/// light and a wide sky light (so sub-lights are split), 32-texel opacity maps.
#[allow(dead_code)] // not every test binary uses it
pub fn tiny_scene() -> Scene {
    let lights = vec![
        SrbfLight::new(Vec3::new(0.6, 0.5, -0.6), 0.35, Vec3::new(6.0, 5.0, 4.0)),
        SrbfLight::new(Vec3::new(0.0, 1.0, 0.0), 1.2, Vec3::new(0.4, 0.5, 0.8)),
    ];
    let env = EnvMap::from_fn(64, 32, |d| evaluate_lights(&lights, d).as_vec3());
    let groom = generate(&GroomParams {
        strands: 200,
        ..Preset::Straight.params()
    })
    .unwrap();
    let spec = SceneSpec {
        width: 48,
        height: 32,
        supersampling: 2,
        multiple: true,
        shadows: ShadowOptions {
            resolution: 32,
            ..ShadowOptions::default()
        },
        ..SceneSpec::default()
    };
    Scene::from_parts(spec, groom, env, lights)
}
