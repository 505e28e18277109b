//! What a frame's buffers hold, read back to the CPU: the shadows, the visibility buffer, the
//! visible points and the strand at each subsample (tests compare them with the CPU renderer's;
//! the window picks strands to paint with [`GpuRenderer::visibility`]).

use super::GpuRenderer;
use crate::buffers;
use crate::frame::{GpuFrame, Visibility};
use crate::shading::PointRecord;
use cuticle_render::frame::draw::{Coverage, EMPTY};

impl GpuRenderer {
    /// T̃ of light j at visible point k, `[k * lights + j]` (the layout of the CPU renderer's
    /// `Prepared::shadow`), read back from the buffer the shading pass reads.
    pub fn shadows(&self, frame: &GpuFrame) -> Vec<f32> {
        let p = &frame.shadows.params;
        let bytes = buffers::read(
            &self.gpu.device,
            &self.gpu.queue,
            &frame.shadows.shadow,
            (p.points * p.lights) as usize * 4,
        );
        bytemuck::pod_collect_to_vec(&bytes)
    }

    /// The visibility buffer as drawn on the GPU (the first point of the nearest segment and
    /// t along it per subsample), read back.
    pub fn coverage(&self, frame: &GpuFrame) -> Coverage {
        let n = frame.width * frame.ss * frame.height * frame.ss;
        let bytes = buffers::read(
            &self.gpu.device,
            &self.gpu.queue,
            &frame.drawing.coverage,
            n * 8,
        );
        let pairs: Vec<[u32; 2]> = bytemuck::pod_collect_to_vec(&bytes);
        Coverage::from_parts(
            frame.width,
            frame.height,
            frame.ss,
            pairs.iter().map(|p| p[0]).collect(),
            pairs.iter().map(|p| f32::from_bits(p[1])).collect(),
        )
    }

    /// The visible points, ascending (the order of [`Self::shadows`]), read back.
    pub fn visible_points(&self, frame: &GpuFrame) -> Vec<u32> {
        let bytes = buffers::read(
            &self.gpu.device,
            &self.gpu.queue,
            &frame.drawing.visible,
            frame.visible * size_of::<PointRecord>(),
        );
        let records: Vec<PointRecord> = bytemuck::pod_collect_to_vec(&bytes);
        records.iter().map(|r| r.index).collect()
    }

    /// The strand seen at each subsample (for picking strands to paint), read back from the
    /// visibility buffer the GPU drew.
    pub fn visibility(&self, frame: &GpuFrame) -> Visibility {
        let cov = self.coverage(frame);
        let of = &frame.drawing.strand_of_point;
        Visibility {
            width: cov.width,
            height: cov.height,
            ss: cov.ss,
            strand: cov
                .segment
                .iter()
                .map(|&s| {
                    if s == EMPTY {
                        Visibility::EMPTY
                    } else {
                        of[s as usize]
                    }
                })
                .collect(),
        }
    }
}
