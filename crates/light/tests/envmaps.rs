//! Every map in ../shared/data/envmaps loads with its expected size and finite, non-negative
//! values; broken files give errors, not panics.

use cuticle_light::{LightError, load_env_map};
use std::path::{Path, PathBuf};

fn envmap_dir() -> Option<PathBuf> {
    let dir = PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../../shared/data/envmaps"
    ));
    if dir.is_dir() {
        Some(dir)
    } else {
        println!("skipped: {} is absent", dir.display());
        None
    }
}

/// The sizes the files' headers declare (read independently of the decoders under test: the
/// Radiance resolution line, and for EXR the data window of the first header).
fn declared_size(path: &Path) -> (usize, usize) {
    let bytes = std::fs::read(path).unwrap();
    if bytes.starts_with(b"#?") {
        let text = String::from_utf8_lossy(&bytes[..bytes.len().min(4096)]);
        let line = text
            .lines()
            .find(|l| l.starts_with("-Y "))
            .expect("resolution line");
        let fields: Vec<&str> = line.split_whitespace().collect();
        (fields[3].parse().unwrap(), fields[1].parse().unwrap())
    } else {
        exr_data_window(&bytes)
    }
}

/// Width and height from the `dataWindow` box2i attribute of an EXR header.
fn exr_data_window(bytes: &[u8]) -> (usize, usize) {
    let key = b"dataWindow\0box2i\0";
    let at = bytes
        .windows(key.len())
        .position(|w| w == key)
        .expect("dataWindow attribute")
        + key.len()
        + 4;
    let int = |k: usize| i32::from_le_bytes(bytes[at + 4 * k..at + 4 * k + 4].try_into().unwrap());
    (
        (int(2) - int(0) + 1) as usize,
        (int(3) - int(1) + 1) as usize,
    )
}

#[test]
fn every_shared_map_loads_with_its_size_and_finite_values() {
    let Some(dir) = envmap_dir() else { return };
    let mut paths: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| matches!(p.extension().and_then(|e| e.to_str()), Some("hdr" | "exr")))
        .collect();
    paths.sort();
    assert!(
        paths.len() >= 10,
        "expected the ten shared maps, found {}",
        paths.len()
    );
    for path in paths {
        let map = load_env_map(&path).unwrap_or_else(|e| panic!("{e}"));
        let (w, h) = declared_size(&path);
        assert_eq!((map.width(), map.height()), (w, h), "{}", path.display());
        assert!(
            map.pixels()
                .iter()
                .all(|p| p.is_finite() && p.min_element() >= 0.0)
        );
        let integral = map.integral();
        assert!(integral.min_element() > 0.0, "{} is black", path.display());
        println!(
            "{}: {}x{}, ∫L dω = {:.3?}, {} negatives clamped",
            path.file_name().unwrap().to_string_lossy(),
            w,
            h,
            integral,
            map.clamped_negatives()
        );
    }
}

#[test]
fn broken_files_give_clear_errors() {
    let dir = std::env::temp_dir().join(format!("cuticle-light-broken-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let missing = load_env_map(&dir.join("nope.hdr")).unwrap_err();
    assert!(matches!(missing, LightError::Io { .. }), "{missing}");

    let text = dir.join("notes.hdr");
    std::fs::write(&text, b"hello, this is not an image").unwrap();
    let unknown = load_env_map(&text).unwrap_err();
    assert!(
        matches!(unknown, LightError::UnknownFormat { .. }),
        "{unknown}"
    );

    let truncated_hdr = dir.join("truncated.hdr");
    std::fs::write(
        &truncated_hdr,
        b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 4 +X 8\n\x02\x02",
    )
    .unwrap();
    let err = load_env_map(&truncated_hdr).unwrap_err();
    assert!(matches!(err, LightError::Decode { .. }), "{err}");

    let huge_hdr = dir.join("huge.hdr");
    std::fs::write(
        &huge_hdr,
        b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 100000 +X 200000\n",
    )
    .unwrap();
    let err = load_env_map(&huge_hdr).unwrap_err();
    assert!(
        err.to_string().contains("more than the file can hold"),
        "{err}"
    );

    let square = dir.join("square.hdr");
    let mut bytes = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 4 +X 4\n".to_vec();
    bytes.extend(std::iter::repeat_n([128u8, 128, 128, 129], 16).flatten());
    std::fs::write(&square, bytes).unwrap();
    let err = load_env_map(&square).unwrap_err();
    assert!(
        matches!(
            err,
            LightError::NotLatLong {
                width: 4,
                height: 4,
                ..
            }
        ),
        "{err}"
    );

    if let Some(shared) = envmap_dir() {
        let exr = std::fs::read(shared.join("WavyLinesLatLong.exr")).unwrap();
        let cut = dir.join("cut.exr");
        std::fs::write(&cut, &exr[..exr.len() / 2]).unwrap();
        let err = load_env_map(&cut).unwrap_err();
        assert!(matches!(err, LightError::Decode { .. }), "{err}");
    }
    std::fs::remove_dir_all(&dir).ok();
}
