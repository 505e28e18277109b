//! Stage 3 on the GPU: T̃ of every lit SRBF light at every visible point, from deep opacity maps
//! (Yuksel & Keyser 2008) filtered to each light's bandwidth, frame/shadows.rs's maps (the
//! reference, in f64) built and read in `shadows.wgsl`, one dispatch per step over all
//! lights at once:
//! 1. `first_hair`: every segment sampled at most a texel apart, the first hair of each texel;
//! 2. `fill_layers`: each sample's fiber count (projected fiber area per texel area) into its
//!    layer behind that first hair ([`cuticle_render::frame::shadows::LAYERS`]);
//! 3. `sum_rows` and 4. `sum_columns`: each layer's summed-area table;
//! 5. `transmittance`: T̃ = exp(−density × depth) at each visible point, each layer boxed to the
//!    light's bandwidth, into the buffer the shading pass reads (no CPU round trip).
//!
//! The maps are built in batches as large as the device's buffer limits allow (the layers of
//! one batch in one buffer, reused by the next): each batch runs steps 1–5 for its own lights,
//! and step 5 leaves the other batches' lights as they are.
//!
//! Each map's frame ([`MapFrame`]) is computed on the CPU in f64, as the reference does. Fiber
//! counts are summed in fixed point (deterministic, unlike f32 atomics, which WGSL lacks), at
//! the largest power-of-two scale for which the groom's whole projected area stays below 2^31:
//! the summed-area tables may then wrap in u32 and every box sum is still exact.

use crate::buffers;
use bytemuck::{Pod, Zeroable};
use cuticle_groom::Groom;
use cuticle_render::WorldLight;
use cuticle_render::frame::shadows::{LAYERS, MapFrame, NL, ShadowOptions};
use glam::DVec3;

/// Invocations per workgroup (shadows.wgsl's `@workgroup_size`).
pub const WORKGROUP: u32 = 64;
/// Workgroups along x of a grid-stride dispatch over segments or points.
const STRIDE_GROUPS: u32 = 1024;
/// shadows.wgsl's NO_MAP.
const NO_MAP: u32 = u32::MAX;
/// shadows.wgsl's OTHER_BATCH: a light whose map another batch builds.
const OTHER_BATCH: u32 = u32::MAX - 1;

/// The entry points, in dispatch order.
pub const STEPS: [&str; 5] = [
    "first_hair",
    "fill_layers",
    "sum_rows",
    "sum_columns",
    "transmittance",
];

/// shadows.wgsl's `ShadowParams`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct ShadowParams {
    pub maps: u32,
    pub lights: u32,
    pub n: u32,
    pub segments: u32,
    pub points: u32,
    pub scale: f32,
    pub density: f32,
    pub _pad: u32,
    pub layers: [f32; 8],
}

/// shadows.wgsl's `MapRecord`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct MapRecord {
    pub centre: [f32; 3],
    pub radius: f32,
    pub u: [f32; 3],
    pub texel: f32,
    pub v: [f32; 3],
    pub light: u32,
    pub travel: [f32; 3],
    pub bandwidth: f32,
}

/// The compiled steps, sharing one layout.
pub struct ShadowPipelines {
    layout: wgpu::BindGroupLayout,
    steps: Vec<wgpu::ComputePipeline>,
}

/// Bindings of shadows.wgsl (0 the uniform, then storage buffers).
const BINDINGS: u32 = 9;

impl ShadowPipelines {
    pub fn new(device: &wgpu::Device) -> Self {
        let entries: Vec<wgpu::BindGroupLayoutEntry> = (0..BINDINGS)
            .map(|b| wgpu::BindGroupLayoutEntry {
                binding: b,
                visibility: wgpu::ShaderStages::COMPUTE,
                ty: wgpu::BindingType::Buffer {
                    ty: if b == 0 {
                        wgpu::BufferBindingType::Uniform
                    } else {
                        wgpu::BufferBindingType::Storage { read_only: false }
                    },
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            })
            .collect();
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("opacity maps"),
            entries: &entries,
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("opacity maps"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("opacity maps"),
            source: wgpu::ShaderSource::Wgsl(include_str!("shadows.wgsl").into()),
        });
        let steps = STEPS
            .iter()
            .map(|entry| {
                device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                    label: Some(entry),
                    layout: Some(&pipeline_layout),
                    module: &module,
                    entry_point: Some(entry),
                    compilation_options: Default::default(),
                    cache: None,
                })
            })
            .collect();
        Self { layout, steps }
    }
}

