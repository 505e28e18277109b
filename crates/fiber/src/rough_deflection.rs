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
//!
//! The same pairs give each offset's exit sine x = sin θ_o: its mean, its spread and its
//! covariance with φ. TT's longitudinal lobe at a column φ is the exit sine over the light
//! that reaches φ from every offset, each offset's x taken given φ
//! ([`RoughTtTable::column_sine`]; departure 21): near the edge an offset's light that lands
//! away from its Φ left at another inclination, which keeps the columns' lobes where the
//! simulation has them though each offset's mean x drifts toward the equator there.

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
    /// The standard deviation of the exit sine.
    pub sin_theta_sd: f64,
    /// The covariance of the exit sine with φ.
    pub covariance: f64,
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
/// at a small offset of sign s, the convention in which Φ = π + s (2γ′ − γ_i − γ_o): (−s, −s),
/// wherever that path leaves (`in_plane_signs_follow_the_smooth_path`), and kept where it is
/// blocked, where the rough surface still lets light out.
fn in_plane_signs(s: f64) -> (f64, f64) {
    (-s, -s)
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
    let (chord_sign, exit_sign) = in_plane_signs(s);
    let d = incident(theta_i, h);
    let gamma_i = in_plane_signed(d, s);
    let entry = AtScale::outside(tilt, d).ok()?;
    let (entry_slopes, exit_slopes) = (
        matched_slopes(beta, rule.entry),
        matched_slopes(beta, rule.exit),
    );
    let normal = |sx: f64, sy: f64| DVec3::new(-sx, -sy, 1.0).normalize();
    let mut sums = [0.0; 6];
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
                    sums[4] += w * leaving.0 * leaving.0;
                    sums[5] += w * leaving.0 * phi;
                }
            }
        }
    }
    let [w, phi, phi2, sin, sin2, sin_phi] = sums;
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
        sin_theta_sd: (sin2 / w - sin_mean * sin_mean).max(0.0).sqrt(),
        covariance: sin_phi / w - sin_mean * mean,
        transmitted: w / pairs,
    })
}

/// Nodes over θ_i ∈ [−π/2, π/2] and over γ = asin |h| ∈ [0, π/2].
const THETA_I_NODES: usize = 129;
const GAMMA_NODES: usize = 65;
/// The end nodes are evaluated this far inside ±π/2.
const GRAZING: f64 = 1e-4;

/// What a rough surface makes of TT's azimuth at one (θ_i, h): the shift from Bravais' Φ(1, h)
/// at θ_d = −θ_i to the mean exit's φ, and the standard deviation in φ.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoughAzimuth {
    pub shift: f64,
    pub sigma: f64,
}

/// The channels of a node while the table is built: the shift, σ, Φ(1, h) itself, the exit
/// sine's mean and standard deviation, the transmitted share, and the exit sine's covariance
/// with φ. The table keeps the first two; the columns are made of the rest.
const SHIFT: usize = 0;
const SIGMA: usize = 1;
const PHI: usize = 2;
const SIN_MEAN: usize = 3;
const SIN_SD: usize = 4;
const TRANSMITTED: usize = 5;
const COVARIANCE: usize = 6;
type Node = [f32; 7];

/// [`rough_tt_exit`] over (θ_i, γ = asin |h|) for one fiber (η, α, β), by [`TABLE_RULE`]: the
/// shift is odd in h, Φ is 2π less its value at −h, and the rest is even (the fiber is
/// symmetric about the plane of incidence), so γ runs over [0, π/2] alone.
#[derive(Clone, Debug)]
pub struct RoughTtTable {
    /// Per node, the shift and σ.
    texels: Vec<[f32; 2]>,
    /// The largest σ of any node: how far a lobe can reach.
    sigma_max: f64,
    /// Per θ_i node and column of |φ|, the mean and standard deviation of the exit sine over
    /// the light of every offset that reaches the column ([`RoughTtTable::column_sine`]).
    columns: Vec<[f32; 2]>,
}

