//! Each kind of broken `.hair` file is refused with its own error.

mod common;

use common::random_hair_file;
use cuticle_groom::hair_file::{MAX_POINTS, MAX_STRANDS};
use cuticle_groom::{ArrayFlags, HairArray, HairFile, HairFileError};

/// A valid file with every array, and its bytes.
fn full_file() -> (HairFile, Vec<u8>) {
    let file = random_hair_file(ArrayFlags::from_bits(0x1f).unwrap(), 42);
    let bytes = file.to_bytes().unwrap();
    (file, bytes)
}

fn set_u32(bytes: &mut [u8], at: usize, value: u32) {
    bytes[at..at + 4].copy_from_slice(&value.to_le_bytes());
}

fn read(bytes: &[u8]) -> HairFileError {
    HairFile::from_bytes(bytes).expect_err("a broken file must be refused")
}

#[test]
fn wrong_magic() {
    let (_, mut bytes) = full_file();
    bytes[..4].copy_from_slice(b"HAIr");
    assert!(matches!(read(&bytes), HairFileError::BadMagic { found } if &found == b"HAIr"));
    let png = b"\x89PNG\r\n\x1a\n".repeat(20);
    assert!(matches!(read(&png), HairFileError::BadMagic { .. }));
}

#[test]
fn shorter_than_a_header() {
    for len in [0, 1, 4, 127] {
        let (_, bytes) = full_file();
        let err = read(&bytes[..len]);
        assert!(matches!(err, HairFileError::HeaderTruncated { len: l } if l == len as u64));
    }
}

#[test]
fn truncated_anywhere_in_the_arrays() {
    let (_, bytes) = full_file();
    for len in [128, 129, bytes.len() / 2, bytes.len() - 1] {
        let err = read(&bytes[..len]);
        let expected = bytes.len() as u64;
        assert!(
            matches!(err, HairFileError::Truncated { expected: e, actual } if e == expected && actual == len as u64),
            "cut at {len}: {err}"
        );
    }
}

#[test]
fn counts_that_disagree_with_the_file_size() {
    let (file, bytes) = full_file();
    let mut fewer_strands = bytes.clone();
    set_u32(&mut fewer_strands, 4, file.strand_count - 1);
    assert!(matches!(
        read(&fewer_strands),
        HairFileError::TrailingBytes { .. }
    ));
    let mut extra = bytes.clone();
    extra.extend_from_slice(&[0; 7]);
    let err = read(&extra);
    let actual = bytes.len() as u64 + 7;
    assert!(matches!(err, HairFileError::TrailingBytes { actual: a, .. } if a == actual));
    let mut more_strands = bytes;
    set_u32(&mut more_strands, 4, file.strand_count + 1000);
    assert!(matches!(
        read(&more_strands),
        HairFileError::Truncated { .. }
    ));
}

#[test]
fn counts_that_disagree_with_each_other() {
    let (file, mut bytes) = full_file();
    let segments_at = 128;
    let first = u16::from_le_bytes([bytes[segments_at], bytes[segments_at + 1]]);
    bytes[segments_at..segments_at + 2].copy_from_slice(&(first + 1).to_le_bytes());
    let err = read(&bytes);
    let points = u64::from(file.point_count);
    assert!(
        matches!(err, HairFileError::PointCountMismatch { header, from_strands } if header == points && from_strands == points + 1),
        "{err}"
    );

    let uniform = random_hair_file(ArrayFlags::from_bits(0x2).unwrap(), 5);
    let mut bytes = uniform.to_bytes().unwrap();
    set_u32(&mut bytes, 16, uniform.defaults.segments + 1);
    assert!(matches!(
        read(&bytes),
        HairFileError::PointCountMismatch { .. }
    ));
}

#[test]
fn absurd_counts() {
    let (_, bytes) = full_file();
    for (at, value, what) in [(4, u32::MAX, "strands"), (8, MAX_POINTS + 1, "points")] {
        let mut inflated = bytes.clone();
        set_u32(&mut inflated, at, value);
        let err = read(&inflated);
        assert!(
            matches!(err, HairFileError::CountTooLarge { what: w, .. } if w == what),
            "{err}"
        );
    }
    let mut inflated = bytes;
    set_u32(&mut inflated, 4, MAX_STRANDS + 1);
    assert!(matches!(
        read(&inflated),
        HairFileError::CountTooLarge {
            what: "strands",
            ..
        }
    ));
}

