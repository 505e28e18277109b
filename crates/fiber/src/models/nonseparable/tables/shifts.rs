//! What tilted scales add to TT's and TRT's deflection Φ(p, h)
//! ([`crate::models::deon2011::azimuthal::AzimuthalScattering::deflection_shift`]), tabulated for
//! the sampler: without it every TT or TRT draw traces its offset's path through the tilted scales
//! (the rotation sequence of [`crate::models::nonseparable::scales::deflection::tilted_exit`]) to
//! find where its φ is centred.
//!
//! The shift depends on (θ_i, h) for a fiber's η and scale tilt, so the table runs over
//! θ_i ∈ [−π/2, π/2] and h ∈ [−1, 1] and blends bilinearly. It is smooth where the path
//! leaves, but 0 by definition where the tilted scales block it, so it jumps at the edges of
//! the blocked offsets, and it bends near total internal reflection. A cell with a corner
//! either side of such an edge, or whose blend misses the exact shift at its centre by more
//! than [`TOLERANCE`], answers nothing, and the sampler traces the path there as before.
//! `shift_table_follows_the_exact_shift` measures the blend between the nodes and centres.
//!
//! The model's evaluation and pdf read the shift through the azimuthal table, which integrated
//! the exact shift over h when it was built; only the sampler's draw reads this one, so an
//! error here moves where samples land, not what they are weighed by.

use crate::math::grid::{fill_rows, locate};
use std::f64::consts::{FRAC_PI_2, PI};

/// Nodes over θ_i ∈ [−π/2, π/2] and over h ∈ [−1, 1].
const THETA_I_NODES: usize = 257;
const H_NODES: usize = 513;

/// The largest miss of a cell's blend at its centre, in radians of φ: a twentieth of TT's
/// azimuthal standard deviation β/√2 at the smallest roughness the model takes (β = 0.0025),
/// under 0.4 % of it at β = 0.04.
pub const TOLERANCE: f64 = 1e-4;

/// TT's and TRT's shift over (θ_i, h) for one fiber.
#[derive(Clone, Debug)]
pub struct ShiftTable {
    /// Per node, the shift of TT and of TRT.
    texels: Vec<[f32; 2]>,
    /// Per cell (indexed by its first corner), bit p − 1 set where lobe p's blend misses the
    /// exact shift at the cell's centre by more than [`TOLERANCE`].
    solve: Vec<u8>,
}

impl ShiftTable {
    /// `shift(p, θ_i, h)` at every node, rows of θ_i shared among the available cores, then
    /// every cell's blend checked at its centre.
    pub fn build(shift: impl Fn(usize, f64, f64) -> f64 + Sync) -> Self {
        let mut texels = vec![[0.0f32; 2]; THETA_I_NODES * H_NODES];
        fill_rows(&mut texels, H_NODES, |i, row| {
            let theta_i = theta_i_at(i);
            for (k, texel) in row.iter_mut().enumerate() {
                let h = h_at(k as f64);
                *texel = [shift(1, theta_i, h) as f32, shift(2, theta_i, h) as f32];
            }
        });
        let mut table = Self {
            texels,
            solve: Vec::new(),
        };
        let mut solve = vec![0u8; THETA_I_NODES * H_NODES];
        fill_rows(&mut solve, H_NODES, |i, row| {
            if i + 1 == THETA_I_NODES {
                return;
            }
            let theta_i = 0.5 * (theta_i_at(i) + theta_i_at(i + 1));
            for (k, flags) in row[..H_NODES - 1].iter_mut().enumerate() {
                let h = h_at(k as f64 + 0.5);
                for p in 1..=2 {
                    let miss = (table.blend(p, i, k, 0.5, 0.5) - shift(p, theta_i, h)).abs();
                    if miss.is_nan() || miss > TOLERANCE {
                        *flags |= 1 << (p - 1);
                    }
                }
            }
        });
        table.solve = solve;
        table
    }

    /// Lobe p's bilinear blend in cell (i, k) at fractions (f_i, f_k).
    #[inline]
    fn blend(&self, p: usize, i: usize, k: usize, fi: f64, fk: f64) -> f64 {
        let at = i * H_NODES + k;
        let node = |n: usize| self.texels[n][p - 1] as f64;
        let low = node(at) + fk * (node(at + 1) - node(at));
        let high = node(at + H_NODES) + fk * (node(at + H_NODES + 1) - node(at + H_NODES));
        low + fi * (high - low)
    }

    /// Lobe p's shift (TT 1, TRT 2) at (θ_i, h), or `None` where the table cannot answer and
    /// the caller must trace the path.
    #[inline]
    pub fn at(&self, p: usize, theta_i: f64, h: f64) -> Option<f64> {
        let (i, fi) = locate((theta_i + FRAC_PI_2) / PI, THETA_I_NODES);
        let (k, fk) = locate(0.5 * (h + 1.0), H_NODES);
        (self.solve[i * H_NODES + k] & (1 << (p - 1)) == 0)
            .then(|| self.blend(p, i, k, fi as f64, fk as f64))
    }
}

fn theta_i_at(i: usize) -> f64 {
    crate::math::grid::theta_i_node(i, THETA_I_NODES)
}

/// h at (fractional) node k.
fn h_at(k: f64) -> f64 {
    -1.0 + 2.0 * k / (H_NODES - 1) as f64
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::models::deon2011::azimuthal::AzimuthalScattering;
    use crate::models::nonseparable::cuticle::WithScales;

    /// Between the nodes and the checked centres (a grid that shares neither), the table
    /// answers within a few tolerances of the traced shift wherever it answers, and answers
    /// for most offsets.
    #[test]
    fn shift_table_follows_the_exact_shift() {
        for alpha_deg in [-4.0f64, 2.0] {
            let az = AzimuthalScattering::new(1.55, 0.04, glam::DVec3::ZERO)
                .with_scale_tilt(alpha_deg.to_radians());
            let table = ShiftTable::build(|p, theta_i, h| az.deflection_shift(p, theta_i, h));
            let (mut worst, mut asked, mut solved) = (0.0f64, 0, 0);
            for i in 0..311 {
                let theta_i = -1.5 + 3.0 * (i as f64 + 0.29) / 311.0;
                for k in 0..97 {
                    let h = -0.999 + 1.998 * (k as f64 + 0.43) / 97.0;
                    for p in 1..=2 {
                        asked += 1;
                        match table.at(p, theta_i, h) {
                            Some(got) => {
                                let want = az.deflection_shift(p, theta_i, h);
                                worst = worst.max((got - want).abs());
                            }
                            None => solved += 1,
                        }
                    }
                }
            }
            let share = solved as f64 / asked as f64;
            eprintln!(
                "α {alpha_deg}°: shift table within {worst:.2e} rad of the trace, {:.1} % traced",
                100.0 * share
            );
            assert!(worst < 2.0 * TOLERANCE, "α {alpha_deg}°: {worst:e}");
            assert!(share < 0.1, "α {alpha_deg}°: {share}");
        }
    }
}
