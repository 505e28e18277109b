//! TT's azimuth through a rough surface, offset by offset: where the light entering at h
//! leaves in φ, and how far it spreads there, in the mean over the micro-normals of both of
//! its events. The project's own extension of d'Eon et al. 2014, whose N_TT centres every
//! offset's light on the smooth path's Φ(1, h) with one azimuthal variance β²/2 (§2.4).
//!
//! Why: near the offsets where the smooth path is blocked (the exit past the critical angle at
//! a tilted scale) or grazes, the smooth Φ(1, h) bends sharply and then stops, where the light
//! a rough surface lets through keeps moving smoothly with h; and the spread in φ grows from
//! β/√2 near h = 0 to several times it at the edges. docs/validation.md, departure 20,
//! has the comparison. Against the simulator: offset by offset in `cuticle-sim`'s
//! `path::tests` (the paths traced at fixed h), and as N_TT over TT's edge columns in
//! `crates/validate/tests/rough_tt_azimuth.rs`.
//!
//! The path: the entry's micro-normals refract the light into a spread of chords (a product
//! grid of equal-probability slopes, each with Walter et al. 2007's transmission weight, as
//! [`crate::rough_interface`] takes them); each chord meets the exit's scale
//! ([`AtScale::inside`]), whose micro-normals refract it out on a finer grid. Each exit's
//! in-plane angles give its Φ = π + γ′ − γ_i + γ′ − γ_o, signed as [`crate::tilted_deflection`]
//! takes them, and the weighted mean and standard deviation over every (entry, exit) pair are
//! the offset's. [`RoughTtTable`] holds them over (θ_i, γ = asin h) for one fiber, read
//! bilinearly; the model's N_TT, its azimuthal table and its sampler all read that one table,
//! so they agree with each other exactly.

use crate::bravais::{azimuthal_deflection, eta_prime};
use crate::nusselt::{self, AtScale, Nusselt, Tilt};
use crate::rough_interface::{refraction_at, slope_quantiles};
use crate::special::{asin_fast, atan2_fast};
use crate::table::{SharedTables, fill_rows, locate, shared_table};
use crate::tilted_attenuation::incident;
use glam::DVec3;
use std::f64::consts::{FRAC_PI_2, PI};
use std::sync::{Arc, OnceLock};

/// Equal-probability slopes per axis at the entry and at the exit of the table's quadrature,
/// within a few thousandths of a radian of 8 × 24 (`coarse_rule_follows_the_fine_one`).
pub const TABLE_RULE: Rule = Rule { entry: 4, exit: 12 };

/// Slopes per axis of a quadrature: entry² × exit² micro-normal pairs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Rule {
    pub entry: usize,
    pub exit: usize,
}

/// Where TT's light entering at one offset leaves, in the mean over the micro-normals.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoughExit {
    /// The mean Φ(1, h), unwrapped like [`azimuthal_deflection`].
    pub phi: f64,
    /// The standard deviation of φ about it.
    pub sigma: f64,
    /// The mean exit sine sin θ_o.
    pub sin_theta: f64,
    /// The share of the light that reaches the exit and leaves there, unabsorbed (the
    /// quadrature's A(1, h) at μ_a = 0).
    pub transmitted: f64,
}

/// The in-plane angle of a Nusselt direction to its normal, signed by `sign`.
fn in_plane_signed((x, y): Nusselt, sign: f64) -> f64 {
    let z = (1.0 - x * x - y * y).max(0.0).sqrt();
    atan2_fast(y * sign, z)
}

/// The signs that make the chord's and the exit's in-plane angles positive on the smooth path
/// at a small offset of sign s: the convention in which Φ = π + s (2γ′ − γ_i − γ_o).
fn in_plane_signs(tilt: Tilt, theta_i: f64, eta: f64, s: f64) -> Option<(f64, f64)> {
    let entry = AtScale::outside(tilt, incident(theta_i, 0.25 * s)).ok()?;
    let chord = entry.refract(eta).ok()?;
    let exit = AtScale::inside(tilt, nusselt::propagate(chord))
        .ok()?
        .refract(eta)
        .ok()?;
    Some((chord.1.signum(), exit.1.signum()))
}

/// `n` equal-probability slopes of the normal law of variance β²/2 ([`slope_quantiles`]),
/// scaled so that their own variance is β²/2: the midpoints of the bins fall short of it (by
/// 29 % for four, 7 % for twelve), and the spread in φ is what this rule is for.
fn matched_slopes(beta: f64, n: usize) -> Vec<f64> {
    let slopes = slope_quantiles(beta, n);
    let variance = slopes.iter().map(|s| s * s).sum::<f64>() / n as f64;
    let scale = if variance > 0.0 {
        beta * std::f64::consts::FRAC_1_SQRT_2 / variance.sqrt()
    } else {
        1.0
    };
    slopes.into_iter().map(|s| s * scale).collect()
}

