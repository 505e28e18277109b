//! The hair scattering model of Marschner, Jensen, Cammarano, Worley and Hanrahan 2003, *Light
//! scattering from human hair fibers* (docs/references.md lists the survey we read it from), with
//! its TRT caustic treatment and eccentricity, and an exact importance sampling.
//!
//! # The model
//! Three lobes p = 0 (R), 1 (TT), 2 (TRT), each M_p(θ_h) N_p(φ) / cos²θ_d (Marschner et al. 2003
//! "The Grand Result"; Marschner 2003's practical model):
//! - M_p is a unit-integral Gaussian in θ_h = (θ_i + θ_o)/2 with shift α_p and width β_p:
//!   α_TT = −α_R/2, α_TRT = −3α_R/2, β_TT = β_R/2, β_TRT = 2β_R (Marschner 2003 Table 1).
//! - N_p(φ) = Σ A(p, h) / |2 dΦ̂/dh| over every root γ_i ∈ [−π/2, π/2] of
//!   Φ̂(p, γ_i) = (6pc/π − 2)γ_i − 8pc/π³ γ_i³ + pπ ≡ φ (mod 2π), c = asin(1/η′),
//!   η′ = η′(η, θ_d) (Marschner 2003's cubic approximation; Marschner et al. 2003 "Finding γ_i").
//!   The cubic has one or three real roots; those in [−π/2, π/2] are what count: TRT has three
//!   between its caustics ±φ_c and one beyond them, except for η′ < 1.556, where φ_c lies beyond
//!   the edge ray
//!   |Φ̂(2, ±π/2) − 2π| = |4c − π|: there two remain between the edge ray and φ_c, and none
//!   beyond φ_c. Φ̂ is within 0.019 rad (TT) and 0.038 rad (TRT) of the exact Φ for every
//!   η′ ≥ 1.55 (0.037 and 0.075 at η′ = 1.4; `cubic_deflection_tracks_the_exact_one`).
//! - A(0, h) = F(η′, η″, γ_i) and A(p, h) = (1 − F(η′, η″, γ_i))² F(1/η′, 1/η″, γ_t)^{p−1} T^p
//!   with the oblique Fresnel factor and T = exp(−2 μ_a cos γ_t / cos θ_t), the chord of the
//!   unit circle (docs/conventions.md §8 erratum; Marschner et al. 2003 prints exp(−μ_a(2 + 2 cos
//!   2γ_t))). The whole azimuthal part is a function of θ_d, as in Marschner's paper, so θ_t is the
//!   refracted inclination of the difference angle, sin θ_t = sin θ_d / η (equal to θ_i's on the
//!   specular cone), and the model stays reciprocal.
//! - TRT replaces its caustic singularities by Gaussian glints (Marschner 2003's N_TRT listing, see
//!   [`Caustic`]), and uses η*(φ_h) for an elliptical fiber (Xu et al. 2011 eq. 24, see
//!   [`eta_star`]).
//!
//! # Units (docs/conventions.md §3)
//! Marschner's S is defined through curve radiance L̄, radiance integrated across the fiber's
//! projected width, which is power per steradian per unit *projected* length: a unit length of
//! fiber seen from ω_o projects to cos θ_o. The power intercepted per unit length from a beam
//! of radiance L_i over dω_i is D L_i cos θ_i dω_i, which is exactly the factor in Marschner's
//! L̄_o = D ∫ S L_i cos θ_i dω_i. So the fraction of intercepted power per steradian — this
//! project's S — is Marschner's S times cos θ_o. (docs/conventions.md's "Marschner's S with cos θ_i
//! kept outside" misses this cos θ_o.) Check on his smooth cylinder, S = δ(θ_o + θ_i) N / cos²θ:
//! ∫ S cos θ_o dω_o = ∫∫ δ N cos²θ_o / cos²θ dθ_o dφ = ∫ N dφ, the albedo. ✓
//!
//! His rough model replaces δ(θ_o + θ_i) by M(θ_h), but M is unit-integral in θ_h and
//! dθ_o = 2 dθ_h at fixed θ_i, so ∫ M dθ_o = 2: as printed, the rough model has twice the
//! energy of the smooth one it blurs. The density in θ_o is M/2. Hence, exactly,
//!
//!   S(ω_i, ω_o) = Σ_p ½ M_p(θ_h) N_p(φ) cos θ_o / cos²θ_d   [sr⁻¹].
//!
//! What the cos²θ_d normalisation implies: a lobe's energy is ∫ N_p dφ times
//! E(θ_i) = ∫ ½ M_p(θ_h) cos²θ_o / cos²θ_d dθ_o over θ_o ∈ [−π/2, π/2]. The ratio
//! cos²θ_o / cos²θ_d is 1 on the specular cone θ_o = −θ_i, so for small β and α = 0, E → 1 and
//! the R lobe carries exactly the Fresnel integral ½ ∫ F dh: the test
//! `r_lobe_energy_is_the_fresnel_integral` finds agreement to 2e-5 at β_R = 0.1°, and a
//! deficit growing as β_R² (3 sec²θ_i − 2 tan²θ_i) (0.08 % at β_R = 1°, θ_i = 0). Off the
//! cone E drifts further: with the default shift α_R = −7.5° and β_R = 7.5°, E_R is 0.90 at
//! θ_i = 0, 1.06 at θ_i = −0.6 and 0.73 at θ_i = 0.6 (`energy_factor_of_the_cos2_normalisation`),
//! because the lobe's peak sits at θ_o = −θ_i + 2α_R, where cos θ_o ≠ cos θ_d. Marschner 2003
//! does not conserve energy, and this is part of why.
//!
//! # Sampling
//! A lobe is chosen by an estimate of its energy at θ_i, θ_h from its Gaussian by inversion
//! (a draw whose θ_o = 2θ_h − θ_i falls beyond ±π/2 returns `None`, and `pdf` integrates to
//! the probability of the others, so nothing needs the Gaussian's truncated mass), then φ
//! given θ_d: for R and TT as the cubic maps a uniformly distributed offset h,
//! φ = Φ̂(p, asin h), whose density Σ 1/|2 dΦ̂/dh| over the same roots is N_p with A = 1; for
//! TRT a mixture of the two glint Gaussians, a wrapped Gaussian over Φ̂(2, ·)'s range and a
//! uniform share. The lobe probabilities, TT's c and TRT's mixture are tabulated once per
//! model and read the same way by `sample` and `pdf` (`sampling.rs`). Every density is
//! closed-form, so [`crate::FiberModel::pdf`] is exactly the density of
//! [`crate::FiberModel::sample`], and weights are S / pdf (`crate::model::weighted_sample`).
//!
//! # The tabulated fast path
//! [`Marschner2003::tabulated`] reads N_TT and N_TRT from an [`NpTable`] over (θ_d, φ) and
//! takes N_R in closed form; the exact model, which solves the cubics at every evaluation,
//! stays the reference it is measured against (`table.rs`).
//!
//! # Files
//! - `params.rs`: [`MarschnerParams`], Table 1's defaults and their range checks.
//! - `longitudinal.rs`: the Gaussian lobes M_p in θ_h.
//! - `deflection.rs`: the cubic deflection Φ̂ ([`CubicDeflection`]) and its roots ([`GammaRoots`]).
//! - `azimuthal.rs`: attenuation A(p, h), N_p, the TRT caustic glints ([`Caustic`]) and
//!   [`eta_star`].
//! - `table.rs`: [`NpTable`], N_TT and N_TRT over (θ_d, φ) for [`Marschner2003::tabulated`].
//! - `sampling.rs`: lobe choice, θ_o and φ sampling, and the [`crate::FiberModel`] implementation.
//! - `tests.rs`: energy, root, reciprocity, χ² and finiteness tests.

