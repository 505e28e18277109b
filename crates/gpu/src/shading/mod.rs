//! Stage 4 on the GPU: L_o at every visible point, one invocation each. The WGSL is the CPU's
//! shading code in f32, file for file under the names of the files it ports:
//! 1. `bindings.wgsl`: the pass's inputs ([`ShadeParams`], tables, strands, points, shadows,
//!    lights) and its output (a colour per groom point);
//! 2. `grid.wgsl` (tables/grid.rs), `angles.wgsl` (angles.rs, fresnel.rs, the fiber frame),
//!    `circular_gaussian.wgsl`, `quadrature.wgsl`, `cg_lobes.wgsl` (with taylor.rs),
//!    `lobe_table.wgsl`: what both scatterings read;
//! 3. `single_scattering.wgsl` (srbf/single_scattering.rs), with the quadrature's integrands;
//! 4. `forward_scattering.wgsl` (with the averages of tables/back_scattering.rs) and
//!    `dual_scattering.wgsl` (srbf/dual_scattering.rs, function for function);
//! 5. `shade.wgsl`: the entry point, frame/renderer.rs's `SrbfFrame::shade`.
//!
//! Precision: f32 throughout. The one rewrite is the exponent of a product of circular
//! Gaussians, κ − κ₁ − κ₂ = 2κ₁κ₂(c − 1)/(κ + κ₁ + κ₂), which f32 would lose for sharp lobes.

use crate::tables::{GridDesc, slot};
use bytemuck::{Pod, Zeroable};
use cuticle_fiber::math::GaussLegendre;
use cuticle_render::srbf::cg_lobes::{KEPT_PANELS, KEPT_POINTS};

/// The WGSL of the pass, in the order above.
pub const SOURCE: [&str; 11] = [
    include_str!("bindings.wgsl"),
    include_str!("grid.wgsl"),
    include_str!("angles.wgsl"),
    include_str!("circular_gaussian.wgsl"),
    include_str!("quadrature.wgsl"),
    include_str!("cg_lobes.wgsl"),
    include_str!("lobe_table.wgsl"),
    include_str!("single_scattering.wgsl"),
    include_str!("forward_scattering.wgsl"),
    include_str!("dual_scattering.wgsl"),
    include_str!("shade.wgsl"),
];

/// Invocations per workgroup (shade.wgsl's `@workgroup_size`).
pub const WORKGROUP: u32 = 64;

/// The frame's uniform (bindings.wgsl's `Params`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct ShadeParams {
    pub eye: [f32; 3],
    pub visible: u32,
    pub eta: f32,
    pub alpha_r: f32,
    pub beta_r: f32,
    pub eccentricity: f32,
    pub caustic_bandwidth: f32,
    pub caustic_fade: f32,
    pub d_b: f32,
    pub cutoff: f32,
    pub lights: u32,
    pub m: u32,
    pub multiple: u32,
    pub mu_a_scale: f32,
    pub min_z: f32,
    /// k_G and Δh_M of Marschner 2003's glints (the TRT fit's [`TrtShape`]).
    pub glint_scale: f32,
    pub caustic_limit: f32,
    /// Bit t set: single-scattering lobe t (R, TT, TRT) shades ([`lobe_bits`]).
    pub lobes: u32,
    pub grids: [GridDesc; slot::COUNT],
}

/// A visible point (bindings.wgsl's `Point`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct PointRecord {
    pub position: [f32; 3],
    pub strand: u32,
    pub tangent: [f32; 3],
    pub index: u32,
}

/// A light (bindings.wgsl's `Light`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct LightRecord {
    pub direction: [f32; 3],
    pub bandwidth: f32,
    pub radiance: [f32; 3],
    /// [`cuticle_render::srbf::light_clusters::LightClusters::group_ends`].
    pub group_end: u32,
}

/// The lights one dispatch of the pass adds (bindings.wgsl's `LightChunk`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct LightChunk {
    pub first: u32,
    pub count: u32,
    pub _pad: [u32; 2],
}

