//! Statistical checks of a model's importance sampling, shared by the models' tests.
//!
//! [`chi2_test`] is the χ² goodness-of-fit test of pbrt-v4 and Mitsuba 3: draw samples into a
//! (θ, φ) histogram, integrate `pdf` over each bin for the expected counts, pool the bins
//! expecting fewer than 5, and reject when the p-value falls below 0.01 corrected for the
//! number of cases tested (Šidák). [`check_weights`] checks that every sample reports the
//! density `pdf` gives and the weight S / pdf.

use crate::geometry::frame::FiberAngles;
use crate::math::GaussLegendre;
use crate::model::FiberModel;
use rand_core::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;
use std::f64::consts::PI;

/// Significance of the whole family of χ² cases.
pub(crate) const SIGNIFICANCE: f64 = 0.01;
/// Bins expecting fewer samples than this are pooled (the usual χ² validity rule).
const MIN_EXPECTED: f64 = 5.0;
/// Gauss–Legendre nodes per bin and dimension when integrating the pdf.
const NODES_PER_BIN: usize = 5;
/// θ panels per bin when integrating the pdf (lobes as narrow as β(η − 1) = 0.011 rad).
const THETA_PANELS_PER_BIN: usize = 6;

/// Four uniform numbers in [0, 1) from a generator.
pub(crate) fn uniform4(rng: &mut Pcg64Mcg) -> [f64; 4] {
    std::array::from_fn(|_| (rng.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64))
}

/// A (θ, φ) histogram of directions over the whole sphere, θ ∈ [−π/2, π/2], φ ∈ (−π, π].
struct Grid {
    theta_bins: usize,
    phi_bins: usize,
}

impl Grid {
    fn index(&self, wo: FiberAngles) -> usize {
        let t = ((wo.theta + 0.5 * PI) / PI * self.theta_bins as f64) as usize;
        let p = ((wo.phi + PI) / (2.0 * PI) * self.phi_bins as f64) as usize;
        t.min(self.theta_bins - 1) * self.phi_bins + p.min(self.phi_bins - 1)
    }

    /// ∫∫ pdf cos θ dθ dφ over every bin, θ split into [`THETA_PANELS_PER_BIN`] panels so that
    /// longitudinal lobes far narrower than a bin are still integrated exactly.
    fn integrate(&self, pdf: impl Fn(FiberAngles) -> f64) -> Vec<f64> {
        let rule = GaussLegendre::cached(NODES_PER_BIN);
        let dt = PI / self.theta_bins as f64;
        let panel = dt / THETA_PANELS_PER_BIN as f64;
        let dp = 2.0 * PI / self.phi_bins as f64;
        let mut out = Vec::with_capacity(self.theta_bins * self.phi_bins);
        for i in 0..self.theta_bins {
            let t0 = -0.5 * PI + i as f64 * dt;
            for j in 0..self.phi_bins {
                let p0 = -PI + j as f64 * dp;
                let v = (0..THETA_PANELS_PER_BIN)
                    .map(|k| {
                        let a = t0 + k as f64 * panel;
                        rule.integrate(a, a + panel, |theta| {
                            theta.cos()
                                * rule
                                    .integrate(p0, p0 + dp, |phi| pdf(FiberAngles::new(theta, phi)))
                        })
                    })
                    .sum();
                out.push(v);
            }
        }
        out
    }
}

/// The χ² test of `model`'s sampling for light from `wi`, with `samples` draws from a
/// generator seeded by `seed` into `bins` = (θ bins, φ bins). `cases` is the number of χ²
/// tests in the family, for the Šidák correction. Returns the p-value, or why it failed.
pub(crate) fn chi2_test(
    model: &dyn FiberModel,
    wi: FiberAngles,
    samples: usize,
    seed: u64,
    bins: (usize, usize),
    cases: usize,
) -> Result<f64, String> {
    let grid = Grid {
        theta_bins: bins.0,
        phi_bins: bins.1,
    };
    let mut rng = Pcg64Mcg::seed_from_u64(seed);
    let mut observed = vec![0.0; bins.0 * bins.1];
    for _ in 0..samples {
        if let Some(s) = model.sample(wi, uniform4(&mut rng)) {
            observed[grid.index(s.wo)] += 1.0;
        }
    }
    let expected: Vec<f64> = grid
        .integrate(|wo| model.pdf(wi, wo))
        .into_iter()
        .map(|p| p * samples as f64)
        .collect();
    let (chi2, dof) = pooled_chi2(&observed, &expected, samples)?;
    let p_value = chi2_survival(chi2, dof as f64);
    let alpha = 1.0 - (1.0 - SIGNIFICANCE).powf(1.0 / cases as f64);
    if p_value < alpha {
        return Err(format!(
            "{}: χ² = {chi2:.1} with {dof} degrees of freedom, p = {p_value:.3e} < {alpha:.3e} \
             (θ_i = {}, φ_i = {}); worst bins: {}",
            model.name(),
            wi.theta,
            wi.phi,
            worst_bins(&observed, &expected, &grid)
        ));
    }
    Ok(p_value)
}

