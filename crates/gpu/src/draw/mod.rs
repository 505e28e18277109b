//! Stage 2 on the GPU: strands drawn into the supersampled visibility buffer, frame/draw.rs's
//! rasteriser (the reference) run as compute passes of `draw.wgsl`, one dispatch per step:
//! 1. `project`: every point to subsample coordinates, its depth and its half width;
//! 2. `count_lines`: each segment's count of lines along its major axis within the image;
//! 3. a prefix sum of those counts ([`scan`]) and `size_cover`: the work list of step 4, one
//!    invocation per line of a segment (so that no invocation draws more than one line across
//!    the image, however large a segment is on screen);
//! 4. `cover`, twice: every subsample centre within a segment's capsule (at least a subsample
//!    wide; where the strand is thinner, a centre only with probability true width / drawn
//!    width, by raster.rs's `coverage_hash` of the strand and the subsample) keeps the nearest
//!    depth, then the lowest segment at that depth (the CPU's strictly-nearer test in segment
//!    order keeps the same one; atomics have 32 bits, too few for both in one pass);
//! 5. `settle`: each subsample's segment and position t along it into the buffer the resolve
//!    reads, and the points of every visible segment flagged;
//! 6. a prefix sum of the flags and `compact`: the visible points' records in ascending point
//!    order, as shading and the opacity maps read them (the CPU's `visible_points` order).
//!
//! The camera's frame (its axes, the focal length) comes from the CPU renderer's f64 `View`;
//! the eye is passed as two f32s (value and remainder) so that p − eye loses nothing. The
//! rest is f32, as the reference's raster is, apart from its projection (f64 rounded to f32):
//! a subsample centre within a few f32 ulps of a capsule's edge, or two depths within a few
//! ulps, may fall the other way (tests/drawing.rs bounds how often).

pub mod scan;

use crate::buffers;
use crate::groom::GroomBuffers;
use bytemuck::{Pod, Zeroable};
use cuticle_groom::Groom;
use cuticle_render::scene::camera::{NEAR, View};
use scan::{Scan, ScanPipelines};

/// Invocations per workgroup (draw.wgsl's `@workgroup_size`, but `size_cover`'s).
pub const WORKGROUP: u32 = 64;

/// The entry points, in dispatch order (`cover` runs twice; the scans run between).
pub const STEPS: [&str; 6] = [
    "project",
    "count_lines",
    "size_cover",
    "cover",
    "settle",
    "compact",
];

/// draw.wgsl's `DrawParams`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct DrawParams {
    pub eye_hi: [f32; 3],
    pub points: u32,
    pub eye_lo: [f32; 3],
    pub segments: u32,
    pub right: [f32; 3],
    pub focal: f32,
    pub up: [f32; 3],
    pub half_width: f32,
    pub forward: [f32; 3],
    pub half_height: f32,
    pub ss: f32,
    pub sub_width: u32,
    pub sub_height: u32,
    pub mode: u32,
    pub near: f32,
    pub _pad: [u32; 3],
}

/// The compiled steps.
pub struct DrawPipelines {
    steps: Vec<wgpu::ComputePipeline>,
    scan: ScanPipelines,
}

impl DrawPipelines {
    pub fn new(device: &wgpu::Device) -> Self {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("draw"),
            source: wgpu::ShaderSource::Wgsl(include_str!("draw.wgsl").into()),
        });
        let steps = STEPS
            .iter()
            .map(|entry| buffers::compute_pipeline(device, &module, entry))
            .collect();
        Self {
            steps,
            scan: ScanPipelines::new(device),
        }
    }

    fn step(&self, name: &str) -> &wgpu::ComputePipeline {
        &self.steps[STEPS.iter().position(|s| *s == name).expect("a step")]
    }
}

/// What one drawing is of.
pub struct DrawInputs<'a> {
    pub groom: &'a Groom,
    pub view: &'a View,
    pub width: usize,
    pub height: usize,
    /// Subsamples per pixel along each axis.
    pub ss: usize,
}

