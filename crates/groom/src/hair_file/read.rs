//! Reading: header first, then its counts against the file's size, and only then the arrays.

use super::HairFile;
use super::header::{HEADER_LEN, Header};
use super::layout::{
    Layout, check_bounded, check_defaults_finite, check_finite, check_segment_sum,
};
use crate::error::{HairArray, HairFileError};
use glam::Vec3;
use std::io::Read;
use std::ops::Range;
use std::path::Path;

impl HairFile {
    /// Decodes a whole file held in memory.
    pub fn from_bytes(bytes: &[u8]) -> Result<Self, HairFileError> {
        let (header, layout) = decode_header(bytes, bytes.len() as u64)?;
        decode_arrays(header, &layout, bytes)
    }

    /// Reads a file from disk. Its size is checked against the header before the rest is read.
    pub fn read(path: impl AsRef<Path>) -> Result<Self, HairFileError> {
        let len = regular_file_len(path.as_ref())?;
        let mut file = std::fs::File::open(path)?;
        let mut head = [0; HEADER_LEN];
        if len < HEADER_LEN as u64 {
            return Err(HairFileError::HeaderTruncated { len });
        }
        file.read_exact(&mut head)?;
        let (header, layout) = decode_header(&head, len)?;
        let mut bytes = Vec::with_capacity(layout.file_len as usize);
        bytes.extend_from_slice(&head);
        file.take(layout.file_len - HEADER_LEN as u64)
            .read_to_end(&mut bytes)?;
        layout.check_len(bytes.len() as u64)?;
        decode_arrays(header, &layout, &bytes)
    }
}

/// The length of `path` if it is a regular file. Checked before it is opened: opening a FIFO
/// for reading blocks until a writer comes (issue 57), and a device has no length.
pub(crate) fn regular_file_len(path: &Path) -> std::io::Result<u64> {
    let meta = std::fs::metadata(path)?;
    if !meta.is_file() {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            "not a regular file (a folder, pipe or device)",
        ));
    }
    Ok(meta.len())
}

/// Decodes and checks the header of a file of `file_len` bytes that starts with `bytes`.
fn decode_header(bytes: &[u8], file_len: u64) -> Result<(Header, Layout), HairFileError> {
    let head: &[u8; HEADER_LEN] = bytes
        .get(..HEADER_LEN)
        .and_then(|head| head.try_into().ok())
        .ok_or(HairFileError::HeaderTruncated { len: file_len })?;
    let header = Header::decode(head)?;
    let layout = Layout::of(&header)?;
    check_defaults_finite(&header)?;
    layout.check_len(file_len)?;
    Ok((header, layout))
}

/// Decodes the arrays of a file whose length already matches `layout`.
fn decode_arrays(header: Header, layout: &Layout, bytes: &[u8]) -> Result<HairFile, HairFileError> {
    let segments = decode(bytes, &layout.segments, |b: &[u8; 2]| {
        u16::from_le_bytes(*b)
    });
    if let Some(segments) = &segments {
        check_segment_sum(segments, header.point_count)?;
    }
    let points = decode(bytes, &layout.points, vec3_le);
    let thickness = decode(bytes, &layout.thickness, f32_le);
    let transparency = decode(bytes, &layout.transparency, f32_le);
    let colors = decode(bytes, &layout.colors, vec3_le);
    check_vec3s(HairArray::Points, &points)?;
    check_floats(HairArray::Thickness, &thickness)?;
    check_floats(HairArray::Transparency, &transparency)?;
    check_vec3s(HairArray::Colors, &colors)?;
    if let Some(points) = &points {
        check_bounded(
            HairArray::Points,
            points.iter().flat_map(|p| p.to_array()),
            3,
        )?;
    }
    if let Some(thickness) = &thickness {
        check_bounded(HairArray::Thickness, thickness.iter().copied(), 1)?;
    }
    Ok(HairFile {
        strand_count: header.strand_count,
        point_count: header.point_count,
        defaults: header.defaults,
        info: header.info,
        segments,
        points,
        thickness,
        transparency,
        colors,
    })
}

/// Decodes the array at `range` (if present), `N` bytes an entry.
fn decode<T, const N: usize>(
    bytes: &[u8],
    range: &Option<Range<usize>>,
    entry: impl Fn(&[u8; N]) -> T,
) -> Option<Vec<T>> {
    let range = range.clone()?;
    let (entries, _) = bytes[range].as_chunks::<N>();
    Some(entries.iter().map(entry).collect())
}

fn f32_le(b: &[u8; 4]) -> f32 {
    f32::from_le_bytes(*b)
}

fn vec3_le(b: &[u8; 12]) -> Vec3 {
    let at = |i: usize| f32::from_le_bytes([b[i], b[i + 1], b[i + 2], b[i + 3]]);
    Vec3::new(at(0), at(4), at(8))
}

fn check_floats(array: HairArray, values: &Option<Vec<f32>>) -> Result<(), HairFileError> {
    values
        .as_ref()
        .map_or(Ok(()), |v| check_finite(array, v.iter().copied(), 1))
}

fn check_vec3s(array: HairArray, values: &Option<Vec<Vec3>>) -> Result<(), HairFileError> {
    values.as_ref().map_or(Ok(()), |v| {
        check_finite(array, v.iter().flat_map(|p| p.to_array()), 3)
    })
}