/// Columns over |φ| ∈ [0, π] of [`RoughTtTable::column_sine`].
const COLUMNS: usize = 129;
/// Steps of γ between two nodes in the mixture over the offsets.
const SUBSTEPS: usize = 16;
/// The least σ a node takes, as a share of the smooth surface's β/√2: where the rule's
/// slopes let one (entry, exit) pair through, the quadrature's own σ is 0.
const LEAST_SIGMA_SHARE: f64 = 0.25;
/// The least standard deviation of the exit sine a column reports.
const LEAST_SIN_SD: f64 = 1e-4;

impl RoughTtTable {
    /// The table for (η, α, β), built once per process and shared.
    pub fn shared(eta: f64, alpha: f64, beta: f64) -> Arc<Self> {
        static CACHE: SharedTables<(u64, u64, u64), RoughTtTable> = OnceLock::new();
        let key = (eta.to_bits(), alpha.to_bits(), beta.to_bits());
        shared_table(&CACHE, key, || Self::build(eta, alpha, beta))
    }

    /// Every node by [`rough_tt_exit`] with [`TABLE_RULE`], the rows of θ_i shared among the
    /// available cores, then every row's columns. Where no light leaves, the node keeps
    /// Bravais' Φ at the specular cone and the smooth spread β/√2 (it carries no power);
    /// elsewhere σ is at least a quarter of that (`LEAST_SIGMA_SHARE`).
    pub fn build(eta: f64, alpha: f64, beta: f64) -> Self {
        let mut nodes: Vec<Node> = vec![[0.0; 7]; THETA_I_NODES * GAMMA_NODES];
        let smooth_sigma = beta * std::f64::consts::FRAC_1_SQRT_2;
        fill_rows(&mut nodes, GAMMA_NODES, |i, row| {
            let theta_i = theta_i_at(i);
            for (k, node) in row.iter_mut().enumerate() {
                let h = gamma_at(k).sin();
                *node = match rough_tt_exit(theta_i, alpha, eta, beta, h, TABLE_RULE) {
                    Some(exit) => [
                        exit.phi - bravais(eta, theta_i, h),
                        exit.sigma.max(LEAST_SIGMA_SHARE * smooth_sigma),
                        exit.phi,
                        exit.sin_theta,
                        exit.sin_theta_sd,
                        exit.transmitted,
                        exit.covariance,
                    ],
                    None => {
                        let phi = bravais(eta, theta_i, h);
                        [
                            0.0,
                            smooth_sigma,
                            phi,
                            -theta_i.sin(),
                            smooth_sigma,
                            0.0,
                            0.0,
                        ]
                    }
                }
                .map(|x| x as f32);
            }
        });
        let mut columns = vec![[0.0f32; 2]; THETA_I_NODES * COLUMNS];
        fill_rows(&mut columns, COLUMNS, |i, row| {
            fill_columns(&nodes[i * GAMMA_NODES..(i + 1) * GAMMA_NODES], row)
        });
        Self {
            texels: nodes.iter().map(|n| [n[SHIFT], n[SIGMA]]).collect(),
            sigma_max: nodes.iter().fold(0.0f64, |m, n| m.max(n[SIGMA] as f64)),
            columns,
        }
    }

    fn row(theta_i: f64) -> (usize, f32) {
        locate((theta_i + FRAC_PI_2) / PI, THETA_I_NODES)
    }

    /// The shift and spread at (θ_i, h), blended bilinearly in (θ_i, γ).
    #[inline]
    pub fn at(&self, theta_i: f64, h: f64) -> RoughAzimuth {
        let gamma = asin_fast(h.abs().min(1.0));
        let column = locate(gamma / FRAC_PI_2, GAMMA_NODES);
        let [shift, sigma] = blend(&self.texels, GAMMA_NODES, Self::row(theta_i), column);
        RoughAzimuth {
            shift: if h < 0.0 { -shift } else { shift },
            sigma,
        }
    }

