//! An adaptive fit target: the map area-averaged onto a coarse `width × height` grid, with cells
//! split quadtree-fashion (down to single pixels) where the coarse grid would mislead the fit.
//!
//! 1. Detail: a cell of pixels P stands for them by its mean L̄; what the fit cannot see there is
//!    its hidden error Σ_{p∈P} Δω_p ‖L_p − L̄‖², exactly what the full-map squared error of any
//!    model constant over the cell exceeds its error on the coarse sample by. Cells with the
//!    largest hidden error (a compact sun, a window's edge) split first, within a budget, until
//!    what stays hidden is below 1e-4 of Σ Δω ‖L‖² (a 1% floor on the relative L2 error), and
//!    later, once the fit is better than that, below a tenth of the fit's own squared error.
//! 2. Lobes: a lobe narrower than the cells around it is not constant over them, and the fit
//!    could make it fit a coarse cell's mean with a spike the full map would not forgive. Cells
//!    wider than λ_j within 3λ_j of a light j split until they are not (or are single pixels).
//!
//! Then the fit's error is close to the full map's while most of the sphere stays coarse.

use super::cells::{ByHidden, Cell, target_of};
use super::target::Target;
use crate::EnvMap;
use glam::DVec3;
use rayon::prelude::*;
use std::collections::BinaryHeap;

/// Hidden error left, as a fraction of Σ Δω ‖L‖², below which detail refinement stops.
const HIDDEN_FLOOR: f64 = 1e-4;
/// Once the fit is good, the target is refined until the detail it hides is below this share of
/// the fit's squared error, so the error on the target stays close to the full map's.
pub const DETAIL_SHARE: f64 = 0.1;
/// A cell counts as near a lobe within this many bandwidths (plus its own extent).
const LOBE_REACH: f64 = 3.0;

pub struct AdaptiveTarget<'a> {
    map: &'a EnvMap,
    cells: Vec<Cell>,
    target: Target,
    /// Samples that detail refinement may still add.
    detail_budget: usize,
    /// Samples that lobe refinement may still add.
    lobe_budget: usize,
}

impl<'a> AdaptiveTarget<'a> {
    /// The coarse grid refined for detail with up to `extra` more samples (all refinements for
    /// detail together); lobe refinement may add as many again.
    pub fn new(map: &'a EnvMap, width: usize, height: usize, extra: usize) -> Self {
        let coarse: Vec<Cell> = (0..width * height)
            .into_par_iter()
            .map(|i| {
                let (j, k) = (i % width, i / width);
                let (c0, c1) = (j * map.width() / width, (j + 1) * map.width() / width);
                let (r0, r1) = (k * map.height() / height, (k + 1) * map.height() / height);
                Cell::new(map, c0, c1, r0, r1)
            })
            .collect();
        let norm2: f64 = coarse
            .iter()
            .map(|c| c.hidden + c.weight * c.mean.length_squared())
            .sum();
        let target = target_of(&coarse);
        let mut adaptive = Self {
            map,
            cells: coarse,
            target,
            detail_budget: extra,
            lobe_budget: extra,
        };
        adaptive.refine_detail(HIDDEN_FLOOR * norm2);
        adaptive
    }

    /// Splits the cells with the largest hidden error first until the hidden error left is below
    /// `floor` (in the units of Σ Δω ‖L‖²) or the detail budget is spent; true if any split.
    pub fn refine_detail(&mut self, floor: f64) -> bool {
        let mut hidden: f64 = self.cells.iter().map(|c| c.hidden).sum();
        if hidden <= floor || self.detail_budget == 0 {
            return false;
        }
        let mut heap: BinaryHeap<ByHidden> = self.cells.drain(..).map(ByHidden).collect();
        let mut changed = false;
        while let Some(&ByHidden(top)) = heap.peek() {
            let children = top.split(self.map);
            if hidden <= floor || children.len() < 2 || children.len() - 1 > self.detail_budget {
                break;
            }
            heap.pop();
            self.detail_budget -= children.len() - 1;
            hidden -= top.hidden;
            for child in children {
                hidden += child.hidden;
                heap.push(ByHidden(child));
            }
            changed = true;
        }
        self.cells = heap.into_iter().map(|c| c.0).collect();
        if changed {
            self.target = target_of(&self.cells);
        }
        changed
    }

    pub fn target(&self) -> &Target {
        &self.target
    }

