//! The GPU renderer: the static tables and compiled passes of one device, and the frame calls
//! (prepare, shade, update_strands, visibility) that [`crate`]'s documentation walks through;
//! [`readback`] reads a frame's buffers back for tests and picking.

mod readback;

use crate::buffers::{self, Stopwatch};
use crate::device::GpuDevice;
use crate::draw::{self, DrawInputs, DrawPipelines, Drawing};
use crate::frame::{GpuFrame, GpuSeconds, Passes};
use crate::groom::GroomBuffers;
use crate::resolve::{self, ResolveParams};
use crate::shading::{self, LightRecord, ShadeParams};
use crate::shadows::{ShadowInputs, ShadowMaps, ShadowPipelines};
use crate::strands::{self, StrandError, StrandParams, StrandSource};
use crate::tables::{self, GridDesc, slot};
use cuticle_render::frame::renderer::{background as frame_background, srbf_lights};
use cuticle_render::scene::hair::caustic_bandwidth;
use cuticle_render::srbf::light_clusters::LightClusters;
use cuticle_render::tables::absorption_axis::MU_A_SCALE;
use cuticle_render::tables::spread::MIN_Z;
use cuticle_render::{Image, Method, Renderer, Scene, Timings};
use glam::DVec3;
use std::sync::Arc;
use std::time::Instant;

/// Why a scene cannot be rendered on the GPU.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum GpuError {
    #[error("the GPU back end renders the SRBF method only (use --device cpu for --method brute)")]
    Method,
    #[error("{what} needs {bytes} bytes, more than the GPU's buffer limit of {limit}")]
    TooLarge {
        what: &'static str,
        bytes: u64,
        limit: u64,
    },
}

/// The renderer on one device.
pub struct GpuRenderer {
    gpu: GpuDevice,
    cpu: Renderer,
    static_tables: wgpu::Buffer,
    static_grids: [GridDesc; slot::COUNT],
    shade: wgpu::ComputePipeline,
    resolve: wgpu::ComputePipeline,
    shadows: ShadowPipelines,
    draw: DrawPipelines,
    /// The most opacity maps one batch builds (`None`: as many as the device's buffer limits
    /// allow); see [`Self::with_shadow_batch`].
    shadow_batch: Option<usize>,
}

impl GpuRenderer {
    /// Uploads the CPU renderer's parameter-independent tables and compiles the passes. The
    /// CPU renderer's lobe and back-scattering caches are shared (a clone of `cpu` holds the
    /// same ones).
    pub fn new(gpu: &GpuDevice, cpu: &Renderer) -> Self {
        let packed = tables::static_grids(&cpu.tables, &cpu.half, &cpu.spread);
        let mut static_grids = [GridDesc::default(); slot::COUNT];
        packed.describe(&mut static_grids);
        let device = &gpu.device;
        Self {
            static_tables: buffers::storage(
                device,
                "static tables",
                bytemuck::cast_slice(&packed.data),
                false,
            ),
            static_grids,
            shade: shading::pipeline(device),
            resolve: resolve::pipeline(device),
            shadows: ShadowPipelines::new(device),
            draw: DrawPipelines::new(device),
            gpu: gpu.clone(),
            cpu: cpu.clone(),
            shadow_batch: None,
        }
    }

    /// This renderer building at most `maps` opacity maps per batch (at least one), as a device
    /// with smaller buffer limits would: the shadows are the same, in more passes.
    pub fn with_shadow_batch(mut self, maps: usize) -> Self {
        self.shadow_batch = Some(maps.max(1));
        self
    }

    pub fn device(&self) -> &GpuDevice {
        &self.gpu
    }

    /// Stages 2–3 on the GPU: drawing ([`crate::draw`]) into the visibility buffer and the
    /// visible points' records, with the lights, the background (the environment through each
    /// pixel, on the CPU while the GPU draws) and every strand's record uploaded, then the
    /// opacity maps and shadows at the visible points ([`crate::shadows`]).
    pub fn prepare(&self, scene: &Scene) -> Result<GpuFrame, GpuError> {
        self.prepare_keeping(scene, None)
    }

