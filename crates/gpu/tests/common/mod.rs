//! Helpers shared by the GPU tests: one device and one CPU renderer per test binary, small
//! scenes, and the image metric the parity tests state their bounds in.

#![allow(dead_code)]

use cuticle_gpu::{GpuDevice, GpuRenderer, Preference, Visibility};
use cuticle_render::frame::draw::{Coverage, EMPTY};
use cuticle_render::{Image, Renderer, Scene, SceneSpec, ShadowOptions};
use std::path::PathBuf;
use std::sync::OnceLock;

/// Any adapter, a software one included. Without one the test fails and says how to get one:
/// a GPU test never skips.
pub fn device() -> &'static GpuDevice {
    static D: OnceLock<GpuDevice> = OnceLock::new();
    D.get_or_init(|| {
        let d = GpuDevice::new(Preference::Any).unwrap_or_else(|e| {
            panic!("the GPU tests need a GPU adapter, hardware or software: {e}")
        });
        eprintln!("adapter: {:?}", d.summary);
        d
    })
}

pub fn cpu() -> &'static Renderer {
    static R: OnceLock<Renderer> = OnceLock::new();
    R.get_or_init(Renderer::new)
}

pub fn gpu() -> &'static GpuRenderer {
    static G: OnceLock<GpuRenderer> = OnceLock::new();
    G.get_or_init(|| GpuRenderer::new(device(), cpu()))
}

/// A preset groom of `strands` strands (each with its own absorption) at 240 × 160, 2 × 2
/// subsamples, 128² opacity maps.
pub fn spec(strands: usize, env: &str, lights: usize) -> SceneSpec {
    SceneSpec {
        groom: "straight".into(),
        strands,
        env: env.into(),
        lights,
        width: 240,
        height: 160,
        supersampling: 2,
        shadows: ShadowOptions {
            resolution: 128,
            ..ShadowOptions::default()
        },
        ..SceneSpec::default()
    }
}

pub fn load(spec: SceneSpec) -> Scene {
    Scene::load(spec, None).expect("test scene")
}

/// A map from ../shared/data/envmaps, which CI has beside the checkout; `None` (said plainly)
/// where it is absent, as every test of the project's data does (DESIGN.md §6).
pub fn shared_map(name: &str) -> Option<String> {
    let path = PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../../shared/data/envmaps"
    ))
    .join(name);
    if path.exists() {
        Some(path.to_string_lossy().into_owned())
    } else {
        println!("skipped: {} is absent", path.display());
        None
    }
}

/// Whether any subsample of pixel k shows hair.
pub fn hair_pixels(vis: &Visibility) -> Vec<bool> {
    (0..vis.width * vis.height)
        .map(|k| {
            vis.pixel(k % vis.width, k / vis.width)
                .any(|s| s != Visibility::EMPTY)
        })
        .collect()
}

/// The pixels an image comparison reads: those whose subsamples keep the same segment in the
/// GPU's drawing and the CPU's (where they differ, at the few subsamples tests/drawing.rs
/// bounds, the images differ by the drawing, not by the shading these tests measure).
pub struct Agreeing {
    /// Per pixel: both drawings agree there.
    pub all: Vec<bool>,
    /// Per pixel: both agree and show hair.
    pub hair: Vec<bool>,
    /// Hair pixels left out because the drawings differ there.
    pub left_out: usize,
}

pub fn agreeing_pixels(gpu: &Coverage, cpu: &Coverage) -> Agreeing {
    assert_eq!(
        gpu.segment.len(),
        cpu.segment.len(),
        "drawings of different sizes"
    );
    let (mut all, mut hair, mut left_out) = (Vec::new(), Vec::new(), 0);
    for k in 0..gpu.width * gpu.height {
        let (x, y) = (k % gpu.width, k / gpu.width);
        let agree = gpu
            .pixel_samples(x, y)
            .all(|s| gpu.segment[s] == cpu.segment[s]);
        let shows = gpu.pixel_samples(x, y).any(|s| gpu.segment[s] != EMPTY);
        left_out += (shows && !agree) as usize;
        all.push(agree);
        hair.push(agree && shows);
    }
    let shown = hair.iter().filter(|&&h| h).count();
    assert!(
        left_out * 100 <= shown,
        "the drawings differ at {left_out} of {} hair pixels",
        shown + left_out
    );
    Agreeing {
        all,
        hair,
        left_out,
    }
}

/// √(Σ|a − b|² / Σ|b|²) over the pixels `mask` marks.
pub fn relative_rmse(a: &Image, b: &Image, mask: &[bool]) -> f64 {
    let (mut num, mut den) = (0.0, 0.0);
    for ((pa, pb), &m) in a.pixels.iter().zip(&b.pixels).zip(mask) {
        if m {
            num += (*pa - *pb).length_squared();
            den += pb.length_squared();
        }
    }
    assert!(
        den > 0.0,
        "no hair pixels: the comparison would compare nothing"
    );
    (num / den).sqrt()
}

/// The largest |a − b| of a pixel channel, over the pixels `mask` marks, relative to the
/// brightest reference channel.
pub fn worst_relative(a: &Image, b: &Image, mask: &[bool]) -> f64 {
    let brightest = b.pixels.iter().map(|p| p.max_element()).fold(0.0, f64::max);
    let worst = a
        .pixels
        .iter()
        .zip(&b.pixels)
        .zip(mask)
        .filter(|(_, m)| **m)
        .map(|((x, y), _)| (*x - *y).abs().max_element())
        .fold(0.0, f64::max);
    worst / brightest
}
