//! Growing a strand's centreline: from its root along the comb direction, bending under
//! gravity, and kept outside the head.

use super::head::Head;
use glam::Vec3;

/// How one centreline grows.
#[derive(Clone, Copy, Debug)]
pub struct Growth {
    pub root: Vec3,
    pub direction: Vec3,
    pub length: f32,
    pub points: usize,
    /// Curvature toward −z, per centimetre of strand.
    pub gravity: f32,
    /// Height above the scalp the strand settles at (volume of the hairdo).
    pub margin: f32,
}

/// Distance along the strand over which it rises from the scalp to its full margin.
const MARGIN_RAMP_CM: f32 = 3.0;

impl Growth {
    /// The centreline's points, root first, spaced `length / (points − 1)` apart.
    pub fn centreline(&self, head: &Head) -> Vec<Vec3> {
        let step = self.length / (self.points - 1) as f32;
        let mut out = Vec::with_capacity(self.points);
        let mut at = self.root;
        let mut heading = self.direction;
        out.push(at);
        for k in 1..self.points {
            heading = (heading + Vec3::NEG_Z * (self.gravity * step)).normalize();
            let margin = self.margin * (k as f32 * step / MARGIN_RAMP_CM).min(1.0);
            let mut next = at + heading * step;
            if let Some(outside) = head.push_out(next, margin) {
                heading = (outside - at).try_normalize().unwrap_or(heading);
                next = at + heading * step;
                next = head.push_out(next, margin).unwrap_or(next);
            }
            out.push(next);
            at = next;
        }
        out
    }
}