    /// [`Self::prepare`], taking from `kept` (a frame of the same renderer) the groom's
    /// buffers where they hold the scene's groom and the strand records where the strand count
    /// and absorption source are the scene's, instead of uploading them again.
    fn prepare_keeping(
        &self,
        scene: &Scene,
        kept: Option<&GpuFrame>,
    ) -> Result<GpuFrame, GpuError> {
        if scene.spec.method != Method::Srbf {
            return Err(GpuError::Method);
        }
        let mut timings = Timings {
            tables: self.cpu.table_seconds,
            srbf_fit: scene.fit_seconds,
            ..Timings::default()
        };
        let spec = &scene.spec;
        let start = Instant::now();
        let view = scene.camera.view(spec.width, spec.height);
        let inputs = DrawInputs {
            groom: &scene.groom,
            view: &view,
            width: spec.width,
            height: spec.height,
            ss: spec.supersampling.max(1),
        };
        let point_count = scene.groom.point_count();
        let (width, height) = (spec.width, spec.height);
        self.check_sizes(&draw::sizes(&inputs))?;
        self.check_sizes(&[
            ("the point colours", point_count * 16),
            ("the image", width * height * 16),
        ])?;
        let device = &self.gpu.device;
        let (groom, groom_uploads) = match kept {
            Some(f) if f.groom.holds(&scene.groom) => (f.groom.clone(), 0),
            _ => (Arc::new(GroomBuffers::new(device, &scene.groom)), 1),
        };
        let drawing = Drawing::new(device, &self.draw, &inputs, &groom);
        let draw_stopwatch = Stopwatch::new(device, &self.gpu.queue, 1);
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
        let drawing_steps = drawing.encode(
            &self.draw,
            &mut encoder,
            draw_stopwatch.as_ref().map(|s| (s.query_set(), 0)),
        );
        if let Some(s) = &draw_stopwatch {
            s.resolve(&mut encoder);
        }
        self.gpu.queue.submit([encoder.finish()]);
        let background = background_records(scene, &view);
        let visible = drawing.read_count(device, &self.gpu.queue);
        timings.drawing = start.elapsed().as_secs_f64();
        let draw_gpu_seconds =
            draw_stopwatch.map(|s| s.seconds(&self.gpu.device, &self.gpu.queue)[0]);
        let start = Instant::now();
        let world_lights = srbf_lights(scene);
        let (layer_bytes, shadow_bytes) =
            ShadowMaps::sizes(&world_lights, scene.spec.shadows.resolution, visible);
        self.check_sizes(&[
            ("the opacity maps", layer_bytes),
            ("the shadows", shadow_bytes),
        ])?;
        let lights = light_records(&world_lights, scene.spec.shadows.merge_bandwidth);
        let strand_source = StrandSource::of(scene);
        let (strand_records, strands_buffer, strand_uploads) = match kept {
            Some(f)
                if f.strands.len() == scene.groom.strand_count()
                    && f.strand_source == strand_source =>
            {
                (f.strands.clone(), f.strands_buffer.clone(), 0)
            }
            _ => {
                let records = strands::derive(scene);
                let buffer =
                    buffers::storage(device, "strands", bytemuck::cast_slice(&records), false);
                (records, buffer, 1)
            }
        };
        let mut params = ShadeParams {
            eye: view.eye.as_vec3().to_array(),
            visible: visible as u32,
            lights: lights.len() as u32,
            mu_a_scale: MU_A_SCALE as f32,
            min_z: MIN_Z as f32,
            grids: self.static_grids,
            ..ShadeParams::default()
        };
        self.set_hair(&mut params, scene);
        let params_buffer = buffers::uniform(device, "shade params", bytemuck::bytes_of(&params));
        let colours_buffer = buffers::output(device, "point colours", point_count * 16);
        let image_buffer = buffers::output(device, "image", width * height * 16);
        let background_buffer = buffers::storage(
            device,
            "background",
            bytemuck::cast_slice(&background),
            false,
        );
        let resolve_params = ResolveParams {
            width: width as u32,
            height: height as u32,
            ss: inputs.ss as u32,
            _pad: 0,
        };
        let resolve_params_buffer = buffers::uniform(
            device,
            "resolve params",
            bytemuck::bytes_of(&resolve_params),
        );
        let shadows = ShadowMaps::new(
            device,
            &self.shadows,
            &ShadowInputs {
                groom: &scene.groom,
                groom_buffers: &groom,
                lights: &world_lights,
                options: &scene.spec.shadows,
                points: &drawing.visible,
                point_count: visible,
                max_batch: self.shadow_batch,
            },
        );
        let upload_seconds = start.elapsed().as_secs_f64();
        let start = Instant::now();
        let shadow_stopwatch = Stopwatch::new(device, &self.gpu.queue, 1);
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
        let shadow_steps = shadows.encode(
            &self.shadows,
            &mut encoder,
            shadow_stopwatch.as_ref().map(|s| (s.query_set(), 0)),
        );
        if let Some(s) = &shadow_stopwatch {
            s.resolve(&mut encoder);
        }
        self.gpu.queue.submit([encoder.finish()]);
        self.wait();
        timings.shadows = start.elapsed().as_secs_f64();
        let shadow_gpu_seconds =
            shadow_stopwatch.map(|s| s.seconds(&self.gpu.device, &self.gpu.queue)[0]);
        let start = Instant::now();
        let resolve_group = buffers::bind_group(
            device,
            &self.resolve.get_bind_group_layout(0),
            "resolve",
            &[
                &resolve_params_buffer,
                &drawing.coverage,
                &background_buffer,
                &colours_buffer,
                &image_buffer,
            ],
        );
        let mut frame = GpuFrame {
            params,
            params_buffer,
            lobes: None,
            back: None,
            no_back: buffers::storage(device, "no back-scattering tables", &[], false),
            strands_buffer,
            strands: strand_records,
            strand_source,
            width,
            height,
            ss: inputs.ss,
            visible,
            drawing,
            groom,
            shadows,
            lights_buffer: buffers::storage(device, "lights", bytemuck::cast_slice(&lights), false),
            colours_buffer,
            image_buffer,
            shade_groups: None,
            resolve_group,
            stopwatch: Stopwatch::new(device, &self.gpu.queue, 2),
            passes: Passes {
                drawing: 1,
                drawing_steps,
                shadows: 1,
                shadow_steps,
                strand_uploads,
                groom_uploads,
                ..Passes::default()
            },
            timings,
            upload_seconds: 0.0,
            gpu_seconds: None,
            draw_gpu_seconds,
            shadow_gpu_seconds,
        };
        frame.upload_seconds = upload_seconds + start.elapsed().as_secs_f64();
        Ok(frame)
    }

