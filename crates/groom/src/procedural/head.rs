//! The head a procedural groom grows on: an ellipsoid centred at the origin, +z up, face toward
//! +y. Hair grows above a hairline that is high at the forehead, lower over the ears and lowest
//! at the nape.

use super::random::Random;
use glam::Vec3;
use serde::{Deserialize, Serialize};

/// The skull as an ellipsoid centred at the origin, semi-axes in centimetres.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Head {
    /// Semi-axes: half the width (x), half the depth front to back (y), half the height (z).
    pub radii: [f32; 3],
}

impl Default for Head {
    fn default() -> Self {
        Self {
            radii: [7.6, 9.6, 9.2],
        }
    }
}

impl Head {
    fn radii_vec(&self) -> Vec3 {
        Vec3::from_array(self.radii)
    }

    /// The surface point in unit direction `dir` of the ellipsoid's parameter sphere.
    pub fn surface_point(&self, dir: Vec3) -> Vec3 {
        dir * self.radii_vec()
    }

    /// Outward unit normal of the surface at `point`.
    pub fn normal_at(&self, point: Vec3) -> Vec3 {
        let r = self.radii_vec();
        (point / (r * r)).try_normalize().unwrap_or(Vec3::Z)
    }

    /// Where `point` lies inside the head grown by `margin` on every axis, the nearest point
    /// (along the parameter sphere's radius) of that grown surface; `None` outside.
    pub fn push_out(&self, point: Vec3, margin: f32) -> Option<Vec3> {
        let r = self.radii_vec() + Vec3::splat(margin);
        let q = point / r;
        let len = q.length();
        (len < 1.0).then(|| q.try_normalize().unwrap_or(Vec3::Z) * r)
    }

    /// Unit direction (on the parameter sphere) of a random root above the hairline, roughly
    /// uniform over the scalp's area.
    pub fn sample_scalp_direction(&self, rng: &mut Random) -> Vec3 {
        let lowest = hairline_elevation(std::f32::consts::PI).sin();
        for _ in 0..64 {
            let z = rng.range(lowest, 1.0);
            let azimuth = rng.angle();
            if z.asin() >= hairline_elevation(azimuth) {
                return direction(azimuth, z);
            }
        }
        Vec3::Z
    }
}

/// Elevation (radians above the head's equator) of the hairline at `azimuth`, measured from
/// the face (+y) toward +x: 35° at the forehead, 10° over the ears, −30° at the nape.
pub fn hairline_elevation(azimuth: f32) -> f32 {
    let degrees = 6.25 + 32.5 * azimuth.cos() - 3.75 * (2.0 * azimuth).cos();
    degrees.to_radians()
}

/// Unit vector at `azimuth` (from +y toward +x) with height `z`.
fn direction(azimuth: f32, z: f32) -> Vec3 {
    let rho = (1.0 - z * z).max(0.0).sqrt();
    Vec3::new(rho * azimuth.sin(), rho * azimuth.cos(), z)
}

/// The way hair is combed at a root: back over the head and away from a centre parting, and
/// down behind the ears; tangent to the scalp, lifted off it by `lift` (0 flat, 1 straight out).
pub fn comb_direction(root_dir: Vec3, normal: Vec3, lift: f32) -> Vec3 {
    let side = (root_dir.x / 0.2).clamp(-1.0, 1.0);
    let down = 0.8 * (-root_dir.y).max(0.0);
    let wanted = Vec3::new(0.7 * side, -1.0, -down);
    let tangent = (wanted - normal * wanted.dot(normal))
        .try_normalize()
        .unwrap_or(Vec3::NEG_Y);
    (tangent + normal * lift).normalize()
}

/// A horizontal direction tangent to the scalp at `normal`: the side to side axis along which
/// waves swing.
pub fn side_direction(normal: Vec3) -> Vec3 {
    Vec3::Z.cross(normal).try_normalize().unwrap_or(Vec3::X)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::procedural::random::Stream;
    use std::f32::consts::PI;

    #[test]
    fn hairline_is_high_at_the_forehead_and_low_at_the_nape() {
        let degrees = |a: f32| hairline_elevation(a).to_degrees();
        assert!((degrees(0.0) - 35.0).abs() < 1e-3);
        assert!((degrees(PI / 2.0) - 10.0).abs() < 1e-3);
        assert!((degrees(-PI / 2.0) - 10.0).abs() < 1e-3);
        assert!((degrees(PI) + 30.0).abs() < 1e-3);
    }

    #[test]
    fn roots_lie_above_the_hairline() {
        let head = Head::default();
        let rng = &mut Random::for_object(3, Stream::Strand, 0);
        for _ in 0..2000 {
            let d = head.sample_scalp_direction(rng);
            assert!((d.length() - 1.0).abs() < 1e-5);
            let azimuth = d.x.atan2(d.y);
            assert!(d.z.asin() >= hairline_elevation(azimuth) - 1e-5, "{d}");
        }
    }

    #[test]
    fn points_inside_are_pushed_onto_the_grown_surface() {
        let head = Head::default();
        let inside = Vec3::new(1.0, 2.0, 3.0);
        let out = head.push_out(inside, 0.5).unwrap();
        let r = Vec3::from_array(head.radii) + 0.5;
        assert!(((out / r).length() - 1.0).abs() < 1e-5);
        let same_ray = (out / r).normalize().dot((inside / r).normalize());
        assert!((same_ray - 1.0).abs() < 1e-5);
        assert_eq!(head.push_out(Vec3::new(0.0, 0.0, 20.0), 0.5), None);
    }

    #[test]
    fn combing_runs_along_the_scalp_and_front_hair_goes_back() {
        let head = Head::default();
        let rng = &mut Random::for_object(4, Stream::Strand, 0);
        for _ in 0..500 {
            let d = head.sample_scalp_direction(rng);
            let normal = head.normal_at(head.surface_point(d));
            let flat = comb_direction(d, normal, 0.0);
            assert!(flat.dot(normal).abs() < 1e-4, "tangent to the scalp");
            if d.y > 0.0 {
                assert!(flat.y <= 1e-4, "front hair goes back: {flat} at {d}");
            }
            assert!(
                comb_direction(d, normal, 0.5).dot(normal) > 0.1,
                "lifted off the scalp"
            );
        }
    }
}
