//! The tabulated fast path: N_TT and N_TRT built once per parameter set over (|θ_d|, |φ|)
//! and read back by bilinear interpolation, instead of solving the cubics for their roots and
//! weighing TRT's glints at every evaluation (N_R has a closed form, [`super::n_r`]).
//!
//! For a circular fiber every N_p is a function of θ_d and φ alone (the module documentation
//! of [`super`]), even in both: θ_d enters through sin²θ_d (η′, η″, cos θ_t) and N_p(−φ) =
//! N_p(φ) (A is even in h, Φ̂ odd about pπ). So θ_d is tabulated on [0, [`THETA_D_MAX`]]
//! and φ on [0, π]. The features to follow are TRT's glints, of width w_c, and the kink
//! where TT's edge ray ends it: the φ spacing is a sixth of w_c (256 to 4096 columns), and a
//! fiber whose glints are narrower than the cap follows has no table ([`NpTable::fits`]).
//! Past θ_d = atan η the parallel index η″ drops below 1 and its total reflection at
//! sin γ = η″ draws a square-root edge across (θ_d, φ), which the grid rounds off locally. An
//! elliptical fiber's N_TRT depends on φ_h too (η*, Xu et al. 2011 eq. 24): the model then
//! takes TRT off the table and keeps TT on it. The error against the exact N_p is measured in
//! the tests below.

use super::azimuthal::{Interface, azimuthal, azimuthal_trt};
use super::params::MarschnerParams;
use crate::math::grid::{bilinear, fill_rows, locate};
use glam::DVec3;
use std::f64::consts::PI;

/// Nodes along |θ_d| ∈ [0, THETA_D_MAX].
const THETA_D_NODES: usize = 128;
const MIN_PHI_NODES: usize = 256;
const MAX_PHI_NODES: usize = 4096;
/// φ nodes per glint width w_c: the spacing is w_c / 6.
const NODES_PER_GLINT_WIDTH: f64 = 6.0;
/// The table's reach in |θ_d|, nodes uniform over [0, THETA_D_MAX]. Beyond it (θ_o and θ_i
/// both within 0.22 rad of opposite poles) η′ grows as 1 / cos θ_d and N_p changes faster
/// than a fixed grid follows: the model is exact there.
pub const THETA_D_MAX: f64 = 1.35;

/// N_p on the (|θ_d|, |φ|) grid; see the module documentation.
#[derive(Clone, Debug)]
pub struct NpTable {
    phi_nodes: usize,
    /// [θ_d][φ] → N_TT, N_TRT, each RGB.
    texels: Vec<[f32; 6]>,
}

impl NpTable {
    /// Whether the table resolves this fiber's glints: w_c / 6 no finer than the cap's spacing.
    pub fn fits(params: &MarschnerParams) -> bool {
        phi_nodes_for(params.caustic_width) <= MAX_PHI_NODES
    }

    /// Fills the table with the exact N_p, a row of θ_d per task on every available core.
    pub fn build(params: &MarschnerParams) -> Self {
        let phi_nodes = phi_nodes_for(params.caustic_width).clamp(MIN_PHI_NODES, MAX_PHI_NODES);
        let mut texels = vec![[0.0f32; 6]; THETA_D_NODES * phi_nodes];
        fill_rows(&mut texels, phi_nodes, |d, row| fill_row(params, d, row));
        Self { phi_nodes, texels }
    }

    /// N_TT and N_TRT at (θ_d, φ), φ ∈ [−π, π]; `None` beyond the table's reach in |θ_d|
    /// (`THETA_D_MAX`).
    #[inline]
    pub fn lookup(&self, theta_d: f64, phi: f64) -> Option<[DVec3; 2]> {
        let x = theta_d.abs() / THETA_D_MAX;
        if x.is_nan() || x > 1.0 {
            return None;
        }
        let (d0, fd) = locate(x, THETA_D_NODES);
        let (f0, ff) = locate(phi.abs() / PI, self.phi_nodes);
        let n = bilinear(
            &self.texels,
            d0 * self.phi_nodes + f0,
            self.phi_nodes,
            fd,
            ff,
        );
        Some(std::array::from_fn(|p| {
            DVec3::new(n[3 * p] as f64, n[3 * p + 1] as f64, n[3 * p + 2] as f64)
        }))
    }

    /// The number of φ columns.
    pub fn phi_nodes(&self) -> usize {
        self.phi_nodes
    }
}

fn phi_nodes_for(caustic_width: f64) -> usize {
    (PI * NODES_PER_GLINT_WIDTH / caustic_width).ceil() as usize + 1
}

