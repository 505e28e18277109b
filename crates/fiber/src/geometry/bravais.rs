//! Geometry of a smooth circular fiber in the Bravais picture: the projected indices η′ and η″,
//! the refracted offsets, the azimuthal deflection Φ(p, h) and the internal path length.

use crate::math::{asin_fast, asin_pair, exp_fast, sin_cos_quadrant};
use std::f64::consts::PI;
use wide::f64x2;

/// Bravais' index for the normal-plane projection, η′ = √(η² − sin²θ) / cos θ (Marschner et al.
/// 2003).
pub fn eta_prime(eta: f64, theta: f64) -> f64 {
    let (s, c) = sin_cos_quadrant(theta);
    (eta * eta - s * s).max(0.0).sqrt() / c.abs().max(1e-12)
}

/// The second Bravais index for the parallel polarisation, η″ = η² cos θ / √(η² − sin²θ).
pub fn eta_double_prime(eta: f64, theta: f64) -> f64 {
    let (s, c) = sin_cos_quadrant(theta);
    eta * eta * c.abs() / (eta * eta - s * s).max(1e-300).sqrt()
}

/// γ_t = asin(h / η′), the refracted azimuthal angle inside the fiber.
pub fn gamma_t(h: f64, eta_prime: f64) -> f64 {
    asin_fast((h / eta_prime).clamp(-1.0, 1.0))
}

/// Φ(p, h) = 2pγ_t − 2γ_i + pπ (d'Eon et al. 2014 eq. 3), unwrapped; γ_i and γ_t from one
/// two-lane arcsine ([`asin_pair`], [`gamma_t`]'s and asin h's values).
pub fn azimuthal_deflection(p: u32, h: f64, eta_prime: f64) -> f64 {
    let p = p as f64;
    let h = h.clamp(-1.0, 1.0);
    let sines = f64x2::new([h, (h / eta_prime).clamp(-1.0, 1.0)]);
    let [gamma_i, gamma_t] = asin_pair(sines).to_array();
    2.0 * p * gamma_t - 2.0 * gamma_i + p * PI
}

/// cos θ_t of the refracted inclination, sin θ_t = sin θ / η.
pub fn cos_theta_t(eta: f64, theta: f64) -> f64 {
    let s = theta.sin() / eta;
    (1.0 - s * s).max(0.0).sqrt()
}

/// Transmittance of one internal segment: exp(−2 μ_a cos γ_t / cos θ_t), the chord of a unit
/// circle at refracted offset γ_t, stretched by the inclination (docs/conventions.md §8 erratum).
pub fn segment_transmittance(mu_a: f64, gamma_t: f64, cos_theta_t: f64) -> f64 {
    chord_transmittance(mu_a, gamma_t.cos(), cos_theta_t)
}

/// [`segment_transmittance`] from cos γ_t, for a caller that has it without the angle.
#[inline]
pub fn chord_transmittance(mu_a: f64, cos_gamma_t: f64, cos_theta_t: f64) -> f64 {
    exp_fast(-2.0 * mu_a * cos_gamma_t / cos_theta_t.max(1e-12))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn indices_reduce_to_eta_at_normal_incidence_and_grow_with_inclination() {
        assert_eq!(eta_prime(1.55, 0.0), 1.55);
        assert!((eta_double_prime(1.55, 0.0) - 1.55).abs() < 1e-15);
        assert!(eta_prime(1.55, 1.0) > 1.55 && eta_double_prime(1.55, 1.0) < 1.55);
        // η′ η″ = η² (Marschner et al. 2003's two indices are reciprocal through η²).
        assert!(
            (eta_prime(1.55, 0.7) * eta_double_prime(1.55, 0.7) - 1.55f64.powi(2)).abs() < 1e-12
        );
    }

    #[test]
    fn deflection_of_the_reflection_and_the_central_transmission() {
        assert!((azimuthal_deflection(0, 0.5, 1.55) + 2.0 * 0.5f64.asin()).abs() < 1e-15);
        assert!((azimuthal_deflection(1, 0.0, 1.55) - PI).abs() < 1e-15);
        // Antisymmetric in h about pπ.
        let a = azimuthal_deflection(2, 0.3, 1.7) - 2.0 * PI;
        let b = azimuthal_deflection(2, -0.3, 1.7) - 2.0 * PI;
        assert!((a + b).abs() < 1e-14);
    }
}