/// χ² over the bins expecting at least [`MIN_EXPECTED`], plus one pooled cell for the rest;
/// fails outright when a bin the pdf gives (numerically) nothing receives samples.
fn pooled_chi2(observed: &[f64], expected: &[f64], samples: usize) -> Result<(f64, usize), String> {
    let (mut chi2, mut cells) = (0.0, 0usize);
    let (mut pool_o, mut pool_e) = (0.0, 0.0);
    for (k, (&o, &e)) in observed.iter().zip(expected).enumerate() {
        if e <= 0.0 && o > 1e-5 * samples as f64 {
            return Err(format!(
                "bin {k} received {o} samples where the pdf integrates to {e}"
            ));
        }
        if e < MIN_EXPECTED {
            pool_o += o;
            pool_e += e;
        } else {
            chi2 += (o - e) * (o - e) / e;
            cells += 1;
        }
    }
    if pool_e > 0.0 {
        chi2 += (pool_o - pool_e) * (pool_o - pool_e) / pool_e;
        cells += 1;
    }
    Ok((chi2, cells.saturating_sub(1).max(1)))
}

fn worst_bins(observed: &[f64], expected: &[f64], grid: &Grid) -> String {
    let mut terms: Vec<(f64, usize)> = observed
        .iter()
        .zip(expected)
        .enumerate()
        .filter(|(_, (_, e))| **e >= MIN_EXPECTED)
        .map(|(k, (o, e))| ((o - e) * (o - e) / e, k))
        .collect();
    terms.sort_by(|a, b| b.0.total_cmp(&a.0));
    terms
        .iter()
        .take(4)
        .map(|&(term, k)| {
            let (i, j) = (k / grid.phi_bins, k % grid.phi_bins);
            format!(
                "(θ bin {i}, φ bin {j}: observed {}, expected {:.1}, term {term:.1})",
                observed[k], expected[k]
            )
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// Checks every `stride`-th of `samples` draws: its pdf equals `model.pdf` and its weight
/// equals eval(ω_i, ω_o).total() / pdf, both to `tolerance` relative.
pub(crate) fn check_weights(
    model: &dyn FiberModel,
    wi: FiberAngles,
    samples: usize,
    seed: u64,
    tolerance: f64,
) -> Result<(), String> {
    let mut rng = Pcg64Mcg::seed_from_u64(seed);
    for n in 0..samples {
        let u = uniform4(&mut rng);
        let Some(s) = model.sample(wi, u) else {
            continue;
        };
        let pdf = model.pdf(wi, s.wo);
        let weight = model.eval(wi, s.wo).total() / pdf;
        let close = |a: f64, b: f64| (a - b).abs() <= tolerance * a.abs().max(b.abs());
        let weight_ok = (0..3).all(|c| close(s.weight[c], weight[c]));
        if !close(s.pdf, pdf) || !weight_ok {
            return Err(format!(
                "sample {n} (u = {u:?}) at {:?}: pdf {} vs {pdf}, weight {} vs {weight}",
                s.wo, s.pdf, s.weight
            ));
        }
    }
    Ok(())
}

/// P(X ≥ x) for X χ²-distributed with `dof` degrees of freedom: Q(dof/2, x/2).
pub(crate) fn chi2_survival(x: f64, dof: f64) -> f64 {
    gamma_q(0.5 * dof, 0.5 * x)
}

/// The regularised upper incomplete gamma function Q(a, x), by its series below x = a + 1
/// and Lentz's continued fraction above (Numerical Recipes §6.2).
fn gamma_q(a: f64, x: f64) -> f64 {
    if x <= 0.0 {
        return 1.0;
    }
    let log_prefix = a * x.ln() - x - ln_gamma(a);
    if x < a + 1.0 {
        let (mut term, mut sum, mut n) = (1.0 / a, 1.0 / a, a);
        while term.abs() > 1e-16 * sum.abs() {
            n += 1.0;
            term *= x / n;
            sum += term;
        }
        1.0 - sum * log_prefix.exp()
    } else {
        let tiny = 1e-300;
        let mut b = x + 1.0 - a;
        let mut c = 1.0 / tiny;
        let mut d = 1.0 / b;
        let mut h = d;
        for i in 1..10_000 {
            let an = -(i as f64) * (i as f64 - a);
            b += 2.0;
            d = an * d + b;
            d = if d.abs() < tiny { tiny } else { d };
            c = b + an / c;
            c = if c.abs() < tiny { tiny } else { c };
            d = 1.0 / d;
            let delta = d * c;
            h *= delta;
            if (delta - 1.0).abs() < 1e-16 {
                break;
            }
        }
        h * log_prefix.exp()
    }
}

/// ln Γ(a) for a > 0 by the Lanczos approximation (g = 7, 9 terms), ~1e-15 relative.
fn ln_gamma(a: f64) -> f64 {
    const C: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    if a < 0.5 {
        return (PI / (PI * a).sin()).ln() - ln_gamma(1.0 - a);
    }
    let a = a - 1.0;
    let t = a + 7.5;
    let series = C[1..]
        .iter()
        .enumerate()
        .fold(C[0], |s, (k, c)| s + c / (a + k as f64 + 1.0));
    0.5 * (2.0 * PI).ln() + (a + 0.5) * t.ln() - t + series.ln()
}

/// The gap between a sampler and the density its `pdf` reports: the total-variation distance
/// ½ Σ |observed − expected| over a (θ, φ) histogram of `samples` draws (probabilities per
/// bin), with the draws' mean fixed-point iteration count.
pub(crate) struct SamplingGap {
    pub total_variation: f64,
    pub mean_iterations: f64,
    /// The total variation the same number of draws from the reported density itself would
    /// show, ≈ ½ Σ √(2 p (1 − p) / (π N)): the noise floor.
    pub noise_floor: f64,
}

pub(crate) fn sampling_gap(
    model: &dyn FiberModel,
    wi: FiberAngles,
    samples: usize,
    seed: u64,
    bins: (usize, usize),
) -> SamplingGap {
    let grid = Grid {
        theta_bins: bins.0,
        phi_bins: bins.1,
    };
    let mut rng = Pcg64Mcg::seed_from_u64(seed);
    let mut observed = vec![0.0; bins.0 * bins.1];
    let mut iterations = 0u64;
    for _ in 0..samples {
        if let Some(s) = model.sample(wi, uniform4(&mut rng)) {
            observed[grid.index(s.wo)] += 1.0 / samples as f64;
            iterations += s.iterations as u64;
        }
    }
    let expected = grid.integrate(|wo| model.pdf(wi, wo));
    let n = samples as f64;
    let total_variation = 0.5
        * observed
            .iter()
            .zip(&expected)
            .map(|(o, e)| (o - e).abs())
            .sum::<f64>();
    let noise_floor = 0.5
        * expected
            .iter()
            .map(|&p| (2.0 * p.clamp(0.0, 1.0) * (1.0 - p.clamp(0.0, 1.0)) / (PI * n)).sqrt())
            .sum::<f64>();
    SamplingGap {
        total_variation,
        mean_iterations: iterations as f64 / n,
        noise_floor,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chi2_survival_matches_closed_forms() {
        // Two degrees of freedom: P(X ≥ x) = e^{−x/2}.
        for &x in &[0.1, 1.0, 5.0, 40.0] {
            assert!((chi2_survival(x, 2.0) - (-0.5 * x).exp()).abs() < 1e-13);
        }
        // ln Γ at integers and a half.
        assert!((ln_gamma(5.0) - 24f64.ln()).abs() < 1e-13);
        assert!((ln_gamma(0.5) - PI.sqrt().ln()).abs() < 1e-13);
        // The median of χ² with 1000 degrees of freedom is about 999.33.
        assert!((chi2_survival(999.3333, 1000.0) - 0.5).abs() < 1e-3);
    }
}
