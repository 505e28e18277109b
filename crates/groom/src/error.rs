//! Errors: one enum per source of failure, one variant per kind of fault, each message written
//! for the person who handed us the file or the parameters.

use std::fmt;
use thiserror::Error;

/// An array of a `.hair` file, named in error messages.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum HairArray {
    Segments,
    Points,
    Thickness,
    Transparency,
    Colors,
}

impl fmt::Display for HairArray {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            HairArray::Segments => "segments",
            HairArray::Points => "points",
            HairArray::Thickness => "thickness",
            HairArray::Transparency => "transparency",
            HairArray::Colors => "colour",
        })
    }
}

/// Why a `.hair` file could not be read, or a [`crate::HairFile`] could not be written.
#[derive(Debug, Error)]
pub enum HairFileError {
    #[error(transparent)]
    Io(#[from] std::io::Error),

    #[error("not a .hair file: it is {len} bytes, shorter than the 128-byte header")]
    HeaderTruncated { len: u64 },

    #[error("not a .hair file: it starts with {:?}, not \"HAIR\"", String::from_utf8_lossy(.found))]
    BadMagic { found: [u8; 4] },

    #[error(
        "the header's array flags are {flags:#x}; only the five bits 0x1f (segments, points, \
         thickness, transparency, colour) are defined"
    )]
    UnknownFlags { flags: u32 },

    #[error("the header claims {count} {what}, more than the {limit} this reader accepts")]
    CountTooLarge {
        what: &'static str,
        count: u64,
        limit: u64,
    },

    #[error(
        "the header says the file has {header} points, but its strands add up to {from_strands} \
         (segments + 1 per strand)"
    )]
    PointCountMismatch { header: u64, from_strands: u64 },

    #[error(
        "the file ends early: its header's counts need {expected} bytes but it has only {actual} \
         (cut short, or the counts are wrong)"
    )]
    Truncated { expected: u64, actual: u64 },

    #[error(
        "the file is {actual} bytes but its header's counts account for {expected}: the counts \
         disagree with the file's size"
    )]
    TrailingBytes { expected: u64, actual: u64 },

    #[error("{array} value at index {index} is {value}, not a finite number")]
    NonFinite {
        array: HairArray,
        index: usize,
        value: f32,
    },

    #[error(
        "{array} value at index {index} is {value:e}, beyond ±{bound:e}, the largest a groom may hold"
    )]
    OutOfRange {
        array: HairArray,
        index: usize,
        value: f32,
        bound: f32,
    },

    #[error("the header's default {field} is {value}, not a finite number")]
    NonFiniteDefault { field: &'static str, value: f32 },

    #[error("the {array} array has {actual} entries, but the header's counts need {expected}")]
    ArrayLength {
        array: HairArray,
        expected: u64,
        actual: u64,
    },

    #[error("strand {strand} has {points} points; a .hair file stores 1 to 65,536 per strand")]
    StrandTooLong { strand: usize, points: usize },

    #[error("the file has no points array, so it holds no hair geometry")]
    NoPoints,

    #[error("the file's strands do not form a groom")]
    Groom(#[from] GroomError),
}

/// Why a [`crate::Groom`] could not be built from its parts.
#[derive(Debug, Error, PartialEq)]
pub enum GroomError {
    #[error(
        "strand offsets must start at 0 and end at the point count {points}, got {first}..{last}"
    )]
    OffsetBounds {
        first: u64,
        last: u64,
        points: usize,
    },

    #[error("strand {strand} has no points; every strand needs at least one")]
    EmptyStrand { strand: usize },

    #[error("the {array} array has {actual} entries for {expected} {per}")]
    ArrayLength {
        array: &'static str,
        expected: usize,
        actual: usize,
        per: &'static str,
    },

    #[error("{array} value at index {index} is not finite")]
    NonFinite { array: &'static str, index: usize },

    #[error("{array} value at index {index} is beyond ±{bound:e}, the largest a groom may hold")]
    OutOfRange {
        array: &'static str,
        index: usize,
        bound: f32,
    },

    #[error("the groom has {points} points, more than the {limit} a groom indexes")]
    TooManyPoints { points: usize, limit: usize },
}

/// Why procedural groom parameters were refused.
#[derive(Debug, Error, PartialEq)]
pub enum ParamsError {
    #[error(transparent)]
    Range(#[from] cuticle_range::RangeError),

    #[error("appearance must be physical (β > 0, η > 1, absorption ≥ 0)")]
    Unphysical,

    #[error("unknown preset {0:?}; the presets are straight, wavy and curly")]
    UnknownPreset(String),

    #[error("these parameters give a broken groom")]
    Degenerate(#[from] GroomError),
}
