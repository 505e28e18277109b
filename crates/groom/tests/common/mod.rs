//! Test helpers: random but valid `.hair` files, and the real data folder.

#![allow(dead_code)]

use cuticle_groom::{ArrayFlags, HairDefaults, HairFile, HairInfo};
use glam::Vec3;
use rand_core::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;
use std::path::PathBuf;

/// A deterministic generator for tests.
pub struct TestRng(Pcg64Mcg);

impl TestRng {
    pub fn new(seed: u64) -> Self {
        Self(Pcg64Mcg::seed_from_u64(seed))
    }

    pub fn below(&mut self, n: u64) -> u64 {
        self.0.next_u64() % n
    }

    pub fn float(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * ((self.0.next_u64() >> 40) as f32 / (1u64 << 24) as f32)
    }

    pub fn vec3(&mut self) -> Vec3 {
        Vec3::new(
            self.float(-50.0, 50.0),
            self.float(-50.0, 50.0),
            self.float(-50.0, 50.0),
        )
    }
}

/// A valid file holding exactly the arrays `flags` names, with random contents.
pub fn random_hair_file(flags: ArrayFlags, seed: u64) -> HairFile {
    let rng = &mut TestRng::new(seed);
    let strands = 1 + rng.below(12) as u32;
    let default_segments = rng.below(6) as u32;
    let segments: Vec<u16> = (0..strands).map(|_| rng.below(9) as u16).collect();
    let points = if flags.segments {
        segments.iter().map(|&s| u32::from(s) + 1).sum()
    } else {
        strands * (default_segments + 1)
    };
    let n = points as usize;
    HairFile {
        strand_count: strands,
        point_count: points,
        defaults: HairDefaults {
            segments: default_segments,
            thickness: rng.float(0.01, 2.0),
            transparency: rng.float(0.0, 1.0),
            color: [
                rng.float(0.0, 1.0),
                rng.float(0.0, 1.0),
                rng.float(0.0, 1.0),
            ],
        },
        info: HairInfo::from_text(&format!("test file {seed} flags {:#x}", flags.bits())),
        segments: flags.segments.then_some(segments),
        points: flags.points.then(|| (0..n).map(|_| rng.vec3()).collect()),
        thickness: flags
            .thickness
            .then(|| (0..n).map(|_| rng.float(0.0, 1.0)).collect()),
        transparency: flags
            .transparency
            .then(|| (0..n).map(|_| rng.float(0.0, 1.0)).collect()),
        colors: flags
            .colors
            .then(|| (0..n).map(|_| rng.vec3().abs() / 50.0).collect()),
    }
}

/// The bytes a file with these counts and arrays must have, computed from the format's spec.
pub fn expected_file_len(file: &HairFile) -> usize {
    let (s, p) = (file.strand_count as usize, file.point_count as usize);
    let f = file.flags();
    let sizes = [
        (f.segments, 2 * s),
        (f.points, 12 * p),
        (f.thickness, 4 * p),
    ];
    let more = [(f.transparency, 4 * p), (f.colors, 12 * p)];
    128 + sizes
        .iter()
        .chain(&more)
        .filter(|(on, _)| *on)
        .map(|(_, n)| n)
        .sum::<usize>()
}

/// The folder of real `.hair` files beside the checkout, or `None` (after saying so) when absent.
pub fn real_hair_dir(test: &str) -> Option<PathBuf> {
    let dir = PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../../shared/data/hair"
    ));
    if dir.is_dir() {
        Some(dir)
    } else {
        println!(
            "skipped: {test} needs the real hair data in {}, which is absent",
            dir.display()
        );
        None
    }
}
