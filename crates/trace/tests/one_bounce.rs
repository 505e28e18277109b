//! One bounce with no occlusion against the model's own evaluation (issue 12): a single straight
//! fiber, rays at offsets uniform across its projected width, max_depth 1, under a constant
//! environment and under a small bright light (angular radius ≈ 0.1 rad) on a dim sky. The
//! tracer's mean matches a quadrature of
//! - Marschner 2003: the renderer's L_o = (1/cos θ_o) ∫ S(ω_i, ω_o) L_i cos θ_i dω_i (the form
//!   `--method srbf|brute` use; the tracer evaluates ∫ S(ω_o, ω_i) L_i dω_i, equal for a
//!   reciprocal model: this is the check that they agree);
//! - Chiang 2016: ∫ S(ω_o, ω_i) L_i dω_i with the far-field S (the tracer uses the near field at
//!   each hit's h, so this also checks that h is uniform across the width and averages back).
//!
//! Tolerance: 4 standard errors of the mean of 60,000 rays, plus 0.3 % of the value for the
//! quadrature (720 × 1440 midpoint nodes over the sphere for Marschner's narrow lobes, 360 × 720
//! for Chiang's) and the map's bilinear lookup.

mod common;

use common::{constant_env, ray_across_fiber, single_fiber, spot_env};
use cuticle_fiber::models::marschner2003::MarschnerParams;
use cuticle_fiber::{Chiang2016, FiberAngles, FiberFrame, FiberModel, FiberParams, Marschner2003};
use cuticle_light::EnvMap;
use cuticle_render::scene::world_to_light;
use cuticle_trace::env_sampling::EnvSampler;
use cuticle_trace::path::World;
use cuticle_trace::{Accel, PathOptions, StrandModels, Strategy};
use glam::DVec3;
use rand_core::SeedableRng;
use rand_pcg::Pcg64Mcg;
use std::f64::consts::PI;

const RAYS: usize = 60_000;

fn traced(model: Box<dyn FiberModel>, env: &EnvMap, dir: DVec3) -> (f64, f64) {
    traced_with(model, env, dir, Strategy::Mis)
}

fn traced_with(
    model: Box<dyn FiberModel>,
    env: &EnvMap,
    dir: DVec3,
    strategy: Strategy,
) -> (f64, f64) {
    let groom = single_fiber();
    let accel = Accel::build(&groom);
    let sampler = EnvSampler::new(env);
    let models = StrandModels::uniform(model, 1);
    let world = World {
        accel: &accel,
        env,
        sampler: &sampler,
        models: &models,
    };
    let options = PathOptions {
        max_depth: 1,
        rr_depth: 10,
        strategy,
    };
    let mut rng = Pcg64Mcg::seed_from_u64(3);
    let (mut sum, mut sum_sq) = (0.0, 0.0);
    for k in 0..RAYS {
        let jitter = cuticle_trace::path::uniform(&mut rng);
        let (origin, d) = ray_across_fiber(dir, k, RAYS, jitter);
        let (l, _) = world.radiance(origin, d, &options, &mut rng);
        sum += l.x;
        sum_sq += l.x * l.x;
    }
    let n = RAYS as f64;
    let mean = sum / n;
    (mean, ((sum_sq / n - mean * mean) / (n - 1.0)).sqrt())
}

/// ∫ f(ω) L(ω) dω over the sphere by midpoint nodes in the fiber frame's (θ, φ).
fn quadrature(env: &EnvMap, frame: &FiberFrame, nt: usize, f: impl Fn(FiberAngles) -> f64) -> f64 {
    let np = 2 * nt;
    let (dt, dp) = (PI / nt as f64, 2.0 * PI / np as f64);
    let mut sum = 0.0;
    for i in 0..nt {
        let theta = -0.5 * PI + (i as f64 + 0.5) * dt;
        for j in 0..np {
            let a = FiberAngles::new(theta, -PI + (j as f64 + 0.5) * dp);
            let l = env.radiance(world_to_light(frame.dir(a)).as_vec3()).x as f64;
            sum += f(a) * l * theta.cos() * dt * dp;
        }
    }
    sum
}

fn environments() -> Vec<(&'static str, EnvMap)> {
    let spot = world_to_light(DVec3::new(-0.2, -0.6, 0.8));
    vec![
        ("constant", constant_env(1.0)),
        ("small light", spot_env(spot)),
    ]
}

fn view_dir() -> DVec3 {
    DVec3::new(0.3, 1.0, 0.2).normalize()
}

fn assert_close(what: &str, (mean, error): (f64, f64), expected: f64) {
    println!("{what}: traced {mean:.5} ± {error:.5}, quadrature {expected:.5}");
    assert!(
        (mean - expected).abs() < 4.0 * error + 3e-3 * expected.abs(),
        "{what}: traced {mean} ± {error}, quadrature {expected}"
    );
}

#[test]
fn marschner_one_bounce_matches_the_renderers_integral() {
    let params = MarschnerParams {
        mu_a: DVec3::splat(0.3),
        ..MarschnerParams::default()
    };
    let frame = FiberFrame::from_tangent(DVec3::X, DVec3::Z);
    let wo = frame.angles(-view_dir());
    for (name, env) in environments() {
        let model = Marschner2003::new(params).unwrap();
        let expected = quadrature(&env, &frame, 720, |wi| {
            model.eval(wi, wo).total().x * wi.theta.cos() / wo.theta.cos()
        });
        let got = traced(
            Box::new(Marschner2003::new(params).unwrap()),
            &env,
            view_dir(),
        );
        assert_close(&format!("marschner, {name}"), got, expected);
    }
}

#[test]
fn chiang_one_bounce_matches_its_far_field_integral() {
    let params = FiberParams {
        eta: 1.55,
        beta: 0.3,
        alpha: (2.0f64).to_radians(),
        mu_a: DVec3::splat(0.4),
    };
    let frame = FiberFrame::from_tangent(DVec3::X, DVec3::Z);
    let wo = frame.angles(-view_dir());
    for (name, env) in environments() {
        let model = Chiang2016::new(params, 0.5).unwrap();
        let expected = quadrature(&env, &frame, 360, |wi| model.eval(wo, wi).total().x);
        let got = traced(Box::new(model), &env, view_dir());
        assert_close(&format!("chiang2016, {name}"), got, expected);
    }
}