/// TT's exit at offset h through scales tilted by α on a surface of Beckmann roughness β, by
/// `rule` (module documentation); `None` where no light leaves.
pub fn rough_tt_exit(
    theta_i: f64,
    alpha: f64,
    eta: f64,
    beta: f64,
    h: f64,
    rule: Rule,
) -> Option<RoughExit> {
    let tilt = Tilt::new(alpha);
    let s = if h < 0.0 { -1.0 } else { 1.0 };
    let (chord_sign, exit_sign) = in_plane_signs(tilt, theta_i, eta, s)?;
    let d = incident(theta_i, h);
    let gamma_i = in_plane_signed(d, s);
    let entry = AtScale::outside(tilt, d).ok()?;
    let (entry_slopes, exit_slopes) = (
        matched_slopes(beta, rule.entry),
        matched_slopes(beta, rule.exit),
    );
    let normal = |sx: f64, sy: f64| DVec3::new(-sx, -sy, 1.0).normalize();
    let mut sums = [0.0; 4];
    for &ax in &entry_slopes {
        for &ay in &entry_slopes {
            let Some((into, w_in)) = refraction_at(entry.arriving(), normal(ax, ay), beta, eta)
            else {
                continue;
            };
            let Ok(chord) = entry.leaving(into) else {
                continue;
            };
            let Ok(exit) = AtScale::inside(tilt, nusselt::propagate(chord)) else {
                continue;
            };
            let twice_chord = 2.0 * in_plane_signed(chord, chord_sign);
            for &bx in &exit_slopes {
                for &by in &exit_slopes {
                    let Some((out, w_out)) =
                        refraction_at(exit.arriving(), normal(bx, by), beta, 1.0 / eta)
                    else {
                        continue;
                    };
                    let Ok(leaving) = exit.leaving(out) else {
                        continue;
                    };
                    let phi =
                        PI + s * (twice_chord - gamma_i - in_plane_signed(leaving, exit_sign));
                    let w = w_in * w_out;
                    sums[0] += w;
                    sums[1] += w * phi;
                    sums[2] += w * phi * phi;
                    sums[3] += w * leaving.0;
                }
            }
        }
    }
    let [w, phi, phi2, sin] = sums;
    // w is a sum of non-negative weights: not positive means no light left (or NaN input).
    if w.is_nan() || w <= 0.0 {
        return None;
    }
    let (mean, sin_mean) = (phi / w, sin / w);
    let pairs = (rule.entry * rule.entry * rule.exit * rule.exit) as f64;
    Some(RoughExit {
        phi: mean,
        sigma: (phi2 / w - mean * mean).max(0.0).sqrt(),
        sin_theta: sin_mean,
        transmitted: w / pairs,
    })
}

/// Nodes over θ_i ∈ [−π/2, π/2] and over γ = asin |h| ∈ [0, π/2].
const THETA_I_NODES: usize = 97;
const GAMMA_NODES: usize = 65;
/// The end nodes are evaluated this far inside ±π/2.
const GRAZING: f64 = 1e-3;

/// What a rough surface makes of TT's azimuth at one (θ_i, h): the shift from Bravais' Φ(1, h)
/// at the θ_d of its own mean exit (as [`crate::tilted_deflection::deflection_shift`] defines
/// it) and the standard deviation in φ.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoughAzimuth {
    pub shift: f64,
    pub sigma: f64,
}

/// [`RoughAzimuth`] over (θ_i, γ = asin |h|) for one fiber (η, α, β), by [`TABLE_RULE`]: the
/// shift is odd in h and the spread even (the fiber is symmetric about the plane of
/// incidence), so γ runs over [0, π/2] alone.
#[derive(Clone, Debug)]
pub struct RoughTtTable {
    /// Per node, the shift and σ.
    texels: Vec<[f32; 2]>,
    /// The largest σ of any node: how far a lobe can reach.
    sigma_max: f64,
}

impl RoughTtTable {
    /// The table for (η, α, β), built once per process and shared.
    pub fn shared(eta: f64, alpha: f64, beta: f64) -> Arc<Self> {
        static CACHE: SharedTables<(u64, u64, u64), RoughTtTable> = OnceLock::new();
        let key = (eta.to_bits(), alpha.to_bits(), beta.to_bits());
        shared_table(&CACHE, key, || Self::build(eta, alpha, beta))
    }

