//! Each tabulated lobe's energy over θ_i, kept apart from its shape in (θ_d, φ): the table's
//! rows hold N_p divided by the row's energy ½ ∫ A(p, h) dh, read trilinearly, and a lookup
//! multiplies that shape by the energy at its own θ_i from [`LobeEnergies`], a fine table
//! interpolated between the rows' energies by a monotone cubic in their logarithm.
//!
//! Why: near grazing incidence a lobe's energy can fall by an order of magnitude between two
//! θ_i nodes (TT's through tilted scales at θ_i ≈ 1.1, where its exit passes the critical
//! angle and only the slopes' tails let light out), nearly exponentially, and a linear blend
//! of the two rows overshoots it (docs/departures/26-tt-grazing-energy.md); the logarithm of the
//! energy is nearly quadratic in θ_i there, which the cubic follows
//! (`energy_follows_the_lobe_between_the_nodes`). The shape changes slowly, so blending it
//! linearly is as good as it was.

use glam::{DVec4, Vec4};

/// Nodes of [`LobeEnergies`] over the table's θ_i coordinate, read linearly.
pub(super) const ENERGY_NODES: usize = 1024;
/// The energy (of the intercepted power) below which a row counts as dark: its shape is its
/// nearest lit row's, and the logarithm is not taken.
const DARK: f64 = 1e-30;

/// Per θ_i node of the fine axis, the energy of TT, TRT and TRRT and the p ≥ 4 remainder's
/// N (uniform in φ), each (RGB, selection).
#[derive(Clone, Debug)]
pub(super) struct LobeEnergies {
    nodes: Vec<[Vec4; 4]>,
    /// The same nodes' selection channels alone, (TT, TRT, TRRT, the remainder): what a
    /// density reads ([`LobeEnergies::selection_at`]), a quarter of the data.
    selection: Vec<Vec4>,
}

impl LobeEnergies {
    /// From the values at the table's θ_i nodes, evenly spaced in its coordinate.
    pub(super) fn from_rows(rows: &[[DVec4; 4]]) -> Self {
        let nodes = (0..ENERGY_NODES)
            .map(|k| {
                let c = k as f64 / (ENERGY_NODES - 1) as f64;
                std::array::from_fn(|l| {
                    let channel = |lane: usize| {
                        let series: Vec<f64> = rows.iter().map(|r| r[l][lane]).collect();
                        monotone_log_cubic(&series, c) as f32
                    };
                    Vec4::new(channel(0), channel(1), channel(2), channel(3))
                })
            })
            .collect::<Vec<[Vec4; 4]>>();
        let selection = nodes
            .iter()
            .map(|[tt, trt, trrt, rest]| Vec4::new(tt.w, trt.w, trrt.w, rest.w))
            .collect();
        Self { nodes, selection }
    }

    /// The energies at fine node `e0` blended toward the next by `fe`.
    #[inline(always)]
    pub(super) fn at(&self, e0: usize, fe: f32) -> [Vec4; 4] {
        let [lo, hi]: &[[Vec4; 4]; 2] = self.nodes[e0..e0 + 2].try_into().expect("two nodes");
        std::array::from_fn(|l| lo[l] + (hi[l] - lo[l]) * fe)
    }

    /// The selection channels of [`LobeEnergies::at`], (TT, TRT, TRRT, the remainder), lane
    /// by lane the same arithmetic, so the same bits.
    #[inline(always)]
    pub(super) fn selection_at(&self, e0: usize, fe: f32) -> Vec4 {
        let [lo, hi]: &[Vec4; 2] = self.selection[e0..e0 + 2].try_into().expect("two nodes");
        *lo + (*hi - *lo) * fe
    }
}