mod azimuthal;
mod deflection;
mod longitudinal;
mod params;
mod sampling;
mod table;
#[cfg(test)]
mod tests;

use crate::geometry::frame::{FiberAngles, wrap_pi};
use crate::math::{cos_quadrant, sin_cos_quadrant};
use crate::optics::fresnel::fresnel_oblique_at;
use crate::params::FiberParams;
use glam::DVec3;
use std::f64::consts::SQRT_2;
use std::sync::{Arc, OnceLock};

pub use azimuthal::{Caustic, eta_star};
use azimuthal::{Interface, azimuthal, azimuthal_trt};
pub use deflection::{CubicDeflection, GammaRoots};
use longitudinal::{GaussianLanes, GaussianLobe};
pub use params::{
    DEFAULT_ALPHA_R_DEG, DEFAULT_BETA_R_DEG, DEFAULT_CAUSTIC_WIDTH_DEG, MarschnerError,
    MarschnerParams,
};
use sampling::SamplingTables;
pub use table::NpTable;

/// The Marschner et al. 2003 fiber model.
#[derive(Clone, Debug)]
pub struct Marschner2003 {
    params: MarschnerParams,
    /// M_R, M_TT, M_TRT.
    lobes: [GaussianLobe; 3],
    /// The same in SIMD lanes, for evaluation.
    lanes: GaussianLanes,
    /// Lobe choice over θ_i and TRT's azimuthal proposal over θ_d; built on first use.
    sampling: OnceLock<SamplingTables>,
    /// N_TT and N_TRT over (θ_d, φ), when the model is [`Marschner2003::tabulated`].
    table: Option<Arc<NpTable>>,
}

