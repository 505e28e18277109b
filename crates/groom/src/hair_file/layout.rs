//! Where each array lies in a file. Everything here works from the header alone, so a file's
//! claims are checked against its size before any array is allocated.

use super::header::{HEADER_LEN, Header};
use crate::error::{HairArray, HairFileError};
use std::ops::Range;

/// Most strands a file may claim (64 Mi); more is taken for a corrupt header.
pub const MAX_STRANDS: u32 = 1 << 26;
/// Most points a file may claim (256 Mi, 3 GiB of positions); more is taken for a corrupt header.
pub const MAX_POINTS: u32 = 1 << 28;

/// Byte ranges of the arrays a header announces, and the file size they add up to.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Layout {
    pub segments: Option<Range<usize>>,
    pub points: Option<Range<usize>>,
    pub thickness: Option<Range<usize>>,
    pub transparency: Option<Range<usize>>,
    pub colors: Option<Range<usize>>,
    pub file_len: u64,
}

impl Layout {
    /// The layout a header implies, after checking its counts are sane and, where the file has
    /// no segments array, that they agree with each other.
    pub fn of(header: &Header) -> Result<Self, HairFileError> {
        check_count_limits(header)?;
        if !header.flags.segments {
            check_uniform_point_count(header)?;
        }
        let strands = header.strand_count as usize;
        let points = header.point_count as usize;
        let flags = header.flags;
        let mut cursor = HEADER_LEN;
        let mut place = |present: bool, len: usize| {
            present.then(|| {
                let range = cursor..cursor + len;
                cursor = range.end;
                range
            })
        };
        let segments = place(flags.segments, strands * 2);
        let points_range = place(flags.points, points * 12);
        let thickness = place(flags.thickness, points * 4);
        let transparency = place(flags.transparency, points * 4);
        let colors = place(flags.colors, points * 12);
        Ok(Self {
            segments,
            points: points_range,
            thickness,
            transparency,
            colors,
            file_len: cursor as u64,
        })
    }

    /// Checks that a file of `actual` bytes is exactly as long as the header's counts say.
    pub fn check_len(&self, actual: u64) -> Result<(), HairFileError> {
        let expected = self.file_len;
        match actual.cmp(&expected) {
            std::cmp::Ordering::Less => Err(HairFileError::Truncated { expected, actual }),
            std::cmp::Ordering::Greater => Err(HairFileError::TrailingBytes { expected, actual }),
            std::cmp::Ordering::Equal => Ok(()),
        }
    }
}

fn check_count_limits(header: &Header) -> Result<(), HairFileError> {
    let too_large = |what, count: u32, limit: u32| {
        (count > limit).then_some(HairFileError::CountTooLarge {
            what,
            count: count.into(),
            limit: limit.into(),
        })
    };
    match too_large("strands", header.strand_count, MAX_STRANDS)
        .or_else(|| too_large("points", header.point_count, MAX_POINTS))
    {
        Some(err) => Err(err),
        None => Ok(()),
    }
}

/// Without a segments array every strand has `default segments + 1` points.
fn check_uniform_point_count(header: &Header) -> Result<(), HairFileError> {
    let per_strand = u64::from(header.defaults.segments) + 1;
    let from_strands = u64::from(header.strand_count) * per_strand;
    let claimed = u64::from(header.point_count);
    if from_strands != claimed {
        return Err(HairFileError::PointCountMismatch {
            header: claimed,
            from_strands,
        });
    }
    Ok(())
}

/// Checks that per-strand segment counts add up to the header's point count.
pub fn check_segment_sum(segments: &[u16], point_count: u32) -> Result<(), HairFileError> {
    let from_strands: u64 = segments.iter().map(|&s| u64::from(s) + 1).sum();
    let claimed = u64::from(point_count);
    if from_strands != claimed {
        return Err(HairFileError::PointCountMismatch {
            header: claimed,
            from_strands,
        });
    }
    Ok(())
}

