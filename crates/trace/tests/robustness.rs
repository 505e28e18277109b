//! Determinism and degenerate input (issue 12): the same seed gives the same image bit for bit
//! on rayon pools of 1 and 2 threads; an empty groom, a groom of one-point strands and a black
//! map render without a panic, every pixel finite (the environment, or black).

mod common;

use common::{constant_env, front_camera, scene, single_fiber, slab, spot_env};
use cuticle_groom::{Groom, GroomParts};
use cuticle_light::EnvMap;
use cuticle_render::scene::world_to_light;
use cuticle_trace::{StrandModels, TraceImage, TraceOptions, render};
use glam::{DVec3, Vec3};

fn trace(s: &cuticle_trace::Scene, spp: u32) -> TraceImage {
    let models = StrandModels::marschner(s).unwrap();
    let options = TraceOptions {
        spp,
        seed: 5,
        ..TraceOptions::default()
    };
    render(s, &models, &options, &|_, _| {})
}

#[test]
fn same_seed_same_image_on_one_and_two_threads() {
    let env = spot_env(world_to_light(DVec3::new(0.3, -0.5, 0.8)));
    let s = scene(slab(3, 24, 0.1), env, 16, 8, front_camera(8.0));
    let run = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| trace(&s, 4))
    };
    let (one, two) = (run(1), run(2));
    assert_eq!(one.image.pixels, two.image.pixels);
    assert_eq!(one.standard_error, two.standard_error);
    assert_eq!(one.stats.rays, two.stats.rays);
    let other_seed = render(
        &s,
        &StrandModels::marschner(&s).unwrap(),
        &TraceOptions {
            spp: 4,
            seed: 6,
            ..TraceOptions::default()
        },
        &|_, _| {},
    );
    assert_ne!(one.image.pixels, other_seed.image.pixels);
}

fn groom(positions: Vec<Vec3>, offsets: Vec<u32>) -> Groom {
    Groom::from_parts(GroomParts {
        thickness: vec![0.1; positions.len()],
        positions,
        strand_offsets: offsets,
        ..GroomParts::default()
    })
    .unwrap()
}

#[test]
fn degenerate_input_renders_without_a_panic() {
    let empty = groom(Vec::new(), vec![0]);
    let out = trace(&scene(empty, constant_env(0.7), 8, 4, front_camera(8.0)), 2);
    assert!(out.image.pixels.iter().all(|p| (p.x - 0.7).abs() < 1e-6));
    let points = groom(vec![Vec3::ZERO, Vec3::X, Vec3::X], vec![0, 1, 2, 3]);
    let out = trace(
        &scene(points, constant_env(0.7), 8, 4, front_camera(8.0)),
        2,
    );
    assert!(out.image.pixels.iter().all(|p| (p.x - 0.7).abs() < 1e-6));
    let black = EnvMap::new(16, 8, vec![Vec3::ZERO; 128]);
    let out = trace(&scene(slab(2, 8, 0.1), black, 8, 4, front_camera(8.0)), 2);
    assert!(out.image.pixels.iter().all(|p| *p == DVec3::ZERO));
    assert!(out.standard_error.iter().all(|e| e.is_finite()));
}

/// The coverage a render reports is the tubes' own: one fiber of diameter 0.2 at distance 10,
/// across an image whose pixels are 0.55 of it tall, covers 0.2 / pixel height per column in
/// sum (to the sampling noise of 64 spp), and nothing two pixels off it.
#[test]
fn coverage_is_the_fibers_projected_width() {
    let camera = front_camera(20.0);
    let (w, h) = (6, 32);
    let s = scene(single_fiber(), constant_env(1.0), w, h, camera);
    let traced = trace(&s, 64);
    let pixel = 10.0 / s.camera.view(w, h).focal;
    assert!(pixel > 0.2 / 2.0 && pixel < 0.2, "pixel {pixel}");
    for x in 0..w {
        let column: Vec<f64> = (0..h).map(|y| traced.coverage[y * w + x]).collect();
        let sum: f64 = column.iter().sum();
        assert!(
            (sum * pixel / 0.2 - 1.0).abs() < 0.05,
            "column {x}: {sum} pixels of coverage, {} expected",
            0.2 / pixel
        );
        assert!(
            column[..h / 2 - 3]
                .iter()
                .chain(&column[h / 2 + 3..])
                .all(|&c| c == 0.0)
        );
    }
}
