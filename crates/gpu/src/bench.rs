//! The GPU renderer's benchmark, the twin of `cuticle_render::bench`: full frames (drawing,
//! upload, shadows, shading and resolve on the GPU) and re-renders after an
//! absorption edit (every strand's record rewritten, then shading and resolve), as medians of
//! each stage, with the GPU's own timestamps where the adapter has them.

use crate::frame::GpuSeconds;
use crate::renderer::{GpuError, GpuRenderer};
use cuticle_render::Scene;
use cuticle_render::Timings;
use cuticle_render::bench::{median, median_timings, with_absorption_edit};
use serde::Serialize;
use std::time::Instant;

/// Medians over the benchmark's frames.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct GpuBenchReport {
    pub frames: usize,
    pub visible_points: usize,
    /// Median seconds of each stage of a full frame (wall; shading and resolve each waited for,
    /// the resolve with its readback of the image).
    pub full: Timings,
    /// Median seconds of uploading a prepared frame.
    pub upload: f64,
    /// Median wall seconds of a full frame: drawing + shadows + upload + shading + resolve.
    pub full_frame: f64,
    /// Median GPU seconds of a full frame's passes (drawing, shadows, shading, resolve), where
    /// the adapter has timestamps.
    pub full_gpu: Option<GpuSeconds>,
    /// Median seconds of each stage of a re-render after an absorption edit.
    pub rerender: Timings,
    /// Median wall seconds of a re-render, the edit's strand upload included.
    pub rerender_frame: f64,
    /// Median GPU seconds of a re-render's passes, where the adapter has timestamps (`drawing`
    /// and `shadows` 0: an edit does not re-run them).
    pub rerender_gpu: Option<GpuSeconds>,
}

/// Renders `scene` `frames` times in full, and after each frame re-renders it with its
/// absorption edited, keeping that frame's visibility and shadows.
pub fn run(gpu: &GpuRenderer, scene: &Scene, frames: usize) -> Result<GpuBenchReport, GpuError> {
    let frames = frames.max(1);
    let (mut full, mut upload, mut full_frame) = (Vec::new(), Vec::new(), Vec::new());
    let (mut rerender, mut rerender_frame, mut gpu_times) = (Vec::new(), Vec::new(), Vec::new());
    let mut full_gpu = Vec::new();
    let mut visible_points = 0;
    for i in 0..frames {
        let start = Instant::now();
        let (_, mut frame) = gpu.render(scene)?;
        full_frame.push(start.elapsed().as_secs_f64());
        visible_points = frame.visible_count();
        full.push(frame.timings());
        upload.push(frame.upload_seconds());
        full_gpu.extend(frame.gpu_seconds());
        let edited = with_absorption_edit(scene, i);
        let start = Instant::now();
        gpu.shade(&mut frame, &edited);
        rerender_frame.push(start.elapsed().as_secs_f64());
        rerender.push(frame.timings());
        gpu_times.extend(frame.gpu_seconds());
    }
    let rerender_gpu = median_gpu(&gpu_times).map(|g| GpuSeconds {
        drawing: 0.0,
        shadows: 0.0,
        ..g
    });
    Ok(GpuBenchReport {
        frames,
        visible_points,
        full: median_timings(&full),
        upload: median(upload),
        full_frame: median(full_frame),
        full_gpu: median_gpu(&full_gpu),
        rerender: median_timings(&rerender),
        rerender_frame: median(rerender_frame),
        rerender_gpu,
    })
}

fn median_gpu(runs: &[GpuSeconds]) -> Option<GpuSeconds> {
    let m = |f: fn(&GpuSeconds) -> f64| median(runs.iter().map(f).collect());
    (!runs.is_empty()).then(|| GpuSeconds {
        drawing: m(|t| t.drawing),
        shadows: m(|t| t.shadows),
        shading: m(|t| t.shading),
        resolve: m(|t| t.resolve),
    })
}
