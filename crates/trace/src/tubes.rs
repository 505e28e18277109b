//! Strands as chains of round tubes: each segment a cone frustum (the radius, half the groom's
//! thickness, linear along it) cut at each joint by the plane bisecting the two segments'
//! directions (a mitre). Neighbours share that plane, so a chain has no cracks at a bend and no
//! overlap: a point of the plane belongs to the segment after it only (half-open), and a ray
//! meets each joint once.
//!
//! Only entering hits count: a ray that starts inside a tube (every continuation ray starts on
//! the fiber's axis, as the fiber's scattering function covers the paths inside it) leaves its
//! own fiber unseen and meets the next one. Strand ends are open (a disc of the radius;
//! negligible next to the tube's side). Bends sharper than [`MAX_MITRE_BEND_DEG`] are cut square
//! instead, leaving a wedge there rather than a mitre reaching far outside the tube.
//!
//! A hit reports the fiber frame of docs/conventions.md §2: u the segment's direction, and h
//! the offset across the projected width as the fiber crate's Φ(p, h) reads it: minus the hit's
//! offset along w = u × v, v the projection of the direction the ray came from (the test
//! `reflection_leaves_where_the_cylinder_mirrors_it` checks this against the mirror direction).

use cuticle_groom::Groom;
use glam::{DVec3, Vec3A};
use obvhs::aabb::Aabb;
use obvhs::ray::Ray;

/// Bends above this angle are cut square rather than mitred.
pub const MAX_MITRE_BEND_DEG: f32 = 120.0;
/// Length of a tube's pieces in the BVH, in radii.
pub const PIECE_OVER_RADIUS: f32 = 16.0;
/// Most pieces of one tube.
pub const MAX_PIECES: usize = 16;
/// Segments shorter than this fraction of their radius are dropped (repeated points).
const MIN_LENGTH_OVER_RADIUS: f32 = 1e-3;

/// One segment: a tapered tube between two mitre planes.
#[derive(Clone, Copy, Debug)]
pub struct Tube {
    pub a: Vec3A,
    /// Unit axis from `a` toward the segment's far end.
    pub axis: Vec3A,
    pub length: f32,
    pub radius_a: f32,
    /// dr/ds along the axis.
    pub taper: f32,
    /// Normals of the planes at `a` and at the far end (each pointing toward the tip).
    pub mitre_a: Vec3A,
    pub mitre_b: Vec3A,
    pub strand: u32,
}

/// Where a ray met a tube.
#[derive(Clone, Copy, Debug)]
pub struct TubeHit {
    pub tube: u32,
    pub t: f32,
}

/// The geometry a hit gives the shading: position, the point on the axis the next ray leaves
/// from, the fiber tangent and the offset h (module documentation).
#[derive(Clone, Copy, Debug)]
pub struct HitFrame {
    pub position: DVec3,
    pub on_axis: DVec3,
    pub tangent: DVec3,
    pub h: f64,
    pub strand: u32,
}

/// Every segment of a groom as a tube.
#[derive(Clone, Debug, Default)]
pub struct Tubes {
    pub tubes: Vec<Tube>,
}

impl Tubes {
    pub fn from_groom(groom: &Groom) -> Self {
        let positions = groom.positions();
        let thickness = groom.thickness();
        let mut tubes = Vec::with_capacity(groom.segment_count());
        for s in 0..groom.strand_count() {
            let points = distinct_points(groom, s);
            let dirs: Vec<Vec3A> = points
                .windows(2)
                .map(|w| (Vec3A::from(positions[w[1]]) - Vec3A::from(positions[w[0]])).normalize())
                .collect();
            for (k, w) in points.windows(2).enumerate() {
                let (a, b) = (Vec3A::from(positions[w[0]]), Vec3A::from(positions[w[1]]));
                let (ra, rb) = (0.5 * thickness[w[0]].abs(), 0.5 * thickness[w[1]].abs());
                let length = (b - a).length();
                let axis = dirs[k];
                let prev = k.checked_sub(1).map(|j| dirs[j]);
                let next = dirs.get(k + 1).copied();
                tubes.push(Tube {
                    a,
                    axis,
                    length,
                    radius_a: ra,
                    taper: (rb - ra) / length,
                    mitre_a: mitre(prev, axis),
                    mitre_b: mitre(next.map(|_| axis), next.unwrap_or(axis)),
                    strand: s as u32,
                });
            }
        }
        Self { tubes }
    }

