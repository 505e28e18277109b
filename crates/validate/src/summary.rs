//! The figures of a whole validation: one [`Row`] per (configuration, model, lobe), written as
//! CSV, and the Markdown report's summary tables (by lobe, θ_i, α, β, per model), with the noise
//! floor beside every model figure where the validation has two runs per configuration
//! ([`crate::noise`]), and the per-lobe verdicts ([`crate::summary_verdict`]).

use crate::metrics::LobeFigures;
use crate::sweep_dir::SimConfig;
use cuticle_fiber::Lobe;
use cuticle_fiber::ModelId;
use serde::Serialize;
use std::collections::BTreeMap;
use std::fmt::Write;

/// One (configuration, model, lobe) figure set.
#[derive(Clone, Debug, Serialize)]
pub struct Row {
    pub config: String,
    pub theta_i: f64,
    pub alpha_deg: f64,
    pub beta: f64,
    pub eta: f64,
    pub mu_a: f64,
    pub model: &'static str,
    pub lobe: &'static str,
    #[serde(flatten)]
    pub figures: LobeFigures,
}

impl Row {
    pub fn new(config: &SimConfig, model: ModelId, lobe: Lobe, figures: LobeFigures) -> Self {
        Self {
            config: config.name.clone(),
            theta_i: config.theta_i,
            alpha_deg: config.alpha_deg,
            beta: config.beta,
            eta: config.eta,
            mu_a: config.mu_a_mean(),
            model: model.name(),
            lobe: lobe.name(),
            figures,
        }
    }
}

fn opt(v: Option<f64>) -> String {
    v.map(|x| format!("{x:.6}")).unwrap_or_default()
}

/// Every row as CSV; empty cells where a figure is undefined (a black simulated lobe).
pub fn csv(rows: &[Row]) -> String {
    let mut s = String::from(
        "config,theta_i,alpha_deg,beta,eta,mu_a,model,lobe,relative_l1,energy_model,energy_sim,energy_difference,peak_theta_error_deg,seed_to_seed_l1,noise_floor,residual_l1\n",
    );
    for r in rows {
        let f = &r.figures;
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{},{},{:.6},{:.6},{:.6},{},{},{},{}",
            r.config,
            r.theta_i,
            r.alpha_deg,
            r.beta,
            r.eta,
            r.mu_a,
            r.model,
            r.lobe,
            opt(f.relative_l1),
            f.energy_model,
            f.energy_sim,
            f.energy_difference(),
            opt(f.peak_theta_error.map(f64::to_degrees)),
            opt(f.seed_to_seed_l1),
            opt(f.noise_floor()),
            opt(f.residual_l1()),
        );
    }
    s
}

/// Simulated lobe energy below which a lobe's relative L1 is left out of the summary tables
/// (it stays in the CSV): where total internal reflection empties a lobe at grazing θ_i, Σ|sim|
/// is Monte Carlo dust and the ratio runs to thousands, swamping every mean.
pub const MIN_SIM_ENERGY: f64 = 1e-3;

/// The relative L1 a summary counts: `None` for a lobe the simulation leaves (nearly) black.
pub fn counted_l1(r: &Row) -> Option<f64> {
    counted(r, r.figures.relative_l1)
}

/// The noise floor of a counted figure.
pub fn counted_floor(r: &Row) -> Option<f64> {
    counted(r, r.figures.noise_floor())
}

/// The noise-corrected residual of a counted figure.
pub fn counted_residual(r: &Row) -> Option<f64> {
    counted(r, r.figures.residual_l1())
}

fn counted(r: &Row, v: Option<f64>) -> Option<f64> {
    (r.figures.energy_sim >= MIN_SIM_ENERGY).then_some(v)?
}

/// The rows whose model image is not finite: its energy or its L1 is NaN or infinite (a
/// model that returned NaN somewhere on the sphere), which no median may hide.
pub fn non_finite(rows: &[Row]) -> Vec<&Row> {
    rows.iter()
        .filter(|r| {
            !r.figures.energy_model.is_finite()
                || r.figures.relative_l1.is_some_and(|l1| !l1.is_finite())
        })
        .collect()
}

