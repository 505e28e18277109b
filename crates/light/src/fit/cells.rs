//! Cells of an adaptive target: rectangles of whole pixels of the map, each with its solid angle,
//! mean radiance and hidden error, split quadtree-fashion.

use super::target::Target;
use crate::EnvMap;
use crate::latlong::direction_from_angles;
use glam::DVec3;
use std::cmp::Ordering;
use std::f64::consts::PI;

/// Pixels `c0..c1 × r0..r1` of a map with their statistics.
#[derive(Clone, Copy, Debug)]
pub struct Cell {
    pub c0: usize,
    pub c1: usize,
    pub r0: usize,
    pub r1: usize,
    /// Σ Δω_p over the cell.
    pub weight: f64,
    /// Solid-angle-weighted mean radiance L̄.
    pub mean: DVec3,
    /// Σ Δω_p ‖L_p − L̄‖²: the error a model constant over the cell hides from the fit.
    pub hidden: f64,
    /// World direction of the centre (map rotation applied).
    pub centre: DVec3,
    /// Largest angular extent: the height Δθ or the width Δφ cos θ at the widest row.
    pub extent: f64,
}

impl Cell {
    /// The statistics of the pixels `c0..c1 × r0..r1` of `map`.
    pub fn new(map: &EnvMap, c0: usize, c1: usize, r0: usize, r1: usize) -> Self {
        let (mut weight, mut sum) = (0.0, DVec3::ZERO);
        for row in r0..r1 {
            let w = map.solid_angle(row);
            for column in c0..c1 {
                weight += w;
                sum += map.pixel(column, row).as_dvec3() * w;
            }
        }
        let mean = sum / weight;
        let mut hidden = 0.0;
        for row in r0..r1 {
            let w = map.solid_angle(row);
            for column in c0..c1 {
                hidden += w * (map.pixel(column, row).as_dvec3() - mean).length_squared();
            }
        }
        Self {
            c0,
            c1,
            r0,
            r1,
            weight,
            mean,
            hidden,
            centre: centre(map, c0, c1, r0, r1),
            extent: extent(map, c0, c1, r0, r1),
        }
    }

    pub fn pixels(&self) -> usize {
        (self.c1 - self.c0) * (self.r1 - self.r0)
    }

    /// The cell halved along each side longer than one pixel (two or four children; none for a
    /// single pixel).
    pub fn split(&self, map: &EnvMap) -> Vec<Cell> {
        if self.pixels() == 1 {
            return Vec::new();
        }
        let halves = |a: usize, b: usize| {
            if b - a > 1 {
                vec![(a, (a + b) / 2), ((a + b) / 2, b)]
            } else {
                vec![(a, b)]
            }
        };
        let mut children = Vec::with_capacity(4);
        for &(r0, r1) in &halves(self.r0, self.r1) {
            for &(c0, c1) in &halves(self.c0, self.c1) {
                children.push(Cell::new(map, c0, c1, r0, r1));
            }
        }
        children
    }

    /// The blur of a cell of n pixels and solid angle A: its mean is compared with the model's
    /// mean over its n pixel centres, modelled as a box filter of area A(1 − 1/n), whose variance
    /// per axis is that area / 12. A single pixel is a point sample, as in the full-map error.
    pub fn blur(&self) -> f64 {
        self.weight * (1.0 - 1.0 / self.pixels() as f64) / 12.0
    }

    /// Z-order key of the cell's corner: cells sorted by it lie in spatially compact runs, which
    /// lets the fit's batched accumulations skip lights that a whole batch does not see.
    pub fn morton(&self) -> u64 {
        let spread = |v: usize| {
            let mut v = v as u64 & 0xffff_ffff;
            v = (v | (v << 16)) & 0x0000_ffff_0000_ffff;
            v = (v | (v << 8)) & 0x00ff_00ff_00ff_00ff;
            v = (v | (v << 4)) & 0x0f0f_0f0f_0f0f_0f0f;
            v = (v | (v << 2)) & 0x3333_3333_3333_3333;
            (v | (v << 1)) & 0x5555_5555_5555_5555
        };
        spread(self.c0) | (spread(self.r0) << 1)
    }
}

/// World direction of the centre of pixels `c0..c1 × r0..r1` (map rotation applied).
fn centre(map: &EnvMap, c0: usize, c1: usize, r0: usize, r1: usize) -> DVec3 {
    let (w, h) = (map.width() as f64, map.height() as f64);
    let theta = PI / 2.0 - PI * (r0 + r1) as f64 / (2.0 * h);
    let phi = -PI + 2.0 * PI * (c0 + c1) as f64 / (2.0 * w) + map.rotation();
    direction_from_angles(theta, phi)
}

/// Largest angular extent of pixels `c0..c1 × r0..r1`: Δθ, or Δφ cos θ at the widest row.
fn extent(map: &EnvMap, c0: usize, c1: usize, r0: usize, r1: usize) -> f64 {
    let (w, h) = (map.width() as f64, map.height() as f64);
    let d_theta = PI * (r1 - r0) as f64 / h;
    let crosses_equator = r0 as f64 <= h / 2.0 && r1 as f64 >= h / 2.0;
    let widest = if crosses_equator {
        1.0
    } else {
        [r0, r1]
            .iter()
            .map(|&r| (PI / 2.0 - PI * r as f64 / h).cos())
            .fold(0.0, f64::max)
    };
    d_theta.max(2.0 * PI * (c1 - c0) as f64 / w * widest)
}

/// Max-heap order by hidden error.
#[derive(Clone, Copy, Debug)]
pub struct ByHidden(pub Cell);

impl PartialEq for ByHidden {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}
impl Eq for ByHidden {}
impl PartialOrd for ByHidden {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for ByHidden {
    fn cmp(&self, other: &Self) -> Ordering {
        self.0.hidden.total_cmp(&other.0.hidden)
    }
}

/// One sample per cell, in Z order: centre direction, solid angle, mean and blur.
pub fn target_of(cells: &[Cell]) -> Target {
    let mut sorted = cells.to_vec();
    sorted.sort_by_key(Cell::morton);
    Target::new(
        sorted.iter().map(|c| c.centre).collect(),
        sorted.iter().map(|c| c.weight).collect(),
        sorted.iter().map(|c| c.mean).collect(),
        sorted.iter().map(Cell::blur).collect(),
    )
}
