//! The groom's tubes in a BVH: obvhs's compressed-wide BVH (CWBVH, built by PLOC and
//! reinsertion) over each tube's bounds, traversed in f32 with [`Tube::intersect`] at the leaves.
//! BENCHMARKS.md (from `cuticle bench trace`) carries its build time and rays per second.

use crate::tubes::{HitFrame, Tube, TubeHit, Tubes};
use cuticle_groom::Groom;
use glam::{DVec3, Vec3A};
use obvhs::BvhBuildParams;
use obvhs::cwbvh::CwBvh;
use obvhs::cwbvh::builder::build_cwbvh;
use obvhs::ray::{Ray, RayHit};
use std::time::{Duration, Instant};

/// Tubes and the BVH over them (none for a groom without segments).
pub struct Accel {
    tubes: Tubes,
    /// The tube of each BVH primitive (a piece of it), in the BVH's leaf order, so a leaf
    /// reads it without indirection.
    ordered: Vec<Tube>,
    /// The index of each of those tubes in `tubes`.
    ordered_owner: Vec<u32>,
    bvh: Option<CwBvh>,
    pub build_seconds: f64,
}

impl Accel {
    pub fn build(groom: &Groom) -> Self {
        let start = Instant::now();
        let tubes = Tubes::from_groom(groom);
        let (boxes, owner) = tubes.bounds();
        let bvh = (!tubes.is_empty()).then(|| {
            build_cwbvh(
                &boxes,
                BvhBuildParams::medium_build(),
                &mut Duration::default(),
            )
        });
        let (ordered, ordered_owner) = match &bvh {
            Some(b) => b
                .primitive_indices
                .iter()
                .map(|&i| (tubes.tubes[owner[i as usize] as usize], owner[i as usize]))
                .unzip(),
            None => (Vec::new(), Vec::new()),
        };
        Self {
            tubes,
            ordered,
            ordered_owner,
            bvh,
            build_seconds: start.elapsed().as_secs_f64(),
        }
    }

    pub fn tube_count(&self) -> usize {
        self.tubes.len()
    }

    /// The nearest entering hit along the ray, if any.
    pub fn closest(&self, origin: DVec3, dir: DVec3) -> Option<TubeHit> {
        let bvh = self.bvh.as_ref()?;
        let ray = Ray::new_inf(Vec3A::from(origin.as_vec3()), Vec3A::from(dir.as_vec3()));
        let mut hit = RayHit::none();
        bvh.ray_traverse(ray, &mut hit, |ray, id| self.ordered[id].intersect(ray))
            .then(|| TubeHit {
                tube: self.ordered_owner[hit.primitive_id as usize],
                t: hit.t,
            })
    }

    /// Whether anything lies along the ray.
    pub fn occluded(&self, origin: DVec3, dir: DVec3) -> bool {
        let Some(bvh) = self.bvh.as_ref() else {
            return false;
        };
        let ray = Ray::new_inf(Vec3A::from(origin.as_vec3()), Vec3A::from(dir.as_vec3()));
        !bvh.ray_traverse_miss(ray, |ray, id| self.ordered[id].intersect(ray))
    }

    /// The fiber frame of a hit found along (origin, dir).
    pub fn frame(&self, hit: TubeHit, origin: DVec3, dir: DVec3) -> HitFrame {
        self.tubes.frame(hit, origin, dir)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use cuticle_groom::GroomParts;
    use glam::Vec3;

    /// The BVH finds what testing every tube finds, for rays in every direction.
    #[test]
    fn traversal_agrees_with_testing_every_tube() {
        let mut positions = Vec::new();
        let mut offsets = vec![0u32];
        for s in 0..40 {
            for k in 0..8 {
                let (x, y) = ((s % 8) as f32 * 0.3, (s / 8) as f32 * 0.3);
                positions.push(Vec3::new(x + 0.05 * (k as f32).sin(), y, k as f32 * 0.4));
            }
            offsets.push(positions.len() as u32);
        }
        let groom = Groom::from_parts(GroomParts {
            thickness: vec![0.12; positions.len()],
            positions,
            strand_offsets: offsets,
            ..GroomParts::default()
        })
        .unwrap();
        let accel = Accel::build(&groom);
        let tubes = Tubes::from_groom(&groom);
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut hits = 0;
        for _ in 0..4000 {
            let origin = DVec3::new(next() * 3.0 - 0.5, next() * 2.0 - 0.5, next() * 3.0);
            let dir = DVec3::new(next() - 0.5, next() - 0.5, next() - 0.5).normalize();
            let ray = Ray::new_inf(origin.as_vec3().into(), dir.as_vec3().into());
            let brute = (0..tubes.len())
                .map(|i| (tubes.tubes[i].intersect(&ray), i as u32))
                .filter(|(t, _)| t.is_finite())
                .min_by(|a, b| a.0.total_cmp(&b.0));
            let found = accel.closest(origin, dir);
            assert_eq!(found.map(|h| h.tube), brute.map(|b| b.1));
            assert_eq!(accel.occluded(origin, dir), brute.is_some());
            hits += brute.is_some() as usize;
        }
        assert!(hits > 400, "{hits}");
    }
}
