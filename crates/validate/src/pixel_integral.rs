//! A model's lobe images on a lat-long grid (docs/conventions.md §4), each pixel the mean of S over
//! the pixel's solid angle, ∫∫ S cos θ dθ dφ / Ω, so that they compare with the simulator's
//! histograms bin for bin. At β = 0.02 the TT lobe's width β(η − 1) ≈ 0.011 rad is a third of a
//! row (π/100), so S at the pixel centre misses or overstates it; a small product
//! Gauss–Legendre rule per pixel does not.
//!
//! The rule: in φ, `phi_nodes` points per column everywhere (columns are π/200 wide, and the
//! azimuthal terms vary slowly on that scale); in θ, `near_nodes` points for the rows within
//! [`PixelRule::band`] of the specular cone θ_o = −θ_i (where every lobe's cone lies, shifted
//! by at most (6η − 2)|α| for TRRT, d'Eon et al. 2014 §2.2), and `far_nodes` elsewhere, where S is
//! smooth. The defaults (8, 3, 3) conserve each lobe's energy, as `furnace::albedo` integrates
//! it independently (the bound is test `pixel_integral_conserves_energy`'s).

use cuticle_fiber::furnace::{self, FurnaceRule};
use cuticle_fiber::math::GaussLegendre;
use cuticle_fiber::ranges::{CountRange, RangeError};
use cuticle_fiber::{FiberAngles, FiberModel, LatLongGrid, LatLongImage};
use glam::DVec3;
use rayon::prelude::*;

/// The per-pixel quadrature.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PixelRule {
    /// Gauss–Legendre points in θ per row near the cones.
    pub near_nodes: usize,
    /// Points in θ per row away from them.
    pub far_nodes: usize,
    /// Points in φ per column.
    pub phi_nodes: usize,
    /// Half-width (radians) of the band around θ_o = −θ_i whose rows get `near_nodes`.
    pub band: f64,
}

impl PixelRule {
    /// The default rule for a fiber of index `eta`, tilt `alpha` (radians), roughness `beta`:
    /// the band holds every cone shift with 0.25 rad and four of the widest narrow lobe's
    /// widths to spare.
    pub fn for_fiber(eta: f64, alpha: f64, beta: f64) -> Self {
        Self {
            near_nodes: 8,
            far_nodes: 3,
            phi_nodes: 3,
            band: (6.0 * eta - 2.0) * alpha.abs() + 0.25 + 4.0 * beta,
        }
    }

    /// S at the pixel centre only: what this module exists to avoid (for comparison in tests).
    pub fn centre() -> Self {
        Self {
            near_nodes: 1,
            far_nodes: 1,
            phi_nodes: 1,
            band: 0.0,
        }
    }

    /// θ nodes of row `k`, weights including cos θ, both half-widths of the pixel (θ and φ,
    /// for the rules on [−1, 1]) and the division by the pixel's solid angle.
    fn row_nodes(&self, grid: &LatLongGrid, k: usize, theta_i: f64) -> Vec<(f64, f64)> {
        let (top, bottom) = (grid.theta_top(k), grid.theta_top(k + 1));
        let nearest = (-theta_i).clamp(bottom, top);
        let distance = (nearest + theta_i).abs();
        let n = if distance <= self.band {
            self.near_nodes
        } else {
            self.far_nodes
        };
        let gl = GaussLegendre::cached(n);
        let (mid, half) = (0.5 * (top + bottom), 0.5 * (top - bottom));
        let scale = half * 0.5 * grid.d_phi() / grid.pixel_solid_angle(k);
        gl.nodes
            .iter()
            .zip(&gl.weights)
            .map(|(x, w)| {
                let theta = mid + half * x;
                (theta, w * theta.cos() * scale)
            })
            .collect()
    }

    /// φ nodes (offsets from a column's centre, in units of Δφ/2) and weights.
    fn phi_nodes(&self) -> &'static GaussLegendre {
        GaussLegendre::cached(self.phi_nodes)
    }
}

/// Width of the lobe images of [`lobe_grid`] (their height is a quarter of it): at most
/// 4000 × 1000, 0.5 GB for the five lobes and their sum.
pub const LOBE_WIDTH: CountRange = CountRange {
    name: "width",
    min: 8,
    max: 4000,
};

/// A width that is not one of [`lobe_grid`]'s.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum LobeGridError {
    #[error(transparent)]
    Range(#[from] RangeError),
    #[error("width must be a multiple of 4, got {0}")]
    NotMultipleOfFour(usize),
}

/// The grid of `cuticle lobes`' images (and the bindings' `Fiber.latlong`): `width` in
/// [`LOBE_WIDTH`], a multiple of 4, and a quarter as high.
pub fn lobe_grid(width: usize) -> Result<LatLongGrid, LobeGridError> {
    LOBE_WIDTH.check_usize(width)?;
    if !width.is_multiple_of(4) {
        return Err(LobeGridError::NotMultipleOfFour(width));
    }
    Ok(LatLongGrid::new(width, width / 4))
}

/// Points in φ per column of [`lobe_images`]: columns are π/200 wide at the default width, and
/// S varies slowly in φ on that scale.
const LOBE_PHI_NODES: usize = 3;