impl Marschner2003 {
    pub fn new(params: MarschnerParams) -> Result<Self, MarschnerError> {
        params.validate()?;
        let lobes = params
            .longitudinal()
            .map(|(alpha, beta)| GaussianLobe { alpha, beta });
        Ok(Self {
            params,
            lobes,
            lanes: GaussianLanes::new(&lobes),
            sampling: OnceLock::new(),
            table: None,
        })
    }

    /// The same model with N_TT and N_TRT read from an [`NpTable`] built once for these
    /// parameters, and N_R in closed form: the fast path (see the table for its resolution
    /// and measured error). A fiber whose glints the table cannot resolve
    /// ([`NpTable::fits`]) stays exact.
    pub fn tabulated(mut self) -> Self {
        if NpTable::fits(&self.params) {
            self.table = Some(Arc::new(NpTable::build(&self.params)));
        }
        self
    }

    /// The table, when the model has one.
    pub fn table(&self) -> Option<&NpTable> {
        self.table.as_deref()
    }

    /// The model for the physical parameters every model shares: η and μ_a as given, an R
    /// lobe on d'Eon 2011's (its cone at θ_o = −θ_i + 2α with width √2 β), the rest of
    /// Table 1's defaults. M_R is a Gaussian in θ_h = (θ_i + θ_o)/2, so its cone sits at
    /// θ_o = −θ_i + 2α_R with width 2β_R in θ_o: matching takes α_R = α and β_R = β/√2.
    /// (Setting α_R = 2α and β_R = √2 β, d'Eon's θ_o figures, would double both.)
    pub fn from_fiber(fiber: &FiberParams) -> Result<Self, MarschnerError> {
        fiber.validate()?;
        Self::new(MarschnerParams {
            eta: fiber.eta,
            alpha_r: fiber.alpha,
            beta_r: fiber.beta / SQRT_2,
            mu_a: fiber.mu_a,
            ..MarschnerParams::default()
        })
    }

    pub fn params(&self) -> &MarschnerParams {
        &self.params
    }

    /// M_R, M_TT and M_TRT at θ_h, in lanes ([`GaussianLanes`]).
    fn longitudinal(&self, wi: FiberAngles, wo: FiberAngles) -> [f64; 3] {
        self.lanes.eval(0.5 * (wi.theta + wo.theta))
    }

    /// S of R, TT and TRT (docs/conventions.md §3 units, see the module documentation) given
    /// M_p(θ_h) ([`Self::longitudinal`]).
    fn lobe_values_with(&self, wi: FiberAngles, wo: FiberAngles, m: &[f64; 3]) -> [DVec3; 3] {
        let theta_d = 0.5 * (wo.theta - wi.theta);
        let phi = wrap_pi(wo.phi - wi.phi);
        let scale = per_steradian_factor(wo.theta, theta_d);
        let m = [m[0] * scale, m[1] * scale, m[2] * scale];
        let n = match self.table.as_deref() {
            Some(table) => self.azimuthal_tabulated(table, wi, wo, theta_d, phi),
            None => self.azimuthal_exact(wi, wo, theta_d, phi, &m),
        };
        let lobe = |p: usize| if m[p] > 0.0 { m[p] * n[p] } else { DVec3::ZERO };
        [lobe(0), lobe(1), lobe(2)]
    }

