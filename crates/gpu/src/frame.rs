//! One prepared frame on the GPU: what stays valid while only hair parameters change (the
//! visible points, their opacity maps and shadows, the lights, the visibility buffer, the
//! background) in device
//! buffers, the parameter tables and strand records last uploaded, and counts of what ran.

use crate::buffers::Stopwatch;
use crate::draw::Drawing;
use crate::groom::GroomBuffers;
use crate::shading::ShadeParams;
use crate::shadows::ShadowMaps;
use crate::strands::{StrandParams, StrandSource};
use cuticle_render::Timings;
use cuticle_render::tables::back_scattering::BackScatteringTables;
use cuticle_render::tables::lobe_table::LobeTable;
use std::sync::Arc;

/// How many times each stage ran on this frame, and how many uploads an edit caused: an edit
/// of hair parameters must add shading and resolve passes only.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct Passes {
    /// Visibility-buffer drawings (stage 2, on the GPU).
    pub drawing: usize,
    /// Compute dispatches of those drawings ([`crate::draw::STEPS`], `cover` twice, and the
    /// prefix sums' steps).
    pub drawing_steps: usize,
    /// Opacity-map builds with their shadows (stage 3, on the GPU).
    pub shadows: usize,
    /// Compute dispatches of those builds (up to five each: [`crate::shadows::STEPS`]).
    pub shadow_steps: usize,
    /// Shading passes.
    pub shading: usize,
    /// Dispatches of those passes (one per [`crate::shading::light_chunks`] chunk).
    pub shading_steps: usize,
    /// Resolve dispatches.
    pub resolve: usize,
    /// Uploads of the lobe table or back-scattering tables.
    pub table_uploads: usize,
    /// Writes of strand records (a whole re-derivation or an `update_strands`).
    pub strand_uploads: usize,
    /// Uploads of the groom itself ([`crate::groom::GroomBuffers`]): once per groom.
    pub groom_uploads: usize,
}

/// The strand seen at each subsample, for picking strands to paint.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Visibility {
    pub width: usize,
    pub height: usize,
    /// Subsamples per pixel along each axis.
    pub ss: usize,
    /// Per subsample, row-major over `width·ss × height·ss`: the strand index, or
    /// [`Visibility::EMPTY`].
    pub strand: Vec<u32>,
}

impl Visibility {
    /// No strand covers the subsample.
    pub const EMPTY: u32 = u32::MAX;

    /// The strands seen in pixel (x, y), one per subsample.
    pub fn pixel(&self, x: usize, y: usize) -> impl Iterator<Item = u32> + '_ {
        let (ss, sw) = (self.ss, self.width * self.ss);
        (0..ss * ss).map(move |k| self.strand[(y * ss + k / ss) * sw + x * ss + k % ss])
    }
}

/// Seconds each pass took on the GPU by timestamp queries, where the adapter has them.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct GpuSeconds {
    /// The drawing of the frame's prepare (first step to last).
    pub drawing: f64,
    /// The opacity maps and shadows of the frame's prepare (first step to last).
    pub shadows: f64,
    pub shading: f64,
    pub resolve: f64,
}

/// A frame ready to shade ([`crate::GpuRenderer::prepare`]).
pub struct GpuFrame {
    pub(crate) width: usize,
    pub(crate) height: usize,
    pub(crate) ss: usize,
    /// Visible points: the first `visible` records of `drawing.visible`.
    pub(crate) visible: usize,
    pub(crate) drawing: Drawing,
    pub(crate) groom: Arc<GroomBuffers>,
    pub(crate) params: ShadeParams,
    pub(crate) params_buffer: wgpu::Buffer,
    pub(crate) lobes: Option<(Arc<LobeTable>, wgpu::Buffer)>,
    pub(crate) back: Option<(Arc<BackScatteringTables>, wgpu::Buffer)>,
    /// Bound while no back-scattering tables are (single scattering only).
    pub(crate) no_back: wgpu::Buffer,
    pub(crate) strands: Vec<StrandParams>,
    pub(crate) strand_source: StrandSource,
    pub(crate) strands_buffer: wgpu::Buffer,
    pub(crate) shadows: ShadowMaps,
    pub(crate) lights_buffer: wgpu::Buffer,
    pub(crate) colours_buffer: wgpu::Buffer,
    pub(crate) image_buffer: wgpu::Buffer,
    /// The shading pass's bind groups for its light chunks, rebuilt when a table buffer is
    /// replaced or the chunks change.
    pub(crate) shade_groups: Option<(Vec<crate::shading::LightChunk>, Vec<wgpu::BindGroup>)>,
    pub(crate) resolve_group: wgpu::BindGroup,
    pub(crate) stopwatch: Option<Stopwatch>,
    pub(crate) passes: Passes,
    pub(crate) timings: Timings,
    pub(crate) upload_seconds: f64,
    pub(crate) gpu_seconds: Option<GpuSeconds>,
    pub(crate) draw_gpu_seconds: Option<f64>,
    pub(crate) shadow_gpu_seconds: Option<f64>,
}

impl GpuFrame {
    /// What ran on this frame so far.
    pub fn passes(&self) -> Passes {
        self.passes
    }

    /// Wall seconds of each stage of the last prepare and shade, each submitted and waited for
    /// (the drawing with the background computed on the CPU meanwhile and the visible count
    /// read back; the resolve with its readback of the image).
    pub fn timings(&self) -> Timings {
        self.timings
    }

    /// Seconds spent uploading the prepared frame to the device.
    pub fn upload_seconds(&self) -> f64 {
        self.upload_seconds
    }

    /// The last shade's passes timed on the GPU, where the adapter has timestamp queries.
    pub fn gpu_seconds(&self) -> Option<GpuSeconds> {
        self.gpu_seconds
    }

    /// The count of visible points the drawing found (shaded, and shadowed per light).
    pub fn visible_count(&self) -> usize {
        self.visible
    }

    /// The strand records as last written.
    pub fn strands(&self) -> &[StrandParams] {
        &self.strands
    }
}
