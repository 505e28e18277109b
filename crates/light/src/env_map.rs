//! A lat-long environment map in memory: linear RGB radiance per pixel, row 0 at the zenith, plus a
//! rotation about the up axis (conventions in the crate docs).

use crate::latlong::{
    direction_from_angles, direction_to_angles, phi_center, pixel_coords, pixel_solid_angle,
    theta_center,
};
use glam::{DVec3, Vec3};
use rayon::prelude::*;

/// An equirectangular environment map (+y up, docs/conventions.md §4 layout).
#[derive(Clone, Debug)]
pub struct EnvMap {
    width: usize,
    height: usize,
    pixels: Vec<Vec3>,
    rotation: f64,
    clamped_negatives: usize,
}

/// One pixel of a map with its world direction (rotation applied) and solid angle.
#[derive(Clone, Copy, Debug)]
pub struct EnvPixel {
    pub column: usize,
    pub row: usize,
    pub direction: DVec3,
    pub solid_angle: f64,
    pub radiance: Vec3,
}

impl EnvMap {
    /// A map from row-major pixels (row 0 on top). Panics if `pixels.len() != width * height` or a
    /// side is zero: callers build the vector themselves. Loading validates values; this does not.
    pub fn new(width: usize, height: usize, pixels: Vec<Vec3>) -> Self {
        assert!(width > 0 && height > 0, "an environment map needs pixels");
        assert_eq!(
            pixels.len(),
            width * height,
            "pixel count must be width × height"
        );
        Self {
            width,
            height,
            pixels,
            rotation: 0.0,
            clamped_negatives: 0,
        }
    }

    /// A map whose pixel (column, row) holds `f(direction)`, directions taken at pixel centres.
    pub fn from_fn(width: usize, height: usize, f: impl Fn(DVec3) -> Vec3 + Sync) -> Self {
        let pixels = (0..width * height)
            .into_par_iter()
            .map(|i| {
                let (column, row) = (i % width, i / width);
                f(direction_from_angles(
                    theta_center(row, height),
                    phi_center(column, width),
                ))
            })
            .collect();
        Self::new(width, height, pixels)
    }

    pub(crate) fn with_clamped_negatives(mut self, count: usize) -> Self {
        self.clamped_negatives = count;
        self
    }

    /// The same pixels rotated about +y by `radians`: content at file azimuth φ appears at φ + ρ.
    pub fn with_rotation(mut self, radians: f64) -> Self {
        self.rotation = radians;
        self
    }

    pub fn width(&self) -> usize {
        self.width
    }

    pub fn height(&self) -> usize {
        self.height
    }

    /// Rotation about +y, radians.
    pub fn rotation(&self) -> f64 {
        self.rotation
    }

    /// How many negative channel values loading clamped to 0.
    pub fn clamped_negatives(&self) -> usize {
        self.clamped_negatives
    }

    /// Row-major pixels, row 0 on top, in the file's orientation (rotation not applied).
    pub fn pixels(&self) -> &[Vec3] {
        &self.pixels
    }

    pub fn pixel(&self, column: usize, row: usize) -> Vec3 {
        self.pixels[row * self.width + column]
    }

    /// Solid angle of any pixel of `row`: Δφ (sin θ_top − sin θ_bottom), Δφ = 2π/W.
    pub fn solid_angle(&self, row: usize) -> f64 {
        pixel_solid_angle(row, self.width, self.height)
    }

    /// World direction of the centre of pixel (column, row), rotation applied.
    pub fn direction(&self, column: usize, row: usize) -> DVec3 {
        direction_from_angles(
            theta_center(row, self.height),
            phi_center(column, self.width) + self.rotation,
        )
    }

    /// Radiance arriving from world direction `dir` (need not be normalised), bilinear between
    /// pixel centres; wraps in φ, clamps at the poles.
    pub fn radiance(&self, dir: Vec3) -> Vec3 {
        let (theta, phi) = direction_to_angles(dir.as_dvec3().normalize());
        let (x, y) = pixel_coords(theta, phi - self.rotation, self.width, self.height);
        self.bilinear(x - 0.5, y - 0.5)
    }

