//! The brute-force reference (`--method brute`): the environment map as K = 6 n² directional
//! lights (a cube map of n × n texels a face, each carrying the map's mean radiance over the
//! texel times its solid angle; n = 16 gives the paper's 1536), shaded with the exact
//! Marschner 2003 model of the fiber crate, L_o = Σ_k E_k T_k S(ω_k, ω_o) cos θ_k / cos θ_o
//! (the crate's units, see lib.rs), with the same visibility and shadow maps as the SRBF path;
//! multiple scattering in [`crate::brute::dual_scattering`].

use crate::scene::{Lobes, Scene, light_to_world};
use cuticle_fiber::{FiberAngles, FiberFrame, FiberModel, Marschner2003};
use glam::DVec3;

/// One directional light: world direction toward it, and irradiance-weight E = L Δω.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Directional {
    pub direction: DVec3,
    pub power: DVec3,
}

/// Subsamples per texel side when averaging the map.
const SUB: usize = 4;

/// The environment of `scene` as 6 n² directional lights (zero-power ones dropped).
pub fn directional_lights(scene: &Scene, n: usize) -> Vec<Directional> {
    let mut out = Vec::with_capacity(6 * n * n);
    for face in 0..6 {
        for a in 0..n {
            for b in 0..n {
                let mut sum = DVec3::ZERO;
                let mut omega = 0.0;
                for sa in 0..SUB {
                    for sb in 0..SUB {
                        let u = -1.0 + 2.0 * (a as f64 + (sa as f64 + 0.5) / SUB as f64) / n as f64;
                        let v = -1.0 + 2.0 * (b as f64 + (sb as f64 + 0.5) / SUB as f64) / n as f64;
                        let d = cube_direction(face, u, v);
                        let w = (1.0 + u * u + v * v).powf(-1.5) * (2.0 / (n * SUB) as f64).powi(2);
                        sum += scene.env.radiance(d.as_vec3()).as_dvec3() * w;
                        omega += w;
                    }
                }
                let centre = cube_direction(
                    face,
                    -1.0 + (2.0 * a as f64 + 1.0) / n as f64,
                    -1.0 + (2.0 * b as f64 + 1.0) / n as f64,
                );
                if sum.max_element() > 0.0 && omega > 0.0 {
                    out.push(Directional {
                        direction: light_to_world(centre),
                        power: sum,
                    });
                }
            }
        }
    }
    out
}

/// Unit direction of cube face `face` at face coordinates (u, v) ∈ [−1, 1]².
fn cube_direction(face: usize, u: f64, v: f64) -> DVec3 {
    let d = match face {
        0 => DVec3::new(1.0, u, v),
        1 => DVec3::new(-1.0, v, u),
        2 => DVec3::new(v, 1.0, u),
        3 => DVec3::new(u, -1.0, v),
        4 => DVec3::new(u, v, 1.0),
        _ => DVec3::new(v, u, -1.0),
    };
    d.normalize()
}

/// A directional light seen from a fiber: its angles in the fiber frame and E = L Δω.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LocalDirectional {
    pub angles: FiberAngles,
    pub power: DVec3,
}

/// `lights` in the fiber frame `frame`.
pub fn local_lights(frame: &FiberFrame, lights: &[Directional]) -> Vec<LocalDirectional> {
    lights
        .iter()
        .map(|l| LocalDirectional {
            angles: frame.angles(l.direction),
            power: l.power,
        })
        .collect()
}

/// Single-scattering L_o toward `ao` (the viewer's angles in the fiber frame) from every light
/// `k` with transmittance `shadow[k]`, the lobes of `shown` only (Marschner 2003 has no others).
pub fn shade(
    model: &Marschner2003,
    ao: FiberAngles,
    lights: &[LocalDirectional],
    shadow: &[f32],
    shown: Lobes,
) -> DVec3 {
    let cos_o = ao.theta.cos().max(1e-4);
    lights
        .iter()
        .zip(shadow)
        .map(|(l, &t)| {
            let v = model.eval(l.angles, ao).0;
            let s = shown.sum([v[0], v[1], v[2]]);
            l.power * s * (t as f64 * l.angles.theta.cos() / cos_o)
        })
        .sum()
}
