//! `cuticle compare A/ B/`: two renders of one scene (output folders of `cuticle render`, any
//! method) against each other over the hair. Per channel: the mean over hair pixels of each,
//! their ratio A/B, and the relative RMSE √(mean (A − B)²) / mean B; for the whole hair and for
//! its bottom fifth (the tips: hair rows below top + 0.8 (bottom − top)). Printed, and written to
//! `compare.json` in `--out`, with `side_by_side.png`: A's image.png beside B's (each tone-mapped
//! by its render for the same map, so the two share an exposure).
//!
//! Hair pixels are those whose coverage is at least `--min-coverage` (default 1: fully covered,
//! so no background mixes in) in every coverage given: `coverage.exr` of A's folder, of B's, and
//! `--coverage FILE`, whichever exist (at least one). Both sides' masks count because they differ
//! where hair is thin: the SRBF and brute renders cover a fiber thinner than a subsample
//! stochastically (its true width on average, frame/draw.rs), the path tracer's coverage (the
//! fraction of its camera rays that meet a tube) by its own rays, so a pixel one calls full may
//! show the background in the other. With `--minus A0/ B0/`,
//! A − A0 is compared against B − B0: multiple scattering as a full render minus a direct one.

use crate::output::OutDir;
use anyhow::{Context, Result, bail};
use cuticle_render::Image;
use glam::DVec3;
use serde::Serialize;
use std::path::{Path, PathBuf};

#[derive(clap::Args, Debug)]
pub struct Args {
    /// Output folder of the render compared (its image.exr).
    pub a: PathBuf,
    /// Output folder of the reference render.
    pub b: PathBuf,
    /// Folders of the renders subtracted from A and from B (e.g. their direct light).
    #[arg(long, num_args = 2, value_names = ["A0", "B0"])]
    pub minus: Option<Vec<PathBuf>>,
    /// A further coverage EXR the hair pixels must fill (with the folders' coverage.exr).
    #[arg(long)]
    pub coverage: Option<PathBuf>,
    /// Smallest coverage of a hair pixel, in (0, 1].
    #[arg(long, default_value_t = 1.0)]
    pub min_coverage: f64,
    /// Folder compare.json is written to.
    #[arg(long, default_value = "out/compare")]
    pub out: PathBuf,
}

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

pub fn run(args: Args) -> Result<()> {
    if !(args.min_coverage > 0.0 && args.min_coverage <= 1.0) {
        bail!(
            "--min-coverage must lie in (0, 1], got {}",
            cuticle_fiber::ranges::short(args.min_coverage)
        );
    }
    let (render_a, render_b) = (Render::open(&args.a)?, Render::open(&args.b)?);
    let mut a = render_a.image("image.exr")?;
    let mut b = render_b.image("image.exr")?;
    if let Some(minus) = &args.minus {
        a = difference(&a, &Render::open(&minus[0])?.image("image.exr")?)?;
        b = difference(&b, &Render::open(&minus[1])?.image("image.exr")?)?;
    }
    let coverage_paths: Vec<PathBuf> = [&render_a, &render_b]
        .into_iter()
        .filter_map(|r| r.path("coverage.exr"))
        .chain(args.coverage.clone())
        .collect();
    if coverage_paths.is_empty() {
        bail!("no coverage.exr in either render; give --coverage FILE");
    }
    let coverages = coverage_paths
        .iter()
        .map(|p| read_image(p))
        .collect::<Result<Vec<_>>>()?;
    let coverage = least_coverage(&coverages)?;
    let result = compare(&a, &b, &coverage, args.min_coverage)?;
    let side_by_side = side_by_side(&render_a, &render_b)?;
    print_region("hair", &result.hair);
    print_region("bottom fifth", &result.bottom_fifth);
    let mut out = OutDir::create(&args.out, "compare")?;
    let record = serde_json::json!({
        "a": args.a,
        "b": args.b,
        "minus": args.minus,
        "coverage": coverage_paths,
        "min_coverage": args.min_coverage,
        "hair": result.hair,
        "bottom_fifth": result.bottom_fifth,
    });
    out.write("side_by_side.png", &side_by_side)?;
    out.finish(record)?;
    Ok(())
}

/// A finished output folder of `cuticle render`: only the files its render.json lists are read.
struct Render {
    dir: PathBuf,
    files: Vec<String>,
}

impl Render {
    fn open(dir: &Path) -> Result<Self> {
        Ok(Self {
            dir: dir.to_path_buf(),
            files: crate::output::read_set(dir, "render")?,
        })
    }

    /// `name` in the folder, when the render wrote it.
    fn path(&self, name: &str) -> Option<PathBuf> {
        self.files
            .iter()
            .any(|f| f == name)
            .then(|| self.dir.join(name))
    }