    /// N_R, N_TT and N_TRT by their roots (the reference), each only where its M_p is not 0.
    fn azimuthal_exact(
        &self,
        wi: FiberAngles,
        wo: FiberAngles,
        theta_d: f64,
        phi: f64,
        m: &[f64; 3],
    ) -> [DVec3; 3] {
        let p = &self.params;
        let circular = Interface::new(p.eta, theta_d, p.mu_a);
        let mut out = [DVec3::ZERO; 3];
        if m[0] > 0.0 {
            out[0] = azimuthal(0, &circular, phi);
        }
        if m[1] > 0.0 {
            out[1] = azimuthal(1, &circular, phi);
        }
        if m[2] > 0.0 {
            out[2] = self.trt(wi, wo, &circular, phi);
        }
        out
    }

    /// N_R in closed form, N_TT and N_TRT from the table where it reaches (exactly beyond),
    /// an elliptical fiber's N_TRT exactly.
    fn azimuthal_tabulated(
        &self,
        table: &NpTable,
        wi: FiberAngles,
        wo: FiberAngles,
        theta_d: f64,
        phi: f64,
    ) -> [DVec3; 3] {
        let p = &self.params;
        let Some([tt, trt]) = table.lookup(theta_d, phi) else {
            return self.azimuthal_exact(wi, wo, theta_d, phi, &[1.0; 3]);
        };
        let r = DVec3::splat(n_r(p.eta, theta_d, phi));
        if p.eccentricity == 1.0 {
            return [r, tt, trt];
        }
        let circular = Interface::new(p.eta, theta_d, p.mu_a);
        [r, tt, self.trt(wi, wo, &circular, phi)]
    }

    /// N_TRT at η*(φ_h) (the circle's interface unless the fiber is elliptical).
    fn trt(&self, wi: FiberAngles, wo: FiberAngles, circular: &Interface, phi: f64) -> DVec3 {
        let p = &self.params;
        let eta = eta_star(p.eta, p.eccentricity, wi.phi + wo.phi);
        let interface = if eta == p.eta {
            *circular
        } else {
            let theta_d = 0.5 * (wo.theta - wi.theta);
            Interface::new(eta, theta_d, p.mu_a)
        };
        azimuthal_trt(&interface, p, phi)
    }
}

/// N_R(φ) = F(η′, η″, γ) cos γ / 4 at its one root γ = −φ/2 of Φ̂(0, γ) = −2γ ≡ φ
/// (Marschner et al. 2003 "Finding N_p" with p = 0, where |dΦ̂/dh| = 2 / cos γ): what
/// [`azimuthal`] finds for R by its root search. The Bravais indices from sin θ_d and
/// cos θ_d with one square root.
fn n_r(eta: f64, theta_d: f64, phi: f64) -> f64 {
    let (sin_d, cos_d) = sin_cos_quadrant(theta_d);
    let cos_d = cos_d.abs();
    let root = (eta * eta - sin_d * sin_d).max(1e-300).sqrt();
    let eta_prime = root / cos_d.max(1e-12);
    let eta_double_prime = eta * eta * cos_d / root;
    let (sin_g, cos_g) = sin_cos_quadrant(0.5 * phi.abs());
    0.25 * cos_g * fresnel_oblique_at(eta_prime, eta_double_prime, sin_g, cos_g)
}

/// ½ cos θ_o / cos²θ_d: Marschner's 1/cos²θ_d, his M taken as a density in θ_o (½) and his
/// curve-radiance S turned into power per steradian (cos θ_o); module documentation.
fn per_steradian_factor(theta_o: f64, theta_d: f64) -> f64 {
    0.5 * cos_quadrant(theta_o).max(0.0) / cos_quadrant(theta_d).powi(2).max(MIN_COS2_THETA_D)
}

/// Floor on cos²θ_d, reached only within 1e-6 rad of θ_o = −θ_i = ±π/2.
const MIN_COS2_THETA_D: f64 = 1e-12;
/// Floor on |dΦ̂/dγ| where two roots merge (a caustic), so N stays finite there.
const MIN_SLOPE: f64 = 1e-9;