    /// Bilinear lookup at continuous pixel-centre coordinates (pixel (j, k) at (j, k)).
    fn bilinear(&self, x: f64, y: f64) -> Vec3 {
        let y = y.clamp(0.0, (self.height - 1) as f64);
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = ((x - x0) as f32, (y - y0) as f32);
        let wrap = |c: f64| (c as i64).rem_euclid(self.width as i64) as usize;
        let (c0, c1) = (wrap(x0), wrap(x0 + 1.0));
        let r0 = y0 as usize;
        let r1 = (r0 + 1).min(self.height - 1);
        let top = self.pixel(c0, r0).lerp(self.pixel(c1, r0), fx);
        let bottom = self.pixel(c0, r1).lerp(self.pixel(c1, r1), fx);
        top.lerp(bottom, fy)
    }

    /// Every pixel with its world direction and solid angle, row by row.
    pub fn iter(&self) -> impl Iterator<Item = EnvPixel> + '_ {
        (0..self.height).flat_map(move |row| {
            let solid_angle = self.solid_angle(row);
            (0..self.width).map(move |column| EnvPixel {
                column,
                row,
                direction: self.direction(column, row),
                solid_angle,
                radiance: self.pixel(column, row),
            })
        })
    }

    /// ∫ L dω over the sphere, per channel (the map's total radiant intensity).
    pub fn integral(&self) -> DVec3 {
        (0..self.height)
            .map(|row| {
                let sum: DVec3 = self.pixels[row * self.width..(row + 1) * self.width]
                    .iter()
                    .map(|p| p.as_dvec3())
                    .sum();
                sum * self.solid_angle(row)
            })
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn ramp_map() -> EnvMap {
        EnvMap::new(
            8,
            4,
            (0..32).map(|i| Vec3::new(i as f32, 0.0, 1.0)).collect(),
        )
    }

    #[test]
    fn radiance_at_pixel_centres_is_the_pixel() {
        let map = ramp_map().with_rotation(0.7);
        for p in map.iter() {
            let got = map.radiance(p.direction.as_vec3());
            assert!(
                got.abs_diff_eq(p.radiance, 1e-4),
                "{:?} vs {:?}",
                got,
                p.radiance
            );
        }
    }

    #[test]
    fn radiance_interpolates_between_centres_and_wraps() {
        use crate::latlong::{phi_center, theta_center};
        let map = ramp_map();
        let at = |theta: f64, phi: f64| map.radiance(direction_from_angles(theta, phi).as_vec3());
        let between = at(theta_center(1, 4), phi_center(2, 8) + PI / 8.0);
        assert!((between.x - 10.5).abs() < 1e-3, "{between}");
        let across_seam = at(theta_center(2, 4), PI);
        assert!((across_seam.x - 19.5).abs() < 1e-3, "{across_seam}");
        let quarter_down = at(theta_center(1, 4) - PI / 16.0, phi_center(5, 8));
        assert!((quarter_down.x - 15.0).abs() < 1e-3, "{quarter_down}");
    }

    #[test]
    fn rotation_moves_content_to_larger_azimuth() {
        let rho = 2.0 * PI / 8.0;
        let map = ramp_map();
        let rotated = map.clone().with_rotation(rho);
        let d = map.direction(3, 1);
        let moved = DVec3::new(
            d.x * rho.cos() - d.z * rho.sin(),
            d.y,
            d.x * rho.sin() + d.z * rho.cos(),
        );
        assert!(
            rotated
                .radiance(moved.as_vec3())
                .abs_diff_eq(map.pixel(3, 1), 1e-4)
        );
        assert!(rotated.direction(3, 1).abs_diff_eq(moved, 1e-12));
    }

    #[test]
    fn integral_of_a_constant_map_is_four_pi_times_it() {
        let map = EnvMap::new(64, 32, vec![Vec3::new(1.0, 2.0, 0.5); 64 * 32]);
        let expected = DVec3::new(1.0, 2.0, 0.5) * 4.0 * PI;
        assert!((map.integral() - expected).abs().max_element() < 1e-9);
    }
}
