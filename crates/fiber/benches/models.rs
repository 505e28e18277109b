//! Criterion benchmarks of every fiber model's eval (all lobes, RGB), sample (with its weight
//! S / pdf) and pdf on the inputs of pbrt-v4's `HairBxDF` figures in issue 15: uniformly random
//! directions on the sphere, β = 0.3 (β_m = β_n = 0.3 for Chiang 2016, β_R = β/√2 for
//! Marschner 2003 through [`Marschner2003::from_fiber`]), α = 2°, η = 1.55, μ_a from
//! eumelanin 1.3 ([`mu_a_from_melanin`]), h = 0.3 for the near-field Chiang 2016 (pbrt's `f`,
//! `Sample_f` and `PDF` take the offset too). Each iteration makes one call per case, 1,024
//! independent single calls in a loop, as pbrt-v4's harness timed `HairBxDF`: criterion's own
//! lines give the time of the 1,024 and the calls per second. After the runs it prints the
//! issue's table, criterion's medians per call beside pbrt-v4's figures and the aims.
//!
//! `cargo bench -p cuticle-fiber --bench models` runs everything; criterion's filter (a regex)
//! runs a part, e.g. only the table's four models:
//! `cargo bench -p cuticle-fiber --bench models --
//! '^(deon2011_table|chiang2016_h0.3|nonseparable_table|marschner2003_table)/'` (exact Marschner
//! 2003, the far-field Chiang 2016, direct d'Eon 2011 and the table build come after them).

#[path = "common/inputs.rs"]
mod inputs;

use criterion::{BatchSize, Criterion, Throughput};
use cuticle_fiber::models::deon2011::azimuthal::AzimuthalScattering;
use cuticle_fiber::models::deon2011::table::AzimuthalTable;
use cuticle_fiber::{
    BuildOptions, FiberAngles, FiberModel, Marschner2003, ModelId, NonSeparable, Tabulation,
};
use inputs::{cases, params};
use std::hint::black_box;
use std::path::PathBuf;

/// The offset h of the near-field benchmark.
const H: f64 = 0.3;

/// pbrt-v4 `HairBxDF` at β_m = β_n = 0.3, h = 0.3, α = 2°, eumelanin 1.3 (issue 15): `f`,
/// `Sample_f`, `PDF` in ns per call.
const PBRT_NS: [f64; 3] = [305.0, 683.0, 323.0];

/// One row of the printed table: criterion group, label, the aims in ns.
const ROWS: [(&str, &str, [f64; 3]); 4] = [
    (
        "deon2011_table",
        "d'Eon 2011 (tabulated N_p)",
        [100.0, 230.0, 110.0],
    ),
    (
        "chiang2016_h0.3",
        "Chiang 2016 (near field, h = 0.3)",
        [100.0, 230.0, 110.0],
    ),
    (
        "nonseparable_table",
        "non-separable (tabulated N_p)",
        [300.0, 1000.0, 300.0],
    ),
    (
        "marschner2003_table",
        "Marschner 2003 (tabulated N_p)",
        [150.0, 400.0, 150.0],
    ),
];

/// The three calls of one model, as closures over (ω_i, ω_o, u).
struct Calls<'a> {
    eval: Box<dyn Fn(FiberAngles, FiberAngles) -> f64 + 'a>,
    sample: Box<dyn Fn(FiberAngles, [f64; 4]) -> f64 + 'a>,
    pdf: Box<dyn Fn(FiberAngles, FiberAngles) -> f64 + 'a>,
}

fn far_field(model: &dyn FiberModel) -> Calls<'_> {
    Calls {
        eval: Box::new(move |wi, wo| model.eval(wi, wo).total().x),
        sample: Box::new(move |wi, u| model.sample(wi, u).map_or(0.0, |s| s.weight.x)),
        pdf: Box::new(move |wi, wo| model.pdf(wi, wo)),
    }
}

fn near_field(model: &dyn FiberModel, h: f64) -> Calls<'_> {
    Calls {
        eval: Box::new(move |wi, wo| model.eval_at(wi, wo, h).total().x),
        sample: Box::new(move |wi, u| model.sample_at(wi, h, u).map_or(0.0, |s| s.weight.x)),
        pdf: Box::new(move |wi, wo| model.pdf_at(wi, wo, h)),
    }
}

/// Calls per criterion iteration: every case once, in order, as pbrt-v4's harness and
/// `examples/model_calls.rs` time a loop of calls; the table divides by it.
const CALLS_PER_ITER: usize = 1024;

fn bench_calls(c: &mut Criterion, group: &str, calls: &Calls) {
    let cases = cases(CALLS_PER_ITER);
    let mut g = c.benchmark_group(group);
    g.throughput(Throughput::Elements(CALLS_PER_ITER as u64));
    g.bench_function("eval", |b| {
        b.iter(|| {
            cases
                .iter()
                .map(|&(wi, wo, _)| (calls.eval)(black_box(wi), black_box(wo)))
                .sum::<f64>()
        })
    });
    g.bench_function("sample", |b| {
        b.iter(|| {
            cases
                .iter()
                .map(|&(wi, _, u)| (calls.sample)(black_box(wi), black_box(u)))
                .sum::<f64>()
        })
    });
    g.bench_function("pdf", |b| {
        b.iter(|| {
            cases
                .iter()
                .map(|&(wi, wo, _)| (calls.pdf)(black_box(wi), black_box(wo)))
                .sum::<f64>()
        })
    });
    g.finish();
}

