//! The attenuation A(p, h) of a smooth fiber: the fraction of the power entering at offset h
//! that leaves after p internal segments, with the exact Fresnel factor at the 3D incidence
//! angle and Beer–Lambert absorption along the refracted chord (d'Eon et al. 2011).

use crate::lobe::LobeValues;
use crate::math::{exp_lanes_f32, sin_cos_quadrant};
use crate::optics::fresnel::fresnel_dielectric;
use glam::DVec3;
use wide::f64x4;

/// A(p, h) for p = 0…3 and the sum over p ≥ 4, for light inclined at `theta_i`.
///
/// With f the Fresnel reflectance at the 3D incidence cosine cos θ_i cos γ_i (the same inside,
/// by reciprocity) and T the per-segment transmittance,
/// A₀ = f, A_p = (1 − f)² f^{p−1} T^p, and Σ_{p≥4} A_p = (1 − f)² f³ T⁴ / (1 − f T), so that a
/// fiber with μ_a = 0 sums to exactly 1.
pub fn attenuation(theta_i: f64, h: f64, eta: f64, mu_a: DVec3) -> LobeValues {
    attenuation_at(Inclination::new(theta_i, eta), h, mu_a)
}

/// What A(p, h) needs of θ_i, found once per incident direction: cos θ_i, and the
/// squared ratio (cos θ_i / √(η² − sin²θ_i))² = 1/η′² and 1/cos θ_t of the refracted ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Inclination {
    pub eta: f64,
    pub cos_theta: f64,
    /// 1/η′², η′ = √(η² − sin²θ) / cos θ (Marschner et al. 2003).
    pub inv_eta_prime_sq: f64,
    /// 1/η′, for sin γ_t = h/η′.
    pub inv_eta_prime: f64,
    /// 1/cos θ_t, sin θ_t = sin θ / η.
    pub inv_cos_theta_t: f64,
}

impl Inclination {
    pub fn new(theta: f64, eta: f64) -> Self {
        let (s, c) = sin_cos_quadrant(theta);
        Self::from_sin_cos(s, c, eta)
    }

    /// The same from sin θ and cos θ (cos θ ≥ 0).
    #[inline]
    pub fn from_sin_cos(sin_theta: f64, cos_theta: f64, eta: f64) -> Self {
        // g = η² − sin²θ = η² cos²θ_t: 1/η′² = cos²θ / g, 1/η′ = cos θ / √g and
        // 1/cos θ_t = η / √g, one division and one root for the three; the root of g runs
        // beside the division rather than after it.
        let g = eta * eta - sin_theta * sin_theta;
        if g <= 0.0 {
            return Self {
                eta,
                cos_theta: cos_theta.abs(),
                inv_eta_prime_sq: 1.0,
                inv_eta_prime: 1.0,
                inv_cos_theta_t: 1e12,
            };
        }
        let inv_g = 1.0 / g;
        let inv_root_g = g.sqrt() * inv_g;
        let c = cos_theta.abs().max(1e-12);
        Self {
            eta,
            cos_theta: cos_theta.abs(),
            inv_eta_prime_sq: c * c * inv_g,
            inv_eta_prime: c * inv_root_g,
            inv_cos_theta_t: (eta * inv_root_g).min(1e12),
        }
    }

    /// The chord length factor 2 cos γ_t / cos θ_t at offset h (cos γ_t = √(1 − h²/η′²)),
    /// so that a segment transmits exp(−μ_a ·) of it.
    #[inline]
    pub fn chord(&self, h: f64) -> f64 {
        self.chord_from_h_sq(h * h)
    }

    /// [`Inclination::chord`] from h² (h² ≤ 1), for a caller that has h² and not h.
    #[inline]
    pub fn chord_from_h_sq(&self, h_sq: f64) -> f64 {
        let cos_gamma_t = (1.0 - h_sq * self.inv_eta_prime_sq).max(0.0).sqrt();
        2.0 * cos_gamma_t * self.inv_cos_theta_t
    }

    /// The Fresnel factor at offset h: the 3D incidence cosine cos θ cos γ_i.
    #[inline]
    pub fn fresnel(&self, h: f64) -> f64 {
        let cos_gamma_i = (1.0 - h * h).max(0.0).sqrt();
        fresnel_dielectric(self.cos_theta * cos_gamma_i, self.eta)
    }
}