/// Bytes of the drawing's buffers that grow with the image (the visibility buffer, the depth
/// and segment keys) and with the groom (the visible points' records), for the device's
/// limits.
pub fn sizes(inputs: &DrawInputs) -> [(&'static str, usize); 2] {
    let ss = inputs.ss.max(1);
    let subsamples = inputs.width * ss * inputs.height * ss;
    [
        ("the visibility buffer", subsamples * 8),
        (
            "the visible points",
            inputs.groom.point_count() * size_of::<crate::shading::PointRecord>(),
        ),
    ]
}

/// One frame's drawing on the device: its inputs uploaded, its buffers allocated.
pub struct Drawing {
    pub params: DrawParams,
    /// Per subsample: (first point of the nearest segment or `EMPTY`, t's bits), the resolve's
    /// input.
    pub coverage: wgpu::Buffer,
    /// The visible points' records (shading's `PointRecord`), the first `visible` of them set.
    pub visible: wgpu::Buffer,
    /// The strand of every point, for picking.
    pub strand_of_point: Vec<u32>,
    depth: wgpu::Buffer,
    nearest: wgpu::Buffer,
    seen: wgpu::Buffer,
    cover_groups: wgpu::Buffer,
    /// Bind groups of each step, in [`STEPS`] order; `cover`'s two passes have one each.
    groups: Vec<wgpu::BindGroup>,
    cover_second: wgpu::BindGroup,
    lines_scan: Scan,
    seen_scan: Scan,
    count: wgpu::Buffer,
}

impl Drawing {
    /// Uploads the camera and allocates the buffers, reading the groom from `groom` (already
    /// on the device; no dispatch yet).
    pub fn new(
        device: &wgpu::Device,
        pipelines: &DrawPipelines,
        inputs: &DrawInputs,
        groom_buffers: &GroomBuffers,
    ) -> Self {
        let groom = inputs.groom;
        let ss = inputs.ss.max(1);
        let (sw, sh) = (inputs.width * ss, inputs.height * ss);
        let (point_count, segment_count) = (groom_buffers.point_count, groom_buffers.segment_count);
        let strand_of_point = groom.strand_of_points();
        let view = inputs.view;
        let eye_hi = view.eye.as_vec3();
        let params = DrawParams {
            eye_hi: eye_hi.to_array(),
            points: point_count as u32,
            eye_lo: (view.eye - eye_hi.as_dvec3()).as_vec3().to_array(),
            segments: segment_count as u32,
            right: view.right.as_vec3().to_array(),
            focal: view.focal as f32,
            up: view.up.as_vec3().to_array(),
            half_width: (0.5 * view.width) as f32,
            forward: view.forward.as_vec3().to_array(),
            half_height: (0.5 * view.height) as f32,
            ss: ss as f32,
            sub_width: sw as u32,
            sub_height: sh as u32,
            mode: 0,
            near: NEAR as f32,
            _pad: [0; 3],
        };
        let uniform = buffers::uniform(device, "draw params", bytemuck::bytes_of(&params));
        let second = DrawParams { mode: 1, ..params };
        let uniform_second = buffers::uniform(device, "draw params", bytemuck::bytes_of(&second));
        let groom_buffer = &groom_buffers.points;
        let segments_buffer = &groom_buffers.segments;
        let tangents_buffer = &groom_buffers.tangents;
        let strands_buffer = &groom_buffers.strand_of_point;
        let projected = buffers::output(device, "projected points", point_count * 16);
        let lines = buffers::output(device, "lines", (segment_count + 1) * 4);
        let depth = buffers::output(device, "nearest depth", sw * sh * 4);
        let nearest = buffers::output(device, "nearest segment", sw * sh * 4);
        let coverage = buffers::output(device, "visibility", sw * sh * 8);
        let seen = buffers::output(device, "seen points", (point_count + 1) * 4);
        let visible = buffers::output(
            device,
            "visible points",
            point_count * size_of::<crate::shading::PointRecord>(),
        );
        let cover_groups = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("cover workgroups"),
            size: 16,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::INDIRECT,
            mapped_at_creation: false,
        });
        let count = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("visible count"),
            size: 4,
            usage: wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let bound: [(u32, &wgpu::Buffer); 13] = [
            (0, &uniform),
            (1, groom_buffer),
            (2, segments_buffer),
            (3, &projected),
            (4, &lines),
            (5, &depth),
            (6, &nearest),
            (7, &coverage),
            (8, &seen),
            (9, tangents_buffer),
            (10, strands_buffer),
            (11, &visible),
            (12, &cover_groups),
        ];
        let uses: [&[u32]; 6] = [
            &[0, 1, 3],
            &[0, 2, 3, 4],
            &[0, 4, 12],
            &[0, 2, 3, 4, 5, 6, 10],
            &[0, 3, 6, 7, 8],
            &[0, 1, 8, 9, 10, 11],
        ];
        let group = |pipeline: &wgpu::ComputePipeline, used: &[u32], first: &wgpu::Buffer| {
            let entries: Vec<wgpu::BindGroupEntry> = used
                .iter()
                .map(|&b| wgpu::BindGroupEntry {
                    binding: b,
                    resource: if b == 0 { first } else { bound[b as usize].1 }.as_entire_binding(),
                })
                .collect();
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("draw"),
                layout: &pipeline.get_bind_group_layout(0),
                entries: &entries,
            })
        };
        let groups = pipelines
            .steps
            .iter()
            .zip(uses)
            .map(|(p, used)| group(p, used, &uniform))
            .collect();
        let cover_second = group(pipelines.step("cover"), uses[3], &uniform_second);
        Self {
            params,
            lines_scan: Scan::new(device, &pipelines.scan, &lines, segment_count + 1),
            seen_scan: Scan::new(device, &pipelines.scan, &seen, point_count + 1),
            coverage,
            visible,
            strand_of_point,
            depth,
            nearest,
            seen,
            cover_groups,
            groups,
            cover_second,
            count,
        }
    }

    /// Encodes the drawing (after clearing its keys and flags) into `encoder`, and the copy of
    /// the visible points' count that [`Self::read_count`] reads; `timestamps` times the whole
    /// stage as one span, where the device has them. Returns the dispatches.
    pub fn encode(
        &self,
        pipelines: &DrawPipelines,
        encoder: &mut wgpu::CommandEncoder,
        timestamps: Option<(&wgpu::QuerySet, u32)>,
    ) -> usize {
        encoder.clear_buffer(&self.depth, 0, None);
        encoder.clear_buffer(&self.nearest, 0, None);
        encoder.clear_buffer(&self.seen, 0, None);
        let p = &self.params;
        let along = |count: u32| count.div_ceil(WORKGROUP).clamp(1, 65_535);
        let subsamples = p.sub_width * p.sub_height;
        let mut dispatched = 0;
        let mut pass = |encoder: &mut wgpu::CommandEncoder,
                        step: usize,
                        group: &wgpu::BindGroup,
                        size: Option<u32>,
                        begin: bool,
                        end: bool| {
            let writes = timestamps.map(|(set, base)| wgpu::ComputePassTimestampWrites {
                query_set: set,
                beginning_of_pass_write_index: begin.then_some(base),
                end_of_pass_write_index: end.then_some(base + 1),
            });
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some(STEPS[step]),
                timestamp_writes: writes.filter(|_| begin || end),
            });
            pass.set_pipeline(&pipelines.steps[step]);
            pass.set_bind_group(0, group, &[]);
            match size {
                Some(x) => pass.dispatch_workgroups(x, 1, 1),
                None => pass.dispatch_workgroups_indirect(&self.cover_groups, 0),
            }
            dispatched += 1;
        };
        pass(
            encoder,
            0,
            &self.groups[0],
            Some(along(p.points)),
            true,
            false,
        );
        pass(
            encoder,
            1,
            &self.groups[1],
            Some(along(p.segments)),
            false,
            false,
        );
        let mut scans = self.lines_scan.encode(&pipelines.scan, encoder);
        pass(encoder, 2, &self.groups[2], Some(1), false, false);
        pass(encoder, 3, &self.groups[3], None, false, false);
        pass(encoder, 3, &self.cover_second, None, false, false);
        pass(
            encoder,
            4,
            &self.groups[4],
            Some(along(subsamples)),
            false,
            false,
        );
        scans += self.seen_scan.encode(&pipelines.scan, encoder);
        pass(
            encoder,
            5,
            &self.groups[5],
            Some(along(p.points)),
            false,
            true,
        );
        encoder.copy_buffer_to_buffer(&self.seen, p.points as u64 * 4, &self.count, 0, 4);
        dispatched + scans
    }

    /// The count of visible points, once the encoded drawing has run.
    pub fn read_count(&self, device: &wgpu::Device, queue: &wgpu::Queue) -> usize {
        let bytes = buffers::read(device, queue, &self.count, 4);
        u32::from_le_bytes(bytes[..4].try_into().expect("four bytes")) as usize
    }
}
