//! TRT's exit sine through a rough surface with tilted scales, over every offset: the mean and
//! variance of x = sin θ_o over the light that the micro-normals of TRT's three events (the
//! entry, the reflection inside, the exit) let out. The project's own extension of d'Eon et
//! al. 2014 §2.5, which places TRT's lobe at the smooth path's cone at h = 0 with the paper's
//! width (docs/departures/29-trt-pair-lobe.md).
//!
//! Why: where the scales tilt toward the tip, TRT's smooth path is blocked from some offset
//! on, yet the rough surface lets light out there, toward the equator of the smooth exit and
//! narrower (docs/departures/29-trt-pair-lobe.md has the simulated offsets), as TT's pair
//! quadrature ([`crate::models::nonseparable::rough::deflection`]) found for TT.
//!
//! The quadrature: at each of [`OFFSETS`] offsets over the half fiber (TRT's exit is even in
//! h), the entry's micro-normals refract the light into chords (`refraction_at`), each chord
//! meets the back of the fiber, whose micro-normals reflect it (`reflection_at`), and the
//! second chord meets the exit, whose micro-normals refract it out, each event on a widened
//! Fibonacci lattice of slopes (`lattice_slopes`, [`TRT_RULE`]) with Walter et al. 2007's
//! weight; a path through a back-facing scale or to the wrong side of the surface carries no
//! light. The sums over (offset, entry, reflection, exit), weighted by dh, give the mean and
//! variance of x. [`RoughTrtTable`] holds them over θ_i for one fiber (η, α, β), read
//! linearly. Absorption is left out, as in TT's columns: it scales each offset's light by its
//! chords' transmittance, which moves the mean little beside the offsets the scales block.

use crate::geometry::nusselt::{self, AtScale, Tilt};
use crate::lobes::sine_lobe::SineMoments;
use crate::math::grid::{SharedTables, fill_rows, locate, shared_table};
use crate::models::nonseparable::scales::attenuation::incident;
use crate::optics::rough_interface::{Slope, lattice_slopes, reflection_at, refraction_at};
use glam::DVec3;
use std::f64::consts::{FRAC_1_SQRT_2, FRAC_PI_2, PI};
use std::sync::{Arc, OnceLock};

/// Micro-normals per event of the quadrature: the entry, the reflection inside and the exit,
/// each a widened Fibonacci lattice (`coarse_rule_follows_the_fine_one`).
pub const TRT_RULE: TrtRule = TrtRule {
    entry: 13,
    reflection: 13,
    exit: 34,
};

/// Micro-normals per event of a TRT quadrature ([`TRT_RULE`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TrtRule {
    pub entry: usize,
    pub reflection: usize,
    pub exit: usize,
}

/// Offsets over the half fiber, at the midpoints of equal steps of γ = asin h.
pub const OFFSETS: usize = 16;

