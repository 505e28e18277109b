//! Single scattering under SRBF lights (Xu et al. 2011 §4.2): for each light j and mode t,
//! ℳ_t = ∫ g_j(θ_i) ½M_t(θ_h) (cos²θ_i / cos²θ_d) 𝒩_t(λ′_j, φ_o − φ_j, θ_d) dθ_i (eq. 11), the
//! inner integral 𝒩_t closed-form from the circular Gaussians (eqs. 12–14, 16, 20) and the outer
//! one by the linear quadrature (§4.2.2); eccentricity through η̄* (eqs. 24–26).

use crate::angles::{Incident, Outgoing};
use crate::srbf::cg_lobes::r_convolved;
use crate::srbf::circular_gaussian::{convolve_sharp, sharpness};
use crate::srbf::quadrature::Window;
use crate::tables::cg_integrals::Tables;
use crate::tables::lobe_table::{AzimuthalLobes, TrtLobes, TtLobes};
use cuticle_fiber::Lobe;
use cuticle_fiber::math::sin_cos_quadrant;
use cuticle_fiber::models::marschner2003::MarschnerParams;
use glam::DVec3;

/// An SRBF light seen from a fiber: its centre's angles in the fiber frame, its bandwidth, and
/// L_j T̃_j, the coefficient times the effective transmittance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LocalLight {
    pub theta: f64,
    pub phi: f64,
    pub bandwidth: f64,
    pub radiance: DVec3,
}

/// A fiber as shading reads it: its parameters and where its TT and TRT lobes come from.
pub struct ShadingFiber<'a, L> {
    pub params: &'a MarschnerParams,
    pub lobes: &'a L,
}

impl<L> Clone for ShadingFiber<'_, L> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<L> Copy for ShadingFiber<'_, L> {}

/// What every quadrature sample of one light shares: the azimuth offsets of eq. 12 and 26.
#[derive(Clone, Copy, Debug)]
struct LightAzimuth {
    cos_delta: f64,
    sin_delta: f64,
    phi_sum: f64,
}

/// Radiance L_o toward ω_o = (θ_o, φ_o) from every light (Xu et al. 2011 eq. 2), with m segments.
/// Lights of zero L_j T̃_j (a fitted map leaves unused lights with zero coefficient) add
/// exactly nothing and are skipped.
pub fn shade<L: AzimuthalLobes>(
    tables: &Tables,
    fiber: ShadingFiber<L>,
    theta_o: f64,
    phi_o: f64,
    lights: &[LocalLight],
    m: usize,
) -> DVec3 {
    lights
        .iter()
        .filter(|light| light.radiance != DVec3::ZERO)
        .map(|light| {
            light.radiance
                * modes(tables, fiber, theta_o, phi_o, light, m)
                    .iter()
                    .sum::<DVec3>()
        })
        .sum()
}

/// ℳ_R, ℳ_TT, ℳ_TRT of one light (eq. 11).
pub fn modes<L: AzimuthalLobes>(
    tables: &Tables,
    fiber: ShadingFiber<L>,
    theta_o: f64,
    phi_o: f64,
    light: &LocalLight,
    m: usize,
) -> [DVec3; 3] {
    let cos_j = sin_cos_quadrant(light.theta).1.max(1e-4);
    let delta = phi_o - light.phi;
    let (sin_delta, cos_delta) = delta.sin_cos();
    let azimuth = LightAzimuth {
        cos_delta,
        sin_delta,
        phi_sum: phi_o + light.phi,
    };
    let lobes = fiber.params.longitudinal();
    let outgoing = Outgoing::new(theta_o);
    let fresnel = tables.fresnel_row(fiber.params.eta);
    MarschnerParams::LOBES.map(|lobe| {
        let (alpha, beta) = lobes[lobe.index()];
        let window = Window::product(
            light.theta,
            light.bandwidth,
            2.0 * alpha - theta_o,
            2.0 * beta,
        );
        window.integrate_incident(m, &outgoing, |s| {
            let Incident { cos_i, theta_d, .. } = *s;
            let lambda = light.bandwidth / (cos_i * cos_j).sqrt();
            match lobe {
                Lobe::R => DVec3::splat(r_convolved(tables, fresnel, theta_d, lambda, delta)),
                Lobe::TT => tt_convolved(&fiber.lobes.tt(theta_d), sharpness(lambda), &azimuth),
                // TRT; Marschner 2003 has no further lobe.
                _ => {
                    let eta = mean_eta_star(tables, fiber.params, lambda, azimuth.phi_sum);
                    trt_convolved(&fiber.lobes.trt(eta, theta_d), sharpness(lambda), &azimuth)
                }
            }
        })
    })
}

