//! The figures of a whole validation: one [`Row`] per (configuration, model, lobe), written as
//! CSV, and the Markdown report's summary tables (by lobe, θ_i, α, β, per model) with the
//! per-lobe verdict of the non-separable model against d'Eon 2011.

use crate::metrics::LobeFigures;
use crate::models::ModelKind;
use crate::sweep_dir::SimConfig;
use cuticle_fiber::Lobe;
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
    pub fn new(config: &SimConfig, model: ModelKind, lobe: Lobe, figures: LobeFigures) -> Self {
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
        "config,theta_i,alpha_deg,beta,eta,mu_a,model,lobe,relative_l1,energy_model,energy_sim,energy_difference,peak_theta_error_deg\n",
    );
    for r in rows {
        let f = &r.figures;
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{},{},{:.6},{:.6},{:.6},{}",
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
    (r.figures.energy_sim >= MIN_SIM_ENERGY).then_some(r.figures.relative_l1)?
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

/// Per model and lobe: relative L1 (mean / median), mean |energy difference|, mean peak error.
fn by_lobe_table(rows: &[Row], out: &mut String) {
    out.push_str("| model | lobe | relative L1 (mean / median) | mean abs energy diff | mean energy sim | peak θ error, deg (mean / median) |\n|---|---|---|---|---|---|\n");
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
            let _ = writeln!(
                out,
                "| {model} | {lobe} | {} | {:.4} | {:.4} | {} |",
                cell(l1),
                de.map_or(0.0, |v| v.0),
                es.map_or(0.0, |v| v.0),
                cell(pk)
            );
        }
    }
}

/// Relative L1 (mean / median) of R, TT and TRT per model, grouped by one parameter.
fn by_parameter_table(rows: &[Row], name: &str, key: fn(&Row) -> f64, out: &mut String) {
    let models = models_in(rows);
    let _ = write!(out, "| {name} |");
    for m in &models {
        for l in MAIN_LOBES {
            let _ = write!(out, " {m} {l} |");
        }
    }
    out.push('\n');
    out.push_str(&"|---".repeat(1 + models.len() * MAIN_LOBES.len()));
    out.push_str("|\n");
    let mut groups: BTreeMap<i64, f64> = BTreeMap::new();
    for r in rows {
        groups.insert((key(r) * 1e6).round() as i64, key(r));
    }
    for value in groups.values() {
        let _ = write!(out, "| {value} |");
        for m in &models {
            for l in MAIN_LOBES {
                let v = mean_median(
                    rows.iter()
                        .filter(|r| r.model == *m && r.lobe == l && key(r) == *value)
                        .map(counted_l1),
                );
                let _ = write!(out, " {} |", cell(v));
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
    by_lobe_table(rows, &mut out);
    type Key = fn(&Row) -> f64;
    let groups: [(&str, Key); 4] = [
        ("θ_i", |r| r.theta_i),
        ("α (deg)", |r| r.alpha_deg),
        ("β", |r| r.beta),
        ("μ_a", |r| r.mu_a),
    ];
    for (name, key) in groups {
        let _ = write!(out, "\n## Relative L1 by {name} (mean / median)\n\n");
        by_parameter_table(rows, name, key, &mut out);
    }
    out.push_str("\n## Non-separable against d'Eon 2011, per lobe\n\n");
    out.push_str(&crate::summary_verdict::verdict(rows));
    out
}
