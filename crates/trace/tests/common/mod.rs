//! Small scenes for the tracer's tests: slabs of straight strands in front of a camera, a
//! single fiber, constant and spot-lit environments.

#![allow(dead_code)]

use cuticle_groom::{Groom, GroomParts};
use cuticle_light::EnvMap;
use cuticle_render::{Camera, Scene, SceneSpec};
use glam::{DVec3, Vec3};

/// Strands along x, `layers` deep along +y (away from the camera), rows along z spaced a
/// little over their width, alternate layers shifted by half a row.
pub fn slab(layers: usize, rows: usize, thickness: f32) -> Groom {
    let mut positions = Vec::new();
    let mut offsets = vec![0u32];
    let pitch = 1.2 * thickness;
    for layer in 0..layers {
        for row in 0..rows {
            let z = (row as f32 - rows as f32 / 2.0 + 0.5 * (layer % 2) as f32) * pitch;
            let y = layer as f32 * pitch;
            for k in 0..9 {
                positions.push(Vec3::new(-2.0 + 0.5 * k as f32, y, z));
            }
            offsets.push(positions.len() as u32);
        }
    }
    Groom::from_parts(GroomParts {
        thickness: vec![thickness; positions.len()],
        positions,
        strand_offsets: offsets,
        ..GroomParts::default()
    })
    .unwrap()
}

/// A camera on −y looking at the origin with a vertical field of view of `fov_deg`.
pub fn front_camera(fov_deg: f64) -> Camera {
    Camera {
        eye: [0.0, -10.0, 0.0],
        target: [0.0, 0.0, 0.0],
        up: [0.0, 0.0, 1.0],
        fov_deg,
    }
}

pub fn scene(groom: Groom, env: EnvMap, width: usize, height: usize, camera: Camera) -> Scene {
    let spec = SceneSpec {
        width,
        height,
        camera: Some(camera),
        ..SceneSpec::default()
    };
    Scene::from_parts(spec, groom, env, Vec::new())
}

pub fn constant_env(value: f32) -> EnvMap {
    EnvMap::new(16, 8, vec![Vec3::splat(value); 128])
}

/// A sky of 0.2 with a small bright light of angular radius about 0.1 rad toward `toward`
/// (light-crate space, +y up).
pub fn spot_env(toward: DVec3) -> EnvMap {
    let c = toward.normalize();
    EnvMap::from_fn(512, 256, move |d| {
        let x = (d.dot(c) - 1.0) / 0.005;
        Vec3::splat(0.2 + 200.0 * x.exp() as f32)
    })
}

/// One long straight fiber along x through the origin, radius 0.1.
pub fn single_fiber() -> Groom {
    Groom::from_parts(GroomParts {
        positions: vec![Vec3::new(-50.0, 0.0, 0.0), Vec3::new(50.0, 0.0, 0.0)],
        thickness: vec![0.2; 2],
        strand_offsets: vec![0, 2],
        ..GroomParts::default()
    })
    .unwrap()
}

/// Rays along `dir` meeting the single fiber at offsets uniform across its projected width
/// (the k-th of n at the k-th stratum's centre, jittered by `jitter`).
pub fn ray_across_fiber(dir: DVec3, k: usize, n: usize, jitter: f64) -> (DVec3, DVec3) {
    let across = DVec3::X.cross(dir).normalize();
    let offset = 0.1 * (-1.0 + 2.0 * (k as f64 + jitter) / n as f64);
    (across * offset - dir * 10.0, dir)
}
