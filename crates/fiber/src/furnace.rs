//! The white furnace: the albedo ∫ S(ω_i, ω_o) dω_o of a model, computed from `eval` alone.
//!
//! The integral must not lean on the model's own sampling: with μ_a = 0 a model's S and its
//! sampling pdf coincide, so S / pdf ≡ 1 and a Monte Carlo furnace would prove nothing. It is a
//! deterministic product Gauss–Legendre rule instead: in θ_o, panels graded geometrically away
//! from the specular cone −θ_i (finest at half the narrowest lobe width, β(η − 1)/2,
//! and spanning the scale-tilt shifts); in φ, uniform panels. The same rule at half the
//! resolution gives the error estimate.

use crate::geometry::frame::FiberAngles;
use crate::lobe::LobeValues;
use crate::math::GaussLegendre;
use crate::model::FiberModel;
use glam::DVec3;
use serde::Serialize;
use std::f64::consts::PI;

/// An albedo with the difference from the rule at half resolution (RGB), and its share in each
/// lobe.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct AlbedoEstimate {
    pub albedo: DVec3,
    pub error_estimate: DVec3,
    #[serde(skip)]
    pub per_lobe: LobeValues,
    pub evaluations: usize,
}

/// Geometry the integration rule is fitted to: roughness, the largest cone shift, and a
/// resolution multiplier (1 is the default; 2 doubles the nodes in each dimension).
#[derive(Clone, Copy, Debug)]
pub struct FurnaceRule {
    pub beta: f64,
    pub max_shift: f64,
    pub resolution: usize,
}

impl FurnaceRule {
    /// The default rule for a fiber of roughness `beta` and scale tilt `alpha_deg` (degrees):
    /// the finest panels span the cone shifts of up to six tilts (TRRT's, d'Eon et al. 2014
    /// §2.2), at resolution 1 (what `cuticle lobes`, `cuticle furnace` and the bindings use).
    pub fn for_fiber(beta: f64, alpha_deg: f64) -> Self {
        Self {
            beta,
            max_shift: 6.0 * alpha_deg.abs().to_radians(),
            resolution: 1,
        }
    }
}

/// Gauss–Legendre points per panel (`cuticle lobes`' pixel means use the same).
pub const NODES_PER_PANEL: usize = 8;
/// φ panels at resolution 1.
const PHI_PANELS: usize = 32;
/// The widest θ panel, far from every lobe, at resolution 1.
const WIDEST_THETA_PANEL: f64 = 0.2;
/// Most panels of the finest width on each side of the cone, at resolution 1: what bounds the
/// rule's cost for small β, where the span of the tilt shifts holds ever more lobe widths
/// (about 1.5 |max_shift| / (0.275 β) of them). Below β ≈ 0.0025 at α = 2° the bound widens the
/// finest panels beyond half a lobe width, and the error estimate grows accordingly.
pub const MAX_FINE_PANELS: usize = 128;

/// ∫ S dω_o for light at `theta_i`.
pub fn albedo(model: &dyn FiberModel, theta_i: f64, rule: FurnaceRule) -> AlbedoEstimate {
    let (fine, n_fine) = integrate(model, theta_i, rule, rule.resolution.max(1) * 2);
    let (coarse, n_coarse) = integrate(model, theta_i, rule, rule.resolution.max(1));
    AlbedoEstimate {
        albedo: fine.total(),
        error_estimate: (fine.total() - coarse.total()).abs(),
        per_lobe: fine,
        evaluations: n_fine + n_coarse,
    }
}

fn integrate(
    model: &dyn FiberModel,
    theta_i: f64,
    rule: FurnaceRule,
    resolution: usize,
) -> (LobeValues, usize) {
    let gl = GaussLegendre::cached(NODES_PER_PANEL);
    let thetas = gl.panel_nodes(&theta_breaks(theta_i, rule, resolution));
    let phis = gl.panel_nodes(&uniform_breaks(-PI, PI, PHI_PANELS * resolution));
    let wi = FiberAngles::new(theta_i, 0.0);
    let mut sum = LobeValues::default();
    for &(theta, wt) in &thetas {
        let weight = wt * theta.cos();
        for &(phi, wp) in &phis {
            let s = model.eval(wi, FiberAngles::new(theta, phi));
            for (acc, v) in sum.0.iter_mut().zip(s.0) {
                *acc += weight * wp * v;
            }
        }
    }
    (sum, thetas.len() * phis.len())
}