/// `cuticle lobes`' images (and the bindings' `Fiber.latlong`): each lobe's pixel means for
/// light at `theta_i`, on `rule`'s θ panels at the resolution the furnace reports
/// ([`integrate_lobes_on_breaks`]), so that their energy is the furnace's.
pub fn lobe_images(
    model: &dyn FiberModel,
    theta_i: f64,
    grid: LatLongGrid,
    rule: FurnaceRule,
) -> [LatLongImage; 5] {
    let breaks = furnace::theta_breaks(theta_i, rule, 2 * rule.resolution.max(1));
    integrate_lobes_on_breaks(
        model,
        theta_i,
        grid,
        &breaks,
        furnace::NODES_PER_PANEL,
        LOBE_PHI_NODES,
    )
}

/// The sum of the lobe images (`total.exr`).
pub fn total(lobes: &[LatLongImage; 5]) -> LatLongImage {
    let mut sum = LatLongImage::zeros(lobes[0].grid);
    lobes.iter().for_each(|image| sum.add(image));
    sum
}

/// The five lobe images of `model` for light at `theta_i`, each pixel the mean of S over it, in
/// θ on the panels `breaks` (edges in θ_o, finest near the cones: the furnace's,
/// `cuticle_fiber::furnace::theta_breaks`) cut at each row's edges, `nodes` Gauss–Legendre
/// points per whole panel (a piece of a panel gets its share, at least two: rows far thinner
/// than the panels there, at large widths, do not each take `nodes`), and `phi_nodes` points
/// per column. On the furnace's own panels the images'
/// energy is the furnace's albedo at any β, however much narrower than a row a lobe is (issue 57
/// #15: `cuticle lobes` sampled pixel centres, and its images held 4.6× the TT energy at
/// β = 0.003).
pub fn integrate_lobes_on_breaks(
    model: &dyn FiberModel,
    theta_i: f64,
    grid: LatLongGrid,
    breaks: &[f64],
    nodes: usize,
    phi_nodes: usize,
) -> [LatLongImage; 5] {
    let phi_rule = GaussLegendre::cached(phi_nodes);
    let rows: Vec<Vec<(f64, f64)>> = (0..grid.height)
        .map(|k| {
            let (top, bottom) = (grid.theta_top(k), grid.theta_top(k + 1));
            let mut edges = vec![bottom, top];
            edges.extend(breaks.iter().copied().filter(|b| *b > bottom && *b < top));
            edges.sort_by(f64::total_cmp);
            let scale = 0.5 * grid.d_phi() / grid.pixel_solid_angle(k);
            edges
                .windows(2)
                .flat_map(|piece| {
                    let share = (piece[1] - piece[0]) / panel_width(breaks, piece[0], piece[1]);
                    let n = ((nodes as f64 * share).ceil() as usize).clamp(2, nodes.max(2));
                    GaussLegendre::cached(n).panel_nodes(piece)
                })
                .map(|(theta, w)| (theta, w * theta.cos() * scale))
                .collect()
        })
        .collect();
    integrate_rows(model, theta_i, grid, &rows, phi_rule)
}

/// The width of the panel of `breaks` (sorted) that holds the piece [a, b]; the piece's own
/// width outside them.
fn panel_width(breaks: &[f64], a: f64, b: f64) -> f64 {
    let mid = 0.5 * (a + b);
    let upper = breaks.partition_point(|&x| x <= mid);
    match (upper.checked_sub(1).map(|i| breaks[i]), breaks.get(upper)) {
        (Some(lo), Some(&hi)) => hi - lo,
        _ => b - a,
    }
}

/// Each pixel's Σ over its row's θ nodes (weights already divided by the pixel's solid angle
/// and holding the φ half-width) and `phi_rule`'s nodes across its column; rows in parallel.
fn integrate_rows(
    model: &dyn FiberModel,
    theta_i: f64,
    grid: LatLongGrid,
    row_nodes: &[Vec<(f64, f64)>],
    phi_rule: &GaussLegendre,
) -> [LatLongImage; 5] {
    let wi = FiberAngles::new(theta_i, 0.0);
    let half_dphi = 0.5 * grid.d_phi();
    let rows: Vec<Vec<[DVec3; 5]>> = row_nodes
        .par_iter()
        .map(|thetas| {
            (0..grid.width)
                .map(|j| {
                    let mut acc = [DVec3::ZERO; 5];
                    for (x, wp) in phi_rule.nodes.iter().zip(&phi_rule.weights) {
                        let phi = grid.phi_center(j) + half_dphi * x;
                        for &(theta, wt) in thetas {
                            let s = model.eval(wi, FiberAngles::new(theta, phi));
                            for (a, v) in acc.iter_mut().zip(s.0) {
                                *a += wt * wp * v;
                            }
                        }
                    }
                    acc
                })
                .collect()
        })
        .collect();
    cuticle_fiber::geometry::latlong::lobe_images(grid, &rows)
}

/// The five lobe images (R, TT, TRT, TRRT, rest) of `model` for light at `theta_i` (φ_i = 0),
/// each pixel the mean of S over it; rows in parallel.
pub fn integrate_lobes(
    model: &dyn FiberModel,
    theta_i: f64,
    grid: LatLongGrid,
    rule: &PixelRule,
) -> [LatLongImage; 5] {
    let rows: Vec<Vec<(f64, f64)>> = (0..grid.height)
        .map(|k| rule.row_nodes(&grid, k, theta_i))
        .collect();
    integrate_rows(model, theta_i, grid, &rows, rule.phi_nodes())
}
