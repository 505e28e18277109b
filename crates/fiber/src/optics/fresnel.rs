//! Fresnel reflectance of a smooth dielectric interface.

use crate::math::sin_cos_quadrant;

/// Unpolarised Fresnel reflectance for light arriving at cosine `cos_i` (> 0, measured from the
/// normal on the incident side) onto a medium of relative index `eta` (transmitted / incident).
/// Total internal reflection returns 1.
pub fn fresnel_dielectric(cos_i: f64, eta: f64) -> f64 {
    let cos_i = cos_i.clamp(0.0, 1.0);
    // g = η² cos²θ_t = η² − sin²θ_i; total internal reflection where g ≤ 0.
    let eta2 = eta * eta;
    let g = eta2 - 1.0 + cos_i * cos_i;
    if g <= 0.0 {
        return 1.0;
    }
    // r_s = (cos θ_i − η cos θ_t) / (cos θ_i + η cos θ_t) and r_p = (η cos θ_i − cos θ_t) /
    // (η cos θ_i + cos θ_t), the latter times η/η, over one common denominator: one square
    // root and one division.
    let b = g.sqrt();
    let c = eta2 * cos_i;
    let (s_num, s_den, p_num, p_den) = (cos_i - b, cos_i + b, c - b, c + b);
    let (s_num, s_den, p_num, p_den) = (s_num * s_num, s_den * s_den, p_num * p_num, p_den * p_den);
    0.5 * (s_num * p_den + p_num * s_den) / (s_den * p_den)
}

/// Marschner 2003's oblique Fresnel factor: the projected 2D problem at angle `gamma` with the
/// perpendicular component from η′ and the parallel component from η″ (Marschner et al. 2003
/// "Definition of F"). `eta_prime`, `eta_double_prime` below 1 describe light leaving the fiber.
pub fn fresnel_oblique(eta_prime: f64, eta_double_prime: f64, gamma: f64) -> f64 {
    let (sin_i, cos_i) = sin_cos_quadrant(gamma);
    fresnel_oblique_at(eta_prime, eta_double_prime, sin_i, cos_i.abs())
}

/// [`fresnel_oblique`] at the angle of sine `sin_i` and cosine `cos_i` ≥ 0, for a caller that
/// has them.
#[inline]
pub fn fresnel_oblique_at(eta_prime: f64, eta_double_prime: f64, sin_i: f64, cos_i: f64) -> f64 {
    let s = polarised_reflectance(eta_prime, sin_i, cos_i, Polarisation::Perpendicular);
    let p = polarised_reflectance(eta_double_prime, sin_i, cos_i, Polarisation::Parallel);
    0.5 * (s + p)
}

enum Polarisation {
    Perpendicular,
    Parallel,
}

/// |r|² of one polarisation at the incidence angle of sine `sin_i` and cosine `cos_i` ≥ 0
/// onto relative index `eta`.
fn polarised_reflectance(eta: f64, sin_i: f64, cos_i: f64, pol: Polarisation) -> f64 {
    let sin_t = sin_i / eta;
    if sin_t.abs() >= 1.0 {
        return 1.0;
    }
    let cos_t = (1.0 - sin_t * sin_t).sqrt();
    let r = match pol {
        Polarisation::Perpendicular => (cos_i - eta * cos_t) / (cos_i + eta * cos_t),
        Polarisation::Parallel => (cos_t - eta * cos_i) / (cos_t + eta * cos_i),
    };
    r * r
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The textbook form, r_s and r_p each by its own division: the reference twin of
    /// [`fresnel_dielectric`]'s one-division form.
    fn fresnel_dielectric_reference(cos_i: f64, eta: f64) -> f64 {
        let cos_i = cos_i.clamp(0.0, 1.0);
        let sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
        if sin2_t >= 1.0 {
            return 1.0;
        }
        let cos_t = (1.0 - sin2_t).sqrt();
        let r_s = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
        let r_p = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
        0.5 * (r_s * r_s + r_p * r_p)
    }

    /// Both forms cancel in η² − sin²θ_i near the critical angle, where F's slope is
    /// infinite: there they differ by up to 1.0e-13 (at η = 1/1.55, cos θ_i = 0.764, against
    /// 40-digit arithmetic the textbook form is 1.2e-13 off and this one 2.3e-13); elsewhere by
    /// rounding.
    #[test]
    fn one_division_matches_the_textbook_form() {
        let (mut near, mut far): (f64, f64) = (0.0, 0.0);
        for eta in [1.0 / 1.55, 0.9, 1.0, 1.0001, 1.33, 1.55, 2.4] {
            for k in 0..=20_000 {
                let cos_i = k as f64 / 20_000.0;
                let (got, want) = (
                    fresnel_dielectric(cos_i, eta),
                    fresnel_dielectric_reference(cos_i, eta),
                );
                let critical = eta * eta - 1.0 + cos_i * cos_i < 1e-2;
                let worst = if critical { &mut near } else { &mut far };
                *worst = worst.max((got - want).abs());
            }
        }
        eprintln!(
            "fresnel_dielectric vs the textbook form: ≤ {far:.2e}, within 1e-2 of the \
             critical η² − sin²θ_i ≤ {near:.2e}"
        );
        assert!(far < 2e-15 && near < 5e-13, "{far:e} {near:e}");
    }

    #[test]
    fn normal_incidence_matches_the_textbook_value() {
        let eta: f64 = 1.55;
        let r0 = ((eta - 1.0) / (eta + 1.0)).powi(2);
        assert!((fresnel_dielectric(1.0, eta) - r0).abs() < 1e-15);
        assert!((fresnel_oblique(eta, eta, 0.0) - r0).abs() < 1e-15);
    }

    #[test]
    fn brewster_angle_kills_the_parallel_component() {
        let eta: f64 = 1.5;
        let brewster = eta.atan();
        let s = polarised_reflectance(
            eta,
            brewster.sin(),
            brewster.cos(),
            Polarisation::Perpendicular,
        );
        assert!((fresnel_oblique(eta, eta, brewster) - 0.5 * s).abs() < 1e-15);
        assert!((fresnel_dielectric(brewster.cos(), eta) - 0.5 * s).abs() < 1e-15);
    }

    #[test]
    fn leaving_is_reciprocal_to_entering_and_total_internal_reflection_is_total() {
        let eta = 1.55;
        let cos_i: f64 = 0.4;
        let sin_t = (1.0 - cos_i * cos_i).sqrt() / eta;
        let cos_t = (1.0 - sin_t * sin_t).sqrt();
        assert!(
            (fresnel_dielectric(cos_i, eta) - fresnel_dielectric(cos_t, 1.0 / eta)).abs() < 1e-14
        );
        assert_eq!(fresnel_dielectric(0.1, 1.0 / eta), 1.0);
        assert_eq!(fresnel_dielectric(1.0, 1.0), 0.0);
    }
}
