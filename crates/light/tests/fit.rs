//! The SRBF fit: it recovers lights it could represent exactly, its error falls as J grows on a
//! real map, and it turns with the map.

use cuticle_light::{
    EnvMap, FitOptions, SrbfLight, direction_from_angles, evaluate_lights, fit_srbf, load_env_map,
    relative_l2_error,
};
use glam::Vec3;
use std::path::PathBuf;

fn known_lights() -> Vec<SrbfLight> {
    let light = |theta: f64, phi: f64, bandwidth: f32, rgb: [f32; 3]| {
        SrbfLight::new(
            direction_from_angles(theta, phi).as_vec3(),
            bandwidth,
            Vec3::from(rgb),
        )
    };
    vec![
        light(0.5, 0.3, 0.12, [40.0, 35.0, 30.0]),
        light(1.2, -2.0, 0.6, [0.2, 0.4, 0.9]),
        light(-0.6, 2.2, 0.35, [1.5, 0.8, 0.3]),
        light(0.1, -0.9, 0.25, [0.5, 1.6, 0.6]),
        light(-1.3, -1.5, 0.8, [0.3, 0.25, 0.2]),
    ]
}

#[test]
fn recovers_a_map_made_of_known_srbfs() {
    let truth = known_lights();
    let map = EnvMap::from_fn(128, 64, |d| evaluate_lights(&truth, d).as_vec3());
    let options = FitOptions {
        lights: truth.len(),
        fit_width: 128,
        max_iterations: 300,
        tolerance: 1e-6,
        ..FitOptions::default()
    };
    let report = fit_srbf(&map, &options).unwrap();
    assert!(
        report.relative_l2 < 1e-3,
        "relative L2 error {} (initial {})",
        report.relative_l2,
        report.relative_l2_fit_initial
    );
    for t in &truth {
        let found = report
            .lights
            .iter()
            .max_by(|a, b| {
                a.direction
                    .dot(t.direction)
                    .total_cmp(&b.direction.dot(t.direction))
            })
            .unwrap();
        let angle = found
            .direction
            .dot(t.direction)
            .clamp(-1.0, 1.0)
            .acos()
            .to_degrees();
        assert!(angle < 0.5, "{t:?} found {angle}° away as {found:?}");
        assert!(
            (found.bandwidth / t.bandwidth - 1.0).abs() < 0.02,
            "{t:?} vs {found:?}"
        );
        let coef_error = (found.coefficient - t.coefficient).abs().max_element();
        assert!(
            coef_error < 0.02 * t.coefficient.max_element(),
            "{t:?} vs {found:?}"
        );
    }
}

fn shared_map(name: &str) -> Option<EnvMap> {
    let path = PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../../shared/data/envmaps"
    ))
    .join(name);
    if path.exists() {
        Some(load_env_map(&path).unwrap())
    } else {
        println!("skipped: {} is absent", path.display());
        None
    }
}

#[test]
fn error_falls_as_the_number_of_lights_grows() {
    let Some(full) = shared_map("venice_sunset_1k.hdr") else {
        return;
    };
    let map = full.downsample(128, 64);
    let errors: Vec<f64> = [10, 20, 40, 80]
        .iter()
        .map(|&lights| {
            let options = FitOptions {
                lights,
                fit_width: 64,
                refine_samples: 1024,
                ..FitOptions::default()
            };
            let report = fit_srbf(&map, &options).unwrap();
            assert_eq!(report.lights.len(), lights);
            let independent = relative_l2_error(&map, &report.lights);
            assert!((independent - report.relative_l2).abs() < 1e-9);
            println!("J = {lights}: relative L2 {:.4}", report.relative_l2);
            report.relative_l2
        })
        .collect();
    for pair in errors.windows(2) {
        assert!(pair[1] < pair[0], "error rose with more lights: {errors:?}");
    }
    assert!(errors[3] < 0.85 * errors[0], "{errors:?}");
    assert!(
        errors[0] < 0.5,
        "10 lights miss the map entirely: {errors:?}"
    );
}

#[test]
fn the_fit_turns_with_the_map() {
    let truth = known_lights();
    let map = EnvMap::from_fn(64, 32, |d| {
        (evaluate_lights(&truth, d) + glam::DVec3::splat(0.05 * (1.0 + d.y))).as_vec3()
    });
    let rho = 1.0f64;
    let options = FitOptions {
        lights: 8,
        fit_width: 64,
        ..FitOptions::default()
    };
    let still = fit_srbf(&map, &options).unwrap();
    let turned = fit_srbf(&map.clone().with_rotation(rho), &options).unwrap();
    assert!((still.relative_l2 - turned.relative_l2).abs() < 1e-4 * still.relative_l2.max(1e-3));
    let rotate = |v: Vec3| {
        let (s, c) = (rho as f32).sin_cos();
        Vec3::new(c * v.x - s * v.z, v.y, s * v.x + c * v.z)
    };
    for (a, b) in still.lights.iter().zip(&turned.lights) {
        let angle = rotate(a.direction).dot(b.direction).clamp(-1.0, 1.0).acos();
        assert!(angle < 1e-3, "{a:?} turned is {b:?}");
    }
}

#[test]
fn bad_options_are_refused() {
    let map = EnvMap::new(16, 8, vec![Vec3::ONE; 128]);
    for options in [
        FitOptions {
            lights: 0,
            ..FitOptions::default()
        },
        FitOptions {
            fit_width: 2,
            ..FitOptions::default()
        },
        FitOptions {
            min_bandwidth: Some(-1.0),
            ..FitOptions::default()
        },
        FitOptions {
            max_bandwidth: f64::NAN,
            ..FitOptions::default()
        },
    ] {
        assert!(fit_srbf(&map, &options).is_err(), "{options:?}");
    }
}

/// Parallel sums are split into fixed ranges and combined in order, so the thread count (which
/// would otherwise shape the summation tree) changes no bit of the result.
#[test]
fn a_fit_is_the_same_on_any_number_of_threads() {
    let map = cuticle_light::ProceduralSky::default().to_env_map(256);
    let options = FitOptions {
        lights: 12,
        fit_width: 64,
        ..FitOptions::default()
    };
    let on = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| fit_srbf(&map, &options).unwrap())
    };
    let (one, three) = (on(1), on(3));
    assert_eq!(one.lights, three.lights);
    assert_eq!(one.relative_l2.to_bits(), three.relative_l2.to_bits());
}