    /// A camera move on a shaded frame: stages 2–3 again (drawing, the opacity maps
    /// and the shadows at the newly visible points) for `scene`, keeping the parameter tables,
    /// the groom's buffers and the strand records (painted strands included) already on the
    /// device, so that neither this nor the next [`Self::shade`] uploads what a hair edit has
    /// not changed. Another groom is uploaded; a groom with another strand count, or a changed
    /// absorption source, re-derives the strand records.
    pub fn redraw(&self, frame: &mut GpuFrame, scene: &Scene) -> Result<(), GpuError> {
        let mut fresh = self.prepare_keeping(scene, Some(frame))?;
        let mut passes = frame.passes;
        passes.drawing += fresh.passes.drawing;
        passes.drawing_steps += fresh.passes.drawing_steps;
        passes.shadows += fresh.passes.shadows;
        passes.shadow_steps += fresh.passes.shadow_steps;
        passes.strand_uploads += fresh.passes.strand_uploads;
        passes.groom_uploads += fresh.passes.groom_uploads;
        fresh.lobes = frame.lobes.take();
        fresh.back = frame.back.take();
        fresh.params.grids = frame.params.grids;
        fresh.passes = passes;
        *frame = fresh;
        Ok(())
    }

    /// An environment rotation (or any change of the lights alone) on a prepared frame: the
    /// scene's lights, already turned with the map (a rotation re-fits nothing), replace the
    /// frame's; their opacity maps and shadows at the visible points are built again and the
    /// background is read again from the turned map, while the drawing, the visible points,
    /// the tables and the strand records stay on the device. The camera and groom must be
    /// the frame's (a camera move is [`Self::redraw`]).
    pub fn relight(&self, frame: &mut GpuFrame, scene: &Scene) -> Result<(), GpuError> {
        debug_assert!(
            frame.groom.holds(&scene.groom),
            "relight with another groom"
        );
        let device = &self.gpu.device;
        let start = Instant::now();
        let view = scene.camera.view(frame.width, frame.height);
        let world_lights = srbf_lights(scene);
        let (layer_bytes, shadow_bytes) =
            ShadowMaps::sizes(&world_lights, scene.spec.shadows.resolution, frame.visible);
        self.check_sizes(&[
            ("the opacity maps", layer_bytes),
            ("the shadows", shadow_bytes),
        ])?;
        let lights = light_records(&world_lights, scene.spec.shadows.merge_bandwidth);
        let shadows = ShadowMaps::new(
            device,
            &self.shadows,
            &ShadowInputs {
                groom: &scene.groom,
                groom_buffers: &frame.groom,
                lights: &world_lights,
                options: &scene.spec.shadows,
                points: &frame.drawing.visible,
                point_count: frame.visible,
                max_batch: self.shadow_batch,
            },
        );
        let stopwatch = Stopwatch::new(device, &self.gpu.queue, 1);
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
        let steps = shadows.encode(
            &self.shadows,
            &mut encoder,
            stopwatch.as_ref().map(|s| (s.query_set(), 0)),
        );
        if let Some(s) = &stopwatch {
            s.resolve(&mut encoder);
        }
        self.gpu.queue.submit([encoder.finish()]);
        self.wait();
        frame.shadow_gpu_seconds = stopwatch.map(|s| s.seconds(device, &self.gpu.queue)[0]);
        frame.shadows = shadows;
        frame.lights_buffer =
            buffers::storage(device, "lights", bytemuck::cast_slice(&lights), false);
        frame.params.lights = lights.len() as u32;
        frame.shade_groups = None;
        let background = buffers::storage(
            device,
            "background",
            bytemuck::cast_slice(&background_records(scene, &view)),
            false,
        );
        frame.resolve_group = self.resolve_group(frame, &background);
        frame.passes.shadows += 1;
        frame.passes.shadow_steps += steps;
        frame.timings.shadows = start.elapsed().as_secs_f64();
        Ok(())
    }

