//! Multiple scattering of the brute-force reference: the dual-scattering terms of
//! [`crate::srbf::dual_scattering`] (Zinke et al. 2008; Xu et al. 2011 §4.3) for directional
//! lights, from the exact functions instead of circular Gaussians.
//!
//! A directional light k (angles θ_k, φ_k in the fiber frame, power E_k = L Δω, direct
//! transmittance T̃_k) is an SRBF in the limit λ → 0: E_k stands for L_j ∫G_j dω, and its
//! longitudinal and azimuthal windows become deltas at θ_k and φ_k. Per channel, with
//! δ = φ_o − φ_k, θ_d = (θ_o − θ_k)/2 and (s, σ̄_f²) = forward(T̃_k, averages at θ_k)
//! ([`crate::srbf::forward_scattering`]), the light adds E_k times
//! - 2 T̃_k d_b Ā_b ½M_b(θ_k) (cos²θ_k / cos²θ_d) 𝟙(|δ| < π/2)/(π cos θ_k), the local term of the
//!   direct light (eq. 29 without a window: P(λ → 0, δ)/π is Zinke's s_b on the backward half
//!   circle);
//!
//! and, divided by the spread's normalisation Z(θ_k, σ̄_f) ([`crate::tables::spread`]; cos θ_k in
//! Zinke's narrow limit),
//! - s Σ_p ∫ g^u(θ_i; θ_k, σ̄_f) ½M_p(θ_i) (cos²θ_i / cos²θ_d(θ_i)) 𝒩^G_p(δ, θ_d(θ_i)) dθ_i, the
//!   global term (eqs. 27–28), with ½M_p the exact Marschner lobe as a density in θ_i (mean
//!   2α_p − θ_o, deviation 2β_p) and 𝒩^G_p the half-circle average of the exact N_p
//!   ([`crate::brute::half_circle`]);
//! - 2 s d_b Ā_b ((π − |δ|)/π²) ∫ g^u(θ_i; θ_k, σ̄_f) ½M_b(θ_i) (cos²θ_i / cos²θ_d(θ_i)) dθ_i,
//!   the local term of the forward-scattered light (eqs. 29–31),
//!
//! the 2 being f_back's ([`crate::srbf::dual_scattering::BACK_SCALE`]), with Ā_b, Δ̄_b, σ̄_b
//! from the back-scattering tables at the light's θ_d, as the SRBF path takes
//! them, and ½M_b the normal density of mean 2Δ̄_b − θ_o and deviation 2σ̄_b. Each θ_i integral
//! is a product of two normal densities (a normal density again, in closed form) times a smooth
//! factor, by 8-point Gauss–Legendre over the product's mean ± 4 deviations within
//! [−π/2, π/2] (this file's tests bound it against a fine rule on narrow, wide and clipped
//! windows).
//! Unlike the SRBF path, each channel keeps its own σ̄_f. Fibers are circular, as in Zinke's
//! model and the SRBF path.

use crate::angles::{HALF_PI, wrap_pi};
use crate::brute::half_circle::ExactHalfCircle;
use crate::brute::single_scattering::LocalDirectional;
use crate::srbf::dual_scattering::BACK_SCALE;
use crate::srbf::forward_scattering::{Forward, forward};
use crate::tables::back_scattering::BackScatteringTables;
use crate::tables::spread::SpreadNormalisation;
use cuticle_fiber::FiberAngles;
use cuticle_fiber::math::{GaussLegendre, normal_pdf};
use cuticle_fiber::models::marschner2003::MarschnerParams;
use glam::DVec3;
use std::f64::consts::PI;

/// Scattered shares below this skip the global and scattered local terms.
const NEGLIGIBLE: f64 = 1e-5;
/// Gauss–Legendre nodes per θ_i integral.
const NODES: usize = 8;
/// Half-width of a θ_i integral, in deviations of its window.
const REACH: f64 = 4.0;

/// Everything the brute-force multiple scattering reads besides the point and its lights.
#[derive(Clone, Copy, Debug)]
pub struct BruteDual<'a> {
    /// 𝒩^G_p of the fibers' η.
    pub half: &'a ExactHalfCircle,
    pub back: &'a BackScatteringTables,
    /// Z(θ_k, σ̄_f) of the forward-scattered spreads ([`crate::tables::spread`]).
    pub spread: &'a SpreadNormalisation,
    pub d_b: f64,
}

