//! Long segments split for shading. The renderer shades and shadows a groom at its points and
//! interpolates colour along each segment between them (`frame::renderer::Renderer::resolve`):
//! a segment spanning several opacity-map texels shows its two endpoints' light, blended.
//! Where hair thins the last point of a strand is its most exposed one, so a coarsely sampled
//! file (straight.hair: 15 segments of 5 units for a groom 60 units in bounding radius, 11
//! opacity texels a segment at 256) spreads unshadowed light up the whole last segment: the
//! bottom fifth of that groom's direct light was 1.4–1.7× what it is with its segments split
//! in four (measured under st_fagans_interior_1k.hdr at 360 × 240). Splitting costs shading time in proportion to the
//! points it adds, so only segments longer than [`MAX_SEGMENT`] of the bounding radius are
//! split, into equal pieces.

use cuticle_groom::{Groom, GroomParts};

/// Longest segment kept whole, as a fraction of the groom's bounding radius: 1/12, about 20
/// opacity-map texels at the default 256. The built-in groom's segments (up to about 1/16)
/// stay whole, so the default scene shades the points it always had; straight.hair's
/// (just over 1/12) are split in two.
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
    let pieces = |a: glam::Vec3, b: glam::Vec3| ((a.distance(b) / limit).ceil() as usize).max(1);
    let pos = groom.positions();
    let long = (0..groom.strand_count()).any(|s| {
        let r = groom.strand_range(s);
        (r.start..r.end.saturating_sub(1)).any(|i| pieces(pos[i], pos[i + 1]) > 1)
    });
    if !long || !limit.is_finite() || limit <= 0.0 {
        return groom;
    }
    let parts = groom.parts();
    let mut out = GroomParts {
        positions: Vec::new(),
        thickness: Vec::new(),
        colors: parts.colors.as_ref().map(|_| Vec::new()),
        transparency: parts.transparency.as_ref().map(|_| Vec::new()),
        strand_offsets: vec![0],
    };
    for s in 0..groom.strand_count() {
        let r = groom.strand_range(s);
        for i in r.clone() {
            let k = if i + 1 < r.end {
                pieces(pos[i], pos[i + 1])
            } else {
                1
            };
            for j in 0..k {
                let t = j as f32 / k as f32;
                let next = (i + 1).min(r.end - 1);
                out.positions.push(pos[i].lerp(pos[next], t));
                out.thickness
                    .push(parts.thickness[i] + t * (parts.thickness[next] - parts.thickness[i]));
                if let (Some(c), Some(src)) = (out.colors.as_mut(), parts.colors.as_ref()) {
                    c.push(src[i].lerp(src[next], t));
                }
                if let (Some(c), Some(src)) =
                    (out.transparency.as_mut(), parts.transparency.as_ref())
                {
                    c.push(src[i] + t * (src[next] - src[i]));
                }
            }
        }
        out.strand_offsets.push(out.positions.len() as u32);
    }
    let appearance = groom.appearance().to_vec();
    Groom::from_parts(out)
        .and_then(|g| g.with_appearance(appearance))
        .expect("splitting keeps a valid groom valid")
}

#[cfg(test)]
mod tests {
    use super::*;
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