/// Loop iterations one invocation may run on llvmpipe, the software rasteriser behind lavapipe
/// (Mesa's gallivm, `LP_MAX_TGSI_LOOP_ITERATIONS`): every loop of the invocation counts
/// against this one budget, and past it every loop exits at its next test, so that an
/// invocation shading too many lights silently drops the rest and cuts short the quadratures
/// under way. This was issue 10's eccentric defect: 87 split lights at about 1,700 iterations
/// each (the TRT fit's caustic moments, with a loop over the wrapped Gaussians' images, at
/// every sample) shaded only the first 38 or so. A dispatch shades [`lights_per_dispatch`]
/// lights, within [`BUDGET_SHARE`] of this.
pub const LOOP_BUDGET: u32 = 65_535;

/// The share of [`LOOP_BUDGET`] one dispatch plans for (the loops outside the light loop
/// and a margin).
pub const BUDGET_SHARE: f64 = 0.9;

/// An upper bound on the loop iterations llvmpipe counts per light of the shading pass at m
/// quadrature segments: single scattering's three lobes at m samples each (R's polynomial, TT's
/// lobes and TRT's, read from the table or, for an eccentric fiber, fitted on the spot with its
/// caustic moments: 24 + 20 or 24 + 140 a sample), and dual scattering's averages, local term
/// and global term (76 + 47 m). Counted from the WGSL, each loop once more for its last test,
/// then raised to what lavapipe counts (`loop_cost_bounds_what_llvmpipe_counts`: 187, 560,
/// 370 and 744 measured at m = 4 for single / single + dual, circular / eccentric, 5,461 for
/// eccentric single + dual at m = 32). A group of lights merged for dual scattering
/// (`dual_group`) runs one evaluation (and the moment matching's Newton steps) for all its
/// lights and, per light, the arrival's loop of
/// three and its table reads, less than the per-light bound; a group that runs past a
/// dispatch's last light adds its few remaining lights' arrivals to that dispatch, within the
/// margin [`BUDGET_SHARE`] leaves.
pub fn loop_cost(m: u32, eccentric: bool, multiple: bool) -> u32 {
    let m = m.clamp(2, 256);
    let trt = if eccentric { 140 } else { 20 };
    let single = 16 + m * (24 + trt);
    let dual = if multiple { 76 + 47 * m } else { 0 };
    1 + single + dual
}

/// How many lights one dispatch shades for the frame's uniform: as many as keep an invocation
/// within [`BUDGET_SHARE`] of [`LOOP_BUDGET`] (every light at once for the usual scenes), at
/// least one.
pub fn lights_per_dispatch(params: &ShadeParams) -> u32 {
    let cost = loop_cost(params.m, params.eccentricity != 1.0, params.multiple != 0);
    let fits = (BUDGET_SHARE * LOOP_BUDGET as f64) as u32 / cost;
    fits.clamp(1, params.lights.max(1))
}

/// The frame's lights in dispatches of [`lights_per_dispatch`] (one empty dispatch for no
/// lights, which writes the points' zero colour).
pub fn light_chunks(params: &ShadeParams) -> Vec<LightChunk> {
    let per = lights_per_dispatch(params);
    (0..params.lights.div_ceil(per).max(1))
        .map(|c| LightChunk {
            first: c * per,
            count: per,
            _pad: [0; 2],
        })
        .collect()
}

/// The compiled pass.
pub fn pipeline(device: &wgpu::Device) -> wgpu::ComputePipeline {
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("shade"),
        source: wgpu::ShaderSource::Wgsl((kept_rule() + &SOURCE.concat()).into()),
    });
    crate::buffers::compute_pipeline(device, &module, "shade")
}