/// The mean and variance of TRT's exit sine at θ_i over every offset through a rough surface
/// (module docs), by `rule`; `None` where no light leaves.
pub fn rough_trt_sine(
    theta_i: f64,
    alpha: f64,
    eta: f64,
    beta: f64,
    rule: TrtRule,
) -> Option<SineMoments> {
    let tilt = Tilt::new(alpha);
    let sd = beta * FRAC_1_SQRT_2;
    // Each event's micro-normals (unit-law slopes on this surface) with their weights, found
    // once for every path that meets them.
    let normals = |n: usize| -> Vec<(DVec3, f64)> {
        let normal = |m: &Slope| DVec3::new(-sd * m.x, -sd * m.y, 1.0).normalize();
        lattice_slopes(n)
            .iter()
            .map(|m| (normal(m), m.weight))
            .collect()
    };
    let [entries, reflections, exits] = [rule.entry, rule.reflection, rule.exit].map(normals);
    // A direction leaving a scale's frame, carried across the fiber to the next scale.
    let onward = |at: &AtScale, d: DVec3| {
        at.leaving(d)
            .and_then(|chord| AtScale::inside(tilt, nusselt::propagate(chord)))
    };
    let mut sums = [0.0f64; 3];
    for k in 0..OFFSETS {
        let gamma = FRAC_PI_2 * (k as f64 + 0.5) / OFFSETS as f64;
        let Ok(entry) = AtScale::outside(tilt, incident(theta_i, gamma.sin())) else {
            continue;
        };
        let dh = gamma.cos();
        for &(m_in, weight_in) in &entries {
            let Some((into, w_in)) = refraction_at(entry.arriving(), m_in, beta, eta) else {
                continue;
            };
            let Ok(back) = onward(&entry, into) else {
                continue;
            };
            let w_in = w_in * weight_in * dh;
            for &(m_back, weight_back) in &reflections {
                let turned = reflection_at(back.arriving(), m_back, beta, 1.0 / eta);
                let Some((turned, w_back)) = turned else {
                    continue;
                };
                let Ok(exit) = onward(&back, turned) else {
                    continue;
                };
                let w_back = w_in * w_back * weight_back;
                for &(m_out, weight_out) in &exits {
                    let out = refraction_at(exit.arriving(), m_out, beta, 1.0 / eta);
                    let Some((out, w_out)) = out else {
                        continue;
                    };
                    let Ok((x, _)) = exit.leaving(out) else {
                        continue;
                    };
                    let w = w_back * w_out * weight_out;
                    sums = [sums[0] + w, sums[1] + w * x, sums[2] + w * x * x];
                }
            }
        }
    }
    let [w, wx, wxx] = sums;
    // w is a sum of non-negative weights: not positive means no light left (or NaN input).
    if w.is_nan() || w <= 0.0 {
        return None;
    }
    let mean = wx / w;
    Some(SineMoments {
        mean,
        variance: (wxx / w - mean * mean).max(0.0),
    })
}

/// Nodes over θ_i ∈ [−π/2, π/2].
const THETA_I_NODES: usize = 129;

/// [`rough_trt_sine`] over θ_i for one fiber (η, α, β), by [`TRT_RULE`]; a node where no light
/// leaves holds NaN, and a read there gives `None`.
#[derive(Clone, Debug)]
pub struct RoughTrtTable {
    /// Per node, the mean and variance of the exit sine.
    nodes: Vec<[f64; 2]>,
}

impl RoughTrtTable {
    /// The table for (η, α, β), built once per process and shared.
    pub fn shared(eta: f64, alpha: f64, beta: f64) -> Arc<Self> {
        static CACHE: SharedTables<(u64, u64, u64), RoughTrtTable> = OnceLock::new();
        let key = (eta.to_bits(), alpha.to_bits(), beta.to_bits());
        shared_table(&CACHE, key, || Self::build(eta, alpha, beta))
    }

    /// Every node by [`rough_trt_sine`], shared among the available cores.
    pub fn build(eta: f64, alpha: f64, beta: f64) -> Self {
        let mut nodes = vec![[0.0; 2]; THETA_I_NODES];
        fill_rows(&mut nodes, 1, |i, node| {
            node[0] = match rough_trt_sine(theta_i_at(i), alpha, eta, beta, TRT_RULE) {
                Some(SineMoments { mean, variance }) => [mean, variance],
                None => [f64::NAN; 2],
            };
        });
        Self { nodes }
    }

    /// The mean and variance at θ_i, linear between the nodes; `None` where either node has no
    /// light.
    pub fn at(&self, theta_i: f64) -> Option<SineMoments> {
        let (i, f) = locate((theta_i + FRAC_PI_2) / PI, THETA_I_NODES);
        let f = f as f64;
        let [a, b] = [self.nodes[i], self.nodes[i + 1]];
        let lerp = |l: usize| a[l] + f * (b[l] - a[l]);
        let (mean, variance) = (lerp(0), lerp(1));
        (mean.is_finite() && variance.is_finite()).then_some(SineMoments { mean, variance })
    }
}

