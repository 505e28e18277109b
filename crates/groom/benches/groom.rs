//! Speed of reading `.hair` files and of generating the built-in scene groom.
//!
//! `cargo bench -p cuticle-groom`. The file benchmarks use `../shared/data/hair/straight.hair`
//! and are skipped, with a message, where it is absent.

use criterion::{Criterion, criterion_group, criterion_main};
use cuticle_groom::procedural::{Preset, default_groom, generate};
use cuticle_groom::{Groom, HairFile};
use std::hint::black_box;
use std::path::Path;

const STRAIGHT: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../../shared/data/hair/straight.hair"
);

fn reading(c: &mut Criterion) {
    if !Path::new(STRAIGHT).exists() {
        eprintln!("skipped: {STRAIGHT} is absent, so the file benchmarks do not run");
        return;
    }
    c.bench_function("read straight.hair into a Groom", |b| {
        b.iter(|| Groom::read_hair(black_box(STRAIGHT)).expect("straight.hair reads"))
    });
    let bytes = std::fs::read(STRAIGHT).expect("straight.hair is readable");
    c.bench_function("decode straight.hair from memory", |b| {
        b.iter(|| HairFile::from_bytes(black_box(&bytes)).expect("straight.hair decodes"))
    });
}

fn generating(c: &mut Criterion) {
    let params = Preset::default().params();
    c.bench_function("generate default groom (10k strands)", |b| {
        b.iter(|| generate(black_box(&params)).expect("default parameters are valid"))
    });
    let groom = default_groom();
    c.bench_function("encode default groom as .hair", |b| {
        b.iter(|| {
            black_box(&groom)
                .to_hair_bytes("bench")
                .expect("the groom is writable")
        })
    });
}

criterion_group!(benches, reading, generating);
criterion_main!(benches);
