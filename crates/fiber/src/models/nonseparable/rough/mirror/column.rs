//! R's light in one φ column, in micro-normal space: what the rough surface reflects into
//! each direction ω_o, summed over the offsets, whose moments in sin θ_o give R's
//! longitudinal lobe at that azimuth (docs/departures/18-r-column-lobe.md).
//!
//! For light at ω_i the micro-normal that reflects it into ω_o is the half vector
//! m = (ω_i + ω_o)/|ω_i + ω_o|, the same for every offset; the offsets differ in how likely
//! their surface is to present it. Per unit solid angle of ω_o, the reflection at offset h is
//! D(m) G1(ω_i) G1(ω_o) F(ω_i·m) / (4 ω_i·n) (Walter et al. 2007 eqs. 20 and 41 with the
//! visible-normal weighting the simulator draws, ω_i·m = ω_o·m), D the Beckmann distribution
//! of slopes s = (m·t, m·b)/(m·n) about the scale's normal n at that offset,
//! D = exp(−|s|²/β²) / (πβ² (m·n)⁴), and zero where ω_o leaves below the macro surface or
//! ω_i meets the back of the scale. Over the fiber's width the light per unit solid angle is
//! L(ω_o) = ½ ∫ (that) dh, with h = sin γ; the integrand is concentrated where n(γ) turns
//! toward m, within a few slope deviations of m's own azimuth about the axis.
//!
//! One offset's slope spread, taken as a Gaussian about its smooth mirror, cannot give these
//! moments: at grazing offsets the light that the b-slope carries to a neighbouring azimuth
//! has a narrower spread in θ_o than the offset's own (it leaves by the micro-normals of that
//! azimuth), so a mixture of offsets' Gaussians is too wide near φ = ±π.

use crate::lobes::sine_lobe::SineMoments;
use crate::math::{GaussLegendre, exp_fast, sin_cos_quadrant};
use crate::optics::beckmann::smith_g1;
use crate::optics::fresnel::fresnel_dielectric;
use glam::DVec3;
use std::f64::consts::{FRAC_1_SQRT_2, FRAC_PI_2, PI};

/// Gauss–Legendre nodes over the offsets that present the half vector, and over θ_o.
const OFFSET_NODES: usize = 12;
const THETA_NODES: usize = 24;
/// Slope deviations on either side of the half vector's azimuth that the offsets span.
const OFFSET_REACH: f64 = 6.0;

/// The fiber's geometry at one incidence: scales tilted by α, Beckmann roughness β, index η.
#[derive(Clone, Copy, Debug)]
pub struct RoughSurface {
    pub alpha: f64,
    pub beta: f64,
    pub eta: f64,
    sin_alpha: f64,
    cos_alpha: f64,
}

/// The light R reflects into one φ column: its energy ∫ L cos θ_o dθ_o (N_R at that φ) and
/// the mean and variance of sin θ_o under it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReflectedColumn {
    pub energy: f64,
    pub sine: SineMoments,
}

impl RoughSurface {
    pub fn new(alpha: f64, beta: f64, eta: f64) -> Self {
        let (sin_alpha, cos_alpha) = alpha.sin_cos();
        Self {
            alpha,
            beta,
            eta,
            sin_alpha,
            cos_alpha,
        }
    }

    /// L(ω_o) (module docs) for the incident and outgoing unit vectors (fiber axis x, the
    /// incident direction in the xy plane): per unit solid angle of ω_o and per unit incident
    /// power on the fiber's width.
    fn reflected(&self, wi: DVec3, o: DVec3) -> f64 {
        let sum = wi + o;
        if sum.length_squared() < 1e-24 {
            return 0.0;
        }
        let m = sum.normalize();
        // m's azimuth about the axis, in the parametrisation of the scale normals n(γ).
        let r = m.y.hypot(m.z);
        let zeta = (-m.z).atan2(m.y);
        let reach = OFFSET_REACH * self.beta * FRAC_1_SQRT_2 / r.max(1e-3);
        let Some((lo, hi)) = self.offsets_lit(wi, o, zeta, reach) else {
            return 0.0;
        };
        let rule = GaussLegendre::cached(OFFSET_NODES);
        0.5 * rule.integrate(lo, hi, |gamma| self.at_offset(wi, o, m, gamma))
    }