/// A normal density in θ.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Normal {
    pub mean: f64,
    pub deviation: f64,
}

impl Normal {
    pub fn density(&self, x: f64) -> f64 {
        normal_pdf((x - self.mean) / self.deviation) / self.deviation
    }
}

/// ∫_{−π/2}^{π/2} a(θ) b(θ) f(θ) dθ: a b = N(μ_a − μ_b; 0, μ_a² + σ_b²) times the normal density
/// of mean (μ_a σ_b² + μ_b μ_a²)/(μ_a² + σ_b²) and variance μ_a²σ_b²/(μ_a² + σ_b²).
pub fn product_integral(a: Normal, b: Normal, f: impl Fn(f64) -> f64) -> f64 {
    let (va, vb) = (a.deviation.powi(2), b.deviation.powi(2));
    let sum = va + vb;
    let scale = normal_pdf((a.mean - b.mean) / sum.sqrt()) / sum.sqrt();
    let product = Normal {
        mean: (a.mean * vb + b.mean * va) / sum,
        deviation: (va * vb / sum).sqrt(),
    };
    if product.deviation < 1e-9 {
        return if product.mean.abs() < HALF_PI {
            scale * f(product.mean)
        } else {
            0.0
        };
    }
    let lo = (product.mean - REACH * product.deviation).max(-HALF_PI);
    let hi = (product.mean + REACH * product.deviation).min(HALF_PI);
    if lo >= hi {
        return 0.0;
    }
    scale * GaussLegendre::cached(NODES).integrate(lo, hi, |x| product.density(x) * f(x))
}

/// cos²θ_i / cos²θ_d with θ_d = (θ_o − θ_i)/2.
fn cos_ratio(theta_o: f64, theta_i: f64) -> f64 {
    theta_i.cos().powi(2) / (0.5 * (theta_o - theta_i)).cos().powi(2).max(1e-12)
}

