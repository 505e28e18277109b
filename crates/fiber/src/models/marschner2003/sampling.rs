//! Importance sampling: lobe choice from a table over θ_i, θ_h by inversion, φ by the cubic
//! or TRT's mixture; the [`FiberModel`] implementation.
//!
//! Every proposal here is a choice, not part of the model: any positive lobe weights and any
//! TRT mixture serve, as long as `sample` draws from exactly the density `pdf` reports. So
//! the lobe probabilities, TT's c and TRT's mixture parameters are tabulated once per model
//! ([`SamplingTables`]) and both `sample` and `pdf` read the same interpolated values: the
//! table changes how well the proposal follows S, never the agreement of sample and pdf.

use super::{Caustic, CubicDeflection, GaussianLobe, Interface, Marschner2003, MarschnerParams};
use crate::geometry::bravais::eta_prime;
use crate::geometry::frame::{FiberAngles, wrap_pi};
use crate::lobe::{Lobe, LobeValues, channel_mean};
use crate::lobes::azimuthal::wrapped_gaussian_core;
use crate::math::{GaussLegendre, asin_fast, cos_quadrant, normal_quantile_fast};
use crate::model::weighted_sample;
use crate::model::{FiberModel, FiberSample, per_steradian, select_and_remap};
use glam::DVec3;
use std::f64::consts::{FRAC_PI_2, PI};

/// Share of TRT's azimuthal proposal drawn uniformly, so no φ is left uncovered.
pub(super) const TRT_UNIFORM_SHARE: f64 = 0.1;
/// Share of TRT's azimuthal proposal given to the two glints at full strength (t = 1).
pub(super) const TRT_GLINT_SHARE: f64 = 0.45;
/// Every lobe is chosen with at least this fraction of the total energy estimate.
pub(super) const LOBE_FLOOR: f64 = 0.05;
/// Nodes of the lobe-choice table over θ_i ∈ [−π/2, π/2].
const CHOICE_NODES: usize = 257;
/// Nodes of the azimuthal proposals over |θ_d| ∈ [0, π/2].
const PHI_NODES: usize = 129;

/// The azimuthal proposals' parameters at one θ_d: c = asin(1/η′) of TT's cubic, and the
/// shape of TRT's mixture, glints at ±φ_c of strength t and a central Gaussian of width
/// `spread`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct PhiShape {
    tt_critical_angle: f64,
    trt: TrtShape,
}

impl PhiShape {
    fn new(eta_prime: f64, params: &MarschnerParams) -> Self {
        Self {
            tt_critical_angle: CubicDeflection::critical_angle(eta_prime),
            trt: TrtShape::new(eta_prime, params),
        }
    }

    /// TT's cubic deflection with the interpolated c: TT's φ proposal (a proposal needs only
    /// to be the same in `sample` and `pdf`, not c's exact value).
    fn tt(&self) -> CubicDeflection {
        CubicDeflection::with_critical_angle(1, self.tt_critical_angle)
    }

    fn lerp(self, next: Self, f: f64) -> Self {
        Self {
            tt_critical_angle: self.tt_critical_angle
                + f * (next.tt_critical_angle - self.tt_critical_angle),
            trt: self.trt.lerp(next.trt, f),
        }
    }
}

#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct TrtShape {
    phi_c: f64,
    t: f64,
    spread: f64,
}

impl TrtShape {
    /// At η′: the glints where [`Caustic`] puts them, the central Gaussian spanning half of
    /// Φ̂(2, ·)'s reach about 2π.
    fn new(eta_prime: f64, params: &MarschnerParams) -> Self {
        let caustic = Caustic::new(eta_prime, params);
        let deflection = CubicDeflection::new(2, eta_prime);
        let reach = [deflection.phi(FRAC_PI_2)]
            .into_iter()
            .chain(deflection.fold().map(|g| deflection.phi(g)))
            .map(|x| (x - 2.0 * PI).abs())
            .fold(0.0, f64::max);
        Self {
            phi_c: caustic.phi_c,
            t: caustic.t,
            spread: (0.5 * reach).clamp(0.05, FRAC_PI_2),
        }
    }

    fn lerp(self, next: Self, f: f64) -> Self {
        Self {
            phi_c: self.phi_c + f * (next.phi_c - self.phi_c),
            t: self.t + f * (next.t - self.t),
            spread: self.spread + f * (next.spread - self.spread),
        }
    }
}

/// TRT's azimuthal proposal: the glint Gaussians at ±φ_c (width w_c), a wrapped Gaussian at
/// 0 spanning Φ̂(2, ·)'s range, and a uniform share.
pub(super) struct TrtProposal {
    phi_c: f64,
    caustic_width: f64,
    /// Probabilities of: glint at +φ_c, glint at −φ_c, the central Gaussian, uniform.
    shares: [f64; 4],
    spread: f64,
}

