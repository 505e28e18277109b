//! Paths per second of the simulator on all cores (rayon's global pool), for a typical hair
//! configuration of the paper's suite and for a smooth clear one. Criterion reports the time of
//! one `simulate` call of `RAYS` paths; its "thrpt" line is paths per second.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use cuticle_sim::{SimParams, simulate};
use std::hint::black_box;

const RAYS: u64 = 4_000_000;

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("simulate");
    group.sample_size(10);
    group.throughput(Throughput::Elements(RAYS));
    let configs = [
        (
            "ti0.75_a-2_b0.04_mu0.25",
            SimParams {
                theta_i: 0.75,
                alpha: (-2f64).to_radians(),
                beta: 0.04,
                mu_a: [0.25; 3],
                rays: RAYS,
                ..Default::default()
            },
        ),
        (
            "ti0.25_a0_b0.0025_mu0",
            SimParams {
                theta_i: 0.25,
                beta: 0.0025,
                rays: RAYS,
                ..Default::default()
            },
        ),
    ];
    for (name, params) in configs {
        group.bench_function(name, |b| {
            b.iter(|| simulate(black_box(&params), &|_, _| {}).unwrap())
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