    pub fn len(&self) -> usize {
        self.tubes.len()
    }

    pub fn is_empty(&self) -> bool {
        self.tubes.is_empty()
    }

    /// Boxes around pieces of each tube, wide enough for its mitred ends, with the tube each
    /// bounds. A long thin segment at an angle to the axes fills a small part of one box, so a
    /// tube is split into pieces about [`PIECE_OVER_RADIUS`] radii long (at most
    /// [`MAX_PIECES`]): rays that pass near a strand but not through it are culled in the BVH.
    pub fn bounds(&self) -> (Vec<Aabb>, Vec<u32>) {
        let (mut boxes, mut owner) = (Vec::new(), Vec::new());
        for (i, tube) in self.tubes.iter().enumerate() {
            let r = tube.radius_a.max(tube.radius_b()).max(1e-12);
            let pieces =
                ((tube.length / (PIECE_OVER_RADIUS * r)).ceil() as usize).clamp(1, MAX_PIECES);
            for k in 0..pieces {
                boxes.push(tube.piece_bounds(k, pieces));
                owner.push(i as u32);
            }
        }
        (boxes, owner)
    }

    /// The fiber frame of a hit of `ray` (world space, f64).
    pub fn frame(&self, hit: TubeHit, origin: DVec3, dir: DVec3) -> HitFrame {
        let tube = &self.tubes[hit.tube as usize];
        let position = origin + dir * hit.t as f64;
        let a = tube.a.as_dvec3();
        let u = tube.axis.as_dvec3();
        let s = (position - a).dot(u);
        let on_axis = a + u * s;
        let radius = (tube.radius_a as f64 + tube.taper as f64 * s).max(1e-12);
        let toward = -dir;
        let v = toward - u * u.dot(toward);
        let h = match v.try_normalize() {
            Some(v) => -((position - on_axis).dot(u.cross(v)) / radius).clamp(-1.0, 1.0),
            None => 0.0,
        };
        HitFrame {
            position,
            on_axis,
            tangent: u,
            h,
            strand: tube.strand,
        }
    }
}

/// The strand's point indices without repeats (consecutive points closer than a fraction of
/// the radius).
fn distinct_points(groom: &Groom, strand: usize) -> Vec<usize> {
    let positions = groom.positions();
    let thickness = groom.thickness();
    let mut out: Vec<usize> = Vec::new();
    for i in groom.strand_range(strand) {
        let keep = out.last().is_none_or(|&j| {
            let min = MIN_LENGTH_OVER_RADIUS * 0.5 * thickness[j].abs().max(1e-12);
            (Vec3A::from(positions[i]) - Vec3A::from(positions[j])).length() > min
        });
        if keep {
            out.push(i);
        }
    }
    out
}

/// The plane normal at a joint between directions `before` and `after`: their bisector, or
/// `after` at a strand's end or past the mitre limit.
fn mitre(before: Option<Vec3A>, after: Vec3A) -> Vec3A {
    let Some(before) = before else {
        return after;
    };
    let cos_limit = MAX_MITRE_BEND_DEG.to_radians().cos();
    if before.dot(after) < cos_limit {
        return after;
    }
    (before + after).try_normalize().unwrap_or(after)
}

impl Tube {
    fn radius_b(&self) -> f32 {
        self.radius_a + self.taper * self.length
    }

    /// The box of piece k of n along the axis. A mitre of at most 120° reaches r·tan(60°) <
    /// 2r beyond the end points, so the first and last pieces reach 2r past them; every piece
    /// is padded by 2r across.
    fn piece_bounds(&self, k: usize, n: usize) -> Aabb {
        let reach = Vec3A::splat(2.0 * self.radius_a.max(self.radius_b()));
        let s0 = self.length * k as f32 / n as f32;
        let s1 = self.length * (k + 1) as f32 / n as f32;
        let (p, q) = (self.a + self.axis * s0, self.a + self.axis * s1);
        Aabb::new(p.min(q) - reach, p.max(q) + reach)
    }

