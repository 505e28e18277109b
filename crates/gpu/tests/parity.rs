//! The GPU image against the CPU renderer's (its f64 reference) on small scenes: a preset groom
//! at 240 × 160 with per-strand absorption, single scattering and with dual scattering, under
//! the procedural sky and a real map, and an eccentric fiber.
//!
//! The images are compared where the two drawings agree (every subsample of the pixel keeps
//! the same segment): the drawing is the GPU's own since issue 10's last step, and where it
//! differs from the CPU's, at the few subsamples tests/drawing.rs bounds and measures, a pixel
//! moves by a subsample's share of the difference between two strands, which is the drawing's
//! error, not the shading's; at most 1 % of the hair pixels may be left out so.
//!
//! Bounds: relative RMSE over hair pixels below 5e-3 (the eccentric fiber: 1e-3, see its test)
//! and no pixel channel off by more than 1e-2
//! of the brightest (measured on lavapipe: RMSE 5e-5 to 1e-4, worst pixel 8e-5 to 1.5e-4). The
//! two share every input (visibility, shadows, tables rounded to f32); what differs is f32
//! arithmetic, and WGSL lets hardware compute sin/cos to 2^-11 absolute and exp to 3 + 2|x| ulp,
//! which near grazing angles and in the tails of sharp lobes can cost far more than lavapipe's
//! correctly rounded libm: the bounds are the aim, 50 times what lavapipe shows. The
//! dual-scattering test checks that the bound can tell: its multiple scattering moves the
//! image by far more than the bound.

mod common;

use common::{agreeing_pixels, cpu, gpu, load, relative_rmse, shared_map, spec, worst_relative};
use cuticle_render::Scene;

/// Renders `scene` on both and returns the relative RMSE over hair pixels.
fn compare(scene: &Scene, label: &str) -> f64 {
    let (want, prepared, _) = cpu().render(scene);
    let (got, frame) = gpu().render(scene).expect("GPU render");
    let mask = agreeing_pixels(&gpu().coverage(&frame), &prepared.coverage);
    assert!(
        got.pixels.iter().all(|p| p.is_finite()),
        "{label}: non-finite pixel"
    );
    let e = relative_rmse(&got, &want, &mask.hair);
    let worst = worst_relative(&got, &want, &mask.all);
    eprintln!(
        "{label}: relative RMSE over {} hair pixels {e:.2e}, worst pixel {worst:.2e} of the brightest \
         ({} hair pixels left out: the drawings differ there)",
        mask.hair.iter().filter(|&&m| m).count(),
        mask.left_out,
    );
    assert!(worst < 1e-2, "{label}: worst pixel {worst}");
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
    let scene = load(spec(150, "default", 40));
    let e = compare(&scene, "sky, single + multiple");
    assert!(e < 5e-3, "{e}");
    // The bound is tight enough to catch a port that lost multiple scattering, which moves
    // this image by 1.5 % (measured), three times the bound and 150 times the GPU's error.
    let mut single = scene.clone();
    single.spec.multiple = false;
    let (with, prepared, _) = cpu().render(&scene);
    let (without, _, _) = cpu().render(&single);
    let mask = hair_pixels_of(&prepared);
    let share = relative_rmse(&without, &with, &mask);
    eprintln!("multiple scattering moves this image by {share:.3} (relative RMSE)");
    assert!(share > 2.0 * 5e-3, "{share}");
}

/// Multiple scattering from merged lights (srbf/light_clusters.rs, the default): the GPU's
/// image is the CPU's merged one, and nearer it than the CPU's with every light shaded apart
/// (`merge_bandwidth` 0), so a port that shaded the groups' lights apart, or dropped them,
/// would fail. Light hair, whose multiple scattering is the largest share.
#[test]
fn merged_lights_match_the_cpu() {
    let mut s = spec(150, "default", 40);
    s.hair.mu_a = Some([0.1, 0.2, 0.4]);
    let scene = load(s);
    let e = compare(&scene, "sky, light hair, merged lights");
    assert!(e < 5e-3, "{e}");
    let mut apart = scene.clone();
    apart.spec.shadows.merge_bandwidth = 0.0;
    let (got, frame) = gpu().render(&scene).expect("GPU render");
    let (merged, prepared, _) = cpu().render(&scene);
    let (without, _, _) = cpu().render(&apart);
    let mask = agreeing_pixels(&gpu().coverage(&frame), &prepared.coverage);
    let to_merged = relative_rmse(&got, &merged, &mask.hair);
    let to_apart = relative_rmse(&got, &without, &mask.hair);
    eprintln!(
        "the GPU's image is {to_merged:.2e} from the CPU's merged, {to_apart:.2e} from apart"
    );
    assert!(to_apart > 3.0 * to_merged, "{to_merged} vs {to_apart}");
}

/// Hair pixels from the CPU renderer's visibility buffer.
fn hair_pixels_of(prepared: &cuticle_render::Prepared) -> Vec<bool> {
    let cov = &prepared.coverage;
    (0..cov.width * cov.height)
        .map(|k| {
            cov.pixel_samples(k % cov.width, k / cov.width)
                .any(|s| cov.segment[s] != cuticle_render::frame::draw::EMPTY)
        })
        .collect()
}

