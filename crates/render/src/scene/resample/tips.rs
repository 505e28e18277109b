//! Step 2: each strand's last segment halved where its light bends. Where hair thins a
//! strand's last point is its most exposed one, lit from below and the sides while the point
//! before it lies inside the hair; the light rises steeply over the last stretch, not
//! linearly, so the blend between the two spreads the tip's light up the whole segment and
//! the tips come out too bright.
//!
//! The test is the light itself, as the maps give it: the mean transmittance T̄ of [`PROBES`]
//! directional lights spread over the sphere (deep opacity maps, as shading reads them, at
//! [`PROBE_RESOLUTION`]). A piece of the last segment is halved where T̄ at its midpoint departs
//! from the mean of its ends' T̄ by more than [`BEND_TOLERANCE`], and its halves are tested in
//! turn, down to a texel of the shading's maps. A tip whose light is linear keeps its points,
//! whatever the segment's length. The probes depend on the groom alone, so a groom always gets
//! the same points, whatever its lights.
//!
//! Only the last segment: testing every segment the same way adds points all along the
//! strands for little change in the image (docs/tips.md has the measurement).

use super::knots::{Knots, rebuild, segment_at};
use crate::frame::shadow::{DirectionalMaps, ShadowOptions};
use crate::frame::sub_lights::fibonacci_sphere;
use cuticle_groom::Groom;
use rayon::prelude::*;

/// Directional lights whose mean transmittance is tested.
pub const PROBES: usize = 8;
/// Texels along each side of a probe's map.
pub const PROBE_RESOLUTION: usize = 128;
/// Largest departure of a midpoint's T̄ from the mean of its piece's ends that is left
/// unsplit (T̄ is 1 for an unshadowed point).
pub const BEND_TOLERANCE: f64 = 0.02;

/// `groom` with each strand's last segment halved where its light bends (module doc).
pub fn split_tips(groom: Groom) -> Groom {
    if groom.point_count() == 0 {
        return groom;
    }
    let b = groom.bounds();
    // The finest piece worth cutting: a texel of the maps shading reads, at their default size.
    let texel = f64::from((b.max - b.min).length()) / ShadowOptions::default().resolution as f64;
    if !texel.is_finite() || texel <= 0.0 {
        return groom;
    }
    let maps = DirectionalMaps::build(
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
            .map(|s| strand_knots(&groom, s, &maps, texel))
            .collect(),
    );
    rebuild(groom, &knots)
}

/// Strand `s`'s knots: its points, and the midpoints its last segment keeps.
fn strand_knots(groom: &Groom, s: usize, maps: &DirectionalMaps, texel: f64) -> Vec<f64> {
    let r = groom.strand_range(s);
    let pos = &groom.positions()[r];
    let mut knots: Vec<f64> = (0..pos.len()).map(|i| i as f64).collect();
    if pos.len() < 2 {
        return knots;
    }
    let tip = knots.pop().expect("two points");
    let length = f64::from(pos[pos.len() - 2].distance(pos[pos.len() - 1]));
    let at = |u: f64| {
        let (i, t) = segment_at(u, pos.len());
        maps.mean_transmittance(pos[i].lerp(pos[i + 1], t).as_dvec3())
    };
    // Pieces still to test, as (start, end, T̄ at start, T̄ at end); kept midpoints.
    let mut open = vec![(tip - 1.0, tip, at(tip - 1.0), at(tip))];
    let mut kept = Vec::new();
    while let Some((u0, u1, t0, t1)) = open.pop() {
        if (u1 - u0) * length <= texel {
            continue;
        }
        let mid = 0.5 * (u0 + u1);
        let tm = at(mid);
        if (tm - 0.5 * (t0 + t1)).abs() > BEND_TOLERANCE {
            kept.push(mid);
            open.push((u0, mid, t0, tm));
            open.push((mid, u1, tm, t1));
        }
    }
    kept.sort_by(f64::total_cmp);
    knots.extend(kept);
    knots.push(tip);
    knots
}

#[cfg(test)]
mod tests {
    use super::*;
    use cuticle_groom::GroomParts;
    use glam::Vec3;

    fn hanging(roots: &[(f32, f32, f32)], thickness: f32) -> Groom {
        let mut positions = Vec::new();
        let mut strand_offsets = vec![0];
        for &(x, y, length) in roots {
            positions.extend((0..=4).map(|i| Vec3::new(x, y, -length * i as f32 / 4.0)));
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

    /// A hair-thin lone strand shadows nothing, so its light is flat and its long last segment
    /// stays whole; in a bundle whose strands end at different lengths the tips' light bends
    /// and points are added, on the last segments only.
    #[test]
    fn only_tips_whose_light_bends_are_split() {
        let lone = hanging(&[(0.0, 0.0, 12.0)], 1e-4);
        let before = lone.positions().to_vec();
        assert_eq!(split_tips(lone).positions(), &before[..]);

        let roots: Vec<(f32, f32, f32)> = (0..400)
            .map(|k| {
                let (i, j) = ((k % 20) as f32, (k / 20) as f32);
                (
                    0.3 * i,
                    0.3 * j,
                    8.0 + 4.0 * ((k * 37 % 101) as f32 / 101.0),
                )
            })
            .collect();
        let bundle = hanging(&roots, 0.3);
        let split = split_tips(bundle.clone());
        assert!(split.point_count() > bundle.point_count() + 100);
        for s in 0..split.strand_count() {
            let (old, new) = (bundle.strand_range(s), split.strand_range(s));
            let kept = &split.positions()[new.start..new.start + old.len() - 1];
            assert_eq!(kept, &bundle.positions()[old.start..old.end - 1]);
            assert_eq!(
                split.positions()[new.end - 1],
                bundle.positions()[old.end - 1]
            );
        }
    }
}
