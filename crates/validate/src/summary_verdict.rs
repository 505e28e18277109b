//! The per-lobe verdicts of a validation, each a table the report's prose can quote:
//! - the non-separable model against d'Eon 2011, the paper's claim (d'Eon et al. 2014, Figure 7:
//!   its R, TT and TRT lobes follow the simulation more closely whenever the scales are tilted,
//!   except at extreme roughness and grazing θ_i);
//! - the non-separable model with the tilted scales' losses against the paper's form, per
//!   (θ_i, α) cell (issue 14's aim: better in every cell for TT and TRT);
//! - where there is a noise floor, each model's residual against twice the floor (issue 14's
//!   aim for the tilted model: within it for R and TT at θ_i ≤ 1.1).
//!
//! "Beats" is always a smaller relative L1 on the same configuration (equivalently a smaller
//! residual: both models sit on the same floor).

use crate::summary::{Row, counted_floor, counted_l1, counted_residual, has_noise};
use cuticle_fiber::ModelId;
use std::collections::BTreeMap;
use std::fmt::Write;

const NONSEPARABLE: &str = ModelId::NonSeparable.name();
const PAPER: &str = ModelId::NonSeparablePaper.name();
const DEON: &str = ModelId::DEon2011.name();
const LOBES: [&str; 5] = ["R", "TT", "TRT", "TRRT", "rest"];

/// Two models' relative L1 on one configuration and lobe.
pub struct Pair<'a> {
    pub row: &'a Row,
    pub ours: f64,
    pub theirs: f64,
}

/// The configurations where both `ours` and `theirs` have a figure for `lobe`.
pub fn pairs<'a>(rows: &'a [Row], lobe: &str, ours: &str, theirs: &str) -> Vec<Pair<'a>> {
    let other: BTreeMap<&str, f64> = rows
        .iter()
        .filter(|r| r.model == theirs && r.lobe == lobe)
        .filter_map(|r| Some((r.config.as_str(), counted_l1(r)?)))
        .collect();
    rows.iter()
        .filter(|r| r.model == ours && r.lobe == lobe)
        .filter_map(|r| {
            Some(Pair {
                row: r,
                ours: counted_l1(r)?,
                theirs: *other.get(r.config.as_str())?,
            })
        })
        .collect()
}

fn wins(p: &[&Pair]) -> String {
    let n = p.iter().filter(|x| x.ours < x.theirs).count();
    format!("{n}/{}", p.len())
}

fn median(mut v: Vec<f64>) -> Option<f64> {
    if v.is_empty() {
        return None;
    }
    v.sort_by(f64::total_cmp);
    Some(v[v.len() / 2])
}

fn median_ratio(p: &[&Pair]) -> String {
    median(p.iter().map(|x| x.ours / x.theirs).collect())
        .map_or_else(|| "–".into(), |m| format!("{m:.2}"))
}

fn models_present(rows: &[Row], names: &[&str]) -> bool {
    names.iter().all(|n| rows.iter().any(|r| r.model == *n))
}

/// (θ_i, β) cells of tilted configurations where `theirs` wins at least half the time.
fn losing_cells(tilted: &[&Pair]) -> Vec<String> {
    let mut cells: BTreeMap<(i64, i64), (f64, f64, usize, usize)> = BTreeMap::new();
    for p in tilted {
        let key = ((p.row.theta_i * 1e6) as i64, (p.row.beta * 1e6) as i64);
        let c = cells
            .entry(key)
            .or_insert((p.row.theta_i, p.row.beta, 0, 0));
        c.3 += 1;
        if p.ours >= p.theirs {
            c.2 += 1;
        }
    }
    cells
        .values()
        .filter(|c| 2 * c.2 >= c.3)
        .map(|c| format!("θ_i {} β {} ({}/{})", c.0, c.1, c.2, c.3))
        .collect()
}

/// `ours` against `theirs` per lobe: wins on tilted and untilted configurations, the median
/// ratio, and the (θ_i, β) cells `theirs` takes.
pub fn model_against_model(rows: &[Row], ours: &str, theirs: &str) -> String {
    let mut out = format!(
        "| lobe | {ours} wins, tilted (α ≠ 0) | wins, α = 0 | median L1 ratio {ours}/{theirs}, tilted | tilted (θ_i, β) cells where {theirs} wins ≥ half |\n|---|---|---|---|---|\n"
    );
    for lobe in LOBES {
        let all = pairs(rows, lobe, ours, theirs);
        if all.is_empty() {
            continue;
        }
        let tilted: Vec<&Pair> = all.iter().filter(|p| p.row.alpha_deg != 0.0).collect();
        let flat: Vec<&Pair> = all.iter().filter(|p| p.row.alpha_deg == 0.0).collect();
        let cells = losing_cells(&tilted);
        let _ = writeln!(
            out,
            "| {lobe} | {} | {} | {} | {} |",
            wins(&tilted),
            wins(&flat),
            median_ratio(&tilted),
            if cells.is_empty() {
                "none".to_string()
            } else {
                cells.join("; ")
            }
        );
    }
    out
}

