//! The unit-radius infinite cylinder along u = +x (the canonical fiber frame of
//! `cuticle_fiber::FiberFrame::CANONICAL`). Paths are translation-invariant along the axis, so a
//! point on the surface is kept as its (y, z) position on the unit circle.

use glam::{DVec2, DVec3};

/// The direction rays travel for incident inclination θ_i and φ_i = 0: −ω_i, where
/// ω_i = (sin θ_i, cos θ_i, 0) points toward the light (docs/conventions.md §2).
pub fn incident_ray(theta_i: f64) -> DVec3 {
    let (s, c) = theta_i.sin_cos();
    DVec3::new(-s, -c, 0.0)
}

/// Where the ray at offset h ∈ [−1, 1] first meets the surface: (y, z) = (√(1 − h²), −h), i.e.
/// at azimuth −γ_i with γ_i = asin h, so that the mirror direction has φ = −2γ_i, the sign of
/// Bravais' Φ(0, h) (d'Eon et al. 2014 eq. 3).
pub fn entry_point(h: f64) -> DVec2 {
    DVec2::new((1.0 - h * h).max(0.0).sqrt(), -h)
}

/// The outward macro normal at a surface point.
pub fn macro_normal(p: DVec2) -> DVec3 {
    DVec3::new(0.0, p.x, p.y)
}

/// The 3D length travelled inside from surface point p along unit direction d (pointing inward)
/// to the far side: the root t > 0 of |p + t d_yz|² = 1, t = −2 (p·d_yz)/|d_yz|². At offset h
/// this is the chord 2 cos γ_t / cos θ_t of docs/conventions.md §8.
pub fn chord(p: DVec2, d: DVec3) -> f64 {
    let dyz = DVec2::new(d.y, d.z);
    -2.0 * p.dot(dyz) / dyz.length_squared()
}

/// The surface point reached from p after travelling `t` along d, pulled back onto the unit
/// circle by one Newton step of 1/√r² (q (3 − |q|²)/2), which removes the rounding drift of many
/// bounces without a root or a division.
pub fn advance(p: DVec2, d: DVec3, t: f64) -> DVec2 {
    let q = p + t * DVec2::new(d.y, d.z);
    q * (1.5 - 0.5 * q.length_squared())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chord_matches_the_bravais_length() {
        let (theta_i, eta, h) = (0.6_f64, 1.55_f64, 0.4_f64);
        // Refract the entry ray exactly at the macro normal and compare with docs/conventions.md
        // §8.
        let p = entry_point(h);
        let n = macro_normal(p);
        let i = -incident_ray(theta_i);
        let c = i.dot(n);
        let f = crate::dielectric::fresnel(c, eta);
        let t = crate::dielectric::refract(i, n, c, f.g, 1.0 / eta);
        let sin_theta_t = theta_i.sin() / eta;
        let cos_theta_t = (1.0 - sin_theta_t * sin_theta_t).sqrt();
        let eta_p = (eta * eta - theta_i.sin().powi(2)).sqrt() / theta_i.cos();
        let gamma_t = (h / eta_p).asin();
        let want = 2.0 * gamma_t.cos() / cos_theta_t;
        assert!((chord(p, t) - want).abs() < 1e-12);
        let q = advance(p, t, chord(p, t));
        assert!((q.length() - 1.0).abs() < 1e-15);
        assert!((advance(p * 1.001, t, 0.0).length() - 1.0).abs() < 1e-5);
        assert!(
            (t.x - (-sin_theta_t)).abs() < 1e-12,
            "the axial component is Snell's"
        );
    }
}