impl BruteDual<'_> {
    /// Multiple-scattering radiance toward `ao` from every light, `transmittance` holding their
    /// T̃_k.
    pub fn shade(
        &self,
        fiber: &MarschnerParams,
        ao: FiberAngles,
        lights: &[LocalDirectional],
        transmittance: &[f32],
    ) -> DVec3 {
        lights
            .iter()
            .zip(transmittance)
            .map(|(light, &t)| self.light(fiber, ao, light, t as f64))
            .sum()
    }

    /// One light's global and local terms.
    pub fn light(
        &self,
        fiber: &MarschnerParams,
        ao: FiberAngles,
        light: &LocalDirectional,
        t: f64,
    ) -> DVec3 {
        if light.power.max_element() <= 0.0 {
            return DVec3::ZERO;
        }
        let theta_k = light.angles.theta;
        let delta = wrap_pi(ao.phi - light.angles.phi).abs();
        let terms = std::array::from_fn(|c| self.channel(fiber, c, ao.theta, theta_k, delta, t));
        light.power * DVec3::from_array(terms)
    }

    /// The forward-scattered share of channel `c` when it is not negligible. An unoccluded
    /// light has none ([`forward`]), and needs no lookup.
    fn scattered(&self, mu_a: f64, theta_k: f64, t: f64) -> Option<Forward> {
        (t < 1.0)
            .then(|| forward(t, &self.back.at(theta_k, mu_a)))
            .filter(|f| f.scattered > NEGLIGIBLE)
    }

    /// Channel `c`'s three terms, before the factor E_k: the direct light's divided by cos θ_k
    /// (exact for a directional light), the spread ones by Z(θ_k, σ̄_f).
    fn channel(
        &self,
        fiber: &MarschnerParams,
        c: usize,
        theta_o: f64,
        theta_k: f64,
        delta: f64,
        t: f64,
    ) -> f64 {
        let mu_a = fiber.mu_a[c];
        let scattered = self.scattered(mu_a, theta_k, t);
        let backward = delta < HALF_PI && t > 0.0;
        if scattered.is_none() && !backward {
            return 0.0;
        }
        let a = self.back.at(0.5 * (theta_o - theta_k), mu_a);
        let back_lobe = Normal {
            mean: 2.0 * a.back_shift - theta_o,
            deviation: 2.0 * a.back_width,
        };
        let mut out = 0.0;
        if backward {
            out += BACK_SCALE
                * t
                * self.d_b
                * a.back
                * back_lobe.density(theta_k)
                * cos_ratio(theta_o, theta_k)
                / (PI * theta_k.cos().max(1e-4));
        }
        if let Some(fw) = scattered {
            let spread = Normal {
                mean: theta_k,
                deviation: fw.variance.sqrt(),
            };
            let local = BACK_SCALE * self.d_b * a.back * (PI - delta) / (PI * PI)
                * product_integral(spread, back_lobe, |x| cos_ratio(theta_o, x));
            out += fw.scattered * (self.global(fiber, c, theta_o, spread, delta) + local)
                / self.spread.at(theta_k, spread.deviation);
        }
        out
    }

    /// Σ_p ∫ g^u ½M_p (cos²θ_i / cos²θ_d) 𝒩^G_p dθ_i for channel `c` (eq. 27 without s and
    /// 1/Z).
    fn global(
        &self,
        fiber: &MarschnerParams,
        c: usize,
        theta_o: f64,
        spread: Normal,
        delta: f64,
    ) -> f64 {
        let column = ExactHalfCircle::column(fiber.mu_a[c], delta);
        let lobes = fiber.longitudinal();
        (0..3)
            .map(|p| {
                let (alpha, beta) = lobes[p];
                let lobe = Normal {
                    mean: 2.0 * alpha - theta_o,
                    deviation: 2.0 * beta,
                };
                product_integral(spread, lobe, |x| {
                    cos_ratio(theta_o, x) * self.half.at(p, 0.5 * (theta_o - x), &column)
                })
            })
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::brute::half_circle::half_average;
    use crate::scene::hair::HairParams;

    /// Fine midpoint rule over θ_i ∈ [−π/2, π/2].
    fn fine(f: impl Fn(f64) -> f64) -> f64 {
        let n = 600;
        let d = PI / n as f64;
        (0..n)
            .map(|i| f(-HALF_PI + (i as f64 + 0.5) * d))
            .sum::<f64>()
            * d
    }

    /// The module's formulas for one light and channel, evaluated directly: fine quadrature
    /// in θ_i, 𝒩^G_p integrated from the exact lobes at every θ_i (no table).
    fn direct(
        setup: &(MarschnerParams, BackScatteringTables, f64),
        c: usize,
        ao: FiberAngles,
        light: FiberAngles,
        t: f64,
    ) -> f64 {
        let (fiber, back, d_b) = setup;
        let mu = fiber.mu_a[c];
        let delta = wrap_pi(ao.phi - light.phi).abs();
        let a = back.at(0.5 * (ao.theta - light.theta), mu);
        let gauss = |x: f64, m: f64, s: f64| {
            (-(x - m).powi(2) / (2.0 * s * s)).exp() / (s * (2.0 * PI).sqrt())
        };
        let ratio = |x: f64| x.cos().powi(2) / (0.5 * (ao.theta - x)).cos().powi(2);
        let back_lobe = |x: f64| gauss(x, 2.0 * a.back_shift - ao.theta, 2.0 * a.back_width);
        let mut out = 0.0;
        if delta < HALF_PI {
            out += BACK_SCALE * t * d_b * a.back * back_lobe(light.theta) * ratio(light.theta)
                / (PI * light.theta.cos());
        }
        let fw = forward(t, &back.at(light.theta, mu));
        if fw.scattered > 0.0 {
            let sf = fw.variance.sqrt();
            let lobes = fiber.longitudinal();
            let global = fine(|x| {
                let g = gauss(x, light.theta, sf);
                if g < 1e-9 {
                    return 0.0;
                }
                let theta_d = 0.5 * (ao.theta - x);
                (0..3)
                    .map(|p| {
                        let (alpha, beta) = lobes[p];
                        let n = half_average(p as u32, fiber.eta, theta_d, mu, delta);
                        g * gauss(x, 2.0 * alpha - ao.theta, 2.0 * beta) * ratio(x) * n
                    })
                    .sum()
            });
            let local = BACK_SCALE * d_b * a.back * (PI - delta) / (PI * PI)
                * fine(|x| gauss(x, light.theta, sf) * back_lobe(x) * ratio(x));
            let norm = fine(|x| gauss(x, light.theta, sf) * x.cos());
            out += fw.scattered * (global + local) / norm;
        }
        out
    }

    fn setup(mu_a: [f64; 3]) -> (MarschnerParams, BackScatteringTables, f64) {
        let hair = HairParams {
            mu_a: Some(mu_a),
            ..HairParams::default()
        };
        let fiber = hair.fiber(None);
        (fiber, BackScatteringTables::build(&fiber), hair.d_b)
    }

    /// The tabulated, Gauss–Legendre terms against [`direct`], per channel, for lights in
    /// front (δ ≈ 0: direct local term) and behind (δ ≈ π: global term) the viewer, lit and
    /// deep in the hair: within 1% of each value (measured up to 0.5%: the tables'
    /// interpolation), and the scattered terms really are present where T̃ is small.
    #[test]
    fn terms_match_a_direct_evaluation_of_their_formulas() {
        let s = setup([0.15, 0.4, 1.2]);
        let half = ExactHalfCircle::build(s.0.eta);
        let spread = SpreadNormalisation::build();
        let dual = BruteDual {
            half: &half,
            back: &s.1,
            spread: &spread,
            d_b: s.2,
        };
        let ao = FiberAngles::new(0.2, 0.3);
        let cases = [
            (FiberAngles::new(-0.4, 0.5), 1.0),
            (FiberAngles::new(-0.1, 0.6), 0.02),
            (FiberAngles::new(0.35, -2.6), 0.1),
            (FiberAngles::new(-0.7, 2.9), 0.004),
        ];
        for (k, &(light, t)) in cases.iter().enumerate() {
            let local = LocalDirectional {
                angles: light,
                power: DVec3::ONE,
            };
            let got = dual.light(&s.0, ao, &local, t);
            for c in 0..3 {
                let want = direct(&s, c, ao, light, t);
                assert!(
                    (got[c] - want).abs() <= 0.01 * want + 1e-12,
                    "case {k} channel {c}: {} vs direct {want}",
                    got[c]
                );
            }
            // Where T̃ is small the forward-scattered terms add light beyond the direct local
            // term; behind the viewer (cases 2, 3: |δ| > π/2) they are all there is.
            if k > 0 {
                let direct_only = t * dual.light(&s.0, ao, &local, 1.0).x;
                let behind = wrap_pi(ao.phi - light.phi).abs() > HALF_PI;
                assert_eq!(behind, direct_only == 0.0, "case {k}");
                assert!(
                    got.x > 1.01 * direct_only && got.x > 0.0,
                    "case {k}: {got} vs {direct_only}"
                );
            }
        }
    }

    /// The closed-form product of normals integrates like a fine rule, for a narrow product,
    /// a wide one clipped at ±π/2, and a collapsed one (μ_a = 0: the other density at μ_a).
    #[test]
    fn product_integral_matches_a_fine_rule() {
        let f = |x: f64| x.cos().powi(2) * (1.0 + 0.3 * x);
        for (a, b) in [
            ((0.3, 0.05), (-0.1, 0.13)),
            ((1.2, 0.6), (0.9, 0.5)),
            ((-0.5, 0.2), (0.4, 0.6)),
        ] {
            let (a, b) = (
                Normal {
                    mean: a.0,
                    deviation: a.1,
                },
                Normal {
                    mean: b.0,
                    deviation: b.1,
                },
            );
            let want = fine(|x| a.density(x) * b.density(x) * f(x));
            let got = product_integral(a, b, f);
            assert!((got / want - 1.0).abs() < 4e-3, "{got} vs {want}");
        }
        let b = Normal {
            mean: 0.1,
            deviation: 0.3,
        };
        let delta = Normal {
            mean: 0.4,
            deviation: 0.0,
        };
        let got = product_integral(delta, b, f);
        assert!((got / (b.density(0.4) * f(0.4)) - 1.0).abs() < 1e-12);
    }
}
