//! The GPU back end (crate `cuticle-gpu`) behind [`Shading`]: drawing and shadows by its
//! `prepare` (shadows alone by `relight` when only the lights changed), shading and resolve by
//! its `shade`, a paint stroke written through
//! `update_strands` for the strands it changed only.

use crate::shading::{NO_STRAND, Shading, StrandBuffer};
use cuticle_gpu::strands::{self, StrandSource};
use cuticle_gpu::{GpuFrame, GpuRenderer, Visibility};
use cuticle_render::{Image, Scene};
use std::sync::Arc;
use std::sync::atomic::AtomicBool;

/// The GPU renderer (shared by the preview and full-quality back ends) and its last frame.
pub struct GpuShading {
    renderer: Arc<GpuRenderer>,
    frame: Option<GpuFrame>,
    /// The global absorption the frame's strand records were derived with.
    source: Option<StrandSource>,
    /// Strand records written by `update_strands` by the last shade.
    updated: usize,
}

impl GpuShading {
    pub fn new(renderer: Arc<GpuRenderer>) -> Self {
        Self {
            renderer,
            frame: None,
            source: None,
            updated: 0,
        }
    }

    /// Writes the records of the strands whose absorption differs from what the frame holds,
    /// one `update_strands` per run of consecutive strands. A change of the scene's global
    /// absorption source is left to `shade`, which re-derives every record.
    fn upload_paint(&mut self, scene: &Scene) -> Result<(), String> {
        self.updated = 0;
        let Some(frame) = self.frame.as_mut() else {
            return Ok(());
        };
        if self.source != Some(StrandSource::of(scene)) {
            self.source = Some(StrandSource::of(scene));
            return Ok(());
        }
        let want = strands::derive(scene);
        let have = frame.strands();
        if want.len() != have.len() {
            return Err("the groom changed without a new preparation".into());
        }
        let changed: Vec<usize> = (0..want.len()).filter(|&s| want[s] != have[s]).collect();
        for run in runs(&changed) {
            self.renderer
                .update_strands(frame, run.start, &want[run.clone()])
                .map_err(|e| e.to_string())?;
            self.updated += run.len();
        }
        Ok(())
    }
}

/// Consecutive indices of a sorted list as ranges.
fn runs(sorted: &[usize]) -> Vec<std::ops::Range<usize>> {
    let mut out: Vec<std::ops::Range<usize>> = Vec::new();
    for &s in sorted {
        match out.last_mut() {
            Some(r) if r.end == s => r.end += 1,
            _ => out.push(s..s + 1),
        }
    }
    out
}

impl Shading for GpuShading {
    fn backend(&self) -> String {
        let s = &self.renderer.device().summary;
        format!("GPU, {} ({})", s.name, s.kind)
    }

    fn prepare(&mut self, scene: &Scene) -> Result<(), String> {
        self.frame = None;
        self.updated = 0;
        self.frame = Some(self.renderer.prepare(scene).map_err(|e| e.to_string())?);
        self.source = Some(StrandSource::of(scene));
        Ok(())
    }

    /// `GpuRenderer::relight` on the kept frame: new opacity maps, shadows and background,
    /// the drawing, tables and strand records kept.
    fn relight(&mut self, scene: &Scene) -> Result<(), String> {
        let Some(frame) = self.frame.as_mut() else {
            return self.prepare(scene);
        };
        self.updated = 0;
        if let Err(e) = self.renderer.relight(frame, scene) {
            self.frame = None;
            return Err(e.to_string());
        }
        Ok(())
    }

    /// Not cancellable: a GPU frame is done before an edit could make it stale.
    fn shade(&mut self, scene: &Scene, _cancel: &AtomicBool) -> Result<Option<Image>, String> {
        self.upload_paint(scene)?;
        let Some(frame) = self.frame.as_mut() else {
            return Ok(None);
        };
        Ok(Some(self.renderer.shade(frame, scene)))
    }

    fn strands_updated(&self) -> usize {
        self.updated
    }

    fn strands(&self) -> StrandBuffer {
        let Some(frame) = &self.frame else {
            return StrandBuffer::default();
        };
        let v = self.renderer.visibility(frame);
        StrandBuffer {
            width: v.width,
            height: v.height,
            ss: v.ss,
            strand: v
                .strand
                .into_iter()
                .map(|s| if s == Visibility::EMPTY { NO_STRAND } else { s })
                .collect(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::runs;

    #[test]
    fn runs_split_at_gaps() {
        assert_eq!(runs(&[1, 2, 3, 7, 9, 10]), vec![1..4, 7..8, 9..11]);
        assert!(runs(&[]).is_empty());
    }
}