/// A(p, h) as [`attenuation`] gives it, for an inclination prepared once: one Fresnel factor,
/// one chord, the three channels' transmittance in SIMD lanes ([`transmittance`]).
#[inline]
pub fn attenuation_at(inc: Inclination, h: f64, mu_a: DVec3) -> LobeValues {
    let h = h.clamp(-1.0, 1.0);
    let f = inc.fresnel(h);
    let t = transmittance(mu_a, inc.chord(h));
    let (fv, k) = (f64x4::splat(f), f64x4::splat((1.0 - f) * (1.0 - f)));
    let ft = fv * t;
    let a1 = k * t;
    let a2 = a1 * ft;
    let a3 = a2 * ft;
    let rest = a3 * ft / (f64x4::ONE - ft).fast_max(f64x4::splat(1e-300));
    let rgb = |x: f64x4| {
        let [r, g, b, _] = x.to_array();
        DVec3::new(r, g, b)
    };
    LobeValues([DVec3::splat(f), rgb(a1), rgb(a2), rgb(a3), rgb(rest)])
}

/// The transmittance e^{−μ_a ℓ} of a chord of length ℓ per channel, in the first three of four
/// SIMD lanes (the fourth is 1): one [`exp_lanes_f32`] for the three exponentials, within 3e-7
/// relative of the exact one (`transmittance_matches_the_exponential`), and exactly 1 where
/// μ_a ℓ = 0, so a lossless fiber still conserves energy to rounding.
#[inline(always)]
pub fn transmittance(mu_a: DVec3, chord: f64) -> f64x4 {
    exp_lanes_f32(f64x4::new([-mu_a.x, -mu_a.y, -mu_a.z, 0.0]) * f64x4::splat(chord))
}

/// The channel mean of Σ_p A_p = f + (1 − f)² T / (1 − f T) (the geometric series of
/// [`attenuation`]), without the lobes: what the lobe-selection probability of R divides by.
#[inline]
pub fn mean_total_attenuation(inc: Inclination, h: f64, mu_a: DVec3) -> (f64, f64) {
    let h = h.clamp(-1.0, 1.0);
    let f = inc.fresnel(h);
    (f, mean_total_attenuation_at_h_sq(inc, f, h * h, mu_a))
}

/// The total of [`mean_total_attenuation`] for a Fresnel factor f the caller already has,
/// from h² ∈ [0, 1] (R's root in d'Eon 2011 gives h² = 1 − cos²(φ/2) without a square root):
/// the three channels' (1 − f)² T / (1 − f T) in SIMD lanes, one division for all three.
#[inline]
pub fn mean_total_attenuation_at_h_sq(inc: Inclination, f: f64, h_sq: f64, mu_a: DVec3) -> f64 {
    let t = transmittance(mu_a, inc.chord_from_h_sq(h_sq));
    let k = (1.0 - f) * (1.0 - f);
    let denominator = (f64x4::ONE - f64x4::splat(f) * t).fast_max(f64x4::splat(1e-300));
    let [x, y, z, _] = (t / denominator).to_array();
    f + k * (x + y + z) / 3.0
}

