//! Sweep configurations: the paper's suite, the `small` subset, and JSON files of configs.
//!
//! A configuration file is a JSON list of objects with exactly these keys (the `"params"` keys
//! of `sim.json`, docs/conventions.md §5):
//!
//! ```json
//! [
//!   {"theta_i": 0.5, "alpha_deg": -2, "beta": 0.04, "eta": 1.55, "mu_a": 0.25},
//!   {"theta_i": 1.1, "alpha_deg": 4, "beta": 0.08, "eta": 1.165, "mu_a": [0.12, 0.25, 0.5]}
//! ]
//! ```
//!
//! θ_i in radians, α in degrees, μ_a one value (grey) or `[r, g, b]`, per unit radius.

use crate::params::{SimError, SimParams};
use cuticle_fiber::LatLongGrid;
use cuticle_fiber::ranges::short;
use serde::{Deserialize, Deserializer, Serialize};

/// One point of a sweep; rays, seed and grid are the sweep's.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SweepConfig {
    pub theta_i: f64,
    pub alpha_deg: f64,
    pub beta: f64,
    pub eta: f64,
    #[serde(deserialize_with = "grey_or_rgb")]
    pub mu_a: [f64; 3],
}

fn grey_or_rgb<'de, D: Deserializer<'de>>(d: D) -> Result<[f64; 3], D::Error> {
    #[derive(Deserialize)]
    #[serde(untagged)]
    enum MuA {
        Grey(f64),
        Rgb([f64; 3]),
    }
    Ok(match MuA::deserialize(d)? {
        MuA::Grey(v) => [v; 3],
        MuA::Rgb(v) => v,
    })
}

impl SweepConfig {
    /// The configuration's folder name, from its parameters in shortest round-trip form, e.g.
    /// `ti0.75_a-2_b0.04_mu0.25_eta1.55` (μ_a as `mu0.1-0.2-0.3` when the channels differ),
    /// with an exponent for numbers far from 1 (`mu1e-300`) so that no name runs long.
    pub fn dir_name(&self) -> String {
        let [r, g, b] = self.mu_a.map(short);
        let mu = if r == g && g == b {
            r
        } else {
            format!("{r}-{g}-{b}")
        };
        format!(
            "ti{}_a{}_b{}_mu{}_eta{}",
            short(self.theta_i),
            short(self.alpha_deg),
            short(self.beta),
            mu,
            short(self.eta)
        )
    }

    /// The simulation parameters of this configuration.
    pub fn params(&self, rays: u64, seed: u64, grid: LatLongGrid) -> SimParams {
        SimParams {
            theta_i: self.theta_i,
            alpha: self.alpha_deg.to_radians(),
            beta: self.beta,
            eta: self.eta,
            mu_a: self.mu_a,
            rays,
            seed,
            grid,
        }
    }
}

/// The product θ_i × α × μ_a × β × η, θ_i outermost: a configuration's index in it is its
/// place in the sweep (and decides its shard).
fn product(
    theta: &[f64],
    alpha: &[f64],
    mu: &[f64],
    beta: &[f64],
    eta: &[f64],
) -> Vec<SweepConfig> {
    let mut out = Vec::with_capacity(theta.len() * alpha.len() * mu.len() * beta.len() * eta.len());
    for &theta_i in theta {
        for &alpha_deg in alpha {
            for &m in mu {
                for &beta in beta {
                    for &eta in eta {
                        out.push(SweepConfig {
                            theta_i,
                            alpha_deg,
                            beta,
                            eta,
                            mu_a: [m; 3],
                        });
                    }
                }
            }
        }
    }
    out
}

/// d'Eon et al. 2014 §2.1's suite: 11 θ_i × 5 α × 14 μ_a × 10 β × 2 η = 15,400 configurations.
pub fn paper() -> Vec<SweepConfig> {
    product(
        &[0.0, 0.25, 0.5, 0.75, 1.0, 1.1, 1.2, 1.3, 1.4, 1.5, 1.55],
        &[0.0, -2.0, 2.0, -4.0, 4.0],
        &[
            0.0, 0.003, 0.006, 0.015, 0.03, 0.06, 0.12, 0.25, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0,
        ],
        &[0.0025, 0.005, 0.01, 0.02, 0.03, 0.04, 0.06, 0.08, 0.15, 0.3],
        &[1.55, 1.55 / 1.33],
    )
}

/// The issue's `small` grid: θ_i ∈ {0.25, 0.75, 1.1, 1.3} × α ∈ {−4°, −2°, 0, 2°, 4°} ×
/// μ_a ∈ {0, 0.25} × β ∈ {0.02, 0.04, 0.08} × η = 1.55: 120 configurations.
pub fn small() -> Vec<SweepConfig> {
    product(
        &[0.25, 0.75, 1.1, 1.3],
        &[-4.0, -2.0, 0.0, 2.0, 4.0],
        &[0.0, 0.25],
        &[0.02, 0.04, 0.08],
        &[1.55],
    )
}

/// Configurations from a JSON list (format in the module docs).
pub fn from_json(text: &str) -> Result<Vec<SweepConfig>, SimError> {
    serde_json::from_str(text).map_err(|e| SimError::InvalidParam(format!("config list: {e}")))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grids_have_the_stated_sizes_and_unique_names() {
        for (grid, n) in [(paper(), 15_400), (small(), 120)] {
            assert_eq!(grid.len(), n);
            let mut names: Vec<_> = grid.iter().map(SweepConfig::dir_name).collect();
            names.sort();
            names.dedup();
            assert_eq!(names.len(), n);
        }
        assert_eq!(small()[0].dir_name(), "ti0.25_a-4_b0.02_mu0_eta1.55");
        let tiny = SweepConfig {
            mu_a: [1e-300; 3],
            ..small()[0].clone()
        };
        assert_eq!(tiny.dir_name(), "ti0.25_a-4_b0.02_mu1e-300_eta1.55");
    }

    #[test]
    fn reads_grey_and_rgb_absorption_and_rejects_unknown_keys() {
        let c = from_json(
            r#"[{"theta_i": 0.5, "alpha_deg": -2, "beta": 0.04, "eta": 1.55, "mu_a": 0.25},
                {"theta_i": 1.1, "alpha_deg": 4, "beta": 0.08, "eta": 1.2, "mu_a": [0.1, 0.2, 0.3]}]"#,
        )
        .unwrap();
        assert_eq!(c[0].mu_a, [0.25; 3]);
        assert_eq!(c[1].dir_name(), "ti1.1_a4_b0.08_mu0.1-0.2-0.3_eta1.2");
        assert!(
            from_json(r#"[{"theta_i": 0.5, "alpha": 1, "beta": 0.04, "eta": 1.55, "mu_a": 0}]"#)
                .is_err()
        );
    }
}
