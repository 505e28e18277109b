//! Radiance `.hdr` (RGBE) reading through the `image` crate.

use crate::LightError;
use crate::load::RawImage;
use image::ImageDecoder;
use image::codecs::hdr::HdrDecoder;
use std::io::Cursor;
use std::path::Path;

/// The signature a Radiance file starts with (`#?RADIANCE` or `#?RGBE`).
pub fn is_radiance(bytes: &[u8]) -> bool {
    bytes.starts_with(b"#?")
}

/// Decodes a whole `.hdr` file held in `bytes`; `max_pixels` bounds what its header may claim.
pub fn read_hdr(path: &Path, bytes: &[u8], max_pixels: usize) -> Result<RawImage, LightError> {
    let decode_error = |err: image::ImageError| LightError::Decode {
        path: path.to_path_buf(),
        message: err.to_string(),
    };
    let decoder = HdrDecoder::new(Cursor::new(bytes)).map_err(decode_error)?;
    let (width, height) = decoder.dimensions();
    let (width, height) = (width as usize, height as usize);
    if width.saturating_mul(height) > max_pixels {
        return Err(LightError::Decode {
            path: path.to_path_buf(),
            message: format!("header claims {width}x{height} pixels, more than the file can hold"),
        });
    }
    let image = image::DynamicImage::from_decoder(decoder).map_err(decode_error)?;
    let rgb = image.into_rgb32f();
    Ok(RawImage {
        width,
        height,
        rgb: rgb.into_raw(),
    })
}