    /// Splits cells too coarse for the lobes (centre, bandwidth) near them; true if any split.
    pub fn resolve_lobes(&mut self, lobes: &[(DVec3, f64)]) -> bool {
        let mut changed = false;
        loop {
            let coarse = |c: &Cell| too_coarse(c, lobes);
            let splits: Vec<usize> = (0..self.cells.len())
                .filter(|&i| self.cells[i].pixels() > 1 && coarse(&self.cells[i]))
                .collect();
            let added = 3 * splits.len();
            if splits.is_empty() || added > self.lobe_budget {
                break;
            }
            self.lobe_budget -= added;
            let mut next = Vec::with_capacity(self.cells.len() + added);
            let mut is_split = vec![false; self.cells.len()];
            splits.iter().for_each(|&i| is_split[i] = true);
            for (cell, split) in self.cells.iter().zip(is_split) {
                if split {
                    next.extend(cell.split(self.map));
                } else {
                    next.push(*cell);
                }
            }
            self.cells = next;
            changed = true;
        }
        if changed {
            self.target = target_of(&self.cells);
        }
        changed
    }
}

/// Whether some lobe (μ, λ) narrower than the cell lies within `LOBE_REACH` λ + extent of it.
fn too_coarse(cell: &Cell, lobes: &[(DVec3, f64)]) -> bool {
    lobes.iter().any(|&(dir, bandwidth)| {
        let reach = (LOBE_REACH * bandwidth + cell.extent).min(std::f64::consts::PI);
        cell.extent > bandwidth && cell.centre.dot(dir) > reach.cos()
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;
    use std::f64::consts::PI;

    fn map_with_a_sun() -> EnvMap {
        let (w, h) = (256, 128);
        let mut pixels = vec![Vec3::new(0.5, 0.6, 0.9); w * h];
        pixels[40 * w + 100] = Vec3::splat(5000.0);
        pixels[40 * w + 101] = Vec3::splat(2000.0);
        EnvMap::new(w, h, pixels)
    }

    fn integral(target: &Target) -> DVec3 {
        target
            .weights
            .iter()
            .zip(&target.values)
            .map(|(w, v)| *v * *w)
            .sum()
    }

    #[test]
    fn without_budget_it_is_the_coarse_grid() {
        let map = map_with_a_sun();
        let adaptive = AdaptiveTarget::new(&map, 32, 16, 0);
        let target = adaptive.target();
        assert_eq!(target.len(), 32 * 16);
        let total: f64 = target.weights.iter().sum();
        assert!((total - 4.0 * PI).abs() < 1e-9);
        let diff = (integral(target) - map.integral()).abs().max_element();
        assert!(diff < 1e-6 * map.integral().max_element());
    }

    #[test]
    fn the_sun_is_resolved_to_single_pixels() {
        let map = map_with_a_sun();
        let adaptive = AdaptiveTarget::new(&map, 32, 16, 64);
        let target = adaptive.target();
        assert!(target.len() > 32 * 16 && target.len() <= 32 * 16 + 64);
        let sun = map.direction(100, 40);
        let nearest = (0..target.len())
            .max_by(|&a, &b| target.dirs[a].dot(sun).total_cmp(&target.dirs[b].dot(sun)))
            .unwrap();
        assert!(target.dirs[nearest].dot(sun) > 1.0 - 1e-12);
        assert!((target.values[nearest].x - 5000.0).abs() < 1e-3);
        assert!((target.weights[nearest] - map.solid_angle(40)).abs() < 1e-15);
        assert_eq!(target.blur[nearest], 0.0);
        let total: f64 = target.weights.iter().sum();
        assert!((total - 4.0 * PI).abs() < 1e-9);
    }

    #[test]
    fn cells_near_a_narrow_lobe_become_pixels() {
        let map = EnvMap::new(256, 128, vec![Vec3::ONE; 256 * 128]);
        let mut adaptive = AdaptiveTarget::new(&map, 32, 16, 4096);
        assert_eq!(adaptive.target().len(), 32 * 16, "a flat map hides nothing");
        let lobe = (map.direction(77, 50), 0.01);
        assert!(adaptive.resolve_lobes(&[lobe]));
        let target = adaptive.target();
        for p in 0..target.len() {
            if target.dirs[p].dot(lobe.0) > (3.0 * lobe.1).cos() {
                assert_eq!(
                    target.blur[p], 0.0,
                    "sample {p} near the lobe is not a pixel"
                );
            }
        }
        assert!(target.len() < 32 * 16 + 400);
        let diff = (integral(target) - map.integral()).abs().max_element();
        assert!(diff < 1e-6 * map.integral().max_element());
        assert!(
            !adaptive.resolve_lobes(&[lobe]),
            "a second call has nothing left to do"
        );
    }
}
