//! What the window needs from a back end that shades: the renderer's stages as three calls, so
//! that the CPU renderer ([`cpu`]) and the GPU back end (crate `cuticle-gpu`, when it lands)
//! plug in alike.
//!
//! - [`Shading::prepare`]: visibility, background and shadows for the scene's camera, groom and
//!   lights (a camera move, a new groom or new lights re-run it);
//! - [`Shading::shade`]: L_o at the visible points for the scene's hair parameters and
//!   per-strand absorption, resolved into pixels, on the kept preparation (an edit of the hair
//!   or a paint stroke re-runs only this), given up when a newer edit makes it stale;
//! - [`Shading::strands`]: which strand each subsample of the prepared frame shows, for picking
//!   strands under the brush.

pub mod cpu;

use cuticle_render::{Image, Scene};
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
    /// Stages 2–3 of the frame for `scene`: what stays valid while only the hair changes.
    fn prepare(&mut self, scene: &Scene);
    /// Stages 4–5 on the last preparation; `None` when `cancel` was set before it finished (or
    /// nothing is prepared).
    fn shade(&mut self, scene: &Scene, cancel: &AtomicBool) -> Option<Image>;
    /// The strand at each subsample of the last preparation.
    fn strands(&self) -> StrandBuffer;
}
