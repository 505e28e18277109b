//! The deep opacity maps' transmittance (frame/shadows.rs, a sharp light: λ = 0) against the
//! exact one, where the hair thins: a tuft of hanging strands of varied length, so that the
//! bottom fifth holds few, tapering fibers. The exact transmittance of a point toward a light is
//! visibility by ray casting against every segment as a capsule of the fiber's radius, leaving
//! out the two segments that meet at the point (the ray starts inside its own fiber, as the path
//! tracer's shadow rays do). Averaged over the points of a region, the map must agree with it
//! for lights from above, from the side and from below.

use cuticle_groom::{Groom, GroomParts};
use cuticle_render::ShadowOptions;
use cuticle_render::frame::shadows::transmittance;
use glam::{DVec3, Vec3};
use rand_core::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

const STRANDS: usize = 800;
const SEGMENT: f32 = 0.4;
const ROOT_THICKNESS: f32 = 0.03;
const TIP_THICKNESS: f32 = 0.015;

/// Strands rooted over a disc of radius 2.5 at z = 0, hanging down with a random lean and a
/// gentle bend, 5 to 10 long, tapering over their last fifth (as the procedural grooms do).
fn tuft() -> Groom {
    let mut rng = Pcg64Mcg::seed_from_u64(13);
    let mut uniform = move || (rng.next_u64() >> 11) as f32 / (1u64 << 53) as f32;
    let mut parts = GroomParts::default();
    parts.strand_offsets.push(0);
    for _ in 0..STRANDS {
        let (r, a) = (2.5 * uniform().sqrt(), std::f32::consts::TAU * uniform());
        let mut p = Vec3::new(r * a.cos(), r * a.sin(), 0.0);
        let lean = Vec3::new(uniform() - 0.5, uniform() - 0.5, 0.0) * 0.3;
        let bend = Vec3::new(uniform() - 0.5, uniform() - 0.5, 0.0) * 0.04;
        let length = 5.0 + 5.0 * uniform();
        let n = (length / SEGMENT).ceil() as usize + 1;
        for k in 0..n {
            let t = k as f32 / (n - 1) as f32;
            let taper = ((t - 0.8) / 0.2).clamp(0.0, 1.0);
            parts.positions.push(p);
            parts
                .thickness
                .push(ROOT_THICKNESS + (TIP_THICKNESS - ROOT_THICKNESS) * taper);
            let down = (Vec3::NEG_Z + lean + bend * k as f32).normalize();
            p += down * SEGMENT;
        }
        parts.strand_offsets.push(parts.positions.len() as u32);
    }
    Groom::from_parts(parts).unwrap()
}

/// Squared distance from the ray (o, d), d a unit vector, t ≥ 0, to the segment [a, b].
fn ray_segment_distance2(o: DVec3, d: DVec3, a: DVec3, b: DVec3) -> f64 {
    let e = b - a;
    let w = o - a;
    let (ee, de, dw, ew) = (e.dot(e), d.dot(e), d.dot(w), e.dot(w));
    let den = ee - de * de;
    // Closest points of the two lines, then clamped: s along the segment, t along the ray.
    let mut s = if den > 1e-12 * ee {
        ((ew - de * dw) / den).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let mut t = (s * de - dw).max(0.0);
    s = ((t * de + ew) / ee).clamp(0.0, 1.0);
    t = (s * de - dw).max(0.0);
    (o + d * t - (a + e * s)).length_squared()
}

/// Whether point `i` of `groom` sees along `d` past every segment but its own two.
fn visible(groom: &Groom, i: usize, d: DVec3) -> bool {
    let pos = groom.positions();
    let thick = groom.thickness();
    let o = pos[i].as_dvec3();
    for s in 0..groom.strand_count() {
        let r = groom.strand_range(s);
        for j in r.start..r.end - 1 {
            if j == i || j + 1 == i {
                continue;
            }
            let (a, b) = (pos[j].as_dvec3(), pos[j + 1].as_dvec3());
            let radius = 0.5 * thick[j].max(thick[j + 1]) as f64;
            // Cheap rejection: the ray passes farther from the segment's middle than its reach.
            let m = 0.5 * (a + b) - o;
            let along = m.dot(d);
            let reach = radius + 0.5 * (b - a).length();
            if along < -reach || m.length_squared() - along.max(0.0).powi(2) > reach * reach {
                continue;
            }
            if ray_segment_distance2(o, d, a, b) < radius * radius {
                return false;
            }
        }
    }
    true
}

/// Directions toward the light: above, oblique, sideways, from below.
fn lights() -> Vec<DVec3> {
    [(80.0f64, 0.3f64), (35.0, 1.9), (10.0, -2.8), (-25.0, -1.2)]
        .iter()
        .map(|&(elev, az)| {
            let e = elev.to_radians();
            DVec3::new(e.cos() * az.cos(), e.cos() * az.sin(), e.sin())
        })
        .collect()
}

/// Per light: (mean map transmittance, mean exact transmittance) over `points`.
fn means(groom: &Groom, points: &[u32], options: &ShadowOptions) -> Vec<(f64, f64)> {
    let dirs = lights();
    let map = transmittance(groom, points, &dirs, &vec![0.0; dirs.len()], options);
    let n = points.len() as f64;
    (0..dirs.len())
        .map(|j| {
            let m: f64 = (0..points.len())
                .map(|k| map[k * dirs.len() + j] as f64)
                .sum();
            let exact = points
                .iter()
                .filter(|&&p| visible(groom, p as usize, dirs[j]))
                .count();
            (m / n, exact as f64 / n)
        })
        .collect()
}

/// The points of the bottom fifth of the tuft (by height).
fn tip_points(groom: &Groom) -> Vec<u32> {
    let b = groom.bounds();
    let cut = b.min.z + 0.2 * (b.max.z - b.min.z);
    (0..groom.point_count() as u32)
        .filter(|&p| groom.positions()[p as usize].z < cut)
        .collect()
}

#[test]
fn the_maps_match_ray_casting_where_the_hair_thins() {
    let groom = tuft();
    let points = tip_points(&groom);
    assert!(points.len() > 300, "{} tip points", points.len());
    let options = ShadowOptions {
        resolution: 96,
        ..ShadowOptions::default()
    };
    for (j, (map, exact)) in means(&groom, &points, &options).into_iter().enumerate() {
        println!("light {j}: map {map:.3} exact {exact:.3}");
        assert!(exact > 0.05 && exact < 0.95, "light {j}: exact {exact}");
        assert!(
            (map / exact - 1.0).abs() < 0.1,
            "light {j}: map {map:.3} against exact {exact:.3}"
        );
    }
}
