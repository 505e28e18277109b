//! The CPU renderer (crate `cuticle-render`, f64, rayon over the machine's cores) behind
//! [`Shading`].

use crate::shading::{NO_STRAND, Shading, StrandBuffer};
use cuticle_render::frame::raster::EMPTY;
use cuticle_render::{Image, Prepared, Renderer, Scene, Timings};
use std::sync::atomic::AtomicBool;

/// The CPU renderer and its last preparation.
pub struct CpuShading {
    renderer: Renderer,
    prepared: Option<Prepared>,
}

impl CpuShading {
    /// A back end sharing `renderer`'s tables (a clone shares them).
    pub fn new(renderer: Renderer) -> Self {
        Self {
            renderer,
            prepared: None,
        }
    }
}

impl Shading for CpuShading {
    fn backend(&self) -> String {
        format!("CPU, {} threads", rayon::current_num_threads())
    }

    fn prepare(&mut self, scene: &Scene) -> Result<(), String> {
        let mut timings = Timings::default();
        self.prepared = Some(self.renderer.prepare(scene, &mut timings));
        Ok(())
    }

    fn shade(&mut self, scene: &Scene, cancel: &AtomicBool) -> Result<Option<Image>, String> {
        let Some(prepared) = self.prepared.as_ref() else {
            return Ok(None);
        };
        let colours = self
            .renderer
            .shade_cancellable(scene, prepared, &|_, _| {}, cancel);
        Ok(colours.map(|c| {
            self.renderer
                .resolve(prepared, &c, scene.groom.point_count())
        }))
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
