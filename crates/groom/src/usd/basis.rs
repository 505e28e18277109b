//! Cubic curve bases of `UsdGeomBasisCurves`, and the rule that turns a curve into the
//! polyline the renderers draw.
//!
//! **Subdivision rule.** A `linear` curve keeps its points. A `cubic` curve is cut into its
//! segments (below), and each segment is evaluated at [`STEPS`] + 1 evenly spaced parameters
//! u = k / [`STEPS`], k = 0..=[`STEPS`]; neighbouring segments share their end point, so a curve of
//! S segments becomes S·[`STEPS`] + 1 points.
//!
//! Segments (USD `UsdGeomBasisCurves` documentation, "Segment Indexing"), for n control points:
//! - `bezier`: 4 points a segment, step 3: n = 3S + 1 (n ≥ 4); the curve passes through every
//!   third point. `pinned` changes nothing.
//! - `bspline`, `catmullRom`, `nonperiodic`: 4 points a segment, step 1: S = n − 3 (n ≥ 4).
//! - `bspline`, `catmullRom`, `pinned`: a phantom point is added at each end,
//!   P₋₁ = 2P₀ − P₁ and Pₙ = 2Pₙ₋₁ − Pₙ₋₂, so the curve starts at P₀ and ends at Pₙ₋₁:
//!   S = n − 1 (n ≥ 2).
//!
//! The weights of a segment's four points at u are each basis's cubic polynomials (Foley et al.,
//! *Computer Graphics: Principles and Practice*, 2nd ed., eqs. 11.29 Bézier, 11.43 uniform
//! B-spline; Catmull and Rom 1974 with tension ½).

/// Parameter steps per cubic segment.
pub const STEPS: usize = 8;

/// A cubic basis of USD.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Basis {
    Bezier,
    Bspline,
    CatmullRom,
}

impl Basis {
    /// The basis named by a USD `basis` token, if this reader draws it.
    pub fn from_token(token: &str) -> Option<Self> {
        match token {
            "bezier" => Some(Self::Bezier),
            "bspline" => Some(Self::Bspline),
            "catmullRom" => Some(Self::CatmullRom),
            _ => None,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Self::Bezier => "bezier",
            Self::Bspline => "bspline",
            Self::CatmullRom => "catmullRom",
        }
    }

    /// The weights of a segment's four control points at parameter `u` ∈ [0, 1].
    pub fn weights(self, u: f64) -> [f64; 4] {
        let (u2, u3) = (u * u, u * u * u);
        let v = 1.0 - u;
        match self {
            Self::Bezier => [v * v * v, 3.0 * u * v * v, 3.0 * u2 * v, u3],
            Self::Bspline => [
                v * v * v / 6.0,
                (3.0 * u3 - 6.0 * u2 + 4.0) / 6.0,
                (-3.0 * u3 + 3.0 * u2 + 3.0 * u + 1.0) / 6.0,
                u3 / 6.0,
            ],
            Self::CatmullRom => [
                (-u3 + 2.0 * u2 - u) / 2.0,
                (3.0 * u3 - 5.0 * u2 + 2.0) / 2.0,
                (-3.0 * u3 + 4.0 * u2 + u) / 2.0,
                (u3 - u2) / 2.0,
            ],
        }
    }
}

/// How a curve of `n` points is cut into segments.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Segments {
    pub basis: Basis,
    pub pinned: bool,
}

impl Segments {
    /// Fewest control points a curve of this kind needs.
    pub fn min_points(self) -> usize {
        if self.pinned && self.basis != Basis::Bezier {
            2
        } else {
            4
        }
    }

    /// Number of segments of a curve of `n` points, or `None` when `n` makes no whole curve.
    pub fn count(self, n: usize) -> Option<usize> {
        if n < self.min_points() {
            return None;
        }
        match (self.basis, self.pinned) {
            (Basis::Bezier, _) => (n - 1).is_multiple_of(3).then_some((n - 1) / 3),
            (_, true) => Some(n - 1),
            (_, false) => Some(n - 3),
        }
    }

    /// The polyline of a curve with control values `p` (points, or a scalar per point), in
    /// the subdivision rule's order; `p.len()` must pass [`Self::count`].
    pub fn evaluate<T: Lerp>(self, p: &[T], out: &mut Vec<T>) {
        let Some(segments) = self.count(p.len()) else {
            return;
        };
        let extended;
        let (points, step) = match (self.basis, self.pinned) {
            (Basis::Bezier, _) => (p, 3),
            (_, true) => {
                let n = p.len();
                let mut e = Vec::with_capacity(n + 2);
                e.push(p[0].phantom(p[1]));
                e.extend_from_slice(p);
                e.push(p[n - 1].phantom(p[n - 2]));
                extended = e;
                (&extended[..], 1)
            }
            (_, false) => (p, 1),
        };
        for s in 0..segments {
            let c = &points[s * step..s * step + 4];
            let first = if s == 0 { 0 } else { 1 };
            for k in first..=STEPS {
                let w = self.basis.weights(k as f64 / STEPS as f64);
                out.push(T::combine(c, w));
            }
        }
    }
}

/// A value a basis can combine: a point or a scalar.
pub trait Lerp: Copy {
    /// Σ wᵢ cᵢ over the four control values.
    fn combine(c: &[Self], w: [f64; 4]) -> Self;
    /// The phantom end value 2·self − next.
    fn phantom(self, next: Self) -> Self;
}

impl Lerp for glam::DVec3 {
    fn combine(c: &[Self], w: [f64; 4]) -> Self {
        c[0] * w[0] + c[1] * w[1] + c[2] * w[2] + c[3] * w[3]
    }
    fn phantom(self, next: Self) -> Self {
        2.0 * self - next
    }
}

impl Lerp for f64 {
    fn combine(c: &[Self], w: [f64; 4]) -> Self {
        c[0] * w[0] + c[1] * w[1] + c[2] * w[2] + c[3] * w[3]
    }
    fn phantom(self, next: Self) -> Self {
        2.0 * self - next
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each basis's weights sum to one (the curve moves with its points).
    #[test]
    fn weights_are_a_partition_of_unity() {
        for basis in [Basis::Bezier, Basis::Bspline, Basis::CatmullRom] {
            for k in 0..=10 {
                let sum: f64 = basis.weights(k as f64 / 10.0).iter().sum();
                assert!((sum - 1.0).abs() < 1e-12, "{basis:?}");
            }
        }
    }

    #[test]
    fn segment_counts_follow_the_usd_rules() {
        let s = |basis, pinned| Segments { basis, pinned };
        assert_eq!(s(Basis::Bezier, false).count(7), Some(2));
        assert_eq!(s(Basis::Bezier, false).count(6), None);
        assert_eq!(s(Basis::Bezier, true).count(4), Some(1));
        assert_eq!(s(Basis::Bspline, false).count(7), Some(4));
        assert_eq!(s(Basis::Bspline, false).count(3), None);
        assert_eq!(s(Basis::CatmullRom, true).count(2), Some(1));
        assert_eq!(s(Basis::CatmullRom, true).count(1), None);
    }
}
