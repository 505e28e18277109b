//! Dual-scattering multiple scattering end to end, on tiny scenes (each well under a second in
//! release, the brute force's a few): it adds energy, more for lighter hair, in the SRBF render
//! and in the brute force; the two stay within stated bands of each other under a narrow light
//! and under a wide one at the fibers' axis; it is off when `multiple` is; an isolated strand
//! gets no global term.

mod common;

use common::renderer;
use cuticle_groom::procedural::{GroomParams, Preset, generate};
use cuticle_groom::{Groom, GroomParts};
use cuticle_light::{EnvMap, SrbfLight, evaluate_lights};
use cuticle_render::{Image, Method, Prepared, Renderer, Scene, SceneSpec, ShadowOptions};
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
            ..ShadowOptions::default()
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

/// Multiple scattering adds energy (never removes any), and a lighter fiber (μ_a = 0.1) gains
/// more, relative to its single scattering, than a darker one (μ_a = 1.5).
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
/// neighbouring segments, which takes a share `lost` of its single scattering (measured
/// 0.154 here: 64 texels, a strand 0.6 texels thick). Forward scattering can only give back
/// part of what the map took, d_f (e^{−n(1−ā_f)} − e^{−n}) < 1 − e^{−n}: its global gain stays
/// below `lost` (measured 0.127), where a global term that did not remove the direct share,
/// d_f T_f, would add about 0.7 of the single scattering. (Forward scattering once subtracted
/// half a crossing for a point's own strand, which hid the map's self-shadowing here but
/// took the global term from every point of a real groom: tests/slab.rs.)
#[test]
fn isolated_strand_gets_back_at_most_what_its_self_shadowing_took() {
    let strand = Groom::from_parts(GroomParts {
        positions: (0..12)
            .map(|i| Vec3::new(0.2 * i as f32 - 1.1, 0.0, 0.0))
            .collect(),
        thickness: vec![0.02; 12],
        strand_offsets: vec![0, 12],
        ..GroomParts::default()
    })
    .unwrap();
    let mut unshadowed = spec(false, 0.05);
    unshadowed.shadows.density = 0.0;
    let lost = 1.0
        - total(&render(spec(false, 0.05), strand.clone()))
            / total(&render(unshadowed, strand.clone()));
    let alone = global_gain(strand);
    eprintln!("isolated strand: self-shadowing takes {lost:.3}, global term gives {alone:.3}");
    assert!(lost > 0.0 && lost < 0.5, "lost {lost}");
    assert!(alone > 0.0 && alone < lost, "alone {alone}, lost {lost}");
}

/// The brute force's scene: the environment the lights describe, as 6 n² directional lights.
fn brute_scene(mut spec: SceneSpec, groom: Groom, lights: Vec<SrbfLight>, n: usize) -> Scene {
    spec.method = Method::Brute;
    spec.brute_grid = n;
    let env = EnvMap::from_fn(128, 64, |d| evaluate_lights(&lights, d).as_vec3());
    Scene::from_parts(spec, groom, env, lights)
}

/// Per visible point: (single scattering, multiple scattering alone) of `scene`'s hair with
/// absorption `mu_a`, re-shading one preparation.
fn single_and_multiple(
    r: &Renderer,
    scene: &Scene,
    prepared: &Prepared,
    mu_a: f64,
) -> (Vec<f64>, Vec<f64>) {
    let mut scene = scene.clone();
    scene.spec.hair.mu_a = Some([mu_a; 3]);
    let mut shade = |multiple| {
        scene.spec.multiple = multiple;
        r.shade(&scene, prepared)
    };
    let (on, off) = (shade(true), shade(false));
    let single = off.iter().map(|c| c.element_sum()).collect();
    let multiple = on
        .iter()
        .zip(&off)
        .map(|(a, b)| (*a - *b).element_sum())
        .collect();
    (single, multiple)
}

/// The brute force's multiple scattering (exact functions, directional lights: 6 · 6² here)
/// adds energy at every point, never removes any, and adds more, relative to single
/// scattering, to lighter hair (measured gains 0.116 for μ_a = 0.1, 0.0019 for μ_a = 1.5).
#[test]
fn brute_force_multiple_scattering_adds_more_to_lighter_hair() {
    let r = renderer();
    let scene = brute_scene(spec(true, 0.1), groom(400), lights(), 6);
    let (_, prepared, _) = r.render(&scene);
    let gain = |mu: f64| {
        let (single, multiple) = single_and_multiple(r, &scene, &prepared, mu);
        assert!(
            multiple.iter().all(|&m| m >= -1e-9),
            "multiple scattering removed energy"
        );
        multiple.iter().sum::<f64>() / single.iter().sum::<f64>()
    };
    let (light, dark) = (gain(0.1), gain(1.5));
    eprintln!("brute-force gains: light {light:.4}, dark {dark:.4}");
    assert!(dark > 0.0, "dark gain {dark}");
    assert!(light > 2.0 * dark, "light gain {light}, dark gain {dark}");
}

