//! The environment map resampled onto each renderer's parameterisation, so that every world
//! direction receives the radiance cuticle gives it ([`EnvMap::radiance`], bilinear between
//! texel centres, the map's rotation applied) whatever the two conventions are.
//!
//! # cuticle (docs/conventions.md §4, crate cuticle-light, `cuticle_render::scene`)
//! The map's own frame is +y up: texel (j, k) of a W × H map has its centre at azimuth
//! φ = −π + 2π(j + ½)/W + ρ (ρ the scene's `env_rotate_deg`) and elevation θ = π/2 − π(k + ½)/H,
//! direction ω = (cos θ cos φ, sin θ, cos θ sin φ); the world (the groom's space, +z up) is
//! (x, y, z) ↦ (x, −z, y) of it (`light_to_world`).
//!
//! # Mitsuba 3 (`src/emitters/envmap.cpp`, v3.9.1: `uv_to_direction`, `eval_spectrum`)
//! The emitter's local frame is +y up; a local direction d has u = atan2(d.x, −d.z)/2π,
//! v = acos(d.y)/π, and the texels are centred in u (column j at u = (j + ½)/W′) but
//! corner-aligned in v (row k at v = k/(H′ − 1): the first and last rows sit on the poles),
//! bilinear between them. Its `to_world` is set to cuticle's `light_to_world`
//! ([`MITSUBA_TO_WORLD`]), so a local direction is a light-crate direction and each texel is
//! cuticle's radiance there. The grid has twice the map's columns and 2H + 1 rows (the same
//! columns and H + 1 rows past 4096 columns), so the resampling blurs less than a texel.
//!
//! # pbrt-v4 (`src/pbrt/lights.cpp`, `ImageInfiniteLight`; `src/pbrt/util/math.cpp`)
//! The infinite light takes only square equal-area octahedral images (a non-square one is an
//! error): texel (i, j) of an N × N image is looked up for the light-space direction
//! `EqualAreaSquareToSphere((i + ½)/N, (j + ½)/N)` ([`equal_area_square_to_sphere`], Clarberg
//! 2008), nearest texel, z up. The light is written with no transform, so light space is the
//! world and each texel is cuticle's radiance from that world direction. N is chosen so a texel
//! subtends about a quarter of the map's equatorial texel (N² ≥ 8WH/π; the map's size past 4096
//! columns).
//!
//! Both files are linear RGB OpenEXR at the map's scale (Mitsuba's `scale` and pbrt's `scale`
//! are 1; pbrt divides its images by the colour space's illuminant, so RGB (1, 1, 1) is 1).

use cuticle_light::EnvMap;
use cuticle_render::Image;
use cuticle_render::scene::{light_to_world, world_to_light};
use glam::DVec3;
use std::f64::consts::{FRAC_PI_4, PI};

/// Mitsuba's emitter `to_world`, row-major: cuticle's light-crate frame (+y up) to the world
/// (+z up), (x, y, z) ↦ (x, −z, y).
pub const MITSUBA_TO_WORLD: [[f64; 4]; 4] = [
    [1.0, 0.0, 0.0, 0.0],
    [0.0, 0.0, -1.0, 0.0],
    [0.0, 1.0, 0.0, 0.0],
    [0.0, 0.0, 0.0, 1.0],
];

/// Maps wider than this are resampled at their own density rather than twice it.
const MAX_DOUBLED_WIDTH: usize = 4096;

fn density(env: &EnvMap) -> usize {
    if env.width() <= MAX_DOUBLED_WIDTH {
        2
    } else {
        1
    }
}

/// The size W′ × H′ of the Mitsuba image of `env`.
pub fn mitsuba_size(env: &EnvMap) -> (usize, usize) {
    let f = density(env);
    (f * env.width(), f * env.height() + 1)
}

/// Mitsuba's local direction of texel (column, row) of a `width × height` envmap
/// (`uv_to_direction` at the texel's centre: u = (j + ½)/W, v = k/(H − 1)).
pub fn mitsuba_local_direction(column: usize, row: usize, width: usize, height: usize) -> DVec3 {
    let u = (column as f64 + 0.5) / width as f64;
    let v = row as f64 / (height - 1) as f64;
    let (sin_t, cos_t) = (PI * v).sin_cos();
    let (sin_p, cos_p) = (2.0 * PI * u).sin_cos();
    DVec3::new(sin_p * sin_t, cos_t, -cos_p * sin_t)
}