/// cg_lobes.wgsl's constants of the caustic moments' quadrature: cg_lobes.rs's panels and its
/// Gauss–Legendre rule, so that both integrate at the same nodes.
fn kept_rule() -> String {
    let rule = GaussLegendre::cached(KEPT_POINTS);
    let list = |v: &[f64]| {
        v.iter()
            .map(|x| format!("{x:e}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    format!(
        "const KEPT_PANELS: u32 = {KEPT_PANELS}u;\nconst KEPT_POINTS: u32 = {KEPT_POINTS}u;\n\
         const KEPT_NODES = array<f32, {KEPT_POINTS}>({});\n\
         const KEPT_WEIGHTS = array<f32, {KEPT_POINTS}>({});\n",
        list(&rule.nodes),
        list(&rule.weights)
    )
}

/// Workgroups for `points` invocations, as (x, y) within the 65,535 a dimension allows
/// (shade.wgsl folds y back into the point index).
pub fn workgroups(points: usize) -> (u32, u32) {
    let groups = (points as u32).div_ceil(WORKGROUP);
    let x = groups.clamp(1, 65_535);
    (x, groups.div_ceil(x))
}

/// The scene's lobe mask as `ShadeParams::lobes`: bit `Lobe::index` for each of R, TT, TRT
/// (WGSL's LOBE_R, LOBE_TT, LOBE_TRT).
pub fn lobe_bits(lobes: cuticle_render::Lobes) -> u32 {
    cuticle_fiber::models::marschner2003::MarschnerParams::LOBES
        .iter()
        .zip(lobes.mask())
        .map(|(lobe, on)| u32::from(on) << lobe.index())
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::buffers;
    use crate::device::{GpuDevice, Preference};
    use cuticle_render::srbf::cg_lobes::{CausticMoments, Geometry, trt_fit};
    use cuticle_render::tables::cg_integrals::Tables;
    use cuticle_render::tables::lobe_table::trt_shape;

    /// cg_lobes.wgsl's TRT fit (with its caustic moments) at (η, θ_d, μ_a) on both sides of
    /// η′ = 2 against cg_lobes.rs's: every slot's weight within 1 % relative, its bandwidth
    /// and centre within 2e-3 (relative above 1 rad, absolute below). Measured on lavapipe:
    /// weights 4e-3, bandwidths and centres 1.2e-3, all from φ* (the fold of Φ, where f32
    /// loses the most); without the caustic moments the weights would be 1.8–2.3 times the
    /// CPU's.
    #[test]
    fn trt_fit_matches_the_cpu() {
        let gpu = GpuDevice::new(Preference::Any).expect("a GPU adapter (lavapipe will do)");
        let fiber = cuticle_render::HairParams::default().fiber(None);
        let cases = [
            (1.55, 0.0, 0.3),
            (1.55, 0.4, 0.1),
            (1.7, -0.9, 1.0),
            (1.45, 1.2, 0.5),
            (1.25, 0.3, 0.2),
            (1.97, 0.2, 0.2),
            (1.97, 0.5, 0.05),
        ];
        let probe = format!(
            "@compute @workgroup_size(1) fn probe() {{ {} }}",
            cases
                .iter()
                .enumerate()
                .map(|(k, (eta, td, s))| format!(
                    "{{ let g = geometry({eta:?}, {td:?}); let m = caustic_moments({eta:?}, {td:?}, g.eta_prime); \
                     let f = trt_fit(g, m, {s:?}); colours[{a}] = vec4<f32>(f.weight, 0.0); \
                     colours[{b}] = vec4<f32>(f.bandwidth, 0.0); colours[{c}] = vec4<f32>(f.centre, 0.0); }}",
                    a = 3 * k,
                    b = 3 * k + 1,
                    c = 3 * k + 2
                ))
                .collect::<String>()
        );
        let module = gpu
            .device
            .create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some("probe"),
                source: wgpu::ShaderSource::Wgsl((kept_rule() + &SOURCE.concat() + &probe).into()),
            });
        let pipeline = gpu
            .device
            .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some("probe"),
                layout: None,
                module: &module,
                entry_point: Some("probe"),
                compilation_options: Default::default(),
                cache: None,
            });
        let cpu = cuticle_render::Renderer::new();
        let packed = crate::tables::static_grids(&cpu.tables, &cpu.half, &cpu.spread);
        let mut params = ShadeParams {
            caustic_bandwidth: cuticle_render::scene::hair::caustic_bandwidth(&fiber) as f32,
            caustic_fade: fiber.caustic_fade as f32,
            glint_scale: fiber.glint_scale as f32,
            caustic_limit: fiber.caustic_limit as f32,
            ..ShadeParams::default()
        };
        packed.describe(&mut params.grids);
        let uniform = buffers::uniform(&gpu.device, "probe params", bytemuck::bytes_of(&params));
        let tables = buffers::storage(
            &gpu.device,
            "static tables",
            bytemuck::cast_slice(&packed.data),
            false,
        );
        let out = buffers::output(&gpu.device, "probe out", 16 * 3 * cases.len());
        let layout = pipeline.get_bind_group_layout(0);
        let group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: uniform.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: tables.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 8,
                    resource: out.as_entire_binding(),
                },
            ],
        });
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        {
            let mut pass = encoder.begin_compute_pass(&Default::default());
            pass.set_pipeline(&pipeline);
            pass.set_bind_group(0, &group, &[]);
            pass.dispatch_workgroups(1, 1, 1);
        }
        gpu.queue.submit([encoder.finish()]);
        let got: Vec<[f32; 4]> = bytemuck::pod_collect_to_vec(&buffers::read(
            &gpu.device,
            &gpu.queue,
            &out,
            16 * 3 * cases.len(),
        ));
        let tables: &Tables = &cpu.tables;
        let shape = trt_shape(&fiber);
        for (k, &(eta, td, s)) in cases.iter().enumerate() {
            let g = Geometry::new(tables, eta, td);
            let want = trt_fit(&g, &CausticMoments::new(&g, shape), s, shape);
            for slot in 0..3 {
                let (w, b, c) = (got[3 * k][slot], got[3 * k + 1][slot], got[3 * k + 2][slot]);
                let lobe = want[slot];
                eprintln!("η {eta} θ_d {td} σ {s} slot {slot}: GPU ({w}, {b}, {c}) CPU {lobe:?}");
                assert!((w as f64 - lobe.weight).abs() <= 1e-2 * lobe.weight.abs().max(1e-6));
                assert!((b as f64 - lobe.bandwidth).abs() <= 2e-3 * lobe.bandwidth.max(1.0));
                assert!((c as f64 - lobe.centre).abs() <= 2e-3);
            }
        }
    }
}

