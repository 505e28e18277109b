//! Step 2: each strand's last stretch split where its light bends. Where hair thins, strands
//! end at many lengths: a strand's last stretch runs from inside the hair, shadowed, out to
//! its most exposed point, lit from below and the sides. The light along it rises steeply,
//! not linearly, so the blend between two points far apart spreads the tip's light up the
//! segment and the tips come out too bright.
//!
//! The test is the light itself, as the maps give it: the transmittance T of [`PROBES`]
//! directional lights spread over the sphere (deep opacity maps, as shading reads them, at
//! [`PROBE_RESOLUTION`]). Each segment within [`TIP_ZONE`] of the tip is tested: a piece is
//! halved where, for any probe, T at its midpoint departs from the mean of its ends' T by more
//! than [`BEND_TOLERANCE`], and its halves are tested in turn, down to a texel of the probes'
//! maps (finer, a probe sees the bilinear blend of its own texels, not the light). A stretch
//! whose light is linear keeps its points, whatever its length. The probes depend on the
//! groom alone, so a groom always gets the same points, whatever its lights.
//!
//! Why per probe and only near the tips: the mean T̄ over the probes hides a bend that one
//! direction sees, and testing whole strands adds points all along them for little change in
//! the image (docs/tips.md has both measurements).

use super::knots::{Knots, rebuild, segment_at};
use crate::frame::shadows::{DirectionalShadows, ShadowOptions};
use crate::frame::sub_lights::fibonacci_sphere;
use cuticle_groom::Groom;
use rayon::prelude::*;

/// Directional lights whose transmittance is tested.
pub const PROBES: usize = 8;
/// Texels along each side of a probe's map.
pub const PROBE_RESOLUTION: usize = 128;
/// Largest departure of a midpoint's T from the mean of its piece's ends, for any probe, that
/// is left unsplit (T is 1 for an unshadowed point).
pub const BEND_TOLERANCE: f64 = 0.02;
/// How far up from its tip a strand is tested, as a fraction of the groom's bounding radius: the
/// longest segment step 1 leaves, so at least the last two segments of a strand whose
/// segments are that long. A segment that begins within it is tested whole.
pub const TIP_ZONE: f32 = super::MAX_SEGMENT;

/// `groom` with each strand's last stretch split where its light bends (module doc).
pub fn split_tips(groom: Groom) -> Groom {
    if groom.point_count() == 0 {
        return groom;
    }
    let b = groom.bounds();
    let diagonal = (b.max - b.min).length();
    let texel = f64::from(diagonal) / PROBE_RESOLUTION as f64;
    let zone = TIP_ZONE * 0.5 * diagonal;
    if !texel.is_finite() || texel <= 0.0 {
        return groom;
    }
    let maps = DirectionalShadows::build(
        &groom,
        &fibonacci_sphere(PROBES),
        &ShadowOptions {
            resolution: PROBE_RESOLUTION,
            ..ShadowOptions::default()
        },
    );
    let knots = Knots(
        (0..groom.strand_count())
            .into_par_iter()
            .map(|s| strand_knots(&groom, s, &maps, Lengths { texel, zone }))
            .collect(),
    );
    rebuild(groom, &knots)
}

/// The two lengths the test works to, in the groom's units.
#[derive(Clone, Copy)]
struct Lengths {
    /// A texel of the probes' maps: the finest piece worth cutting (module doc).
    texel: f64,
    /// How far up from the tip segments are tested.
    zone: f32,
}

/// A piece of a segment still to test: its ends as fractional point indices and each probe's
/// T there.
struct Piece {
    from: f64,
    to: f64,
    t_from: Vec<f64>,
    t_to: Vec<f64>,
}

/// Strand `s`'s knots: its points, and the midpoints its last stretch keeps.
fn strand_knots(groom: &Groom, s: usize, maps: &DirectionalShadows, lengths: Lengths) -> Vec<f64> {
    let pos = &groom.positions()[groom.strand_range(s)];
    let mut knots: Vec<f64> = (0..pos.len()).map(|i| i as f64).collect();
    if pos.len() < 2 {
        return knots;
    }
    let at = |u: f64| {
        let (i, t) = segment_at(u, pos.len());
        maps.transmittances(pos[i].lerp(pos[i + 1], t).as_dvec3())
    };
    // Segments from the tip up, while they begin within the zone; each segment's far end is
    // the start of the one after it, whose T is carried over.
    let mut from_tip = 0.0;
    let mut t_end = at((pos.len() - 1) as f64);
    for seg in (0..pos.len().saturating_sub(1)).rev() {
        if from_tip >= lengths.zone {
            break;
        }
        let length = pos[seg].distance(pos[seg + 1]);
        from_tip += length;
        let t_start = at(seg as f64);
        let mut open = vec![Piece {
            from: seg as f64,
            to: seg as f64 + 1.0,
            t_from: t_start.clone(),
            t_to: std::mem::replace(&mut t_end, t_start),
        }];
        while let Some(piece) = open.pop() {
            if (piece.to - piece.from) * f64::from(length) < lengths.texel {
                continue;
            }
            let mid = 0.5 * (piece.from + piece.to);
            let t_mid = at(mid);
            if largest_bend(&piece, &t_mid) > BEND_TOLERANCE {
                knots.push(mid);
                open.push(Piece {
                    from: piece.from,
                    to: mid,
                    t_from: piece.t_from,
                    t_to: t_mid.clone(),
                });
                open.push(Piece {
                    from: mid,
                    to: piece.to,
                    t_from: t_mid,
                    t_to: piece.t_to,
                });
            }
        }
    }
    knots.sort_by(f64::total_cmp);
    knots
}

