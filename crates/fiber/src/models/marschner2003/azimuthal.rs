//! Attenuation A(p, h) and the azimuthal functions N_p, with the TRT caustics and η* of an
//! elliptical fiber.

use super::{CubicDeflection, MarschnerParams};
use crate::geometry::bravais::{chord_transmittance, cos_theta_t, eta_double_prime, eta_prime};
use crate::geometry::frame::wrap_pi;
use crate::lobes::azimuthal::wrapped_gaussian;
use crate::math::sin_cos_quadrant;
use crate::optics::fresnel::fresnel_oblique_at;
use glam::DVec3;

/// The optics of the normal-plane problem at one θ_d: Bravais' indices and the refracted
/// inclination that stretches the internal path.
#[derive(Clone, Copy, Debug)]
pub(super) struct Interface {
    pub(super) eta_prime: f64,
    eta_double_prime: f64,
    cos_theta_t: f64,
    mu_a: DVec3,
    /// c = asin(1/η′), which every lobe's cubic deflection shares.
    critical_angle: f64,
}

impl Interface {
    pub(super) fn new(eta: f64, theta_d: f64, mu_a: DVec3) -> Self {
        let eta_prime = eta_prime(eta, theta_d);
        Self {
            eta_prime,
            eta_double_prime: eta_double_prime(eta, theta_d),
            cos_theta_t: cos_theta_t(eta, theta_d),
            mu_a,
            critical_angle: CubicDeflection::critical_angle(eta_prime),
        }
    }

    /// A(p, h) at h = sin γ_i (Marschner et al. 2003 "Finding A", with docs/conventions.md §8's
    /// transmittance; T^p as one exponential of the p segments' summed path).
    /// One sine and cosine of γ_i serve both Fresnel factors: sin γ_t = sin γ_i / η′ (the
    /// same γ_t as [`crate::geometry::bravais::gamma_t`]) and the chord's cos γ_t follow without
    /// trigonometry.
    pub(super) fn attenuation(&self, p: u32, gamma_i: f64) -> DVec3 {
        let (sin_i, cos_i) = sin_cos_quadrant(gamma_i);
        let f = fresnel_oblique_at(self.eta_prime, self.eta_double_prime, sin_i, cos_i.abs());
        if p == 0 {
            return DVec3::splat(f);
        }
        let sin_t = (sin_i / self.eta_prime).clamp(-1.0, 1.0);
        let cos_t = (1.0 - sin_t * sin_t).sqrt();
        let internal = fresnel_oblique_at(
            1.0 / self.eta_prime,
            1.0 / self.eta_double_prime,
            sin_t,
            cos_t,
        );
        let t = (p as f64 * self.mu_a).map(|mu| chord_transmittance(mu, cos_t, self.cos_theta_t));
        (1.0 - f).powi(2) * internal.powi(p as i32 - 1) * t
    }

    pub(super) fn deflection(&self, p: u32) -> CubicDeflection {
        CubicDeflection::with_critical_angle(p, self.critical_angle)
    }
}

/// N_p(φ) = Σ A(p, h) / |2 dΦ̂/dh| over every root (Marschner et al. 2003 "Finding N_p").
pub(super) fn azimuthal(p: u32, interface: &Interface, phi: f64) -> DVec3 {
    let deflection = interface.deflection(p);
    deflection
        .roots(phi)
        .as_slice()
        .iter()
        .map(|&g| interface.attenuation(p, g) * deflection.inverse_spread(g))
        .sum()
}

/// Marschner 2003's treatment of the TRT caustics (its listing for N_TRT), taken at the
/// cubic's own fold so that the singularity removed is the one N_P has.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Caustic {
    /// φ_c, wrapped: the glints sit at ±φ_c.
    pub phi_c: f64,
    /// γ at the caustic (0 once the caustics have merged).
    pub gamma_c: f64,
    /// Δh, the span of offsets the glint stands for.
    pub delta_h: f64,
    /// t, the glint's strength: 1 while the caustics exist, fading to 0 over Δη′ after.
    pub t: f64,
}

