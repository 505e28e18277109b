//! Between the file form ([`HairFile`]) and the renderer's form ([`Groom`]).

use crate::error::HairFileError;
use crate::groom::{Groom, GroomParts};
use crate::hair_file::{HairDefaults, HairFile, HairInfo};
use glam::Vec3;
use std::path::Path;

/// Most points a strand of a `.hair` file can have (its segment count is a u16).
const MAX_STRAND_POINTS: usize = u16::MAX as usize + 1;

impl HairFile {
    /// The groom this file describes, with absent arrays filled from the defaults (thickness)
    /// or left absent (colour, transparency). The file is validated first, as its fields are
    /// public and may have been changed since it was read.
    pub fn into_groom(mut self) -> Result<Groom, HairFileError> {
        self.validate()?;
        let positions = self.points.take().ok_or(HairFileError::NoPoints)?;
        let strand_offsets = std::iter::once(0)
            .chain(self.strand_ranges().map(|r| r.end as u32))
            .collect();
        let thickness = self
            .thickness
            .unwrap_or_else(|| vec![self.defaults.thickness; positions.len()]);
        let parts = GroomParts {
            positions,
            thickness,
            colors: self.colors,
            transparency: self.transparency,
            strand_offsets,
        };
        Ok(Groom::from_parts(parts)?)
    }

    /// The file that stores `groom`. Arrays whose values are all equal become header defaults
    /// (segments when all strands have the same point count, thickness when uniform).
    pub fn from_groom(groom: &Groom, info: &str) -> Result<HairFile, HairFileError> {
        let counts: Vec<usize> = groom.strands().map(|s| s.point_count()).collect();
        if let Some(strand) = counts.iter().position(|&n| n > MAX_STRAND_POINTS) {
            return Err(HairFileError::StrandTooLong {
                strand,
                points: counts[strand],
            });
        }
        let (segments, default_segments) = match uniform(&counts) {
            Some(n) => (None, n as u32 - 1),
            None => (Some(counts.iter().map(|&n| (n - 1) as u16).collect()), 0),
        };
        let (thickness, default_thickness) = match uniform(groom.thickness()) {
            Some(t) => (None, t),
            None => (
                Some(groom.thickness().to_vec()),
                HairDefaults::default().thickness,
            ),
        };
        Ok(HairFile {
            strand_count: groom.strand_count() as u32,
            point_count: groom.point_count() as u32,
            defaults: HairDefaults {
                segments: default_segments,
                thickness: default_thickness,
                ..HairDefaults::default()
            },
            info: HairInfo::from_text(info),
            segments,
            points: Some(groom.positions().to_vec()),
            thickness,
            transparency: groom.transparency().map(<[f32]>::to_vec),
            colors: groom.colors().map(<[Vec3]>::to_vec),
        })
    }
}

impl Groom {
    /// Reads a `.hair` file into a groom.
    pub fn read_hair(path: impl AsRef<Path>) -> Result<Groom, HairFileError> {
        HairFile::read(path)?.into_groom()
    }

    /// The bytes of a `.hair` file holding this groom.
    pub fn to_hair_bytes(&self, info: &str) -> Result<Vec<u8>, HairFileError> {
        HairFile::from_groom(self, info)?.to_bytes()
    }
}

/// The common value of a non-empty slice whose entries are all equal.
fn uniform<T: Copy + PartialEq>(values: &[T]) -> Option<T> {
    let first = *values.first()?;
    values.iter().all(|&v| v == first).then_some(first)
}