/// The largest departure, over the probes, of T at a piece's midpoint from the mean of its
/// ends' T.
fn largest_bend(piece: &Piece, t_mid: &[f64]) -> f64 {
    t_mid
        .iter()
        .zip(piece.t_from.iter().zip(&piece.t_to))
        .map(|(m, (a, b))| (m - 0.5 * (a + b)).abs())
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;
    use cuticle_groom::GroomParts;
    use glam::Vec3;

    /// Vertical strands hanging from `roots` (x, y, length), each in `segments` equal segments.
    fn hanging(roots: &[(f32, f32, f32)], segments: usize, thickness: f32) -> Groom {
        let mut positions = Vec::new();
        let mut strand_offsets = vec![0];
        for &(x, y, length) in roots {
            positions.extend(
                (0..=segments).map(|i| Vec3::new(x, y, -length * i as f32 / segments as f32)),
            );
            strand_offsets.push(positions.len() as u32);
        }
        Groom::from_parts(GroomParts {
            thickness: vec![thickness; positions.len()],
            positions,
            strand_offsets,
            ..GroomParts::default()
        })
        .unwrap()
    }

    /// A 20 × 20 bundle of strands 0.3 apart and 8–12 long, ending at different lengths.
    fn bundle(segments: usize) -> Groom {
        let roots: Vec<(f32, f32, f32)> = (0..400)
            .map(|k| {
                let (i, j) = ((k % 20) as f32, (k / 20) as f32);
                let length = 8.0 + 4.0 * ((k * 37 % 101) as f32 / 101.0);
                (0.3 * i, 0.3 * j, length)
            })
            .collect();
        hanging(&roots, segments, 0.3)
    }

    /// Per strand of `split`, the original segment each added point lies on (the original
    /// points must all be kept, in order).
    fn added_on_segments(original: &Groom, split: &Groom) -> Vec<Vec<usize>> {
        (0..original.strand_count())
            .map(|s| {
                let old = &original.positions()[original.strand_range(s)];
                let new = &split.positions()[split.strand_range(s)];
                let mut segments = Vec::new();
                let mut next = 0;
                for p in new {
                    if next < old.len() && *p == old[next] {
                        next += 1;
                    } else {
                        segments.push(next - 1);
                    }
                }
                assert_eq!(next, old.len(), "strand {s} lost a point");
                segments
            })
            .collect()
    }

    /// A hair-thin lone strand shadows nothing, so its light is flat and its long last segment
    /// stays whole; in a bundle whose strands end at different lengths the tips' light bends
    /// and points are added, on the last segments only (here longer than the zone).
    #[test]
    fn only_tips_whose_light_bends_are_split() {
        let lone = hanging(&[(0.0, 0.0, 12.0)], 4, 1e-4);
        let before = lone.positions().to_vec();
        assert_eq!(split_tips(lone).positions(), &before[..]);

        let bundle = bundle(4);
        let split = split_tips(bundle.clone());
        assert!(split.point_count() > bundle.point_count() + 100);
        for segments in added_on_segments(&bundle, &split) {
            assert!(segments.iter().all(|&k| k == 3), "{segments:?}");
        }
    }

    /// With short segments the zone reaches past the last one: the bundle's light bends over
    /// the last few, and points are added there, on no segment that begins beyond the zone.
    #[test]
    fn segments_within_the_tip_zone_are_tested() {
        let bundle = bundle(40);
        let b = bundle.bounds();
        let zone = TIP_ZONE * 0.5 * (b.max - b.min).length();
        let split = split_tips(bundle.clone());
        let added = added_on_segments(&bundle, &split);
        let mut before_last = 0;
        for (s, segments) in added.iter().enumerate() {
            let pos = &bundle.positions()[bundle.strand_range(s)];
            let tip = pos[pos.len() - 1];
            for &k in segments {
                assert!(pos[k + 1].distance(tip) < zone, "strand {s} segment {k}");
                before_last += usize::from(k + 2 < pos.len());
            }
        }
        assert!(
            before_last > 100,
            "{before_last} points above the last segments"
        );
    }
}