/// Checks the header's default values are finite numbers.
pub fn check_defaults_finite(header: &Header) -> Result<(), HairFileError> {
    let d = &header.defaults;
    let fields = [
        ("thickness", d.thickness),
        ("transparency", d.transparency),
        ("colour (red)", d.color[0]),
        ("colour (green)", d.color[1]),
        ("colour (blue)", d.color[2]),
    ];
    match fields.into_iter().find(|(_, value)| !value.is_finite()) {
        Some((field, value)) => Err(HairFileError::NonFiniteDefault { field, value }),
        None => Ok(()),
    }
}

/// Checks every value of a per-point array lies within ±[`GroomParts::MAX_COORDINATE`] (points
/// and thickness: what a groom built from the file must hold); `width` floats make one entry.
pub fn check_bounded(
    array: HairArray,
    values: impl IntoIterator<Item = f32>,
    width: usize,
) -> Result<(), HairFileError> {
    let bound = crate::GroomParts::MAX_COORDINATE;
    match values
        .into_iter()
        .enumerate()
        .find(|(_, v)| v.abs() > bound)
    {
        Some((at, value)) => Err(HairFileError::OutOfRange {
            array,
            index: at / width,
            value,
            bound,
        }),
        None => Ok(()),
    }
}

/// Checks every value of a per-point array is finite; `width` floats make one entry.
pub fn check_finite(
    array: HairArray,
    values: impl IntoIterator<Item = f32>,
    width: usize,
) -> Result<(), HairFileError> {
    match values.into_iter().enumerate().find(|(_, v)| !v.is_finite()) {
        Some((at, value)) => Err(HairFileError::NonFinite {
            array,
            index: at / width,
            value,
        }),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hair_file::{ArrayFlags, HairDefaults, HairInfo};

    fn header(strands: u32, points: u32, bits: u32, default_segments: u32) -> Header {
        Header {
            strand_count: strands,
            point_count: points,
            flags: ArrayFlags::from_bits(bits).unwrap(),
            defaults: HairDefaults {
                segments: default_segments,
                ..HairDefaults::default()
            },
            info: HairInfo::default(),
        }
    }

    #[test]
    fn arrays_follow_the_header_in_format_order() {
        let layout = Layout::of(&header(3, 10, 0x1f, 0)).unwrap();
        assert_eq!(layout.segments, Some(128..134));
        assert_eq!(layout.points, Some(134..254));
        assert_eq!(layout.thickness, Some(254..294));
        assert_eq!(layout.transparency, Some(294..334));
        assert_eq!(layout.colors, Some(334..454));
        assert_eq!(layout.file_len, 454);
    }

    #[test]
    fn absent_arrays_take_no_space() {
        let layout = Layout::of(&header(2, 8, 0x12, 3)).unwrap();
        assert_eq!((layout.segments, layout.thickness), (None, None));
        assert_eq!(layout.colors, Some(128 + 96..128 + 192));
        assert_eq!(layout.file_len, 128 + 192);
    }

    #[test]
    fn uniform_strands_must_account_for_every_point() {
        let err = Layout::of(&header(2, 9, 0x2, 3)).unwrap_err();
        assert!(matches!(
            err,
            HairFileError::PointCountMismatch {
                header: 9,
                from_strands: 8
            }
        ));
    }

    #[test]
    fn counts_beyond_the_limits_are_refused() {
        let err = Layout::of(&header(MAX_STRANDS + 1, 0, 0x1, 0)).unwrap_err();
        assert!(matches!(
            err,
            HairFileError::CountTooLarge {
                what: "strands",
                ..
            }
        ));
        let err = Layout::of(&header(1, MAX_POINTS + 1, 0x3, 0)).unwrap_err();
        assert!(matches!(
            err,
            HairFileError::CountTooLarge { what: "points", .. }
        ));
    }

    #[test]
    fn length_is_checked_both_ways() {
        let layout = Layout::of(&header(1, 2, 0x2, 1)).unwrap();
        assert!(layout.check_len(152).is_ok());
        assert!(matches!(
            layout.check_len(151),
            Err(HairFileError::Truncated { .. })
        ));
        assert!(matches!(
            layout.check_len(153),
            Err(HairFileError::TrailingBytes { .. })
        ));
    }
}
