//! The path estimator: one camera sample's radiance.
//!
//! # What a fiber shows, and the estimator's weight
//! The renderer's convention (cuticle-render's crate documentation) is the radiance a fiber
//! shows toward ω_o, averaged across its projected width:
//!
//!   L_o(ω_o) = (1/cos θ_o) ∫ S(ω_i, ω_o) L_i(ω_i) cos θ_i dω_i,
//!
//! with S the far-field fraction of intercepted power per steradian (docs/conventions.md §3).
//! A physical fiber is reciprocal in its scattering cross section, D cos θ_i S(ω_i, ω_o) =
//! D cos θ_o S(ω_o, ω_i), and then the integrand is S(ω_o, ω_i) L_i:
//!
//!   L_o(ω_o) = ∫ S(ω_o, ω_i) L_i(ω_i) dω_i,
//!
//! the form the tracer evaluates. It reads the model with the direction the path arrived from
//! as its given direction, exactly as a model is sampled ([`cuticle_fiber::FiberModel::sample`]
//! draws the other direction from the given one), so:
//! - a BCSDF sample ω_i drawn with density p_b carries the weight S(ω_o, ω_i) / p_b, the
//!   sample's own `weight`;
//! - an environment sample ω_i of density p_e carries S(ω_o, ω_i) L_i(ω_i) / p_e;
//! - the white furnace (L_i ≡ 1, μ_a = 0) gives L_o = ∫ S(ω_o, ω_i) dω_i = 1 for any
//!   energy-conserving model, after any number of bounces: the hair disappears.
//!
//! For Marschner 2003, which is reciprocal (`reciprocal_in_marschners_units` in the fiber
//! crate), both forms are the same number, so `--method path` renders what `srbf` and `brute`
//! approximate (the one-bounce test checks the first form against quadrature). The models with
//! A(p, h) taken at the given inclination (d'Eon 2011, non-separable, Chiang 2016) are
//! reciprocal only on the specular cone; for them this is the form their papers render with.
//!
//! The hit's offset h goes to the model's near-field functions ([`FiberModel::eval_at`] and
//! kin): h of a camera ray is uniform across the projected width seen from ω_o, so a pixel
//! averages Chiang 2016's near field back into the far-field S; the other models ignore h.
//!
//! # Estimators
//! At every vertex: one environment sample (next-event estimation, shadow ray toward it), and
//! one BCSDF sample that continues the path; a continuation that escapes adds the environment
//! seen along it. [`Strategy::Mis`] weighs the two by the power heuristic (Veach 1997),
//! [`Strategy::Environment`] keeps only the first (escaping continuations add nothing past the
//! camera ray), [`Strategy::Bcsdf`] only the second. Russian roulette after `rr_depth`
//! vertices, survival probability the throughput's largest channel (at most 1); at most
//! `max_depth` scattering events.

use crate::accel::Accel;
use crate::env_sampling::EnvSampler;
use crate::models::StrandModels;
use crate::tubes::TubeHit;
use cuticle_fiber::{FiberFrame, FiberModel};
use cuticle_light::EnvMap;
use cuticle_render::scene::{light_to_world, world_to_light};
use glam::DVec3;
use rand_core::Rng;
use rand_pcg::Pcg64Mcg;

/// Which sampling strategies a path uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Strategy {
    /// Environment and BCSDF sampling combined by the power heuristic.
    Mis,
    /// Environment sampling only.
    Environment,
    /// BCSDF sampling only.
    Bcsdf,
}

/// How long paths are.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct PathOptions {
    /// Most scattering events of a path.
    pub max_depth: u32,
    /// Vertices before Russian roulette starts.
    pub rr_depth: u32,
    pub strategy: Strategy,
}

impl Default for PathOptions {
    fn default() -> Self {
        Self {
            max_depth: 64,
            rr_depth: 3,
            strategy: Strategy::Mis,
        }
    }
}

/// One camera ray's path.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraSample {
    pub radiance: DVec3,
    /// Rays traced, the camera ray included.
    pub rays: u64,
    /// Whether the camera ray met hair (the pixel's coverage, averaged over its samples).
    pub hit: bool,
}

/// What a path reads: geometry, light and the fibers.
pub struct World<'a> {
    pub accel: &'a Accel,
    pub env: &'a EnvMap,
    pub sampler: &'a EnvSampler,
    pub models: &'a StrandModels,
}

