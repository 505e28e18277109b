//! The frame pipeline, in the stages `render.json` times:
//! 1. tables (once per process, [`Renderer::new`]);
//! 2. drawing: strands rasterised into the supersampled visibility buffer, and the background;
//! 3. shadows: T̃ of every light at every visible point (depends on geometry and lights only);
//! 4. shading: L_o at every visible point (the only stage a hair-parameter edit re-runs);
//! 5. resolve: subsamples averaged into pixels.

use crate::angles::fiber_frame_at;
use crate::brute::dual_scattering::BruteDual;
use crate::brute::half_circle::ExactHalfCircle;
use crate::brute::single_scattering::{self as brute, Directional};
use crate::frame::draw::{Coverage, EMPTY, draw_strands};
use crate::frame::progress::{Counter, Progress};
use crate::frame::reshade::{Shaded, SharedInputs, stale_points};
use crate::frame::shadows::{ShadowOptions, transmittance};
use crate::frame::sub_lights::split_wide;
use crate::preview::PREVIEW_TABLE_NODES;
use crate::scene::camera::View;
use crate::scene::{Lobes, Method, Scene, light_to_world};
use crate::srbf::cg_lobes::TrtShape;
use crate::srbf::dual_scattering::Dual;
use crate::srbf::light_clusters::{LightClusters, sort_by_cell};
use crate::srbf::single_scattering::{LocalLight, ShadingFiber, modes, shade};
use crate::tables::back_scattering::BackScatteringTables;
use crate::tables::cg_integrals::Tables;
use crate::tables::half_circle::HalfCircle;
use crate::tables::last_built::LastBuilt;
use crate::tables::lobe_table::{LobeTable, trt_shape};
use crate::tables::spread::SpreadNormalisation;
use cuticle_fiber::models::marschner2003::MarschnerParams;
use cuticle_fiber::{FiberAngles, FiberFrame, Marschner2003};
use glam::DVec3;
use rayon::prelude::*;
use serde::Serialize;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

/// A linear RGB image, row-major, top row first.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    pub width: usize,
    pub height: usize,
    pub pixels: Vec<DVec3>,
}

impl Image {
    /// Refuses an image holding a pixel that is NaN or infinite as the f32 the files store (a
    /// finite f64 above 3.4e38 is +∞ there: issue 57 #5, an environment of 3e38 through a
    /// clear fiber). `what` names the image in the message.
    pub fn check_finite(&self, what: &str) -> Result<(), crate::SceneError> {
        match self.pixels.iter().position(|p| !p.as_vec3().is_finite()) {
            Some(k) => Err(crate::SceneError::Invalid(format!(
                "the renderer made {what} pixel ({}, {}) = {} that is not a finite 32-bit \
                 float (the light is too bright?); nothing was written",
                k % self.width,
                k / self.width,
                self.pixels[k]
            ))),
            None => Ok(()),
        }
    }
}

/// Wall seconds of each stage.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Timings {
    pub tables: f64,
    pub srbf_fit: f64,
    pub drawing: f64,
    pub shadows: f64,
    pub shading: f64,
    pub resolve: f64,
}

/// What stays valid while only hair parameters change: visibility, background, lights and
/// their transmittance at the visible points.
#[derive(Clone, Debug)]
pub struct Prepared {
    pub coverage: Coverage,
    pub view: View,
    pub background: Vec<DVec3>,
    /// Visible points, ascending.
    pub points: Vec<u32>,
    /// The lights, in world space.
    pub lights: Vec<WorldLight>,
    /// T̃ of light j at visible point p: `shadow[p * lights + j]`.
    pub shadow: Vec<f32>,
    pub strand_of_point: Vec<u32>,
}

/// A light of the frame in world space: an SRBF light, or a directional one (`bandwidth` 0)
/// of the brute force.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WorldLight {
    /// Unit vector toward the light.
    pub direction: DVec3,
    /// The SRBF bandwidth λ_j (Xu et al. 2011 eq. 1); 0 for a directional light.
    pub bandwidth: f64,
    /// L_j of an SRBF light, or the power E_k of a directional one.
    pub radiance: DVec3,
}