/// One frame's opacity maps on the device, and the shadows they give.
pub struct ShadowMaps {
    /// The whole frame's counts: every lit light's map, every light, every visible point.
    pub params: ShadowParams,
    /// Each batch's map count and bindings (its uniform among them).
    batches: Vec<(u32, wgpu::BindGroup)>,
    first: wgpu::Buffer,
    layers: wgpu::Buffer,
    /// T̃ per (visible point, light), as the shading pass binds it.
    pub shadow: wgpu::Buffer,
}

/// What the maps are built from.
pub struct ShadowInputs<'a> {
    pub groom: &'a Groom,
    /// The same groom on the device.
    pub groom_buffers: &'a crate::groom::GroomBuffers,
    pub lights: &'a [WorldLight],
    pub options: &'a ShadowOptions,
    /// The visible points' buffer (shading's `PointRecord`s).
    pub points: &'a wgpu::Buffer,
    pub point_count: usize,
    /// The most maps one batch builds, below what the device's limits allow (`None`: those).
    pub max_batch: Option<usize>,
}

impl ShadowMaps {
    /// Bytes the largest buffers take, for the device's buffer limits: (one map's layers, the
    /// shadows). The maps are built in batches, so one map's layers must fit.
    pub fn sizes(lights: &[WorldLight], resolution: usize, point_count: usize) -> (usize, usize) {
        (map_bytes(resolution), point_count * lights.len() * 4)
    }

    /// Allocates the buffers and uploads the maps' frames, reading the groom from
    /// `inputs.groom_buffers` (no dispatch yet).
    pub fn new(device: &wgpu::Device, pipelines: &ShadowPipelines, inputs: &ShadowInputs) -> Self {
        let groom = inputs.groom;
        let n = inputs.options.resolution;
        let lit = lit_lights(inputs.lights);
        let maps: Vec<MapRecord> = lit
            .iter()
            .map(|&j| {
                let light = &inputs.lights[j];
                map_record(
                    &MapFrame::new(groom, light.direction, n),
                    j,
                    light.bandwidth,
                )
            })
            .collect();
        let texel = maps.first().map_or(1.0, |m| m.texel as f64);
        let mut layers = [0.0f32; 8];
        for (l, &b) in layers.iter_mut().zip(&LAYERS) {
            *l = b as f32;
        }
        let params = ShadowParams {
            maps: maps.len() as u32,
            lights: inputs.lights.len() as u32,
            n: n as u32,
            segments: inputs.groom_buffers.segment_count as u32,
            points: inputs.point_count as u32,
            scale: fixed_point_scale(groom, texel) as f32,
            density: inputs.options.density as f32,
            _pad: 0,
            layers,
        };
        let per_batch = maps_per_batch(&device.limits(), n)
            .min(inputs.max_batch.unwrap_or(usize::MAX))
            .min(maps.len())
            .max(1);
        let first = buffers::output(device, "first hair", per_batch * n * n * 4);
        let layer_buffer = buffers::output(device, "opacity layers", per_batch * map_bytes(n));
        let shadow = buffers::output(
            device,
            "shadows",
            inputs.point_count * inputs.lights.len() * 4,
        );
        let chunks: Vec<(usize, &[MapRecord])> = maps
            .chunks(per_batch)
            .enumerate()
            .map(|(b, chunk)| (b * per_batch, chunk))
            .collect();
        let chunks = if chunks.is_empty() {
            vec![(0, &maps[..])]
        } else {
            chunks
        };
        let batches = chunks
            .into_iter()
            .map(|(start, chunk)| {
                let mut map_of_light = vec![NO_MAP; inputs.lights.len()];
                for (m, &j) in lit.iter().enumerate() {
                    map_of_light[j] = match m.checked_sub(start) {
                        Some(i) if i < chunk.len() => i as u32,
                        _ => OTHER_BATCH,
                    };
                }
                let batch = ShadowParams {
                    maps: chunk.len() as u32,
                    ..params
                };
                let storage = |label, bytes: &[u8]| buffers::storage(device, label, bytes, false);
                let uniform = buffers::uniform(device, "shadow params", bytemuck::bytes_of(&batch));
                let maps_buffer = storage("map frames", bytemuck::cast_slice(chunk));
                let map_of_light_buffer =
                    storage("map of light", bytemuck::cast_slice(&map_of_light));
                let bound = [
                    &uniform,
                    &maps_buffer,
                    &inputs.groom_buffers.points,
                    &inputs.groom_buffers.segments,
                    &first,
                    &layer_buffer,
                    inputs.points,
                    &shadow,
                    &map_of_light_buffer,
                ];
                let group = buffers::bind_group(device, &pipelines.layout, "opacity maps", &bound);
                (batch.maps, group)
            })
            .collect();
        Self {
            params,
            batches,
            first,
            layers: layer_buffer,
            shadow,
        }
    }