#[cfg(test)]
mod budget_tests {
    use super::*;
    use crate::buffers;
    use crate::device::{GpuDevice, Preference};
    use crate::renderer::GpuRenderer;
    use cuticle_render::{Renderer, Scene, SceneSpec, ShadowOptions};

    /// The chunks cover every light once, in order, each within the budget, and split a
    /// frame only where one invocation could not shade it all: the default scenes shade every
    /// light in one dispatch, the densest quadrature one light per dispatch.
    #[test]
    fn light_chunks_cover_every_light_within_the_budget() {
        for (m, eccentricity, multiple, lights) in [
            (4, 1.0, 1, 87),
            (4, 0.85, 1, 87),
            (64, 0.85, 1, 87),
            (256, 0.85, 1, 40),
            (256, 1.0, 0, 3),
            (4, 1.0, 1, 0),
        ] {
            let params = ShadeParams {
                m,
                eccentricity,
                multiple,
                lights,
                ..ShadeParams::default()
            };
            let chunks = light_chunks(&params);
            let mut next = 0;
            for c in &chunks {
                assert_eq!(c.first, next);
                next = (c.first + c.count).min(lights);
                let cost = c.count * loop_cost(m, eccentricity != 1.0, multiple != 0);
                assert!(c.count == 1 || cost as f64 <= BUDGET_SHARE * LOOP_BUDGET as f64);
            }
            assert_eq!(next, lights);
            let one = loop_cost(m, eccentricity != 1.0, multiple != 0) * lights.max(1);
            assert_eq!(
                chunks.len() == 1,
                one as f64 <= BUDGET_SHARE * LOOP_BUDGET as f64
            );
        }
        let dense = ShadeParams {
            m: 256,
            eccentricity: 0.85,
            multiple: 1,
            lights: 40,
            ..ShadeParams::default()
        };
        assert_eq!(light_chunks(&dense).len(), 40);
    }

