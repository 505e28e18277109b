//! Two renders of one scene against each other over the hair (`cuticle compare`): per channel,
//! the mean over hair pixels of each, their ratio A/B, and the relative RMSE
//! √(mean (A − B)²) / mean B, for the whole hair and for its bottom fifth (the tips: hair rows
//! below top + 0.8 (bottom − top)). Hair pixels are those whose coverage (its first channel)
//! is at least a threshold; [`least_coverage`] combines several renders' masks.

use crate::frame::renderer::Image;
use glam::DVec3;
use serde::Serialize;

/// Why two images cannot be compared: one sentence each.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum CompareError {
    #[error("{what} is {width}x{height}, A is {a_width}x{a_height}")]
    Size {
        what: &'static str,
        width: usize,
        height: usize,
        a_width: usize,
        a_height: usize,
    },
    #[error("no pixel has coverage of at least {0}")]
    NoHair(f64),
    #[error(
        "A's mean over the {pixels} hair pixels is {mean} in channel {channel}: a negative \
         radiance (with --minus, are A0 and B0 swapped?)"
    )]
    NegativeMean {
        pixels: usize,
        mean: f64,
        channel: &'static str,
    },
    #[error(
        "B's mean over the {pixels} hair pixels is {mean} in channel {channel}: the ratio A/B \
         and the relative RMSE are undefined"
    )]
    DarkReference {
        pixels: usize,
        mean: f64,
        channel: &'static str,
    },
}

const CHANNELS: [&str; 3] = ["R", "G", "B"];

/// One region's figures, per channel (R, G, B).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RegionStats {
    pub pixels: usize,
    pub mean_a: [f64; 3],
    pub mean_b: [f64; 3],
    /// mean A / mean B.
    pub ratio: [f64; 3],
    /// √(mean (A − B)²) / mean B.
    pub relative_rmse: [f64; 3],
}

/// The whole hair and its bottom fifth.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Comparison {
    pub hair: RegionStats,
    pub bottom_fifth: RegionStats,
}

/// The figures of A against B over the pixels whose coverage (its first channel) is at least
/// `min_coverage`.
pub fn compare(
    a: &Image,
    b: &Image,
    coverage: &Image,
    min_coverage: f64,
) -> Result<Comparison, CompareError> {
    for (img, what) in [(b, "B"), (coverage, "the coverage")] {
        if (img.width, img.height) != (a.width, a.height) {
            return Err(CompareError::Size {
                what,
                width: img.width,
                height: img.height,
                a_width: a.width,
                a_height: a.height,
            });
        }
    }
    let hair: Vec<usize> = (0..a.pixels.len())
        .filter(|&k| coverage.pixels[k].x >= min_coverage)
        .collect();
    let (Some(&first), Some(&last)) = (hair.first(), hair.last()) else {
        return Err(CompareError::NoHair(min_coverage));
    };
    let (top, bottom) = (first / a.width, last / a.width);
    let cut = bottom as f64 - 0.2 * (bottom - top) as f64;
    let tips: Vec<usize> = hair
        .iter()
        .copied()
        .filter(|&k| (k / a.width) as f64 > cut)
        .collect();
    Ok(Comparison {
        hair: region(a, b, &hair)?,
        bottom_fifth: region(a, b, &tips)?,
    })
}

/// The figures over `pixels`; B's mean must be positive in every channel, or the ratio and
/// the relative RMSE divide by zero.
fn region(a: &Image, b: &Image, pixels: &[usize]) -> Result<RegionStats, CompareError> {
    let n = pixels.len().max(1) as f64;
    let sum = |img: &Image| pixels.iter().map(|&k| img.pixels[k]).sum::<DVec3>() / n;
    let (mean_a, mean_b) = (sum(a), sum(b));
    if let Some(c) = (0..3).find(|&c| mean_a[c] < 0.0) {
        return Err(CompareError::NegativeMean {
            pixels: pixels.len(),
            mean: mean_a[c],
            channel: CHANNELS[c],
        });
    }
    if let Some(c) = (0..3).find(|&c| mean_b[c] <= 0.0) {
        return Err(CompareError::DarkReference {
            pixels: pixels.len(),
            mean: mean_b[c],
            channel: CHANNELS[c],
        });
    }
    let square: DVec3 = pixels
        .iter()
        .map(|&k| (a.pixels[k] - b.pixels[k]).powf(2.0))
        .sum::<DVec3>()
        / n;
    Ok(RegionStats {
        pixels: pixels.len(),
        mean_a: mean_a.to_array(),
        mean_b: mean_b.to_array(),
        ratio: (mean_a / mean_b).to_array(),
        relative_rmse: (square.map(f64::sqrt) / mean_b).to_array(),
    })
}

/// Per pixel, the least of the coverages (one size, at least one).
pub fn least_coverage(coverages: &[Image]) -> Result<Image, CompareError> {
    let mut least = coverages[0].clone();
    for c in &coverages[1..] {
        if (c.width, c.height) != (least.width, least.height) {
            return Err(CompareError::Size {
                what: "a coverage",
                width: c.width,
                height: c.height,
                a_width: least.width,
                a_height: least.height,
            });
        }
        for (l, v) in least.pixels.iter_mut().zip(&c.pixels) {
            *l = l.min(*v);
        }
    }
    Ok(least)
}

