//! The Fresnel factor F(η, θ_d, h) of the azimuthal functions (Xu et al. 2011 eq. 10): Marschner
//! 2003's oblique factor with Bravais' indices η′(η, θ_d) and η″(η, θ_d) at γ_i = asin h, the
//! same factor the exact model uses.

use cuticle_fiber::geometry::bravais::{eta_double_prime, eta_prime};
use cuticle_fiber::optics::fresnel::fresnel_oblique;

/// F(η, θ_d, h) with the projected indices.
pub fn oblique(eta: f64, theta_d: f64, h: f64) -> f64 {
    let gamma = h.clamp(-1.0, 1.0).asin();
    fresnel_oblique(
        eta_prime(eta, theta_d),
        eta_double_prime(eta, theta_d),
        gamma,
    )
}
