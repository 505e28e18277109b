//! What the window needs from a back end that shades: the renderer's stages as three calls, so
//! that the CPU renderer ([`cpu`]) and the GPU back end ([`gpu`], crate `cuticle-gpu`) plug in
//! alike; [`Backends::choose`] picks one for `--device auto|gpu|cpu`.
//!
//! - [`Shading::prepare`]: visibility, background and shadows for the scene's camera, groom and
//!   lights (a camera move, a new groom or new lights re-run it; the CPU back end keeps the
//!   shadows, which do not depend on the camera); [`Shading::relight`] for new lights alone
//!   (the GPU back end keeps its drawing);
//! - [`Shading::shade`]: L_o at the visible points for the scene's hair parameters and
//!   per-strand absorption, resolved into pixels, on the kept preparation (an edit of the hair
//!   or a paint stroke re-runs only this; the CPU back end then shades only the points whose
//!   strand or shared parameters changed), given up when a newer edit makes it stale;
//! - [`Shading::strands`]: which strand each subsample of the prepared frame shows, for picking
//!   strands under the brush.

pub mod cpu;
pub mod gpu;

use cuticle_render::{Image, Renderer, Scene};
use std::sync::atomic::AtomicBool;

/// No strand covers the subsample.
pub const NO_STRAND: u32 = u32::MAX;

/// The strand seen at each subsample of a frame: `ss × ss` subsamples per pixel, row-major over
/// the `width·ss × height·ss` grid.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StrandBuffer {
    pub width: usize,
    pub height: usize,
    pub ss: usize,
    pub strand: Vec<u32>,
}

impl StrandBuffer {
    /// The strand at subsample (sx, sy), if any.
    pub fn at(&self, sx: usize, sy: usize) -> Option<u32> {
        let sw = self.width * self.ss;
        (sx < sw && sy < self.height * self.ss)
            .then(|| self.strand[sy * sw + sx])
            .filter(|&s| s != NO_STRAND)
    }
}

/// A back end that shades frames of a scene.
pub trait Shading: Send {
    /// Which back end this is, as the window shows it.
    fn backend(&self) -> String;
    /// Stages 2–3 of the frame for `scene`: what stays valid while only the hair changes; an
    /// error (one line) when the back end cannot render the scene.
    fn prepare(&mut self, scene: &Scene) -> Result<(), String>;
    /// [`Self::prepare`] for new lights alone (a rotated or re-fitted environment) with the
    /// camera, groom, size and shadow settings of the last preparation: a back end that can
    /// keep its drawing re-does only the shadows and the background.
    fn relight(&mut self, scene: &Scene) -> Result<(), String> {
        self.prepare(scene)
    }
    /// Stages 4–5 on the last preparation; `None` when `cancel` was set before it finished (or
    /// nothing is prepared).
    fn shade(&mut self, scene: &Scene, cancel: &AtomicBool) -> Result<Option<Image>, String>;
    /// The strand at each subsample of the last preparation.
    fn strands(&self) -> StrandBuffer;
    /// Strand records the last shade re-uploaded for paint (a back end that keeps them on a
    /// device; 0 for one that reads the scene directly).
    fn strands_updated(&self) -> usize {
        0
    }
    /// How many times this back end computed shadows for a whole groom and its lights (a
    /// camera move alone needs none on a back end that keeps them); 0 for one that does not
    /// count.
    fn shadow_passes(&self) -> u64 {
        0
    }
    /// How many shading tables (those a hair-parameter edit may rebuild) this back end's
    /// renderer has built so far; 0 for one that does not count.
    fn table_builds(&self) -> u64 {
        0
    }
    /// The points the last shade computed (a back end that keeps the pass before shades only
    /// the points an edit changed: after a paint stroke, the painted strands'); `None` for one
    /// that does not count.
    fn points_shaded(&self) -> Option<usize> {
        None
    }
}

/// The two back ends the worker drives, one per quality, and whether they shade on the GPU.
pub struct Backends {
    pub preview: Box<dyn Shading>,
    pub full: Box<dyn Shading>,
    pub gpu: bool,
}

impl Backends {
    /// The CPU renderer at both qualities, the preview's one [`Renderer::for_preview`] (each
    /// shares `renderer`'s tables and caches).
    pub fn cpu(renderer: &Renderer) -> Self {
        Self {
            preview: Box::new(cpu::CpuShading::new(renderer.for_preview())),
            full: Box::new(cpu::CpuShading::new(renderer.clone())),
            gpu: false,
        }
    }

    /// The back ends for `--device`: `auto` takes a hardware GPU where one exists, else the
    /// CPU renderer; `gpu` any adapter, a software one included (an error when there is none);
    /// `cpu` the CPU renderer.
    pub fn choose(device: cuticle_gpu::Choice, renderer: &Renderer) -> Result<Self, String> {
        match cuticle_gpu::Backend::choose(device).map_err(|e| e.to_string())? {
            cuticle_gpu::Backend::Cpu => Ok(Self::cpu(renderer)),
            cuticle_gpu::Backend::Gpu(device) => {
                let gpu = std::sync::Arc::new(cuticle_gpu::GpuRenderer::new(&device, renderer));
                Ok(Self {
                    preview: Box::new(gpu::GpuShading::new(gpu.clone())),
                    full: Box::new(gpu::GpuShading::new(gpu)),
                    gpu: true,
                })
            }
        }
    }
}