/// Multiple scattering alone, SRBF against brute force (6 · 10² lights), on light hair
/// (μ_a = 0.1) with shadows of `density`, under one light: (relative RMSE over visible
/// points, SRBF total / brute total).
fn srbf_against_brute_multiple(light: SrbfLight, density: f64) -> (f64, f64) {
    let r = renderer();
    let mut s = spec(true, 0.1);
    s.shadows.density = density;
    let srbf = Scene::from_parts(
        s.clone(),
        groom(400),
        EnvMap::from_fn(64, 32, |_| Vec3::ZERO),
        vec![light],
    );
    let brute = brute_scene(s, groom(400), vec![light], 10);
    let (_, ps, _) = r.render(&srbf);
    let (_, pb, _) = r.render(&brute);
    assert_eq!(ps.points, pb.points);
    let (_, a) = single_and_multiple(r, &srbf, &ps, 0.1);
    let (_, b) = single_and_multiple(r, &brute, &pb, 0.1);
    let num: f64 = a.iter().zip(&b).map(|(x, y)| (x - y).powi(2)).sum();
    let den: f64 = b.iter().map(|y| y * y).sum();
    (
        (num / den).sqrt(),
        a.iter().sum::<f64>() / b.iter().sum::<f64>(),
    )
}

/// Under the key light (λ = 0.35) with dense shadows (density 3, so the global term
/// dominates), relative RMSE below 0.65 (measured 0.47) and the SRBF's total within 30 % of
/// the brute force's (measured 17 % below). They
/// differ by design in the azimuthal functions (circular-Gaussian fits against exact), in one
/// σ̄_f for all channels against one each, and in T̃ (the SRBF light's filtered opacity against
/// each directional light's own), which forward scattering reads.
#[test]
fn srbf_multiple_scattering_matches_brute_force_under_a_narrow_light() {
    let (rmse, ratio) = srbf_against_brute_multiple(lights()[0], 3.0);
    eprintln!(
        "key light, multiple scattering alone: relative RMSE {rmse:.4}, SRBF / brute {ratio:.4}"
    );
    assert!(rmse < 0.65, "relative RMSE {rmse}");
    assert!((ratio - 1.0).abs() < 0.3, "SRBF / brute energy {ratio}");
}

/// Under a light of medium width (λ = 0.3) above the hanging hair, shadows of density 1, the
/// SRBF's multiple scattering is within 5 % of the brute force's in total (measured 0.7 %
/// above) and its relative RMSE below 0.1 (measured 0.069): the whole dual-scattering path
/// agrees tightly where a light is narrow enough for its Gaussians. (Xu et al. 2011's 1/cos θ_j
/// normalisation gives 0.997 and 0.077 here: it fails only for wide lights, the next test.)
/// The agreement loosens as the light widens: 0.956 and 0.10 at λ = 0.6; at 1.2, the next test.
#[test]
fn srbf_multiple_scattering_matches_brute_force_under_a_light_on_the_axis() {
    let light = SrbfLight::new(Vec3::new(0.0, 1.0, 0.0), 0.3, Vec3::new(0.4, 0.5, 0.8));
    let (rmse, ratio) = srbf_against_brute_multiple(light, 1.0);
    eprintln!(
        "light on the axis, multiple scattering alone: relative RMSE {rmse:.4}, SRBF / brute {ratio:.4}"
    );
    assert!(rmse < 0.1, "relative RMSE {rmse}");
    assert!((ratio - 1.0).abs() < 0.05, "SRBF / brute energy {ratio}");
}

/// Under the wide sky light (λ = 1.2) centred on the fibers' axis, shadows of density 1: with
/// Xu et al. 2011's 1/cos θ_j normalisation of the spread the SRBF's multiple scattering was twice
/// the brute force's in total and its relative RMSE 2.75; with the exact normalisation
/// ([`cuticle_render::tables::spread`]) and one opacity map along the light's axis it was 0.57 of
/// it (RMSE 0.44): that map, along the strands, sees almost none of the fibers that the light's
/// lobe crosses obliquely. With the light split into sub-lights, each with its own map
/// ([`cuticle_render::frame::sub_lights`]), it agrees as tightly as a narrow light does.
#[test]
fn srbf_multiple_scattering_matches_brute_force_under_a_wide_light_at_the_axis() {
    let (rmse, ratio) = srbf_against_brute_multiple(lights()[1], 1.0);
    eprintln!(
        "sky light, multiple scattering alone: relative RMSE {rmse:.4}, SRBF / brute {ratio:.4}"
    );
    assert!(rmse < 0.1, "relative RMSE {rmse}");
    assert!((ratio - 1.0).abs() < 0.05, "SRBF / brute energy {ratio}");
}
