//! Loading an environment map from a file (format recognised by its first bytes, not its name),
//! with the checks every map passes: a 2:1-ish lat-long shape, finite values, no negatives.

use crate::exr_reader::{is_exr, read_exr};
use crate::hdr::{is_radiance, read_hdr};
use crate::{EnvMap, LightError, ProceduralSky};
use glam::Vec3;
use std::path::Path;

/// Decoded interleaved RGB before validation.
pub struct RawImage {
    pub width: usize,
    pub height: usize,
    pub rgb: Vec<f32>,
}

/// Accepted width / height ratios of a lat-long map (2:1 ± 5%).
const ASPECT_RANGE: std::ops::RangeInclusive<f64> = 1.9..=2.1;
/// Most pixels any header may claim (16k × 8k).
const MAX_PIXELS: usize = 1 << 27;
/// Most pixels per byte of file any supported compression reaches (deflate on flat half floats).
const MAX_PIXELS_PER_BYTE: usize = 200;

/// Reads a Radiance `.hdr` or OpenEXR lat-long map. Errors: unreadable file, unknown format,
/// corrupt data, a shape that is not about 2:1, NaN or infinite pixels. Negative values are
/// clamped to 0 and counted ([`EnvMap::clamped_negatives`]).
pub fn load_env_map(path: &Path) -> Result<EnvMap, LightError> {
    let bytes = crate::file::read_regular(path, crate::file::MAX_IMAGE_FILE).map_err(|source| {
        LightError::Io {
            path: path.to_path_buf(),
            source,
        }
    })?;
    let max_pixels = MAX_PIXELS.min(max_pixels_of(bytes.len()));
    let raw = if is_exr(&bytes) {
        read_exr(path, &bytes, max_pixels)?
    } else if is_radiance(&bytes) {
        read_hdr(path, &bytes, max_pixels)?
    } else {
        return Err(LightError::UnknownFormat {
            path: path.to_path_buf(),
        });
    };
    validated(path, raw)
}

/// The most pixels a file of `bytes` bytes can hold in any supported compression.
pub(crate) fn max_pixels_of(bytes: usize) -> usize {
    bytes.saturating_mul(MAX_PIXELS_PER_BYTE) + (1 << 16)
}

/// `"default"` gives the procedural sky ([`ProceduralSky::default`] at 1024 × 512); anything else
/// is a path for [`load_env_map`].
pub fn load_or_default(spec: &str) -> Result<EnvMap, LightError> {
    if spec == "default" {
        Ok(ProceduralSky::default().to_env_map(1024))
    } else {
        load_env_map(Path::new(spec))
    }
}

fn validated(path: &Path, raw: RawImage) -> Result<EnvMap, LightError> {
    let RawImage { width, height, rgb } = raw;
    let aspect = width as f64 / height.max(1) as f64;
    if width == 0 || height == 0 || !ASPECT_RANGE.contains(&aspect) {
        return Err(LightError::NotLatLong {
            path: path.to_path_buf(),
            width,
            height,
        });
    }
    if let Some(index) = rgb.iter().position(|v| !v.is_finite()) {
        let pixel = index / 3;
        return Err(LightError::NonFinite {
            path: path.to_path_buf(),
            column: pixel % width,
            row: pixel / width,
            value: rgb[index],
        });
    }
    if let Some(index) = rgb
        .iter()
        .position(|&v| v > crate::srbf::MAX_RADIANCE as f32)
    {
        let pixel = index / 3;
        return Err(LightError::TooBright {
            path: path.to_path_buf(),
            column: pixel % width,
            row: pixel / width,
            value: rgb[index],
        });
    }
    let clamped = rgb.iter().filter(|v| **v < 0.0).count();
    let pixels = rgb
        .chunks_exact(3)
        .map(|p| Vec3::new(p[0], p[1], p[2]).max(Vec3::ZERO))
        .collect();
    Ok(EnvMap::new(width, height, pixels).with_clamped_negatives(clamped))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn raw(width: usize, height: usize, value: f32) -> RawImage {
        RawImage {
            width,
            height,
            rgb: vec![value; width * height * 3],
        }
    }

    #[test]
    fn shapes_far_from_two_to_one_are_rejected() {
        let path = Path::new("x.hdr");
        assert!(validated(path, raw(64, 32, 1.0)).is_ok());
        assert!(validated(path, raw(62, 32, 1.0)).is_ok());
        for (w, h) in [(64, 64), (96, 32), (32, 64), (0, 0)] {
            let err = validated(path, raw(w, h, 1.0)).unwrap_err();
            assert!(
                matches!(err, LightError::NotLatLong { .. }),
                "{w}x{h}: {err}"
            );
        }
    }

    #[test]
    fn non_finite_values_name_their_pixel() {
        for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
            let mut image = raw(8, 4, 1.0);
            image.rgb[3 * (2 * 8 + 5) + 1] = bad;
            match validated(Path::new("x.exr"), image) {
                Err(LightError::NonFinite { column, row, .. }) => assert_eq!((column, row), (5, 2)),
                other => panic!("expected NonFinite, got {other:?}"),
            }
        }
    }

    #[test]
    fn pixels_brighter_than_a_light_may_be_are_refused() {
        let mut image = raw(8, 4, 1.0);
        image.rgb[3 * (8 + 2)] = 3e38;
        match validated(Path::new("x.exr"), image) {
            Err(LightError::TooBright { column, row, .. }) => assert_eq!((column, row), (2, 1)),
            other => panic!("expected TooBright, got {other:?}"),
        }
        assert!(validated(Path::new("x.exr"), raw(8, 4, 1e20)).is_ok());
    }

    #[test]
    fn negatives_are_clamped_and_counted() {
        let mut image = raw(8, 4, 1.0);
        image.rgb[0] = -2.0;
        image.rgb[10] = -0.5;
        let map = validated(Path::new("x.hdr"), image).unwrap();
        assert_eq!(map.clamped_negatives(), 2);
        assert_eq!(map.pixel(0, 0), Vec3::new(0.0, 1.0, 1.0));
        assert!(map.pixels().iter().all(|p| p.min_element() >= 0.0));
    }
}