/// How many times a [`Renderer`] (and its clones, which share the caches) built each table that
/// a hair-parameter edit may rebuild.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TableBuilds {
    /// [`LobeTable`]s (η or the caustic parameters changed).
    pub lobes: u64,
    /// [`BackScatteringTables`] (a parameter other than absorption changed).
    pub back_scattering: u64,
    /// The coarse [`BackScatteringTables`] of a preview renderer ([`Renderer::for_preview`]).
    pub preview_back_scattering: u64,
}

/// The renderer: its tables, built once, and the lobe table of the last hair parameters.
#[derive(Clone, Debug)]
pub struct Renderer {
    pub tables: Arc<Tables>,
    pub half: Arc<HalfCircle>,
    pub spread: Arc<SpreadNormalisation>,
    pub table_seconds: f64,
    /// Rebuilt when η or the caustic parameters change (absorption is one of its axes).
    lobes: Arc<LastBuilt<(f64, TrtShape), LobeTable>>,
    /// Rebuilt when any parameter but absorption (one of its axes) changes.
    back: Arc<LastBuilt<MarschnerParams, BackScatteringTables>>,
    /// The same on [`PREVIEW_TABLE_NODES`]², for a preview renderer (kept apart, so that a
    /// preview and a full frame of one edit each build theirs once).
    preview_back: Arc<LastBuilt<MarschnerParams, BackScatteringTables>>,
    /// Whether this renderer shades with the coarse back-scattering tables.
    preview: bool,
}

impl Default for Renderer {
    fn default() -> Self {
        Self::new()
    }
}

impl Renderer {
    pub fn new() -> Self {
        let start = Instant::now();
        let tables = Arc::new(Tables::build());
        let half = Arc::new(HalfCircle::build());
        let spread = Arc::new(SpreadNormalisation::build());
        Self {
            tables,
            half,
            spread,
            table_seconds: start.elapsed().as_secs_f64(),
            lobes: Arc::default(),
            back: Arc::default(),
            preview_back: Arc::default(),
            preview: false,
        }
    }

    /// A renderer for preview frames ([`crate::preview`]): the same tables and caches, but
    /// back-scattering tables built on a [`PREVIEW_TABLE_NODES`]² grid, so that an edit
    /// that rebuilds them costs a preview little.
    pub fn for_preview(&self) -> Self {
        Self {
            preview: true,
            ..self.clone()
        }
    }

    /// Whether this renderer is one of [`Self::for_preview`].
    pub fn is_preview(&self) -> bool {
        self.preview
    }

    /// The lobe table of `fiber`'s η and caustics.
    pub fn lobe_table(&self, fiber: &MarschnerParams) -> Arc<LobeTable> {
        self.lobes.get_or_build((fiber.eta, trt_shape(fiber)), || {
            LobeTable::build(&self.tables, fiber)
        })
    }

    /// The builds so far of the tables kept across edits.
    pub fn table_builds(&self) -> TableBuilds {
        TableBuilds {
            lobes: self.lobes.builds(),
            back_scattering: self.back.builds(),
            preview_back_scattering: self.preview_back.builds(),
        }
    }

    /// The back-scattering tables of `fiber`'s parameters but absorption (d_b enters none:
    /// a d_b edit reuses the built ones); coarse ones for a preview renderer.
    pub fn back_scattering(&self, fiber: &MarschnerParams) -> Arc<BackScatteringTables> {
        let key = MarschnerParams {
            mu_a: DVec3::ZERO,
            ..*fiber
        };
        if self.preview {
            self.preview_back.get_or_build(key, || {
                BackScatteringTables::build_at(fiber, PREVIEW_TABLE_NODES)
            })
        } else {
            self.back
                .get_or_build(key, || BackScatteringTables::build(fiber))
        }
    }

    /// Whether this renderer renders `scene`'s method: [`Method::Path`] belongs to the path
    /// tracer (crate cuticle-trace).
    pub fn accepts(scene: &Scene) -> Result<(), crate::SceneError> {
        match scene.spec.method {
            Method::Srbf | Method::Brute => Ok(()),
            Method::Path => Err(crate::SceneError::Invalid(
                "method path is rendered by the path tracer (crate cuticle-trace), not the SRBF renderer".into(),
            )),
        }
    }

