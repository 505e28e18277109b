//! `cuticle compare A/ B/`: two renders of one scene (output folders of `cuticle render`, any
//! method) against each other over the hair, by [`cuticle_render::compare`]'s figures. Printed,
//! and written to `compare.json` in `--out`, with `side_by_side.png`: A's image.png beside B's
//! (each tone-mapped by its render for the same map, so the two share an exposure).
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
use cuticle_render::compare::{RegionStats, compare, difference, least_coverage};
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
