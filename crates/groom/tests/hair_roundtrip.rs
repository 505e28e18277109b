//! A `.hair` file written and read back is the same file, for every combination of arrays.

mod common;

use common::{expected_file_len, random_hair_file};
use cuticle_groom::{ArrayFlags, Groom, HairFile};
use proptest::prelude::*;

#[test]
fn every_combination_of_arrays_round_trips_through_bytes() {
    for flags in ArrayFlags::all_combinations() {
        for seed in 0..4 {
            let file = random_hair_file(flags, seed);
            let bytes = file.to_bytes().unwrap();
            assert_eq!(
                bytes.len(),
                expected_file_len(&file),
                "flags {:#x}",
                flags.bits()
            );
            assert_eq!(
                u32::from_le_bytes(bytes[12..16].try_into().unwrap()),
                flags.bits()
            );
            let back = HairFile::from_bytes(&bytes).unwrap();
            assert_eq!(back, file, "flags {:#x} seed {seed}", flags.bits());
            assert_eq!(back.to_bytes().unwrap(), bytes);
        }
    }
}

#[test]
fn every_combination_of_arrays_round_trips_through_disk() {
    let dir = tempfile::tempdir().unwrap();
    for flags in ArrayFlags::all_combinations() {
        let file = random_hair_file(flags, 100 + u64::from(flags.bits()));
        let path = dir.path().join(format!("flags{}.hair", flags.bits()));
        file.write_to(std::fs::File::create(&path).unwrap())
            .unwrap();
        assert_eq!(
            HairFile::read(&path).unwrap(),
            file,
            "flags {:#x}",
            flags.bits()
        );
    }
}

#[test]
fn a_groom_keeps_its_geometry_through_a_file() {
    for flags in ArrayFlags::all_combinations().filter(|f| f.points) {
        let file = random_hair_file(flags, 7);
        let groom = file.clone().into_groom().unwrap();
        let default_thickness = vec![file.defaults.thickness; groom.point_count()];
        let thickness = file.thickness.as_deref().unwrap_or(&default_thickness);
        assert_eq!(groom.thickness(), thickness);
        assert_eq!(groom.positions(), file.points.as_deref().unwrap());
        let expected_counts: Vec<usize> = file.strand_point_counts().collect();
        let counts: Vec<usize> = groom.strands().map(|s| s.point_count()).collect();
        assert_eq!(counts, expected_counts);
        let bytes = groom.to_hair_bytes("again").unwrap();
        let again = HairFile::from_bytes(&bytes).unwrap().into_groom().unwrap();
        assert_eq!(again.parts(), groom.parts(), "flags {:#x}", flags.bits());
    }
}

#[test]
fn uniform_arrays_become_header_defaults() {
    let mut file = random_hair_file(ArrayFlags::from_bits(0x7).unwrap(), 3);
    let strands = file.strand_count as usize;
    file.segments = Some(vec![4; strands]);
    file.point_count = 5 * strands as u32;
    file.points = Some(vec![glam::Vec3::ONE; 5 * strands]);
    file.thickness = Some(vec![0.25; 5 * strands]);
    let written = HairFile::from_groom(&file.into_groom().unwrap(), "uniform").unwrap();
    assert_eq!(
        (written.segments.is_none(), written.thickness.is_none()),
        (true, true)
    );
    assert_eq!(
        (written.defaults.segments, written.defaults.thickness),
        (4, 0.25)
    );
    assert_eq!(written.info.text(), "uniform");
}

#[test]
fn a_groom_reads_from_disk() {
    let file = random_hair_file(ArrayFlags::from_bits(0x1f).unwrap(), 11);
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("all.hair");
    std::fs::write(&path, file.to_bytes().unwrap()).unwrap();
    let groom = Groom::read_hair(&path).unwrap();
    assert_eq!(groom.strand_count(), file.strand_count as usize);
    assert_eq!(groom.colors(), file.colors.as_deref());
    assert_eq!(groom.transparency(), file.transparency.as_deref());
}

fn any_float() -> impl Strategy<Value = f32> {
    use proptest::num::f32::{NEGATIVE, NORMAL, POSITIVE, SUBNORMAL, ZERO};
    (NORMAL | SUBNORMAL | ZERO | POSITIVE | NEGATIVE).prop_filter("within a groom's range", |v| {
        v.is_finite() && v.abs() <= cuticle_groom::GroomParts::MAX_COORDINATE
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Any values a groom may hold (within ±`GroomParts::MAX_COORDINATE`), including −0 and
    /// subnormals, come back bit for bit.
    #[test]
    fn arbitrary_values_round_trip_bit_for_bit(
        bits in 0u32..32,
        segments in proptest::collection::vec(0u16..6, 1..8),
        pool in proptest::collection::vec(any_float(), 1..64),
        info in proptest::collection::vec(any::<u8>(), 88),
    ) {
        let mut file = random_hair_file(ArrayFlags::from_bits(bits).unwrap(), 0);
        let points: u32 = segments.iter().map(|&s| u32::from(s) + 1).sum();
        if file.segments.is_some() {
            file.strand_count = segments.len() as u32;
            file.point_count = points;
            file.segments = Some(segments);
        }
        let n = file.point_count as usize;
        let value = |i: usize| pool[i % pool.len()];
        let vec3 = |i: usize| glam::Vec3::new(value(3 * i), value(3 * i + 1), value(3 * i + 2));
        file.points = file.points.map(|_| (0..n).map(vec3).collect());
        file.thickness = file.thickness.map(|_| (0..n).map(value).collect());
        file.transparency = file.transparency.map(|_| (0..n).map(|i| value(i + 1)).collect());
        file.colors = file.colors.map(|_| (0..n).map(|i| vec3(i + 5)).collect());
        file.info.0.copy_from_slice(&info);
        let bytes = file.to_bytes().unwrap();
        let back = HairFile::from_bytes(&bytes).unwrap();
        prop_assert_eq!(back.to_bytes().unwrap(), bytes);
        let same_bits = |a: &[glam::Vec3], b: &[glam::Vec3]| {
            a.iter().zip(b).all(|(p, q)| p.to_array().map(f32::to_bits) == q.to_array().map(f32::to_bits))
        };
        prop_assert!(same_bits(back.points.as_deref().unwrap_or(&[]), file.points.as_deref().unwrap_or(&[])));
    }
}

/// A point or thickness beyond the range is refused on read, naming the array and the entry.
#[test]
fn coordinates_beyond_the_range_are_refused() {
    for (bits, at, value) in [(0b11, 0usize, 1e20f32), (0b111, 0, -3e38)] {
        let mut file = random_hair_file(ArrayFlags::from_bits(bits).unwrap(), 3);
        let points = file.points.as_mut().unwrap();
        points[at].y = value;
        let err = HairFile::from_bytes(&file.to_bytes().unwrap())
            .unwrap_err()
            .to_string();
        assert!(
            err.starts_with(&format!("points value at index {at} is")),
            "{err}"
        );
        assert!(err.contains("the largest a groom may hold"), "{err}");
    }
    let mut file = random_hair_file(ArrayFlags::from_bits(0b111).unwrap(), 4);
    file.thickness.as_mut().unwrap()[0] = 2e6;
    let err = HairFile::from_bytes(&file.to_bytes().unwrap())
        .unwrap_err()
        .to_string();
    assert!(err.starts_with("thickness value at index 0"), "{err}");
}
