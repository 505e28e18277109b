//! The SRBF raster's coverage (ss = 3, which draws a fiber at least a subsample wide) against
//! the tubes' true coverage (8 × 8 camera rays a pixel) at 360 × 240, default camera: the true
//! coverage of the pixels the raster calls full, over the hair and its bottom fifth, and the
//! environment seen through them. `cargo run --release --example coverage_probe [GROOM]`;
//! `coverage_probe mask FILE.exr [GROOM]` writes min(raster, true) per pixel, a `--coverage`
//! mask for `cuticle compare` against path renders made before they wrote coverage.exr.
use cuticle_render::frame::raster::rasterize;
use cuticle_render::{Scene, SceneSpec};
use cuticle_trace::Accel;
use rayon::prelude::*;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.get(1).map(String::as_str) == Some("mask") {
        write_mask(&args[2], args.get(3));
        return;
    }
    let mut spec = SceneSpec::default();
    if let Some(g) = args.get(1) {
        spec.groom = g.clone();
    }
    let (w, h) = (360usize, 240usize);
    let scene = Scene::load_without_lights(spec).unwrap();
    let accel = Accel::build(&scene.groom);
    let view = scene.camera.view(w, h);
    let cov = rasterize(&scene.groom, &view, w, h, 3);
    let hair: Vec<usize> = (0..w * h)
        .filter(|&k| cov.pixel_fraction(k % w, k / w) >= 1.0)
        .collect();
    let top = hair.iter().map(|k| k / w).min().unwrap();
    let bottom = hair.iter().map(|k| k / w).max().unwrap();
    let cut = top as f64 + 0.8 * (bottom - top) as f64;
    let n = 8;
    let truth: Vec<(f64, glam::DVec3)> = hair
        .par_iter()
        .map(|&k| {
            let (x, y) = ((k % w) as f64, (k / w) as f64);
            let mut hits = 0;
            let mut miss = glam::DVec3::ZERO;
            for i in 0..n {
                for j in 0..n {
                    let d = view.ray(
                        x + (i as f64 + 0.5) / n as f64,
                        y + (j as f64 + 0.5) / n as f64,
                    );
                    if accel.closest(view.eye, d).is_some() {
                        hits += 1;
                    } else {
                        miss += scene.env_radiance(d);
                    }
                }
            }
            (hits as f64 / (n * n) as f64, miss / (n * n) as f64)
        })
        .collect();
    let (mut s_all, mut s_tip, mut n_tip) = (0.0, 0.0, 0);
    let (mut b_all, mut b_tip) = (glam::DVec3::ZERO, glam::DVec3::ZERO);
    for (i, &k) in hair.iter().enumerate() {
        s_all += truth[i].0;
        b_all += truth[i].1;
        if (k / w) as f64 > cut {
            s_tip += truth[i].0;
            b_tip += truth[i].1;
            n_tip += 1;
        }
    }
    println!(
        "hair pixels {} true coverage {:.3}; bottom fifth {} pixels true coverage {:.3}; raster covered fraction {:.3}",
        hair.len(),
        s_all / hair.len() as f64,
        n_tip,
        s_tip / n_tip as f64,
        cov.covered_fraction()
    );
    println!(
        "background seen through hair pixels (mean): all {:.4?} bottom fifth {:.4?}",
        b_all / hair.len() as f64,
        b_tip / n_tip as f64
    );
}

/// Writes min(raster, true) coverage of every pixel to `path` (the mask of a fair comparison).
pub fn write_mask(path: &str, groom: Option<&String>) {
    let (w, h) = (360usize, 240usize);
    let mut spec = SceneSpec::default();
    if let Some(g) = groom {
        spec.groom = g.clone();
    }
    let scene = Scene::load_without_lights(spec).unwrap();
    let accel = Accel::build(&scene.groom);
    let view = scene.camera.view(w, h);
    let cov = rasterize(&scene.groom, &view, w, h, 3);
    let n = 8;
    let px: Vec<glam::DVec3> = (0..w * h)
        .into_par_iter()
        .map(|k| {
            let (x, y) = ((k % w) as f64, (k / w) as f64);
            let mut hits = 0;
            for i in 0..n {
                for j in 0..n {
                    let d = view.ray(
                        x + (i as f64 + 0.5) / n as f64,
                        y + (j as f64 + 0.5) / n as f64,
                    );
                    if accel.closest(view.eye, d).is_some() {
                        hits += 1;
                    }
                }
            }
            let c = (hits as f64 / (n * n) as f64).min(cov.pixel_fraction(k % w, k / w));
            glam::DVec3::splat(c)
        })
        .collect();
    std::fs::write(
        path,
        cuticle_light::image_file::exr_bytes(w, h, &px).unwrap(),
    )
    .unwrap();
}
