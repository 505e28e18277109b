//! The shading stage reports its progress: one report is every visible point, every count lies
//! within the total, and reporting leaves the image unchanged.

use cuticle_groom::procedural::{GroomParams, Preset, generate};
use cuticle_light::{EnvMap, SrbfLight, evaluate_lights};
use cuticle_render::{Renderer, Scene, SceneSpec, ShadowOptions};
use glam::Vec3;
use std::sync::Mutex;

fn tiny_scene() -> Scene {
    let lights = vec![SrbfLight::new(
        Vec3::new(0.6, 0.5, -0.6),
        0.35,
        Vec3::new(6.0, 5.0, 4.0),
    )];
    let env = EnvMap::from_fn(64, 32, |d| evaluate_lights(&lights, d).as_vec3());
    let groom = generate(&GroomParams {
        strands: 300,
        ..Preset::Straight.params()
    })
    .unwrap();
    let spec = SceneSpec {
        width: 64,
        height: 48,
        supersampling: 2,
        shadows: ShadowOptions {
            resolution: 32,
            ..ShadowOptions::default()
        },
        ..SceneSpec::default()
    };
    Scene::from_parts(spec, groom, env, lights)
}

#[test]
fn render_reports_every_visible_point() {
    let scene = tiny_scene();
    let renderer = Renderer::new();
    let seen = Mutex::new(Vec::new());
    let report = |done: usize, total: usize| seen.lock().unwrap().push((done, total));
    let (image, prepared, _) = renderer.render_with_progress(&scene, &report);
    let seen = seen.into_inner().unwrap();
    let n = prepared.points.len();
    assert!(n > 0, "the tiny groom must be visible");
    assert!(seen.iter().all(|&(_, total)| total == n));
    assert!(seen.iter().any(|&(done, _)| done == n), "no final report");
    assert!(seen.iter().all(|&(done, _)| done >= 1 && done <= n));
    assert_eq!(image, renderer.render(&scene).0);
}