    /// The mean and standard deviation of the exit sine over the light leaving at azimuth φ
    /// for light at θ_i, blended bilinearly.
    pub fn column_sine(&self, theta_i: f64, phi: f64) -> (f64, f64) {
        let column = locate(crate::frame::wrap_pi(phi).abs() / PI, COLUMNS);
        let [mean, sd] = blend(&self.columns, COLUMNS, Self::row(theta_i), column);
        (mean, sd)
    }

    /// The largest spread of any offset.
    pub fn sigma_max(&self) -> f64 {
        self.sigma_max
    }
}

/// One θ_i row's columns from its `nodes`: the exit sine's moments over the light of every
/// offset that reaches the column, each offset weighted by its transmitted share and its
/// Gaussian in φ there, its exit sine taken given φ (each offset's (x, φ) a bivariate normal
/// with the quadrature's covariance: the light an offset sends away from its Φ leaves at
/// another inclination). Both signs of h; γ stepped [`SUBSTEPS`] times between nodes, the
/// nodes' channels linear between.
fn fill_columns(nodes: &[Node], row: &mut [[f32; 2]]) {
    let mut steps = Vec::with_capacity(GAMMA_NODES * SUBSTEPS);
    for k in 0..GAMMA_NODES - 1 {
        for j in 0..SUBSTEPS {
            let t = (j as f64 + 0.5) / SUBSTEPS as f64;
            let lerp = |l: usize| nodes[k][l] as f64 * (1.0 - t) + nodes[k + 1][l] as f64 * t;
            let gamma = gamma_at(k) * (1.0 - t) + gamma_at(k + 1) * t;
            let weight = lerp(TRANSMITTED) * gamma.cos();
            if weight > 0.0 {
                let sigma = lerp(SIGMA);
                // x given φ, a bivariate normal per offset: mean x̄ + c (φ − Φ) / σ², variance
                // σ_x² − c² / σ².
                let covariance = lerp(COVARIANCE);
                let slope = covariance / (sigma * sigma);
                let sd = lerp(SIN_SD);
                let conditional = (sd * sd - slope * covariance).max(0.0);
                steps.push([lerp(PHI), sigma, weight, lerp(SIN_MEAN), slope, conditional]);
            }
        }
    }
    for (j, column) in row.iter_mut().enumerate() {
        let phi = PI * j as f64 / (COLUMNS - 1) as f64;
        let mut sums = [0.0f64; 3];
        for &[centre, sigma, weight, mean, slope, conditional] in &steps {
            // Offset h leaves about Φ(1, h), its mirror −h about −Φ(1, h) (where the
            // covariance changes sign with φ − Φ's).
            for c in [centre, -centre] {
                let d = crate::frame::wrap_pi(phi - c);
                let z = d / sigma;
                if z.abs() < 8.0 {
                    let w = weight * (-0.5 * z * z).exp() / sigma;
                    let m = mean + slope * d * c.signum();
                    sums[0] += w;
                    sums[1] += w * m;
                    sums[2] += w * (conditional + m * m);
                }
            }
        }
        let (mean, sd) = if sums[0] > 0.0 {
            let mean = sums[1] / sums[0];
            (mean, (sums[2] / sums[0] - mean * mean).max(0.0).sqrt())
        } else {
            // No offset's light reaches the column: the edge offset's lobe.
            let edge = &nodes[GAMMA_NODES - 1];
            (edge[SIN_MEAN] as f64, edge[SIN_SD] as f64)
        };
        *column = [mean as f32, sd.max(LEAST_SIN_SD) as f32];
    }
}

/// Both channels of `texels` (rows of `stride`) at the cells (i, f_i) and (k, f_k), blended
/// bilinearly in f64.
#[inline]
fn blend(
    texels: &[[f32; 2]],
    stride: usize,
    (i, fi): (usize, f32),
    (k, fk): (usize, f32),
) -> [f64; 2] {
    let at = i * stride + k;
    let (fi, fk) = (fi as f64, fk as f64);
    let node = |n: usize, l: usize| texels[n][l] as f64;
    let mut out = [0.0; 2];
    for (l, o) in out.iter_mut().enumerate() {
        let low = node(at, l) + fk * (node(at + 1, l) - node(at, l));
        let high = node(at + stride, l) + fk * (node(at + stride + 1, l) - node(at + stride, l));
        *o = low + fi * (high - low);
    }
    out
}