    /// Stages 2–3.
    ///
    /// # Panics
    /// For [`Method::Path`] (see [`Renderer::accepts`]).
    pub fn prepare(&self, scene: &Scene, timings: &mut Timings) -> Prepared {
        let mut prepared = self.draw(scene, timings);
        let start = Instant::now();
        prepared.shadow = self.shadows(scene, &prepared.points, &prepared.lights);
        timings.shadows = start.elapsed().as_secs_f64();
        prepared
    }

    /// Stage 3: T̃ of each of `lights` at each of `points` (`[k * lights + j]` for `points[k]`),
    /// a function of the groom, the lights and the shadow settings only, point by point: a
    /// caller may keep it for every point across camera moves.
    pub fn shadows(&self, scene: &Scene, points: &[u32], lights: &[WorldLight]) -> Vec<f32> {
        shadows_of_lit(scene, points, lights)
    }

    /// Stage 2 and the frame's lights, with `shadow` left empty (the GPU renderer makes its
    /// own): [`Self::prepare`] without the opacity maps.
    ///
    /// # Panics
    /// For [`Method::Path`] (see [`Renderer::accepts`]).
    pub fn draw(&self, scene: &Scene, timings: &mut Timings) -> Prepared {
        if let Err(e) = Self::accepts(scene) {
            panic!("{e}");
        }
        let spec = &scene.spec;
        let start = Instant::now();
        let view = scene.camera.view(spec.width, spec.height);
        let coverage = draw_strands(
            &scene.groom,
            &view,
            spec.width,
            spec.height,
            spec.supersampling,
        );
        let background = background(scene, &view);
        let points = coverage.visible_points(scene.groom.point_count());
        timings.drawing = start.elapsed().as_secs_f64();
        let lights = match spec.method {
            Method::Srbf => srbf_lights(scene),
            Method::Brute | Method::Path => brute::directional_lights(scene, spec.brute_grid)
                .into_iter()
                .map(|Directional { direction, power }| WorldLight {
                    direction,
                    bandwidth: 0.0,
                    radiance: power,
                })
                .collect(),
        };
        Prepared {
            coverage,
            view,
            background,
            points,
            lights,
            shadow: Vec::new(),
            strand_of_point: scene.groom.strand_of_points(),
        }
    }

    /// Stage 4: L_o at each visible point (in `prepared.points` order), for the scene's
    /// current hair parameters.
    pub fn shade(&self, scene: &Scene, prepared: &Prepared) -> Vec<DVec3> {
        self.shade_with_progress(scene, prepared, &|_, _| {})
    }

    /// [`Self::shade`], reporting the points shaded so far to `progress`.
    pub fn shade_with_progress(
        &self,
        scene: &Scene,
        prepared: &Prepared,
        progress: Progress,
    ) -> Vec<DVec3> {
        let never = AtomicBool::new(false);
        self.shade_cancellable(scene, prepared, progress, &never)
            .unwrap_or_default()
    }

    /// [`Self::shade_with_progress`] that gives up once `cancel` is set (the points left are
    /// skipped) and then returns `None`: a live window drops a frame made stale by a newer edit.
    pub fn shade_cancellable(
        &self,
        scene: &Scene,
        prepared: &Prepared,
        progress: Progress,
        cancel: &AtomicBool,
    ) -> Option<Vec<DVec3>> {
        self.shade_reusing(scene, prepared, None, progress, cancel)
            .map(|shaded| shaded.colours)
    }

