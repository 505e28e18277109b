//! The exact azimuthal functions the circular Gaussians approximate (Xu et al. 2011 eqs. 8–10):
//! N_t(η, θ_d, φ) = Σ_h ½ |dΦ/dh|⁻¹ A_t(θ_d, h) over every h ∈ (−1, 1) with Φ(p, h) ≡ φ, with the
//! exact deflection Φ, the oblique Fresnel factor and T = exp(−2σ′_a √(1 − h²/η′²)). Used by the
//! tests and by nothing in the hot path.

use crate::angles::{deflection, deflection_slope, eta_prime, sigma_prime, wrap_pi};
use crate::fresnel::oblique;

/// A_t(θ_d, h) of mode p (0 = R, 1 = TT, 2 = TRT) for one absorption channel (Xu et al. 2011 eq.
/// 10).
pub fn attenuation(p: u32, eta: f64, theta_d: f64, mu_a: f64, h: f64) -> f64 {
    let f = oblique(eta, theta_d, h);
    if p == 0 {
        return f;
    }
    let t = transmittance(sigma_prime(mu_a, eta, theta_d), eta_prime(eta, theta_d), h);
    (1.0 - f).powi(2) * f.powi(p as i32 - 1) * t.powi(p as i32)
}

/// T(σ′_a, h) = exp(−2σ′_a √(1 − h²/η′²)) (Xu et al. 2011 §4.1).
pub fn transmittance(sigma_prime: f64, eta_prime: f64, h: f64) -> f64 {
    let s = (h / eta_prime).powi(2);
    (-2.0 * sigma_prime * (1.0 - s).max(0.0).sqrt()).exp()
}

/// N_t(η, θ_d, φ) by root finding on a fine grid of h (Xu et al. 2011 eq. 9).
pub fn azimuthal(p: u32, eta: f64, theta_d: f64, mu_a: f64, phi: f64) -> f64 {
    let ep = eta_prime(eta, theta_d);
    roots(p, ep, phi)
        .into_iter()
        .map(|h| 0.5 * attenuation(p, eta, theta_d, mu_a, h) / deflection_slope(p, h, ep).abs())
        .sum()
}

/// ∫_{−π}^{π} N_t dφ = ½ ∫_{−1}^{1} A_t dh, by 4000-point midpoint rule in h.
pub fn energy(p: u32, eta: f64, theta_d: f64, mu_a: f64) -> f64 {
    let n = 4000;
    (0..n)
        .map(|i| {
            let h = -1.0 + (i as f64 + 0.5) * 2.0 / n as f64;
            0.5 * attenuation(p, eta, theta_d, mu_a, h) * 2.0 / n as f64
        })
        .sum()
}

/// Every h ∈ (−1, 1) with Φ(p, h) ≡ φ (mod 2π), by bracketing on 2048 cells and bisection.
pub fn roots(p: u32, eta_prime: f64, phi: f64) -> Vec<f64> {
    let g = |h: f64| wrap_pi(deflection(p, h, eta_prime) - phi);
    let n = 2048;
    let node = |i: usize| -1.0 + 2.0 * i as f64 / n as f64;
    let mut out = Vec::new();
    for i in 0..n {
        let (mut a, mut b) = (node(i).max(-1.0 + 1e-12), node(i + 1).min(1.0 - 1e-12));
        let (ga, gb) = (g(a), g(b));
        if ga.signum() == gb.signum() || (ga - gb).abs() > 3.0 {
            continue;
        }
        for _ in 0..60 {
            let m = 0.5 * (a + b);
            if g(m).signum() == ga.signum() {
                a = m;
            } else {
                b = m;
            }
        }
        out.push(0.5 * (a + b));
    }
    out
}
