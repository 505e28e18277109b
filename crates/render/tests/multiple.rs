//! Dual-scattering multiple scattering end to end, on tiny scenes (each well under a second in
//! release): it adds energy, more for lighter hair; it is off when `multiple` is; an isolated
//! strand gets no global term.

mod common;

use common::renderer;
use cuticle_groom::procedural::{GroomParams, Preset, generate};
use cuticle_groom::{Groom, GroomParts};
use cuticle_light::{EnvMap, SrbfLight};
use cuticle_render::{Image, Method, Scene, SceneSpec, ShadowOptions};
use glam::Vec3;

fn lights() -> Vec<SrbfLight> {
    vec![
        SrbfLight::new(Vec3::new(0.6, 0.5, -0.6), 0.35, Vec3::new(6.0, 5.0, 4.0)),
        SrbfLight::new(Vec3::new(0.0, 1.0, 0.0), 1.2, Vec3::new(0.4, 0.5, 0.8)),
    ]
}

fn spec(multiple: bool, mu_a: f64) -> SceneSpec {
    let mut s = SceneSpec {
        width: 64,
        height: 48,
        supersampling: 2,
        method: Method::Srbf,
        multiple,
        shadows: ShadowOptions {
            resolution: 64,
            density: 1.0,
        },
        ..SceneSpec::default()
    };
    s.hair.mu_a = Some([mu_a; 3]);
    s
}

fn groom(strands: usize) -> Groom {
    generate(&GroomParams {
        strands,
        ..Preset::Straight.params()
    })
    .unwrap()
}

fn render(spec: SceneSpec, groom: Groom) -> Image {
    let env = EnvMap::from_fn(64, 32, |_| Vec3::ZERO);
    renderer()
        .render(&Scene::from_parts(spec, groom, env, lights()))
        .0
}

fn total(img: &Image) -> f64 {
    img.pixels.iter().map(|p| p.element_sum()).sum()
}

/// Multiple scattering adds energy (never removes any), and a lighter fiber (σ_a = 0.1) gains
/// more, relative to its single scattering, than a darker one (σ_a = 1.5).
#[test]
fn multiple_scattering_adds_more_to_lighter_hair() {
    let gain = |mu: f64| {
        let single = render(spec(false, mu), groom(400));
        let both = render(spec(true, mu), groom(400));
        for (a, b) in both.pixels.iter().zip(&single.pixels) {
            assert!((*a - *b).min_element() >= -1e-9, "{a} < {b}");
        }
        total(&both) / total(&single) - 1.0
    };
    let (light, dark) = (gain(0.1), gain(1.5));
    assert!(dark > 0.0, "dark gain {dark}");
    assert!(light > 2.0 * dark, "light gain {light}, dark gain {dark}");
}

/// Turning `multiple` on changes the image; off, renders are single scattering's, repeatably.
#[test]
fn no_multiple_is_single_scattering() {
    let off = render(spec(false, 0.2), groom(200));
    let again = render(spec(false, 0.2), groom(200));
    let on = render(spec(true, 0.2), groom(200));
    assert_eq!(off, again);
    assert!(total(&on) > total(&off) * 1.01);
}

/// Global multiple-scattering gain (d_b = 0, so no local term) of `groom`, relative to its
/// single scattering.
fn global_gain(groom: Groom) -> f64 {
    let mut with = spec(true, 0.05);
    with.hair.d_b = 0.0;
    let single = total(&render(spec(false, 0.05), groom.clone()));
    assert!(single > 0.0);
    total(&render(with, groom)) / single - 1.0
}

/// One straight strand alone, across the lights: nothing lies between it and any light, so
/// T_f − T̃ vanishes up to the deep opacity map's self-shadowing of a strand by its own
/// neighbouring segments: its global gain stays under 2% of its single scattering (a global
/// term that did not remove the direct share, d_f T_f, would add tens of percent).
#[test]
fn isolated_strand_gets_almost_no_global_multiple_scattering() {
    let strand = Groom::from_parts(GroomParts {
        positions: (0..12)
            .map(|i| Vec3::new(0.2 * i as f32 - 1.1, 0.0, 0.0))
            .collect(),
        thickness: vec![0.02; 12],
        strand_offsets: vec![0, 12],
        ..GroomParts::default()
    })
    .unwrap();
    let alone = global_gain(strand);
    assert!((0.0..0.02).contains(&alone), "alone {alone}");
}
