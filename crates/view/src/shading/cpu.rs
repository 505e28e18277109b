//! The CPU renderer (crate `cuticle-render`, f64, rayon over the machine's cores) behind
//! [`Shading`]. It keeps T̃ of every light at every point of the groom (stage 3, which depends
//! on the groom, lights and shadow settings only), so that a camera move re-runs drawing alone,
//! up to [`KEPT_SHADOW_VALUES`]; a larger groom computes them at the visible points each time.

use crate::shading::{NO_STRAND, Shading, StrandBuffer};
use cuticle_groom::GroomParts;
use cuticle_render::frame::draw::EMPTY;
use cuticle_render::{
    Image, Prepared, Renderer, Scene, Shaded, ShadowOptions, Timings, WorldLight,
};
use std::sync::atomic::AtomicBool;

/// Most T̃ values (points × lights) kept: 256 MiB of f32, enough for the default scene
/// (318,287 points × 174 shaded lights), whose camera orbits then re-run drawing alone.
pub const KEPT_SHADOW_VALUES: usize = 1 << 26;

/// What the kept transmittances were computed for.
#[derive(Clone, Debug, PartialEq)]
struct ShadowKey {
    groom: GroomParts,
    lights: Vec<WorldLight>,
    options: ShadowOptions,
}

/// T̃ of light j at point p of the groom: `all[p * lights + j]`.
struct KeptShadows {
    key: ShadowKey,
    all: Vec<f32>,
}

/// The CPU renderer and its last preparation.
pub struct CpuShading {
    renderer: Renderer,
    prepared: Option<Prepared>,
    /// The last shading pass on `prepared`: the next shades only the points it changes.
    shaded: Option<Shaded>,
    shadows: Option<KeptShadows>,
    /// Times T̃ was computed: for every point (a new groom, lights or shadow settings), or at
    /// the visible points of a groom too large to keep them for.
    shadow_passes: u64,
}

impl CpuShading {
    /// A back end sharing `renderer`'s tables (a clone shares them).
    pub fn new(renderer: Renderer) -> Self {
        Self {
            renderer,
            prepared: None,
            shaded: None,
            shadows: None,
            shadow_passes: 0,
        }
    }

    /// T̃ at the prepared points, from the kept values unless the groom, lights or shadow
    /// settings changed (then for every point of the groom, and kept), or computed there alone
    /// beyond [`KEPT_SHADOW_VALUES`].
    fn shadows_at(&mut self, scene: &Scene, prepared: &Prepared) -> Vec<f32> {
        let nl = prepared.lights.len();
        if scene.groom.point_count().saturating_mul(nl) > KEPT_SHADOW_VALUES {
            self.shadows = None;
            self.shadow_passes += 1;
            return self
                .renderer
                .shadows(scene, &prepared.points, &prepared.lights);
        }
        let key = ShadowKey {
            groom: scene.groom.parts().clone(),
            lights: prepared.lights.clone(),
            options: scene.spec.shadows,
        };
        if self.shadows.as_ref().is_none_or(|k| k.key != key) {
            self.shadows = None;
            let every: Vec<u32> = (0..scene.groom.point_count() as u32).collect();
            let all = self.renderer.shadows(scene, &every, &prepared.lights);
            self.shadow_passes += 1;
            self.shadows = Some(KeptShadows { key, all });
        }
        let Some(kept) = &self.shadows else {
            return Vec::new();
        };
        prepared
            .points
            .iter()
            .flat_map(|&p| &kept.all[p as usize * nl..(p as usize + 1) * nl])
            .copied()
            .collect()
    }
}

impl Shading for CpuShading {
    fn backend(&self) -> String {
        format!("CPU, {} threads", rayon::current_num_threads())
    }

    fn prepare(&mut self, scene: &Scene) -> Result<(), String> {
        self.prepared = None;
        self.shaded = None;
        let mut timings = Timings::default();
        let mut prepared = self.renderer.draw(scene, &mut timings);
        prepared.shadow = self.shadows_at(scene, &prepared);
        self.prepared = Some(prepared);
        Ok(())
    }

    fn shadow_passes(&self) -> u64 {
        self.shadow_passes
    }

    fn table_builds(&self) -> u64 {
        let b = self.renderer.table_builds();
        b.lobes + b.back_scattering + b.preview_back_scattering
    }

    fn shade(&mut self, scene: &Scene, cancel: &AtomicBool) -> Result<Option<Image>, String> {
        let Some(prepared) = self.prepared.as_ref() else {
            return Ok(None);
        };
        let previous = self.shaded.take();
        let Some(shaded) =
            self.renderer
                .shade_reusing(scene, prepared, previous.as_ref(), &|_, _| {}, cancel)
        else {
            // Cancelled: the pass before still describes nothing newer; keep it.
            self.shaded = previous;
            return Ok(None);
        };
        let image = self
            .renderer
            .resolve(prepared, &shaded.colours, scene.groom.point_count());
        self.shaded = Some(shaded);
        Ok(Some(image))
    }

    fn points_shaded(&self) -> Option<usize> {
        self.shaded.as_ref().map(|s| s.points_shaded)
    }

    fn strands(&self) -> StrandBuffer {
        let Some(p) = &self.prepared else {
            return StrandBuffer::default();
        };
        let cov = &p.coverage;
        StrandBuffer {
            width: cov.width,
            height: cov.height,
            ss: cov.ss,
            strand: cov
                .segment
                .iter()
                .map(|&s| match s {
                    EMPTY => NO_STRAND,
                    s => p.strand_of_point[s as usize],
                })
                .collect(),
        }
    }
}
