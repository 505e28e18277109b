//! Multiple scattering by dual scattering under SRBF lights (Xu et al. 2011 §4.3, Zinke et al.
//! 2008).
//!
//! Each light j of energy E_j = L_j ∫G_j dω reaches a point two ways: unscattered with share T̃
//! (single scattering's, [`crate::srbf::single_scattering`]) and forward-scattered with share
//! d_f (T_f − T̃)⁺ ([`crate::srbf::forward_scattering`]), spread by ψ_f = s̃_f g^u(θ_i; θ_j,
//! σ_f)/cos θ_j (eq. 5), s̃_f = 1/π over the half circle around φ_j and σ_f² = λ_j²/2 + σ̄_f² (the
//! SRBF's longitudinal variance plus the spread). In the crate's units (lib.rs) they add
//! - the global term (eqs. 27–28): ℳ^G_t = (1/cos θ_j) ∫ g^u(θ_i; θ_j, σ_f) ½M_t(θ_h)
//!   (cos²θ_i/cos²θ_d) 𝒩^G_t(φ_o − φ_j, θ_d) dθ_i, with 𝒩^G_t closed form from the circular
//!   Gaussians and the half-circle tables ([`crate::tables::half_circle`]);
//! - the local term (eqs. 29–31), d_b times ℳ^L = (2/cos θ_j) ∫ g^u(θ_i; θ_j, σ) ½M_b(θ_h)
//!   (cos²θ_i/cos²θ_d) Ā_b 𝒩^L dθ_i, where ½M_b is the unit normal density in θ_i of mean
//!   2Δ̄_b − θ_o and deviation 2σ̄_b (as ½M_p is for α_p, β_p: Xu et al. 2011 eq. 7), the 2
//!   eq. 29's and Zinke et al. 2008's f_back = 2Ā_b g(θ_h − Δ̄_b, σ̄_b²)/(π cos²θ_d)
//!   ([`BACK_SCALE`]), and 𝒩^L the
//!   overlap of the light's azimuthal spread with s_b = 1/π on the backward half circle around
//!   φ_o: (π − |δ|)/π² for the scattered light, P(λ′, δ)/π for the direct light (which Zinke's
//!   F_direct also back-scatters, with σ = λ_j/√2).
//!
//! Where the paper divides by cos θ_j (the narrow limit of the spread's normalisation) we divide
//! by the exact Z(θ_j, σ) of [`crate::tables::spread`]: cos θ_j overstated a wide sky above hanging
//! hair twice over against the brute force.
//!
//! Ā_b, Δ̄_b, σ̄_b are taken at the θ_d of the light's centre, (θ_o − θ_j)/2 (eqs. 29–31 as
//! printed, Ā_b at each quadrature node and Δ̃_b, σ̃_b averaged over θ_j ± σ, were tried: the
//! agreement with the brute force in tests/multiple.rs moved by under 2 % and shading took 24 %
//! longer); all outer integrals use the linear quadrature of §4.2.2. Eccentricity is ignored
//! here (Zinke's model is for circular fibers). Channels share one σ_f, the mean of theirs
//! weighted by their scattered shares.

use crate::angles::Outgoing;
use crate::angles::wrap_pi;
use crate::frame::shadows::ShadowOptions;
use crate::srbf::cg_lobes::r_coefficients_in;
use crate::srbf::circular_gaussian as cg;
use crate::srbf::forward_scattering::{Forward, forward};
use crate::srbf::quadrature::Window;
use crate::srbf::single_scattering::{LocalLight, ShadingFiber};
use crate::tables::absorption_axis;
use crate::tables::back_scattering::{Averages, BackScatteringTables};
use crate::tables::cg_integrals::{FresnelRow, Tables};
use crate::tables::half_circle::HalfCircle;
use crate::tables::lobe_table::AzimuthalLobes;
use crate::tables::spread::SpreadNormalisation;
use cuticle_fiber::Lobe;
use cuticle_fiber::math::sin_cos_quadrant;
use cuticle_fiber::models::marschner2003::MarschnerParams;
use glam::DVec3;
use std::f64::consts::{FRAC_1_SQRT_2, PI};

/// Scattered shares below this skip the global and scattered local terms.
const NEGLIGIBLE: f64 = 1e-5;

/// What [`forward`] gives a light that crosses no fiber (T̃ = 1).
const UNSCATTERED: Forward = Forward {
    scattered: 0.0,
    variance: 0.0,
};

