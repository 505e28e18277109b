//! A model's lobe images on a lat-long grid (docs/conventions.md §4), each pixel the mean of S over the
//! pixel's solid angle, ∫∫ S cos θ dθ dφ / Ω, so that they compare with the simulator's
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

use cuticle_fiber::math::GaussLegendre;
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

/// The five lobe images (R, TT, TRT, TRRT, rest) of `model` for light at `theta_i` (φ_i = 0),
/// each pixel the mean of S over it; rows in parallel.
pub fn integrate_lobes(
    model: &dyn FiberModel,
    theta_i: f64,
    grid: LatLongGrid,
    rule: &PixelRule,
) -> [LatLongImage; 5] {
    let wi = FiberAngles::new(theta_i, 0.0);
    let phi_rule = rule.phi_nodes();
    let half_dphi = 0.5 * grid.d_phi();
    let rows: Vec<Vec<[DVec3; 5]>> = (0..grid.height)
        .into_par_iter()
        .map(|k| {
            let thetas = rule.row_nodes(&grid, k, theta_i);
            (0..grid.width)
                .map(|j| {
                    let mut acc = [DVec3::ZERO; 5];
                    for (x, wp) in phi_rule.nodes.iter().zip(&phi_rule.weights) {
                        let phi = grid.phi_center(j) + half_dphi * x;
                        for &(theta, wt) in &thetas {
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