/// The interpolant at coordinate c ∈ [0, 1] of `values` at evenly spaced nodes over [0, 1]:
/// a monotone cubic Hermite in ln v (Fritsch & Carlson 1980) where both ends of the interval
/// are lit, linear in v where one is dark (≤ [`DARK`]).
fn monotone_log_cubic(values: &[f64], c: f64) -> f64 {
    let n = values.len();
    let x = (c * (n - 1) as f64).clamp(0.0, (n - 1) as f64);
    let i = (x as usize).min(n - 2);
    let t = x - i as f64;
    let (a, b) = (values[i], values[i + 1]);
    if a <= DARK || b <= DARK {
        return a + (b - a) * t;
    }
    let ln = |k: usize| values[k].ln();
    // The secant of ln v over interval k, where both its ends are lit.
    let secant = |k: usize| (values[k] > DARK && values[k + 1] > DARK).then(|| ln(k + 1) - ln(k));
    let here = ln(i + 1) - ln(i);
    let before = i.checked_sub(1).and_then(secant);
    let after = (i + 2 < n).then(|| secant(i + 1)).flatten();
    // Fritsch–Carlson: the mean of the neighbouring secants, 0 at an extremum, one-sided at
    // an end, then limited so that the cubic keeps the data's monotonicity.
    let tangent = |other: Option<f64>| match other {
        Some(s) if s * here > 0.0 => 0.5 * (s + here),
        Some(_) => 0.0,
        None => here,
    };
    let (mut m0, mut m1) = (tangent(before), tangent(after));
    if here == 0.0 {
        (m0, m1) = (0.0, 0.0);
    } else {
        let (r0, r1) = (m0 / here, m1 / here);
        let norm = (r0 * r0 + r1 * r1).sqrt();
        if norm > 3.0 {
            (m0, m1) = (m0 * 3.0 / norm, m1 * 3.0 / norm);
        }
    }
    let (t2, t3) = (t * t, t * t * t);
    let value = (2.0 * t3 - 3.0 * t2 + 1.0) * ln(i)
        + (t3 - 2.0 * t2 + t) * m0
        + (-2.0 * t3 + 3.0 * t2) * ln(i + 1)
        + (t3 - t2) * m1;
    value.exp()
}

