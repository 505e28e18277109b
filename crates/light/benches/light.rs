//! Benchmarks: loading a 1k Radiance map and a 1k tiled OpenEXR map, and fitting 40 SRBF lights
//! to the Radiance one.

use criterion::{Criterion, criterion_group, criterion_main};
use cuticle_light::{FitOptions, fit_srbf, load_env_map};
use std::path::PathBuf;

fn map_path() -> Option<PathBuf> {
    shared("venice_sunset_1k.hdr")
}

fn shared(name: &str) -> Option<PathBuf> {
    let path = PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../../shared/data/envmaps"
    ))
    .join(name);
    if path.exists() {
        Some(path)
    } else {
        eprintln!("skipped: {} is absent", path.display());
        None
    }
}

fn load(c: &mut Criterion) {
    let Some(path) = map_path() else { return };
    c.bench_function("load venice_sunset_1k.hdr", |b| {
        b.iter(|| load_env_map(&path).expect("map loads"))
    });
    let Some(exr) = shared("KernerEnvLatLong.exr") else {
        return;
    };
    c.bench_function(
        "load KernerEnvLatLong.exr (tiled, mip-mapped, ZIP, half)",
        |b| b.iter(|| load_env_map(&exr).expect("map loads")),
    );
}

fn fit(c: &mut Criterion) {
    let Some(path) = map_path() else { return };
    let map = load_env_map(&path).expect("map loads");
    let mut group = c.benchmark_group("fit");
    group.sample_size(10);
    group.bench_function("40 lights, venice_sunset_1k", |b| {
        b.iter(|| fit_srbf(&map, &FitOptions::default()).expect("fit runs"))
    });
    group.finish();
}

criterion_group!(benches, load, fit);
criterion_main!(benches);