/// Whether the rows carry a noise floor (the validation had two runs per configuration).
pub fn has_noise(rows: &[Row]) -> bool {
    rows.iter().any(|r| r.figures.seed_to_seed_l1.is_some())
}

/// Mean and median of the defined values.
pub fn mean_median(values: impl IntoIterator<Item = Option<f64>>) -> Option<(f64, f64)> {
    let mut v: Vec<f64> = values.into_iter().flatten().collect();
    if v.is_empty() {
        return None;
    }
    v.sort_by(f64::total_cmp);
    let n = v.len();
    let median = if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    };
    Some((v.iter().sum::<f64>() / n as f64, median))
}

/// Lobes the report tabulates by parameter (the ones the models differ in).
const MAIN_LOBES: [&str; 3] = ["R", "TT", "TRT"];
const ALL_LOBES: [&str; 5] = ["R", "TT", "TRT", "TRRT", "rest"];

fn models_in(rows: &[Row]) -> Vec<&'static str> {
    let mut m: Vec<&'static str> = Vec::new();
    for r in rows {
        if !m.contains(&r.model) {
            m.push(r.model);
        }
    }
    m
}

fn cell(v: Option<(f64, f64)>) -> String {
    v.map(|(mean, median)| format!("{mean:.3} / {median:.3}"))
        .unwrap_or_else(|| "–".into())
}

fn median_of(values: impl IntoIterator<Item = Option<f64>>) -> String {
    mean_median(values)
        .map(|(_, median)| format!("{median:.3}"))
        .unwrap_or_else(|| "–".into())
}

/// Per model and lobe: relative L1 (mean / median), with the noise floor, the residual and
/// their ratio (medians) where there is a floor, mean |energy difference|, mean peak error.
fn by_lobe_table(rows: &[Row], out: &mut String) {
    let noise = has_noise(rows);
    out.push_str("| model | lobe | relative L1 (mean / median) |");
    if noise {
        out.push_str(" noise floor (median) | residual (median) | residual / floor (median) |");
    }
    out.push_str(" mean abs energy diff | mean energy sim | peak θ error, deg (mean / median) |\n");
    out.push_str(&"|---".repeat(if noise { 9 } else { 6 }));
    out.push_str("|\n");
    for model in models_in(rows) {
        for lobe in ALL_LOBES {
            let sel: Vec<&Row> = rows
                .iter()
                .filter(|r| r.model == model && r.lobe == lobe)
                .collect();
            let l1 = mean_median(sel.iter().map(|r| counted_l1(r)));
            let de = mean_median(
                sel.iter()
                    .map(|r| Some(r.figures.energy_difference().abs())),
            );
            let es = mean_median(sel.iter().map(|r| Some(r.figures.energy_sim)));
            let pk = mean_median(
                sel.iter()
                    .map(|r| r.figures.peak_theta_error.map(f64::to_degrees)),
            );
            let _ = write!(out, "| {model} | {lobe} | {} |", cell(l1));
            if noise {
                let ratio = sel.iter().map(|r| {
                    let floor = counted_floor(r)?;
                    (floor > 0.0).then(|| counted_residual(r).map(|x| x / floor))?
                });
                let _ = write!(
                    out,
                    " {} | {} | {} |",
                    median_of(sel.iter().map(|r| counted_floor(r))),
                    median_of(sel.iter().map(|r| counted_residual(r))),
                    median_of(ratio)
                );
            }
            let _ = writeln!(
                out,
                " {:.4} | {:.4} | {} |",
                de.map_or(0.0, |v| v.0),
                es.map_or(0.0, |v| v.0),
                cell(pk)
            );
        }
    }
}