/// 𝒩_TT (eq. 12 with 16): each channel's pair of Gaussians at π ± δ against the light's of
/// sharpness κ₁, cos(Δ − π ∓ δ) = −(cos Δ cos δ ± sin Δ sin δ).
fn tt_convolved(tt: &TtLobes, k1: f64, azimuth: &LightAzimuth) -> DVec3 {
    DVec3::from_array(std::array::from_fn(|c| {
        if tt.weight[c] == 0.0 {
            return 0.0;
        }
        let k2 = sharpness(tt.bandwidth[c]);
        let (sin_off, cos_off) = sin_cos_quadrant(tt.offset[c]);
        let (a, b) = (azimuth.cos_delta * cos_off, azimuth.sin_delta * sin_off);
        tt.weight[c] * (convolve_sharp(k1, k2, -(a + b)) + convolve_sharp(k1, k2, -(a - b)))
    }))
}

/// 𝒩_TRT (eq. 12 with 20 and 25): the three slots of each channel; a slot whose bandwidth equals
/// the first channel's (the glints and centre below η′ = 2) reuses its convolution.
fn trt_convolved(trt: &TrtLobes, k1: f64, azimuth: &LightAzimuth) -> DVec3 {
    debug_assert!(trt.centre[1] == -trt.centre[0] && trt.centre[2] == 0.0);
    let (sin_star, cos_star) = sin_cos_quadrant(trt.centre[0]);
    let (a, b) = (azimuth.cos_delta * cos_star, azimuth.sin_delta * sin_star);
    let cos = [a + b, a - b, azimuth.cos_delta];
    trt.weighted_sum(|s, bandwidth| convolve_sharp(k1, sharpness(bandwidth), cos[s]))
}

/// η̄* (eq. 26): η* of eq. 24 averaged over the light's azimuthal Gaussian, with
/// ⟨cos 2φ_h⟩ = 2𝒞₂(λ′, φ_o + φ_j)/Z − 1 from the R-mode table.
pub fn mean_eta_star(tables: &Tables, fiber: &MarschnerParams, lambda: f64, phi_sum: f64) -> f64 {
    if fiber.eccentricity == 1.0 {
        return fiber.eta;
    }
    let (eta1, eta2) = eta_star_extremes(fiber);
    let cos2 = 2.0 * tables.cosine_normalised(lambda, phi_sum)[2] - 1.0;
    (0.5 * ((eta1 + eta2) + cos2 * (eta1 - eta2))).max(1.0 + 1e-6)
}

/// η*₁ and η*₂ of eq. 24, the indices of an eccentric fiber seen along and across its axes.
fn eta_star_extremes(fiber: &MarschnerParams) -> (f64, f64) {
    let (eta, a2) = (fiber.eta, fiber.eccentricity * fiber.eccentricity);
    (
        2.0 * (eta - 1.0) * a2 - eta + 2.0,
        2.0 * (eta - 1.0) / a2 - eta + 2.0,
    )
}

