//! The fiber frame at each point and small angle helpers shared by the shading code.

use cuticle_fiber::FiberFrame;
use cuticle_fiber::math::sin_cos_quadrant;
use cuticle_groom::Groom;
use glam::DVec3;
use std::f64::consts::PI;

/// The fiber frame at point `i` of `groom`: u the strand tangent, v the part of the outward
/// direction from the origin (the head's centre in procedural grooms) normal to u, so that an
/// elliptical fiber's axes (Xu et al. 2011 eq. 24, through φ_h) keep one orientation relative
/// to the scalp.
pub fn fiber_frame_at(groom: &Groom, i: usize) -> FiberFrame {
    let t = groom.tangents()[i].as_dvec3();
    let tangent = if t.length_squared() > 1e-20 {
        t
    } else {
        DVec3::Z
    };
    FiberFrame::from_tangent(tangent, groom.positions()[i].as_dvec3())
}

/// Wraps an angle to (−π, π].
pub fn wrap_pi(x: f64) -> f64 {
    cuticle_fiber::wrap_pi(x)
}

/// A viewing inclination θ_o with its sine and cosine, so that each θ_i sample of the
/// quadratures needs one sine and cosine for cos θ_i and cos²θ_d = (1 + cos(θ_o − θ_i))/2,
/// both inclinations in [−π/2, π/2], where `sin_cos_quadrant` needs no range reduction and no
/// call.
#[derive(Clone, Copy, Debug)]
pub struct Outgoing {
    pub theta: f64,
    sin: f64,
    cos: f64,
}

/// One incident sample θ_i seen from an [`Outgoing`] θ_o.
#[derive(Clone, Copy, Debug)]
pub struct Incident {
    pub cos_i: f64,
    /// θ_d = (θ_o − θ_i)/2.
    pub theta_d: f64,
    pub cos2_d: f64,
}

impl Outgoing {
    pub fn new(theta: f64) -> Self {
        let (sin, cos) = sin_cos_quadrant(theta);
        Self { theta, sin, cos }
    }

    pub fn incident(&self, theta_i: f64) -> Incident {
        let (sin_i, cos_i) = sin_cos_quadrant(theta_i);
        Incident {
            cos_i,
            theta_d: 0.5 * (self.theta - theta_i),
            cos2_d: 0.5 * (1.0 + self.cos * cos_i + self.sin * sin_i),
        }
    }
}

/// Hermite smoothstep of x from a to b.
pub fn smoothstep(a: f64, b: f64, x: f64) -> f64 {
    let s = ((x - a) / (b - a)).clamp(0.0, 1.0);
    s * s * (3.0 - 2.0 * s)
}

/// η′ = √(η² − sin²θ_d)/cos θ_d (Xu et al. 2011 Table 1).
pub fn eta_prime(eta: f64, theta_d: f64) -> f64 {
    cuticle_fiber::geometry::bravais::eta_prime(eta, theta_d)
}

/// σ′_a = μ_a/√(1 − sin²θ_d/η²) (Xu et al. 2011 Table 1).
pub fn sigma_prime(mu_a: f64, eta: f64, theta_d: f64) -> f64 {
    mu_a / cuticle_fiber::geometry::bravais::cos_theta_t(eta, theta_d).max(1e-6)
}

/// Φ(p, h) = 2p asin(h/η′) − 2 asin h + pπ (Xu et al. 2011 eq. 8).
pub fn deflection(p: u32, h: f64, eta_prime: f64) -> f64 {
    cuticle_fiber::geometry::bravais::azimuthal_deflection(p, h, eta_prime)
}

/// dΦ/dh = 2p/√(η′² − h²) − 2/√(1 − h²).
pub fn deflection_slope(p: u32, h: f64, eta_prime: f64) -> f64 {
    2.0 * p as f64 / (eta_prime * eta_prime - h * h).max(1e-300).sqrt()
        - 2.0 / (1.0 - h * h).max(1e-300).sqrt()
}

/// π/2.
pub const HALF_PI: f64 = PI / 2.0;

#[cfg(test)]
mod tests {
    use super::Outgoing;

    /// cos θ_i and cos²θ_d from one sin_cos match their direct forms.
    #[test]
    fn incident_matches_direct_trigonometry() {
        for &(o, i) in &[(0.3, -1.2), (-1.4, 1.5), (0.0, 0.0), (1.1, 0.9)] {
            let s = Outgoing::new(o).incident(i);
            let td: f64 = 0.5 * (o - i);
            assert!((s.cos_i - i.cos()).abs() < 1e-15);
            assert!((s.theta_d - td).abs() < 1e-15);
            assert!((s.cos2_d - td.cos().powi(2)).abs() < 1e-14);
        }
    }
}
