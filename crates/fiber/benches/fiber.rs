//! Criterion benchmarks of the fiber models: eval (all lobes, RGB), sample (which includes the
//! S / pdf weight) and pdf, per model; the tabulated fast path against direct quadrature; and
//! building the table.

use criterion::{BatchSize, Criterion, criterion_group, criterion_main};
use cuticle_fiber::azimuthal::AzimuthalScattering;
use cuticle_fiber::table::AzimuthalTable;
use cuticle_fiber::{DEon2011, FiberAngles, FiberModel, FiberParams, Marschner2003, NonSeparable};
use std::hint::black_box;

fn directions(n: usize) -> Vec<(FiberAngles, FiberAngles, [f64; 4])> {
    let mut state = 0x2545_F491_4F6C_DD1Du64;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..n)
        .map(|_| {
            let wi = FiberAngles::new((next() - 0.5) * 2.8, 0.0);
            let wo = FiberAngles::new((next() - 0.5) * 2.8, (next() - 0.5) * std::f64::consts::TAU);
            (wi, wo, [next(), next(), next(), next()])
        })
        .collect()
}

fn bench_model(c: &mut Criterion, name: &str, model: &dyn FiberModel) {
    let cases = directions(1024);
    let mut group = c.benchmark_group(name);
    let mut i = 0;
    group.bench_function("eval", |b| {
        b.iter(|| {
            i = (i + 1) % cases.len();
            let (wi, wo, _) = cases[i];
            black_box(model.eval(black_box(wi), black_box(wo)))
        })
    });
    group.bench_function("sample", |b| {
        b.iter(|| {
            i = (i + 1) % cases.len();
            let (wi, _, u) = cases[i];
            black_box(model.sample(black_box(wi), black_box(u)))
        })
    });
    group.bench_function("pdf", |b| {
        b.iter(|| {
            i = (i + 1) % cases.len();
            let (wi, wo, _) = cases[i];
            black_box(model.pdf(black_box(wi), black_box(wo)))
        })
    });
    group.finish();
}

fn models(c: &mut Criterion) {
    let params = FiberParams::default();
    bench_model(
        c,
        "deon2011_table",
        &DEon2011::new(params).unwrap().tabulated(),
    );
    bench_model(c, "deon2011_direct", &DEon2011::new(params).unwrap());
    bench_model(
        c,
        "nonseparable_table",
        &NonSeparable::new(params).unwrap().tabulated(),
    );
    bench_model(
        c,
        "nonseparable_direct",
        &NonSeparable::new(params).unwrap(),
    );
    bench_model(
        c,
        "marschner2003",
        &Marschner2003::from_fiber(&params).unwrap(),
    );
}

fn table_build(c: &mut Criterion) {
    let p = FiberParams::default();
    let az = AzimuthalScattering::new(p.eta, p.beta, p.mu_a);
    let mut group = c.benchmark_group("azimuthal_table");
    group.sample_size(10);
    group.bench_function("build_beta_0.04", |b| {
        b.iter_batched(
            || az,
            |az| black_box(AzimuthalTable::build(&az)),
            BatchSize::SmallInput,
        )
    });
    group.finish();
}

criterion_group!(benches, models, table_build);
criterion_main!(benches);
