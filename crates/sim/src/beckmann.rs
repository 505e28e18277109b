//! The Beckmann microfacet distribution and its Smith shadowing-masking term (Walter et al. 2007,
//! "Microfacet models for refraction through rough surfaces", §5.1), with roughness β.

use cuticle_fiber::special::erfc_rel_1_2e7;
use cuticle_fiber::special::ln_fast;
use glam::{DVec2, DVec3};
use std::f64::consts::PI;

/// D(m) = exp(−tan²θ_m/β²) / (π β² cos⁴θ_m) for cos θ_m = m·n > 0 (Walter 2007 eq. 25).
pub fn distribution(cos_m: f64, beta: f64) -> f64 {
    if cos_m <= 0.0 {
        return 0.0;
    }
    let c2 = cos_m * cos_m;
    let tan2 = (1.0 - c2) / c2;
    (-tan2 / (beta * beta)).exp() / (PI * beta * beta * c2 * c2)
}

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

/// Smith's Λ for Beckmann, Λ(a) = (exp(−a²)/(a√π) − erfc(a)) / 2 with a = 1/(β tan θ_v), so that
/// G1 = 1/(1 + Λ) = 2 / (1 + erf(a) + exp(−a²)/(a√π)) is Walter 2007 eq. 27 (the exact erf form,
/// not the rational approximation). Λ < 10⁻¹⁵ once a > 6, where it is taken as 0.
fn smith_lambda(a: f64) -> f64 {
    if a > 6.0 {
        return 0.0;
    }
    0.5 * ((-a * a).exp() / (a * PI.sqrt()) - erfc_rel_1_2e7(a))
}

/// Smith G1(v, m) for Beckmann (Walter 2007 eq. 27), given cos θ_v = v·n and v·m. Zero when v
/// sees m from the other side than n (the χ⁺ factor); exactly 1 where a > 6 (Λ < 10⁻¹⁵), which
/// is tested as cos²θ_v > 36 β² sin²θ_v without a root or a division.
pub fn smith_g1(cos_v: f64, v_dot_m: f64, beta: f64) -> f64 {
    if v_dot_m * cos_v <= 0.0 {
        return 0.0;
    }
    let c2 = (cos_v * cos_v).min(1.0);
    let s2 = 1.0 - c2;
    if c2 > 36.0 * beta * beta * s2 {
        return 1.0;
    }
    1.0 / (1.0 + smith_lambda(c2.sqrt() / (beta * s2.sqrt())))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::TAU;

    /// ∫ D(m) (m·n) dω_m = 1 (Walter 2007 eq. 4), by quadrature over θ_m.
    #[test]
    fn distribution_projects_to_unit_area() {
        for beta in [0.05, 0.3, 0.8] {
            let n = 200_000;
            let d_theta = (PI / 2.0) / n as f64;
            let area: f64 = (0..n)
                .map(|k| {
                    let t = (k as f64 + 0.5) * d_theta;
                    distribution(t.cos(), beta) * t.cos() * t.sin() * TAU * d_theta
                })
                .sum();
            assert!((area - 1.0).abs() < 1e-6, "β = {beta}: ∫D cos = {area}");
        }
    }

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

    /// The Smith identity ∫ G1(v,m) max(0, v·m) D(m) dω_m = v·n (Walter 2007 §5, Heitz 2014
    /// eq. 18), which holds only for the right Λ.
    #[test]
    fn smith_g1_normalises_the_projected_area() {
        for (beta, theta_v) in [(0.3, 1.2), (0.1, 1.4), (0.5, 0.7)] {
            let v = DVec3::new(f64::sin(theta_v), 0.0, f64::cos(theta_v));
            let (nt, np) = (800, 800);
            let mut sum = 0.0;
            for i in 0..nt {
                let t = (i as f64 + 0.5) * (PI / 2.0) / nt as f64;
                for j in 0..np {
                    let p = (j as f64 + 0.5) * TAU / np as f64;
                    let m = DVec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos());
                    let vm = v.dot(m).max(0.0);
                    sum += vm
                        * distribution(m.z, beta)
                        * t.sin()
                        * (PI / 2.0 / nt as f64)
                        * (TAU / np as f64);
                }
            }
            let projected = smith_g1(v.z, 1.0, beta) * sum;
            assert!(
                (projected - v.z).abs() < 2e-3 * v.z,
                "β {beta} θ {theta_v}: {projected} vs {}",
                v.z
            );
        }
    }
}
