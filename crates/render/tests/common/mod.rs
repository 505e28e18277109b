//! Helpers shared by the renderer's integration tests.

use cuticle_groom::{Groom, GroomParts};
use cuticle_render::Renderer;
use glam::Vec3;
use std::sync::OnceLock;

/// One renderer (its parameter-independent tables) for every test in a binary.
pub fn renderer() -> &'static Renderer {
    static R: OnceLock<Renderer> = OnceLock::new();
    R.get_or_init(Renderer::new)
}

/// Segments per strand of [`block`].
#[allow(dead_code)] // not every test binary uses it
pub const SEGMENTS: usize = 15;

/// 40 × 40 strands 0.22 apart (jittered), hanging from z = 10, 5 to 10 units long (the hair
/// thins toward the bottom, as where a groom's strands end at different lengths); segments
/// just short enough for `split_long_segments` to keep them whole, as in straight.hair.
#[allow(dead_code)] // not every test binary uses it
pub fn block() -> Groom {
    let mut positions = Vec::new();
    let mut strand_offsets = vec![0];
    let jitter = |k: u32| (k.wrapping_mul(2_654_435_761) >> 8) as f32 / (1u32 << 24) as f32 - 0.5;
    for i in 0..40u32 {
        for j in 0..40u32 {
            let x = (i as f32 - 19.5) * 0.22 + 0.18 * jitter(i * 40 + j);
            let y = (j as f32 - 19.5) * 0.22 + 0.18 * jitter(i * 40 + j + 7919);
            let length = 7.5 + 5.0 * jitter(i * 40 + j + 104_729);
            for k in 0..=SEGMENTS {
                let z = 10.0 - length * k as f32 / SEGMENTS as f32;
                positions.push(Vec3::new(x, y, z));
            }
            strand_offsets.push(positions.len() as u32);
        }
    }
    Groom::from_parts(GroomParts {
        thickness: vec![0.25; positions.len()],
        positions,
        strand_offsets,
        ..GroomParts::default()
    })
    .unwrap()
}
