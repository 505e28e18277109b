//! Images as files, the one encoder and reader every crate that writes or reads an image uses
//! (the command line's renders and lobe images, the window's screenshots): linear RGB as
//! 32-bit float OpenEXR (lossless compression), 8-bit sRGB as PNG, and RGB EXR read back with
//! its header bounded by the file's size before anything is allocated.

use crate::LightError;
use crate::ToneMap;
use glam::DVec3;
use std::io::Cursor;
use std::path::Path;

/// Linear RGB pixels, row-major from the top-left.
#[derive(Clone, Debug, PartialEq)]
pub struct LinearImage {
    pub width: usize,
    pub height: usize,
    pub pixels: Vec<DVec3>,
}

/// `width × height` linear RGB `pixels` (row-major) as 32-bit float RGB OpenEXR bytes.
pub fn exr_bytes(width: usize, height: usize, pixels: &[DVec3]) -> Result<Vec<u8>, LightError> {
    use exr::prelude::{Encoding, SpecificChannels, Vec2, WritableImage};
    check_size(width, height, pixels.len())?;
    let channels = SpecificChannels::rgb(|Vec2(x, y): Vec2<usize>| {
        let p = pixels[y * width + x];
        (p.x as f32, p.y as f32, p.z as f32)
    });
    let image = exr::prelude::Image::from_encoded_channels(
        (width, height),
        Encoding::SMALL_LOSSLESS,
        channels,
    );
    let mut bytes = Cursor::new(Vec::new());
    image
        .write()
        .to_buffered(&mut bytes)
        .map_err(|e| LightError::Encode(format!("EXR: {e}")))?;
    Ok(bytes.into_inner())
}

/// `width × height` 8-bit sRGB triplets (row-major) as PNG bytes.
pub fn png_bytes(width: usize, height: usize, rgb: Vec<u8>) -> Result<Vec<u8>, LightError> {
    check_size(width, height, rgb.len() / 3)?;
    let buffer = image::RgbImage::from_raw(width as u32, height as u32, rgb)
        .ok_or_else(|| LightError::Encode(format!("PNG: not {width}x{height} RGB bytes")))?;
    let mut bytes = Cursor::new(Vec::new());
    buffer
        .write_to(&mut bytes, image::ImageFormat::Png)
        .map_err(|e| LightError::Encode(format!("PNG: {e}")))?;
    Ok(bytes.into_inner())
}

/// Linear RGB `pixels` tone-mapped by `tone` ([`ToneMap::apply`]) as PNG bytes.
pub fn tone_mapped_png(
    width: usize,
    height: usize,
    pixels: &[DVec3],
    tone: ToneMap,
) -> Result<Vec<u8>, LightError> {
    let rgb = pixels
        .iter()
        .flat_map(|p| tone.apply(p.as_vec3()))
        .collect();
    png_bytes(width, height, rgb)
}

fn check_size(width: usize, height: usize, pixels: usize) -> Result<(), LightError> {
    if width.checked_mul(height) != Some(pixels) || width == 0 || u32::try_from(width).is_err() {
        return Err(LightError::Encode(format!(
            "{pixels} pixels are not a {width}x{height} image"
        )));
    }
    Ok(())
}

/// Most pixels an image read back may claim (16k × 8k, the largest map or render).
const MAX_READ_PIXELS: usize = 1 << 27;

/// The most bytes one allocation may take while an OpenEXR file is decoded: the RGB floats of
/// [`MAX_READ_PIXELS`] pixels and the f64 copy of them, with room to spare. The fuzz test
/// (tests/fuzz_exr.rs) holds the reader to it for every compression.
pub const MAX_DECODE_BYTES: usize = MAX_READ_PIXELS * 3 * 8 + (1 << 20);

/// Reads the R, G, B channels of an OpenEXR file's first layer (alpha ignored), refusing a
/// header that claims more pixels than the file's bytes could hold, and NaN or infinite
/// pixels (naming the first).
pub fn read_rgb_exr(path: &Path) -> Result<LinearImage, LightError> {
    let bytes = crate::file::read_regular(path, crate::file::MAX_IMAGE_FILE).map_err(|e| {
        LightError::Image {
            path: path.to_path_buf(),
            message: e.to_string(),
        }
    })?;
    rgb_exr_from_bytes(path, &bytes)
}

/// [`read_rgb_exr`] of a file already in memory (`path` names it in errors).
pub fn rgb_exr_from_bytes(path: &Path, bytes: &[u8]) -> Result<LinearImage, LightError> {
    let refused = |message: String| LightError::Image {
        path: path.to_path_buf(),
        message,
    };
    if !crate::exr_reader::is_exr(bytes) {
        return Err(refused("not an OpenEXR file".into()));
    }
    let max = MAX_READ_PIXELS.min(crate::load::max_pixels_of(bytes.len()));
    let raw = crate::exr_reader::read_exr(path, bytes, max).map_err(|e| match e {
        LightError::Decode { message, .. } => refused(message),
        other => other,
    })?;
    let pixels: Vec<DVec3> = raw
        .rgb
        .chunks_exact(3)
        .map(|c| DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64))
        .collect();
    if let Some(k) = pixels.iter().position(|p| !p.is_finite()) {
        let value = raw.rgb[3 * k..3 * k + 3]
            .iter()
            .copied()
            .find(|v| !v.is_finite())
            .unwrap_or(f32::NAN);
        return Err(LightError::NonFinite {
            path: path.to_path_buf(),
            column: k % raw.width.max(1),
            row: k / raw.width.max(1),
            value,
        });
    }
    Ok(LinearImage {
        width: raw.width,
        height: raw.height,
        pixels,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample(width: usize, height: usize) -> Vec<DVec3> {
        (0..width * height)
            .map(|k| DVec3::new(k as f64 * 0.5, 1.0 / (1.0 + k as f64), 2.25))
            .collect()
    }

    #[test]
    fn exr_round_trips_at_f32_precision() {
        let dir = std::env::temp_dir().join(format!("cuticle-image-file-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("x.exr");
        let pixels = sample(7, 3);
        std::fs::write(&path, exr_bytes(7, 3, &pixels).unwrap()).unwrap();
        let back = read_rgb_exr(&path).unwrap();
        assert_eq!((back.width, back.height), (7, 3));
        for (a, b) in pixels.iter().zip(&back.pixels) {
            assert!((*a - *b).abs().max_element() <= 1e-6 * a.abs().max_element().max(1.0));
        }
        let mut nan = pixels.clone();
        nan[9] = DVec3::new(1.0, f64::NAN, 0.0);
        std::fs::write(&path, exr_bytes(7, 3, &nan).unwrap()).unwrap();
        let err = read_rgb_exr(&path).unwrap_err().to_string();
        assert!(err.contains("column 2, row 1"), "{err}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn png_decodes_to_the_size_and_a_wrong_size_is_an_error() {
        let bytes = tone_mapped_png(5, 4, &sample(5, 4), ToneMap { exposure: 1.0 }).unwrap();
        let decoded = image::load_from_memory(&bytes).unwrap();
        assert_eq!((decoded.width(), decoded.height()), (5, 4));
        assert!(exr_bytes(5, 4, &sample(4, 4)).is_err());
        assert!(png_bytes(5, 4, vec![0; 5 * 4 * 3 - 1]).is_err());
    }
}