impl TrtProposal {
    fn of(shape: TrtShape, params: &MarschnerParams) -> Self {
        let glint = 0.5 * TRT_GLINT_SHARE * shape.t;
        Self {
            phi_c: shape.phi_c,
            caustic_width: params.caustic_width,
            shares: [
                glint,
                glint,
                1.0 - TRT_UNIFORM_SHARE - 2.0 * glint,
                TRT_UNIFORM_SHARE,
            ],
            spread: shape.spread,
        }
    }

    /// The mixture's density; with its uniform share, the Gaussians' far images are lost to
    /// rounding ([`wrapped_gaussian_core`]).
    fn density(&self, phi: f64) -> f64 {
        let w = self.caustic_width;
        let [glint, _, central, uniform] = self.shares;
        let mut density = central * wrapped_gaussian_core(phi, self.spread) + uniform / (2.0 * PI);
        // Once the caustics have merged and faded (t = 0) the glints have no share.
        if glint > 0.0 {
            density += glint
                * (wrapped_gaussian_core(phi - self.phi_c, w)
                    + wrapped_gaussian_core(phi + self.phi_c, w));
        }
        density
    }

    fn sample(&self, u_choice: f64, u: f64) -> f64 {
        let offset = || normal_quantile_fast(u.clamp(1e-16, 1.0 - 1e-16));
        match select_and_remap(&self.shares, u_choice).0 {
            0 => wrap_pi(self.phi_c + self.caustic_width * offset()),
            1 => wrap_pi(-self.phi_c + self.caustic_width * offset()),
            2 => wrap_pi(self.spread * offset()),
            _ => wrap_pi(2.0 * PI * u - PI),
        }
    }
}

/// The proposals' parameters, tabulated once per model and interpolated linearly (see the
/// module documentation): lobe probabilities over θ_i, TT's cubic and TRT's mixture over
/// |θ_d|.
#[derive(Clone, Debug)]
pub(super) struct SamplingTables {
    choice: Vec<[f64; 3]>,
    phi: Vec<PhiShape>,
}

impl SamplingTables {
    fn new(params: &MarschnerParams, lobes: &[GaussianLobe; 3]) -> Self {
        let choice = (0..CHOICE_NODES)
            .map(|k| {
                let theta_i = -FRAC_PI_2 + PI * k as f64 / (CHOICE_NODES - 1) as f64;
                lobe_weights(params, lobes, theta_i)
            })
            .collect();
        let phi = (0..PHI_NODES)
            .map(|k| {
                let theta_d = FRAC_PI_2 * k as f64 / (PHI_NODES - 1) as f64;
                PhiShape::new(eta_prime(params.eta, theta_d), params)
            })
            .collect();
        Self { choice, phi }
    }

    fn choice(&self, theta_i: f64) -> [f64; 3] {
        let (k, f) = node(((theta_i + FRAC_PI_2) / PI).clamp(0.0, 1.0), CHOICE_NODES);
        let (a, b) = (self.choice[k], self.choice[k + 1]);
        std::array::from_fn(|p| a[p] + f * (b[p] - a[p]))
    }

    fn phi(&self, theta_d: f64) -> PhiShape {
        let (k, f) = node((theta_d.abs() / FRAC_PI_2).min(1.0), PHI_NODES);
        self.phi[k].lerp(self.phi[k + 1], f)
    }
}

/// The lower node and the fraction toward the next for t ∈ [0, 1] on n nodes.
fn node(t: f64, n: usize) -> (usize, f64) {
    let x = t * (n - 1) as f64;
    let k = (x as usize).min(n - 2);
    (k, x - k as f64)
}

/// Lobe weights at θ_i, normalised: each lobe's energy estimate ½ ∫ A(p, h) dh (channel mean,
/// at its peak θ_d = α_p − θ_i) plus a floor, times roughly the share of its Gaussian that
/// θ_o ∈ [−π/2, π/2] keeps. Zero when every weight is.
pub(super) fn lobe_weights(
    params: &MarschnerParams,
    lobes: &[GaussianLobe; 3],
    theta_i: f64,
) -> [f64; 3] {
    let rule = GaussLegendre::cached(4);
    let energy: [f64; 3] = std::array::from_fn(|p| {
        let theta_d = (lobes[p].alpha - theta_i).clamp(-FRAC_PI_2, FRAC_PI_2);
        let interface = Interface::new(params.eta, theta_d, params.mu_a);
        rule.integrate(0.0, FRAC_PI_2, |g| {
            channel_mean(interface.attenuation(p as u32, g)) * g.cos()
        })
    });
    let total: f64 = energy.iter().sum();
    let w: [f64; 3] = std::array::from_fn(|p| {
        (energy[p] + LOBE_FLOOR * total) * lobes[p].approximate_mass(theta_i)
    });
    let sum: f64 = w.iter().sum();
    if sum > 0.0 && sum.is_finite() {
        w.map(|x| x / sum)
    } else {
        [0.0; 3]
    }
}

