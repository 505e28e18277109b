//! Shading again after an edit: a pass that reuses the one before shades only the points of
//! the strands whose fiber changed, and gives bit for bit the image of shading every point;
//! an edit every point reads (a hair parameter) shades them all.

mod common;

use common::tiny_scene;
use cuticle_groom::Absorption;
use cuticle_render::{Prepared, Renderer, Scene, Shaded, Timings};
use std::sync::atomic::AtomicBool;

/// `scene` with strands `0..n` painted.
fn painted(scene: &Scene, n: usize) -> Scene {
    let mut edited = scene.clone();
    for a in edited.groom.appearance_mut().iter_mut().take(n) {
        a.absorption = Some(Absorption::MuA([0.1, 2.0, 4.0]));
    }
    edited
}

/// The tiny scene, prepared and shaded once.
fn first_pass() -> (Scene, Renderer, Prepared, Shaded) {
    let scene = tiny_scene();
    let renderer = Renderer::new();
    let prepared = renderer.prepare(&scene, &mut Timings::default());
    let never = AtomicBool::new(false);
    let first = renderer
        .shade_reusing(&scene, &prepared, None, &|_, _| {}, &never)
        .unwrap();
    (scene, renderer, prepared, first)
}

/// A pass of `scene` that reuses `before`.
fn reshade(renderer: &Renderer, scene: &Scene, prepared: &Prepared, before: &Shaded) -> Shaded {
    let never = AtomicBool::new(false);
    renderer
        .shade_reusing(scene, prepared, Some(before), &|_, _| {}, &never)
        .unwrap()
}

#[test]
fn a_paint_stroke_shades_only_its_strands_points_and_changes_nothing_else() {
    let (scene, renderer, prepared, first) = first_pass();
    assert_eq!(first.points_shaded, prepared.points.len());

    let stroke = painted(&scene, 20);
    let again = reshade(&renderer, &stroke, &prepared, &first);
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

    let same = reshade(&renderer, &stroke, &prepared, &again);
    assert_eq!(same.points_shaded, 0, "nothing changed, nothing shaded");
    assert_eq!(same.colours, every);
}

#[test]
fn a_hair_parameter_edit_shades_every_point() {
    let (scene, renderer, prepared, first) = first_pass();
    let mut edited = scene.clone();
    edited.spec.hair.d_b *= 0.5;
    let again = reshade(&renderer, &edited, &prepared, &first);
    assert_eq!(again.points_shaded, prepared.points.len());
    assert_eq!(again.colours, renderer.shade(&edited, &prepared));
}