#[test]
fn real_map_matches_the_cpu() {
    let Some(map) = shared_map("venice_sunset_1k.hdr") else {
        return;
    };
    let e = compare(
        &load(spec(150, &map, 20)),
        "venice sunset, single + multiple",
    );
    assert!(e < 5e-3, "{e}");
}

/// The eccentric fiber's TRT is fitted at every sample (η̄* varies), with the CPU's caustic
/// moments (Marschner 2003's N_TRT energy): it now agrees as closely as the circular scenes
/// (1.0e-4 on lavapipe; the fit without the caustic moments was 4e-3 off), so its bound is
/// 1e-3, ten times that, where the circular scenes keep the 5e-3: the on-the-spot fit
/// evaluates more transcendentals (asin, exp near the fold of Φ) than a table read, and a
/// hardware GPU's WGSL precision there is what the margin is for. And eccentricity moves this
/// image by far more than the bound: at least five times it (measured on lavapipe 0.0074, and
/// 0.0075 under split lights, whose image was 0.014 from the circular one while the raster drew
/// strands thinner than a subsample a whole subsample wide).
///
/// Under the fitted lights (`split_bandwidth` off); with the sub-lights, see below.
#[test]
fn eccentric_fiber_matches_the_cpu() {
    let mut s = spec(150, "default", 40);
    s.hair.eccentricity = 0.85;
    s.shadows.split_bandwidth = 1000.0;
    let scene = load(s);
    let e = compare(&scene, "sky, eccentric 0.85, single + multiple");
    assert!(e < 1e-3, "{e}");
    let mut circular = scene.clone();
    circular.spec.hair.eccentricity = 1.0;
    let (with, prepared, _) = cpu().render(&scene);
    let (without, _, _) = cpu().render(&circular);
    let share = relative_rmse(&without, &with, &hair_pixels_of(&prepared));
    eprintln!("eccentricity 0.85 moves this image by {share:.3} (relative RMSE)");
    assert!(share > 5.0 * 1e-3, "{share}");
}

/// With wide lights split into sub-lights (frame/sub_lights.rs: 87 lights here) under the same
/// bound. This image was 0.17 off while one invocation shaded every light: llvmpipe stops every
/// loop of an invocation after 65,535 iterations in all (shading/mod.rs's LOOP_BUDGET), and 87
/// lights with the TRT fit's caustic moments at every sample needed about 150,000, so the
/// last lights and the quadratures under way were cut short. The pass now shades the lights in
/// dispatches that fit the budget, and the fit's wrapped Gaussians run no loop.
#[test]
fn eccentric_fiber_under_split_lights_matches_the_cpu() {
    let mut s = spec(150, "default", 40);
    s.hair.eccentricity = 0.85;
    let scene = load(s);
    let e = compare(&scene, "sky, eccentric 0.85, split lights");
    assert!(e < 1e-3, "{e}");
    // The GPU's image is the eccentric one: far from the circular fiber's under these lights
    // (0.0075 on lavapipe), as in the test above.
    let mut circular = scene.clone();
    circular.spec.hair.eccentricity = 1.0;
    let (got, frame) = gpu().render(&scene).expect("GPU render");
    let (without, prepared, _) = cpu().render(&circular);
    let mask = agreeing_pixels(&gpu().coverage(&frame), &prepared.coverage);
    let share = relative_rmse(&got, &without, &mask.hair);
    eprintln!("under split lights the GPU's eccentric image is {share:.3} from the circular one");
    assert!(share > 5.0 * 1e-3, "{share}");
}

/// Zero-length segments, one-point strands and an empty groom render finite pixels equal to the
/// CPU's within the worst-pixel bound (the empty groom: its background, read back in f32).
#[test]
fn degenerate_grooms_render() {
    use cuticle_groom::{Groom, GroomParts};
    use glam::Vec3;
    let odd = Groom::from_parts(GroomParts {
        positions: vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(0.0, 0.0, -5.0),
            Vec3::new(3.0, 0.0, 0.0),
            Vec3::new(1.0, 1.0, 1.0),
            Vec3::new(1.0, 1.0, 1.0),
        ],
        thickness: vec![0.05; 6],
        strand_offsets: vec![0, 3, 4, 6],
        ..GroomParts::default()
    })
    .unwrap();
    let empty = Groom::from_parts(GroomParts {
        strand_offsets: vec![0],
        ..GroomParts::default()
    })
    .unwrap();
    let base = load(spec(10, "default", 4));
    for (name, groom) in [("odd", odd), ("empty", empty)] {
        let mut s = base.spec.clone();
        s.width = 48;
        s.height = 32;
        let scene = Scene::from_parts(s, groom, base.env.clone(), base.lights.clone());
        let (want, prepared, _) = cpu().render(&scene);
        let (got, frame) = gpu().render(&scene).unwrap();
        assert!(got.pixels.iter().all(|p| p.is_finite()), "{name}");
        let mask = agreeing_pixels(&gpu().coverage(&frame), &prepared.coverage);
        let worst = worst_relative(&got, &want, &mask.all);
        assert!(worst < 1e-2, "{name}: {worst}");
    }
}
