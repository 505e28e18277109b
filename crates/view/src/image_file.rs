//! A rendered image as files: PNG tone-mapped with the environment's exposure, EXR linear
//! (32-bit float RGB), as `cuticle render` writes them.

use cuticle_light::ToneMap;
use cuticle_render::Image;
use exr::prelude::{Encoding, SpecificChannels, Vec2, WritableImage};
use std::io::Cursor;

/// 8-bit sRGB PNG bytes.
pub fn png_bytes(image: &Image, tone: ToneMap) -> Result<Vec<u8>, String> {
    let mut img = image::RgbImage::new(image.width as u32, image.height as u32);
    for (k, p) in image.pixels.iter().enumerate() {
        let c = tone.apply(p.as_vec3());
        img.put_pixel(
            (k % image.width) as u32,
            (k / image.width) as u32,
            image::Rgb(c),
        );
    }
    let mut bytes = Cursor::new(Vec::new());
    img.write_to(&mut bytes, image::ImageFormat::Png)
        .map_err(|e| format!("cannot encode PNG: {e}"))?;
    Ok(bytes.into_inner())
}

/// Linear 32-bit float RGB OpenEXR bytes.
pub fn exr_bytes(image: &Image) -> Result<Vec<u8>, String> {
    let channels = SpecificChannels::rgb(|Vec2(x, y): Vec2<usize>| {
        let p = image.pixels[y * image.width + x];
        (p.x as f32, p.y as f32, p.z as f32)
    });
    let exr = exr::prelude::Image::from_encoded_channels(
        (image.width, image.height),
        Encoding::SMALL_LOSSLESS,
        channels,
    );
    let mut bytes = Cursor::new(Vec::new());
    exr.write()
        .to_buffered(&mut bytes)
        .map_err(|e| format!("cannot encode EXR: {e}"))?;
    Ok(bytes.into_inner())
}

/// Writes `bytes` to `path` through a temporary file beside it and a rename.
pub fn write_atomic(path: &std::path::Path, bytes: &[u8]) -> Result<(), String> {
    let tmp = path.with_extension(format!(
        "{}.partial",
        path.extension().and_then(|e| e.to_str()).unwrap_or("")
    ));
    std::fs::write(&tmp, bytes)
        .and_then(|_| std::fs::rename(&tmp, path))
        .map_err(|e| {
            let _ = std::fs::remove_file(&tmp);
            format!("cannot write {}: {e}", path.display())
        })
}
