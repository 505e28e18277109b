//! OpenEXR reading through the `exr` crate: scanline or tiled, half or float, any compression the
//! crate decodes within bounds ([`BOUNDED_COMPRESSIONS`]: not DWAA/DWAB); of a mip- or
//! rip-mapped file only the full-resolution level.

use crate::LightError;
use crate::load::RawImage;
use exr::meta::MetaData;
use exr::prelude::*;
use std::io::Cursor;
use std::path::Path;

/// The four magic bytes every OpenEXR file starts with.
const MAGIC: [u8; 4] = [0x76, 0x2f, 0x31, 0x01];

/// The compressions whose decoders bound what they allocate by the header's (already bounded)
/// size, whatever a chunk claims: tests/fuzz_exr.rs mutates files of each. DWAA and DWAB are not
/// among them: the `exr` crate allocates the DC and AC counts a chunk states (issue 57 #1).
const BOUNDED_COMPRESSIONS: [Compression; 8] = [
    Compression::Uncompressed,
    Compression::RLE,
    Compression::ZIP1,
    Compression::ZIP16,
    Compression::PIZ,
    Compression::PXR24,
    Compression::B44,
    Compression::B44A,
];

pub fn is_exr(bytes: &[u8]) -> bool {
    bytes.starts_with(&MAGIC)
}

/// Decodes the R, G, B channels of the first layer that has them, at full resolution.
/// `max_pixels` bounds what the header may claim before anything is allocated.
pub fn read_exr(
    path: &Path,
    bytes: &[u8],
    max_pixels: usize,
) -> std::result::Result<RawImage, LightError> {
    let decode_error = |err: exr::error::Error| LightError::Decode {
        path: path.to_path_buf(),
        message: err.to_string(),
    };
    let meta = MetaData::read_from_buffered(Cursor::new(bytes), false).map_err(decode_error)?;
    if let Some(refused) = meta
        .headers
        .iter()
        .map(|h| h.compression)
        .find(|c| !BOUNDED_COMPRESSIONS.contains(c))
    {
        return Err(LightError::Decode {
            path: path.to_path_buf(),
            message: format!(
                "{} compression is not read (its decoder trusts counts in the file); \
                 save the image with ZIP or PIZ",
                refused
                    .to_string()
                    .trim_end_matches(" compression")
                    .to_uppercase()
            ),
        });
    }
    if let Some(too_big) = meta
        .headers
        .iter()
        .map(|h| h.layer_size)
        .find(|size| size.0.saturating_mul(size.1) > max_pixels)
    {
        return Err(LightError::Decode {
            path: path.to_path_buf(),
            message: format!(
                "header claims {}x{} pixels, more than the file can hold",
                too_big.0, too_big.1
            ),
        });
    }
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .rgb_channels(new_raw_image, set_raw_pixel)
        .first_valid_layer()
        .all_attributes()
        .from_buffered(Cursor::new(bytes))
        .map_err(decode_error)?;
    Ok(image.layer_data.channel_data.pixels)
}

fn new_raw_image(size: Vec2<usize>, _channels: &RgbChannels) -> RawImage {
    RawImage {
        width: size.0,
        height: size.1,
        rgb: vec![0.0; size.0 * size.1 * 3],
    }
}

fn set_raw_pixel(image: &mut RawImage, position: Vec2<usize>, (r, g, b): (f32, f32, f32)) {
    let index = 3 * (position.1 * image.width + position.0);
    image.rgb[index..index + 3].copy_from_slice(&[r, g, b]);
}