/// x − y pixel by pixel (multiple scattering as a full render minus a direct one).
pub fn difference(x: &Image, y: &Image) -> Result<Image, CompareError> {
    if (x.width, x.height) != (y.width, y.height) {
        return Err(CompareError::Size {
            what: "the image subtracted",
            width: y.width,
            height: y.height,
            a_width: x.width,
            a_height: x.height,
        });
    }
    Ok(Image {
        width: x.width,
        height: x.height,
        pixels: x
            .pixels
            .iter()
            .zip(&y.pixels)
            .map(|(p, q)| *p - *q)
            .collect(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image(w: usize, h: usize, f: impl Fn(usize, usize) -> DVec3) -> Image {
        Image {
            width: w,
            height: h,
            pixels: (0..w * h).map(|k| f(k % w, k / w)).collect(),
        }
    }

    /// Hair in rows 2..=11 of a 4-wide image (columns 1 and 2), huge values outside it that
    /// must not count: B is 1 (R), 2 (G), 4 (B); A is twice B above the bottom fifth (rows
    /// 10 and 11, below 11 − 0.2·9 = 9.2) and three times B there, alternating ±0.5 in R.
    /// Means, ratios and the relative RMSE follow by hand.
    #[test]
    fn figures_over_the_hair_and_its_tips() {
        let hair = |x: usize, y: usize| (1..=2).contains(&x) && (2..=11).contains(&y);
        let coverage = image(4, 14, |x, y| {
            DVec3::splat(if hair(x, y) { 1.0 } else { 0.5 })
        });
        let base = DVec3::new(1.0, 2.0, 4.0);
        let b = image(
            4,
            14,
            |x, y| if hair(x, y) { base } else { DVec3::splat(1e9) },
        );
        let a = image(4, 14, |x, y| {
            let k = if y >= 10 { 3.0 } else { 2.0 };
            let wobble = if x == 1 { 0.5 } else { -0.5 };
            base * k + DVec3::new(wobble, 0.0, 0.0)
        });
        let c = compare(&a, &b, &coverage, 1.0).unwrap();
        assert_eq!((c.hair.pixels, c.bottom_fifth.pixels), (20, 4));
        let close = |x: f64, y: f64| assert!((x - y).abs() < 1e-12, "{x} vs {y}");
        close(c.hair.mean_b[1], 2.0);
        // 16 pixels at 2, 4 at 3: mean factor 2.2.
        close(c.hair.ratio[2], 2.2);
        close(c.bottom_fifth.ratio[1], 3.0);
        // B channel: (A − B)/B is 1 on 16 pixels and 2 on 4: √((16 + 16)/20) = √1.6.
        close(c.hair.relative_rmse[2], 1.6f64.sqrt());
        // R in the tips: A − B = 2 ± 0.5: √((2.5² + 1.5²)/2) / 1.
        close(
            c.bottom_fifth.relative_rmse[0],
            ((6.25 + 2.25) / 2.0f64).sqrt(),
        );
        // A lower threshold lets the half-covered background in.
        assert_eq!(compare(&a, &b, &coverage, 0.5).unwrap().hair.pixels, 56);
    }

    /// The mask is the least of the coverages: a pixel full in one and partial in the other
    /// is not hair; coverages of two sizes are an error.
    #[test]
    fn the_mask_is_the_least_coverage() {
        let a = image(3, 1, |x, _| DVec3::splat([1.0, 1.0, 0.4][x]));
        let b = image(3, 1, |x, _| DVec3::splat([1.0, 0.75, 1.0][x]));
        let least = least_coverage(&[a.clone(), b]).unwrap();
        let first: Vec<f64> = least.pixels.iter().map(|p| p.x).collect();
        assert_eq!(first, [1.0, 0.75, 0.4]);
        assert!(least_coverage(&[a, image(2, 1, |_, _| DVec3::ONE)]).is_err());
    }

    /// Images of different sizes, or a mask with no hair, are one clear error each.
    #[test]
    fn mismatched_or_empty_inputs_are_errors() {
        let one = image(3, 3, |_, _| DVec3::ONE);
        let other = image(3, 4, |_, _| DVec3::ONE);
        assert!(compare(&one, &other, &one, 1.0).is_err());
        assert!(compare(&one, &one, &other, 1.0).is_err());
        let empty = image(3, 3, |_, _| DVec3::ZERO);
        let err = compare(&one, &one, &empty, 1.0).unwrap_err().to_string();
        assert!(err.contains("no pixel"), "{err}");
        // A black B (say, B − B0 of two equal renders) leaves the ratio undefined: refused,
        // not written as NaN.
        let black_green = image(3, 3, |_, _| DVec3::new(1.0, 0.0, 1.0));
        let err = compare(&one, &black_green, &one, 1.0)
            .unwrap_err()
            .to_string();
        assert!(err.contains("channel G"), "{err}");
    }
}
