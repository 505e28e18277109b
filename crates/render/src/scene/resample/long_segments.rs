//! Step 1: segments much longer than an opacity texel split evenly. A segment spanning many
//! texels shows its two endpoints' light, blended, however the light runs between them; a
//! coarsely sampled file (straight.hair: 15 segments of 5 units for a groom 60 units in
//! bounding radius, 11 opacity texels a segment at 256) is cut to [`MAX_SEGMENT`] before
//! step 2 looks where the light bends.

use super::knots::{Knots, rebuild};
use cuticle_groom::Groom;

/// Longest segment kept whole, as a fraction of the groom's bounding radius: 1/12, about 20
/// opacity-map texels at the default 256. The built-in groom's segments (up to about 1/16)
/// stay whole; straight.hair's (just over 1/12) are split in two.
pub const MAX_SEGMENT: f32 = 1.0 / 12.0;

/// `groom` with every segment longer than [`MAX_SEGMENT`] of its bounding radius split into
/// equal pieces (points, thickness, colour and transparency interpolated linearly; strand
/// appearance kept). A groom with none that long is returned as it is.
pub fn split_long_segments(groom: Groom) -> Groom {
    if groom.point_count() == 0 {
        return groom;
    }
    let b = groom.bounds();
    let limit = MAX_SEGMENT * 0.5 * (b.max - b.min).length();
    if !limit.is_finite() || limit <= 0.0 {
        return groom;
    }
    let pos = groom.positions();
    let knots = Knots(
        (0..groom.strand_count())
            .map(|s| {
                let r = groom.strand_range(s);
                let mut strand = vec![0.0];
                for i in 0..r.len().saturating_sub(1) {
                    let (a, b) = (pos[r.start + i], pos[r.start + i + 1]);
                    let k = ((a.distance(b) / limit).ceil() as usize).max(1);
                    strand.extend((1..=k).map(|j| i as f64 + j as f64 / k as f64));
                }
                strand
            })
            .collect(),
    );
    rebuild(groom, &knots)
}

#[cfg(test)]
mod tests {
    use super::*;
    use cuticle_groom::GroomParts;
    use glam::Vec3;

    fn strand(points: &[Vec3]) -> Groom {
        Groom::from_parts(GroomParts {
            positions: points.to_vec(),
            thickness: (0..points.len()).map(|i| 0.1 + 0.1 * i as f32).collect(),
            strand_offsets: vec![0, points.len() as u32],
            ..GroomParts::default()
        })
        .unwrap()
    }

    /// A strand of one long and many short segments: the long one is split evenly, the short
    /// ones kept, the ends and thickness carried over; a groom with short segments only is
    /// returned unchanged.
    #[test]
    fn only_long_segments_are_split() {
        let mut points: Vec<Vec3> = (0..=96)
            .map(|i| Vec3::new(i as f32 * 0.01, 0.0, 0.0))
            .collect();
        points.push(Vec3::new(0.96, 0.5, 0.0));
        let g = split_long_segments(strand(&points));
        let p = g.positions();
        assert_eq!(p[0], points[0]);
        assert_eq!(*p.last().unwrap(), *points.last().unwrap());
        // Bounding radius √(0.96² + 0.5²)/2: the 0.5 segment becomes ⌈0.5 / limit⌉ pieces.
        let limit = MAX_SEGMENT * 0.5 * (0.96f32.powi(2) + 0.25).sqrt();
        let pieces = (0.5 / limit).ceil() as usize;
        assert!(pieces > 5, "{pieces}");
        assert_eq!(g.point_count(), 97 + pieces);
        let t = g.thickness();
        assert!(
            (t[97] - (9.7 + 0.1 / pieces as f32)).abs() < 1e-4,
            "{}",
            t[97]
        );
        // 0.01 apart beside a short strand a unit away (limit ≥ 1.386/2/12): none split.
        let mut short: Vec<Vec3> = (0..=96)
            .map(|i| Vec3::new(i as f32 * 0.01, 0.0, 0.0))
            .collect();
        short.extend([Vec3::new(0.0, 1.0, 0.0), Vec3::new(0.0, 1.0, 0.01)]);
        let two = Groom::from_parts(GroomParts {
            thickness: vec![0.1; short.len()],
            strand_offsets: vec![0, 97, 99],
            positions: short,
            ..GroomParts::default()
        })
        .unwrap();
        assert_eq!(split_long_segments(two).point_count(), 99);
    }
}
