//! The fiber frame at each point: u the strand tangent, v the part of the outward direction
//! from the origin (the head's centre in procedural grooms) normal to u, so that an elliptical
//! fiber's axes (Xu et al. 2011 eq. 24, through φ_h) keep one orientation relative to the scalp.

use cuticle_fiber::FiberFrame;
use cuticle_groom::Groom;
use glam::DVec3;

/// The frame at point `i` of `groom`.
pub fn frame_at(groom: &Groom, i: usize) -> FiberFrame {
    let t = groom.tangents()[i].as_dvec3();
    let tangent = if t.length_squared() > 1e-20 {
        t
    } else {
        DVec3::Z
    };
    FiberFrame::from_tangent(tangent, groom.positions()[i].as_dvec3())
}

/// The strand each point belongs to.
pub fn strand_of_points(groom: &Groom) -> Vec<u32> {
    let mut out = vec![0u32; groom.point_count()];
    for s in 0..groom.strand_count() {
        for i in groom.strand_range(s) {
            out[i] = s as u32;
        }
    }
    out
}
