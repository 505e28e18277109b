//! Preview quality (`cuticle_render::preview`): the default environment's fitted lights merged
//! into [`PREVIEW_LIGHTS`] describe it better than the strongest fitted lights did (the
//! preview before), the preview image is close to the full one at the same size, and a
//! preview renderer's parameter edit rebuilds its coarse back-scattering tables only, which
//! stay close to the full ones. A small scene: 600 strands, 120 × 90, the default map with 40
//! fitted lights.

mod common;

use common::renderer;
use cuticle_fiber::models::marschner2003::MarschnerParams;
use cuticle_light::SrbfLight;
use cuticle_render::frame::renderer::srbf_lights;
use cuticle_render::frame::sub_lights::{fibonacci_sphere, split_wide};
use cuticle_render::preview::{
    NO_SPLIT, PREVIEW_LIGHTS, PREVIEW_QUADRATURE, PREVIEW_SPLIT_BANDWIDTH, PREVIEW_TABLE_NODES,
    preview_lights, preview_scene,
};
use cuticle_render::scene::hair::HairParams;
use cuticle_render::tables::back_scattering::BackScatteringTables;
use cuticle_render::{Image, Renderer, Scene, SceneSpec, TableBuilds};
use glam::DVec3;
use std::sync::OnceLock;

fn scene() -> &'static Scene {
    static S: OnceLock<Scene> = OnceLock::new();
    S.get_or_init(|| {
        let mut spec = SceneSpec {
            strands: 600,
            width: 120,
            height: 90,
            supersampling: 1,
            ..SceneSpec::default()
        };
        spec.shadows.resolution = 128;
        Scene::load(spec, None).expect("the default scene loads")
    })
}

/// The preview's lights before they were merged: the `count` fitted lights of most energy,
/// each channel scaled to keep the fitted lights' energy (then split at the preview's width).
fn strongest(lights: &[SrbfLight], count: usize) -> Vec<SrbfLight> {
    let energy = |l: &SrbfLight| l.integral().element_sum();
    let mut kept = lights.to_vec();
    kept.sort_by(|a, b| energy(b).total_cmp(&energy(a)));
    kept.truncate(count);
    let total: DVec3 = lights.iter().map(SrbfLight::integral).sum();
    let carried: DVec3 = kept.iter().map(SrbfLight::integral).sum();
    let gain = DVec3::select(carried.cmpgt(DVec3::ZERO), total / carried, DVec3::ONE);
    kept.iter()
        .map(|l| SrbfLight {
            coefficient: (l.coefficient.as_dvec3() * gain).as_vec3(),
            ..*l
        })
        .collect()
}

/// Relative L2 error over the sphere of `model`'s radiance against `truth`'s, channels pooled.
fn radiance_error(truth: &[SrbfLight], model: &[SrbfLight]) -> f64 {
    let (mut err, mut norm) = (0.0, 0.0);
    for d in fibonacci_sphere(20_000) {
        let t = cuticle_light::evaluate_lights(truth, d);
        err += (t - cuticle_light::evaluate_lights(model, d)).length_squared();
        norm += t.length_squared();
    }
    (err / norm).sqrt()
}

/// √(Σ|a − b|² / Σ|b − bg|²) over the pixels where `b` shows hair (differs from `bg`).
fn hair_rmse(a: &Image, b: &Image, background: &[DVec3]) -> f64 {
    let (mut num, mut den) = (0.0, 0.0);
    for ((pa, pb), bg) in a.pixels.iter().zip(&b.pixels).zip(background) {
        if (*pb - *bg).length() > 1e-9 {
            num += (*pa - *pb).length_squared();
            den += (*pb - *bg).length_squared();
        }
    }
    (num / den).sqrt()
}

/// The preview scene: its size, one subsample, at most m = 2, exactly [`PREVIEW_LIGHTS`]
/// lights that the frame does not split again, with the frame's energy per channel.
#[test]
fn the_preview_scene_shades_few_merged_lights() {
    let scene = scene();
    let preview = preview_scene(scene, 3);
    preview.spec.validate().expect("a preview scene is valid");
    assert_eq!((preview.spec.width, preview.spec.height), (40, 30));
    assert_eq!(preview.spec.supersampling, 1);
    assert_eq!(
        preview.spec.quadrature,
        scene.spec.quadrature.min(PREVIEW_QUADRATURE)
    );
    assert_eq!(preview.spec.shadows.split_bandwidth, NO_SPLIT);
    let full = srbf_lights(scene);
    let shaded = srbf_lights(&preview);
    assert!(full.len() > 3 * PREVIEW_LIGHTS, "{} lights", full.len());
    assert_eq!(shaded.len(), PREVIEW_LIGHTS);
    let energy = |lights: &[SrbfLight]| -> DVec3 { lights.iter().map(SrbfLight::integral).sum() };
    let split = split_wide(&scene.lights, scene.spec.shadows.split_bandwidth);
    let (want, got) = (energy(&split), energy(&preview.lights));
    assert!(
        ((got - want) / want).abs().max_element() < 1e-5,
        "{got} vs {want}"
    );
}

