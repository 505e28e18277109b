//! Importance sampling: lobe choice by an energy table, θ_h by inversion, φ by the cubic or
//! TRT's mixture; the [`FiberModel`] implementation.

use super::{
    Caustic, CubicDeflection, GaussianLobe, Interface, Marschner2003, MarschnerParams,
    azimuthal_and_density, per_steradian_factor,
};
use crate::azimuthal::wrapped_gaussian;
use crate::bravais::eta_prime;
use crate::deon2011::weighted_sample;
use crate::frame::{FiberAngles, wrap_pi};
use crate::lobe::{Lobe, LobeValues, channel_mean};
use crate::model::{FiberModel, FiberSample, per_steradian, select_and_remap};
use crate::special::{GaussLegendre, normal_quantile};
use glam::DVec3;
use std::f64::consts::{FRAC_PI_2, PI};

/// Share of TRT's azimuthal proposal drawn uniformly, so no φ is left uncovered.
pub(super) const TRT_UNIFORM_SHARE: f64 = 0.1;
/// Share of TRT's azimuthal proposal given to the two glints at full strength (t = 1).
pub(super) const TRT_GLINT_SHARE: f64 = 0.45;
/// Every lobe is chosen with at least this fraction of the total energy estimate.
pub(super) const LOBE_FLOOR: f64 = 0.05;

/// TRT's azimuthal proposal at one θ_d: the glint Gaussians at ±φ_c (width w_c), a wrapped
/// Gaussian at 0 spanning Φ̂(2, ·)'s range, and a uniform share.
pub(super) struct TrtProposal {
    phi_c: f64,
    caustic_width: f64,
    /// Probabilities of: glint at +φ_c, glint at −φ_c, the central Gaussian, uniform.
    shares: [f64; 4],
    spread: f64,
}

impl TrtProposal {
    fn new(eta_prime: f64, params: &MarschnerParams) -> Self {
        let caustic = Caustic::new(eta_prime, params);
        let deflection = CubicDeflection::new(2, eta_prime);
        let reach = [deflection.phi(FRAC_PI_2)]
            .into_iter()
            .chain(deflection.fold().map(|g| deflection.phi(g)))
            .map(|x| (x - 2.0 * PI).abs())
            .fold(0.0, f64::max);
        let glint = 0.5 * TRT_GLINT_SHARE * caustic.t;
        Self {
            phi_c: caustic.phi_c,
            caustic_width: params.caustic_width,
            shares: [
                glint,
                glint,
                1.0 - TRT_UNIFORM_SHARE - 2.0 * glint,
                TRT_UNIFORM_SHARE,
            ],
            spread: (0.5 * reach).clamp(0.05, FRAC_PI_2),
        }
    }

    fn density(&self, phi: f64) -> f64 {
        let v = self.caustic_width.powi(2);
        let [g1, g2, central, uniform] = self.shares;
        g1 * wrapped_gaussian(phi - self.phi_c, v)
            + g2 * wrapped_gaussian(phi + self.phi_c, v)
            + central * wrapped_gaussian(phi, self.spread.powi(2))
            + uniform / (2.0 * PI)
    }

    fn sample(&self, u_choice: f64, u: f64) -> f64 {
        let offset = || normal_quantile(u.clamp(1e-16, 1.0 - 1e-16));
        match select_and_remap(&self.shares, u_choice).0 {
            0 => wrap_pi(self.phi_c + self.caustic_width * offset()),
            1 => wrap_pi(-self.phi_c + self.caustic_width * offset()),
            2 => wrap_pi(self.spread * offset()),
            _ => wrap_pi(2.0 * PI * u - PI),
        }
    }
}

/// Nodes of the lobe-energy table over θ_i ∈ [−π/2, π/2].
pub(super) const ENERGY_NODES: usize = 33;

/// ½ ∫ A(p, h) dh (channel mean) at each lobe's peak θ_d = α_p − θ_i, tabulated over θ_i and
/// interpolated linearly: any positive function of θ_i serves lobe choice, this one follows
/// the lobes' energies.
#[derive(Clone, Debug)]
pub(super) struct EnergyTable([[f64; ENERGY_NODES]; 3]);

impl EnergyTable {
    fn new(params: &MarschnerParams, lobes: &[GaussianLobe; 3]) -> Self {
        let rule = GaussLegendre::cached(4);
        Self(std::array::from_fn(|p| {
            std::array::from_fn(|k| {
                let theta_i = -FRAC_PI_2 + PI * k as f64 / (ENERGY_NODES - 1) as f64;
                let theta_d = (lobes[p].alpha - theta_i).clamp(-FRAC_PI_2, FRAC_PI_2);
                let interface = Interface::new(params.eta, theta_d, params.mu_a);
                rule.integrate(0.0, FRAC_PI_2, |g| {
                    channel_mean(interface.attenuation(p as u32, g)) * g.cos()
                })
            })
        }))
    }