    /// The entering hit of `ray` within (tmin, tmax), or infinity.
    ///
    /// With q the ray origin relative to `a`, everything is split into parts along the axis
    /// and normal to it before squaring (no cancellation between |q|² and (q·axis)² far from
    /// the tube): |q⊥ + t d⊥|² = (R₀ + k t)², R₀ the radius at the origin's axial position and
    /// k = taper · (d·axis). Its discriminant b² − ac is taken in the equal form
    /// |k q⊥ − R₀ d⊥|² − |q⊥ × d⊥|² (Lagrange's identity), whose terms are of the order of the
    /// radius squared near the tube: b² and ac are each of the order of |q|², and far from a
    /// thin tube their f32 difference lost the radius, widening it
    /// (`a_thin_tube_far_away_is_hit_across_its_width`).
    #[inline]
    pub fn intersect(&self, ray: &Ray) -> f32 {
        let q = ray.origin - self.a;
        let d = ray.direction;
        let (qs, ds) = (q.dot(self.axis), d.dot(self.axis));
        let (qp, dp) = (q - self.axis * qs, d - self.axis * ds);
        let r0 = self.radius_a + self.taper * qs;
        let k = self.taper * ds;
        let a = dp.length_squared() - k * k;
        let b = qp.dot(dp) - r0 * k;
        let c = qp.length_squared() - r0 * r0;
        if a <= 0.0 || c <= 0.0 {
            // Along the axis, or starting inside: no entering hit.
            return f32::INFINITY;
        }
        let disc = (qp * k - dp * r0).length_squared() - qp.cross(dp).length_squared();
        if disc < 0.0 || b >= 0.0 {
            return f32::INFINITY;
        }
        let t = (-b - disc.sqrt()) / a;
        if !(t > ray.tmin && t < ray.tmax) {
            return f32::INFINITY;
        }
        let p = q + d * t;
        let end = p - self.axis * self.length;
        if p.dot(self.mitre_a) >= 0.0 && end.dot(self.mitre_b) < 0.0 {
            t
        } else {
            f32::INFINITY
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use cuticle_groom::GroomParts;
    use glam::Vec3;

    pub(crate) fn bent_strand() -> Groom {
        Groom::from_parts(GroomParts {
            positions: vec![
                Vec3::new(0.0, 0.0, 0.0),
                Vec3::new(0.0, 0.0, 1.0),
                Vec3::new(0.0, 0.6, 1.8),
            ],
            thickness: vec![0.2; 3],
            strand_offsets: vec![0, 3],
            ..GroomParts::default()
        })
        .unwrap()
    }

    fn hits(tubes: &Tubes, origin: Vec3A, dir: Vec3A) -> Vec<f32> {
        let ray = Ray::new_inf(origin, dir.normalize());
        tubes
            .tubes
            .iter()
            .map(|t| t.intersect(&ray))
            .filter(|t| t.is_finite())
            .collect()
    }

    /// A fan of rays across the joint of a bent strand: every ray whose line passes within
    /// the radius of the chain's axis hits exactly one tube (no crack, no double hit), and
    /// none farther out does.
    #[test]
    fn a_bent_chain_has_no_cracks_and_no_double_hits() {
        let tubes = Tubes::from_groom(&bent_strand());
        assert_eq!(tubes.len(), 2);
        let (mut inside, mut outside) = (0, 0);
        for i in 0..400 {
            for j in 0..50 {
                // Rays along x through the plane x = 0 near the joint at (0, 0, 1).
                let y = -0.3 + 0.6 * i as f32 / 400.0;
                let z = 0.7 + 0.6 * j as f32 / 50.0;
                let n = hits(&tubes, Vec3A::new(-5.0, y, z), Vec3A::X).len();
                let inner = within_chain(y, z, 0.1 - 1e-3);
                let outer = !within_chain(y, z, 0.1 + 1e-3);
                if inner {
                    assert_eq!(n, 1, "y {y} z {z}");
                    inside += 1;
                }
                if outer {
                    assert_eq!(n, 0, "y {y} z {z}");
                    outside += 1;
                }
            }
        }
        assert!(inside > 1000 && outside > 1000, "{inside} {outside}");
    }

    /// Whether the ray along x through (0, y, z) crosses the mitred chain, whose axis lies in
    /// the plane x = 0: within `r` of segment k's axis line and between its two cut planes.
    fn within_chain(y: f32, z: f32, r: f32) -> bool {
        use glam::Vec2;
        let p = Vec2::new(y, z);
        let (a, b, c) = (Vec2::ZERO, Vec2::new(0.0, 1.0), Vec2::new(0.6, 1.8));
        let (d1, d2) = ((b - a).normalize(), (c - b).normalize());
        let n = (d1 + d2).normalize();
        let perp = |o: Vec2, d: Vec2| (p - o).perp_dot(d).abs();
        let first = perp(a, d1) < r && (p - a).dot(d1) >= 0.0 && (p - b).dot(n) < 0.0;
        let second = perp(b, d2) < r && (p - b).dot(n) >= 0.0 && (p - c).dot(d2) < 0.0;
        first || second
    }

    /// A tube of radius 0.01 seen from 12 units away (the default scene's fibers from its
    /// camera): rays aimed across it at 20,000 points of a line through its axis, normal to
    /// both the axis and the view, hit it over 2r within 0.5 % (the silhouette's own excess,
    /// D / √(D² − r²), is 4e-7). The discriminant as b² − ac in f32 hit it 5.9 % wider.
    #[test]
    fn a_thin_tube_far_away_is_hit_across_its_width() {
        let r = 0.01f32;
        let tubes = Tubes::from_groom(
            &Groom::from_parts(GroomParts {
                positions: vec![Vec3::new(-2.0, 0.3, 0.1), Vec3::new(2.0, -0.2, 0.4)],
                thickness: vec![2.0 * r; 2],
                strand_offsets: vec![0, 2],
                ..GroomParts::default()
            })
            .unwrap(),
        );
        let axis = tubes.tubes[0].axis;
        let centre = tubes.tubes[0].a + axis * 1.7;
        let eye = centre + Vec3A::new(0.37, -11.0, 4.3).normalize() * 12.0;
        let across = (centre - eye).cross(axis).normalize();
        let (n, span) = (20_000, 4.0 * r);
        let hit = (0..n)
            .filter(|&i| {
                let p = centre + across * (span * ((i as f32 + 0.5) / n as f32 - 0.5));
                !hits(&tubes, eye, p - eye).is_empty()
            })
            .count();
        let width = hit as f32 * span / n as f32;
        assert!(
            (width / (2.0 * r) - 1.0).abs() < 5e-3,
            "{} × 2r",
            width / (2.0 * r)
        );
    }

    #[test]
    fn rays_starting_on_the_axis_leave_their_own_fiber_unseen() {
        let tubes = Tubes::from_groom(&bent_strand());
        for dir in [Vec3A::X, Vec3A::Y, Vec3A::new(0.3, -1.0, 0.2), Vec3A::Z] {
            assert!(hits(&tubes, Vec3A::new(0.0, 0.0, 0.5), dir).is_empty());
            assert!(hits(&tubes, Vec3A::new(0.0, 0.0, 1.0), dir).is_empty());
        }
    }

    #[test]
    fn offset_runs_across_the_projected_width() {
        let tubes = Tubes::from_groom(&bent_strand());
        for y in [-0.09f64, -0.05, 0.0, 0.07] {
            let origin = DVec3::new(-5.0, y, 0.5);
            let ray = Ray::new_inf(origin.as_vec3().into(), Vec3A::X);
            let t = tubes.tubes[0].intersect(&ray);
            let f = tubes.frame(TubeHit { tube: 0, t }, origin, DVec3::X);
            // Seen from −x with u = +z: v = −x, w = u × v = −y, so h = −(offset · w) = y / r.
            assert!((f.h - y / 0.1).abs() < 1e-4, "y {y}: h {}", f.h);
            assert!((f.on_axis - DVec3::new(0.0, 0.0, 0.5)).length() < 1e-5);
        }
    }
}
