//! TT's and TRT's longitudinal lobes tabulated for the fast path: TRT's cone and width depend
//! on θ_i alone (d'Eon et al. 2014 §2.5, at h = 0 and θ_d = −θ_i), TT's on θ_i and the offset
//! h that Φ(1, h) = φ selects (§2.4), so on (θ_i, φ). Each evaluation and each fixed-point
//! step of sampling otherwise solves TT's offset and runs the Nusselt rotations again. Both
//! `eval` and `sample` read the same table, so the model they agree on is the interpolated
//! one; its distance from the exact lobes is measured by `lobe_table_follows_the_exact_lobes`.
//!
//! What is tabulated is smooth where the lobes are not: the sine x of the Nusselt exit before
//! any clamp (the cone is asin of x clamped, or the paper's pole where |x| > 1, both of which
//! the caller applies to the interpolated x), and the width: √v times cos θ_d for a von
//! Mises–Fisher lobe (v itself grows as 1 / cos²θ_d at grazing incidence), or the standard
//! deviation of the exit sine for the tilted model's TT lobe, which is Gaussian in that sine
//! ([`crate::lobes::sine_lobe`]).

use crate::lobes::sine_lobe::SkewSplit;
use crate::math::grid::{fill_rows, locate};
use std::f64::consts::{FRAC_PI_2, PI};

/// Nodes over θ_i ∈ [−π/2, π/2] and over |φ| ∈ [0, π]: dense in θ_i, where the Nusselt
/// rotations' clamped square roots put kinks into x.
const THETA_I_NODES: usize = 1025;
const PHI_NODES: usize = 129;

/// A lobe's shape as the table holds it: the exit's sine x and its width (module docs).
pub type Shape = [f64; 2];

/// TT's lobe at one (θ_i, |φ|): its [`Shape`], how the skewness of its exit sine splits it
/// and its reach (the tilted model's; no split and the full reach in the paper's).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TtShape {
    pub shape: Shape,
    pub split: SkewSplit,
    pub reach: f64,
}

/// The [`TtShape`] of TT over (θ_i, |φ|) and the [`Shape`] of TRT over θ_i.
#[derive(Clone, Debug)]
pub struct LobeTable {
    /// Per cell x, width, the split's mixture offset, two-piece asymmetry and two-piece
    /// share ([`SkewSplit::from_channels`]), and the reach.
    tt: Vec<[f64; 6]>,
    trt: Vec<[f64; 2]>,
}

impl LobeTable {
    /// Fills the table from `tt(θ_i, φ)`, TT's lobes (even in φ), and `trt(θ_i)`, rows of θ_i
    /// shared among the available cores.
    pub fn build(
        tt: impl Fn(f64, f64) -> TtShape + Sync,
        trt: impl Fn(f64) -> Shape + Sync,
    ) -> Self {
        let mut rows = vec![[[0.0; 6]; PHI_NODES]; THETA_I_NODES];
        fill_rows(&mut rows, 1, |i, row| {
            let theta_i = theta_i_at(i);
            for (k, cell) in row[0].iter_mut().enumerate() {
                let TtShape {
                    shape: [x, w],
                    split,
                    reach,
                } = tt(theta_i, PI * k as f64 / (PHI_NODES - 1) as f64);
                *cell = [x, w, split.offset, split.asymmetry, split.two_piece, reach];
            }
        });
        let mut trt_cells = vec![[0.0; 2]; THETA_I_NODES];
        fill_rows(&mut trt_cells, 1, |i, cell| cell[0] = trt(theta_i_at(i)));
        Self {
            tt: rows.into_iter().flatten().collect(),
            trt: trt_cells,
        }
    }

    /// TT's lobe at (θ_i, φ), bilinear in every channel.
    #[inline]
    pub fn tt(&self, theta_i: f64, phi: f64) -> TtShape {
        let (i0, fi) = theta_i_cell(theta_i);
        let (k0, fk) = locate(phi.abs() / PI, PHI_NODES);
        let (fi, fk) = (fi as f64, fk as f64);
        let at = i0 * PHI_NODES + k0;
        let next = at + PHI_NODES;
        let lerp = |a: [f64; 6], b: [f64; 6], f: f64| -> [f64; 6] {
            std::array::from_fn(|l| a[l] + f * (b[l] - a[l]))
        };
        let low = lerp(self.tt[at], self.tt[at + 1], fk);
        let high = lerp(self.tt[next], self.tt[next + 1], fk);
        let [x, w, offset, asymmetry, share, reach] = lerp(low, high, fi);
        TtShape {
            shape: [x, w],
            split: SkewSplit::from_channels(offset, asymmetry, share),
            reach,
        }
    }

    /// TRT's shape at θ_i, linear.
    #[inline]
    pub fn trt(&self, theta_i: f64) -> Shape {
        let (i0, fi) = theta_i_cell(theta_i);
        let fi = fi as f64;
        let (a, b) = (self.trt[i0], self.trt[i0 + 1]);
        [a[0] + fi * (b[0] - a[0]), a[1] + fi * (b[1] - a[1])]
    }
}

fn theta_i_at(i: usize) -> f64 {
    crate::math::grid::theta_i_node(i, THETA_I_NODES)
}

#[inline]
fn theta_i_cell(theta_i: f64) -> (usize, f32) {
    locate((theta_i + FRAC_PI_2) / PI, THETA_I_NODES)
}