/// Panel edges in θ_o: fine near the cone −θ_i (and its shifted copies), growing by 1.5× away.
/// [`albedo`]'s own estimate integrates on these at `2 * rule.resolution`.
pub fn theta_breaks(theta_i: f64, rule: FurnaceRule, resolution: usize) -> Vec<f64> {
    let center = -theta_i;
    let flat = rule.max_shift.abs() * 1.5 + 4.0 * rule.beta;
    let finest = (0.5 * 0.55 * rule.beta).max(flat / MAX_FINE_PANELS as f64) / resolution as f64;
    let mut breaks = vec![-0.5 * PI, 0.5 * PI];
    for side in [-1.0, 1.0] {
        let mut offset = 0.0;
        let mut step = finest;
        while offset < PI {
            breaks.push(center + side * offset);
            offset += step;
            if offset > flat {
                step = (step * 1.5).min(WIDEST_THETA_PANEL / resolution as f64);
            }
        }
    }
    breaks.retain(|b| (-0.5 * PI..=0.5 * PI).contains(b));
    breaks.sort_by(f64::total_cmp);
    breaks.dedup_by(|a, b| (*a - *b).abs() < 1e-12);
    breaks
}

fn uniform_breaks(a: f64, b: f64, n: usize) -> Vec<f64> {
    (0..=n).map(|k| a + (b - a) * k as f64 / n as f64).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lobe::Lobe;
    use crate::lobes::longitudinal::LongitudinalLobe;
    use crate::model::FiberSample;

    /// The rule's cost is bounded for any β (issue 9: β = 1e-3 took 50 s and 1e-9 never
    /// ended): the θ panels stay within the fine-panel bound plus the graded ones.
    #[test]
    fn the_rule_is_bounded_for_tiny_beta() {
        let panels = |beta: f64| {
            let rule = FurnaceRule {
                beta,
                max_shift: 6f64.to_radians() * 2.0,
                resolution: 2,
            };
            theta_breaks(0.5, rule, 2).len()
        };
        let bound = 2 * 2 * MAX_FINE_PANELS + 200;
        for beta in [0.04, 1e-3, crate::ranges::MIN_BETA, 1e-9] {
            assert!(panels(beta) <= bound, "β {beta}: {} panels", panels(beta));
        }
        assert!(
            panels(0.04) < panels(1e-3),
            "finer panels for narrower lobes"
        );
    }

    /// A narrow longitudinal lobe at the cone times a uniform azimuth: albedo exactly 1.
    struct Narrow(f64);
    impl FiberModel for Narrow {
        fn name(&self) -> &'static str {
            "narrow"
        }
        fn eval(&self, wi: FiberAngles, wo: FiberAngles) -> LobeValues {
            let m = LongitudinalLobe::new(self.0 * self.0, -wi.theta).eval(wo.theta);
            let mut v = LobeValues::default();
            v[Lobe::TT] = DVec3::splat(m / (2.0 * PI));
            v
        }
        fn sample(&self, _: FiberAngles, _: [f64; 4]) -> Option<FiberSample> {
            None
        }
        fn pdf(&self, _: FiberAngles, _: FiberAngles) -> f64 {
            0.0
        }
    }

    #[test]
    fn integrates_a_lobe_narrower_than_the_rule_is_told() {
        for (width, theta) in [(0.002, 0.3), (0.05, 1.4), (0.5, 0.0)] {
            let rule = FurnaceRule {
                beta: width * 2.0,
                max_shift: 0.0,
                resolution: 1,
            };
            let est = albedo(&Narrow(width), theta, rule);
            assert!((est.albedo.x - 1.0).abs() < 1e-6, "width {width}: {est:?}");
        }
    }
}
