//! Polyline geometry shared by grooms and files: bounding boxes, tangents, lengths.

use glam::Vec3;

/// An axis-aligned bounding box. Empty (min > max) when it holds no point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    pub min: Vec3,
    pub max: Vec3,
}

impl Aabb {
    /// The box holding nothing.
    pub const EMPTY: Aabb = Aabb {
        min: Vec3::INFINITY,
        max: Vec3::NEG_INFINITY,
    };

    /// The smallest box holding all `points`.
    pub fn of_points(points: &[Vec3]) -> Self {
        points.iter().fold(Self::EMPTY, |b, &p| Aabb {
            min: b.min.min(p),
            max: b.max.max(p),
        })
    }

    pub fn is_empty(&self) -> bool {
        self.min.cmpgt(self.max).any()
    }

    pub fn center(&self) -> Vec3 {
        (self.min + self.max) * 0.5
    }

    pub fn size(&self) -> Vec3 {
        if self.is_empty() {
            Vec3::ZERO
        } else {
            self.max - self.min
        }
    }
}

/// Length of a polyline: the sum of its segments.
pub fn polyline_length(points: &[Vec3]) -> f32 {
    points.windows(2).map(|w| w[0].distance(w[1])).sum()
}

/// Unit tangents at the vertices of a polyline, written into `out` (same length as `points`).
///
/// Inside the strand a vertex takes the direction from its previous to its next vertex, the
/// ends take their one segment. Where neighbours coincide the previous tangent carries on; a
/// polyline without extent gets zero tangents.
pub fn vertex_tangents(points: &[Vec3], out: &mut [Vec3]) {
    let last = points.len().saturating_sub(1);
    let mut carried = Vec3::ZERO;
    for (i, slot) in out.iter_mut().enumerate() {
        let chord = points[(i + 1).min(last)] - points[i.saturating_sub(1)];
        carried = chord.try_normalize().unwrap_or(carried);
        *slot = carried;
    }
    if let Some(first) = out.iter().position(|t| *t != Vec3::ZERO) {
        let lead = out[first];
        out[..first].fill(lead);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tangents_follow_a_bent_polyline() {
        let points = [Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0)];
        let mut out = [Vec3::ZERO; 3];
        vertex_tangents(&points, &mut out);
        assert_eq!(out[0], Vec3::X);
        assert!((out[1] - Vec3::new(1.0, 1.0, 0.0).normalize()).length() < 1e-6);
        assert_eq!(out[2], Vec3::Y);
    }

    #[test]
    fn coincident_points_inherit_a_neighbour_tangent() {
        let points = [Vec3::ZERO, Vec3::ZERO, Vec3::ZERO, Vec3::Z, Vec3::Z];
        let mut out = [Vec3::ONE; 5];
        vertex_tangents(&points, &mut out);
        assert!(out.iter().all(|&t| t == Vec3::Z), "{out:?}");
        let mut single = [Vec3::ONE];
        vertex_tangents(&[Vec3::X], &mut single);
        assert_eq!(single[0], Vec3::ZERO);
    }

    #[test]
    fn length_and_bounds_of_a_polyline() {
        let points = [
            Vec3::ZERO,
            Vec3::new(3.0, 4.0, 0.0),
            Vec3::new(3.0, 4.0, -2.0),
        ];
        assert_eq!(polyline_length(&points), 7.0);
        let b = Aabb::of_points(&points);
        assert_eq!(
            (b.min, b.max),
            (Vec3::new(0.0, 0.0, -2.0), Vec3::new(3.0, 4.0, 0.0))
        );
        assert!(Aabb::of_points(&[]).is_empty());
        assert_eq!(Aabb::EMPTY.size(), Vec3::ZERO);
    }
}