    /// Encodes the five steps of every batch (each after clearing the maps) into `encoder`;
    /// `timestamps` times the whole stage as one span, where the device has them.
    pub fn encode(
        &self,
        pipelines: &ShadowPipelines,
        encoder: &mut wgpu::CommandEncoder,
        timestamps: Option<(&wgpu::QuerySet, u32)>,
    ) -> usize {
        let p = &self.params;
        let along = |count: u32| count.div_ceil(WORKGROUP).clamp(1, STRIDE_GROUPS);
        let lines = p.n.div_ceil(WORKGROUP);
        let last = STEPS.len() - 1;
        let mut dispatched = 0;
        for (b, (maps, group)) in self.batches.iter().enumerate() {
            let maps = *maps;
            encoder.clear_buffer(&self.first, 0, None);
            encoder.clear_buffer(&self.layers, 0, None);
            let grids = [
                (along(p.segments), maps),
                (along(p.segments), maps),
                (lines, maps * NL as u32),
                (lines, maps * NL as u32),
                (along(p.points), p.lights),
            ];
            let (first_batch, last_batch) = (b == 0, b + 1 == self.batches.len());
            for (k, (pipeline, &(x, y))) in pipelines.steps.iter().zip(&grids).enumerate() {
                if y == 0 || (k < last && (p.segments == 0 || p.points == 0)) {
                    continue;
                }
                let (opens, closes) = (first_batch && k == 0, last_batch && k == last);
                let writes = timestamps.map(|(set, base)| wgpu::ComputePassTimestampWrites {
                    query_set: set,
                    beginning_of_pass_write_index: opens.then_some(base),
                    end_of_pass_write_index: closes.then_some(base + 1),
                });
                let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: Some(STEPS[k]),
                    timestamp_writes: writes.filter(|_| opens || closes),
                });
                pass.set_pipeline(pipeline);
                pass.set_bind_group(0, group, &[]);
                pass.dispatch_workgroups(x, y, 1);
                dispatched += 1;
            }
        }
        dispatched
    }
}

/// Bytes of one map's layers at `n` texels a side.
fn map_bytes(n: usize) -> usize {
    NL * n * n * 4
}

/// How many maps' layers fit in one buffer under `limits` (at least one: [`ShadowMaps::sizes`]
/// lets a caller refuse a resolution at which not even one does).
fn maps_per_batch(limits: &wgpu::Limits, n: usize) -> usize {
    let limit = limits
        .max_storage_buffer_binding_size
        .min(limits.max_buffer_size);
    (limit / map_bytes(n) as u64).max(1) as usize
}

/// The lights that add light (the reference builds no map for a black one: T̃ = 1).
fn lit_lights(lights: &[WorldLight]) -> Vec<usize> {
    (0..lights.len())
        .filter(|&j| lights[j].radiance != DVec3::ZERO)
        .collect()
}

fn map_record(f: &MapFrame, light: usize, bandwidth: f64) -> MapRecord {
    let v3 = |v: DVec3| v.as_vec3().to_array();
    MapRecord {
        centre: v3(f.centre),
        radius: f.radius as f32,
        u: v3(f.axes[0]),
        texel: f.texel as f32,
        v: v3(f.axes[1]),
        light: light as u32,
        travel: v3(f.axes[2]),
        bandwidth: bandwidth as f32,
    }
}

/// Fixed-point units per fiber count: the largest power of two (at most 2^20) at which the
/// groom's whole projected fiber area, bounded by Σ length × thickness / texel² over its
/// segments, stays below 2^30 (every sample's rounding adds at most half a unit, so the sums
/// keep a factor of two to spare below 2^31).
pub fn fixed_point_scale(groom: &Groom, texel: f64) -> f64 {
    let pos = groom.positions();
    let thick = groom.thickness();
    let mut total = 0.0f64;
    let mut samples = 0usize;
    for s in 0..groom.strand_count() {
        let r = groom.strand_range(s);
        for i in r.start..r.end.saturating_sub(1) {
            let length = (pos[i + 1] - pos[i]).as_dvec3().length();
            total += length * 0.5 * (thick[i] + thick[i + 1]) as f64 / (texel * texel);
            samples += (length / texel).ceil().max(1.0) as usize;
        }
    }
    let budget = (1u64 << 30) as f64 - samples as f64;
    if total <= 0.0 || budget <= 0.0 {
        return 1.0;
    }
    (budget / total).log2().floor().clamp(0.0, 20.0).exp2()
}