impl Caustic {
    /// Marschner 2003's N_TRT listing: for η′ < 2, h_c where dΦ/dh = 0, φ_c = Φ(2, h_c),
    /// Δh = min(Δh_M, 2 √(2 w_c / |d²Φ/dh²(h_c)|)), t = 1; for η′ ≥ 2, φ_c = 0, Δh = Δh_M and
    /// t = 1 − smoothstep(2, 2 + Δη′, η′). The paper's h_c = √((4 − η′²)/3) is the exact Φ's
    /// fold; the cubic's fold (γ_c² = a/3b) is used here, since the cubic's N_P is what the
    /// glint replaces: they differ by ≤ 0.019 in h_c and ≤ 0.033 rad in φ_c for
    /// η′ ∈ [1.55, 2), more below (0.11 rad in φ_c at η′ = 1.2).
    /// Some transcriptions of the listing drop the "1 −" in t, which would switch the glint
    /// off at η′ = 2 and back on above; t is kept continuous here.
    pub fn new(eta_prime: f64, params: &MarschnerParams) -> Self {
        Self::of(CubicDeflection::new(2, eta_prime), eta_prime, params)
    }

    /// [`Caustic::new`] with TRT's cubic deflection at η′ already made.
    pub(super) fn of(
        deflection: CubicDeflection,
        eta_prime: f64,
        params: &MarschnerParams,
    ) -> Self {
        match deflection.fold() {
            Some(g) if eta_prime < 2.0 => {
                let cos2 = g.cos().powi(2);
                let d2phi_dh2 = deflection.curvature(g) / cos2;
                let spread = 2.0 * (2.0 * params.caustic_width / d2phi_dh2.abs()).sqrt();
                Self {
                    phi_c: wrap_pi(deflection.phi(g)),
                    gamma_c: g,
                    delta_h: params.caustic_limit.min(spread),
                    t: 1.0,
                }
            }
            _ => Self {
                phi_c: 0.0,
                gamma_c: 0.0,
                delta_h: params.caustic_limit,
                t: 1.0 - smoothstep(2.0, 2.0 + params.caustic_fade, eta_prime),
            },
        }
    }
}

pub(super) fn smoothstep(a: f64, b: f64, x: f64) -> f64 {
    let s = ((x - a) / (b - a)).clamp(0.0, 1.0);
    s * s * (3.0 - 2.0 * s)
}

/// N_TRT (Marschner 2003's listing): N_P(2, φ) with the caustics removed,
/// L ← L (1 − t g(w_c; φ − φ_c)/g(w_c; 0)) (1 − t g(w_c; φ + φ_c)/g(w_c; 0)), plus the glints
/// t k_G A(2, h_c) Δh (g(w_c; φ − φ_c) + g(w_c; φ + φ_c)), g a wrapped unit Gaussian.
pub(super) fn azimuthal_trt(interface: &Interface, params: &MarschnerParams, phi: f64) -> DVec3 {
    let caustic = Caustic::of(interface.deflection(2), interface.eta_prime, params);
    let v = params.caustic_width.powi(2);
    let g0 = wrapped_gaussian(0.0, v);
    let (g_minus, g_plus) = (
        wrapped_gaussian(phi - caustic.phi_c, v),
        wrapped_gaussian(phi + caustic.phi_c, v),
    );
    // Each factor lies in [0, 1]: the wrapped Gaussian peaks at 0.
    let keep = (1.0 - caustic.t * g_minus / g0) * (1.0 - caustic.t * g_plus / g0);
    let smooth = azimuthal(2, interface, phi) * keep.max(0.0);
    let glint = caustic.t * params.glint_scale * caustic.delta_h * (g_minus + g_plus);
    smooth + glint * interface.attenuation(2, caustic.gamma_c)
}

/// η*(φ_h) of an elliptical fiber (Xu et al. 2011 eq. 24, after Marschner 2003):
/// η*₁ = 2(η − 1)a² − η + 2, η*₂ = 2(η − 1)a⁻² − η + 2,
/// η* = ½((η*₁ + η*₂) + cos(2φ_h)(η*₁ − η*₂)), with 2φ_h = φ_i + φ_o. A circle (a = 1) gives η.
pub fn eta_star(eta: f64, eccentricity: f64, phi_sum: f64) -> f64 {
    if eccentricity == 1.0 {
        return eta;
    }
    let e2 = eccentricity * eccentricity;
    let eta1 = 2.0 * (eta - 1.0) * e2 - eta + 2.0;
    let eta2 = 2.0 * (eta - 1.0) / e2 - eta + 2.0;
    0.5 * ((eta1 + eta2) + phi_sum.cos() * (eta1 - eta2))
}
