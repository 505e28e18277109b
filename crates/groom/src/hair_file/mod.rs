//! Cem Yuksel's cyHair `.hair` format, read and written completely.
//!
//! A file is a 128-byte little-endian header ([`Header`]) followed by up to five arrays, each
//! present only when its flag is set, in this order: segments (u16 per strand, points − 1),
//! points (3 × f32 per point), thickness (f32 per point), transparency (f32 per point) and
//! colour (3 × f32 per point). An absent array takes its value from the header's defaults.
//!
//! [`HairFile`] mirrors the file exactly, so that reading and writing back gives the same
//! bytes; [`crate::Groom`] is the form a renderer works with. The reader checks every claim of
//! the header against the file's size before allocating anything, and refuses a broken file
//! with one [`crate::HairFileError`].

mod header;
mod layout;
pub(crate) mod read;
mod write;

pub use header::{ArrayFlags, HEADER_LEN, HairDefaults, HairInfo, Header, INFO_LEN, MAGIC};
pub use layout::{MAX_POINTS, MAX_STRANDS};

use glam::Vec3;
use std::ops::Range;

/// The contents of a `.hair` file, array for array. Counts live in the header fields because a
/// file may hold no array from which to count.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct HairFile {
    pub strand_count: u32,
    pub point_count: u32,
    pub defaults: HairDefaults,
    pub info: HairInfo,
    /// Segments (points − 1) of each strand.
    pub segments: Option<Vec<u16>>,
    pub points: Option<Vec<Vec3>>,
    pub thickness: Option<Vec<f32>>,
    pub transparency: Option<Vec<f32>>,
    pub colors: Option<Vec<Vec3>>,
}

impl HairFile {
    /// Which arrays this file holds.
    pub fn flags(&self) -> ArrayFlags {
        ArrayFlags {
            segments: self.segments.is_some(),
            points: self.points.is_some(),
            thickness: self.thickness.is_some(),
            transparency: self.transparency.is_some(),
            colors: self.colors.is_some(),
        }
    }

    /// The header this file is written with.
    pub fn header(&self) -> Header {
        Header {
            strand_count: self.strand_count,
            point_count: self.point_count,
            flags: self.flags(),
            defaults: self.defaults,
            info: self.info,
        }
    }

    /// Number of points of each strand, from the segments array or the default.
    pub fn strand_point_counts(&self) -> impl Iterator<Item = usize> + '_ {
        let uniform = self.defaults.segments as usize + 1;
        let explicit = self.segments.as_deref().unwrap_or_default();
        let count = self.strand_count as usize;
        (0..count).map(move |i| explicit.get(i).map_or(uniform, |&s| usize::from(s) + 1))
    }

    /// The range of point indices of each strand.
    pub fn strand_ranges(&self) -> impl Iterator<Item = Range<usize>> + '_ {
        self.strand_point_counts().scan(0, |start, count| {
            let range = *start..*start + count;
            *start = range.end;
            Some(range)
        })
    }
}
