//! Lat-long images on disk (docs/conventions.md §4–5): 32-bit float RGB OpenEXR (ZIP-compressed), a
//! tone-mapped PNG beside each for people, and `azimuthal.csv`. Shared by every command that
//! writes lobe images (`sim`, `sweep`, `lobes`).

use crate::output::OutDir;
use anyhow::{Context, Result, bail};
use cuticle_fiber::{LatLongGrid, LatLongImage};
use exr::prelude::*;
use glam::DVec3;
use std::io::Cursor;
use std::path::Path;

/// The lobe file names, in lobe order, then the sum (docs/conventions.md §5).
pub const LOBE_FILES: [&str; 6] = ["R", "TT", "TRT", "TRRT", "rest", "total"];

/// The image as an OpenEXR file in memory: R, G, B channels of 32-bit floats, ZIP compression.
pub fn exr_bytes(img: &LatLongImage) -> Result<Vec<u8>> {
    let g = img.grid;
    let channels = SpecificChannels::rgb(|Vec2(x, y): Vec2<usize>| {
        let p = img.at(x, y);
        (p.x as f32, p.y as f32, p.z as f32)
    });
    let image =
        Image::from_encoded_channels((g.width, g.height), Encoding::SMALL_LOSSLESS, channels);
    let mut bytes = Cursor::new(Vec::new());
    image
        .write()
        .to_buffered(&mut bytes)
        .context("cannot encode EXR")?;
    Ok(bytes.into_inner())
}

/// Most pixels a lat-long image read back may claim (4000 × 1000, the largest `lobes` writes,
/// is 4e6): a hostile header is refused before anything is allocated.
const MAX_READ_PIXELS: usize = 1 << 24;

/// Reads a lat-long EXR written by [`exr_bytes`] (or any RGB EXR; alpha is ignored): for the
/// commands that consume a sweep (validation).
pub fn read_exr(path: &Path) -> Result<LatLongImage> {
    let meta = exr::meta::MetaData::read_from_file(path, false)
        .with_context(|| format!("cannot read {}", path.display()))?;
    if let Some(size) = meta
        .headers
        .iter()
        .map(|h| h.layer_size)
        .find(|s| s.0.saturating_mul(s.1) > MAX_READ_PIXELS || s.0 == 0 || s.1 == 0)
    {
        bail!(
            "cannot read {}: its header claims {}x{} pixels",
            path.display(),
            size.0,
            size.1
        );
    }
    let image = read_first_rgba_layer_from_file(
        path,
        |size, _| LatLongImage::zeros(LatLongGrid::new(size.0, size.1)),
        |img: &mut LatLongImage, Vec2(x, y), (r, g, b, _a): (f32, f32, f32, f32)| {
            let w = img.grid.width;
            img.pixels[y * w + x] = DVec3::new(r as f64, g as f64, b as f64);
        },
    )
    .with_context(|| format!("cannot read {}", path.display()))?;
    Ok(image.layer_data.channel_data.pixels)
}

/// The luminance below which 99.5 % of the image's non-zero pixels lie: the white point of
/// [`png_bytes`], robust to a few Monte Carlo fireflies. 0 for a black image.
pub fn white_point(img: &LatLongImage) -> f64 {
    let mut lum: Vec<f64> = img
        .pixels
        .iter()
        .map(|p| (p.x + p.y + p.z) / 3.0)
        .filter(|&l| l > 0.0)
        .collect();
    if lum.is_empty() {
        return 0.0;
    }
    let k = ((lum.len() as f64 * 0.995) as usize).min(lum.len() - 1);
    *lum.select_nth_unstable_by(k, f64::total_cmp).1
}

/// sRGB encoding of a linear value in [0, 1].
fn srgb(v: f64) -> u8 {
    let v = v.clamp(0.0, 1.0);
    let s = if v <= 0.003_130_8 {
        12.92 * v
    } else {
        1.055 * v.powf(1.0 / 2.4) - 0.055
    };
    (s * 255.0).round() as u8
}

/// A PNG for people: each channel mapped by ln(1 + 16 S/w)/ln 17, with w the image's
/// [`white_point`], so that a lobe's faint tails show beside its bright cone; then sRGB.
pub fn png_bytes(img: &LatLongImage) -> Result<Vec<u8>> {
    png_bytes_with_white(img, white_point(img))
}