/// The world direction of a Mitsuba local direction under [`MITSUBA_TO_WORLD`].
pub fn mitsuba_to_world(local: DVec3) -> DVec3 {
    let m = &MITSUBA_TO_WORLD;
    let row = |r: usize| m[r][0] * local.x + m[r][1] * local.y + m[r][2] * local.z;
    DVec3::new(row(0), row(1), row(2))
}

/// The Mitsuba envmap image of `env` (module documentation).
pub fn mitsuba_image(env: &EnvMap) -> Image {
    let (width, height) = mitsuba_size(env);
    let pixels = (0..width * height)
        .map(|k| {
            let world =
                mitsuba_to_world(mitsuba_local_direction(k % width, k / width, width, height));
            world_radiance(env, world)
        })
        .collect();
    Image {
        width,
        height,
        pixels,
    }
}

/// The side N of the pbrt-v4 equal-area image of `env`.
pub fn pbrt_size(env: &EnvMap) -> usize {
    let f = density(env) as f64;
    let texels = (env.width() * env.height()) as f64;
    ((f * (2.0 * texels / PI).sqrt()).ceil() as usize).max(2)
}

/// pbrt-v4's `EqualAreaSquareToSphere` (Clarberg 2008, "Fast equal-area mapping of the
/// (hemi)sphere using SIMD"): the unit direction of point (u, v) ∈ [0, 1]² of the octahedral
/// square, z the pole.
pub fn equal_area_square_to_sphere(u: f64, v: f64) -> DVec3 {
    let (u, v) = (2.0 * u - 1.0, 2.0 * v - 1.0);
    let (up, vp) = (u.abs(), v.abs());
    let signed_distance = 1.0 - (up + vp);
    let r = 1.0 - signed_distance.abs();
    let phi = if r == 0.0 { 1.0 } else { (vp - up) / r + 1.0 } * FRAC_PI_4;
    let z = (1.0 - r * r).copysign(signed_distance);
    let (sin_p, cos_p) = phi.sin_cos();
    let s = r * (2.0 - r * r).max(0.0).sqrt();
    DVec3::new(cos_p.copysign(u) * s, sin_p.copysign(v) * s, z)
}

/// The pbrt-v4 infinite light's image of `env` (module documentation).
pub fn pbrt_image(env: &EnvMap) -> Image {
    let n = pbrt_size(env);
    let pixels = (0..n * n)
        .map(|k| {
            let (i, j) = (k % n, k / n);
            let world = equal_area_square_to_sphere(
                (i as f64 + 0.5) / n as f64,
                (j as f64 + 0.5) / n as f64,
            );
            world_radiance(env, world)
        })
        .collect();
    Image {
        width: n,
        height: n,
        pixels,
    }
}

/// cuticle's radiance arriving from world direction `world` (as `Scene::env_radiance`).
fn world_radiance(env: &EnvMap, world: DVec3) -> DVec3 {
    env.radiance(world_to_light(world).as_vec3()).as_dvec3()
}