/// R, TT and TRT per model, grouped by one parameter: relative L1 (mean / median), or, where
/// there is a noise floor, the floor of each lobe beside each model's median L1 and residual.
fn by_parameter_table(rows: &[Row], name: &str, key: fn(&Row) -> f64, out: &mut String) {
    let models = models_in(rows);
    let noise = has_noise(rows);
    let _ = write!(out, "| {name} |");
    for l in MAIN_LOBES {
        if noise {
            let _ = write!(out, " {l} floor |");
        }
        for m in &models {
            let _ = write!(out, " {m} {l} |");
        }
    }
    out.push('\n');
    let columns = MAIN_LOBES.len() * (models.len() + usize::from(noise));
    out.push_str(&"|---".repeat(1 + columns));
    out.push_str("|\n");
    let mut groups: BTreeMap<i64, f64> = BTreeMap::new();
    for r in rows {
        groups.insert((key(r) * 1e6).round() as i64, key(r));
    }
    for value in groups.values() {
        let _ = write!(out, "| {value} |");
        for l in MAIN_LOBES {
            let of = |m: &'static str| {
                rows.iter()
                    .filter(move |r| r.model == m && r.lobe == l && key(r) == *value)
            };
            if noise {
                let floor = models.first().map(|m| median_of(of(m).map(counted_floor)));
                let _ = write!(out, " {} |", floor.unwrap_or_default());
            }
            for m in &models {
                if noise {
                    let _ = write!(
                        out,
                        " {} ({}) |",
                        median_of(of(m).map(counted_l1)),
                        median_of(of(m).map(counted_residual))
                    );
                } else {
                    let _ = write!(out, " {} |", cell(mean_median(of(m).map(counted_l1))));
                }
            }
        }
        out.push('\n');
    }
}

/// The Markdown report: summary tables and the per-lobe verdict.
pub fn markdown(rows: &[Row], header: &str) -> String {
    let mut out = String::from(header);
    let _ = write!(
        out,
        "\n## Per model and lobe\n\nRelative L1 = Σ|model − sim|·Ω / Σ|sim|·Ω per lobe image, left out of these tables (not the CSV) where the simulated lobe's energy is below {MIN_SIM_ENERGY}; energies are ∫ S dω (channel mean); the peak θ error is the density-weighted mean over bright φ columns (`peak.rs`).\n\n"
    );
    if has_noise(rows) {
        out.push_str("Each configuration was simulated twice with different seeds; the models are compared with the mean of the two runs. Noise floor = half the seed-to-seed relative L1 (what a perfect model scores against that mean); residual = √(L1² − floor²), the model's own error (`crates/validate/src/noise.rs`). By-parameter tables: each lobe's floor, then each model's median L1 with its median residual in brackets.\n\n");
    }
    by_lobe_table(rows, &mut out);
    type Key = fn(&Row) -> f64;
    let groups: [(&str, Key); 4] = [
        ("θ_i", |r| r.theta_i),
        ("α (deg)", |r| r.alpha_deg),
        ("β", |r| r.beta),
        ("μ_a", |r| r.mu_a),
    ];
    for (name, key) in groups {
        let what = if has_noise(rows) {
            "median; residual in brackets"
        } else {
            "mean / median"
        };
        let _ = write!(out, "\n## Relative L1 by {name} ({what})\n\n");
        by_parameter_table(rows, name, key, &mut out);
    }
    out.push_str(&crate::summary_verdict::verdicts(rows));
    out
}

#[cfg(test)]
mod non_finite_tests {
    use super::*;

    fn row(l1: Option<f64>, energy_model: f64) -> Row {
        Row {
            config: "c".into(),
            theta_i: 0.5,
            alpha_deg: 0.0,
            beta: 0.04,
            eta: 1.55,
            mu_a: 0.0,
            model: "m",
            lobe: "TT",
            figures: LobeFigures {
                relative_l1: l1,
                energy_model,
                energy_sim: 0.5,
                peak_theta_error: None,
                seed_to_seed_l1: None,
            },
        }
    }

    /// A NaN L1 or model energy is reported; a black simulated lobe (no L1) is not.
    #[test]
    fn non_finite_finds_nan_models_only() {
        let rows = [
            row(Some(0.05), 0.5),
            row(Some(f64::NAN), 0.5),
            row(None, 0.5),
            row(Some(0.1), f64::NAN),
            row(Some(f64::INFINITY), 0.5),
        ];
        let bad = non_finite(&rows);
        assert_eq!(bad.len(), 3);
        assert!(
            bad.iter().all(|r| !r.figures.energy_model.is_finite()
                || !r.figures.relative_l1.unwrap().is_finite())
        );
    }
}
