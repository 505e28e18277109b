//! Writing: the same checks the reader makes, then the header and the arrays it announces.

use super::HairFile;
use super::layout::{Layout, check_defaults_finite, check_finite, check_segment_sum};
use crate::error::{HairArray, HairFileError};
use glam::Vec3;
use std::io::Write;

impl HairFile {
    /// Checks that this file would read back as itself: counts within limits and consistent
    /// with each other and with the arrays' lengths, all values finite.
    pub fn validate(&self) -> Result<(), HairFileError> {
        let header = self.header();
        Layout::of(&header)?;
        check_defaults_finite(&header)?;
        self.check_array_lengths()?;
        if let Some(segments) = &self.segments {
            check_segment_sum(segments, self.point_count)?;
        }
        check_finite(HairArray::Points, vec3s(&self.points), 3)?;
        check_finite(HairArray::Thickness, floats(&self.thickness), 1)?;
        check_finite(HairArray::Transparency, floats(&self.transparency), 1)?;
        check_finite(HairArray::Colors, vec3s(&self.colors), 3)?;
        Ok(())
    }

    /// The file's bytes, after [`HairFile::validate`].
    pub fn to_bytes(&self) -> Result<Vec<u8>, HairFileError> {
        self.validate()?;
        let layout = Layout::of(&self.header())?;
        let mut out = Vec::with_capacity(layout.file_len as usize);
        out.extend_from_slice(&self.header().encode());
        for &s in self.segments.iter().flatten() {
            out.extend_from_slice(&s.to_le_bytes());
        }
        extend_vec3s(&mut out, &self.points);
        extend_floats(&mut out, &self.thickness);
        extend_floats(&mut out, &self.transparency);
        extend_vec3s(&mut out, &self.colors);
        Ok(out)
    }

    /// Writes the file to `writer`, after [`HairFile::validate`].
    pub fn write_to(&self, mut writer: impl Write) -> Result<(), HairFileError> {
        writer.write_all(&self.to_bytes()?)?;
        Ok(())
    }

    fn check_array_lengths(&self) -> Result<(), HairFileError> {
        let strands = u64::from(self.strand_count);
        let points = u64::from(self.point_count);
        let lengths = [
            (
                HairArray::Segments,
                self.segments.as_ref().map(Vec::len),
                strands,
            ),
            (
                HairArray::Points,
                self.points.as_ref().map(Vec::len),
                points,
            ),
            (
                HairArray::Thickness,
                self.thickness.as_ref().map(Vec::len),
                points,
            ),
            (
                HairArray::Transparency,
                self.transparency.as_ref().map(Vec::len),
                points,
            ),
            (
                HairArray::Colors,
                self.colors.as_ref().map(Vec::len),
                points,
            ),
        ];
        for (array, actual, expected) in lengths {
            match actual.map(|n| n as u64) {
                Some(actual) if actual != expected => {
                    return Err(HairFileError::ArrayLength {
                        array,
                        expected,
                        actual,
                    });
                }
                _ => {}
            }
        }
        Ok(())
    }
}

fn extend_floats(out: &mut Vec<u8>, values: &Option<Vec<f32>>) {
    for v in values.iter().flatten() {
        out.extend_from_slice(&v.to_le_bytes());
    }
}

fn extend_vec3s(out: &mut Vec<u8>, values: &Option<Vec<Vec3>>) {
    for v in values.iter().flatten() {
        for c in v.to_array() {
            out.extend_from_slice(&c.to_le_bytes());
        }
    }
}

fn vec3s(values: &Option<Vec<Vec3>>) -> impl Iterator<Item = f32> + '_ {
    values.iter().flatten().flat_map(|p| p.to_array())
}

fn floats(values: &Option<Vec<f32>>) -> impl Iterator<Item = f32> + '_ {
    values.iter().flatten().copied()
}