/// Per (θ_i, α) cell (all β and μ_a together) and lobe: the two models' median L1, and on how
/// many of the cell's configurations `ours` is the closer; the last row counts the tilted cells
/// whose median `ours` lowers (at α = 0 the tilted and the paper's forms coincide).
pub fn cells_against(rows: &[Row], ours: &str, theirs: &str, lobes: &[&str]) -> String {
    let mut out = String::from("| θ_i | α (deg) |");
    for l in lobes {
        let _ = write!(out, " {l}: {ours} / {theirs} (wins) |");
    }
    out.push('\n');
    out.push_str(&"|---".repeat(2 + lobes.len()));
    out.push_str("|\n");
    let mut cells: BTreeMap<(i64, i64), (f64, f64)> = BTreeMap::new();
    for r in rows.iter().filter(|r| r.model == ours) {
        let key = (
            (r.theta_i * 1e6).round() as i64,
            (r.alpha_deg * 1e6).round() as i64,
        );
        cells.insert(key, (r.theta_i, r.alpha_deg));
    }
    let mut better = vec![(0usize, 0usize); lobes.len()];
    for (theta_i, alpha) in cells.values() {
        let _ = write!(out, "| {theta_i} | {alpha} |");
        for (k, l) in lobes.iter().enumerate() {
            let p: Vec<Pair> = pairs(rows, l, ours, theirs)
                .into_iter()
                .filter(|p| p.row.theta_i == *theta_i && p.row.alpha_deg == *alpha)
                .collect();
            let (a, b) = (
                median(p.iter().map(|x| x.ours).collect()),
                median(p.iter().map(|x| x.theirs).collect()),
            );
            match (a, b) {
                (Some(a), Some(b)) => {
                    let n = p.iter().filter(|x| x.ours < x.theirs).count();
                    // Untilted cells are where the two forms coincide: not counted.
                    if *alpha != 0.0 {
                        better[k].1 += 1;
                        if a < b {
                            better[k].0 += 1;
                        }
                    }
                    let _ = write!(out, " {a:.3} / {b:.3} ({n}/{}) |", p.len());
                }
                _ => out.push_str(" – |"),
            }
        }
        out.push('\n');
    }
    out.push_str("| tilted cells where the median is lower | |");
    for (won, of) in better {
        let _ = write!(out, " {won}/{of} |");
    }
    out.push('\n');
    out
}

/// Per model and lobe: the configurations whose residual is within twice the noise floor, for
/// θ_i ≤ 1.1 and over all, and the median residual / floor.
pub fn against_the_floor(rows: &[Row]) -> String {
    let mut out = String::from(
        "| model | lobe | residual ≤ 2 × floor, θ_i ≤ 1.1 | residual ≤ 2 × floor, all | median residual / floor, θ_i ≤ 1.1 |\n|---|---|---|---|---|\n",
    );
    let mut models: Vec<&str> = Vec::new();
    for r in rows {
        if !models.contains(&r.model) {
            models.push(r.model);
        }
    }
    for m in models {
        for lobe in ["R", "TT", "TRT"] {
            let ratios = |max_theta: f64| -> Vec<f64> {
                rows.iter()
                    .filter(|r| r.model == m && r.lobe == lobe && r.theta_i.abs() <= max_theta)
                    .filter_map(|r| {
                        let floor = counted_floor(r)?;
                        (floor > 0.0).then(|| counted_residual(r).map(|x| x / floor))?
                    })
                    .collect()
            };
            let count =
                |v: &[f64]| format!("{}/{}", v.iter().filter(|&&x| x <= 2.0).count(), v.len());
            let (near, all) = (ratios(1.1 + 1e-9), ratios(f64::INFINITY));
            let _ = writeln!(
                out,
                "| {m} | {lobe} | {} | {} | {} |",
                count(&near),
                count(&all),
                median(near).map_or_else(|| "–".into(), |x| format!("{x:.2}"))
            );
        }
    }
    out
}

/// Every verdict the rows allow, as Markdown sections.
pub fn verdicts(rows: &[Row]) -> String {
    let mut out = String::new();
    if models_present(rows, &[NONSEPARABLE, PAPER]) {
        out.push_str(
            "\n## The tilted non-separable model against the paper's, per (θ_i, α) cell\n\n",
        );
        out.push_str(&cells_against(
            rows,
            NONSEPARABLE,
            PAPER,
            &["R", "TT", "TRT"],
        ));
        out.push_str("\n### Per lobe\n\n");
        out.push_str(&model_against_model(rows, NONSEPARABLE, PAPER));
    }
    for ours in [NONSEPARABLE, PAPER] {
        if models_present(rows, &[ours, DEON]) {
            let _ = write!(out, "\n## {ours} against d'Eon 2011, per lobe\n\n");
            out.push_str(&model_against_model(rows, ours, DEON));
        }
    }
    if has_noise(rows) {
        out.push_str("\n## Residuals against the noise floor\n\n");
        out.push_str(&against_the_floor(rows));
    }
    out
}
