//! An exclusive prefix sum of a u32 buffer in place on the GPU (`scan.wgsl`): the drawing's
//! work list (lines per segment) and its compaction of visible points (flags per point).

use crate::buffers;
use bytemuck::{Pod, Zeroable};

/// Values per workgroup (scan.wgsl's BLOCK).
const BLOCK: usize = 256;

/// scan.wgsl's `ScanParams`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
struct ScanParams {
    n: u32,
    _pad: [u32; 3],
}

/// The two compiled steps.
pub struct ScanPipelines {
    blocks: wgpu::ComputePipeline,
    add: wgpu::ComputePipeline,
}

impl ScanPipelines {
    pub fn new(device: &wgpu::Device) -> Self {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("scan"),
            source: wgpu::ShaderSource::Wgsl(include_str!("scan.wgsl").into()),
        });
        let pipeline = |entry: &str| buffers::compute_pipeline(device, &module, entry);
        Self {
            blocks: pipeline("scan_blocks"),
            add: pipeline("add_sums"),
        }
    }
}

/// One level: its values' blocks and where their totals go.
struct Level {
    groups: (u32, u32),
    scan: wgpu::BindGroup,
    add: wgpu::BindGroup,
}

/// The scan of the first `n` values of one buffer, its levels allocated.
pub struct Scan {
    levels: Vec<Level>,
}

impl Scan {
    pub fn new(
        device: &wgpu::Device,
        pipelines: &ScanPipelines,
        data: &wgpu::Buffer,
        n: usize,
    ) -> Self {
        let mut levels = Vec::new();
        let (mut data, mut n) = (data.clone(), n);
        loop {
            let blocks = n.div_ceil(BLOCK).max(1);
            let sums = buffers::output(device, "scan sums", blocks * 4);
            let params = ScanParams {
                n: n as u32,
                ..ScanParams::default()
            };
            let uniform = buffers::uniform(device, "scan params", bytemuck::bytes_of(&params));
            let group = |pipeline: &wgpu::ComputePipeline| {
                buffers::bind_group(
                    device,
                    &pipeline.get_bind_group_layout(0),
                    "scan",
                    &[&uniform, &data, &sums],
                )
            };
            levels.push(Level {
                groups: fold(blocks),
                scan: group(&pipelines.blocks),
                add: group(&pipelines.add),
            });
            if blocks == 1 {
                break;
            }
            (data, n) = (sums, blocks);
        }
        Self { levels }
    }

    /// Encodes the scan (one pass per step); returns the dispatches.
    pub fn encode(&self, pipelines: &ScanPipelines, encoder: &mut wgpu::CommandEncoder) -> usize {
        let mut dispatched = 0;
        let mut run = |pipeline: &wgpu::ComputePipeline, level: &Level, group: &wgpu::BindGroup| {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("scan"),
                timestamp_writes: None,
            });
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, group, &[]);
            pass.dispatch_workgroups(level.groups.0, level.groups.1, 1);
            dispatched += 1;
        };
        for level in &self.levels {
            run(&pipelines.blocks, level, &level.scan);
        }
        // The top level's one block is complete; each level below adds its blocks' offsets,
        // scanned one level up.
        for level in self.levels.iter().rev().skip(1) {
            run(&pipelines.add, level, &level.add);
        }
        dispatched
    }
}

/// Workgroups for `blocks`, folded over y past the 65,535 a dimension allows.
fn fold(blocks: usize) -> (u32, u32) {
    let x = (blocks as u32).clamp(1, 65_535);
    (x, (blocks as u32).div_ceil(x))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::device::{GpuDevice, Preference};

    /// The GPU's exclusive scan equals the CPU's over one, two and three levels, with sizes
    /// off the block boundaries.
    #[test]
    fn scan_matches_the_cpu() {
        let gpu = GpuDevice::new(Preference::Any).expect("a GPU adapter (lavapipe will do)");
        let pipelines = ScanPipelines::new(&gpu.device);
        for n in [1usize, 255, 256, 257, 70_000, 65_537 * 2 + 3] {
            let values: Vec<u32> = (0..n as u32)
                .map(|i| (i.wrapping_mul(2_654_435_761) >> 29) & 3)
                .collect();
            let buffer =
                buffers::storage(&gpu.device, "values", bytemuck::cast_slice(&values), true);
            let scan = Scan::new(&gpu.device, &pipelines, &buffer, n);
            let mut encoder = gpu.device.create_command_encoder(&Default::default());
            scan.encode(&pipelines, &mut encoder);
            gpu.queue.submit([encoder.finish()]);
            let got: Vec<u32> = bytemuck::pod_collect_to_vec(&buffers::read(
                &gpu.device,
                &gpu.queue,
                &buffer,
                n * 4,
            ));
            let mut acc = 0u32;
            let want: Vec<u32> = values
                .iter()
                .map(|&v| {
                    let before = acc;
                    acc += v;
                    before
                })
                .collect();
            assert_eq!(got, want, "n = {n}");
        }
    }
}
