//! Per-strand parameters as the shading pass reads them: one record per strand in a storage
//! buffer, derived from the scene by [`GpuRenderer::prepare`](crate::GpuRenderer::prepare) and
//! rewritten for a few strands by
//! [`GpuRenderer::update_strands`](crate::GpuRenderer::update_strands) without touching the groom.
//!
//! A strand carries its absorption μ_a (RGB, per unit radius, as `HairParams::fiber` gives it);
//! the CPU renderer takes every other parameter from the scene's global set (scene/hair.rs), and
//! so does this one.

use bytemuck::{Pod, Zeroable};
use cuticle_render::Scene;
use cuticle_render::tables::absorption_axis::MU_A_MAX;

/// One strand's record (16 bytes; the fourth float is spare).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct StrandParams {
    /// μ_a per unit radius, RGB.
    pub mu_a: [f32; 3],
    pub _spare: f32,
}

impl StrandParams {
    pub fn new(mu_a: [f32; 3]) -> Self {
        Self { mu_a, _spare: 0.0 }
    }
}

/// Why an update was refused.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum StrandError {
    #[error("strands {first}..{end} lie outside the groom's {count} strands")]
    OutOfRange {
        first: usize,
        end: usize,
        count: usize,
    },
    #[error("strand {strand}: mu_a {value} is outside [0, {max}]")]
    BadAbsorption { strand: usize, value: f32, max: f64 },
}

/// What decides every strand's absorption besides its own appearance: a change re-derives all.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StrandSource {
    pub mu_a: Option<[f64; 3]>,
    pub default_mu_a: [f64; 3],
}

impl StrandSource {
    pub fn of(scene: &Scene) -> Self {
        Self {
            mu_a: scene.spec.hair.mu_a,
            default_mu_a: scene.spec.hair.default_mu_a,
        }
    }
}

/// Every strand's record, as the CPU renderer's shading derives each strand's parameters.
pub fn derive(scene: &Scene) -> Vec<StrandParams> {
    (0..scene.groom.strand_count())
        .map(|s| {
            let mu = scene.spec.hair.fiber(scene.groom.appearance().get(s)).mu_a;
            StrandParams::new([mu.x as f32, mu.y as f32, mu.z as f32])
        })
        .collect()
}

/// Checks an update of strands `first..first + params.len()` of `count`: in range, μ_a finite
/// and within the tables' range (the same range `HairParams::validate` checks).
pub fn check(first: usize, params: &[StrandParams], count: usize) -> Result<(), StrandError> {
    let end = first.saturating_add(params.len());
    if end > count {
        return Err(StrandError::OutOfRange { first, end, count });
    }
    for (k, p) in params.iter().enumerate() {
        if let Some(&value) = p
            .mu_a
            .iter()
            .find(|v| !(v.is_finite() && (0.0..=MU_A_MAX as f32).contains(*v)))
        {
            return Err(StrandError::BadAbsorption {
                strand: first + k,
                value,
                max: MU_A_MAX,
            });
        }
    }
    Ok(())
}
