//! The quick frame shown first after each edit ([`crate::worker::Quality::Preview`]): the
//! renderer's preview scene ([`cuticle_render::preview`]: fewer pixels, one subsample, the
//! frame's lights merged into a few, a coarser quadrature) at a reduction along each axis
//! chosen from the last preview's shading time ([`next_scale`]), shaded by a preview renderer
//! ([`cuticle_render::Renderer::for_preview`]: coarse back-scattering tables).
//!
//! The full-quality frame that follows uses the scene as it is.

pub use cuticle_render::preview::{PREVIEW_LIGHTS, PREVIEW_QUADRATURE, preview_scene};

/// Shading seconds a preview aims at (the first updated frame after an edit).
pub const PREVIEW_BUDGET_S: f64 = 0.04;
/// Largest reduction of the preview along each axis.
pub const MAX_PREVIEW_SCALE: usize = 8;
/// Shading times within these factors of [`PREVIEW_BUDGET_S`] keep the preview's size (a
/// resize re-runs the preview's drawing): wide enough for one step of scale (0.56× the pixels
/// from 3 to 4) and for the noise of a loaded machine, so that the budget times the upper one
/// plus a preview's scene and hand-over stays within issue 11's aim of 100 ms.
pub const KEEP_SCALE: (f64, f64) = (0.5, 2.0);

/// The preview reduction after a preview at `scale` that shaded in `shade_s`: unchanged while
/// the time is within [`KEEP_SCALE`] of [`PREVIEW_BUDGET_S`], else the one whose pixel count
/// (to which shading is about proportional) meets the budget, within 1..=[`MAX_PREVIEW_SCALE`].
pub fn next_scale(scale: usize, shade_s: f64) -> usize {
    let ratio = shade_s / PREVIEW_BUDGET_S;
    if !(KEEP_SCALE.0..=KEEP_SCALE.1).contains(&ratio) {
        let ideal = scale as f64 * ratio.sqrt();
        return (ideal.round() as usize).clamp(1, MAX_PREVIEW_SCALE);
    }
    scale
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A slow preview shrinks in one step to the budget's size; one near budget stays.
    #[test]
    fn next_scale_meets_the_budget_in_one_step() {
        assert_eq!(next_scale(2, 16.0 * PREVIEW_BUDGET_S), 8);
        assert_eq!(next_scale(2, 4.0 * PREVIEW_BUDGET_S), 4);
        assert_eq!(next_scale(4, 1.5 * PREVIEW_BUDGET_S), 4);
        assert_eq!(next_scale(4, 2.5 * PREVIEW_BUDGET_S), 6);
        assert_eq!(next_scale(4, 0.6 * PREVIEW_BUDGET_S), 4);
        assert_eq!(next_scale(4, 0.25 * PREVIEW_BUDGET_S), 2);
        assert_eq!(next_scale(8, 100.0), MAX_PREVIEW_SCALE);
        assert_eq!(next_scale(1, 0.0), 1);
    }
}
