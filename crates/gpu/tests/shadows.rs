//! The GPU's deep opacity maps (crates/gpu/src/shadows) against frame/shadows.rs's (the
//! reference, in f64): T̃ of every light at every visible point of the same drawing.
//!
//! Bounds: mean |ΔT̃| below 2e-5 and fewer than 0.1 % of the (point, light) pairs off by more
//! than 0.05 (measured on lavapipe: mean 2.4e-7, no pair off by 0.05). The two build the same
//! maps from the same frames; what differs is f32 against f64 in the samples' positions and
//! depths, so a sample or a looked-up point near a texel edge or a layer boundary can fall on
//! the other side and move T̃ by a texel's or a layer's share, and the fixed-point sums round
//! each sample by at most half a unit (2^-20 of a fiber count here, coarser for large grooms).
//! lavapipe rounds like the CPU; a hardware GPU contracts multiply-adds and may flip more
//! samples, which the bounds' factor of 100 over the measured mean is for. They can tell:
//! maps that ignored the lights' bandwidth (the filter of Ren et al. 2010's convolution) are
//! 6e-2 off.

mod common;

use common::{cpu, device, gpu, load, spec};
use cuticle_gpu::GpuRenderer;
use cuticle_render::frame::renderer::shadows_of_lit;
use cuticle_render::frame::shadows::transmittance;
use cuticle_render::{Prepared, Scene, Timings};

/// (mean |a − b|, share of entries off by more than 0.05).
fn distance(a: &[f32], b: &[f32]) -> (f64, f64) {
    assert_eq!(a.len(), b.len());
    assert!(!a.is_empty(), "no shadows to compare");
    let mean = a
        .iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs() as f64)
        .sum::<f64>()
        / a.len() as f64;
    let off = a
        .iter()
        .zip(b)
        .filter(|(x, y)| (*x - *y).abs() > 0.05)
        .count();
    (mean, off as f64 / a.len() as f64)
}

/// The CPU renderer's shadows of `drawn`'s lights at `points`.
fn at_points(scene: &Scene, drawn: &Prepared, points: &[u32]) -> Prepared {
    Prepared {
        points: points.to_vec(),
        shadow: shadows_of_lit(scene, points, &drawn.lights),
        ..drawn.clone()
    }
}

#[test]
fn gpu_shadows_match_the_cpu_opacity_maps() {
    let scene = load(spec(150, "default", 40));
    let drawn = cpu().prepare(&scene, &mut Timings::default());
    let frame = gpu().prepare(&scene).expect("GPU prepare");
    // The reference's maps at the points the GPU drew (its drawing has its own test,
    // tests/drawing.rs), so that only the maps are compared.
    let points = gpu().visible_points(&frame);
    let want = at_points(&scene, &drawn, &points);
    let got = gpu().shadows(&frame);
    assert!(got.iter().all(|t| t.is_finite() && (0.0..=1.0).contains(t)));
    // The maps shadow something: 7.4 % of the pairs lie below T̃ = 0.5 (the reference's).
    let dark = want.shadow.iter().filter(|&&t| t < 0.5).count();
    assert!(
        dark * 20 > want.shadow.len(),
        "{dark} of {} dark",
        want.shadow.len()
    );
    let (mean, off) = distance(&got, &want.shadow);
    eprintln!("GPU against CPU shadows: mean |ΔT| {mean:.2e}, {off:.2e} of pairs off by > 0.05");
    assert!(mean < 2e-5, "mean |ΔT| {mean}");
    assert!(off < 1e-3, "{off} of pairs off by more than 0.05");
    // Unfiltered maps (every light treated as directional) are far from the GPU's.
    let dirs: Vec<_> = want.lights.iter().map(|l| l.direction).collect();
    let sharp = transmittance(
        &scene.groom,
        &points,
        &dirs,
        &vec![0.0; dirs.len()],
        &scene.spec.shadows,
    );
    let (unfiltered, _) = distance(&got, &sharp);
    eprintln!("unfiltered maps differ by mean |ΔT| {unfiltered:.2e}");
    assert!(unfiltered > 100.0 * 2e-5, "{unfiltered}");
}

#[test]
fn no_density_and_black_lights_cast_no_shadow() {
    let mut s = spec(40, "default", 8);
    s.shadows.density = 0.0;
    let scene = load(s);
    let frame = gpu().prepare(&scene).unwrap();
    assert!(gpu().shadows(&frame).iter().all(|&t| t == 1.0));
    // A black light gets no map (T̃ = 1), the others theirs, as the CPU renderer does.
    let mut scene = load(spec(40, "default", 8));
    scene.lights[3].coefficient = glam::Vec3::ZERO;
    let drawn = cpu().prepare(&scene, &mut Timings::default());
    let frame = gpu().prepare(&scene).unwrap();
    let want = at_points(&scene, &drawn, &gpu().visible_points(&frame));
    let got = gpu().shadows(&frame);
    // The frame's lights (wide ones split into sub-lights): every black one has T̃ = 1.
    let lights = want.lights.len();
    let black: Vec<usize> = (0..lights)
        .filter(|&j| want.lights[j].radiance == glam::DVec3::ZERO)
        .collect();
    assert!(!black.is_empty());
    for j in black {
        assert!(got.iter().skip(j).step_by(lights).all(|&t| t == 1.0));
    }
    let (mean, _) = distance(&got, &want.shadow);
    assert!(mean < 2e-5, "{mean}");
    assert_eq!(frame.passes().shadow_steps, 5);
}

/// Maps built in batches, as a device whose buffer limit holds fewer maps builds them (lavapipe's
/// 128 MiB holds 85 maps of 256²), give the same shadows as one batch, bit for bit, in five
/// passes a batch.
#[test]
fn maps_built_in_batches_give_the_same_shadows() {
    let scene = load(spec(40, "default", 8));
    let whole = gpu().prepare(&scene).unwrap();
    let batched = GpuRenderer::new(device(), cpu()).with_shadow_batch(7);
    let frame = batched.prepare(&scene).unwrap();
    let maps = cpu()
        .draw(&scene, &mut Timings::default())
        .lights
        .iter()
        .filter(|l| l.radiance != glam::DVec3::ZERO)
        .count();
    assert!(maps > 2 * 7, "{maps} maps make too few batches");
    assert_eq!(whole.passes().shadow_steps, 5);
    assert_eq!(frame.passes().shadow_steps, 5 * maps.div_ceil(7));
    assert_eq!(batched.shadows(&frame), gpu().shadows(&whole));
}