#[test]
fn undefined_flag_bits() {
    let (_, mut bytes) = full_file();
    set_u32(&mut bytes, 12, 0x3f);
    assert!(matches!(
        read(&bytes),
        HairFileError::UnknownFlags { flags: 0x3f }
    ));
}

#[test]
fn non_finite_coordinates_and_values() {
    let (file, bytes) = full_file();
    let p = file.point_count as usize;
    let points_at = 128 + 2 * file.strand_count as usize;
    let cases = [
        (points_at + 12 * 2 + 4, f32::NAN, HairArray::Points, 2),
        (
            points_at + 12 * (p - 1) + 8,
            f32::INFINITY,
            HairArray::Points,
            p - 1,
        ),
        (
            points_at + 12 * p + 4,
            f32::NEG_INFINITY,
            HairArray::Thickness,
            1,
        ),
        (points_at + 16 * p, f32::NAN, HairArray::Transparency, 0),
        (
            points_at + 20 * p + 12 * (p - 1),
            f32::INFINITY,
            HairArray::Colors,
            p - 1,
        ),
    ];
    for (at, value, array, index) in cases {
        let mut broken = bytes.clone();
        broken[at..at + 4].copy_from_slice(&value.to_le_bytes());
        let err = read(&broken);
        assert!(
            matches!(err, HairFileError::NonFinite { array: a, index: i, .. } if a == array && i == index),
            "{array} {index}: {err}"
        );
    }
    let mut broken = bytes;
    broken[20..24].copy_from_slice(&f32::NAN.to_le_bytes());
    let err = read(&broken);
    assert!(
        matches!(
            err,
            HairFileError::NonFiniteDefault {
                field: "thickness",
                ..
            }
        ),
        "{err}"
    );
}

#[test]
fn a_file_without_points_has_no_groom() {
    let file = random_hair_file(ArrayFlags::from_bits(0x1d).unwrap(), 9);
    let back = HairFile::from_bytes(&file.to_bytes().unwrap()).unwrap();
    assert!(matches!(back.into_groom(), Err(HairFileError::NoPoints)));
}

#[test]
fn a_missing_file_is_an_io_error() {
    let err = HairFile::read("/nonexistent/folder/none.hair").unwrap_err();
    assert!(matches!(err, HairFileError::Io(_)));
}

#[test]
fn inconsistent_files_are_not_written() {
    let (file, _) = full_file();
    let mut short = file.clone();
    short.thickness.as_mut().unwrap().pop();
    let err = short.to_bytes().unwrap_err();
    assert!(matches!(
        err,
        HairFileError::ArrayLength {
            array: HairArray::Thickness,
            ..
        }
    ));
    let mut nan = file;
    nan.colors.as_mut().unwrap()[0].y = f32::NAN;
    assert!(matches!(
        nan.to_bytes(),
        Err(HairFileError::NonFinite {
            array: HairArray::Colors,
            index: 0,
            ..
        })
    ));
}

#[test]
fn strands_too_long_for_the_format_are_not_written() {
    let points = 70_000;
    let groom = cuticle_groom::Groom::from_parts(cuticle_groom::GroomParts {
        positions: vec![glam::Vec3::ZERO; points],
        thickness: vec![1.0; points],
        strand_offsets: vec![0, 1, points as u32],
        ..Default::default()
    })
    .unwrap();
    let err = HairFile::from_groom(&groom, "").unwrap_err();
    assert!(matches!(
        err,
        HairFileError::StrandTooLong {
            strand: 1,
            points: 69_999
        }
    ));
}

#[test]
fn messages_say_what_is_wrong() {
    let (_, mut bytes) = full_file();
    bytes[..4].copy_from_slice(b"JUNK");
    assert_eq!(
        read(&bytes).to_string(),
        "not a .hair file: it starts with \"JUNK\", not \"HAIR\""
    );
    let message = read(
        &bytes[..200]
            .iter()
            .enumerate()
            .map(|(i, &b)| if i < 4 { b"HAIR"[i] } else { b })
            .collect::<Vec<_>>(),
    )
    .to_string();
    assert!(message.contains("ends early"), "{message}");
}

#[test]
fn an_edited_file_is_checked_before_it_becomes_a_groom() {
    let (mut file, _) = full_file();
    file.segments = None;
    file.strand_count = MAX_STRANDS;
    let err = file.into_groom().unwrap_err();
    assert!(
        matches!(err, HairFileError::PointCountMismatch { .. }),
        "{err}"
    );
}
