//! The offset h a hit reports is the one the models' Φ(p, h) reads: with Chiang 2016 nearly
//! smooth (β_m = β_n = 0.01), the R lobe sampled at a hit leaves within a few hundredths of a
//! radian of the mirror reflection of the ray about the tube's actual surface normal there, for
//! offsets across the whole width. With h of the wrong sign it would leave 4 asin|h| away.

mod common;

use common::{ray_across_fiber, single_fiber};
use cuticle_fiber::{Chiang2016, FiberFrame, FiberModel, FiberParams, Lobe};
use cuticle_trace::Accel;
use glam::DVec3;

#[test]
fn reflection_leaves_where_the_cylinder_mirrors_it() {
    let params = FiberParams {
        eta: 1.55,
        beta: 0.01,
        alpha: 0.0,
        mu_a: DVec3::splat(0.5),
    };
    let model = Chiang2016::new(params, 0.01).unwrap();
    let accel = Accel::build(&single_fiber());
    let dir = DVec3::new(0.3, 1.0, 0.2).normalize();
    let mut checked = 0;
    for k in 0..40 {
        let (origin, d) = ray_across_fiber(dir, k, 40, 0.5);
        let hit = accel.closest(origin, d).expect("every ray meets the fiber");
        let f = accel.frame(hit, origin, d);
        let normal = (f.position - f.on_axis).normalize();
        let mirror = d - 2.0 * d.dot(normal) * normal;
        let frame = FiberFrame::from_tangent(f.tangent, f.position);
        let given = frame.angles(-d);
        for j in 0..64 {
            // A lobe draw below R's probability (≥ 0.04 here), remapped into its azimuth.
            let u = [0.0, (j as f64 + 0.5) / 64.0 * 0.04, 0.37, 0.61];
            let Some(s) = model.sample_at(given, f.h, u) else {
                continue;
            };
            if s.lobe != Lobe::R {
                continue;
            }
            let out = frame.dir(s.wo);
            let angle = out.dot(mirror).clamp(-1.0, 1.0).acos();
            assert!(
                angle < 0.05,
                "h {}: {angle} rad from the mirror direction",
                f.h
            );
            checked += 1;
        }
    }
    assert!(checked > 500, "{checked}");
}
