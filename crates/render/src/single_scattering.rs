//! Single scattering under SRBF lights (seed 004 §4.2): for each light j and mode t,
//! ℳ_t = ∫ g_j(θ_i) ½M_t(θ_h) (cos²θ_i / cos²θ_d) 𝒩_t(λ′_j, φ_o − φ_j, θ_d) dθ_i (eq. 11), the
//! inner integral 𝒩_t closed-form from the circular Gaussians (eqs. 12–14, 16, 20) and the outer
//! one by the linear quadrature (§4.2.2); eccentricity through η̄* (eqs. 24–26).

use crate::cg_lobes::{Geometry, TrtShape, r_convolved, trt_fit, tt_fit};
use crate::hair::caustic_bandwidth;
use crate::quadrature::Window;
use crate::tables::Tables;
use cuticle_fiber::marschner2003::MarschnerParams;
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

/// The inner integral 𝒩_t of one mode at one θ_i sample.
#[derive(Clone, Copy, Debug)]
struct Sample {
    theta_d: f64,
    lambda: f64,
    delta: f64,
    phi_sum: f64,
}

/// Radiance L_o toward ω_o = (θ_o, φ_o) from every light (seed 004 eq. 2), with m segments.
/// Lights of zero L_j T̃_j (a fitted map leaves unused lights with zero coefficient) add
/// exactly nothing and are skipped.
pub fn shade(
    tables: &Tables,
    fiber: &MarschnerParams,
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
pub fn modes(
    tables: &Tables,
    fiber: &MarschnerParams,
    theta_o: f64,
    phi_o: f64,
    light: &LocalLight,
    m: usize,
) -> [DVec3; 3] {
    let cos_j = light.theta.cos().max(1e-4);
    let lobes = fiber.longitudinal();
    std::array::from_fn(|t| {
        let (alpha, beta) = lobes[t];
        let window = Window::product(
            light.theta,
            light.bandwidth,
            2.0 * alpha - theta_o,
            2.0 * beta,
        );
        if window.scale < 1e-12 {
            return DVec3::ZERO;
        }
        window.integrate(m, |theta_i| {
            let cos_i = theta_i.cos();
            if cos_i <= 1e-6 {
                return DVec3::ZERO;
            }
            let theta_d = 0.5 * (theta_o - theta_i);
            let s = Sample {
                theta_d,
                lambda: light.bandwidth / (cos_i * cos_j).sqrt(),
                delta: phi_o - light.phi,
                phi_sum: phi_o + light.phi,
            };
            inner(tables, fiber, t, s) * (cos_i * cos_i / theta_d.cos().powi(2))
        })
    })
}

/// 𝒩_t at one sample (eqs. 14, 12 with 16, 12 with 20 and 25).
fn inner(tables: &Tables, fiber: &MarschnerParams, t: usize, s: Sample) -> DVec3 {
    match t {
        0 => DVec3::splat(r_convolved(tables, fiber.eta, s.theta_d, s.lambda, s.delta)),
        1 => {
            let g = Geometry::new(tables, fiber.eta, s.theta_d);
            DVec3::from_array(std::array::from_fn(|c| {
                tt_fit(&g, fiber.mu_a[c]).convolve(s.lambda, s.delta)
            }))
        }
        _ => {
            let eta = mean_eta_star(tables, fiber, s.lambda, s.phi_sum);
            let shape = TrtShape {
                caustic_bandwidth: caustic_bandwidth(fiber),
                caustic_fade: fiber.caustic_fade,
            };
            let g = Geometry::new(tables, eta, s.theta_d);
            DVec3::from_array(std::array::from_fn(|c| {
                trt_fit(&g, fiber.mu_a[c], shape)
                    .iter()
                    .map(|l| l.convolve(s.lambda, s.delta))
                    .sum()
            }))
        }
    }
}

/// η̄* (eq. 26): η* of eq. 24 averaged over the light's azimuthal Gaussian, with
/// ⟨cos 2φ_h⟩ = 2𝒞₂(λ′, φ_o + φ_j)/Z − 1 from the R-mode table.
pub fn mean_eta_star(tables: &Tables, fiber: &MarschnerParams, lambda: f64, phi_sum: f64) -> f64 {
    if fiber.eccentricity == 1.0 {
        return fiber.eta;
    }
    let (eta, a2) = (fiber.eta, fiber.eccentricity * fiber.eccentricity);
    let eta1 = 2.0 * (eta - 1.0) * a2 - eta + 2.0;
    let eta2 = 2.0 * (eta - 1.0) / a2 - eta + 2.0;
    let cos2 = 2.0 * tables.cosine_normalised(lambda, phi_sum)[2] - 1.0;
    (0.5 * ((eta1 + eta2) + cos2 * (eta1 - eta2))).max(1.0 + 1e-6)
}

#[cfg(test)]
mod tests {
    use super::{LocalLight, modes, shade};
    use crate::hair::HairParams;
    use crate::tables::Tables;
    use glam::DVec3;

    /// Skipping zero lights gives bit for bit the sum over every light, negative channels kept.
    #[test]
    fn skipping_zero_lights_changes_nothing() {
        let tables = Tables::build();
        let fiber = HairParams::default().fiber(None);
        let light = |theta: f64, phi: f64, radiance: DVec3| LocalLight {
            theta,
            phi,
            bandwidth: 0.4,
            radiance,
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
                    * modes(&tables, &fiber, theta_o, phi_o, l, 4)
                        .iter()
                        .sum::<DVec3>()
            })
            .sum();
        assert_ne!(every, DVec3::ZERO);
        assert_eq!(shade(&tables, &fiber, theta_o, phi_o, &lights, 4), every);
    }
}
