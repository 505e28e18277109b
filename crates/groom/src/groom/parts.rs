//! [`GroomParts`]: the raw arrays a groom is built from, and the checks they must pass.

use crate::error::GroomError;
use glam::Vec3;

/// The arrays of a groom, before its derived data (tangents, lengths, bounds) is computed.
///
/// Points of all strands lie in one array; strand `i` owns the points
/// `strand_offsets[i]..strand_offsets[i + 1]`, so `strand_offsets` has one entry more than
/// there are strands, starts at 0 and ends at the point count.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct GroomParts {
    pub positions: Vec<Vec3>,
    /// Per point: the strand's diameter there, in the units of `positions`.
    pub thickness: Vec<f32>,
    /// Per point, optional: RGB colour.
    pub colors: Option<Vec<Vec3>>,
    /// Per point, optional: transparency (0 opaque, as in `.hair` files).
    pub transparency: Option<Vec<f32>>,
    pub strand_offsets: Vec<u32>,
}

impl GroomParts {
    /// Most points a groom may hold: offsets are u32.
    pub const MAX_POINTS: usize = u32::MAX as usize;

    /// The largest |coordinate| of a position, and the largest thickness, in a groom's units
    /// (real grooms span tens of them): beyond it the path tracer's BVH and the renderers' f32
    /// arithmetic (lengths, bounds, squared distances) overflow — at 1e20 the BVH builder
    /// panicked (issue 57 #2), at 3e38 a strand's length was ∞. Every groom passes this check,
    /// and `.hair` files are held to it when read.
    pub const MAX_COORDINATE: f32 = 1e6;

    /// Checks offsets, array lengths, finiteness and [`Self::MAX_COORDINATE`].
    pub fn validate(&self) -> Result<(), GroomError> {
        self.check_offsets()?;
        let points = self.positions.len();
        check_len("thickness", points, self.thickness.len())?;
        if let Some(colors) = &self.colors {
            check_len("colour", points, colors.len())?;
        }
        if let Some(transparency) = &self.transparency {
            check_len("transparency", points, transparency.len())?;
        }
        check_finite("position", self.positions.iter().map(|p| p.is_finite()))?;
        check_finite("thickness", self.thickness.iter().map(|t| t.is_finite()))?;
        check_bounded(
            "position",
            self.positions.iter().map(|p| p.abs().max_element()),
        )?;
        check_bounded("thickness", self.thickness.iter().map(|t| t.abs()))?;
        check_finite(
            "colour",
            self.colors.iter().flatten().map(|c| c.is_finite()),
        )?;
        check_finite(
            "transparency",
            self.transparency.iter().flatten().map(|t| t.is_finite()),
        )
    }

    fn check_offsets(&self) -> Result<(), GroomError> {
        let points = self.positions.len();
        if points > Self::MAX_POINTS {
            return Err(GroomError::TooManyPoints {
                points,
                limit: Self::MAX_POINTS,
            });
        }
        let first = self.strand_offsets.first().copied().unwrap_or(0);
        let last = self.strand_offsets.last().copied().unwrap_or(0);
        if first != 0 || last as usize != points || self.strand_offsets.is_empty() {
            return Err(GroomError::OffsetBounds {
                first: first.into(),
                last: last.into(),
                points,
            });
        }
        match self.strand_offsets.windows(2).position(|w| w[1] <= w[0]) {
            Some(strand) => Err(GroomError::EmptyStrand { strand }),
            None => Ok(()),
        }
    }
}

fn check_len(array: &'static str, expected: usize, actual: usize) -> Result<(), GroomError> {
    if expected != actual {
        return Err(GroomError::ArrayLength {
            array,
            expected,
            actual,
            per: "points",
        });
    }
    Ok(())
}

fn check_finite(array: &'static str, finite: impl Iterator<Item = bool>) -> Result<(), GroomError> {
    let mut finite = finite;
    match finite.position(|ok| !ok) {
        Some(index) => Err(GroomError::NonFinite { array, index }),
        None => Ok(()),
    }
}

fn check_bounded(array: &'static str, sizes: impl Iterator<Item = f32>) -> Result<(), GroomError> {
    let mut sizes = sizes;
    match sizes.position(|s| s > GroomParts::MAX_COORDINATE) {
        Some(index) => Err(GroomError::OutOfRange {
            array,
            index,
            bound: GroomParts::MAX_COORDINATE,
        }),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn two_strands() -> GroomParts {
        GroomParts {
            positions: vec![Vec3::ZERO, Vec3::Z, Vec3::X, Vec3::ONE, Vec3::Y],
            thickness: vec![0.1; 5],
            strand_offsets: vec![0, 2, 5],
            ..GroomParts::default()
        }
    }

    #[test]
    fn consistent_parts_pass() {
        assert_eq!(two_strands().validate(), Ok(()));
    }

    #[test]
    fn each_inconsistency_is_named() {
        let mut parts = two_strands();
        parts.strand_offsets = vec![0, 2, 2, 5];
        assert_eq!(parts.validate(), Err(GroomError::EmptyStrand { strand: 1 }));
        let mut parts = two_strands();
        parts.strand_offsets = vec![0, 2, 4];
        assert!(matches!(
            parts.validate(),
            Err(GroomError::OffsetBounds { last: 4, .. })
        ));
        let mut parts = two_strands();
        parts.colors = Some(vec![Vec3::ONE; 4]);
        assert!(matches!(
            parts.validate(),
            Err(GroomError::ArrayLength {
                array: "colour",
                ..
            })
        ));
        let mut parts = two_strands();
        parts.positions[3].y = f32::INFINITY;
        let expected = GroomError::NonFinite {
            array: "position",
            index: 3,
        };
        assert_eq!(parts.validate(), Err(expected));
        let mut parts = two_strands();
        parts.positions[4].x = -1e20;
        assert!(matches!(
            parts.validate(),
            Err(GroomError::OutOfRange {
                array: "position",
                index: 4,
                ..
            })
        ));
    }
}