/// Bravais' Φ(1, h) at θ_d = −θ_i, from which the table's shift is measured: where N_TT reads
/// it whatever θ_o ([`crate::azimuthal::AzimuthalScattering::lobe_eta_prime`]).
fn bravais(eta: f64, theta_i: f64, h: f64) -> f64 {
    azimuthal_deflection(1, h, eta_prime(eta, theta_i))
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

    /// Every node spreads its light: where the rule lets one (entry, exit) pair through
    /// (here at h = ±0.999, η 1.67, α 7.7°, β 0.016 — a configuration the finiteness test
    /// drew), the quadrature's σ is 0, and N_TT's Gaussian there would be 0/0.
    #[test]
    fn every_node_spreads_its_light() {
        let (eta, alpha, beta) = (1.670571912434109, 0.13412231792810372, 0.016424339525713382);
        let table = RoughTtTable::build(eta, alpha, beta);
        let least = LEAST_SIGMA_SHARE * beta * std::f64::consts::FRAC_1_SQRT_2;
        for theta_i in [-1.2, -0.5, 0.0, 0.49, 1.0] {
            for k in 0..=2000 {
                let h = -1.0 + k as f64 / 1000.0;
                let at = table.at(theta_i, h);
                assert!(
                    at.sigma >= least * (1.0 - 1e-6) && at.shift.is_finite(),
                    "θ_i {theta_i} h {h}: {at:?}"
                );
            }
        }
    }

    /// The signs that make the chord's and the exit's in-plane angles positive on the smooth
    /// path at offset 0.25 s, traced; `None` where that path is blocked.
    fn smooth_in_plane_signs(tilt: Tilt, theta_i: f64, eta: f64, s: f64) -> Option<(f64, f64)> {
        let entry = AtScale::outside(tilt, incident(theta_i, 0.25 * s)).ok()?;
        let chord = entry.refract(eta).ok()?;
        let exit = AtScale::inside(tilt, nusselt::propagate(chord))
            .ok()?
            .refract(eta)
            .ok()?;
        Some((chord.1.signum(), exit.1.signum()))
    }

    /// The sign convention of the in-plane angles is the smooth path's wherever that path at a
    /// small offset leaves, so the quadrature keeps it where the path is blocked.
    #[test]
    fn in_plane_signs_follow_the_smooth_path() {
        let (mut open, mut blocked) = (0, 0);
        for eta in [1.2, 1.55, 2.0] {
            for i in 0..60 {
                for alpha_deg in -10..=10 {
                    let theta_i = -1.5 + 3.0 * i as f64 / 59.0;
                    let tilt = Tilt::new((alpha_deg as f64).to_radians());
                    for s in [-1.0, 1.0] {
                        match smooth_in_plane_signs(tilt, theta_i, eta, s) {
                            Some(signs) => {
                                assert_eq!(
                                    signs,
                                    in_plane_signs(s),
                                    "η {eta} θ_i {theta_i} α {alpha_deg}°"
                                );
                                open += 1;
                            }
                            None => blocked += 1,
                        }
                    }
                }
            }
        }
        assert!(open > 1000 && blocked > 100, "{open} {blocked}");
    }

    /// Where the smooth path at small offsets is blocked (θ_i 1.1, α +4°), the rough surface
    /// still lets TT out, at an azimuth and spread the quadrature finds.
    #[test]
    fn light_leaves_where_the_smooth_path_is_blocked() {
        let (theta_i, alpha) = (1.1, 4f64.to_radians());
        assert!(tilted_exit(1, theta_i, alpha, 1.55, 0.25).is_none());
        let exit = rough_tt_exit(theta_i, alpha, 1.55, 0.04, 0.25, TABLE_RULE).expect("it leaves");
        assert!(exit.transmitted > 0.0 && exit.sigma > 0.0, "{exit:?}");
    }
}
