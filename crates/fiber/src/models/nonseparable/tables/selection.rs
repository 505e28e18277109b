//! The tilted model's lobe selection over (θ_i, h), tabulated for the fast path.
//!
//! Importance sampling draws the offset h uniformly and then a lobe with probability
//! proportional to the channel mean of A(p, h) (d'Eon et al. 2013); the pdf weighs R's
//! offsets by the same probability. In the tilted model A(p, h) is a trace of every lobe's
//! rotations and rough Fresnel factors ([`crate::models::nonseparable::scales::attenuation`]), at α
//! = 0 too, the dearest part of a sample or a pdf. The probabilities are a proposal: any that
//! `sample` draws with and `pdf` reports alike serve. So the fast path reads them from this table,
//! bilinear in (θ_i, h) and normalised to sum 1, in both. Where the tilted scales lose everything
//! at all four corners of a cell the table gives 0 and the sampler draws nothing, as the exact
//! model does at such an offset. The azimuthal table's TT, TRT, TRRT and remainder densities are
//! built from these probabilities too
//! ([`crate::models::deon2011::table::AzimuthalTable::build_with_selection`]), so every lobe's
//! density is the one the sampler realises, to the azimuthal table's own interpolation in φ.

use crate::math::grid::{bilinear, fill_rows, locate};
use crate::models::deon2011::azimuthal::AzimuthalScattering;
use std::f64::consts::FRAC_PI_2;

/// Nodes over θ_i ∈ [−π/2, π/2] and over h ∈ [−1, 1].
const THETA_I_NODES: usize = 129;
const H_NODES: usize = 257;
/// The end nodes of θ_i are evaluated this far inside ±π/2, where the incident ray grazes.
const GRAZING: f64 = 1e-4;

/// Selection probabilities of R, TT, TRT, TRRT and the remainder on the (θ_i, h) grid.
#[derive(Clone, Debug)]
pub struct SelectionTable {
    /// [θ_i][h] → the five probabilities.
    values: Vec<[f32; 5]>,
}

impl SelectionTable {
    /// Fills the table with the exact probabilities of `az`, a row of θ_i per task.
    pub fn build(az: &AzimuthalScattering) -> Self {
        let mut values = vec![[0.0f32; 5]; THETA_I_NODES * H_NODES];
        fill_rows(&mut values, H_NODES, |i, row| {
            let theta_i = (-FRAC_PI_2 + 2.0 * FRAC_PI_2 * i as f64 / (THETA_I_NODES - 1) as f64)
                .clamp(-FRAC_PI_2 + GRAZING, FRAC_PI_2 - GRAZING);
            for (k, cell) in row.iter_mut().enumerate() {
                let h = -1.0 + 2.0 * k as f64 / (H_NODES - 1) as f64;
                *cell = az.selection(theta_i, h).map(|x| x as f32);
            }
        });
        Self { values }
    }

    /// The probabilities at (θ_i, h), bilinear between the nodes and normalised to sum 1;
    /// all 0 where every corner of the cell is.
    #[inline]
    pub fn at(&self, theta_i: f64, h: f64) -> [f64; 5] {
        let (i0, fi) = locate((theta_i + FRAC_PI_2) / (2.0 * FRAC_PI_2), THETA_I_NODES);
        let (k0, fk) = locate(0.5 * (h + 1.0), H_NODES);
        let p = bilinear(&self.values, i0 * H_NODES + k0, H_NODES, fi, fk);
        let p = p.map(|x| x as f64);
        let sum: f64 = p.iter().sum();
        if sum > 0.0 {
            p.map(|x| x / sum)
        } else {
            [0.0; 5]
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::models::nonseparable::cuticle::WithScales;
    use glam::DVec3;

    /// Mean absolute error of R's probability against the exact one over a grid offset from
    /// the nodes, and the share of points where the two disagree on whether anything is drawn
    /// (measured 4.9e-3 and 0.3 % at α = −4°, 4.1e-3 and 0.1 % at α = 2°). The sampling tests
    /// of `super` bound what it does to the samples.
    #[test]
    fn table_follows_the_exact_selection() {
        for alpha_deg in [-4.0f64, 2.0] {
            let az = AzimuthalScattering::new(1.55, 0.04, DVec3::new(0.1, 0.3, 0.6))
                .with_scale_tilt(alpha_deg.to_radians());
            let table = SelectionTable::build(&az);
            let (mut err, mut n, mut disagree) = (0.0, 0, 0);
            for i in 0..200 {
                let theta_i = -1.5 + 3.0 * (i as f64 + 0.31) / 200.0;
                for k in 0..400 {
                    let h = -1.0 + 2.0 * (k as f64 + 0.57) / 400.0;
                    let (got, want) = (table.at(theta_i, h), az.selection(theta_i, h));
                    let drawn = |s: [f64; 5]| s.iter().sum::<f64>() > 0.0;
                    if drawn(got) != drawn(want) {
                        disagree += 1;
                    } else if drawn(want) {
                        err += (got[0] - want[0]).abs();
                        n += 1;
                    }
                }
            }
            let (mean, share) = (err / n as f64, disagree as f64 / 80_000.0);
            eprintln!("α {alpha_deg}°: mean |ΔP_R| {mean:.2e}, draw/no-draw disagree {share:.4}");
            assert!(mean < 6e-3 && share < 5e-3, "{mean} {share}");
        }
    }
}