    /// The offsets γ within `reach` of `zeta` where the reflection into ω_o is not cut off,
    /// as one interval: on the fiber (|γ| < π/2), ω_i on the front of the scale
    /// (ω_i·n > 0), ω_o above the macro surface and on the front of the scale (ω_o·n > 0,
    /// where G1(ω_o) vanishes). Each cut is an arc cos(γ − c) > k; integrating between them,
    /// rather than across, keeps the Gauss–Legendre rule on a smooth integrand where the
    /// offsets graze. `None` where nothing is left.
    fn offsets_lit(&self, wi: DVec3, o: DVec3, zeta: f64, reach: f64) -> Option<(f64, f64)> {
        let (sa, ca) = (self.sin_alpha, self.cos_alpha);
        let (mut lo, mut hi) = (
            (zeta - reach).max(-FRAC_PI_2),
            (zeta + reach).min(FRAC_PI_2),
        );
        // ω·n(γ) = ω_x sin α + cos α ρ cos(γ + ψ) for ω = (ω_x, ρ cos ψ, ρ sin ψ); the macro
        // surface's normal is n at α = 0.
        let o_rho = o.y.hypot(o.z);
        let psi = o.z.atan2(o.y);
        let arcs = [
            (0.0, -(wi.x * sa) / (wi.y * ca)),
            (-psi, 0.0),
            (-psi, -(o.x * sa) / (ca * o_rho.max(1e-300))),
        ];
        for (centre, k) in arcs {
            if k >= 1.0 {
                return None;
            }
            if k <= -1.0 {
                continue;
            }
            // The arc's centre taken within π of ζ, where the window lies.
            let centre = zeta + crate::geometry::frame::wrap_pi(centre - zeta);
            let half = k.acos();
            lo = lo.max(centre - half);
            hi = hi.min(centre + half);
        }
        (lo < hi).then_some((lo, hi))
    }

    /// The reflection into ω_o at the offset at angle γ per unit solid angle (module docs),
    /// times dh/dγ = cos γ.
    fn at_offset(&self, wi: DVec3, o: DVec3, m: DVec3, gamma: f64) -> f64 {
        let (sa, ca) = (self.sin_alpha, self.cos_alpha);
        let (sg, cg) = sin_cos_quadrant(gamma);
        let n = DVec3::new(sa, ca * cg, -ca * sg);
        let cos_i = wi.dot(n);
        let mn = m.dot(n);
        if cos_i <= 0.0 || mn <= 0.0 || o.dot(DVec3::new(0.0, cg, -sg)) <= 0.0 {
            return 0.0;
        }
        let t = DVec3::new(ca, -sa * cg, sa * sg);
        let b = DVec3::new(0.0, sg, cg);
        let (st, sb) = (m.dot(t) / mn, m.dot(b) / mn);
        let beta2 = self.beta * self.beta;
        let d = exp_fast(-(st * st + sb * sb) / beta2) / (PI * beta2 * mn.powi(4));
        let c = wi.dot(m);
        let g = smith_g1(cos_i, c, self.beta) * smith_g1(o.dot(n), o.dot(m), self.beta);
        d * g * fresnel_dielectric(c, self.eta) * cg / (4.0 * cos_i)
    }

    /// The column at φ over θ_o ∈ [lo, hi] (which should hold all of its light): `None`
    /// where no light reaches it.
    pub fn column(&self, theta_i: f64, phi: f64, lo: f64, hi: f64) -> Option<ReflectedColumn> {
        let rule = GaussLegendre::cached(THETA_NODES);
        let (mid, half) = (0.5 * (lo + hi), 0.5 * (hi - lo));
        let wi = incident(theta_i);
        let (sp, cp) = phi.sin_cos();
        let (mut m0, mut m1, mut m2) = (0.0, 0.0, 0.0);
        for (x, w) in rule.nodes.iter().zip(&rule.weights) {
            let (s, c) = sin_cos_quadrant(mid + half * x);
            let o = DVec3::new(s, c * cp, c * sp);
            let weight = w * half * c * self.reflected(wi, o);
            m0 += weight;
            m1 += weight * s;
            m2 += weight * s * s;
        }
        (m0 > 0.0).then(|| {
            let mean = m1 / m0;
            ReflectedColumn {
                energy: m0,
                sine: SineMoments {
                    mean,
                    variance: (m2 / m0 - mean * mean).max(0.0),
                },
            }
        })
    }
}