impl Marschner2003 {
    fn sampling(&self) -> &SamplingTables {
        self.sampling
            .get_or_init(|| SamplingTables::new(&self.params, &self.lobes))
    }

    /// Lobe probabilities at θ_i (interpolated from [`lobe_weights`] at the table's nodes).
    pub(super) fn lobe_probabilities(&self, theta_i: f64) -> [f64; 3] {
        self.sampling().choice(theta_i)
    }

    /// S (all lobes) and [`FiberModel::pdf`] together, for a sample: the lobe probabilities
    /// passed in. The arithmetic of `eval` and `pdf`, so the same results.
    fn eval_and_pdf(&self, wi: FiberAngles, wo: FiberAngles, probs: &[f64; 3]) -> (DVec3, f64) {
        let m = self.longitudinal(wi, wo);
        let [r, tt, trt] = self.lobe_values_with(wi, wo, &m);
        let total = LobeValues([r, tt, trt, DVec3::ZERO, DVec3::ZERO]).total();
        (total, self.density(wi, wo, probs, &m))
    }

    /// The density of `sample`'s directions given its lobe probabilities and M_p(θ_h): θ_o
    /// is drawn as 2θ_h − θ_i with θ_h from M_p, so its density is ½ M_p (it is not
    /// renormalised to θ_o ∈ [−π/2, π/2]; draws beyond are rejected instead).
    fn density(&self, wi: FiberAngles, wo: FiberAngles, probs: &[f64; 3], m: &[f64; 3]) -> f64 {
        let shape = self.sampling().phi(0.5 * (wo.theta - wi.theta));
        let phi = wrap_pi(wo.phi - wi.phi);
        let mut density = 0.0;
        for p in 0..3 {
            if probs[p] > 0.0 {
                density += probs[p] * (0.5 * m[p]) * self.phi_density(p, &shape, phi);
            }
        }
        per_steradian(density, wo.theta)
    }

    /// The density of φ given the proposals' shape at θ_d with which lobe p is sampled: for
    /// R and TT the offsets' Σ 1/|2 dΦ̂/dh| (R's in closed form, cos(φ/2)/4 at its one root
    /// γ = −φ/2), for TRT its mixture.
    fn phi_density(&self, p: usize, shape: &PhiShape, phi: f64) -> f64 {
        match p {
            0 => 0.25 * cos_quadrant(0.5 * phi),
            1 => shape.tt().offset_density(phi),
            _ => TrtProposal::of(shape.trt, &self.params).density(phi),
        }
    }

    /// φ for lobe p given θ_d: R and TT map a uniform offset h through Φ̂, TRT draws from
    /// its mixture.
    fn sample_phi(&self, p: usize, theta_d: f64, u: [f64; 2]) -> f64 {
        let gamma = || asin_fast((2.0 * u[0] - 1.0).clamp(-1.0, 1.0));
        match p {
            0 => wrap_pi(-2.0 * gamma()),
            1 => wrap_pi(self.sampling().phi(theta_d).tt().phi(gamma())),
            _ => {
                let shape = self.sampling().phi(theta_d);
                TrtProposal::of(shape.trt, &self.params).sample(u[0], u[1])
            }
        }
    }
}

impl FiberModel for Marschner2003 {
    fn tabulate(&mut self) {
        *self = self.clone().tabulated();
    }

    fn name(&self) -> &'static str {
        "marschner"
    }

    fn eval(&self, wi: FiberAngles, wo: FiberAngles) -> LobeValues {
        let [r, tt, trt] = self.lobe_values_with(wi, wo, &self.longitudinal(wi, wo));
        LobeValues([r, tt, trt, DVec3::ZERO, DVec3::ZERO])
    }

    fn sample(&self, wi: FiberAngles, u: [f64; 4]) -> Option<FiberSample> {
        let probs = self.lobe_probabilities(wi.theta);
        if probs.iter().all(|&x| x == 0.0) {
            return None;
        }
        let (p, _) = select_and_remap(&probs, u[0]);
        let theta_o = self.lobes[p].sample(wi.theta, u[1])?;
        let theta_d = 0.5 * (theta_o - wi.theta);
        let phi = self.sample_phi(p, theta_d, [u[2], u[3]]);
        let wo = FiberAngles::new(theta_o, wrap_pi(wi.phi + phi));
        let (s, pdf) = self.eval_and_pdf(wi, wo, &probs);
        weighted_sample(wo, s, pdf, Lobe::from_index(p), 1)
    }

    /// The density of [`FiberModel::sample`]'s directions; it integrates to the probability
    /// that a draw's θ_o lands inside [−π/2, π/2] (the rest return `None`).
    fn pdf(&self, wi: FiberAngles, wo: FiberAngles) -> f64 {
        let m = self.longitudinal(wi, wo);
        self.density(wi, wo, &self.lobe_probabilities(wi.theta), &m)
    }
}
