//! MIS (issue 12): on a three-layer slab under a small bright light on a dim sky, the
//! environment-only, BCSDF-only and MIS estimators agree within noise (image means within 4
//! combined standard errors), and MIS has the lowest variance (mean per-pixel variance over
//! the image). 24 × 12 pixels, 32 samples each, Marschner 2003 at the scene's defaults.

mod common;

use common::{front_camera, scene, slab, spot_env};
use cuticle_render::scene::world_to_light;
use cuticle_trace::{PathOptions, StrandModels, Strategy, TraceOptions, render};
use glam::DVec3;

#[test]
fn estimators_agree_and_mis_has_the_lowest_variance() {
    let env = spot_env(world_to_light(DVec3::new(0.3, -0.5, 0.8)));
    let s = scene(slab(3, 24, 0.1), env, 24, 12, front_camera(8.0));
    let models = StrandModels::marschner(&s).unwrap();
    let results: Vec<(Strategy, f64, f64, f64)> =
        [Strategy::Environment, Strategy::Bcsdf, Strategy::Mis]
            .into_iter()
            .map(|strategy| {
                let options = TraceOptions {
                    spp: 32,
                    seed: 11,
                    path: PathOptions {
                        strategy,
                        ..PathOptions::default()
                    },
                };
                let out = render(&s, &models, &options, &|_, _| {});
                let n = out.image.pixels.len() as f64;
                let mean = out.image.pixels.iter().map(|p| p.x).sum::<f64>() / n;
                let error = (out.standard_error.iter().map(|e| e.x * e.x).sum::<f64>()).sqrt() / n;
                let variance = out.standard_error.iter().map(|e| e.x * e.x).sum::<f64>() / n * 32.0;
                println!(
                    "{strategy:?}: mean {mean:.5} ± {error:.5}, per-pixel variance {variance:.5}"
                );
                (strategy, mean, error, variance)
            })
            .collect();
    for a in &results {
        for b in &results {
            let combined = (a.2 * a.2 + b.2 * b.2).sqrt();
            assert!(
                (a.1 - b.1).abs() < 4.0 * combined,
                "{:?} {} vs {:?} {} (± {combined})",
                a.0,
                a.1,
                b.0,
                b.1
            );
        }
    }
    let mis = results[2].3;
    assert!(mis < results[0].3 && mis < results[1].3, "{results:?}");
}
