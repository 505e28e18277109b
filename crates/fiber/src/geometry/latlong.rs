//! The lat-long grid every lobe image uses (docs/conventions.md §4): `width` columns over φ ∈ [−π,
//! π), `height` rows over θ from +π/2 (row 0) down to −π/2; pixel values are S in sr⁻¹.

use glam::DVec3;
use std::f64::consts::PI;

/// Geometry of a lat-long image: which pixel a direction falls in, and each pixel's solid angle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LatLongGrid {
    pub width: usize,
    pub height: usize,
}

impl Default for LatLongGrid {
    fn default() -> Self {
        Self {
            width: 400,
            height: 100,
        }
    }
}

impl LatLongGrid {
    pub const fn new(width: usize, height: usize) -> Self {
        Self { width, height }
    }

    pub fn len(&self) -> usize {
        self.width * self.height
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    pub fn d_phi(&self) -> f64 {
        2.0 * PI / self.width as f64
    }

    /// θ of the top edge of row `k`.
    pub fn theta_top(&self, k: usize) -> f64 {
        PI / 2.0 - PI * k as f64 / self.height as f64
    }

    /// θ at the centre of row `k`.
    pub fn theta_center(&self, k: usize) -> f64 {
        PI / 2.0 - PI * (k as f64 + 0.5) / self.height as f64
    }

    /// φ at the centre of column `j`.
    pub fn phi_center(&self, j: usize) -> f64 {
        -PI + self.d_phi() * (j as f64 + 0.5)
    }

    /// Solid angle of any pixel of row `k`: Δφ · (sin θ_top − sin θ_bottom).
    pub fn pixel_solid_angle(&self, k: usize) -> f64 {
        self.d_phi() * (self.theta_top(k).sin() - self.theta_top(k + 1).sin())
    }

    /// The pixel (column, row) holding the direction with angles (θ, φ).
    pub fn pixel_of(&self, theta: f64, phi: f64) -> (usize, usize) {
        let j = ((phi + PI) / self.d_phi()).floor() as i64;
        let k = ((PI / 2.0 - theta) / PI * self.height as f64).floor() as i64;
        let j = j.rem_euclid(self.width as i64) as usize;
        let k = k.clamp(0, self.height as i64 - 1) as usize;
        (j, k)
    }

    /// Flat index (row-major, row 0 first) of the pixel holding (θ, φ).
    pub fn index_of(&self, theta: f64, phi: f64) -> usize {
        let (j, k) = self.pixel_of(theta, phi);
        k * self.width + j
    }
}

/// A lat-long image of RGB values, row-major from the top row.
#[derive(Clone, Debug, PartialEq)]
pub struct LatLongImage {
    pub grid: LatLongGrid,
    pub pixels: Vec<DVec3>,
}

impl LatLongImage {
    pub fn zeros(grid: LatLongGrid) -> Self {
        Self {
            grid,
            pixels: vec![DVec3::ZERO; grid.len()],
        }
    }

    pub fn at(&self, j: usize, k: usize) -> DVec3 {
        self.pixels[k * self.grid.width + j]
    }

    /// ∫ S dω over the sphere (the lobe's energy), RGB.
    pub fn energy(&self) -> DVec3 {
        (0..self.grid.height)
            .map(|k| {
                let row = &self.pixels[k * self.grid.width..(k + 1) * self.grid.width];
                row.iter().copied().sum::<DVec3>() * self.grid.pixel_solid_angle(k)
            })
            .sum()
    }

    /// The density in φ per column, ∫ S cos θ dθ (docs/conventions.md §5 `azimuthal.csv`), RGB.
    pub fn azimuthal(&self) -> Vec<DVec3> {
        let g = self.grid;
        (0..g.width)
            .map(|j| {
                (0..g.height)
                    .map(|k| self.at(j, k) * g.pixel_solid_angle(k) / g.d_phi())
                    .sum()
            })
            .collect()
    }

    /// Adds `other` pixel by pixel.
    pub fn add(&mut self, other: &LatLongImage) {
        for (a, b) in self.pixels.iter_mut().zip(&other.pixels) {
            *a += *b;
        }
    }

    /// Multiplies every pixel by `s`.
    pub fn scale(&mut self, s: f64) {
        self.pixels.iter_mut().for_each(|p| *p *= s);
    }
}

/// The five lobe images (R, TT, TRT, TRRT, rest) from rows of per-pixel lobe values, row 0
/// (θ near +π/2) first, as a parallel evaluation over rows produces them.
pub fn lobe_images(grid: LatLongGrid, rows: &[Vec<[DVec3; 5]>]) -> [LatLongImage; 5] {
    std::array::from_fn(|p| LatLongImage {
        grid,
        pixels: rows
            .iter()
            .flat_map(|row| row.iter().map(move |v| v[p]))
            .collect(),
    })
}

/// A direction's pixel index: convenience for accumulating in the canonical frame.
pub fn index_of_dir(grid: &LatLongGrid, d: DVec3) -> usize {
    let a = crate::geometry::frame::FiberAngles::from_dir(d);
    grid.index_of(a.theta, a.phi)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solid_angles_sum_to_the_sphere() {
        let g = LatLongGrid::default();
        let total: f64 = (0..g.height)
            .map(|k| g.pixel_solid_angle(k) * g.width as f64)
            .sum();
        assert!((total - 4.0 * PI).abs() < 1e-9);
    }

    #[test]
    fn pixel_of_inverts_pixel_centres() {
        let g = LatLongGrid::new(40, 10);
        for k in 0..g.height {
            for j in 0..g.width {
                assert_eq!(g.pixel_of(g.theta_center(k), g.phi_center(j)), (j, k));
            }
        }
        assert_eq!(g.pixel_of(PI / 2.0, PI), (0, 0));
        assert_eq!(g.pixel_of(-PI / 2.0, -PI), (0, 9));
    }

    #[test]
    fn constant_image_has_energy_of_its_value_times_four_pi() {
        let mut img = LatLongImage::zeros(LatLongGrid::new(64, 32));
        img.pixels.iter_mut().for_each(|p| *p = DVec3::splat(0.25));
        assert!((img.energy().x - PI).abs() < 1e-9);
        let az: f64 = img.azimuthal().iter().map(|v| v.y).sum::<f64>() * img.grid.d_phi();
        assert!((az - PI).abs() < 1e-9);
    }
}
