//! Shading again only what an edit changed. A point's colour depends on the preparation (its
//! frame, view and T̃), its strand's fiber and settings every point shares (the hair
//! parameters that build the tables, the lights, the quadrature, the lobes shown): a paint
//! stroke, which changes a few strands' absorption, leaves every other point's colour as it
//! was. [`Shaded`] keeps one pass's colours with what they were computed from, and the next pass
//! ([`crate::Renderer::shade_reusing`]) copies the colours whose inputs are unchanged and shades
//! the rest: the same image, bit for bit, as shading every point.

use crate::frame::shadows::ShadowOptions;
use crate::scene::hair::HairParams;
use crate::scene::{Lobes, Method, Scene};
use cuticle_fiber::models::marschner2003::MarschnerParams;
use glam::DVec3;

/// One shading pass: L_o of each prepared point, with what it was computed from.
#[derive(Clone, Debug)]
pub struct Shaded {
    /// L_o at each of the preparation's visible points, in its order.
    pub colours: Vec<DVec3>,
    /// The points this pass shaded (the others were copied from the pass before).
    pub points_shaded: usize,
    /// Each strand's fiber.
    pub(crate) fibers: Vec<MarschnerParams>,
    pub(crate) shared: SharedInputs,
}

/// What every point's shading reads besides its own strand's fiber and the preparation.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct SharedInputs {
    hair: HairParams,
    method: Method,
    quadrature: usize,
    multiple: bool,
    lobes: Lobes,
    shadows: ShadowOptions,
    brute_grid: usize,
}

impl SharedInputs {
    pub(crate) fn of(scene: &Scene) -> Self {
        let s = &scene.spec;
        Self {
            hair: s.hair,
            method: s.method,
            quadrature: s.quadrature,
            multiple: s.multiple,
            lobes: s.lobes,
            shadows: s.shadows,
            brute_grid: s.brute_grid,
        }
    }
}

/// Which of `points` (strand of each point by `strand_of_point`) must be shaded again, given
/// the pass before (`None`: every point). A point keeps its colour when the shared inputs are
/// the same and its strand's fiber equals the one it was shaded with.
pub(crate) fn stale_points(
    previous: Option<&Shaded>,
    shared: &SharedInputs,
    fibers: &[MarschnerParams],
    points: &[u32],
    strand_of_point: &[u32],
) -> Vec<bool> {
    let Some(before) = previous.filter(|b| {
        b.shared == *shared && b.fibers.len() == fibers.len() && b.colours.len() == points.len()
    }) else {
        return vec![true; points.len()];
    };
    let changed: Vec<bool> = fibers
        .iter()
        .zip(&before.fibers)
        .map(|(now, then)| now != then)
        .collect();
    points
        .iter()
        .map(|&p| changed[strand_of_point[p as usize] as usize])
        .collect()
}