/// The range [`mean_eta_star`] takes values in: η alone for a circular fiber.
pub fn eta_star_range(fiber: &MarschnerParams) -> (f64, f64) {
    if fiber.eccentricity == 1.0 {
        return (fiber.eta, fiber.eta);
    }
    let (eta1, eta2) = eta_star_extremes(fiber);
    let floor = 1.0 + 1e-6;
    (eta1.min(eta2).max(floor), eta1.max(eta2).max(floor))
}

#[cfg(test)]
mod tests {
    use super::{LocalLight, ShadingFiber, modes, shade};
    use crate::scene::hair::HairParams;
    use crate::tables::cg_integrals::Tables;
    use crate::tables::lobe_table::{FittedLobes, LobeTable};
    use cuticle_fiber::models::marschner2003::MarschnerParams;
    use glam::DVec3;

    fn light(theta: f64, phi: f64, radiance: DVec3) -> LocalLight {
        LocalLight {
            theta,
            phi,
            bandwidth: 0.4,
            radiance,
        }
    }

    /// Skipping zero lights gives bit for bit the sum over every light, negative channels kept.
    #[test]
    fn skipping_zero_lights_changes_nothing() {
        let tables = Tables::build();
        let params = HairParams::default().fiber(None);
        let lobes = FittedLobes {
            tables: &tables,
            fiber: &params,
        };
        let fiber = ShadingFiber {
            params: &params,
            lobes: &lobes,
        };
        let lights = [
            light(0.3, 2.5, DVec3::new(2.0, 1.5, 1.0)),
            light(-0.2, 1.0, DVec3::ZERO),
            light(0.1, -2.8, DVec3::new(-0.5, 0.0, 0.7)),
            light(0.6, 0.4, DVec3::ZERO),
        ];
        let (theta_o, phi_o) = (0.2, 0.1);
        let every: DVec3 = lights
            .iter()
            .map(|l| {
                l.radiance
                    * modes(&tables, fiber, theta_o, phi_o, l, 4)
                        .iter()
                        .sum::<DVec3>()
            })
            .sum();
        assert_ne!(every, DVec3::ZERO);
        assert_eq!(shade(&tables, fiber, theta_o, phi_o, &lights, 4), every);
    }

    /// Shading from the lobe table against shading from fits made at every sample, each mode
    /// and channel, circular and eccentric fibers, over views and lights around the fiber:
    /// within 0.5 % of the largest mode of the sweep.
    #[test]
    fn tabulated_lobes_shade_as_fitted_lobes() {
        let tables = Tables::build();
        for eccentricity in [1.0, 0.85] {
            let params = MarschnerParams {
                eccentricity,
                mu_a: DVec3::new(0.15, 0.4, 1.2),
                ..HairParams::default().fiber(None)
            };
            let fitted = FittedLobes {
                tables: &tables,
                fiber: &params,
            };
            let table = LobeTable::build(&tables, &params);
            let tabulated = table.for_fiber(&tables, &params);
            let (mut worst, mut largest) = (0.0f64, 0.0f64);
            for i in 0..9 {
                let theta_o = -1.2 + 0.3 * i as f64;
                for j in 0..12 {
                    let l = light(0.9 - 0.15 * j as f64, -3.0 + 0.5 * j as f64, DVec3::ONE);
                    let phi_o = 0.7 * i as f64 - 2.0;
                    let want = modes(
                        &tables,
                        ShadingFiber {
                            params: &params,
                            lobes: &fitted,
                        },
                        theta_o,
                        phi_o,
                        &l,
                        4,
                    );
                    let got = modes(
                        &tables,
                        ShadingFiber {
                            params: &params,
                            lobes: &tabulated,
                        },
                        theta_o,
                        phi_o,
                        &l,
                        4,
                    );
                    for t in 0..3 {
                        worst = worst.max((got[t] - want[t]).abs().max_element());
                        largest = largest.max(want[t].max_element());
                    }
                }
            }
            assert!(
                worst <= 5e-3 * largest,
                "eccentricity {eccentricity}: {worst} of {largest}"
            );
        }
    }
}