/// The 2 of Zinke et al. 2008's f_back = 2Ā_b g(θ_h − Δ̄_b, σ̄_b²)/(π cos²θ_d) and of Xu et
/// al. 2011 eq. 29: with g a unit Gaussian in θ_h, f_back carries 2Ā_b of the power a fiber
/// intercepts, in the crate's units as in theirs (in which single scattering's ½M_p is the
/// unit density in θ_i, and so is ½M_b here). Dropping it, as this module once did, gave half
/// the local term of an exact path trace of a fiber slab (tests/slab.rs).
pub const BACK_SCALE: f64 = 2.0;

/// Everything multiple scattering reads besides the point and its lights.
#[derive(Clone, Copy, Debug)]
pub struct Dual<'a> {
    /// Xu et al. 2011 §5's tables (N_R's Fresnel quintic).
    pub tables: &'a Tables,
    pub half: &'a HalfCircle,
    /// Z(θ_j, σ) of each spread (the narrow limit cos θ_j overstates wide lights at the axis).
    pub spread: &'a SpreadNormalisation,
    /// Decides whether the direct light's local term is worth computing.
    pub shadows: ShadowOptions,
    pub back: &'a BackScatteringTables,
    pub d_b: f64,
    /// Segments m of the linear quadrature.
    pub m: usize,
}

/// What every light of one point shares: its view and its channels' absorption coordinates
/// in the back-scattering tables.
struct PointView {
    outgoing: Outgoing,
    phi_o: f64,
    absorption: [f64; 3],
}

/// ∫ G_j dω of an SRBF exp(κ(ω·ω_j − 1)), κ = 2/λ².
pub fn srbf_integral(lambda: f64) -> f64 {
    let kappa = 2.0 / (lambda * lambda).max(1e-12);
    2.0 * PI * (1.0 - (-2.0 * kappa).exp()) / kappa
}