fn models(c: &mut Criterion) {
    let p = params();
    let build = |id: ModelId, tabulation| id.build(&p, &BuildOptions::with(tabulation)).unwrap();
    let deon = build(ModelId::DEon2011, Tabulation::Tabulated);
    bench_calls(c, ROWS[0].0, &far_field(deon.as_ref()));
    let chiang = build(ModelId::Chiang2016, Tabulation::Direct);
    bench_calls(c, ROWS[1].0, &near_field(chiang.as_ref(), H));
    let nonsep = build(ModelId::NonSeparable, Tabulation::Tabulated);
    bench_calls(c, ROWS[2].0, &far_field(nonsep.as_ref()));
    let marschner_table = build(ModelId::Marschner, Tabulation::Tabulated);
    bench_calls(c, ROWS[3].0, &far_field(marschner_table.as_ref()));
    let marschner = build(ModelId::Marschner, Tabulation::Direct);
    bench_calls(c, "marschner2003_exact", &far_field(marschner.as_ref()));
    bench_calls(c, "chiang2016_far", &far_field(chiang.as_ref()));
    let deon_direct = build(ModelId::DEon2011, Tabulation::Direct);
    bench_calls(c, "deon2011_direct", &far_field(deon_direct.as_ref()));
}

fn table_build(c: &mut Criterion) {
    let p = params();
    let az = AzimuthalScattering::new(p.eta, p.beta, p.mu_a);
    let mut group = c.benchmark_group("azimuthal_table");
    group.sample_size(10);
    group.bench_function("build_beta_0.3", |b| {
        b.iter_batched(
            || az.clone(),
            |az| black_box(AzimuthalTable::build(&az)),
            BatchSize::SmallInput,
        )
    });
    let nonsep = NonSeparable::new(p).unwrap();
    group.bench_function("build_nonseparable", |b| {
        b.iter(|| black_box(nonsep.clone().tabulated()))
    });
    let marschner = Marschner2003::from_fiber(&p).unwrap();
    group.bench_function("build_marschner2003", |b| {
        b.iter(|| black_box(marschner.clone().tabulated()))
    });
    group.finish();
}

/// criterion's output folder: `CRITERION_HOME`, else `$CARGO_TARGET_DIR/criterion`, else the
/// first `target/criterion` above the working directory.
fn criterion_dir() -> Option<PathBuf> {
    if let Some(home) = std::env::var_os("CRITERION_HOME") {
        return Some(home.into());
    }
    if let Some(target) = std::env::var_os("CARGO_TARGET_DIR") {
        return Some(PathBuf::from(target).join("criterion"));
    }
    let cwd = std::env::current_dir().ok()?;
    cwd.ancestors()
        .map(|d| d.join("target").join("criterion"))
        .find(|d| d.is_dir())
}

/// The median (ns) criterion recorded for `group/function` in this run, if it ran.
fn median_ns(dir: &std::path::Path, group: &str, function: &str) -> Option<f64> {
    let path = dir
        .join(group)
        .join(function)
        .join("new")
        .join("estimates.json");
    let text = std::fs::read_to_string(path).ok()?;
    let at = text.find("\"median\"")?;
    let rest = &text[at..];
    let key = "\"point_estimate\":";
    let start = rest.find(key)? + key.len();
    let end = rest[start..].find([',', '}'])? + start;
    rest[start..end].trim().parse().ok()
}

fn format_ns(ns: Option<f64>) -> String {
    match ns {
        Some(x) if x >= 1000.0 => format!("{:.2} µs", x / 1000.0),
        Some(x) => format!("{x:.0} ns"),
        None => "—".into(),
    }
}

fn print_table(started: std::time::SystemTime) {
    let Some(dir) = criterion_dir() else {
        eprintln!("criterion's output folder not found: no table");
        return;
    };
    // Only figures written by this run: an older estimate of a filtered-out group is left out.
    let fresh = |group: &str, f: &str| {
        let path = dir.join(group).join(f).join("new").join("estimates.json");
        let modified = std::fs::metadata(path).and_then(|m| m.modified()).ok()?;
        (modified >= started).then(|| median_ns(&dir, group, f))?
    };
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    println!();
    println!(
        "Fiber models, criterion medians per call (load average: {})",
        load.trim()
    );
    println!("| model | eval | sample (with weight) | pdf | aim eval / sample / pdf |");
    println!("|---|---|---|---|---|");
    for (group, label, aim) in ROWS {
        let m: Vec<String> = ["eval", "sample", "pdf"]
            .iter()
            .map(|f| format_ns(fresh(group, f).map(|ns| ns / CALLS_PER_ITER as f64)))
            .collect();
        let aims: Vec<String> = aim.iter().map(|&a| format_ns(Some(a))).collect();
        println!(
            "| {label} | {} | {} | {} | {} |",
            m[0],
            m[1],
            m[2],
            aims.join(" / ")
        );
    }
    let pbrt: Vec<String> = PBRT_NS.iter().map(|&a| format_ns(Some(a))).collect();
    println!(
        "| pbrt-v4 HairBxDF (issue 15; idle Zen 3, f32) | {} | {} | {} | — |",
        pbrt[0], pbrt[1], pbrt[2]
    );
}

fn main() {
    let started = std::time::SystemTime::now();
    let mut c = Criterion::default().configure_from_args();
    models(&mut c);
    table_build(&mut c);
    c.final_summary();
    print_table(started);
}