/// Uniform numbers in [0, 1).
pub fn uniform(rng: &mut Pcg64Mcg) -> f64 {
    (rng.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

impl World<'_> {
    /// Environment radiance arriving from world direction `dir`.
    pub fn env_radiance(&self, dir: DVec3) -> DVec3 {
        self.env.radiance(world_to_light(dir).as_vec3()).as_dvec3()
    }

    fn env_pdf(&self, dir: DVec3) -> f64 {
        self.sampler.pdf(world_to_light(dir))
    }

    /// The radiance arriving at `origin` from along `dir` (a camera ray), and the rays traced.
    pub fn radiance(
        &self,
        origin: DVec3,
        dir: DVec3,
        options: &PathOptions,
        rng: &mut Pcg64Mcg,
    ) -> (DVec3, u64) {
        let s = self.camera_sample(origin, dir, options, rng);
        (s.radiance, s.rays)
    }

    /// [`Self::radiance`], and whether the camera ray met hair.
    pub fn camera_sample(
        &self,
        origin: DVec3,
        dir: DVec3,
        options: &PathOptions,
        rng: &mut Pcg64Mcg,
    ) -> CameraSample {
        let Some(hit) = self.accel.closest(origin, dir) else {
            return CameraSample {
                radiance: self.env_radiance(dir),
                rays: 1,
                hit: false,
            };
        };
        let (radiance, rays) = self.radiance_from_hair(hit, origin, dir, options, rng);
        CameraSample {
            radiance,
            rays: rays + 1,
            hit: true,
        }
    }

    /// The radiance leaving the hair at `hit` toward `origin`, and the rays traced after it.
    fn radiance_from_hair(
        &self,
        mut hit: TubeHit,
        origin: DVec3,
        dir: DVec3,
        options: &PathOptions,
        rng: &mut Pcg64Mcg,
    ) -> (DVec3, u64) {
        let mut rays = 0u64;
        let (mut origin, mut dir) = (origin, dir);
        let mut throughput = DVec3::ONE;
        let mut radiance = DVec3::ZERO;
        for depth in 0..options.max_depth {
            let f = self.accel.frame(hit, origin, dir);
            let frame = FiberFrame::from_tangent(f.tangent, f.position);
            let model = self.models.of(f.strand);
            let given = frame.angles(-dir);
            if options.strategy != Strategy::Bcsdf {
                let (direct, shadow_rays) =
                    self.next_event(model, &frame, given, f.h, f.on_axis, options, rng);
                radiance += throughput * direct;
                rays += shadow_rays;
            }
            let u = [uniform(rng), uniform(rng), uniform(rng), uniform(rng)];
            let Some(sample) = model.sample_at(given, f.h, u) else {
                break;
            };
            throughput *= sample.weight;
            if !throughput.is_finite() || throughput.max_element() <= 0.0 {
                break;
            }
            origin = f.on_axis;
            dir = frame.dir(sample.wo);
            rays += 1;
            match self.accel.closest(origin, dir) {
                None => {
                    let w = match options.strategy {
                        Strategy::Mis => power_heuristic(sample.pdf, self.env_pdf(dir)),
                        Strategy::Bcsdf => 1.0,
                        Strategy::Environment => 0.0,
                    };
                    if w > 0.0 {
                        radiance += throughput * self.env_radiance(dir) * w;
                    }
                    break;
                }
                Some(next) => hit = next,
            }
            if depth + 1 >= options.rr_depth {
                let survive = throughput.max_element().min(1.0);
                if uniform(rng) >= survive {
                    break;
                }
                throughput /= survive;
            }
        }
        (radiance, rays)
    }

    /// One environment sample seen from a vertex: S L / p_e, MIS-weighted, if unoccluded.
    #[allow(clippy::too_many_arguments)]
    fn next_event(
        &self,
        model: &dyn FiberModel,
        frame: &FiberFrame,
        given: cuticle_fiber::FiberAngles,
        h: f64,
        on_axis: DVec3,
        options: &PathOptions,
        rng: &mut Pcg64Mcg,
    ) -> (DVec3, u64) {
        let u = [uniform(rng), uniform(rng)];
        let Some(e) = self.sampler.sample(u) else {
            return (DVec3::ZERO, 0);
        };
        let dir = light_to_world(e.direction);
        let toward = frame.angles(dir);
        let s = model.eval_at(given, toward, h).total();
        if s.max_element() <= 0.0 || !s.is_finite() {
            return (DVec3::ZERO, 0);
        }
        if self.accel.occluded(on_axis, dir) {
            return (DVec3::ZERO, 1);
        }
        let w = match options.strategy {
            Strategy::Mis => power_heuristic(e.pdf, model.pdf_at(given, toward, h)),
            _ => 1.0,
        };
        let value = s * self.env_radiance(dir) * (w / e.pdf);
        (
            if value.is_finite() {
                value
            } else {
                DVec3::ZERO
            },
            1,
        )
    }
}

/// The power heuristic (β = 2) weight of a sample drawn with density `p` against one `q`.
pub fn power_heuristic(p: f64, q: f64) -> f64 {
    let (p2, q2) = (p * p, q * q);
    if p2 + q2 > 0.0 && (p2 + q2).is_finite() {
        p2 / (p2 + q2)
    } else if p.is_infinite() {
        1.0
    } else {
        0.0
    }
}
