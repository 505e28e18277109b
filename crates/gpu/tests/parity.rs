//! The GPU image against the CPU renderer's (its f64 reference) on small scenes: a preset groom
//! at 240 × 160 with per-strand absorption, single scattering and with dual scattering, under
//! the procedural sky and a real map, and an eccentric fiber.

mod common;

use common::{cpu, gpu, hair_pixels, load, relative_rmse, shared_map, spec, worst_relative};
use cuticle_render::Scene;

/// Renders `scene` on both and returns the relative RMSE over hair pixels.
fn compare(scene: &Scene, label: &str) -> f64 {
    let (want, _, _) = cpu().render(scene);
    let (got, frame) = gpu().render(scene).expect("GPU render");
    let mask = hair_pixels(&gpu().visibility(&frame));
    assert!(got.pixels.iter().all(|p| p.is_finite()), "{label}: non-finite pixel");
    let e = relative_rmse(&got, &want, &mask);
    eprintln!(
        "{label}: relative RMSE over {} hair pixels {e:.2e}, worst pixel {:.2e} of the brightest",
        mask.iter().filter(|&&m| m).count(),
        worst_relative(&got, &want)
    );
    e
}

#[test]
fn single_scattering_under_the_sky_matches_the_cpu() {
    let mut s = spec(150, "default", 40);
    s.multiple = false;
    let e = compare(&load(s), "sky, single");
    assert!(e < 5e-3, "{e}");
}

#[test]
fn dual_scattering_under_the_sky_matches_the_cpu() {
    let e = compare(&load(spec(150, "default", 40)), "sky, single + multiple");
    assert!(e < 5e-3, "{e}");
}

#[test]
fn real_map_matches_the_cpu() {
    let e = compare(
        &load(spec(150, &shared_map("venice_sunset_1k.hdr"), 20)),
        "venice sunset, single + multiple",
    );
    assert!(e < 5e-3, "{e}");
}

#[test]
fn eccentric_fiber_matches_the_cpu() {
    let mut s = spec(150, "default", 40);
    s.hair.eccentricity = 0.85;
    let e = compare(&load(s), "sky, eccentric 0.85, single + multiple");
    assert!(e < 5e-3, "{e}");
}