    /// Every node by [`rough_tt_exit`] with [`TABLE_RULE`], the rows of θ_i shared among the
    /// available cores. Where no light leaves, the node keeps Bravais' Φ and the smooth
    /// spread β/√2 (it carries no power).
    pub fn build(eta: f64, alpha: f64, beta: f64) -> Self {
        let fallback = [0.0, (beta * std::f64::consts::FRAC_1_SQRT_2) as f32];
        let mut texels = vec![fallback; THETA_I_NODES * GAMMA_NODES];
        fill_rows(&mut texels, GAMMA_NODES, |i, row| {
            let theta_i = theta_i_at(i);
            for (k, texel) in row.iter_mut().enumerate() {
                let h = gamma_at(k).sin();
                if let Some(exit) = rough_tt_exit(theta_i, alpha, eta, beta, h, TABLE_RULE) {
                    let theta_o = asin_fast(exit.sin_theta.clamp(-1.0, 1.0));
                    let eta_p = eta_prime(eta, 0.5 * (theta_o - theta_i));
                    let shift = exit.phi - azimuthal_deflection(1, h, eta_p);
                    *texel = [shift as f32, exit.sigma as f32];
                }
            }
        });
        let sigma_max = texels.iter().fold(0.0f64, |m, t| m.max(t[1] as f64));
        Self { texels, sigma_max }
    }

    /// The shift and spread at (θ_i, h), blended bilinearly in (θ_i, γ).
    #[inline]
    pub fn at(&self, theta_i: f64, h: f64) -> RoughAzimuth {
        let (i, fi) = locate((theta_i + FRAC_PI_2) / PI, THETA_I_NODES);
        let gamma = asin_fast(h.abs().min(1.0));
        let (k, fk) = locate(gamma / FRAC_PI_2, GAMMA_NODES);
        let at = i * GAMMA_NODES + k;
        let node = |n: usize, l: usize| self.texels[n][l] as f64;
        let blend = |l: usize| {
            let (fi, fk) = (fi as f64, fk as f64);
            let low = node(at, l) + fk * (node(at + 1, l) - node(at, l));
            let high = node(at + GAMMA_NODES, l)
                + fk * (node(at + GAMMA_NODES + 1, l) - node(at + GAMMA_NODES, l));
            low + fi * (high - low)
        };
        let shift = blend(0);
        RoughAzimuth {
            shift: if h < 0.0 { -shift } else { shift },
            sigma: blend(1),
        }
    }

    /// The largest spread of any offset.
    pub fn sigma_max(&self) -> f64 {
        self.sigma_max
    }
}

fn theta_i_at(i: usize) -> f64 {
    (-FRAC_PI_2 + PI * i as f64 / (THETA_I_NODES - 1) as f64)
        .clamp(-FRAC_PI_2 + GRAZING, FRAC_PI_2 - GRAZING)
}

fn gamma_at(k: usize) -> f64 {
    (FRAC_PI_2 * k as f64 / (GAMMA_NODES - 1) as f64).min(FRAC_PI_2 - GRAZING)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tilted_deflection::tilted_exit;

    /// As β → 0 the rough exit is the smooth one, where the smooth path leaves.
    #[test]
    fn a_nearly_smooth_surface_leaves_on_the_smooth_path() {
        for (theta_i, alpha) in [(0.75, 2f64), (0.25, -4.0), (1.1, 0.0)] {
            for h in [-0.8, -0.3, 0.0, 0.4, 0.7] {
                let alpha = alpha.to_radians();
                let Some(smooth) = tilted_exit(1, theta_i, alpha, 1.55, h) else {
                    continue;
                };
                let rough =
                    rough_tt_exit(theta_i, alpha, 1.55, 1e-6, h, Rule { entry: 1, exit: 2 })
                        .expect("it leaves");
                assert!(
                    (rough.phi - smooth.phi).abs() < 1e-4
                        && (rough.sin_theta - smooth.sin_theta).abs() < 1e-5
                        && rough.sigma < 1e-4,
                    "θ_i {theta_i} α {alpha} h {h}: {rough:?} vs {smooth:?}"
                );
            }
        }
    }

    /// The table's rule against a finer one, and the table's blend against its rule between
    /// the nodes.
    #[test]
    fn coarse_rule_follows_the_fine_one() {
        let fine = Rule { entry: 8, exit: 24 };
        let (mut worst_phi, mut worst_sigma) = (0.0f64, 0.0f64);
        for theta_i in [0.25, 0.75, 1.1] {
            for h in [0.3, 0.7, 0.9, 0.98] {
                let a = rough_tt_exit(theta_i, 0.035, 1.55, 0.04, h, TABLE_RULE).unwrap();
                let b = rough_tt_exit(theta_i, 0.035, 1.55, 0.04, h, fine).unwrap();
                worst_phi = worst_phi.max((a.phi - b.phi).abs());
                worst_sigma = worst_sigma.max((a.sigma - b.sigma).abs());
            }
        }
        eprintln!("table rule vs 8 × 24: Φ within {worst_phi:.4}, σ within {worst_sigma:.4}");
        assert!(
            worst_phi < 0.005 && worst_sigma < 0.006,
            "{worst_phi} {worst_sigma}"
        );
    }
}