/// R's lobe-selection probability f / mean_c(Σ_p A_p) for a Fresnel factor f the caller
/// already has, from h²: the quotient of f by [`mean_total_attenuation_at_h_sq`] over one
/// common denominator. With D_c = 1 − f T_c, Σ_c T_c / D_c = Q / P for P = D_r D_g D_b and
/// Q = T_r D_g D_b + T_g D_r D_b + T_b D_r D_g, so f / (f + k Q / 3P) = 3fP / (3fP + kQ),
/// k = (1 − f)²: one division where the mean and the quotient took one after the other
/// (`r_selection_is_f_over_the_mean_total`). Where no light leaves (the denominator
/// vanishes: a lossless fiber at grazing incidence, f T = 1, or an opaque one at f = 0) it is
/// the quotient of the mean itself.
#[inline]
pub fn r_selection_at_h_sq(inc: Inclination, f: f64, h_sq: f64, mu_a: DVec3) -> f64 {
    let t = transmittance(mu_a, inc.chord_from_h_sq(h_sq));
    let [tr, tg, tb, _] = t.to_array();
    let [dr, dg, db, _] = (f64x4::ONE - f64x4::splat(f) * t).to_array();
    let k = (1.0 - f) * (1.0 - f);
    let fp = 3.0 * f * (dr * dg * db);
    let denominator = fp + k * (tr * (dg * db) + tg * (dr * db) + tb * (dr * dg));
    if denominator > 1e-300 {
        return fp / denominator;
    }
    let total = mean_total_attenuation_at_h_sq(inc, f, h_sq, mu_a);
    if total > 0.0 { f / total } else { 0.0 }
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

    #[test]
    fn transmittance_matches_the_exponential() {
        let mut worst: f64 = 0.0;
        for &mu in &[0.0, 1e-3, 0.05, 0.43, 1.9, 12.0, 80.0] {
            let mu_a = DVec3::new(mu, 0.5 * mu, 3.0 * mu);
            for k in 0..=400 {
                let chord = 4.0 * k as f64 / 400.0;
                let got = transmittance(mu_a, chord).to_array();
                for (g, m) in got.into_iter().zip(mu_a.to_array()) {
                    let want = (-m * chord).exp();
                    if want > 1e-300 {
                        worst = worst.max((g / want - 1.0).abs());
                    }
                }
                assert_eq!(got[3], 1.0);
            }
        }
        eprintln!("transmittance in lanes vs exp: relative error ≤ {worst:.2e}");
        assert!(worst < 3e-7, "{worst:e}");
    }

    /// The prepared inclination reproduces the Bravais geometry (η′, γ_t, θ_t of
    /// [`crate::geometry::bravais`]) and the closed-form total matches the lobes' sum.
    #[test]
    fn prepared_inclination_matches_the_bravais_geometry() {
        use crate::geometry::bravais::{cos_theta_t, eta_prime, gamma_t, segment_transmittance};
        let mu = DVec3::new(0.2, 0.7, 1.9);
        for &theta in &[-1.5, -0.6, 0.0, 0.4, 1.3] {
            let inc = Inclination::new(theta, 1.55);
            let ep = eta_prime(1.55, theta);
            assert!((inc.inv_eta_prime * ep - 1.0).abs() < 1e-14, "{theta}");
            assert!(
                (inc.inv_eta_prime_sq * ep * ep - 1.0).abs() < 1e-14,
                "{theta}"
            );
            for &h in &[-0.99, -0.3, 0.0, 0.5, 1.0] {
                let gt = gamma_t(h, eta_prime(1.55, theta));
                let ct = cos_theta_t(1.55, theta);
                let t = segment_transmittance(0.7, gt, ct);
                assert!(
                    (t - (-0.7 * inc.chord(h)).exp()).abs() < 1e-13,
                    "{theta} {h}"
                );
                let a = attenuation_at(inc, h, mu);
                let (f, total) = mean_total_attenuation(inc, h, mu);
                assert_eq!(f, a.0[0].x);
                let want = crate::lobe::channel_mean(a.total());
                assert!((total - want).abs() < 1e-14 * want, "{total} {want}");
            }
        }
    }

    /// R's selection over one common denominator is f over the mean total, at every
    /// inclination and offset, absorbing or not, and at the limits where no light leaves.
    #[test]
    fn r_selection_is_f_over_the_mean_total() {
        for mu in [DVec3::ZERO, DVec3::new(0.2, 0.5, 1.3), DVec3::splat(40.0)] {
            for theta in [-1.5, -0.6, 0.0, 0.4, 1.3, 1.57] {
                let inc = Inclination::new(theta, 1.55);
                for h in [-1.0, -0.99, -0.3, 0.0, 0.5, 0.999, 1.0] {
                    let (f, total) = mean_total_attenuation(inc, h, mu);
                    let got = r_selection_at_h_sq(inc, f, h * h, mu);
                    let want = f / total;
                    assert!(
                        (got - want).abs() <= 2e-15 * want,
                        "{mu} {theta} {h}: {got} {want}"
                    );
                }
            }
        }
        // Every channel reflects all it transmits: nothing but R leaves.
        let inc = Inclination::new(0.3, 1.55);
        assert_eq!(r_selection_at_h_sq(inc, 1.0, 1.0, DVec3::ZERO), 1.0);
        // Nothing reflects and nothing is transmitted: R is never chosen.
        assert_eq!(r_selection_at_h_sq(inc, 0.0, 0.0, DVec3::splat(1e6)), 0.0);
    }
}