fn theta_i_at(i: usize) -> f64 {
    crate::math::grid::theta_i_node(i, THETA_I_NODES)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// As β → 0 the rough paths are the smooth one at each offset, weighted by its Fresnel
    /// factors (1 − F) F (1 − F) dh: the quadrature's mean and variance of x are the smooth
    /// exits' under those weights, where the smooth path leaves.
    #[test]
    fn a_nearly_smooth_surface_leaves_on_the_smooth_paths() {
        use crate::optics::fresnel::fresnel_dielectric;
        let one = TrtRule {
            entry: 1,
            reflection: 1,
            exit: 1,
        };
        let eta = 1.55;
        for (theta_i, alpha_deg) in [(0.25, -2.0f64), (0.75, 0.0), (1.1, -4.0), (0.75, 4.0)] {
            let tilt = Tilt::new(alpha_deg.to_radians());
            let got =
                rough_trt_sine(theta_i, alpha_deg.to_radians(), eta, 1e-7, one).expect("it leaves");
            let smooth = |h: f64| -> Result<(f64, f64), nusselt::Blocked> {
                let entry = AtScale::outside(tilt, incident(theta_i, h))?;
                let back = AtScale::inside(tilt, nusselt::propagate(entry.refract(eta)?))?;
                let exit = AtScale::inside(tilt, nusselt::propagate(back.reflect()?))?;
                let (x, _) = exit.refract(eta)?;
                let weight = (1.0 - fresnel_dielectric(entry.cos, eta))
                    * fresnel_dielectric(back.cos, 1.0 / eta)
                    * (1.0 - fresnel_dielectric(exit.cos, 1.0 / eta));
                Ok((x, weight))
            };
            let (mut w, mut wx, mut wxx) = (0.0, 0.0, 0.0);
            for k in 0..OFFSETS {
                let gamma = FRAC_PI_2 * (k as f64 + 0.5) / OFFSETS as f64;
                if let Ok((x, f)) = smooth(gamma.sin()) {
                    let f = f * gamma.cos();
                    (w, wx, wxx) = (w + f, wx + f * x, wxx + f * x * x);
                }
            }
            let (mean, variance) = (wx / w, wxx / w - (wx / w).powi(2));
            assert!(
                (got.mean - mean).abs() < 1e-5 && (got.variance - variance).abs() < 1e-6,
                "θ_i {theta_i} α {alpha_deg}: {got:?} against {mean}, {variance}"
            );
        }
    }

    /// The table's rule against a finer one (21 × 21 × 89): the mean exit sine within 1.5e-3
    /// and the deviation within 3 % over inclinations and tilts (measured 9.8e-4 and 2.5 %, the
    /// worst at θ_i = 1.1, α = +2°). Left out: θ_i = 1.1, α = +4°, where what leaves is the slopes'
    /// far tails and the finer rules disagree among themselves (21 × 21 × 89 against
    /// 34 × 34 × 144: 1.1e-3 and 15 %); TRT carries little light there.
    #[test]
    fn coarse_rule_follows_the_fine_one() {
        let fine = TrtRule {
            entry: 21,
            reflection: 21,
            exit: 89,
        };
        let (mut mean_error, mut sd_error) = (0.0f64, 0.0f64);
        for theta_i in [0.25, 0.75, 1.1] {
            for alpha_deg in [-4.0f64, 2.0, 4.0] {
                if theta_i == 1.1 && alpha_deg == 4.0 {
                    continue;
                }
                let alpha = alpha_deg.to_radians();
                let a = rough_trt_sine(theta_i, alpha, 1.55, 0.04, TRT_RULE).expect("it leaves");
                let b = rough_trt_sine(theta_i, alpha, 1.55, 0.04, fine).expect("it leaves");
                mean_error = mean_error.max((a.mean - b.mean).abs());
                sd_error = sd_error.max((a.variance.sqrt() / b.variance.sqrt() - 1.0).abs());
            }
        }
        eprintln!("TRT rule against 21 × 21 × 89: mean sine {mean_error:.1e}, σ {sd_error:.3}");
        assert!(
            mean_error < 1.5e-3 && sd_error < 0.03,
            "{mean_error} {sd_error}"
        );
    }
}
