//! Multiple scattering by dual scattering under SRBF lights (seed 004 §4.3, Zinke et al. 2008).
//!
//! Each light j of energy E_j = L_j ∫G_j dω reaches a point two ways: unscattered with share T̃
//! (single scattering's, [`crate::single_scattering`]) and forward-scattered with share
//! d_f (T_f − T̃)⁺ ([`crate::forward_scattering`]), spread by ψ_f = s̃_f g^u(θ_i; θ_j, σ_f)/cos θ_j
//! (eq. 5), s̃_f = 1/π over the half circle around φ_j and σ_f² = λ_j²/2 + σ̄_f² (the SRBF's
//! longitudinal variance plus the spread). In the crate's units (lib.rs) they add
//! - the global term (eqs. 27–28): ℳ^G_t = (1/cos θ_j) ∫ g^u(θ_i; θ_j, σ_f) ½M_t(θ_h)
//!   (cos²θ_i/cos²θ_d) 𝒩^G_t(φ_o − φ_j, θ_d) dθ_i, with 𝒩^G_t closed form from the circular
//!   Gaussians and the half-circle tables ([`crate::half_circle`]);
//! - the local term (eqs. 29–31), d_b times ℳ^L = (1/cos θ_j) ∫ g^u(θ_i; θ_j, σ) ½M_b(θ_h)
//!   (cos²θ_i/cos²θ_d) Ā_b 𝒩^L dθ_i, where ½M_b is the unit normal density in θ_i of mean
//!   2Δ̄_b − θ_o and deviation 2σ̄_b (as ½M_p is for α_p, β_p: seed 004 eq. 7) and 𝒩^L the
//!   overlap of the light's azimuthal spread with s_b = 1/π on the backward half circle around
//!   φ_o: (π − |δ|)/π² for the scattered light, P(λ′, δ)/π for the direct light (which Zinke's
//!   F_direct also back-scatters, with σ = λ_j/√2).
//!
//! Ā_b, Δ̄_b, σ̄_b are taken at the θ_d of the light's centre, (θ_o − θ_j)/2; all outer integrals
//! use the linear quadrature of §4.2.2. Eccentricity is ignored here (Zinke's model is for
//! circular fibers). Channels share one σ_f, the mean of theirs weighted by their scattered
//! shares.

use crate::angles::wrap_pi;
use crate::back_scattering_tables::BackScatteringTables;
use crate::cg_lobes::{Geometry, Lobe, TrtShape, r_coefficients, trt_fit, tt_fit};
use crate::circular_gaussian as cg;
use crate::forward_scattering::forward;
use crate::hair::caustic_bandwidth;
use crate::half_circle::HalfCircle;
use crate::quadrature::Window;
use crate::single_scattering::LocalLight;
use crate::tables::Tables;
use cuticle_fiber::marschner2003::MarschnerParams;
use glam::DVec3;
use std::f64::consts::{FRAC_1_SQRT_2, PI};

/// Scattered shares below this skip the global and scattered local terms.
const NEGLIGIBLE: f64 = 1e-5;

/// Everything multiple scattering reads besides the point and its lights.
#[derive(Clone, Copy, Debug)]
pub struct Dual<'a> {
    pub tables: &'a Tables,
    pub half: &'a HalfCircle,
    pub back: &'a BackScatteringTables,
    pub d_b: f64,
    /// Segments m of the linear quadrature.
    pub m: usize,
}

/// ∫ G_j dω of an SRBF exp(κ(ω·ω_j − 1)), κ = 2/λ².
pub fn srbf_integral(lambda: f64) -> f64 {
    let kappa = 2.0 / (lambda * lambda).max(1e-12);
    2.0 * PI * (1.0 - (-2.0 * kappa).exp()) / kappa
}