    /// [`loop_cost`] bounds the loop iterations llvmpipe counts per light: one invocation
    /// shades the same light over and over, counting the repetitions it finished, until the
    /// budget cuts it short; the repetitions done times the bound must reach the budget. With
    /// single and dual scattering, circular and eccentric, at m = 2, 4 and 32, under a light in
    /// the specular cone that passes every branch (its window, the cutoff, the scattered
    /// share). A device without the limit (hardware) finishes every repetition and shows
    /// nothing here; lavapipe, the CI device, does.
    #[test]
    fn loop_cost_bounds_what_llvmpipe_counts() {
        let device = GpuDevice::new(Preference::Any).expect("a GPU adapter (lavapipe will do)");
        let cpu = Renderer::new();
        let gpu = GpuRenderer::new(&device, &cpu);
        let spec = SceneSpec {
            groom: "straight".into(),
            strands: 10,
            lights: 4,
            width: 48,
            height: 32,
            shadows: ShadowOptions {
                resolution: 32,
                ..ShadowOptions::default()
            },
            ..SceneSpec::default()
        };
        let scene = Scene::load(spec, None).expect("scene");
        let (_, frame) = gpu.render(&scene).expect("render");
        const REPS: u32 = 70_000;
        let probe = format!(
            "@group(0) @binding(10) var<storage, read_write> done: array<u32>;
             @compute @workgroup_size(1) fn count() {{
                 fiber = fiber_point(vec3<f32>(0.5, 0.9, 1.7));
                 var acc = vec3<f32>(0.0);
                 for (var r = 0u; r < {REPS}u; r++) {{
                     acc += modes(0.3, 0.2, -0.25, 0.4, 0.4, 7u);
                     if (params.multiple != 0u) {{
                         acc += dual_light(0.3, 0.2, -0.25, 0.4, 0.4, vec3<f32>(1.0), 0.3);
                     }}
                     done[0] = r + 1u;
                 }}
                 done[1] = bitcast<u32>(acc.x);
             }}"
        );
        let module = device
            .device
            .create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some("loop count"),
                source: wgpu::ShaderSource::Wgsl((kept_rule() + &SOURCE.concat() + &probe).into()),
            });
        let pipeline = buffers::compute_pipeline(&device.device, &module, "count");
        let lobes = &frame.lobes.as_ref().expect("lobe table").1;
        let back = &frame.back.as_ref().expect("back-scattering tables").1;
        let mut short = Vec::new();
        for (m, eccentric, multiple) in [
            (4, false, false),
            (4, true, false),
            (4, false, true),
            (4, true, true),
            (2, true, true),
            (32, true, true),
        ] {
            let params = ShadeParams {
                m,
                eccentricity: if eccentric { 0.85 } else { 1.0 },
                multiple: multiple as u32,
                cutoff: 0.0,
                ..frame.params
            };
            let uniform = buffers::uniform(&device.device, "params", bytemuck::bytes_of(&params));
            let static_tables = {
                let packed = crate::tables::static_grids(&cpu.tables, &cpu.half, &cpu.spread);
                buffers::storage(
                    &device.device,
                    "static",
                    bytemuck::cast_slice(&packed.data),
                    false,
                )
            };
            let out = buffers::output(&device.device, "done", 16);
            let entries: Vec<wgpu::BindGroupEntry> = [
                (0, &uniform),
                (1, &static_tables),
                (2, lobes),
                (3, back),
                (10, &out),
            ]
            .iter()
            .map(|(b, buf)| wgpu::BindGroupEntry {
                binding: *b,
                resource: buf.as_entire_binding(),
            })
            .collect();
            let group = device.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: None,
                layout: &pipeline.get_bind_group_layout(0),
                entries: &entries,
            });
            let mut encoder = device.device.create_command_encoder(&Default::default());
            {
                let mut pass = encoder.begin_compute_pass(&Default::default());
                pass.set_pipeline(&pipeline);
                pass.set_bind_group(0, &group, &[]);
                pass.dispatch_workgroups(1, 1, 1);
            }
            device.queue.submit([encoder.finish()]);
            let got: Vec<u32> = bytemuck::pod_collect_to_vec(&buffers::read(
                &device.device,
                &device.queue,
                &out,
                8,
            ));
            let done = got[0];
            let bound = loop_cost(m, eccentric, multiple);
            eprintln!(
                "m {m} eccentric {eccentric} multiple {multiple}: {done} repetitions, about {} \
                 iterations each, bound {bound}",
                LOOP_BUDGET / done.max(1)
            );
            assert!(f32::from_bits(got[1]).is_finite());
            if !(done == REPS || done as u64 * bound as u64 >= LOOP_BUDGET as u64) {
                short.push(format!("m {m} eccentric {eccentric} multiple {multiple}: {done} repetitions, bound {bound}"));
            }
        }
        assert!(short.is_empty(), "{short:?}");
    }
}
