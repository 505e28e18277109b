//! The per-lobe debug views (`SceneSpec::lobes`): a lobe off contributes zero, so at every
//! visible point the R, TT and TRT views sum to the all-lobes single scattering, in the SRBF
//! path and the brute force alike.

mod common;

use common::renderer;
use cuticle_render::{Lobes, Method, Scene, SceneSpec, ShadowOptions, Timings};
use glam::DVec3;

fn scene(method: Method) -> Scene {
    let spec = SceneSpec {
        method,
        brute_grid: 4,
        strands: 200,
        width: 96,
        height: 64,
        supersampling: 1,
        lights: 12,
        multiple: false,
        shadows: ShadowOptions {
            resolution: 64,
            ..ShadowOptions::default()
        },
        ..SceneSpec::default()
    };
    Scene::load(spec, None).expect("the test scene loads")
}

fn only(t: usize) -> Lobes {
    let on = |k| k == t;
    Lobes {
        r: on(0),
        tt: on(1),
        trt: on(2),
    }
}

#[test]
fn single_lobes_sum_to_all_lobes() {
    for method in [Method::Srbf, Method::Brute] {
        single_lobes_sum_to_all_lobes_in(scene(method));
    }
}

fn single_lobes_sum_to_all_lobes_in(mut scene: Scene) {
    let method = scene.spec.method;
    let r = renderer();
    let prepared = r.prepare(&scene, &mut Timings::default());
    let all = r.shade(&scene, &prepared);
    let views: Vec<Vec<DVec3>> = (0..3)
        .map(|t| {
            scene.spec.lobes = only(t);
            r.shade(&scene, &prepared)
        })
        .collect();
    assert!(all.len() > 500, "{} visible points", all.len());
    let brightest = all.iter().map(|c| c.max_element()).fold(0.0, f64::max);
    for (k, want) in all.iter().enumerate() {
        let sum = views[0][k] + views[1][k] + views[2][k];
        let e = (sum - *want).abs().max_element();
        assert!(
            e <= 1e-9 * brightest,
            "{method:?} point {k}: {sum} against {want}"
        );
    }
    // Each lobe carries light of its own (an ignored mask would give three times the total).
    for (t, view) in views.iter().enumerate() {
        let share = view.iter().map(|c| c.element_sum()).sum::<f64>()
            / all.iter().map(|c| c.element_sum()).sum::<f64>();
        assert!(
            share > 1e-3 && share < 0.99,
            "{method:?} lobe {t}: share {share}"
        );
    }
}

#[test]
fn lobes_in_the_path_tracer_are_refused() {
    let spec = SceneSpec {
        method: Method::Path,
        lobes: only(1),
        ..SceneSpec::default()
    };
    let e = spec.validate().unwrap_err().to_string();
    assert!(e.contains("lobes"), "{e}");
    for method in [Method::Srbf, Method::Brute] {
        let ok = SceneSpec {
            method,
            lobes: only(1),
            ..SceneSpec::default()
        };
        ok.validate().unwrap();
    }
}
