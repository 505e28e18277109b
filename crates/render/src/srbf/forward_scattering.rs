//! Forward scattering along a light's shadow path (Zinke et al. 2008 §4.1; Xu et al. 2011 eqs. 3, 5).
//!
//! Sparse sampling of the hair volume: the deep opacity map of [`crate::frame::shadow`] already gives,
//! for every light and visible point, the optical depth n = −ln T̃ in front of the point, the
//! expected number of fibers a ray toward the light crosses (optical depth counts projected
//! fiber area per texel area). With every crossed fiber at the point's own inclination (forward
//! scattering keeps θ), Zinke's products and sums become
//! T_f = ā_f(θ_j)ⁿ and σ̄_f² = n β̄_f²(θ_j).
//! Of T_f, the part T̃ = e^{−n} reaches the point unscattered and is single scattering's; the
//! global term carries the rest, d_f (T_f − T̃)⁺, with Zinke's density factor d_f = 0.7.
//! The map counts a point's own and neighbouring segments as up to about half a crossing (they
//! share its texels), so the crossings that scatter are n_f = (n − ½)⁺: a lone strand gets no
//! global term, as Zinke's binary direct fraction gives it none.

use crate::tables::back_scattering::Averages;

/// Crossings the opacity map attributes to a point's own strand.
pub const SELF_CROSSINGS: f64 = 0.5;

/// Zinke 2008's density factor d_f.
pub const DENSITY_FACTOR: f64 = 0.7;

/// What reaches a point from one light through forward scattering, for one channel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Forward {
    /// d_f (T_f − T̃)⁺: the scattered share of the light's power.
    pub scattered: f64,
    /// σ̄_f²: the longitudinal variance the crossings add.
    pub variance: f64,
}

/// Forward scattering through the optical depth implied by the direct transmittance `direct`.
pub fn forward(direct: f64, averages: &Averages) -> Forward {
    let direct = direct.clamp(1e-12, 1.0);
    let n = (-direct.ln() - SELF_CROSSINGS).max(0.0);
    let t_f = averages.forward.clamp(0.0, 1.0).powf(n);
    Forward {
        scattered: DENSITY_FACTOR * (t_f - (-n).exp()).max(0.0),
        variance: n * averages.forward_variance,
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
        assert!((light.variance - 0.025).abs() < 1e-9);
        // Power can only be lost: T_f ≤ 1.
        assert!(light.scattered <= DENSITY_FACTOR);
    }
}