    /// [`Self::shade_cancellable`] that shades only the points whose inputs changed since
    /// `previous`, a pass on the same `prepared` ([`crate::frame::reshade`]): after a paint
    /// stroke, the painted strands' points. `progress` counts the points shaded.
    pub fn shade_reusing(
        &self,
        scene: &Scene,
        prepared: &Prepared,
        previous: Option<&Shaded>,
        progress: Progress,
        cancel: &AtomicBool,
    ) -> Option<Shaded> {
        let fibers: Vec<MarschnerParams> = (0..scene.groom.strand_count())
            .map(|s| scene.spec.hair.fiber(scene.groom.appearance().get(s)))
            .collect();
        let shared = SharedInputs::of(scene);
        let stale = stale_points(
            previous,
            &shared,
            &fibers,
            &prepared.points,
            &prepared.strand_of_point,
        );
        let points_shaded = stale.iter().filter(|&&s| s).count();
        let counter = Counter::new(points_shaded, progress);
        let hair = &scene.spec.hair;
        let multiple = scene.spec.multiple;
        let back = multiple.then(|| self.back_scattering(&hair.fiber(None)));
        let (lobes, exact_half) = match scene.spec.method {
            Method::Srbf => (Some(self.lobe_table(&hair.fiber(None))), None),
            Method::Brute | Method::Path => {
                (None, multiple.then(|| ExactHalfCircle::build(hair.eta)))
            }
        };
        let shader = match (&lobes, &exact_half) {
            (Some(lobes), _) => FrameShader::Srbf(SrbfFrame {
                tables: &self.tables,
                lobes,
                dual: back.as_deref().map(|back| Dual {
                    tables: &self.tables,
                    half: &self.half,
                    spread: &self.spread,
                    shadows: scene.spec.shadows,
                    back,
                    d_b: hair.d_b,
                    m: scene.spec.quadrature,
                }),
                lights: &prepared.lights,
                clusters: LightClusters::of(&prepared.lights, scene.spec.shadows.merge_bandwidth),
                shadows: scene.spec.shadows,
                m: scene.spec.quadrature,
                shown: scene.spec.lobes,
            }),
            (None, half) => FrameShader::Brute(BruteFrame {
                shown: scene.spec.lobes,
                lights: prepared
                    .lights
                    .iter()
                    .map(|l| Directional {
                        direction: l.direction,
                        power: l.radiance,
                    })
                    .collect(),
                dual: back
                    .as_deref()
                    .zip(half.as_ref())
                    .map(|(back, half)| BruteDual {
                        half,
                        spread: &self.spread,
                        back,
                        d_b: hair.d_b,
                    }),
            }),
        };
        let nl = prepared.lights.len();
        let colours = prepared
            .points
            .par_iter()
            .enumerate()
            .map_init(
                || (Vec::new(), Vec::new(), Vec::new()),
                |scratch, (k, &p)| {
                    if !stale[k] {
                        return previous.map_or(DVec3::ZERO, |b| b.colours[k]);
                    }
                    if cancel.load(Ordering::Relaxed) {
                        return DVec3::ZERO;
                    }
                    counter.tick();
                    let p = p as usize;
                    let point = ShadingPoint {
                        fiber: &fibers[prepared.strand_of_point[p] as usize],
                        fiber_frame: fiber_frame_at(&scene.groom, p),
                        toward_eye: (prepared.view.eye - scene.groom.positions()[p].as_dvec3())
                            .normalize(),
                        shadow: &prepared.shadow[k * nl..(k + 1) * nl],
                    };
                    match &shader {
                        FrameShader::Srbf(srbf) => srbf.shade(&point, scratch),
                        FrameShader::Brute(brute) => brute.shade(&point),
                    }
                },
            )
            .collect::<Vec<_>>();
        (!cancel.load(Ordering::Relaxed)).then_some(Shaded {
            colours,
            points_shaded,
            fibers,
            shared,
        })
    }

    /// Stage 5: averages each pixel's subsamples, hair shaded by interpolating its segment's
    /// two point colours, the rest showing the background.
    pub fn resolve(&self, prepared: &Prepared, colours: &[DVec3], point_count: usize) -> Image {
        let mut by_point = vec![DVec3::ZERO; point_count];
        for (&p, &c) in prepared.points.iter().zip(colours) {
            by_point[p as usize] = c;
        }
        let cov = &prepared.coverage;
        let n = (cov.ss * cov.ss) as f64;
        let pixels = (0..cov.width * cov.height)
            .into_par_iter()
            .map(|k| {
                let (x, y) = (k % cov.width, k / cov.width);
                let sum: DVec3 = cov
                    .pixel_samples(x, y)
                    .map(|s| match cov.segment[s] {
                        EMPTY => prepared.background[k],
                        seg => {
                            let t = cov.t[s] as f64;
                            by_point[seg as usize].lerp(by_point[seg as usize + 1], t)
                        }
                    })
                    .sum();
                sum / n
            })
            .collect();
        Image {
            width: cov.width,
            height: cov.height,
            pixels,
        }
    }

