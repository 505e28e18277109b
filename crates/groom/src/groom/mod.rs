//! [`Groom`]: hair as a renderer reads it. All points of all strands sit in flat arrays, with
//! strand offsets into them, so the arrays can be uploaded or iterated without indirection.

mod parts;
mod strand;

pub use parts::GroomParts;
pub use strand::Strand;

use crate::appearance::Appearance;
use crate::error::GroomError;
use crate::geometry::{Aabb, polyline_length, vertex_tangents};
use glam::Vec3;
use std::ops::Range;

/// Strands as polylines, with their derived geometry and per-strand appearance.
///
/// Geometry is fixed once built (tangents, lengths and bounds are computed from it); the
/// appearance of each strand can be changed freely through [`Groom::appearance_mut`].
#[derive(Clone, Debug, PartialEq)]
pub struct Groom {
    parts: GroomParts,
    tangents: Vec<Vec3>,
    strand_lengths: Vec<f32>,
    bounds: Aabb,
    appearance: Vec<Appearance>,
}

impl Groom {
    /// Builds a groom from its arrays, each strand with the default appearance.
    pub fn from_parts(parts: GroomParts) -> Result<Self, GroomError> {
        parts.validate()?;
        let strands = parts.strand_offsets.len() - 1;
        let mut groom = Self {
            tangents: vec![Vec3::ZERO; parts.positions.len()],
            strand_lengths: Vec::with_capacity(strands),
            bounds: Aabb::of_points(&parts.positions),
            appearance: vec![Appearance::default(); strands],
            parts,
        };
        for i in 0..strands {
            let range = groom.strand_range(i);
            let points = &groom.parts.positions[range.clone()];
            vertex_tangents(points, &mut groom.tangents[range]);
            groom.strand_lengths.push(polyline_length(points));
        }
        Ok(groom)
    }

    /// Replaces the per-strand appearance (one entry per strand).
    pub fn with_appearance(mut self, appearance: Vec<Appearance>) -> Result<Self, GroomError> {
        if appearance.len() != self.strand_count() {
            return Err(GroomError::ArrayLength {
                array: "appearance",
                expected: self.strand_count(),
                actual: appearance.len(),
                per: "strands",
            });
        }
        self.appearance = appearance;
        Ok(self)
    }

    /// The raw arrays, giving up the derived data.
    pub fn into_parts(self) -> GroomParts {
        self.parts
    }

    pub fn parts(&self) -> &GroomParts {
        &self.parts
    }

    pub fn strand_count(&self) -> usize {
        self.parts.strand_offsets.len() - 1
    }

    pub fn point_count(&self) -> usize {
        self.parts.positions.len()
    }

    /// Segments over all strands: points minus strands.
    pub fn segment_count(&self) -> usize {
        self.point_count() - self.strand_count()
    }

    pub fn positions(&self) -> &[Vec3] {
        &self.parts.positions
    }

    /// Per point: diameter, in the units of the positions.
    pub fn thickness(&self) -> &[f32] {
        &self.parts.thickness
    }

    pub fn colors(&self) -> Option<&[Vec3]> {
        self.parts.colors.as_deref()
    }

    pub fn transparency(&self) -> Option<&[f32]> {
        self.parts.transparency.as_deref()
    }

    /// Strand `i` owns points `offsets[i]..offsets[i + 1]`.
    pub fn strand_offsets(&self) -> &[u32] {
        &self.parts.strand_offsets
    }

    /// Per point: unit tangent pointing from root to tip (see [`vertex_tangents`]).
    pub fn tangents(&self) -> &[Vec3] {
        &self.tangents
    }

    /// Per strand: arc length from root to tip.
    pub fn strand_lengths(&self) -> &[f32] {
        &self.strand_lengths
    }

    /// Bounds of all points (centrelines; add half the thickness to enclose the fibers).
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// Per strand: its scattering parameters.
    pub fn appearance(&self) -> &[Appearance] {
        &self.appearance
    }

    /// Per strand, for painting: change any strand's parameters in place.
    pub fn appearance_mut(&mut self) -> &mut [Appearance] {
        &mut self.appearance
    }

    /// Point indices of strand `i`.
    pub fn strand_range(&self, i: usize) -> Range<usize> {
        let offsets = &self.parts.strand_offsets;
        offsets[i] as usize..offsets[i + 1] as usize
    }

    /// The strand each point belongs to (the inverse of [`Self::strand_range`]).
    pub fn strand_of_points(&self) -> Vec<u32> {
        let mut out = vec![0u32; self.point_count()];
        for s in 0..self.strand_count() {
            out[self.strand_range(s)].fill(s as u32);
        }
        out
    }

    /// A view of strand `i`.
    pub fn strand(&self, i: usize) -> Strand<'_> {
        let range = self.strand_range(i);
        Strand {
            positions: &self.parts.positions[range.clone()],
            thickness: &self.parts.thickness[range.clone()],
            tangents: &self.tangents[range.clone()],
            colors: self.parts.colors.as_deref().map(|c| &c[range.clone()]),
            transparency: self.parts.transparency.as_deref().map(|t| &t[range]),
            length: self.strand_lengths[i],
            appearance: &self.appearance[i],
        }
    }

    /// Views of all strands, root to tip each.
    pub fn strands(&self) -> impl ExactSizeIterator<Item = Strand<'_>> + '_ {
        (0..self.strand_count()).map(|i| self.strand(i))
    }
}
