//! The deep opacity maps' transmittance (render's frame/shadows.rs, sharp lights) against exact
//! ray casting through the path tracer's tubes, from the groom's points, for 19 light
//! directions: the mean over the bottom fifth of the groom (by height) and over all points.
//! `cargo run --release --example shadow_probe [GROOM [visible]]`: GROOM a preset or a .hair
//! file (default: straight); `visible`: only the points the default camera sees at 360 × 240
//! (else every third point). Issue 13's instrument for the tips.
use cuticle_render::frame::shadows::{ShadowOptions, transmittance};
use cuticle_render::{Scene, SceneSpec};
use cuticle_trace::Accel;
use glam::DVec3;
use rayon::prelude::*;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let mut spec = SceneSpec::default();
    if let Some(g) = args.get(1) {
        spec.groom = g.clone();
    }
    let scene = Scene::load_without_lights(spec).unwrap();
    let groom = &scene.groom;
    let accel = Accel::build(groom);
    let pos = groom.positions();
    let (zlo, zhi) = (groom.bounds().min.z, groom.bounds().max.z);
    let visible_only = args.get(2).map(String::as_str) == Some("visible");
    let all: Vec<u32> = if visible_only {
        let view = scene.camera.view(360, 240);
        cuticle_render::frame::draw::draw_strands(groom, &view, 360, 240, 8)
            .visible_points(groom.point_count())
    } else {
        (0..groom.point_count() as u32).step_by(3).collect()
    };
    let tips: Vec<u32> = all
        .iter()
        .copied()
        .filter(|&p| pos[p as usize].z < zlo + 0.2 * (zhi - zlo))
        .collect();
    println!("points {} tips {} z {zlo}..{zhi}", all.len(), tips.len());
    let mut dirs = Vec::new();
    for &(elev, n) in &[
        (90.0f64, 1),
        (55.0, 4),
        (35.0, 4),
        (10.0, 4),
        (-20.0, 4),
        (-60.0, 2),
    ] {
        for k in 0..n {
            let az = (k as f64 / n as f64) * std::f64::consts::TAU + 0.3;
            let (e, a) = (elev.to_radians(), az);
            dirs.push(DVec3::new(e.cos() * a.cos(), e.cos() * a.sin(), e.sin()));
        }
    }
    let opts = ShadowOptions::default();
    let zeros = vec![0.0; dirs.len()];
    for (name, set) in [("tips", &tips), ("all", &all)] {
        let map = transmittance(groom, set, &dirs, &zeros, &opts);
        let nl = dirs.len();
        let mut tm_all = 0.0;
        let mut te_all = 0.0;
        for (j, d) in dirs.iter().enumerate() {
            let exact: f64 = set
                .par_iter()
                .map(|&p| {
                    let x = pos[p as usize].as_dvec3();
                    if accel.occluded(x, *d) { 0.0 } else { 1.0 }
                })
                .sum::<f64>()
                / set.len() as f64;
            let m: f64 =
                (0..set.len()).map(|k| map[k * nl + j] as f64).sum::<f64>() / set.len() as f64;
            tm_all += m;
            te_all += exact;
            println!(
                "{name} dir elev {:5.1} az {:5.2}: map {:.3} exact {:.3} ratio {:.3}",
                d.z.asin().to_degrees(),
                d.y.atan2(d.x),
                m,
                exact,
                m / exact
            );
        }
        println!(
            "{name} mean map {:.3} exact {:.3} ratio {:.3}",
            tm_all / nl as f64,
            te_all / nl as f64,
            tm_all / te_all
        );
    }
}