    /// A whole frame: prepare, shade, resolve, with the time of each stage.
    pub fn render(&self, scene: &Scene) -> (Image, Prepared, Timings) {
        self.render_with_progress(scene, &|_, _| {})
    }

    /// [`Self::render`], reporting the shading stage's progress to `progress`.
    pub fn render_with_progress(
        &self,
        scene: &Scene,
        progress: Progress,
    ) -> (Image, Prepared, Timings) {
        let mut timings = Timings {
            tables: self.table_seconds,
            srbf_fit: scene.fit_seconds,
            ..Timings::default()
        };
        let prepared = self.prepare(scene, &mut timings);
        let image = self.rerender_with_progress(scene, &prepared, &mut timings, progress);
        (image, prepared, timings)
    }

    /// Shading and resolve only: what an edit of the hair parameters costs.
    pub fn rerender(&self, scene: &Scene, prepared: &Prepared, timings: &mut Timings) -> Image {
        self.rerender_with_progress(scene, prepared, timings, &|_, _| {})
    }

    /// [`Self::rerender`], reporting the shading stage's progress to `progress`.
    pub fn rerender_with_progress(
        &self,
        scene: &Scene,
        prepared: &Prepared,
        timings: &mut Timings,
        progress: Progress,
    ) -> Image {
        let start = Instant::now();
        let colours = self.shade_with_progress(scene, prepared, progress);
        timings.shading = start.elapsed().as_secs_f64();
        let start = Instant::now();
        let image = self.resolve(prepared, &colours, scene.groom.point_count());
        timings.resolve = start.elapsed().as_secs_f64();
        image
    }
}

/// One visible point as shading reads it.
struct ShadingPoint<'a> {
    fiber: &'a MarschnerParams,
    fiber_frame: FiberFrame,
    /// Unit vector from the point toward the eye.
    toward_eye: DVec3,
    /// T̃ of each light at the point.
    shadow: &'a [f32],
}

/// How one frame's points are shaded.
enum FrameShader<'a> {
    Srbf(SrbfFrame<'a>),
    Brute(BruteFrame<'a>),
}

/// What the SRBF path reads at every point of a frame.
struct SrbfFrame<'a> {
    tables: &'a Tables,
    lobes: &'a LobeTable,
    dual: Option<Dual<'a>>,
    lights: &'a [WorldLight],
    /// The lights' groups for multiple scattering.
    clusters: LightClusters,
    shadows: ShadowOptions,
    m: usize,
    /// The single-scattering lobes that shade (a debug view).
    shown: Lobes,
}

impl SrbfFrame<'_> {
    /// Single scattering from the lights seen in the fiber frame and shadowed (none below the
    /// cutoff), plus dual scattering from the unshadowed lights and their T̃, merged in the
    /// frame's groups. The scratch lists (the lights seen from the point, shadowed, and their
    /// directions in the fiber frame) are kept between points.
    fn shade(
        &self,
        point: &ShadingPoint,
        (local, lit, directions): &mut (Vec<LocalLight>, Vec<LocalLight>, Vec<DVec3>),
    ) -> DVec3 {
        let ao = point.fiber_frame.angles(point.toward_eye);
        directions.clear();
        directions.extend(
            self.lights
                .iter()
                .map(|l| point.fiber_frame.local(l.direction)),
        );
        local.clear();
        local.extend(directions.iter().zip(self.lights).map(|(&d, l)| {
            let a = FiberAngles::from_dir(d);
            LocalLight {
                theta: a.theta,
                phi: a.phi,
                bandwidth: l.bandwidth,
                radiance: l.radiance,
            }
        }));
        lit.clear();
        lit.extend(local.iter().zip(point.shadow).map(|(l, &t)| {
            let t = t as f64;
            let passes = self.shadows.passes(t);
            LocalLight {
                radiance: if passes { l.radiance * t } else { DVec3::ZERO },
                ..*l
            }
        }));
        let lobes = self.lobes.for_fiber(self.tables, point.fiber);
        let fiber = ShadingFiber {
            params: point.fiber,
            lobes: &lobes,
        };
        let single = match self.shown {
            Lobes::ALL => shade(self.tables, fiber, ao.theta, ao.phi, lit, self.m),
            shown => lit
                .iter()
                .filter(|l| l.radiance != DVec3::ZERO)
                .map(|l| {
                    l.radiance * shown.sum(modes(self.tables, fiber, ao.theta, ao.phi, l, self.m))
                })
                .sum(),
        };
        let multiple = self.dual.as_ref().map_or(DVec3::ZERO, |d| {
            d.shade_clustered(
                fiber,
                ao.theta,
                ao.phi,
                local,
                directions,
                point.shadow,
                &self.clusters,
            )
        });
        single + multiple
    }
}