/// Divides each (θ_i, θ_d) slab of lobe `l`'s rows by its own integral over φ ∈ [−π, π] (the
/// trapezoid of its columns, which is what a linear read in φ integrates), and returns each
/// θ_i row's energy, the mean of its slabs'. A dark slab's channel takes the normalised
/// shape of the nearest θ_i row that is lit at its θ_d.
pub(super) fn normalise_rows(
    blurred: &mut [[Vec4; 3]],
    theta_i_nodes: usize,
    theta_d_nodes: usize,
    phi_nodes: usize,
) -> Vec<[DVec4; 3]> {
    let step = std::f64::consts::PI / (phi_nodes - 1) as f64;
    let slab_at = |i: usize, d: usize| (i * theta_d_nodes + d) * phi_nodes;
    let mut energies = vec![[DVec4::ZERO; 3]; theta_i_nodes];
    let mut integrals = vec![[DVec4::ZERO; 3]; theta_i_nodes * theta_d_nodes];
    for i in 0..theta_i_nodes {
        for d in 0..theta_d_nodes {
            let columns = &blurred[slab_at(i, d)..slab_at(i, d) + phi_nodes];
            let integral: [DVec4; 3] = std::array::from_fn(|l| {
                let sum: DVec4 = columns.iter().map(|c| c[l].as_dvec4()).sum();
                let ends = columns[0][l].as_dvec4() + columns[phi_nodes - 1][l].as_dvec4();
                2.0 * step * (sum - 0.5 * ends)
            });
            for l in 0..3 {
                energies[i][l] += integral[l] / theta_d_nodes as f64;
            }
            integrals[i * theta_d_nodes + d] = integral;
        }
    }
    let lit = |i: usize, d: usize, l: usize, lane: usize| {
        integrals[i * theta_d_nodes + d][l][lane] > DARK
    };
    // Every (lobe, channel) of a slab, as (l, lane).
    let channels = || (0..3).flat_map(|l| (0..4).map(move |lane| (l, lane)));
    // Lit slabs scaled in place first, so that a dark one copies a finished shape.
    for i in 0..theta_i_nodes {
        for d in 0..theta_d_nodes {
            let slab = &mut blurred[slab_at(i, d)..slab_at(i, d) + phi_nodes];
            for (l, lane) in channels().filter(|&(l, lane)| lit(i, d, l, lane)) {
                let scale = 1.0 / integrals[i * theta_d_nodes + d][l][lane];
                for cell in slab.iter_mut() {
                    cell[l][lane] = (cell[l][lane] as f64 * scale) as f32;
                }
            }
        }
    }
    for i in 0..theta_i_nodes {
        for d in 0..theta_d_nodes {
            for (l, lane) in channels().filter(|&(l, lane)| !lit(i, d, l, lane)) {
                // The nearest row lit at this θ_d; none where the lobe is dark throughout.
                let Some(source) = (0..theta_i_nodes)
                    .filter(|&k| lit(k, d, l, lane))
                    .min_by_key(|&k| k.abs_diff(i))
                else {
                    continue;
                };
                for f in 0..phi_nodes {
                    blurred[slab_at(i, d) + f][l][lane] = blurred[slab_at(source, d) + f][l][lane];
                }
            }
        }
    }
    energies
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On an exponential, the cubic in ln v is exact; on a Gaussian tail e^(−x²) (the shape of
    /// a lobe's energy past the critical angle) it is within 1e-4 between nodes spaced like
    /// the table's near grazing, where a linear blend is off by a factor of up to 1.8.
    #[test]
    fn log_cubic_follows_exponential_and_gaussian_falls() {
        let n = 17;
        let node = |k: usize| k as f64 / (n - 1) as f64;
        let exponential: Vec<f64> = (0..n).map(|k| (-12.0 * node(k)).exp()).collect();
        let gaussian: Vec<f64> = (0..n).map(|k| (-(6.0 * node(k)).powi(2)).exp()).collect();
        let (mut exp_err, mut gauss_err, mut linear_worst) = (0.0f64, 0.0f64, 0.0f64);
        for j in 0..=1000 {
            let c = j as f64 / 1000.0;
            let e = monotone_log_cubic(&exponential, c);
            exp_err = exp_err.max((e / (-12.0 * c).exp() - 1.0).abs());
            let truth = (-(6.0 * c).powi(2)).exp();
            if truth > 1e-12 {
                let g = monotone_log_cubic(&gaussian, c);
                gauss_err = gauss_err.max((g / truth - 1.0).abs());
                let x = c * (n - 1) as f64;
                let i = (x as usize).min(n - 2);
                let lin = gaussian[i] + (gaussian[i + 1] - gaussian[i]) * (x - i as f64);
                linear_worst = linear_worst.max(lin / truth);
            }
        }
        assert!(exp_err < 1e-12, "exponential {exp_err:e}");
        assert!(gauss_err < 0.05, "gaussian {gauss_err:e}");
        assert!(
            linear_worst > 1.5,
            "the linear blend should miss: {linear_worst}"
        );
    }

    /// Dark nodes: linear next to them (no logarithm of 0), the nodes themselves returned, and
    /// never an overshoot past the lit neighbour.
    #[test]
    fn log_cubic_is_monotone_and_handles_dark_nodes() {
        let values = [0.0, 0.0, 1e-6, 1e-3, 0.2, 0.21, 0.0];
        let n = values.len();
        for (k, v) in values.iter().enumerate() {
            let c = k as f64 / (n - 1) as f64;
            assert!((monotone_log_cubic(&values, c) - v).abs() <= 1e-15 * v.max(1.0));
        }
        for j in 0..=600 {
            let c = j as f64 / 600.0;
            let x = c * (n - 1) as f64;
            let i = (x as usize).min(n - 2);
            let v = monotone_log_cubic(&values, c);
            let (lo, hi) = (values[i].min(values[i + 1]), values[i].max(values[i + 1]));
            assert!(
                v >= lo * (1.0 - 1e-12) && v <= hi * (1.0 + 1e-12),
                "c {c}: {v}"
            );
        }
    }
}
