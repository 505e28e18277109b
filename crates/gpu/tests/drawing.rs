//! The GPU's drawing (crates/gpu/src/draw) against frame/draw.rs's (the reference): the
//! strand each subsample shows, t along its segment, and the visible points, on the parity
//! scene, an odd size with 3 × 3 subsamples, and a close-up whose strands are several
//! subsamples wide and whose nearest points lie behind the near plane.
//!
//! Bounds: fewer than 2e-3 of the subsamples either drawing covers show another strand (or
//! none) in the other, and where both keep the same segment |Δt| < 1e-3. The two run the same
//! rules on the same f32 capsules but for the projection (f64 rounded to f32 on the CPU, f32
//! with the eye split in two on the GPU, a few f32 ulps apart), so a subsample centre within a
//! few ulps of a capsule's edge, or two strands' depths within a few
//! ulps, can go the other way; a hardware GPU that contracts multiply-adds moves a few more.
//! Strands thinner than a subsample cover each subsample of their capsule by a hash of the
//! strand and the subsample (raster.rs's `keeps`), the same u32 arithmetic on both; a draw
//! compares u · half < true half, f32 products rounded alike, so it too flips only where the
//! two widths differ by ulps (a GPU hash one off in its increment puts 0.85 of the parity
//! scene's covered subsamples off). Measured on lavapipe: none of the parity scene's 5,398 covered
//! subsamples, none of the other two cases', and no visible point seen by one drawing only;
//! |Δt| ≤ 1.3e-5. The
//! share is of subsamples covered, so a wrong width, depth test or clipping, which changes
//! whole runs of subsamples along every strand, is far above it: drawing every capsule half a
//! subsample wide puts 0.91 of the close-up's subsamples off (the other scenes' hair is all
//! that thin), keeping the farthest depth 0.46 to 0.64 of every scene's, and the close-up's
//! own CPU drawing one subsample to the side 0.17 (checked below).

mod common;

use common::{gpu, load, spec};
use cuticle_render::Scene;
use cuticle_render::frame::draw::{Coverage, EMPTY, draw_strands};
use glam::DVec3;

/// How two drawings of one groom differ.
struct Difference {
    /// Subsamples covered by either.
    covered: usize,
    /// Of those, the share whose strand (or none) differs.
    strand_share: f64,
    /// Largest |Δt| where both keep the same segment.
    worst_t: f64,
}

fn difference(a: &Coverage, b: &Coverage, strand: &[u32]) -> Difference {
    assert_eq!(
        a.segment.len(),
        b.segment.len(),
        "drawings of different sizes"
    );
    let of = |s: u32| (s != EMPTY).then(|| strand[s as usize]);
    let (mut covered, mut differ, mut worst_t) = (0usize, 0usize, 0.0f64);
    for k in 0..a.segment.len() {
        let (sa, sb) = (a.segment[k], b.segment[k]);
        if sa == EMPTY && sb == EMPTY {
            continue;
        }
        covered += 1;
        differ += (of(sa) != of(sb)) as usize;
        if sa == sb {
            worst_t = worst_t.max((a.t[k] - b.t[k]).abs() as f64);
        }
    }
    Difference {
        covered,
        strand_share: differ as f64 / covered.max(1) as f64,
        worst_t,
    }
}

/// Draws `scene` on both, checks the bounds, and returns the CPU's drawing.
fn compare(scene: &Scene, label: &str) -> Coverage {
    let spec = &scene.spec;
    let view = scene.camera.view(spec.width, spec.height);
    let want = draw_strands(
        &scene.groom,
        &view,
        spec.width,
        spec.height,
        spec.supersampling,
    );
    let frame = gpu().prepare(scene).expect("GPU prepare");
    let got = gpu().coverage(&frame);
    assert_eq!(
        (got.width, got.height, got.ss),
        (want.width, want.height, want.ss)
    );
    let strand = scene.groom.strand_of_points();
    let d = difference(&got, &want, &strand);
    let points = gpu().visible_points(&frame);
    let cpu_points = want.visible_points(scene.groom.point_count());
    let only_one = symmetric_difference(&points, &cpu_points);
    eprintln!(
        "{label}: {} subsamples covered ({:.1} %), {:.2e} show another strand, worst |Δt| {:.1e}; \
         {} visible points, {only_one} seen by one drawing only",
        d.covered,
        100.0 * want.covered_fraction(),
        d.strand_share,
        d.worst_t,
        points.len(),
    );
    assert!(
        want.covered_fraction() > 0.02,
        "{label}: the scene shows almost no hair"
    );
    assert!(d.strand_share < 2e-3, "{label}: {} differ", d.strand_share);
    assert!(d.worst_t < 1e-3, "{label}: |Δt| {}", d.worst_t);
    assert!(points.windows(2).all(|w| w[0] < w[1]), "{label}: unsorted");
    assert_eq!(points.len(), frame.visible_count());
    assert!(
        (only_one as f64) < 2e-3 * cpu_points.len() as f64,
        "{label}: {only_one} of {} points seen by one drawing only",
        cpu_points.len()
    );
    want
}

