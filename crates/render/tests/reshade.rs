//! Shading again after an edit: a pass that reuses the one before shades only the points of
//! the strands whose fiber changed, and gives bit for bit the image of shading every point;
//! an edit every point reads (a hair parameter) shades them all.

use cuticle_groom::Absorption;
use cuticle_groom::procedural::{GroomParams, Preset, generate};
use cuticle_light::{EnvMap, SrbfLight, evaluate_lights};
use cuticle_render::{Renderer, Scene, SceneSpec, ShadowOptions, Timings};
use glam::Vec3;
use std::sync::atomic::AtomicBool;

fn tiny_scene() -> Scene {
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

/// `scene` with strands `0..n` painted.
fn painted(scene: &Scene, n: usize) -> Scene {
    let mut edited = scene.clone();
    for a in edited.groom.appearance_mut().iter_mut().take(n) {
        a.absorption = Some(Absorption::MuA([0.1, 2.0, 4.0]));
    }
    edited
}

#[test]
fn a_paint_stroke_shades_only_its_strands_points_and_changes_nothing_else() {
    let scene = tiny_scene();
    let renderer = Renderer::new();
    let never = AtomicBool::new(false);
    let prepared = renderer.prepare(&scene, &mut Timings::default());
    let first = renderer
        .shade_reusing(&scene, &prepared, None, &|_, _| {}, &never)
        .unwrap();
    assert_eq!(first.points_shaded, prepared.points.len());

    let stroke = painted(&scene, 20);
    let again = renderer
        .shade_reusing(&stroke, &prepared, Some(&first), &|_, _| {}, &never)
        .unwrap();
    let on_painted = prepared
        .points
        .iter()
        .filter(|&&p| prepared.strand_of_point[p as usize] < 20)
        .count();
    assert!(on_painted > 0, "the painted strands must be visible");
    assert_eq!(again.points_shaded, on_painted);
    let every = renderer.shade(&stroke, &prepared);
    assert_eq!(again.colours, every, "reuse gives the full pass's colours");
    assert_ne!(again.colours, first.colours, "the paint shows");

    let same = renderer
        .shade_reusing(&stroke, &prepared, Some(&again), &|_, _| {}, &never)
        .unwrap();
    assert_eq!(same.points_shaded, 0, "nothing changed, nothing shaded");
    assert_eq!(same.colours, every);
}

#[test]
fn a_hair_parameter_edit_shades_every_point() {
    let scene = tiny_scene();
    let renderer = Renderer::new();
    let never = AtomicBool::new(false);
    let prepared = renderer.prepare(&scene, &mut Timings::default());
    let first = renderer
        .shade_reusing(&scene, &prepared, None, &|_, _| {}, &never)
        .unwrap();
    let mut edited = scene.clone();
    edited.spec.hair.d_b *= 0.5;
    let again = renderer
        .shade_reusing(&edited, &prepared, Some(&first), &|_, _| {}, &never)
        .unwrap();
    assert_eq!(again.points_shaded, prepared.points.len());
    assert_eq!(again.colours, renderer.shade(&edited, &prepared));
}