impl Dual<'_> {
    /// Multiple-scattering radiance toward (θ_o, φ_o) from every light; `lights` carry the
    /// unshadowed coefficients L_j, `direct` the transmittances T̃_j.
    pub fn shade(
        &self,
        fiber: &MarschnerParams,
        theta_o: f64,
        phi_o: f64,
        lights: &[LocalLight],
        direct: &[f32],
    ) -> DVec3 {
        lights
            .iter()
            .zip(direct)
            .map(|(light, &t)| self.light(fiber, theta_o, phi_o, light, t as f64))
            .sum()
    }

    /// One light's global and local terms.
    fn light(
        &self,
        fiber: &MarschnerParams,
        theta_o: f64,
        phi_o: f64,
        light: &LocalLight,
        t: f64,
    ) -> DVec3 {
        let energy = light.radiance * srbf_integral(light.bandwidth);
        if energy.max_element() <= 0.0 {
            return DVec3::ZERO;
        }
        let cos_j = light.theta.cos().max(1e-4);
        let delta = wrap_pi(phi_o - light.phi);
        let fw: [_; 3] =
            std::array::from_fn(|c| forward(t, &self.back.at(light.theta, fiber.mu_a[c])));
        let scattered = DVec3::from_array(fw.map(|f| f.scattered));
        let light_var = srbf_deviation(light.bandwidth).powi(2);
        let direct_azimuth = self.half.share(light.bandwidth / cos_j, delta) / PI;
        let mut out = t
            * self.d_b
            * self.local(
                fiber,
                theta_o,
                light.theta,
                light_var.sqrt(),
                direct_azimuth,
            );
        if scattered.max_element() > NEGLIGIBLE {
            let weight = scattered.element_sum();
            let spread = (0..3)
                .map(|c| fw[c].variance * fw[c].scattered)
                .sum::<f64>()
                / weight;
            let sigma_f = (light_var + spread).sqrt();
            let scattered_azimuth = (PI - delta.abs()) / (PI * PI);
            out += scattered
                * (self.global(fiber, theta_o, light.theta, sigma_f, delta)
                    + self.d_b
                        * self.local(fiber, theta_o, light.theta, sigma_f, scattered_azimuth));
        }
        energy * out / cos_j
    }

    /// Σ_t ∫ g^u(θ_i; θ_j, σ_f) ½M_t (cos²θ_i/cos²θ_d) 𝒩^G_t dθ_i (eq. 27 without 1/cos θ_j).
    fn global(
        &self,
        fiber: &MarschnerParams,
        theta_o: f64,
        theta_j: f64,
        sigma_f: f64,
        delta: f64,
    ) -> DVec3 {
        let shape = TrtShape {
            caustic_bandwidth: caustic_bandwidth(fiber),
            caustic_fade: fiber.caustic_fade,
        };
        let w = self.half.cosines(delta);
        let lobes = fiber.longitudinal();
        (0..3)
            .map(|t| {
                let (alpha, beta) = lobes[t];
                let window =
                    Window::normal_product(theta_j, sigma_f, 2.0 * alpha - theta_o, 2.0 * beta);
                if window.scale < 1e-12 {
                    return DVec3::ZERO;
                }
                window.integrate(self.m, |theta_i| {
                    let cos_i = theta_i.cos();
                    let theta_d = 0.5 * (theta_o - theta_i);
                    let n = match t {
                        0 => DVec3::splat(r_half(fiber.eta, theta_d, &w)),
                        1 => {
                            let g = Geometry::new(self.tables, fiber.eta, theta_d);
                            DVec3::from_array(std::array::from_fn(|c| {
                                self.lobe_half(&tt_fit(&g, fiber.mu_a[c]), delta)
                            }))
                        }
                        _ => {
                            let g = Geometry::new(self.tables, fiber.eta, theta_d);
                            DVec3::from_array(std::array::from_fn(|c| {
                                trt_fit(&g, fiber.mu_a[c], shape)
                                    .iter()
                                    .map(|l| self.lobe_half(l, delta))
                                    .sum()
                            }))
                        }
                    };
                    n * (cos_i * cos_i / theta_d.cos().powi(2))
                })
            })
            .sum()
    }

    /// (1/π) ∫ over the half circle around δ of b g^c(φ; μ, λ).
    fn lobe_half(&self, lobe: &Lobe, delta: f64) -> f64 {
        if lobe.weight == 0.0 {
            return 0.0;
        }
        lobe.weight
            * cg::integral(lobe.bandwidth)
            * self.half.share(lobe.bandwidth, delta - lobe.centre)
            / PI
    }

    /// Per channel Ā_b 𝒩^L ∫ g^u(θ_i; θ_j, σ) ½M_b (cos²θ_i/cos²θ_d) dθ_i (eq. 29 without
    /// 1/cos θ_j), `azimuth` being 𝒩^L.
    fn local(
        &self,
        fiber: &MarschnerParams,
        theta_o: f64,
        theta_j: f64,
        sigma: f64,
        azimuth: f64,
    ) -> DVec3 {
        if azimuth <= 0.0 {
            return DVec3::ZERO;
        }
        let theta_d = 0.5 * (theta_o - theta_j);
        DVec3::from_array(std::array::from_fn(|c| {
            let a = self.back.at(theta_d, fiber.mu_a[c]);
            if a.back <= 0.0 {
                return 0.0;
            }
            let window = Window::normal_product(
                theta_j,
                sigma,
                2.0 * a.back_shift - theta_o,
                2.0 * a.back_width,
            );
            let integral = window.integrate(self.m, |theta_i| {
                let d = 0.5 * (theta_o - theta_i);
                DVec3::splat(theta_i.cos().powi(2) / d.cos().powi(2))
            });
            a.back * azimuth * integral.x
        }))
    }
}

/// 𝒩^G_R = (1/π) Σ_k C_k W_k(δ) (eqs. 13, 28).
fn r_half(eta: f64, theta_d: f64, w: &[f64; 7]) -> f64 {
    let c = r_coefficients(eta, theta_d);
    (1..7).map(|k| c[k] * w[k]).sum::<f64>() / PI
}

/// λ_j/√2: the longitudinal deviation of an SRBF of bandwidth λ_j.
pub fn srbf_deviation(lambda: f64) -> f64 {
    FRAC_1_SQRT_2 * lambda
}
