//! Small wgpu helpers: storage buffers that are never empty (a binding must have a size),
//! compute pipelines and bind groups, readback, and the timestamp queries of one frame's passes.

use wgpu::util::DeviceExt;

/// The smallest buffer made: a binding needs at least one element of any record here.
const MIN_BYTES: usize = 64;

/// The compute pipeline of `module`'s entry point `entry`, its bind group layout inferred from
/// the shader.
pub fn compute_pipeline(
    device: &wgpu::Device,
    module: &wgpu::ShaderModule,
    entry: &str,
) -> wgpu::ComputePipeline {
    device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some(entry),
        layout: None,
        module,
        entry_point: Some(entry),
        compilation_options: Default::default(),
        cache: None,
    })
}

/// A bind group of `buffers` at bindings 0, 1, … of `layout`.
pub fn bind_group(
    device: &wgpu::Device,
    layout: &wgpu::BindGroupLayout,
    label: &str,
    buffers: &[&wgpu::Buffer],
) -> wgpu::BindGroup {
    let entries: Vec<wgpu::BindGroupEntry> = buffers
        .iter()
        .enumerate()
        .map(|(k, b)| wgpu::BindGroupEntry {
            binding: k as u32,
            resource: b.as_entire_binding(),
        })
        .collect();
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(label),
        layout,
        entries: &entries,
    })
}

/// A storage buffer holding `bytes` (zero-padded to [`MIN_BYTES`]).
pub fn storage(device: &wgpu::Device, label: &str, bytes: &[u8], writable: bool) -> wgpu::Buffer {
    let mut usage = wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST;
    if writable {
        usage |= wgpu::BufferUsages::COPY_SRC;
    }
    if bytes.len() >= MIN_BYTES {
        return device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents: bytes,
            usage,
        });
    }
    let mut padded = bytes.to_vec();
    padded.resize(MIN_BYTES, 0);
    device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(label),
        contents: &padded,
        usage,
    })
}

/// A zeroed storage buffer of `bytes` that shaders write and readback copies from.
pub fn output(device: &wgpu::Device, label: &str, bytes: usize) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: bytes.max(MIN_BYTES) as u64,
        usage: wgpu::BufferUsages::STORAGE
            | wgpu::BufferUsages::COPY_SRC
            | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

/// A uniform buffer holding `bytes`.
pub fn uniform(device: &wgpu::Device, label: &str, bytes: &[u8]) -> wgpu::Buffer {
    device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(label),
        contents: bytes,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
    })
}

/// Copies the first `bytes` of `buffer` back to the CPU (blocks until the GPU is done).
pub fn read(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    buffer: &wgpu::Buffer,
    bytes: usize,
) -> Vec<u8> {
    if bytes == 0 {
        return Vec::new();
    }
    let size = (bytes as u64).next_multiple_of(wgpu::COPY_BUFFER_ALIGNMENT);
    let staging = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback"),
        size,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
    encoder.copy_buffer_to_buffer(buffer, 0, &staging, 0, size);
    queue.submit([encoder.finish()]);
    let slice = staging.slice(..);
    let (tx, rx) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    device
        .poll(wgpu::PollType::wait_indefinitely())
        .expect("the GPU device was lost while reading back");
    rx.recv()
        .expect("map callback")
        .expect("the GPU could not map a readback buffer");
    let out = slice.get_mapped_range().expect("a mapped readback buffer")[..bytes].to_vec();
    staging.unmap();
    out
}

/// Timestamps around a frame's passes, where the device has them: pass k writes queries 2k and
/// 2k + 1.
pub struct Stopwatch {
    set: wgpu::QuerySet,
    resolved: wgpu::Buffer,
    period_ns: f32,
    passes: u32,
}

impl Stopwatch {
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue, passes: u32) -> Option<Self> {
        if !device.features().contains(wgpu::Features::TIMESTAMP_QUERY) {
            return None;
        }
        let set = device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("stage timestamps"),
            ty: wgpu::QueryType::Timestamp,
            count: 2 * passes,
        });
        let resolved = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("stage timestamps resolved"),
            size: 16 * passes as u64,
            usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        Some(Self {
            set,
            resolved,
            period_ns: queue.get_timestamp_period(),
            passes,
        })
    }

    /// The timestamp writes of pass `k`.
    pub fn writes(&self, k: u32) -> wgpu::ComputePassTimestampWrites<'_> {
        wgpu::ComputePassTimestampWrites {
            query_set: &self.set,
            beginning_of_pass_write_index: Some(2 * k),
            end_of_pass_write_index: Some(2 * k + 1),
        }
    }

    /// The queries, for passes that write only one end of a span (pass k: 2k and 2k + 1).
    pub fn query_set(&self) -> &wgpu::QuerySet {
        &self.set
    }

    /// Resolves the queries at the end of `encoder`'s work.
    pub fn resolve(&self, encoder: &mut wgpu::CommandEncoder) {
        encoder.resolve_query_set(&self.set, 0..2 * self.passes, &self.resolved, 0);
    }

    /// Seconds each pass took on the GPU.
    pub fn seconds(&self, device: &wgpu::Device, queue: &wgpu::Queue) -> Vec<f64> {
        let bytes = read(device, queue, &self.resolved, 16 * self.passes as usize);
        let ticks: Vec<u64> = bytemuck::pod_collect_to_vec(&bytes);
        ticks
            .chunks(2)
            .map(|t| t[1].saturating_sub(t[0]) as f64 * self.period_ns as f64 * 1e-9)
            .collect()
    }
}
