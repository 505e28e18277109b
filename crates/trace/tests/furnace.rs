//! The white furnace of a groom (issue 12): μ_a = 0, an energy-conserving model, a uniform white
//! environment of radiance 1. Every pixel — hair or not — is 1 within its Monte Carlo error,
//! for slabs 1, 4 and 12 layers deep: the hair disappears. Any pdf, weight or frame error, a
//! missing cos θ ratio or double-counted MIS shows as a pixel off 1.
//!
//! Tolerance: each pixel within 5 of its own standard errors (plus 2e-3 for the model's
//! furnace error), 32 × 16 pixels at 48 samples each, paths unlimited in depth (max_depth
//! 100,000: a lossless path ends only by escaping); and the mean of all pixels within 4 of its
//! standard errors (about 0.2 %) plus the same 2e-3.

mod common;

use common::{constant_env, front_camera, scene, slab};
use cuticle_fiber::{Chiang2016, DEon2011, FiberModel, FiberParams};
use cuticle_trace::{PathOptions, StrandModels, Strategy, TraceOptions, render};
use glam::DVec3;

fn lossless(beta: f64) -> FiberParams {
    FiberParams {
        eta: 1.55,
        beta,
        alpha: (2.0f64).to_radians(),
        mu_a: DVec3::ZERO,
    }
}

fn check(model: impl Fn() -> Box<dyn FiberModel>, slack: f64) {
    for layers in [1, 4, 12] {
        let groom = slab(layers, 24, 0.1);
        let s = scene(groom, constant_env(1.0), 32, 16, front_camera(8.0));
        let models = StrandModels::uniform(model(), s.groom.strand_count());
        let options = TraceOptions {
            spp: 48,
            seed: 7,
            path: PathOptions {
                max_depth: 100_000,
                rr_depth: 3,
                strategy: Strategy::Mis,
            },
        };
        let out = render(&s, &models, &options, &|_, _| {});
        let n = out.image.pixels.len() as f64;
        let (mut mean, mut variance) = (0.0, 0.0);
        for (k, (p, e)) in out.image.pixels.iter().zip(&out.standard_error).enumerate() {
            for c in 0..3 {
                let tolerance = 5.0 * e[c] + slack;
                assert!(
                    (p[c] - 1.0).abs() <= tolerance,
                    "{} layers {layers} pixel {k}: {} ± {}",
                    models.name(),
                    p[c],
                    e[c]
                );
            }
            mean += p.x / n;
            variance += e.x * e.x / (n * n);
        }
        let error = variance.sqrt();
        println!(
            "{} layers {layers}: mean {mean:.6} ± {error:.6}, rays {}",
            models.name(),
            out.stats.rays
        );
        assert!(
            (mean - 1.0).abs() < 4.0 * error + slack,
            "{} layers {layers}: mean {mean} ± {error}",
            models.name()
        );
    }
}

#[test]
fn chiang2016_groom_vanishes_in_the_white_furnace() {
    check(
        || Box::new(Chiang2016::new(lossless(0.3), 0.3).unwrap()),
        2e-3,
    );
}

#[test]
fn deon2011_groom_vanishes_in_the_white_furnace() {
    check(
        || Box::new(DEon2011::new(lossless(0.2)).unwrap().tabulated()),
        2e-3,
    );
}
