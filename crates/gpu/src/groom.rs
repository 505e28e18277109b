//! The groom on the device: its points (position and thickness), segments, tangents and the
//! strand of every point, uploaded once and read by the drawing ([`crate::draw`]) and the
//! opacity maps ([`crate::shadows`]) of every frame drawn from it, so that a camera move or an
//! environment rotation sends no strand again ([`crate::Passes::groom_uploads`] counts the
//! uploads).

use crate::buffers;
use cuticle_groom::Groom;

/// The groom's buffers, and what was uploaded (to tell whether another groom is this one).
pub struct GroomBuffers {
    /// Per point: position and thickness.
    pub points: wgpu::Buffer,
    /// The first point of every segment (a strand of n points has n − 1).
    pub segments: wgpu::Buffer,
    /// Per point: the unit tangent (and a spare).
    pub tangents: wgpu::Buffer,
    /// Per point: its strand.
    pub strand_of_point: wgpu::Buffer,
    pub point_count: usize,
    pub segment_count: usize,
    uploaded_points: Vec<[f32; 4]>,
    uploaded_segments: Vec<u32>,
}

impl GroomBuffers {
    /// Uploads `groom`.
    pub fn new(device: &wgpu::Device, groom: &Groom) -> Self {
        let points = point_records(groom);
        let segments = segment_starts(groom);
        let tangents: Vec<[f32; 4]> = groom
            .tangents()
            .iter()
            .map(|t| [t.x, t.y, t.z, 0.0])
            .collect();
        let storage = |label, bytes: &[u8]| buffers::storage(device, label, bytes, false);
        Self {
            points: storage("groom points", bytemuck::cast_slice(&points)),
            segments: storage("segments", bytemuck::cast_slice(&segments)),
            tangents: storage("tangents", bytemuck::cast_slice(&tangents)),
            strand_of_point: storage(
                "strand of point",
                bytemuck::cast_slice(&groom.strand_of_points()),
            ),
            point_count: points.len(),
            segment_count: segments.len(),
            uploaded_points: points,
            uploaded_segments: segments,
        }
    }

    /// Whether these buffers hold `groom` (its points, thicknesses and strands; the tangents
    /// and each point's strand follow from them).
    pub fn holds(&self, groom: &Groom) -> bool {
        self.point_count == groom.point_count()
            && self.uploaded_points == point_records(groom)
            && self.uploaded_segments == segment_starts(groom)
    }
}

fn point_records(groom: &Groom) -> Vec<[f32; 4]> {
    groom
        .positions()
        .iter()
        .zip(groom.thickness())
        .map(|(p, &t)| [p.x, p.y, p.z, t])
        .collect()
}

fn segment_starts(groom: &Groom) -> Vec<u32> {
    (0..groom.strand_count())
        .flat_map(|s| {
            let r = groom.strand_range(s);
            (r.start..r.end.saturating_sub(1)).map(|i| i as u32)
        })
        .collect()
}
