//! Sampling the Beckmann microfacet distribution (Walter et al. 2007 §5.1, eqs. 28–29); the
//! distribution and its Smith term are the fiber crate's ([`cuticle_fiber::optics::beckmann`]),
//! which the models' rough interface averages over.

use cuticle_fiber::math::ln_fast;
pub use cuticle_fiber::optics::beckmann::{distribution, smith_g1};
use glam::{DVec2, DVec3};

/// A micro-normal with density D(m)|m·n|, in the local frame where n = +z (Walter 2007
/// eqs. 28–29: tan²θ_m = −β² ln(1 − ξ₁), φ_m uniform). φ_m comes from `disk`, a point uniform in
/// the unit disk: its doubled angle, cos = (x² − y²)/r², sin = 2xy/r², is uniform, with no trig.
pub fn sample_normal(beta: f64, xi1: f64, disk: DVec2) -> DVec3 {
    let tan2 = -beta * beta * ln_fast(1.0 - xi1);
    let r2 = disk.length_squared();
    // One reciprocal serves both cos θ_m = 1/√(1 + tan²) and the azimuth's 1/r².
    let inv = 1.0 / ((1.0 + tan2).sqrt() * r2);
    let cos_m = r2 * inv;
    let scale = tan2.sqrt() * inv;
    DVec3::new(
        (disk.x * disk.x - disk.y * disk.y) * scale,
        2.0 * disk.x * disk.y * scale,
        cos_m,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The sampled tan²θ_m follow D(m)|m·n|: P(tan θ_m < t) = 1 − exp(−t²/β²).
    #[test]
    fn samples_follow_the_projected_distribution() {
        let beta = 0.2;
        let n = 100_000;
        let t = 0.15;
        let inside = (0..n)
            .filter(|&k| {
                let xi1 = (k as f64 + 0.5) / n as f64;
                let m = sample_normal(beta, xi1, DVec2::new(0.3, -0.5));
                assert!((m.length() - 1.0).abs() < 1e-12);
                (m.x * m.x + m.y * m.y).sqrt() / m.z < t
            })
            .count();
        let want = 1.0 - (-t * t / (beta * beta)).exp();
        assert!((inside as f64 / n as f64 - want).abs() < 1e-4);
    }

    /// Disk points at angle ψ give micro-normal azimuth 2ψ, so a uniform disk gives uniform φ_m.
    #[test]
    fn azimuth_is_twice_the_disk_angle() {
        for psi in [0.3f64, 1.2, 2.5, -2.0] {
            let m = sample_normal(0.3, 0.5, DVec2::new(psi.cos(), psi.sin()) * 0.7);
            let phi = m.y.atan2(m.x);
            assert!((cuticle_fiber::wrap_pi(phi - 2.0 * psi)).abs() < 1e-12);
            assert!((m.length() - 1.0).abs() < 1e-12);
        }
    }
}
