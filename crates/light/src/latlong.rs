//! Lat-long geometry (docs/conventions.md §4, +y up): directions ↔ (θ, φ) ↔ continuous pixel
//! coordinates, and the solid angle of a pixel.

use glam::DVec3;
use std::f64::consts::PI;

/// ω = (cos θ cos φ, sin θ, cos θ sin φ) for elevation θ and azimuth φ (+y up, φ = 0 along +x).
pub fn direction_from_angles(theta: f64, phi: f64) -> DVec3 {
    let (sin_t, cos_t) = theta.sin_cos();
    let (sin_p, cos_p) = phi.sin_cos();
    DVec3::new(cos_t * cos_p, sin_t, cos_t * sin_p)
}

/// (θ, φ) of a unit direction: θ = asin y ∈ [−π/2, π/2], φ = atan2(z, x) ∈ (−π, π].
pub fn direction_to_angles(dir: DVec3) -> (f64, f64) {
    (dir.y.clamp(-1.0, 1.0).asin(), dir.z.atan2(dir.x))
}

/// θ at the top edge of row `row` of a map `height` rows tall.
pub fn theta_top(row: usize, height: usize) -> f64 {
    PI / 2.0 - PI * row as f64 / height as f64
}

/// θ at the centre of row `row`.
pub fn theta_center(row: usize, height: usize) -> f64 {
    PI / 2.0 - PI * (row as f64 + 0.5) / height as f64
}

/// φ at the centre of column `column` of a map `width` columns wide.
pub fn phi_center(column: usize, width: usize) -> f64 {
    -PI + 2.0 * PI * (column as f64 + 0.5) / width as f64
}

/// Solid angle of a pixel of row `row`: Δφ · (sin θ_top − sin θ_bottom), Δφ = 2π/W
/// (docs/conventions.md §4).
pub fn pixel_solid_angle(row: usize, width: usize, height: usize) -> f64 {
    let d_phi = 2.0 * PI / width as f64;
    d_phi * (theta_top(row, height).sin() - theta_top(row + 1, height).sin())
}

/// Continuous pixel coordinates (x, y) of angles (θ, φ): pixel (j, k) has its centre at
/// (j + 0.5, k + 0.5); x ∈ [0, W) wraps, y ∈ [0, H].
pub fn pixel_coords(theta: f64, phi: f64, width: usize, height: usize) -> (f64, f64) {
    let x = (phi + PI) / (2.0 * PI) * width as f64;
    let y = (PI / 2.0 - theta) / PI * height as f64;
    (x.rem_euclid(width as f64), y)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn angles_round_trip_and_axes() {
        for &(t, p) in &[(0.3, -2.0), (-1.2, 0.4), (0.0, 3.0), (1.5, -0.1)] {
            let d = direction_from_angles(t, p);
            assert!((d.length() - 1.0).abs() < 1e-12);
            let (t2, p2) = direction_to_angles(d);
            assert!((t - t2).abs() < 1e-12 && (p - p2).abs() < 1e-12);
        }
        assert!(direction_from_angles(0.0, 0.0).abs_diff_eq(DVec3::X, 1e-12));
        assert!(direction_from_angles(0.0, PI / 2.0).abs_diff_eq(DVec3::Z, 1e-12));
        assert!(direction_from_angles(PI / 2.0, 0.7).abs_diff_eq(DVec3::Y, 1e-12));
    }

    #[test]
    fn pixel_solid_angles_sum_to_four_pi() {
        for &(w, h) in &[(8, 4), (400, 100), (1024, 512)] {
            let total: f64 = (0..h).map(|k| pixel_solid_angle(k, w, h) * w as f64).sum();
            assert!((total - 4.0 * PI).abs() < 1e-9, "{w}x{h}: {total}");
        }
    }

    #[test]
    fn pixel_centres_map_to_their_own_coordinates() {
        let (w, h) = (16, 8);
        for k in 0..h {
            for j in 0..w {
                let (x, y) = pixel_coords(theta_center(k, h), phi_center(j, w), w, h);
                assert!((x - (j as f64 + 0.5)).abs() < 1e-9);
                assert!((y - (k as f64 + 0.5)).abs() < 1e-9);
            }
        }
    }
}
