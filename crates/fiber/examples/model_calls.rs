//! A fixed number of eval, sample and pdf calls of one model on the inputs of
//! `benches/models.rs` (pbrt-v4's: directions uniform on the sphere, β = 0.3, α = 2°,
//! eumelanin 1.3, h = 0.3 for Chiang 2016's near field), each in its own function, for
//! instruction counts that a loaded machine does not disturb:
//! `valgrind --tool=callgrind --toggle-collect='model_calls::run_*' target/release/examples/model_calls deon2011`
//! then `callgrind_annotate --inclusive=yes` gives each `run_*`'s instructions for CALLS calls.
use cuticle_fiber::{Chiang2016, DEon2011, FiberModel, Marschner2003, NonSeparable};
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
    let (model, h): (Box<dyn FiberModel>, Option<f64>) = match which.as_str() {
        "deon2011" => (Box::new(DEon2011::new(p).unwrap().tabulated()), None),
        "chiang2016" => (Box::new(Chiang2016::new(p, p.beta).unwrap()), Some(0.3)),
        "nonseparable" => (Box::new(NonSeparable::new(p).unwrap().tabulated()), None),
        "marschner2003" => (
            Box::new(Marschner2003::from_fiber(&p).unwrap().tabulated()),
            None,
        ),
        "marschner2003_exact" => (Box::new(Marschner2003::from_fiber(&p).unwrap()), None),
        other => {
            eprintln!(
                "unknown model {other}: deon2011, chiang2016, nonseparable, marschner2003, \
                 marschner2003_exact"
            );
            std::process::exit(2);
        }
    };
    let cases = inputs::cases(CALLS);
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