/// Against the full frame's lights (the fitted ones, wide ones split), the merged lights'
/// radiance is closer than the old preview's (the 8 strongest fitted lights, split as the
/// preview splits them), and within a stated bound.
#[test]
fn merged_lights_describe_the_map_better_than_the_strongest() {
    let scene = scene();
    let full = split_wide(&scene.lights, scene.spec.shadows.split_bandwidth);
    let merged = radiance_error(&full, &preview_lights(scene));
    let old = radiance_error(
        &full,
        &split_wide(
            &strongest(&scene.lights, PREVIEW_LIGHTS),
            PREVIEW_SPLIT_BANDWIDTH,
        ),
    );
    eprintln!("radiance error against the frame's lights: merged {merged:.3}, strongest {old:.3}");
    assert!(merged < old, "merged {merged}, strongest {old}");
    assert!(merged < 0.35, "merged {merged}");
}

/// At the full frame's size, the preview (merged lights, m ≤ 2, coarse tables) is within a
/// stated bound of the full render over the hair (the old preview's error is printed beside
/// it).
#[test]
fn the_preview_image_is_close_to_the_full_image() {
    let scene = scene();
    let (full, prepared, _) = renderer().render(scene);
    let preview_renderer = renderer().for_preview();
    let (preview, _, _) = preview_renderer.render(&preview_scene(scene, 1));
    assert_eq!((preview.width, preview.height), (full.width, full.height));
    let mut old = preview_scene(scene, 1);
    old.lights = strongest(&scene.lights, PREVIEW_LIGHTS);
    old.spec.shadows.split_bandwidth = PREVIEW_SPLIT_BANDWIDTH;
    let (old, _, _) = renderer().render(&old);
    let e_preview = hair_rmse(&preview, &full, &prepared.background);
    let e_old = hair_rmse(&old, &full, &prepared.background);
    eprintln!(
        "hair relative RMSE against the full image: preview {e_preview:.3}, old preview {e_old:.3}"
    );
    let mut lights_only = preview_scene(scene, 1);
    lights_only.spec.quadrature = scene.spec.quadrature;
    let (lights_only, _, _) = renderer().render(&lights_only);
    let e_lights = hair_rmse(&lights_only, &full, &prepared.background);
    eprintln!("merged lights alone (full m, full tables): {e_lights:.3}");
    assert!(e_preview < 0.1, "preview {e_preview}, old preview {e_old}");
}

/// A β_R edit on a preview renderer builds its coarse back-scattering tables and nothing
/// else; an absorption edit builds nothing; the full renderer's tables are its own.
#[test]
fn a_preview_edit_rebuilds_only_the_coarse_tables() {
    let full = Renderer::new();
    let preview = full.for_preview();
    assert!(preview.is_preview() && !full.is_preview());
    let mut scene = preview_scene(scene(), 4);
    preview.render(&scene);
    let built = preview.table_builds();
    assert_eq!(
        built,
        TableBuilds {
            lobes: 1,
            back_scattering: 0,
            preview_back_scattering: 1
        }
    );
    scene.spec.hair.beta_r_deg += 2.0;
    preview.render(&scene);
    let after = preview.table_builds();
    assert_eq!(
        (
            after.lobes,
            after.back_scattering,
            after.preview_back_scattering
        ),
        (1, 0, 2),
        "β_R rebuilt other tables than the coarse ones"
    );
    scene.spec.hair.mu_a = Some([0.9, 1.4, 2.5]);
    preview.render(&scene);
    assert_eq!(
        preview.table_builds(),
        after,
        "an absorption edit built a table"
    );
    assert_eq!(full.table_builds(), after, "clones share the counts");
}

/// The coarse tables' averages at off-node points are close to the full tables': ā_f and Ā_b
/// within 0.02, the widths within 10 %.
#[test]
fn coarse_back_scattering_tables_are_close_to_the_full_ones() {
    let hair = HairParams::default();
    let fiber: MarschnerParams = hair.fiber(None);
    let fine = BackScatteringTables::build(&fiber);
    let coarse = BackScatteringTables::build_at(&fiber, PREVIEW_TABLE_NODES);
    let mut worst = [0.0f64; 3];
    for theta_d in [0.07, 0.33, 0.61, 0.95, 1.31] {
        for mu_a in [0.01, 0.13, 0.6, 2.2, 9.0] {
            let (f, c) = (fine.at(theta_d, mu_a), coarse.at(theta_d, mu_a));
            worst[0] = worst[0].max((f.forward - c.forward).abs());
            worst[1] = worst[1].max((f.back - c.back).abs());
            worst[2] = worst[2].max((f.back_width / c.back_width - 1.0).abs());
        }
    }
    eprintln!(
        "coarse against full: |Δā_f| {:.4}, |ΔĀ_b| {:.4}, σ̄_b ratio {:.3}",
        worst[0], worst[1], worst[2]
    );
    assert!(
        worst[0] < 0.02 && worst[1] < 0.02 && worst[2] < 0.1,
        "{worst:?}"
    );
}