    /// The resolve pass's bind group for `frame` with `background`.
    fn resolve_group(&self, frame: &GpuFrame, background: &wgpu::Buffer) -> wgpu::BindGroup {
        let params = ResolveParams {
            width: frame.width as u32,
            height: frame.height as u32,
            ss: frame.ss as u32,
            _pad: 0,
        };
        let params = buffers::uniform(
            &self.gpu.device,
            "resolve params",
            bytemuck::bytes_of(&params),
        );
        buffers::bind_group(
            &self.gpu.device,
            &self.resolve.get_bind_group_layout(0),
            "resolve",
            &[
                &params,
                &frame.drawing.coverage,
                background,
                &frame.colours_buffer,
                &frame.image_buffer,
            ],
        )
    }

    /// Refuses buffers over the device's limits with a clear error (wgpu would panic).
    fn check_sizes(&self, sizes: &[(&'static str, usize)]) -> Result<(), GpuError> {
        let limits = self.gpu.device.limits();
        let limit = limits
            .max_storage_buffer_binding_size
            .min(limits.max_buffer_size);
        match sizes.iter().find(|(_, bytes)| *bytes as u64 > limit) {
            Some(&(what, bytes)) => Err(GpuError::TooLarge {
                what,
                bytes: bytes as u64,
                limit,
            }),
            None => Ok(()),
        }
    }

    /// The scene's global hair parameters and settings into the uniform.
    fn set_hair(&self, params: &mut ShadeParams, scene: &Scene) {
        let spec = &scene.spec;
        let fiber = spec.hair.fiber(None);
        params.eta = fiber.eta as f32;
        params.alpha_r = fiber.alpha_r as f32;
        params.beta_r = fiber.beta_r as f32;
        params.eccentricity = fiber.eccentricity as f32;
        params.caustic_bandwidth = caustic_bandwidth(&fiber) as f32;
        params.caustic_fade = fiber.caustic_fade as f32;
        params.glint_scale = fiber.glint_scale as f32;
        params.caustic_limit = fiber.caustic_limit as f32;
        params.d_b = spec.hair.d_b as f32;
        params.cutoff = spec.shadows.cutoff as f32;
        params.m = spec.quadrature as u32;
        params.multiple = spec.multiple as u32;
        params.lobes = shading::lobe_bits(spec.lobes);
    }

    /// Stages 4–5 for the scene's current hair parameters: uploads what they changed (the lobe
    /// and back-scattering tables when rebuilt, every strand's record when the scene's
    /// absorption source changed), shades, resolves and reads the image back.
    pub fn shade(&self, frame: &mut GpuFrame, scene: &Scene) -> Image {
        self.upload_tables(frame, scene);
        if StrandSource::of(scene) != frame.strand_source {
            frame.strands = strands::derive(scene);
            frame.strand_source = StrandSource::of(scene);
            self.gpu.queue.write_buffer(
                &frame.strands_buffer,
                0,
                bytemuck::cast_slice(&frame.strands),
            );
            frame.passes.strand_uploads += 1;
        }
        let mut params = frame.params;
        self.set_hair(&mut params, scene);
        frame.params = params;
        self.gpu
            .queue
            .write_buffer(&frame.params_buffer, 0, bytemuck::bytes_of(&params));
        let chunks = shading::light_chunks(&params);
        if frame
            .shade_groups
            .as_ref()
            .is_none_or(|(c, _)| *c != chunks)
        {
            frame.shade_groups = Some((chunks.clone(), self.shade_groups(frame, &chunks)));
        }
        let groups = &frame.shade_groups.as_ref().expect("just made").1;
        let start = Instant::now();
        let (gx, gy) = shading::workgroups(frame.params.visible as usize);
        self.submit_pass(
            &self.shade,
            groups,
            (gx, gy),
            frame.stopwatch.as_ref(),
            0,
            false,
        );
        self.wait();
        frame.passes.shading_steps += groups.len();
        frame.passes.shading += 1;
        frame.timings.shading = start.elapsed().as_secs_f64();
        let start = Instant::now();
        let (w, h) = (frame.width, frame.height);
        let tiles = (
            (w as u32).div_ceil(resolve::TILE),
            (h as u32).div_ceil(resolve::TILE),
        );
        let stopwatch = frame.stopwatch.as_ref();
        self.submit_pass(
            &self.resolve,
            std::slice::from_ref(&frame.resolve_group),
            tiles,
            stopwatch,
            1,
            true,
        );
        let bytes = buffers::read(
            &self.gpu.device,
            &self.gpu.queue,
            &frame.image_buffer,
            w * h * 16,
        );
        frame.passes.resolve += 1;
        frame.timings.resolve = start.elapsed().as_secs_f64();
        frame.gpu_seconds = stopwatch.map(|s| {
            let t = s.seconds(&self.gpu.device, &self.gpu.queue);
            GpuSeconds {
                drawing: frame.draw_gpu_seconds.unwrap_or(0.0),
                shadows: frame.shadow_gpu_seconds.unwrap_or(0.0),
                shading: t[0],
                resolve: t[1],
            }
        });
        let rgba: Vec<[f32; 4]> = bytemuck::pod_collect_to_vec(&bytes);
        Image {
            width: w,
            height: h,
            pixels: rgba
                .iter()
                .map(|p| DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64))
                .collect(),
        }
    }

    /// Uploads the lobe table and (with multiple scattering) the back-scattering tables when
    /// the CPU renderer rebuilt them for the scene's parameters.
    fn upload_tables(&self, frame: &mut GpuFrame, scene: &Scene) {
        let hair = &scene.spec.hair;
        let fiber = hair.fiber(None);
        let lobes = self.cpu.lobe_table(&fiber);
        if frame
            .lobes
            .as_ref()
            .is_none_or(|(l, _)| !Arc::ptr_eq(l, &lobes))
        {
            let packed = tables::lobe_grids(&lobes);
            let buffer = self.table_buffer("lobe table", &packed.data);
            packed.describe(&mut frame.params.grids);
            frame.lobes = Some((lobes, buffer));
            frame.shade_groups = None;
            frame.passes.table_uploads += 1;
        }
        if scene.spec.multiple {
            let back = self.cpu.back_scattering(&fiber);
            if frame
                .back
                .as_ref()
                .is_none_or(|(b, _)| !Arc::ptr_eq(b, &back))
            {
                let packed = tables::back_grid(&back);
                let buffer = self.table_buffer("back-scattering tables", &packed.data);
                packed.describe(&mut frame.params.grids);
                frame.back = Some((back, buffer));
                frame.shade_groups = None;
                frame.passes.table_uploads += 1;
            }
        }
    }

    fn table_buffer(&self, label: &str, data: &[f32]) -> wgpu::Buffer {
        buffers::storage(&self.gpu.device, label, bytemuck::cast_slice(data), false)
    }

    /// The shading pass's bind groups, one per dispatch of `chunks` (each with its own
    /// [`shading::LightChunk`] uniform).
    fn shade_groups(
        &self,
        frame: &GpuFrame,
        chunks: &[shading::LightChunk],
    ) -> Vec<wgpu::BindGroup> {
        let lobes = &frame.lobes.as_ref().expect("uploaded").1;
        let back = frame.back.as_ref().map_or(&frame.no_back, |b| &b.1);
        let layout = self.shade.get_bind_group_layout(0);
        chunks
            .iter()
            .map(|chunk| {
                let chunk =
                    buffers::uniform(&self.gpu.device, "light chunk", bytemuck::bytes_of(chunk));
                buffers::bind_group(
                    &self.gpu.device,
                    &layout,
                    "shade",
                    &[
                        &frame.params_buffer,
                        &self.static_tables,
                        lobes,
                        back,
                        &frame.strands_buffer,
                        &frame.drawing.visible,
                        &frame.shadows.shadow,
                        &frame.lights_buffer,
                        &frame.colours_buffer,
                        &chunk,
                    ],
                )
            })
            .collect()
    }

    /// Encodes and submits one compute pass of a dispatch per bind group in `groups` (in
    /// order: wgpu makes each dispatch's writes visible to the next), timed as pass `k` where
    /// timestamps exist (resolving the queries with the last pass).
    fn submit_pass(
        &self,
        pipeline: &wgpu::ComputePipeline,
        groups: &[wgpu::BindGroup],
        (x, y): (u32, u32),
        stopwatch: Option<&Stopwatch>,
        k: u32,
        last: bool,
    ) {
        let mut encoder = self
            .gpu
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: None,
                timestamp_writes: stopwatch.map(|s| s.writes(k)),
            });
            pass.set_pipeline(pipeline);
            for group in groups {
                pass.set_bind_group(0, group, &[]);
                pass.dispatch_workgroups(x, y, 1);
            }
        }
        if let (Some(s), true) = (stopwatch, last) {
            s.resolve(&mut encoder);
        }
        self.gpu.queue.submit([encoder.finish()]);
    }

    fn wait(&self) {
        self.gpu
            .device
            .poll(wgpu::PollType::wait_indefinitely())
            .expect("the GPU device was lost");
    }

    /// Writes the records of strands `first..first + params.len()` (a paint edit) without
    /// touching the groom or any other strand; the next [`Self::shade`] shows them.
    pub fn update_strands(
        &self,
        frame: &mut GpuFrame,
        first: usize,
        params: &[StrandParams],
    ) -> Result<(), StrandError> {
        strands::check(first, params, frame.strands.len())?;
        frame.strands[first..first + params.len()].copy_from_slice(params);
        self.gpu.queue.write_buffer(
            &frame.strands_buffer,
            (first * size_of::<StrandParams>()) as u64,
            bytemuck::cast_slice(params),
        );
        frame.passes.strand_uploads += 1;
        Ok(())
    }

    /// A whole frame: prepare and shade.
    pub fn render(&self, scene: &Scene) -> Result<(Image, GpuFrame), GpuError> {
        let mut frame = self.prepare(scene)?;
        let image = self.shade(&mut frame, scene);
        Ok((image, frame))
    }
}

/// The lights as the shading pass reads them, with the groups multiple scattering merges them
/// in (cells of `merge_bandwidth`).
fn light_records(lights: &[cuticle_render::WorldLight], merge_bandwidth: f64) -> Vec<LightRecord> {
    let ends = LightClusters::of(lights, merge_bandwidth).group_ends();
    lights
        .iter()
        .zip(ends)
        .map(|(l, group_end)| LightRecord {
            direction: l.direction.as_vec3().to_array(),
            bandwidth: l.bandwidth as f32,
            radiance: l.radiance.as_vec3().to_array(),
            group_end,
        })
        .collect()
}

/// The environment through each pixel (computed on the CPU), as the resolve pass reads it.
fn background_records(scene: &Scene, view: &cuticle_render::scene::camera::View) -> Vec<[f32; 4]> {
    frame_background(scene, view)
        .iter()
        .map(|b| [b.x as f32, b.y as f32, b.z as f32, 1.0])
        .collect()
}