    fn at(&self, theta_i: f64) -> [f64; 3] {
        let x = ((theta_i + FRAC_PI_2) / PI).clamp(0.0, 1.0) * (ENERGY_NODES - 1) as f64;
        let k = (x as usize).min(ENERGY_NODES - 2);
        let f = x - k as f64;
        self.0.map(|row| row[k] + f * (row[k + 1] - row[k]))
    }
}

impl Marschner2003 {
    /// Lobe choice at θ_i: each lobe's energy estimate (plus a floor) times roughly the share
    /// of its Gaussian that θ_o ∈ [−π/2, π/2] keeps.
    fn lobe_probabilities(&self, theta_i: f64) -> [f64; 3] {
        let energy = self
            .energy
            .get_or_init(|| EnergyTable::new(&self.params, &self.lobes))
            .at(theta_i);
        let total: f64 = energy.iter().sum();
        let w: [f64; 3] = std::array::from_fn(|p| {
            (energy[p] + LOBE_FLOOR * total) * self.lobes[p].approximate_mass(theta_i)
        });
        let sum: f64 = w.iter().sum();
        if sum > 0.0 && sum.is_finite() {
            w.map(|x| x / sum)
        } else {
            [0.0; 3]
        }
    }

    /// S (all lobes) and [`FiberModel::pdf`] together, for a sample: the lobe probabilities
    /// passed in, M_p and the interface found once, R's and TT's roots searched once for both
    /// N_p and their φ density. The arithmetic of `eval` and `pdf`, so the same results.
    fn eval_and_pdf(&self, wi: FiberAngles, wo: FiberAngles, probs: &[f64; 3]) -> (DVec3, f64) {
        let theta_h = 0.5 * (wi.theta + wo.theta);
        let theta_d = 0.5 * (wo.theta - wi.theta);
        let phi = wrap_pi(wo.phi - wi.phi);
        let scale = per_steradian_factor(wo.theta, theta_d);
        let raw = self.lobes.map(|lobe| lobe.eval(theta_h));
        let m = raw.map(|x| x * scale);
        let p = &self.params;
        let circular = Interface::new(p.eta, theta_d, p.mu_a);
        let mut s = [DVec3::ZERO; 3];
        let mut phi_density = [0.0; 3];
        for lobe in 0..2 {
            if m[lobe] > 0.0 || probs[lobe] > 0.0 {
                let (n, density) = azimuthal_and_density(lobe as u32, &circular, phi);
                if m[lobe] > 0.0 {
                    s[lobe] = m[lobe] * n;
                }
                phi_density[lobe] = density;
            }
        }
        if m[2] > 0.0 {
            s[2] = m[2] * self.trt(wi, wo, &circular, phi);
        }
        if probs[2] > 0.0 {
            phi_density[2] = TrtProposal::new(circular.eta_prime, p).density(phi);
        }
        // GaussianLobe::density is ½ M_p(θ_h).
        let density: f64 = (0..3)
            .filter(|&l| probs[l] > 0.0)
            .map(|l| probs[l] * (0.5 * raw[l]) * phi_density[l])
            .sum();
        let [r, tt, trt] = s;
        let total = LobeValues([r, tt, trt, DVec3::ZERO, DVec3::ZERO]).total();
        (total, per_steradian(density, wo.theta))
    }

    /// The density of φ given θ_d with which lobe p is sampled.
    fn phi_density(&self, p: usize, theta_d: f64, phi: f64) -> f64 {
        let eta_prime = eta_prime(self.params.eta, theta_d);
        match p {
            2 => TrtProposal::new(eta_prime, &self.params).density(phi),
            _ => {
                let deflection = CubicDeflection::new(p as u32, eta_prime);
                let roots = deflection.roots(phi);
                roots
                    .as_slice()
                    .iter()
                    .map(|&g| deflection.inverse_spread(g))
                    .sum()
            }
        }
    }

    /// φ for lobe p given θ_d: R and TT map a uniform offset h through Φ̂, TRT draws from
    /// its mixture.
    fn sample_phi(&self, p: usize, theta_d: f64, u: [f64; 2]) -> f64 {
        let eta_prime = eta_prime(self.params.eta, theta_d);
        match p {
            2 => TrtProposal::new(eta_prime, &self.params).sample(u[0], u[1]),
            _ => {
                let gamma = (2.0 * u[0] - 1.0).clamp(-1.0, 1.0).asin();
                wrap_pi(CubicDeflection::new(p as u32, eta_prime).phi(gamma))
            }
        }
    }
}

impl FiberModel for Marschner2003 {
    fn name(&self) -> &'static str {
        "marschner"
    }

    fn eval(&self, wi: FiberAngles, wo: FiberAngles) -> LobeValues {
        let [r, tt, trt] = self.lobe_values(wi, wo);
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
        let probs = self.lobe_probabilities(wi.theta);
        let theta_d = 0.5 * (wo.theta - wi.theta);
        let phi = wrap_pi(wo.phi - wi.phi);
        let density: f64 = (0..3)
            .filter(|&p| probs[p] > 0.0)
            .map(|p| {
                probs[p]
                    * self.lobes[p].density(wi.theta, wo.theta)
                    * self.phi_density(p, theta_d, phi)
            })
            .sum();
        per_steradian(density, wo.theta)
    }
}