/// As [`png_bytes`] with a given white point `w`, so several images share one scale.
pub fn png_bytes_with_white(img: &LatLongImage, w: f64) -> Result<Vec<u8>> {
    let g = img.grid;
    let map = |s: f64| {
        if w > 0.0 {
            (1.0 + 16.0 * s.max(0.0) / w).ln() / 17f64.ln()
        } else {
            0.0
        }
    };
    let rgb: Vec<u8> = img
        .pixels
        .iter()
        .flat_map(|p| [srgb(map(p.x)), srgb(map(p.y)), srgb(map(p.z))])
        .collect();
    let buffer =
        image::RgbImage::from_raw(g.width as u32, g.height as u32, rgb).context("image size")?;
    let mut bytes = Cursor::new(Vec::new());
    buffer
        .write_to(&mut bytes, image::ImageFormat::Png)
        .context("cannot encode PNG")?;
    Ok(bytes.into_inner())
}

/// `azimuthal.csv`: a `phi` column (the φ of each column's centre), then for each named image
/// its density in φ, ∫ S cos θ dθ (channel mean), so that a column's sum times Δφ is the
/// image's energy (docs/conventions.md §5).
pub fn azimuthal_csv(images: &[(&str, &LatLongImage)]) -> Result<String> {
    let Some((_, first)) = images.first() else {
        bail!("no images for azimuthal.csv")
    };
    let g = first.grid;
    if images.iter().any(|(_, img)| img.grid != g) {
        bail!("azimuthal.csv needs images on one grid");
    }
    let columns: Vec<Vec<DVec3>> = images.iter().map(|(_, img)| img.azimuthal()).collect();
    let mut csv = String::from("phi");
    for (name, _) in images {
        csv.push(',');
        csv.push_str(name);
    }
    csv.push('\n');
    for j in 0..g.width {
        csv.push_str(&format!("{}", g.phi_center(j)));
        for col in &columns {
            let v = col[j];
            csv.push_str(&format!(",{}", (v.x + v.y + v.z) / 3.0));
        }
        csv.push('\n');
    }
    Ok(csv)
}

/// Writes `NAME.exr` for each image (and `NAME.png` beside it when `png`), then
/// `azimuthal.csv` over all of them, each file atomically.
pub fn write_images(out: &mut OutDir, images: &[(&str, &LatLongImage)], png: bool) -> Result<()> {
    for (name, img) in images {
        out.write(&format!("{name}.exr"), &exr_bytes(img)?)?;
        if png {
            out.write(&format!("{name}.png"), &png_bytes(img)?)?;
        }
    }
    out.write("azimuthal.csv", azimuthal_csv(images)?.as_bytes())?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample_image() -> LatLongImage {
        let mut img = LatLongImage::zeros(LatLongGrid::new(16, 8));
        for (i, p) in img.pixels.iter_mut().enumerate() {
            *p = DVec3::new(
                i as f64 * 0.5,
                1.0 / (1.0 + i as f64),
                if i % 3 == 0 { 0.0 } else { 2.25 },
            );
        }
        img
    }

    #[test]
    fn exr_round_trips_at_f32_precision() {
        let dir = tempfile::tempdir().unwrap();
        let img = sample_image();
        let path = dir.path().join("x.exr");
        std::fs::write(&path, exr_bytes(&img).unwrap()).unwrap();
        let back = read_exr(&path).unwrap();
        assert_eq!(back.grid, img.grid);
        for (a, b) in img.pixels.iter().zip(&back.pixels) {
            assert!((*a - *b).abs().max_element() <= 1e-6 * a.abs().max_element().max(1.0));
        }
    }

    #[test]
    fn csv_columns_integrate_to_the_energy() {
        let img = sample_image();
        let csv = azimuthal_csv(&[("R", &img), ("total", &img)]).unwrap();
        let mut lines = csv.lines();
        assert_eq!(lines.next(), Some("phi,R,total"));
        let sum: f64 = lines
            .map(|l| l.split(',').nth(1).unwrap().parse::<f64>().unwrap())
            .sum();
        let e = img.energy();
        assert!((sum * img.grid.d_phi() - (e.x + e.y + e.z) / 3.0).abs() < 1e-9);
    }

    #[test]
    fn png_decodes_to_the_grid_size() {
        let bytes = png_bytes(&sample_image()).unwrap();
        let decoded = image::load_from_memory(&bytes).unwrap();
        assert_eq!((decoded.width(), decoded.height()), (16, 8));
        assert!(png_bytes(&LatLongImage::zeros(LatLongGrid::new(4, 2))).is_ok());
    }
}
