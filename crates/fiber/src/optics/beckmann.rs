//! The Beckmann microfacet distribution and its Smith shadowing-masking term (Walter et al. 2007,
//! "Microfacet models for refraction through rough surfaces", §5.1), with roughness β: the
//! rough dielectric that `cuticle-sim` traces and [`crate::optics::rough_interface`] averages over.

use crate::math::erfc_rel_1_2e7;
use std::f64::consts::PI;

/// D(m) = exp(−tan²θ_m/β²) / (π β² cos⁴θ_m) for cos θ_m = m·n > 0 (Walter 2007 eq. 25).
#[inline]
pub fn distribution(cos_m: f64, beta: f64) -> f64 {
    if cos_m <= 0.0 {
        return 0.0;
    }
    let c2 = cos_m * cos_m;
    let tan2 = (1.0 - c2) / c2;
    (-tan2 / (beta * beta)).exp() / (PI * beta * beta * c2 * c2)
}

/// Smith's Λ for Beckmann, Λ(a) = (exp(−a²)/(a√π) − erfc(a)) / 2 with a = 1/(β tan θ_v), so that
/// G1 = 1/(1 + Λ) = 2 / (1 + erf(a) + exp(−a²)/(a√π)) is Walter 2007 eq. 27 (the exact erf form,
/// not the rational approximation). Λ < 10⁻¹⁵ once a > 6, where it is taken as 0.
#[inline]
fn smith_lambda(a: f64) -> f64 {
    if a > 6.0 {
        return 0.0;
    }
    0.5 * ((-a * a).exp() / (a * PI.sqrt()) - erfc_rel_1_2e7(a))
}

/// Smith G1(v, m) for Beckmann (Walter 2007 eq. 27), given cos θ_v = v·n and v·m. Zero when v
/// sees m from the other side than n (the χ⁺ factor); exactly 1 where a > 6 (Λ < 10⁻¹⁵), which
/// is tested as cos²θ_v > 36 β² sin²θ_v without a root or a division.
#[inline]
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
    use glam::DVec3;
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