/// The world direction of texel (column, row) of a cuticle map, its rotation applied.
pub fn cuticle_world_direction(env: &EnvMap, column: usize, row: usize) -> DVec3 {
    light_to_world(env.direction(column, row))
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    /// A black 32 × 16 map with one bright texel, rotated by 30°.
    fn one_bright_texel(column: usize, row: usize) -> EnvMap {
        let (w, h) = (32, 16);
        let mut pixels = vec![Vec3::ZERO; w * h];
        pixels[row * w + column] = Vec3::new(1000.0, 500.0, 250.0);
        EnvMap::new(w, h, pixels).with_rotation(30f64.to_radians())
    }

    /// The texel of `image` with the largest value.
    fn brightest(image: &Image) -> (usize, usize) {
        let k = (0..image.pixels.len())
            .max_by(|&a, &b| image.pixels[a].x.total_cmp(&image.pixels[b].x))
            .unwrap();
        (k % image.width, k / image.width)
    }

    /// An angle between two directions, degrees.
    fn angle_deg(a: DVec3, b: DVec3) -> f64 {
        a.normalize()
            .dot(b.normalize())
            .clamp(-1.0, 1.0)
            .acos()
            .to_degrees()
    }

    /// The bright texel lights the same world direction in cuticle and in the Mitsuba image
    /// read by Mitsuba's own formula, to within a texel (a cuticle texel spans 11.25°), for
    /// texels near a pole, near the seam and in between.
    #[test]
    fn mitsuba_image_puts_the_bright_texel_where_cuticle_has_it() {
        for (column, row) in [(5, 4), (0, 8), (31, 1), (17, 14)] {
            let env = one_bright_texel(column, row);
            let image = mitsuba_image(&env);
            let (j, k) = brightest(&image);
            let there = mitsuba_to_world(mitsuba_local_direction(j, k, image.width, image.height));
            let want = cuticle_world_direction(&env, column, row);
            let off = angle_deg(there, want);
            assert!(off < 6.0, "texel ({column}, {row}): {off}° apart");
        }
    }

    /// The same for pbrt-v4's equal-area image, read by pbrt's formula.
    #[test]
    fn pbrt_image_puts_the_bright_texel_where_cuticle_has_it() {
        for (column, row) in [(5, 4), (0, 8), (31, 1), (17, 14)] {
            let env = one_bright_texel(column, row);
            let image = pbrt_image(&env);
            assert_eq!(image.width, image.height);
            let (i, j) = brightest(&image);
            let n = image.width as f64;
            let there = equal_area_square_to_sphere((i as f64 + 0.5) / n, (j as f64 + 0.5) / n);
            let want = cuticle_world_direction(&env, column, row);
            let off = angle_deg(there, want);
            assert!(off < 6.0, "texel ({column}, {row}): {off}° apart");
        }
    }

    /// Mitsuba's direction formula inverts its `direction_to_uv` (atan2(x, −z)/2π, acos(y)/π),
    /// the one the emitter looks texels up with, and its first row is the +y pole.
    #[test]
    fn mitsuba_directions_match_its_lookup() {
        let (w, h) = (24, 13);
        for (j, k) in [(0, 3), (7, 6), (23, 11), (12, 1)] {
            let d = mitsuba_local_direction(j, k, w, h);
            let u = d.x.atan2(-d.z) / (2.0 * PI);
            let v = d.y.clamp(-1.0, 1.0).acos() / PI;
            assert!((u.rem_euclid(1.0) * w as f64 - (j as f64 + 0.5)).abs() < 1e-9);
            assert!((v * (h - 1) as f64 - k as f64).abs() < 1e-9);
        }
        assert!(mitsuba_local_direction(5, 0, w, h).abs_diff_eq(DVec3::Y, 1e-12));
        assert!(mitsuba_to_world(DVec3::Y).abs_diff_eq(DVec3::Z, 1e-12));
    }

    /// Equal-area: unit directions, the square's centre at +z and corners at −z, and equal
    /// cells sample the sphere evenly (the mean of z over the cell centres is near 0, as is
    /// each octant's share).
    #[test]
    fn equal_area_mapping_is_pbrts() {
        assert!(equal_area_square_to_sphere(0.5, 0.5).abs_diff_eq(DVec3::Z, 1e-12));
        assert!(equal_area_square_to_sphere(0.0, 0.0).abs_diff_eq(-DVec3::Z, 1e-12));
        assert!(equal_area_square_to_sphere(1.0, 0.5).abs_diff_eq(DVec3::X, 1e-12));
        assert!(equal_area_square_to_sphere(0.5, 1.0).abs_diff_eq(DVec3::Y, 1e-12));
        let n = 64;
        let mut above = 0;
        for k in 0..n * n {
            let d = equal_area_square_to_sphere(
                ((k % n) as f64 + 0.5) / n as f64,
                ((k / n) as f64 + 0.5) / n as f64,
            );
            assert!((d.length() - 1.0).abs() < 1e-12);
            above += usize::from(d.z > 0.5);
        }
        // The cap z > 1/2 is a quarter of the sphere's area.
        let share = above as f64 / (n * n) as f64;
        assert!((share - 0.25).abs() < 0.01, "{share}");
    }

    /// A uniform map stays uniform (no texel is missed or doubled).
    #[test]
    fn a_constant_map_resamples_to_itself() {
        let env = EnvMap::new(16, 8, vec![Vec3::new(0.5, 1.0, 2.0); 128]);
        for image in [mitsuba_image(&env), pbrt_image(&env)] {
            assert!(
                image
                    .pixels
                    .iter()
                    .all(|p| p.abs_diff_eq(DVec3::new(0.5, 1.0, 2.0), 1e-6))
            );
        }
    }
}