/// What the brute-force reference reads at every point of a frame.
struct BruteFrame<'a> {
    lights: Vec<Directional>,
    /// The single-scattering lobes that shade (a debug view).
    shown: Lobes,
    dual: Option<BruteDual<'a>>,
}

impl BruteFrame<'_> {
    /// The exact model's single scattering from every directional light, plus dual scattering.
    fn shade(&self, point: &ShadingPoint) -> DVec3 {
        let model = Marschner2003::new(*point.fiber).expect("validated parameters");
        let lights = brute::local_lights(&point.fiber_frame, &self.lights);
        let ao = point.fiber_frame.angles(point.toward_eye);
        let single = brute::shade(&model, ao, &lights, point.shadow, self.shown);
        let multiple = self.dual.map_or(DVec3::ZERO, |d| {
            d.shade(point.fiber, ao, &lights, point.shadow)
        });
        single + multiple
    }
}

/// T̃ of every light at every point (`[p * lights + j]`), with opacity maps built only for
/// lights that carry light: a fitted map leaves some SRBF coefficients zero, and their T̃
/// (left at 1) is never read.
pub fn shadows_of_lit(scene: &Scene, points: &[u32], lights: &[WorldLight]) -> Vec<f32> {
    let lit: Vec<usize> = (0..lights.len())
        .filter(|&j| lights[j].radiance != DVec3::ZERO)
        .collect();
    let dirs: Vec<DVec3> = lit.iter().map(|&j| lights[j].direction).collect();
    let widths: Vec<f64> = lit.iter().map(|&j| lights[j].bandwidth).collect();
    let compact = transmittance(&scene.groom, points, &dirs, &widths, &scene.spec.shadows);
    let mut out = vec![1.0f32; points.len() * lights.len()];
    for (row, compact_row) in out
        .chunks_mut(lights.len().max(1))
        .zip(compact.chunks(lit.len().max(1)))
    {
        for (&j, &t) in lit.iter().zip(compact_row) {
            row[j] = t;
        }
    }
    out
}

/// The SRBF lights in world space, the wide ones split into sub-lights
/// ([`crate::frame::sub_lights`]), ordered by the cells multiple scattering merges them in
/// ([`crate::srbf::light_clusters`]).
pub fn srbf_lights(scene: &Scene) -> Vec<WorldLight> {
    let mut lights = split_wide(&scene.lights, scene.spec.shadows.split_bandwidth)
        .iter()
        .map(|l| WorldLight {
            direction: light_to_world(l.centre()),
            bandwidth: l.bandwidth as f64,
            radiance: l.coefficient.as_dvec3(),
        })
        .collect();
    sort_by_cell(&mut lights, scene.spec.shadows.merge_bandwidth);
    lights
}

/// The environment seen through each pixel centre.
pub fn background(scene: &Scene, view: &View) -> Vec<DVec3> {
    let (w, h) = (scene.spec.width, scene.spec.height);
    (0..w * h)
        .into_par_iter()
        .map(|k| scene.env_radiance(view.ray((k % w) as f64 + 0.5, (k / w) as f64 + 0.5)))
        .collect()
}