    fn image(&self, name: &str) -> Result<Image> {
        let path = self
            .path(name)
            .with_context(|| format!("{}: its render.json lists no {name}", self.dir.display()))?;
        let image = read_image(&path)?;
        // Radiance is never negative: a render that says so is not one (issue 57 #6).
        if let Some(k) = image.pixels.iter().position(|p| p.min_element() < 0.0) {
            bail!(
                "{}: pixel (column {}, row {}) is negative, {}; a render's radiance never is",
                path.display(),
                k % image.width,
                k / image.width,
                image.pixels[k]
            );
        }
        Ok(image)
    }
}

/// A's image.png and B's, left and right.
fn side_by_side(a: &Render, b: &Render) -> Result<Vec<u8>> {
    let read = |r: &Render| {
        let path = r
            .path("image.png")
            .with_context(|| format!("{}: its render.json lists no image.png", r.dir.display()))?;
        let image = image::open(&path)
            .with_context(|| format!("cannot read {}", path.display()))?
            .to_rgb8();
        Ok::<_, anyhow::Error>((path, image))
    };
    let ((left_path, left), (right_path, right)) = (read(a)?, read(b)?);
    if left.dimensions() != right.dimensions() {
        bail!(
            "{} is {}x{} and {} is {}x{}",
            left_path.display(),
            left.width(),
            left.height(),
            right_path.display(),
            right.width(),
            right.height()
        );
    }
    let (w, h) = left.dimensions();
    let mut both = image::RgbImage::new(2 * w, h);
    image::imageops::replace(&mut both, &left, 0, 0);
    image::imageops::replace(&mut both, &right, w as i64, 0);
    Ok(cuticle_light::image_file::png_bytes(
        2 * w as usize,
        h as usize,
        both.into_raw(),
    )?)
}

fn print_region(name: &str, r: &RegionStats) {
    let f = |v: [f64; 3]| format!("{:.4} {:.4} {:.4}", v[0], v[1], v[2]);
    println!(
        "{name} ({} px): mean A {}  mean B {}  A/B {}  rel. RMSE {}",
        r.pixels,
        f(r.mean_a),
        f(r.mean_b),
        f(r.ratio),
        f(r.relative_rmse)
    );
}

/// The figures of A against B over the pixels whose coverage (its first channel) is at least
/// `min_coverage`.
pub fn compare(a: &Image, b: &Image, coverage: &Image, min_coverage: f64) -> Result<Comparison> {
    for (img, what) in [(b, "B"), (coverage, "the coverage")] {
        if (img.width, img.height) != (a.width, a.height) {
            bail!(
                "{what} is {}x{}, A is {}x{}",
                img.width,
                img.height,
                a.width,
                a.height
            );
        }
    }
    let hair: Vec<usize> = (0..a.pixels.len())
        .filter(|&k| coverage.pixels[k].x >= min_coverage)
        .collect();
    let (Some(&first), Some(&last)) = (hair.first(), hair.last()) else {
        bail!("no pixel has coverage of at least {min_coverage}");
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
fn region(a: &Image, b: &Image, pixels: &[usize]) -> Result<RegionStats> {
    let n = pixels.len().max(1) as f64;
    let sum = |img: &Image| pixels.iter().map(|&k| img.pixels[k]).sum::<DVec3>() / n;
    let (mean_a, mean_b) = (sum(a), sum(b));
    if let Some(c) = (0..3).find(|&c| mean_a[c] < 0.0) {
        bail!(
            "A's mean over the {} hair pixels is {} in channel {}: a negative radiance (with \
             --minus, are A0 and B0 swapped?)",
            pixels.len(),
            mean_a[c],
            ["R", "G", "B"][c]
        );
    }
    if let Some(c) = (0..3).find(|&c| mean_b[c] <= 0.0) {
        bail!(
            "B's mean over the {} hair pixels is {} in channel {}: the ratio A/B and the \
             relative RMSE are undefined",
            pixels.len(),
            mean_b[c],
            ["R", "G", "B"][c]
        );
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
fn least_coverage(coverages: &[Image]) -> Result<Image> {
    let mut least = coverages[0].clone();
    for c in &coverages[1..] {
        if (c.width, c.height) != (least.width, least.height) {
            bail!(
                "coverages of {}x{} and {}x{} pixels",
                least.width,
                least.height,
                c.width,
                c.height
            );
        }
        for (l, v) in least.pixels.iter_mut().zip(&c.pixels) {
            *l = l.min(*v);
        }
    }
    Ok(least)
}

fn difference(x: &Image, y: &Image) -> Result<Image> {
    if (x.width, x.height) != (y.width, y.height) {
        bail!(
            "cannot subtract a {}x{} image from a {}x{} one",
            y.width,
            y.height,
            x.width,
            x.height
        );
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

/// An RGB(A) EXR's first layer as linear RGB: its header bounded by the file's size, every
/// pixel finite (cuticle_light's reader).
fn read_image(path: &Path) -> Result<Image> {
    let image = cuticle_light::image_file::read_rgb_exr(path)?;
    Ok(Image {
        width: image.width,
        height: image.height,
        pixels: image.pixels,
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
