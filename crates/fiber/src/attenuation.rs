//! The attenuation A(p, h) of a smooth fiber: the fraction of the power entering at offset h
//! that leaves after p internal segments, with the exact Fresnel factor at the 3D incidence
//! angle and Beer–Lambert absorption along the refracted chord (d'Eon et al. 2011).

use crate::bravais::{cos_theta_t, eta_prime, gamma_t, segment_transmittance};
use crate::fresnel::fresnel_dielectric;
use crate::lobe::LobeValues;
use glam::DVec3;

/// A(p, h) for p = 0…3 and the sum over p ≥ 4, for light inclined at `theta_i`.
///
/// With f the Fresnel reflectance at the 3D incidence cosine cos θ_i cos γ_i (the same inside,
/// by reciprocity) and T the per-segment transmittance,
/// A₀ = f, A_p = (1 − f)² f^{p−1} T^p, and Σ_{p≥4} A_p = (1 − f)² f³ T⁴ / (1 − f T), so that a
/// fiber with μ_a = 0 sums to exactly 1.
pub fn attenuation(theta_i: f64, h: f64, eta: f64, mu_a: DVec3) -> LobeValues {
    let h = h.clamp(-1.0, 1.0);
    let cos_gamma_i = (1.0 - h * h).max(0.0).sqrt();
    let f = fresnel_dielectric(theta_i.cos() * cos_gamma_i, eta);
    let gt = gamma_t(h, eta_prime(eta, theta_i));
    let ct = cos_theta_t(eta, theta_i);
    let t = DVec3::new(
        segment_transmittance(mu_a.x, gt, ct),
        segment_transmittance(mu_a.y, gt, ct),
        segment_transmittance(mu_a.z, gt, ct),
    );
    let k = (1.0 - f) * (1.0 - f);
    let a1 = k * t;
    let a2 = a1 * f * t;
    let a3 = a2 * f * t;
    let rest = a3 * f * t / (DVec3::ONE - f * t).max(DVec3::splat(1e-300));
    LobeValues([DVec3::splat(f), a1, a2, a3, rest])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lossless_fiber_conserves_energy_for_every_offset_and_inclination() {
        for &theta in &[0.0, 0.5, 1.2, 1.55] {
            for &h in &[-1.0, -0.7, 0.0, 0.3, 0.999] {
                let total = attenuation(theta, h, 1.55, DVec3::ZERO).total();
                assert!(
                    (total - DVec3::ONE).abs().max_element() < 1e-12,
                    "θ {theta} h {h}: {total}"
                );
            }
        }
    }

    #[test]
    fn absorption_darkens_each_mode_by_its_segment_count() {
        let clear = attenuation(0.3, 0.2, 1.55, DVec3::ZERO);
        let dark = attenuation(0.3, 0.2, 1.55, DVec3::splat(0.5));
        let t = dark.0[1].x / clear.0[1].x;
        assert!((dark.0[0].x - clear.0[0].x).abs() < 1e-15);
        assert!((dark.0[2].x / clear.0[2].x - t * t).abs() < 1e-12);
        assert!((dark.0[3].x / clear.0[3].x - t * t * t).abs() < 1e-12);
    }
}
