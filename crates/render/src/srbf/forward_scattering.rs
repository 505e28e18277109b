//! Forward scattering along a light's shadow path (Zinke et al. 2008 §4.1; Xu et al. 2011 eqs. 3,
//! 5).
//!
//! Sparse sampling of the hair volume: the deep opacity map of [`crate::frame::shadows`] already
//! gives, for every light and visible point, the optical depth n = −ln T̃ in front of the point,
//! the expected number of fibers a ray toward the light crosses (optical depth counts projected
//! fiber area per texel area). With every crossed fiber at the point's own inclination (forward
//! scattering keeps θ), Zinke's product over the k fibers a ray actually crosses,
//! T_f = ∏ ā_f = ā_f^k, and sum σ̄_f² = k β̄_f², are averaged here over the number of
//! crossings k, which for fibers placed independently is Poisson of mean n — the same law that
//! makes T̃ = e^{−n} the chance of crossing none, which single scattering already uses:
//! - T_f = E[ā_f^k] = e^{−n(1 − ā_f)}, of which the k = 0 share T̃ = e^{−n} reaches the point
//!   unscattered and is single scattering's; the global term carries the rest,
//!   d_f (T_f − T̃) = d_f e^{−n} (e^{n ā_f} − 1) ≥ 0, with Zinke's density factor d_f = 0.7;
//! - σ̄_f² = β̄_f² E[k | scattered] = β̄_f² n ā_f / (1 − e^{−n ā_f}), the mean number of
//!   crossings of the light that was scattered (at least one).
//!
//! Zinke et al. 2008 take ā_f^n with n the count along one shadow ray and a binary direct
//! fraction; raising ā_f to the *mean* count while taking T̃ = e^{−n} for the direct fraction
//! (as this module did) gives T_f < T̃ whenever ā_f < e^{−1}, i.e. no global term at all for
//! μ_a ≳ 0.5 (tests/slab.rs measures both against an exact path trace of a fiber slab). The
//! maps count a point's own strand as well, but as under 0.2 crossings on a slab of
//! random fibers (tests/slab.rs), so nothing is subtracted for it.

use crate::tables::back_scattering::Averages;

/// Zinke 2008's density factor d_f.
pub const DENSITY_FACTOR: f64 = 0.7;

/// What reaches a point from one light through forward scattering, for one channel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Forward {
    /// d_f (T_f − T̃): the scattered share of the light's power.
    pub scattered: f64,
    /// σ̄_f²: the longitudinal variance the crossings add.
    pub variance: f64,
}

/// Forward scattering through the optical depth implied by the direct transmittance `direct`.
pub fn forward(direct: f64, averages: &Averages) -> Forward {
    let direct = direct.clamp(1e-300, 1.0);
    let n = -direct.ln();
    let a_f = averages.forward.clamp(0.0, 1.0);
    let m = n * a_f;
    // e^{−n} (e^{n ā_f} − 1), and E[k | k ≥ 1] = m / (1 − e^{−m}) → 1 as m → 0.
    let scattered = direct * m.exp_m1();
    let crossings = if m > 1e-12 { m / -(-m).exp_m1() } else { 1.0 };
    Forward {
        scattered: DENSITY_FACTOR * scattered,
        variance: if n > 0.0 {
            crossings * averages.forward_variance
        } else {
            0.0
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn averages(forward: f64) -> Averages {
        Averages {
            forward,
            forward_variance: 0.01,
            back: 0.1,
            back_shift: 0.0,
            back_width: 0.1,
        }
    }

    #[test]
    fn unoccluded_light_is_not_scattered() {
        let f = forward(1.0, &averages(0.6));
        assert_eq!(f.scattered, 0.0);
        assert_eq!(f.variance, 0.0);
    }

    #[test]
    fn scattered_share_grows_with_forward_attenuation_and_spread_with_depth() {
        let t = (-3.0f64).exp();
        let light = forward(t, &averages(0.8));
        let dark = forward(t, &averages(0.4));
        assert!(light.scattered > dark.scattered && dark.scattered > 0.0);
        // d_f (e^{−n(1−ā_f)} − e^{−n}) at n = 3, ā_f = 0.8.
        let want = DENSITY_FACTOR * ((-0.6f64).exp() - t);
        assert!((light.scattered - want).abs() < 1e-12, "{light:?}");
        // Spread: β̄_f² m/(1 − e^{−m}), m = n ā_f = 2.4 crossings' worth of the scattered light.
        let crossings = 2.4 / (1.0 - (-2.4f64).exp());
        assert!((light.variance - 0.01 * crossings).abs() < 1e-12);
        assert!(dark.variance < light.variance);
        // Power can only be lost: T_f ≤ 1.
        assert!(light.scattered <= DENSITY_FACTOR);
    }

    /// Dark fibers still pass light on: with ā_f below e^{−1}, ā_f^n falls below e^{−n} and
    /// the old (ā_f^n − e^{−n})⁺ vanished; the Poisson mean stays positive, and through one
    /// thin layer (n → 0) the scattered share is d_f n ā_f with one crossing's spread.
    #[test]
    fn dark_fibers_and_thin_layers_still_scatter_forward() {
        let dark = forward((-2.0f64).exp(), &averages(0.2));
        let old = (0.2f64.powi(2) - (-2.0f64).exp()).max(0.0);
        assert_eq!(old, 0.0);
        assert!(dark.scattered > 0.04, "{dark:?}");
        let thin = forward((-1e-3f64).exp(), &averages(0.5));
        assert!((thin.scattered / (DENSITY_FACTOR * 1e-3 * 0.5) - 1.0).abs() < 2e-3);
        assert!((thin.variance - 0.01).abs() < 1e-5);
    }
}
