//! R off a tilted scale: the exact mirror direction at each offset h, and its inverse, the
//! offset whose mirror leaves at azimuth φ.
//!
//! d'Eon et al. 2014 §2.3 keeps Bravais' φ = −2γ_i = −2 asin h for R (and writes its cone as a
//! function of φ through cos(φ/2) = √(1 − h²)). A tilted normal bends the mirror's azimuth as
//! well as its inclination, little at normal incidence (0.2° at |φ| = 2.2, θ_i ≤ 1.1, α = 2°,
//! `cuticle-sim` `tests/tilt.rs`) but much at grazing incidence: at θ_i = 1.3, α = −4° the
//! offset h = 0.86 mirrors to φ = −2.60 where −2γ_i = −2.07, so the last reflections before the
//! scales cut R off land half a radian further round than Bravais puts them (the simulator's R
//! reaches |φ| = 2.85 there). The tilted model places R by this mapping instead.

use crate::frame::{FiberAngles, wrap_pi};
use glam::DVec3;
use std::f64::consts::FRAC_PI_2;

/// The mirror of ω_i = (sin θ_i, cos θ_i, 0) (φ_i = 0) at offset h about the scale normal tilted
/// by α (the simulator's sign: toward +u for α > 0): n_s = (sin α, cos α cos γ, −cos α sin γ) at
/// the surface point of azimuth −γ, h = sin γ. Its azimuth is unwrapped about −2γ, so that it
/// is continuous and decreasing in h over the whole fiber.
pub fn tilted_mirror(theta_i: f64, alpha: f64, h: f64) -> FiberAngles {
    let gamma = h.clamp(-1.0, 1.0).asin();
    let (sa, ca) = alpha.sin_cos();
    let (sg, cg) = gamma.sin_cos();
    let n = DVec3::new(sa, ca * cg, -ca * sg);
    let wi = DVec3::new(theta_i.sin(), theta_i.cos(), 0.0);
    let r = 2.0 * wi.dot(n) * n - wi;
    let bravais = -2.0 * gamma;
    let phi = bravais + wrap_pi(r.z.atan2(r.y) - bravais);
    FiberAngles::new(r.x.clamp(-1.0, 1.0).asin(), phi)
}

/// The offset h whose tilted mirror leaves at azimuth φ (unwrapped, as [`tilted_mirror`] gives
/// it), and |dh/dφ| there: bisection on γ, where the mirror's azimuth decreases monotonically;
/// `None` outside the range the fiber's offsets reach.
pub fn tilted_mirror_offset(theta_i: f64, alpha: f64, phi: f64) -> Option<(f64, f64)> {
    let at = |g: f64| tilted_mirror(theta_i, alpha, g.sin()).phi;
    let (mut lo, mut hi) = (-FRAC_PI_2, FRAC_PI_2);
    if !(phi <= at(lo) && phi >= at(hi)) {
        return None;
    }
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if at(mid) > phi {
            lo = mid;
        } else {
            hi = mid;
        }
        if hi - lo < 1e-13 {
            break;
        }
    }
    let gamma = 0.5 * (lo + hi);
    // dh/dφ = cos γ / (dφ/dγ), the derivative by a central difference on γ.
    let e = 1e-6;
    let slope = (at((gamma + e).min(FRAC_PI_2)) - at((gamma - e).max(-FRAC_PI_2)))
        / ((gamma + e).min(FRAC_PI_2) - (gamma - e).max(-FRAC_PI_2));
    (slope < 0.0).then(|| (gamma.sin(), gamma.cos() / -slope))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nusselt;
    use crate::tilted_attenuation::incident;

    #[test]
    fn flat_scales_mirror_by_bravais_and_tilted_ones_agree_with_the_rotations() {
        for &(theta, h) in &[(0.3, 0.4), (1.3, -0.9), (-1.0, 0.2)] {
            let flat = tilted_mirror(theta, 0.0, h);
            assert!((flat.phi + 2.0 * f64::asin(h)).abs() < 1e-12);
            assert!((flat.theta + theta).abs() < 1e-12);
            let alpha = -0.07;
            let tilted = tilted_mirror(theta, alpha, h);
            let x = nusselt::exit_r(alpha, incident(theta, h));
            assert!((tilted.theta - x.asin()).abs() < 1e-12, "θ {theta} h {h}");
        }
        // The grazing case of the module docs.
        let m = tilted_mirror(1.3, (-4f64).to_radians(), 0.86);
        assert!((m.phi + 2.601).abs() < 1e-3, "{}", m.phi);
    }

    #[test]
    fn the_offset_inverts_the_mirror_and_its_slope_is_the_derivative() {
        let (theta, alpha) = (1.3, (-4f64).to_radians());
        for &h in &[-0.95, -0.5, 0.0, 0.3, 0.86] {
            let phi = tilted_mirror(theta, alpha, h).phi;
            let (back, dh) = tilted_mirror_offset(theta, alpha, phi).unwrap();
            assert!((back - h).abs() < 1e-9, "h {h}: {back}");
            let e = 1e-5;
            let numeric = 2.0 * e
                / (tilted_mirror(theta, alpha, h - e).phi - tilted_mirror(theta, alpha, h + e).phi);
            assert!(
                (dh - numeric).abs() < 1e-4 * numeric,
                "h {h}: {dh} vs {numeric}"
            );
        }
        // Untilted, |dh/dφ| = ½ cos(φ/2).
        let (h, dh) = tilted_mirror_offset(0.5, 0.0, 1.0).unwrap();
        assert!((h + 0.5f64.sin()).abs() < 1e-9 && (dh - 0.5 * 0.5f64.cos()).abs() < 1e-6);
    }
}