/// The exact N_p along one row of θ_d, the circle's interface (η* = η).
fn fill_row(params: &MarschnerParams, d: usize, row: &mut [[f32; 6]]) {
    let theta_d = THETA_D_MAX * d as f64 / (THETA_D_NODES - 1) as f64;
    let interface = Interface::new(params.eta, theta_d, params.mu_a);
    let phi_nodes = row.len();
    for (k, texel) in row.iter_mut().enumerate() {
        let phi = PI * k as f64 / (phi_nodes - 1) as f64;
        let n = [
            azimuthal(1, &interface, phi),
            azimuthal_trt(&interface, params, phi),
        ];
        for (p, v) in n.iter().enumerate() {
            texel[3 * p..3 * p + 3].copy_from_slice(&v.as_vec3().to_array());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The table against the exact N_p per lobe (channel sums) on a grid offset from the
    /// nodes in both axes: relative L1 over the table's reach, and the largest error relative
    /// to the lobe's peak where η″ ≥ 1 (|θ_d| ≤ atan η) and where η″ < 1.
    struct TableError {
        l1: f64,
        worst: f64,
        worst_grazing: f64,
    }

    fn table_error(params: &MarschnerParams) -> [TableError; 2] {
        let table = NpTable::build(params);
        let (mut diff, mut total, mut peak) = ([0.0; 2], [0.0; 2], [0.0f64; 2]);
        let (mut worst, mut worst_grazing) = ([0.0f64; 2], [0.0f64; 2]);
        for i in 0..301 {
            let theta_d = THETA_D_MAX * (i as f64 + 0.37) / 301.0;
            let interface = Interface::new(params.eta, theta_d, params.mu_a);
            for k in 0..997 {
                let phi = PI * (k as f64 + 0.61) / 997.0 - if k % 2 == 0 { 0.0 } else { PI };
                let exact = [
                    azimuthal(1, &interface, phi),
                    azimuthal_trt(&interface, params, phi),
                ];
                let got = table.lookup(theta_d, phi).unwrap();
                for p in 0..2 {
                    let e = (got[p] - exact[p]).abs().element_sum();
                    diff[p] += e;
                    total[p] += exact[p].element_sum();
                    peak[p] = peak[p].max(exact[p].element_sum());
                    if theta_d <= params.eta.atan() {
                        worst[p] = worst[p].max(e);
                    } else {
                        worst_grazing[p] = worst_grazing[p].max(e);
                    }
                }
            }
        }
        std::array::from_fn(|p| TableError {
            l1: diff[p] / total[p],
            worst: worst[p] / peak[p],
            worst_grazing: worst_grazing[p] / peak[p],
        })
    }

    /// Bounds of N_TT and N_TRT from the table (above the measured worst of the three fibers:
    /// relative L1 0.05 % and 0.13 %; largest error 0.6 % and 1.7 % of the peak where η″ ≥ 1,
    /// 9 % and 11 % in the grazing band where η″ < 1, where the parallel polarisation's total
    /// reflection at sin γ = η″ is a square-root edge that bilinear interpolation rounds off).
    #[test]
    fn table_follows_the_exact_azimuthal_functions() {
        let cases = [
            MarschnerParams::default(),
            MarschnerParams {
                mu_a: DVec3::ZERO,
                eta: 1.3,
                caustic_width: 10f64.to_radians(),
                glint_scale: 3.0,
                ..Default::default()
            },
            MarschnerParams {
                mu_a: DVec3::new(0.5, 2.0, 8.0),
                eta: 1.8,
                caustic_width: 25f64.to_radians(),
                ..Default::default()
            },
        ];
        for params in cases {
            let [tt, trt] = table_error(&params);
            eprintln!(
                "η {} w_c {:.3}: relative L1 TT {:.5} TRT {:.5}, worst / peak TT {:.4} TRT {:.4}, grazing TT {:.3} TRT {:.3}",
                params.eta,
                params.caustic_width,
                tt.l1,
                trt.l1,
                tt.worst,
                trt.worst,
                tt.worst_grazing,
                trt.worst_grazing
            );
            assert!(tt.l1 < 1e-3 && trt.l1 < 2e-3);
            assert!(tt.worst < 0.01 && trt.worst < 0.025);
            assert!(tt.worst_grazing < 0.12 && trt.worst_grazing < 0.15);
        }
    }

    #[test]
    fn beyond_its_reach_the_table_declines() {
        let table = NpTable::build(&MarschnerParams::default());
        assert!(table.lookup(THETA_D_MAX, 0.3).is_some());
        assert!(table.lookup(-THETA_D_MAX, -3.0).is_some());
        assert!(table.lookup(THETA_D_MAX + 1e-9, 0.3).is_none());
        assert!(table.lookup(f64::NAN, 0.3).is_none());
    }

    #[test]
    fn glints_narrower_than_the_cap_follows_have_no_table() {
        let narrow = |deg: f64| MarschnerParams {
            caustic_width: deg.to_radians(),
            ..Default::default()
        };
        assert!(NpTable::fits(&narrow(10.0)));
        assert!(NpTable::fits(&narrow(0.3)));
        assert!(!NpTable::fits(&narrow(0.1)));
        assert_eq!(NpTable::build(&narrow(17.5)).phi_nodes(), MIN_PHI_NODES);
    }
}
