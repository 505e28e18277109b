//! The SRBF raster's coverage (ss = 3, or `PROBE_SS` in the environment) against the tubes'
//! true coverage (8 × 8 camera rays a pixel) at 360 × 240, default camera: the true coverage
//! of the pixels the raster calls full, over the hair and its bottom fifth, and the environment
//! seen through them; then the raster's covered area against the true one, summed over every
//! pixel and over the bottom fifth of the rows the true hair spans.
//! `cargo run --release --example coverage_probe [GROOM]`; `coverage_probe mask FILE.exr
//! [GROOM]` writes min(raster, true) per pixel, a `--coverage` mask for `cuticle compare`
//! against path renders made before they wrote coverage.exr.
use cuticle_render::frame::draw::draw_strands;
use cuticle_render::{Scene, SceneSpec};
use cuticle_trace::Accel;
use glam::DVec3;
use rayon::prelude::*;

/// Width and height of the probe's images (those of the path references it masks).
const SIZE: (usize, usize) = (360, 240);
/// Camera rays per pixel side for the true coverage.
const RAYS: usize = 8;

/// The scene, the tubes' acceleration structure, the camera and the raster's coverage.
struct Probe {
    scene: Scene,
    accel: Accel,
    view: cuticle_render::scene::camera::View,
    cov: cuticle_render::frame::draw::Coverage,
}

/// A pixel's true coverage and the mean environment radiance seen through it.
struct TruePixel {
    coverage: f64,
    background: DVec3,
}

impl Probe {
    fn load(groom: Option<&String>) -> Self {
        let mut spec = SceneSpec::default();
        if let Some(g) = groom {
            spec.groom = g.clone();
        }
        let scene = Scene::load_without_lights(spec).unwrap();
        let accel = Accel::build(&scene.groom);
        let view = scene.camera.view(SIZE.0, SIZE.1);
        let cov = draw_strands(
            &scene.groom,
            &view,
            SIZE.0,
            SIZE.1,
            std::env::var("PROBE_SS")
                .map(|s| {
                    s.parse()
                        .expect("PROBE_SS: a count of subsamples per pixel side")
                })
                .unwrap_or(3),
        );
        Probe {
            scene,
            accel,
            view,
            cov,
        }
    }

    /// Pixel `k`'s true coverage from RAYS × RAYS camera rays through the tubes.
    fn true_pixel(&self, k: usize) -> TruePixel {
        let (x, y) = ((k % SIZE.0) as f64, (k / SIZE.0) as f64);
        let (mut hits, mut background) = (0, DVec3::ZERO);
        for i in 0..RAYS {
            for j in 0..RAYS {
                let d = self.view.ray(
                    x + (i as f64 + 0.5) / RAYS as f64,
                    y + (j as f64 + 0.5) / RAYS as f64,
                );
                if self.accel.closest(self.view.eye, d).is_some() {
                    hits += 1;
                } else {
                    background += self.scene.env_radiance(d);
                }
            }
        }
        let n = (RAYS * RAYS) as f64;
        TruePixel {
            coverage: hits as f64 / n,
            background: background / n,
        }
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.get(1).map(String::as_str) == Some("mask") {
        write_mask(&args[2], args.get(3));
        return;
    }
    let probe = Probe::load(args.get(1));
    let w = SIZE.0;
    let hair: Vec<usize> = (0..SIZE.0 * SIZE.1)
        .filter(|&k| probe.cov.pixel_fraction(k % w, k / w) >= 1.0)
        .collect();
    let top = hair.iter().map(|k| k / w).min().unwrap();
    let bottom = hair.iter().map(|k| k / w).max().unwrap();
    let cut = top as f64 + 0.8 * (bottom - top) as f64;
    let truth: Vec<TruePixel> = hair.par_iter().map(|&k| probe.true_pixel(k)).collect();
    let (mut s_all, mut s_tip, mut n_tip) = (0.0, 0.0, 0);
    let (mut b_all, mut b_tip) = (DVec3::ZERO, DVec3::ZERO);
    for (t, &k) in truth.iter().zip(&hair) {
        s_all += t.coverage;
        b_all += t.background;
        if (k / w) as f64 > cut {
            s_tip += t.coverage;
            b_tip += t.background;
            n_tip += 1;
        }
    }
    println!(
        "hair pixels {} true coverage {:.3}; bottom fifth {} pixels true coverage {:.3}; raster covered fraction {:.3}",
        hair.len(),
        s_all / hair.len() as f64,
        n_tip,
        s_tip / n_tip as f64,
        probe.cov.covered_fraction()
    );
    println!(
        "background seen through hair pixels (mean): all {:.4?} bottom fifth {:.4?}",
        b_all / hair.len() as f64,
        b_tip / n_tip as f64
    );
    let every: Vec<f64> = (0..SIZE.0 * SIZE.1)
        .into_par_iter()
        .map(|k| probe.true_pixel(k).coverage)
        .collect();
    let rows: Vec<usize> = (0..every.len())
        .filter(|&k| every[k] > 0.0)
        .map(|k| k / w)
        .collect();
    let (top, bottom) = (*rows.iter().min().unwrap(), *rows.iter().max().unwrap());
    let cut = top as f64 + 0.8 * (bottom - top) as f64;
    let (mut raster, mut truth, mut raster_tip, mut truth_tip) = (0.0, 0.0, 0.0, 0.0);
    for (k, &t) in every.iter().enumerate() {
        let r = probe.cov.pixel_fraction(k % w, k / w);
        (raster, truth) = (raster + r, truth + t);
        if (k / w) as f64 > cut {
            (raster_tip, truth_tip) = (raster_tip + r, truth_tip + t);
        }
    }
    println!(
        "covered area, every pixel (raster / true): all {raster:.0} / {truth:.0} pixels ({:.3}); \
         bottom fifth of the true hair's rows {raster_tip:.0} / {truth_tip:.0} ({:.3})",
        raster / truth,
        raster_tip / truth_tip
    );
}

/// Writes min(raster, true) coverage of every pixel to `path` (the mask of a fair comparison).
pub fn write_mask(path: &str, groom: Option<&String>) {
    let probe = Probe::load(groom);
    let w = SIZE.0;
    let px: Vec<DVec3> = (0..SIZE.0 * SIZE.1)
        .into_par_iter()
        .map(|k| {
            let raster = probe.cov.pixel_fraction(k % w, k / w);
            DVec3::splat(probe.true_pixel(k).coverage.min(raster))
        })
        .collect();
    std::fs::write(
        path,
        cuticle_light::image_file::exr_bytes(SIZE.0, SIZE.1, &px).unwrap(),
    )
    .unwrap();
}
