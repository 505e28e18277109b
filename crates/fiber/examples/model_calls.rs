//! A fixed number of eval, sample and pdf calls of one model on the inputs of
//! `benches/models.rs` (pbrt-v4's: directions uniform on the sphere, β = 0.3, α = 2°,
//! eumelanin 1.3, h = 0.3 for Chiang 2016's near field), each in its own function, for
//! instruction counts that a loaded machine does not disturb:
//! `valgrind --tool=callgrind --toggle-collect='model_calls::run_*'
//! target/release/examples/model_calls deon2011` then `callgrind_annotate --inclusive=yes` gives
//! each `run_*`'s instructions for CALLS calls.
//!
//! With `--time` it times each kind of call instead: 301 rounds of CALLS calls, the three kinds
//! interleaved, and prints per call the fastest round and the median round. Other programs on a
//! shared host only ever add time, so the fastest round is the steadiest figure for comparing
//! two builds run one after the other; the median is the one to quote.
use cuticle_fiber::{BuildOptions, FiberModel, ModelId, Tabulation};
use std::hint::black_box;

const CALLS: usize = 4096;

#[path = "../benches/common/inputs.rs"]
mod inputs;
use inputs::Case;

#[inline(never)]
fn run_eval(m: &dyn FiberModel, h: Option<f64>, cases: &[Case]) -> f64 {
    cases
        .iter()
        .map(|&(wi, wo, _)| match h {
            Some(h) => m.eval_at(black_box(wi), black_box(wo), h).total().x,
            None => m.eval(black_box(wi), black_box(wo)).total().x,
        })
        .sum()
}

#[inline(never)]
fn run_sample(m: &dyn FiberModel, h: Option<f64>, cases: &[Case]) -> f64 {
    cases
        .iter()
        .map(|&(wi, _, u)| {
            let s = match h {
                Some(h) => m.sample_at(black_box(wi), h, black_box(u)),
                None => m.sample(black_box(wi), black_box(u)),
            };
            s.map_or(0.0, |s| s.weight.x)
        })
        .sum()
}

#[inline(never)]
fn run_pdf(m: &dyn FiberModel, h: Option<f64>, cases: &[Case]) -> f64 {
    cases
        .iter()
        .map(|&(wi, wo, _)| match h {
            Some(h) => m.pdf_at(black_box(wi), black_box(wo), h),
            None => m.pdf(black_box(wi), black_box(wo)),
        })
        .sum()
}

#[inline(never)]
fn warm_up(m: &dyn FiberModel, h: Option<f64>, cases: &[Case]) -> f64 {
    cases
        .iter()
        .map(|&(wi, wo, u)| {
            let s = match h {
                Some(h) => m.sample_at(wi, h, u),
                None => m.sample(wi, u),
            };
            s.map_or(0.0, |s| s.weight.x) + m.pdf(wi, wo) + m.eval(wi, wo).total().x
        })
        .sum()
}

fn main() {
    let p = inputs::params();
    let which = std::env::args().nth(1).unwrap_or_else(|| "deon2011".into());
    // A registry name, `_exact` for its direct (untabulated) form; Chiang 2016 at h = 0.3.
    let (name, tabulation) = match which.strip_suffix("_exact") {
        Some(name) => (name, Tabulation::Direct),
        None => (which.as_str(), Tabulation::Tabulated),
    };
    let id = match name.parse::<ModelId>() {
        Ok(id) => id,
        Err(e) => {
            eprintln!("{e}; add _exact for the direct form");
            std::process::exit(2);
        }
    };
    let model = id.build(&p, &BuildOptions::with(tabulation)).unwrap();
    let h = (id == ModelId::Chiang2016).then_some(0.3);
    let cases = inputs::cases(CALLS);
    if std::env::args().any(|a| a == "--time") {
        time_calls(&which, model.as_ref(), h, &cases);
        return;
    }
    // Outside the counted functions, so lazy state (quadrature rules, the lobe-energy table)
    // is built before counting.
    let warm = warm_up(model.as_ref(), h, &cases[..8]);
    let total = run_eval(model.as_ref(), h, &cases)
        + run_sample(model.as_ref(), h, &cases)
        + run_pdf(model.as_ref(), h, &cases);
    println!(
        "{which}: {} calls each, checksum {}",
        CALLS,
        total + 0.0 * warm
    );
}

/// Per-call nanoseconds of eval, sample and pdf: the fastest and the median of 301 rounds.
fn time_calls(which: &str, m: &dyn FiberModel, h: Option<f64>, cases: &[Case]) {
    type Run = fn(&dyn FiberModel, Option<f64>, &[Case]) -> f64;
    let runs: [(&str, Run); 3] = [("eval", run_eval), ("sample", run_sample), ("pdf", run_pdf)];
    let mut rounds = [(); 3].map(|_| Vec::with_capacity(301));
    let mut sink = warm_up(m, h, cases);
    for _ in 0..301 {
        for ((_, run), times) in runs.iter().zip(&mut rounds) {
            let start = std::time::Instant::now();
            sink += run(m, h, cases);
            times.push(start.elapsed().as_secs_f64() * 1e9 / CALLS as f64);
        }
    }
    for ((name, _), times) in runs.iter().zip(&mut rounds) {
        times.sort_by(f64::total_cmp);
        println!(
            "{which} {name:6} fastest {:7.1} ns  median {:7.1} ns",
            times[0], times[150]
        );
    }
    black_box(sink);
}
