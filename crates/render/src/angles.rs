//! Small angle helpers shared by the shading code.

use std::f64::consts::PI;

/// Wraps an angle to (−π, π].
pub fn wrap_pi(x: f64) -> f64 {
    cuticle_fiber::wrap_pi(x)
}

/// Hermite smoothstep of x from a to b.
pub fn smoothstep(a: f64, b: f64, x: f64) -> f64 {
    let s = ((x - a) / (b - a)).clamp(0.0, 1.0);
    s * s * (3.0 - 2.0 * s)
}

/// η′ = √(η² − sin²θ_d)/cos θ_d (seed 004 Table 1).
pub fn eta_prime(eta: f64, theta_d: f64) -> f64 {
    cuticle_fiber::bravais::eta_perp(eta, theta_d)
}

/// σ′_a = σ_a/√(1 − sin²θ_d/η²) (seed 004 Table 1).
pub fn sigma_prime(sigma_a: f64, eta: f64, theta_d: f64) -> f64 {
    sigma_a / cuticle_fiber::bravais::cos_theta_t(eta, theta_d).max(1e-6)
}

/// Φ(p, h) = 2p asin(h/η′) − 2 asin h + pπ (seed 004 eq. 8).
pub fn deflection(p: u32, h: f64, eta_prime: f64) -> f64 {
    cuticle_fiber::bravais::azimuthal_deflection(p, h, eta_prime)
}

/// dΦ/dh = 2p/√(η′² − h²) − 2/√(1 − h²).
pub fn deflection_slope(p: u32, h: f64, eta_prime: f64) -> f64 {
    2.0 * p as f64 / (eta_prime * eta_prime - h * h).max(1e-300).sqrt()
        - 2.0 / (1.0 - h * h).max(1e-300).sqrt()
}

/// π/2.
pub const HALF_PI: f64 = PI / 2.0;