/// The unit vector toward the light at θ_i, in the plane φ = 0.
fn incident(theta_i: f64) -> DVec3 {
    let (s, c) = theta_i.sin_cos();
    DVec3::new(s, c, 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::frame::wrap_pi;
    use crate::math::unit_normal_midpoints;

    const ETA: f64 = 1.55;

    /// The column at φ₀ the simulator's way: one micro-facet reflection at each of 2,000
    /// offsets and 64² equal-probability slopes per offset with
    /// [`super::super::reflection_moments`]'s weights, the reflections whose azimuth falls
    /// within `half_width` of φ₀ kept.
    fn binned(surface: &RoughSurface, theta_i: f64, phi0: f64, half_width: f64) -> ReflectedColumn {
        const OFFSETS: usize = 2000;
        let slopes = unit_normal_midpoints::<64>();
        let RoughSurface {
            alpha, beta, eta, ..
        } = *surface;
        let (sa, ca) = alpha.sin_cos();
        let wi = DVec3::new(theta_i.sin(), theta_i.cos(), 0.0);
        let sigma = beta * FRAC_1_SQRT_2;
        let (mut m0, mut m1, mut m2) = (0.0, 0.0, 0.0);
        for k in 0..OFFSETS {
            let d_gamma = PI / OFFSETS as f64;
            let gamma = -FRAC_PI_2 + (k as f64 + 0.5) * d_gamma;
            let (sg, cg) = gamma.sin_cos();
            let n = DVec3::new(sa, ca * cg, -ca * sg);
            let t = DVec3::new(ca, -sa * cg, sa * sg);
            let b = DVec3::new(0.0, sg, cg);
            let cos_i = wi.dot(n);
            if cos_i <= 0.0 {
                continue;
            }
            let per_slope = 0.5 * cg * d_gamma / (slopes.len() * slopes.len()) as f64;
            for &st in &slopes {
                for &sb in &slopes {
                    let m = (n + sigma * (st * t + sb * b)).normalize();
                    let c = wi.dot(m);
                    let o = 2.0 * c * m - wi;
                    if c <= 0.0 || o.dot(DVec3::new(0.0, cg, -sg)) <= 0.0 {
                        continue;
                    }
                    if wrap_pi(o.z.atan2(o.y) - phi0).abs() > half_width {
                        continue;
                    }
                    let g = smith_g1(cos_i, c, beta) * smith_g1(o.dot(n), o.dot(m), beta);
                    let w = per_slope * c * g * fresnel_dielectric(c, eta) / (cos_i * m.dot(n));
                    m0 += w;
                    m1 += w * o.x;
                    m2 += w * o.x * o.x;
                }
            }
        }
        let mean = m1 / m0;
        ReflectedColumn {
            energy: m0 / (2.0 * half_width),
            sine: SineMoments {
                mean,
                variance: m2 / m0 - mean * mean,
            },
        }
    }

    /// The quadrature in micro-normal space against the simulator's way of reflecting, binned:
    /// the same energy per radian of φ, mean sine and variance, at central and grazing
    /// columns, for scales tilted either way. (Integrated across the cuts instead of between
    /// them, the grazing column's variance came out 6 % high.)
    #[test]
    fn column_is_what_the_slopes_reflect_there() {
        for (theta_i, alpha_deg, beta, phi) in [
            (1.1, -4.0, 0.08, 2.75),
            (1.1, -4.0, 0.08, -1.5),
            (0.75, 2.0, 0.04, -2.0),
            (0.25, 0.0, 0.08, 2.9),
            (1.4, 0.0, 0.04, 2.945),
        ] {
            let surface = RoughSurface::new(f64::to_radians(alpha_deg), beta, ETA);
            let reference = binned(&surface, theta_i, phi, 0.01);
            let (want, sd) = (reference.sine, reference.sine.variance.sqrt());
            let (lo, hi) = (want.mean - 8.0 * sd, want.mean + 8.0 * sd);
            let ours = surface
                .column(theta_i, phi, lo.max(-1.0).asin(), hi.min(1.0).asin())
                .unwrap();
            let label = format!("θ_i {theta_i} α {alpha_deg}° β {beta} φ {phi}");
            println!("{label}: {ours:?} against {reference:?}");
            assert!(
                (ours.energy / reference.energy - 1.0).abs() < 0.01,
                "{label}: energy"
            );
            assert!(
                (ours.sine.mean - want.mean).abs() < 0.02 * sd,
                "{label}: mean"
            );
            assert!(
                (ours.sine.variance / want.variance - 1.0).abs() < 0.02,
                "{label}: variance"
            );
        }
    }
}