impl Dual<'_> {
    /// Multiple-scattering radiance toward (θ_o, φ_o) from every light; `lights` carry the
    /// unshadowed coefficients L_j, `transmittance` their T̃_j.
    pub fn shade<L: AzimuthalLobes>(
        &self,
        fiber: ShadingFiber<L>,
        theta_o: f64,
        phi_o: f64,
        lights: &[LocalLight],
        transmittance: &[f32],
    ) -> DVec3 {
        let view = PointView {
            outgoing: Outgoing::new(theta_o),
            phi_o,
            absorption: fiber
                .params
                .mu_a
                .to_array()
                .map(absorption_axis::coordinate),
        };
        lights
            .iter()
            .zip(transmittance)
            .map(|(light, &t)| self.light(fiber, &view, light, t as f64))
            .sum()
    }

    /// One light's global and local terms.
    fn light<L: AzimuthalLobes>(
        &self,
        fiber: ShadingFiber<L>,
        view: &PointView,
        light: &LocalLight,
        t: f64,
    ) -> DVec3 {
        let (outgoing, theta_o) = (view.outgoing, view.outgoing.theta);
        let energy = light.radiance * srbf_integral(light.bandwidth);
        if energy.max_element() <= 0.0 {
            return DVec3::ZERO;
        }
        let delta = wrap_pi(view.phi_o - light.phi);
        // An unshadowed light (T̃ = 1: no optical depth) scatters nothing forward, exactly.
        let fw = if t < 1.0 {
            view.absorption
                .map(|x| forward(t, &self.back.at_coordinate(light.theta, x)))
        } else {
            [UNSCATTERED; 3]
        };
        let scattered = DVec3::from_array(fw.map(|f| f.scattered));
        let direct = self.shadows.passes(t);
        let forward_scattered = scattered.max_element() > NEGLIGIBLE;
        if !direct && !forward_scattered {
            return DVec3::ZERO;
        }
        let light_var = srbf_deviation(light.bandwidth).powi(2);
        let theta_d = 0.5 * (theta_o - light.theta);
        let back = view.absorption.map(|x| self.back.at_coordinate(theta_d, x));
        let mut out = if direct {
            let cos_j = sin_cos_quadrant(light.theta).1.max(1e-4);
            let direct_azimuth = self.half.share(light.bandwidth / cos_j, delta) / PI;
            let sigma_light = light_var.sqrt();
            t * self.d_b * self.local(&back, outgoing, light.theta, sigma_light, direct_azimuth)
                / self.spread.at(light.theta, sigma_light)
        } else {
            DVec3::ZERO
        };
        if forward_scattered {
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
                        * self.local(&back, outgoing, light.theta, sigma_f, scattered_azimuth))
                / self.spread.at(light.theta, sigma_f);
        }
        energy * out
    }

    /// Σ_t ∫ g^u(θ_i; θ_j, σ_f) ½M_t (cos²θ_i/cos²θ_d) 𝒩^G_t dθ_i (eq. 27 without 1/Z).
    fn global<L: AzimuthalLobes>(
        &self,
        fiber: ShadingFiber<L>,
        theta_o: f64,
        theta_j: f64,
        sigma_f: f64,
        delta: f64,
    ) -> DVec3 {
        let w = self.half.cosines(delta);
        let eta = fiber.params.eta;
        let fresnel = self.tables.fresnel_row(eta);
        let lobes = fiber.params.longitudinal();
        let outgoing = Outgoing::new(theta_o);
        MarschnerParams::LOBES
            .into_iter()
            .map(|lobe| {
                let (alpha, beta) = lobes[lobe.index()];
                let window =
                    Window::normal_product(theta_j, sigma_f, 2.0 * alpha - theta_o, 2.0 * beta);
                window.integrate_incident(self.m, &outgoing, |sample| {
                    let theta_d = sample.theta_d;
                    match lobe {
                        Lobe::R => DVec3::splat(r_half(self.tables, fresnel, theta_d, &w)),
                        Lobe::TT => {
                            let tt = fiber.lobes.tt(theta_d);
                            DVec3::from_array(std::array::from_fn(|c| {
                                if tt.weight[c] == 0.0 {
                                    return 0.0;
                                }
                                let bandwidth = tt.bandwidth[c];
                                let [near, far] = self.half.shares(
                                    bandwidth,
                                    [delta - PI - tt.offset[c], delta - PI + tt.offset[c]],
                                );
                                tt.weight[c] * cg::integral(bandwidth) / PI * (near + far)
                            }))
                        }
                        // TRT; Marschner 2003 has no further lobe.
                        _ => {
                            let trt = fiber.lobes.trt(eta, theta_d);
                            trt.weighted_sum(|s, bandwidth| {
                                self.unit_half(bandwidth, delta - trt.centre[s])
                            })
                        }
                    }
                })
            })
            .sum()
    }

    /// (1/π) ∫ over the half circle around `offset` = δ − μ of g^c(φ; μ, λ).
    fn unit_half(&self, bandwidth: f64, offset: f64) -> f64 {
        cg::integral(bandwidth) * self.half.share(bandwidth, offset) / PI
    }

    /// Per channel 2Ā_b 𝒩^L ∫ g^u(θ_i; θ_j, σ) ½M_b (cos²θ_i/cos²θ_d) dθ_i (eq. 29 without
    /// 1/Z), `azimuth` being 𝒩^L and `back` each channel's averages at θ_d of the light.
    fn local(
        &self,
        back: &[Averages; 3],
        outgoing: Outgoing,
        theta_j: f64,
        sigma: f64,
        azimuth: f64,
    ) -> DVec3 {
        if azimuth <= 0.0 {
            return DVec3::ZERO;
        }
        DVec3::from_array(std::array::from_fn(|c| {
            let a = &back[c];
            if a.back <= 0.0 {
                return 0.0;
            }
            let window = Window::normal_product(
                theta_j,
                sigma,
                2.0 * a.back_shift - outgoing.theta,
                2.0 * a.back_width,
            );
            let integral = window.integrate_incident(self.m, &outgoing, |_| DVec3::ONE);
            BACK_SCALE * a.back * azimuth * integral.x
        }))
    }
}

/// 𝒩^G_R = (1/π) Σ_k C_k W_k(δ) (eqs. 13, 28).
fn r_half(tables: &Tables, fresnel: FresnelRow, theta_d: f64, w: &[f64; 7]) -> f64 {
    let c = r_coefficients_in(tables, fresnel, theta_d);
    (1..7).map(|k| c[k] * w[k]).sum::<f64>() / PI
}

/// λ_j/√2: the longitudinal deviation of an SRBF of bandwidth λ_j.
pub fn srbf_deviation(lambda: f64) -> f64 {
    FRAC_1_SQRT_2 * lambda
}