/// Count of entries in one sorted list but not the other.
fn symmetric_difference(a: &[u32], b: &[u32]) -> usize {
    let (mut i, mut j, mut n) = (0, 0, 0);
    while i < a.len() || j < b.len() {
        match (a.get(i), b.get(j)) {
            (Some(x), Some(y)) if x == y => (i, j) = (i + 1, j + 1),
            (Some(x), Some(y)) if x < y => (i, n) = (i + 1, n + 1),
            (Some(_), Some(_)) | (None, Some(_)) => (j, n) = (j + 1, n + 1),
            (Some(_), None) => (i, n) = (i + 1, n + 1),
            (None, None) => unreachable!(),
        }
    }
    n
}

#[test]
fn drawing_matches_the_cpu_raster_on_the_parity_scene() {
    compare(
        &load(spec(150, "default", 8)),
        "parity scene 240 x 160, 2 x 2",
    );
}

#[test]
fn drawing_matches_at_an_odd_size_with_3_by_3_subsamples() {
    let mut s = spec(150, "default", 8);
    (s.width, s.height, s.supersampling) = (97, 61, 3);
    compare(&load(s), "97 x 61, 3 x 3");
}

/// Close enough that the nearest strands are many subsamples wide and some points lie behind
/// the near plane (dropped with their segments, as the CPU drops them).
#[test]
fn drawing_matches_in_a_close_up_with_clipped_points() {
    let mut scene = load(spec(600, "default", 8));
    // The eye half a centimetre inside the hair nearest to it, looking at the head.
    let (eye, target) = (
        DVec3::from(scene.camera.eye),
        DVec3::from(scene.camera.target),
    );
    let nearest = scene
        .groom
        .positions()
        .iter()
        .map(|p| p.as_dvec3())
        .min_by(|a, b| a.distance(eye).total_cmp(&b.distance(eye)))
        .expect("a groom with points");
    scene.camera.eye = (nearest + 0.5 * (target - eye).normalize()).to_array();
    let spec = &scene.spec;
    let view = scene.camera.view(spec.width, spec.height);
    let behind = scene
        .groom
        .positions()
        .iter()
        .filter(|p| view.project(p.as_dvec3()).is_none())
        .count();
    let wide = scene
        .groom
        .positions()
        .iter()
        .zip(scene.groom.thickness())
        .filter_map(|(p, &t)| view.project(p.as_dvec3()).map(|q| (q, t)))
        .filter(|(q, t)| {
            0.5 * *t as f64 * view.pixels_per_unit(q.depth as f64) * spec.supersampling as f64 > 2.0
        })
        .count();
    eprintln!(
        "close-up: {behind} points behind the near plane, {wide} drawn over 4 subsamples wide"
    );
    assert!(behind > 0, "the close-up clips nothing");
    assert!(wide > 20, "the close-up draws no wide strand");
    let want = compare(&scene, "close-up 240 x 160, 2 x 2");
    // The bound can tell: the reference itself, one subsample to the side, is far off it.
    let sw = want.width * want.ss;
    let shifted = Coverage::from_parts(
        want.width,
        want.height,
        want.ss,
        (0..want.segment.len())
            .map(|k| {
                if k % sw == 0 {
                    EMPTY
                } else {
                    want.segment[k - 1]
                }
            })
            .collect(),
        want.t.clone(),
    );
    let d = difference(&shifted, &want, &scene.groom.strand_of_points());
    eprintln!(
        "one subsample to the side: {:.2e} show another strand",
        d.strand_share
    );
    assert!(d.strand_share > 10.0 * 2e-3, "{}", d.strand_share);
}
