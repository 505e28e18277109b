//! The benchmark on a tiny scene: it runs, and its medians are finite, positive and consistent
//! (a re-render, which skips drawing and shadows, costs no more than a full frame, up to the
//! timer noise of a loaded machine: shading a different absorption takes a little longer or
//! shorter, so the bound has 25% slack).

use cuticle_groom::procedural::{GroomParams, Preset, generate};
use cuticle_light::{EnvMap, SrbfLight, evaluate_lights};
use cuticle_render::bench::{self, BenchReport};
use cuticle_render::{Renderer, Scene, SceneSpec, ShadowOptions};
use glam::Vec3;

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

fn stages(report: &BenchReport) -> [f64; 6] {
    let (f, r) = (&report.full, &report.rerender);
    [
        f.drawing, f.shadows, f.shading, f.resolve, r.shading, r.resolve,
    ]
}

#[test]
fn bench_reports_consistent_medians() {
    let report = bench::run(&Renderer::new(), &tiny_scene(), 3);
    assert_eq!(report.frames, 3);
    assert!(report.visible_points > 0, "the tiny groom must be visible");
    assert!(stages(&report).iter().all(|s| s.is_finite() && *s >= 0.0));
    assert!(report.full_frame > 0.0 && report.rerender_frame > 0.0);
    let f = &report.full;
    let full_sum = f.drawing + f.shadows + f.shading + f.resolve;
    assert!((report.full_frame - full_sum).abs() < 1e-12);
    assert_eq!(report.rerender.drawing, 0.0, "a re-render draws nothing");
    assert_eq!(
        report.rerender.shadows, 0.0,
        "a re-render keeps the shadows"
    );
    assert!(
        report.rerender_frame <= 1.25 * report.full_frame,
        "re-render {} s > full frame {} s",
        report.rerender_frame,
        report.full_frame
    );
}

#[test]
fn absorption_edit_changes_only_absorption() {
    let scene = tiny_scene();
    let a = bench::with_absorption_edit(&scene, 0);
    let b = bench::with_absorption_edit(&scene, 1);
    assert_ne!(a.spec.hair.mu_a, b.spec.hair.mu_a);
    let mut back = a.spec.clone();
    back.hair.mu_a = scene.spec.hair.mu_a;
    assert_eq!(back, scene.spec);
}
