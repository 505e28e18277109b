//! Where the non-separable model beats d'Eon 2011, per lobe: the paper's claim (d'Eon et al. 2014,
//! Figure 7) is that its R, TT and TRT lobes follow the simulation more closely whenever the
//! scales are tilted, except at extreme roughness and grazing θ_i. "Beats" here: a smaller
//! relative L1 error on the same configuration.

use crate::summary::{Row, counted_l1};
use std::collections::BTreeMap;
use std::fmt::Write;

/// (non-separable, d'Eon 2011) relative L1 of one configuration and lobe.
pub struct Pair<'a> {
    pub row: &'a Row,
    pub nonseparable: f64,
    pub deon: f64,
}

/// The configurations where both models have a figure for `lobe`.
pub fn pairs<'a>(rows: &'a [Row], lobe: &str) -> Vec<Pair<'a>> {
    let deon: BTreeMap<&str, f64> = rows
        .iter()
        .filter(|r| r.model == "deon2011" && r.lobe == lobe)
        .filter_map(|r| Some((r.config.as_str(), counted_l1(r)?)))
        .collect();
    rows.iter()
        .filter(|r| r.model == "nonseparable" && r.lobe == lobe)
        .filter_map(|r| {
            Some(Pair {
                row: r,
                nonseparable: counted_l1(r)?,
                deon: *deon.get(r.config.as_str())?,
            })
        })
        .collect()
}

fn wins(p: &[&Pair]) -> String {
    let n = p.iter().filter(|x| x.nonseparable < x.deon).count();
    format!("{n}/{}", p.len())
}

fn median_ratio(p: &[&Pair]) -> String {
    let mut r: Vec<f64> = p.iter().map(|x| x.nonseparable / x.deon).collect();
    if r.is_empty() {
        return "–".into();
    }
    r.sort_by(f64::total_cmp);
    format!("{:.2}", r[r.len() / 2])
}

/// (θ_i, β) cells of tilted configurations where d'Eon 2011 wins at least half the time.
fn losing_cells(tilted: &[&Pair]) -> Vec<String> {
    let mut cells: BTreeMap<(i64, i64), (f64, f64, usize, usize)> = BTreeMap::new();
    for p in tilted {
        let key = ((p.row.theta_i * 1e6) as i64, (p.row.beta * 1e6) as i64);
        let c = cells
            .entry(key)
            .or_insert((p.row.theta_i, p.row.beta, 0, 0));
        c.3 += 1;
        if p.nonseparable >= p.deon {
            c.2 += 1;
        }
    }
    cells
        .values()
        .filter(|c| 2 * c.2 >= c.3)
        .map(|c| format!("θ_i {} β {} ({}/{})", c.0, c.1, c.2, c.3))
        .collect()
}

/// The verdict table and one statement per lobe.
pub fn verdict(rows: &[Row]) -> String {
    let mut out = String::from(
        "| lobe | non-separable wins, tilted (α ≠ 0) | wins, α = 0 | median L1 ratio ns/d'Eon, tilted | tilted (θ_i, β) cells where d'Eon 2011 wins ≥ half |\n|---|---|---|---|---|\n",
    );
    for lobe in ["R", "TT", "TRT", "TRRT", "rest"] {
        let all = pairs(rows, lobe);
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
