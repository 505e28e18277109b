//! The hair scattering model of Marschner, Jensen, Cammarano, Worley and Hanrahan 2003, *Light
//! scattering from human hair fibers* (docs/references.md lists the survey we read it from), with its TRT caustic treatment and
//! eccentricity, and an exact importance sampling.
//!
//! # The model
//! Three lobes p = 0 (R), 1 (TT), 2 (TRT), each M_p(θ_h) N_p(φ) / cos²θ_d (Marschner et al. 2003 "The
//! Grand Result"; Marschner 2003's practical model):
//! - M_p is a unit-integral Gaussian in θ_h = (θ_i + θ_o)/2 with shift α_p and width β_p:
//!   α_TT = −α_R/2, α_TRT = −3α_R/2, β_TT = β_R/2, β_TRT = 2β_R (Marschner 2003 Table 1).
//! - N_p(φ) = Σ A(p, h) / |2 dΦ̂/dh| over every root γ_i ∈ [−π/2, π/2] of
//!   Φ̂(p, γ_i) = (6pc/π − 2)γ_i − 8pc/π³ γ_i³ + pπ ≡ φ (mod 2π), c = asin(1/η′),
//!   η′ = η′(η, θ_d) (Marschner 2003's cubic approximation; Marschner et al. 2003 "Finding γ_i"). The cubic has one or three real
//!   roots; those in [−π/2, π/2] are what count: TRT has three between its caustics ±φ_c and
//!   one beyond them, except for η′ < 1.556, where φ_c lies beyond the edge ray
//!   |Φ̂(2, ±π/2) − 2π| = |4c − π|: there two remain between the edge ray and φ_c, and none
//!   beyond φ_c. Φ̂ is within 0.019 rad (TT) and 0.038 rad (TRT) of the exact Φ for every
//!   η′ ≥ 1.55 (0.037 and 0.075 at η′ = 1.4; `cubic_deflection_tracks_the_exact_one`).
//! - A(0, h) = F(η′, η″, γ_i) and A(p, h) = (1 − F(η′, η″, γ_i))² F(1/η′, 1/η″, γ_t)^{p−1} T^p
//!   with the oblique Fresnel factor and T = exp(−2 μ_a cos γ_t / cos θ_t), the chord of the
//!   unit circle (docs/conventions.md §8 erratum; Marschner et al. 2003 prints exp(−σ_a(2 + 2 cos 2γ_t))). The whole
//!   azimuthal part is a function of θ_d, as in Marschner's paper, so θ_t is the refracted
//!   inclination of the difference angle, sin θ_t = sin θ_d / η (equal to θ_i's on the specular
//!   cone), and the model stays reciprocal.
//! - TRT replaces its caustic singularities by Gaussian glints (Marschner 2003's N_TRT listing, see
//!   [`Caustic`]), and uses η*(φ_h) for an elliptical fiber (Xu et al. 2011 eq. 24, see [`eta_star`]).
//!
//! # Units (docs/conventions.md §3)
//! Marschner's S is defined through curve radiance L̄, radiance integrated across the fiber's
//! projected width, which is power per steradian per unit *projected* length: a unit length of
//! fiber seen from ω_o projects to cos θ_o. The power intercepted per unit length from a beam
//! of radiance L_i over dω_i is D L_i cos θ_i dω_i, which is exactly the factor in Marschner's
//! L̄_o = D ∫ S L_i cos θ_i dω_i. So the fraction of intercepted power per steradian — this
//! project's S — is Marschner's S times cos θ_o. (docs/conventions.md's "Marschner's S with cos θ_i kept
//! outside" misses this cos θ_o.) Check on his smooth cylinder, S = δ(θ_o + θ_i) N / cos²θ:
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
//! given θ_d: for R and TT
//! exactly as the cubic maps a uniformly distributed offset h, φ = Φ̂(p, asin h), whose density
//! Σ 1/|2 dΦ̂/dh| over the same roots is N_p with A = 1; for TRT a mixture of the two glint
//! Gaussians, a wrapped Gaussian over Φ̂(2, ·)'s range and a uniform share. Every density is
//! closed-form, so [`FiberModel::pdf`] is exactly the density of [`FiberModel::sample`], and
//! weights are S / pdf ([`crate::deon2011::finish_sample`]).

use crate::azimuthal::wrapped_gaussian;
use crate::bravais::{cos_theta_t, eta_par, eta_perp, gamma_t, segment_transmittance};
use crate::cubic::Cubic;
use crate::deon2011::finish_sample;
use crate::frame::{FiberAngles, wrap_pi};
use crate::fresnel::fresnel_oblique;
use crate::lobe::{Lobe, LobeValues, channel_mean};
use crate::model::{FiberModel, FiberSample, per_steradian, select_and_remap};
use crate::params::FiberParams;
use crate::ranges::{self, RangeError};
use crate::special::{GaussLegendre, normal_pdf, normal_quantile};
use glam::DVec3;
use std::f64::consts::{FRAC_PI_2, PI, SQRT_2};
use std::sync::OnceLock;

/// The parameters of Marschner 2003 (its Table 1), angles in radians.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct MarschnerParams {
    /// Index of refraction η.
    pub eta: f64,
    /// Longitudinal shift of the R lobe α_R (the paper: −10° to −5°).
    pub alpha_r: f64,
    /// Longitudinal width (standard deviation) of the R lobe β_R (the paper: 5° to 10°).
    pub beta_r: f64,
    /// Absorption μ_a per unit radius, RGB (the paper: σ_a from 0.2 to ∞).
    pub mu_a: DVec3,
    /// Eccentricity a of the cross section, 1 for a circle (the paper: 0.85 to 1).
    pub eccentricity: f64,
    /// Azimuthal width w_c of the TRT caustic glint (the paper: 10° to 25°).
    pub caustic_width: f64,
    /// Glint scale factor k_G (the paper: 0.5 to 5).
    pub glint_scale: f64,
    /// Fade range Δη′ over which the glint vanishes once the caustics merge (0.2 to 0.4).
    pub caustic_fade: f64,
    /// Caustic intensity limit Δh_M (0.5).
    pub caustic_limit: f64,
}

/// Table 1's α_R, β_R and w_c in degrees, as [`MarschnerParams::default`] takes them and as a
/// user types them.
pub const DEFAULT_ALPHA_R_DEG: f64 = -7.5;
/// See [`DEFAULT_ALPHA_R_DEG`].
pub const DEFAULT_BETA_R_DEG: f64 = 7.5;
/// See [`DEFAULT_ALPHA_R_DEG`].
pub const DEFAULT_CAUSTIC_WIDTH_DEG: f64 = 17.5;

impl Default for MarschnerParams {
    /// Marschner 2003 Table 1: η = 1.55, the middle of each range given as a range
    /// (α_R = −7.5°, β_R = 7.5°, w_c = 17.5°, Δη′ = 0.3), Δh_M = 0.5, a circular fiber, and
    /// k_G = 0.5, the low end of its range and the scale at which a glint carries the energy
    /// of the offsets Δh it replaces (k_G A Δh per caustic against ½ A Δh, twice). μ_a is a
    /// light brown starting at the table's smallest σ_a.
    fn default() -> Self {
        Self {
            eta: 1.55,
            alpha_r: DEFAULT_ALPHA_R_DEG.to_radians(),
            beta_r: DEFAULT_BETA_R_DEG.to_radians(),
            mu_a: DVec3::new(0.2, 0.3, 0.5),
            eccentricity: 1.0,
            caustic_width: DEFAULT_CAUSTIC_WIDTH_DEG.to_radians(),
            glint_scale: 0.5,
            caustic_fade: 0.3,
            caustic_limit: 0.5,
        }
    }
}

/// Why a parameter set cannot describe a Marschner fiber: the parameter (named as a scene
/// key, angles in degrees), its value and its range.
pub type MarschnerError = RangeError;

impl MarschnerParams {
    /// (α_p, β_p) of M_R, M_TT, M_TRT from α_R, β_R (Marschner 2003 Table 1: α_TT = −α_R/2,
    /// α_TRT = −3α_R/2, β_TT = β_R/2, β_TRT = 2β_R).
    pub fn longitudinal(&self) -> [(f64, f64); 3] {
        let (a, b) = (self.alpha_r, self.beta_r);
        [(a, b), (-0.5 * a, 0.5 * b), (-1.5 * a, 2.0 * b)]
    }

    /// Checks every field against its range ([`crate::ranges`]), returning the first fault.
    pub fn validate(&self) -> Result<(), MarschnerError> {
        ranges::ETA.check(self.eta)?;
        ranges::ALPHA_R_DEG.check_radians(self.alpha_r)?;
        ranges::BETA_R_DEG.check_radians(self.beta_r)?;
        ranges::MU_A.check_all(&self.mu_a.to_array())?;
        ranges::ECCENTRICITY.check(self.eccentricity)?;
        ranges::CAUSTIC_WIDTH_DEG.check_radians(self.caustic_width)?;
        ranges::GLINT_SCALE.check(self.glint_scale)?;
        ranges::CAUSTIC_FADE.check(self.caustic_fade)?;
        ranges::CAUSTIC_LIMIT.check(self.caustic_limit)?;
        Ok(())
    }
}

/// The Marschner et al. 2003 fiber model.
#[derive(Clone, Debug)]
pub struct Marschner2003 {
    params: MarschnerParams,
    /// M_R, M_TT, M_TRT.
    lobes: [GaussianLobe; 3],
    /// Each lobe's energy estimate over θ_i, for lobe choice; built on first use.
    energy: OnceLock<EnergyTable>,
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
            energy: OnceLock::new(),
        })
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

    /// S of R, TT and TRT (docs/conventions.md §3 units, see the module documentation).
    fn lobe_values(&self, wi: FiberAngles, wo: FiberAngles) -> [DVec3; 3] {
        let theta_h = 0.5 * (wi.theta + wo.theta);
        let theta_d = 0.5 * (wo.theta - wi.theta);
        let phi = wrap_pi(wo.phi - wi.phi);
        let scale = per_steradian_factor(wo.theta, theta_d);
        let m = self.lobes.map(|lobe| lobe.eval(theta_h) * scale);
        let p = &self.params;
        let circular = Interface::new(p.eta, theta_d, p.mu_a);
        let mut out = [DVec3::ZERO; 3];
        if m[0] > 0.0 {
            out[0] = m[0] * azimuthal(0, &circular, phi);
        }
        if m[1] > 0.0 {
            out[1] = m[1] * azimuthal(1, &circular, phi);
        }
        if m[2] > 0.0 {
            let eta = eta_star(p.eta, p.eccentricity, wi.phi + wo.phi);
            let interface = if eta == p.eta {
                circular
            } else {
                Interface::new(eta, theta_d, p.mu_a)
            };
            out[2] = m[2] * azimuthal_trt(&interface, p, phi);
        }
        out
    }
}

/// ½ cos θ_o / cos²θ_d: Marschner's 1/cos²θ_d, his M taken as a density in θ_o (½) and his
/// curve-radiance S turned into power per steradian (cos θ_o); module documentation.
fn per_steradian_factor(theta_o: f64, theta_d: f64) -> f64 {
    0.5 * theta_o.cos().max(0.0) / theta_d.cos().powi(2).max(MIN_COS2_THETA_D)
}

/// Floor on cos²θ_d, reached only within 1e-6 rad of θ_o = −θ_i = ±π/2.
const MIN_COS2_THETA_D: f64 = 1e-12;
/// Floor on |dΦ̂/dγ| where two roots merge (a caustic), so N stays finite there.
const MIN_SLOPE: f64 = 1e-9;

// ---------------------------------------------------------------------------------------------
// Longitudinal lobes

/// M_p: a unit-integral Gaussian in θ_h (Marschner 2003's practical model, Table 1).
#[derive(Clone, Copy, Debug, PartialEq)]
struct GaussianLobe {
    alpha: f64,
    beta: f64,
}

impl GaussianLobe {
    /// M_p(θ_h).
    fn eval(&self, theta_h: f64) -> f64 {
        normal_pdf((theta_h - self.alpha) / self.beta) / self.beta
    }

    /// The density in θ_o of θ_o = 2θ_h − θ_i with θ_h drawn from M_p: M_p / 2. It is not
    /// renormalised to θ_o ∈ [−π/2, π/2]; draws beyond are rejected instead.
    fn density(&self, theta_i: f64, theta_o: f64) -> f64 {
        0.5 * self.eval(0.5 * (theta_i + theta_o))
    }

    /// θ_o = 2θ_h − θ_i with θ_h from M_p by inversion, or `None` beyond ±π/2.
    fn sample(&self, theta_i: f64, u: f64) -> Option<f64> {
        let theta_h = self.alpha + self.beta * normal_quantile(u);
        let theta_o = 2.0 * theta_h - theta_i;
        (theta_o.abs() <= FRAC_PI_2).then_some(theta_o)
    }

    /// Roughly the share of M_p that lands inside θ_o ∈ [−π/2, π/2] (a logistic stand-in for
    /// the normal distribution function, within 2e-4): it only steers lobe choice.
    fn approximate_mass(&self, theta_i: f64) -> f64 {
        let cdf = |theta_h: f64| {
            let x = (theta_h - self.alpha) / self.beta;
            0.5 * (1.0 + ((2.0 / PI).sqrt() * (x + 0.044715 * x * x * x)).tanh())
        };
        (cdf(0.5 * (theta_i + FRAC_PI_2)) - cdf(0.5 * (theta_i - FRAC_PI_2))).max(0.0)
    }
}

// ---------------------------------------------------------------------------------------------
// The cubic deflection and its roots

/// Φ̂(p, γ) = (6pc/π − 2)γ − (8pc/π³)γ³ + pπ with c = asin(1/η′) (Marschner 2003's cubic
/// approximation, Marschner et al. 2003 "Finding γ_i"):
/// the exact Φ = 2pγ_t − 2γ + pπ with γ_t replaced by the cubic through γ_t(0) = 0,
/// γ_t(±π/2) = ±c and dγ_t/dγ(±π/2) = 0.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CubicDeflection {
    p: u32,
    /// Coefficient of γ.
    a: f64,
    /// Coefficient of −γ³.
    b: f64,
}

/// Up to six roots γ_i: three per branch φ + 2πk, and Φ̂'s range spans less than 4π.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct GammaRoots {
    values: [f64; 6],
    len: usize,
}

impl GammaRoots {
    pub fn as_slice(&self) -> &[f64] {
        &self.values[..self.len]
    }
}

impl CubicDeflection {
    pub fn new(p: u32, eta_prime: f64) -> Self {
        let c = (1.0 / eta_prime).clamp(-1.0, 1.0).asin();
        let pc = p as f64 * c;
        Self {
            p,
            a: 6.0 * pc / PI - 2.0,
            b: 8.0 * pc / PI.powi(3),
        }
    }

    /// Φ̂(p, γ), unwrapped.
    pub fn phi(&self, gamma: f64) -> f64 {
        (self.a - self.b * gamma * gamma) * gamma + self.p as f64 * PI
    }

    /// dΦ̂/dγ.
    pub fn slope(&self, gamma: f64) -> f64 {
        self.a - 3.0 * self.b * gamma * gamma
    }

    /// d²Φ̂/dγ².
    fn curvature(&self, gamma: f64) -> f64 {
        -6.0 * self.b * gamma
    }

    /// The positive γ where dΦ̂/dγ = 0 (the caustic), if Φ̂ has a fold inside (−π/2, π/2).
    pub fn fold(&self) -> Option<f64> {
        let g = (self.a / (3.0 * self.b)).sqrt();
        (self.a > 0.0 && self.b > 0.0 && g < FRAC_PI_2).then_some(g)
    }

    /// The smallest and largest Φ̂ over [−π/2, π/2].
    fn range(&self) -> (f64, f64) {
        let ends = [self.phi(-FRAC_PI_2), self.phi(FRAC_PI_2)];
        let folds = self.fold().map(|g| [self.phi(-g), self.phi(g)]);
        ends.into_iter()
            .chain(folds.into_iter().flatten())
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
                (lo.min(x), hi.max(x))
            })
    }

    /// Every γ ∈ [−π/2, π/2] with Φ̂(p, γ) = φ + 2πk for some integer k.
    pub fn roots(&self, phi: f64) -> GammaRoots {
        let (lo, hi) = self.range();
        let k_min = ((lo - phi) / (2.0 * PI)).ceil() as i64;
        let k_max = ((hi - phi) / (2.0 * PI)).floor() as i64;
        let mut out = GammaRoots::default();
        for k in k_min..=k_max {
            let target = phi + 2.0 * PI * k as f64;
            let cubic = Cubic([self.p as f64 * PI - target, self.a, 0.0, -self.b]);
            for &g in cubic.roots_in(-FRAC_PI_2, FRAC_PI_2).as_slice() {
                if out.len < out.values.len() {
                    out.values[out.len] = g;
                    out.len += 1;
                }
            }
        }
        out
    }

    /// 1/|2 dΦ̂/dh| = cos γ / (2 |dΦ̂/dγ|), the density in φ of the offsets near γ.
    fn inverse_spread(&self, gamma: f64) -> f64 {
        gamma.cos().max(0.0) / (2.0 * self.slope(gamma).abs().max(MIN_SLOPE))
    }
}

// ---------------------------------------------------------------------------------------------
// Attenuation and the azimuthal functions

/// The optics of the normal-plane problem at one θ_d: Bravais' indices and the refracted
/// inclination that stretches the internal path.
#[derive(Clone, Copy, Debug)]
struct Interface {
    eta_perp: f64,
    eta_par: f64,
    cos_theta_t: f64,
    mu_a: DVec3,
}

impl Interface {
    fn new(eta: f64, theta_d: f64, mu_a: DVec3) -> Self {
        Self {
            eta_perp: eta_perp(eta, theta_d),
            eta_par: eta_par(eta, theta_d),
            cos_theta_t: cos_theta_t(eta, theta_d),
            mu_a,
        }
    }

    /// A(p, h) at h = sin γ_i (Marschner et al. 2003 "Finding A", with docs/conventions.md §8's transmittance; T^p
    /// as one exponential of the p segments' summed path).
    fn attenuation(&self, p: u32, gamma_i: f64) -> DVec3 {
        let f = fresnel_oblique(self.eta_perp, self.eta_par, gamma_i);
        if p == 0 {
            return DVec3::splat(f);
        }
        let gt = gamma_t(gamma_i.sin(), self.eta_perp);
        let internal = fresnel_oblique(1.0 / self.eta_perp, 1.0 / self.eta_par, gt);
        let path = |mu: f64| segment_transmittance(p as f64 * mu, gt, self.cos_theta_t);
        let t = DVec3::new(path(self.mu_a.x), path(self.mu_a.y), path(self.mu_a.z));
        (1.0 - f).powi(2) * internal.powi(p as i32 - 1) * t
    }

    fn deflection(&self, p: u32) -> CubicDeflection {
        CubicDeflection::new(p, self.eta_perp)
    }
}

/// N_p(φ) = Σ A(p, h) / |2 dΦ̂/dh| over every root (Marschner et al. 2003 "Finding N_p").
fn azimuthal(p: u32, interface: &Interface, phi: f64) -> DVec3 {
    let deflection = interface.deflection(p);
    deflection
        .roots(phi)
        .as_slice()
        .iter()
        .map(|&g| interface.attenuation(p, g) * deflection.inverse_spread(g))
        .sum()
}

/// Marschner 2003's treatment of the TRT caustics (its listing for N_TRT), taken at the
/// cubic's own fold so that the singularity removed is the one N_P has.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Caustic {
    /// φ_c, wrapped: the glints sit at ±φ_c.
    pub phi_c: f64,
    /// γ at the caustic (0 once the caustics have merged).
    pub gamma_c: f64,
    /// Δh, the span of offsets the glint stands for.
    pub delta_h: f64,
    /// t, the glint's strength: 1 while the caustics exist, fading to 0 over Δη′ after.
    pub t: f64,
}

impl Caustic {
    /// Marschner 2003's N_TRT listing: for η′ < 2, h_c where dΦ/dh = 0, φ_c = Φ(2, h_c),
    /// Δh = min(Δh_M, 2 √(2 w_c / |d²Φ/dh²(h_c)|)), t = 1; for η′ ≥ 2, φ_c = 0, Δh = Δh_M and
    /// t = 1 − smoothstep(2, 2 + Δη′, η′). The paper's h_c = √((4 − η′²)/3) is the exact Φ's
    /// fold; the cubic's fold (γ_c² = a/3b) is used here, since the cubic's N_P is what the
    /// glint replaces: they differ by ≤ 0.019 in h_c and ≤ 0.033 rad in φ_c for
    /// η′ ∈ [1.55, 2), more below (0.11 rad in φ_c at η′ = 1.2).
    /// Some transcriptions of the listing drop the "1 −" in t, which would switch the glint
    /// off at η′ = 2 and back on above; t is kept continuous here.
    pub fn new(eta_prime: f64, params: &MarschnerParams) -> Self {
        let deflection = CubicDeflection::new(2, eta_prime);
        match deflection.fold() {
            Some(g) if eta_prime < 2.0 => {
                let cos2 = g.cos().powi(2);
                let d2phi_dh2 = deflection.curvature(g) / cos2;
                let spread = 2.0 * (2.0 * params.caustic_width / d2phi_dh2.abs()).sqrt();
                Self {
                    phi_c: wrap_pi(deflection.phi(g)),
                    gamma_c: g,
                    delta_h: params.caustic_limit.min(spread),
                    t: 1.0,
                }
            }
            _ => Self {
                phi_c: 0.0,
                gamma_c: 0.0,
                delta_h: params.caustic_limit,
                t: 1.0 - smoothstep(2.0, 2.0 + params.caustic_fade, eta_prime),
            },
        }
    }
}

fn smoothstep(a: f64, b: f64, x: f64) -> f64 {
    let s = ((x - a) / (b - a)).clamp(0.0, 1.0);
    s * s * (3.0 - 2.0 * s)
}

/// N_TRT (Marschner 2003's listing): N_P(2, φ) with the caustics removed,
/// L ← L (1 − t g(w_c; φ − φ_c)/g(w_c; 0)) (1 − t g(w_c; φ + φ_c)/g(w_c; 0)), plus the glints
/// t k_G A(2, h_c) Δh (g(w_c; φ − φ_c) + g(w_c; φ + φ_c)), g a wrapped unit Gaussian.
fn azimuthal_trt(interface: &Interface, params: &MarschnerParams, phi: f64) -> DVec3 {
    let caustic = Caustic::new(interface.eta_perp, params);
    let v = params.caustic_width.powi(2);
    let g0 = wrapped_gaussian(0.0, v);
    let (g_minus, g_plus) = (
        wrapped_gaussian(phi - caustic.phi_c, v),
        wrapped_gaussian(phi + caustic.phi_c, v),
    );
    // Each factor lies in [0, 1]: the wrapped Gaussian peaks at 0.
    let keep = (1.0 - caustic.t * g_minus / g0) * (1.0 - caustic.t * g_plus / g0);
    let smooth = azimuthal(2, interface, phi) * keep.max(0.0);
    let glint = caustic.t * params.glint_scale * caustic.delta_h * (g_minus + g_plus);
    smooth + glint * interface.attenuation(2, caustic.gamma_c)
}

/// η*(φ_h) of an elliptical fiber (Xu et al. 2011 eq. 24, after Marschner 2003):
/// η*₁ = 2(η − 1)a² − η + 2, η*₂ = 2(η − 1)a⁻² − η + 2,
/// η* = ½((η*₁ + η*₂) + cos(2φ_h)(η*₁ − η*₂)), with 2φ_h = φ_i + φ_o. A circle (a = 1) gives η.
pub fn eta_star(eta: f64, eccentricity: f64, phi_sum: f64) -> f64 {
    if eccentricity == 1.0 {
        return eta;
    }
    let e2 = eccentricity * eccentricity;
    let eta1 = 2.0 * (eta - 1.0) * e2 - eta + 2.0;
    let eta2 = 2.0 * (eta - 1.0) / e2 - eta + 2.0;
    0.5 * ((eta1 + eta2) + phi_sum.cos() * (eta1 - eta2))
}

// ---------------------------------------------------------------------------------------------
// Importance sampling

/// Share of TRT's azimuthal proposal drawn uniformly, so no φ is left uncovered.
const TRT_UNIFORM_SHARE: f64 = 0.1;
/// Share of TRT's azimuthal proposal given to the two glints at full strength (t = 1).
const TRT_GLINT_SHARE: f64 = 0.45;
/// Every lobe is chosen with at least this fraction of the total energy estimate.
const LOBE_FLOOR: f64 = 0.05;

/// TRT's azimuthal proposal at one θ_d: the glint Gaussians at ±φ_c (width w_c), a wrapped
/// Gaussian at 0 spanning Φ̂(2, ·)'s range, and a uniform share.
struct TrtProposal {
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
const ENERGY_NODES: usize = 33;

/// ½ ∫ A(p, h) dh (channel mean) at each lobe's peak θ_d = α_p − θ_i, tabulated over θ_i and
/// interpolated linearly: any positive function of θ_i serves lobe choice, this one follows
/// the lobes' energies.
#[derive(Clone, Debug)]
struct EnergyTable([[f64; ENERGY_NODES]; 3]);

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

    /// The density of φ given θ_d with which lobe p is sampled.
    fn phi_density(&self, p: usize, theta_d: f64, phi: f64) -> f64 {
        let eta_prime = eta_perp(self.params.eta, theta_d);
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
        let eta_prime = eta_perp(self.params.eta, theta_d);
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
        finish_sample(self, wi, wo, Lobe::from_index(p), 1)
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bravais::azimuthal_deflection;
    use crate::testing::{check_weights, chi2_test};
    use proptest::prelude::*;

    fn model(params: MarschnerParams) -> Marschner2003 {
        Marschner2003::new(params).expect("valid parameters")
    }

    /// ∫ₐᵇ f by `panels` panels of a 16-point Gauss–Legendre rule.
    fn composite(a: f64, b: f64, panels: usize, mut f: impl FnMut(f64) -> f64) -> f64 {
        let rule = GaussLegendre::cached(16);
        let h = (b - a) / panels as f64;
        (0..panels)
            .map(|k| rule.integrate(a + k as f64 * h, a + (k + 1) as f64 * h, &mut f))
            .sum()
    }

    /// ∫ S_lobe dω_o over the sphere (channel x), θ_o restricted to [lo, hi]; φ runs from
    /// the back (φ_o − φ_i = −π, where N has a kink) round to the back.
    fn lobe_energy(m: &Marschner2003, wi: FiberAngles, lobe: Lobe, lo: f64, hi: f64) -> f64 {
        composite(lo, hi, 16, |theta_o| {
            theta_o.cos()
                * composite(wi.phi - PI, wi.phi + PI, 8, |phi| {
                    m.eval(wi, FiberAngles::new(theta_o, wrap_pi(phi)))[lobe].x
                })
        })
    }

    /// ½ ∫ F(η′, η″, asin h) dh = ∫₀^{π/2} F cos γ dγ at inclination θ.
    fn fresnel_integral(eta: f64, theta: f64) -> f64 {
        let (ep, epp) = (eta_perp(eta, theta), eta_par(eta, theta));
        composite(0.0, FRAC_PI_2, 8, |g| fresnel_oblique(ep, epp, g) * g.cos())
    }

    /// ∫ S_R dω / (½ ∫ F dh) − 1 for an unshifted R lobe of width β_R at θ_i.
    fn r_energy_error(beta_r: f64, theta_i: f64) -> f64 {
        let params = MarschnerParams {
            alpha_r: 0.0,
            beta_r,
            ..Default::default()
        };
        let wi = FiberAngles::new(theta_i, 0.4);
        let reach = 10.0 * 2.0 * beta_r;
        let got = lobe_energy(
            &model(params),
            wi,
            Lobe::R,
            -theta_i - reach,
            -theta_i + reach,
        );
        got / fresnel_integral(params.eta, theta_i) - 1.0
    }

    #[test]
    fn r_lobe_energy_is_the_fresnel_integral() {
        // Narrow and unshifted, the R lobe is the smooth cylinder's reflection blurred along
        // the specular cone: its energy is ½ ∫ F dh up to the O(β²) of cos²θ_o / cos²θ_d,
        // predicted β_R² (2 tan²θ_i − 3 sec²θ_i) to second order.
        let predicted =
            |beta: f64, t: f64| beta * beta * (2.0 * t.tan().powi(2) - 3.0 / t.cos().powi(2));
        let mut worst: f64 = 0.0;
        for &theta_i in &[0.0, 0.3, -0.6, 0.9] {
            let err = r_energy_error(0.1f64.to_radians(), theta_i);
            worst = worst.max(err.abs());
            assert!(err.abs() < 5e-5, "θ_i {theta_i}: relative error {err}");
            let beta = 1f64.to_radians();
            let wide = r_energy_error(beta, theta_i);
            let ratio = wide / predicted(beta, theta_i);
            assert!(
                (0.5..1.5).contains(&ratio),
                "θ_i {theta_i}: {wide} vs {ratio}"
            );
            eprintln!(
                "θ_i {theta_i}: error at β_R = 1° {wide:.3e}, predicted {:.3e}",
                predicted(beta, theta_i)
            );
        }
        eprintln!(
            "R lobe energy vs Fresnel integral at β_R = 0.1°: worst relative error {worst:.2e}"
        );
    }

    #[test]
    fn energy_factor_of_the_cos2_normalisation() {
        // E(θ_i) = ∫ ½ M_R(θ_h) cos²θ_o / cos²θ_d dθ_o for the default lobe.
        let m = model(MarschnerParams::default());
        let lobe = m.lobes[0];
        for &(theta_i, lo, hi) in &[(0.0, 0.89, 0.91), (-0.6, 1.05, 1.07), (0.6, 0.71, 0.74)] {
            let e = composite(-FRAC_PI_2, FRAC_PI_2, 64, |theta_o| {
                let theta_d = 0.5 * (theta_o - theta_i);
                0.5 * lobe.eval(0.5 * (theta_i + theta_o)) * theta_o.cos().powi(2)
                    / theta_d.cos().powi(2)
            });
            eprintln!("E_R(θ_i = {theta_i}) = {e:.4}");
            assert!((lo..hi).contains(&e), "θ_i {theta_i}: {e}");
        }
    }

    /// max over γ ∈ [−π/2, π/2] of |Φ̂(p, γ) − Φ(p, sin γ)|.
    fn cubic_error(p: u32, eta_prime: f64) -> f64 {
        let d = CubicDeflection::new(p, eta_prime);
        (0..=4000)
            .map(|k| {
                let g = -FRAC_PI_2 + PI * k as f64 / 4000.0;
                (d.phi(g) - azimuthal_deflection(p, g.sin(), eta_prime)).abs()
            })
            .fold(0.0, f64::max)
    }

    #[test]
    fn cubic_deflection_tracks_the_exact_one() {
        // R is exact; TT and TRT err by 2p |γ̂_t − γ_t|, least near η′ = 2 and most for η′
        // near 1. Human hair (η = 1.55) has η′ ≥ 1.55 at every inclination.
        let etas = [1.55, 1.7, 2.0, 2.5, 3.0, 5.0, 20.0];
        let worst = |p| etas.iter().map(|&e| cubic_error(p, e)).fold(0.0, f64::max);
        let (r, tt, trt) = (worst(0), worst(1), worst(2));
        eprintln!(
            "max |Φ̂ − Φ| for η′ ≥ 1.55: R {r:.1e}, TT {tt:.4}, TRT {trt:.4}; at η′ = 1.4: \
             TT {:.4}, TRT {:.4}",
            cubic_error(1, 1.4),
            cubic_error(2, 1.4)
        );
        assert!(r < 1e-12);
        assert!(tt < 0.02 && trt < 0.04, "TT {tt} TRT {trt}");
    }

    /// Roots of Φ̂(p, ·) ≡ φ found by sign changes of the wrapped difference on a dense grid.
    fn dense_root_count(d: &CubicDeflection, phi: f64) -> usize {
        let n = 8_000;
        let f = |k: usize| wrap_pi(d.phi(-FRAC_PI_2 + PI * k as f64 / n as f64) - phi);
        (0..n)
            .filter(|&k| {
                let (a, b) = (f(k), f(k + 1));
                (a <= 0.0) != (b <= 0.0) && (a - b).abs() < 1.0
            })
            .count()
    }

    #[test]
    fn every_root_is_found() {
        let mut checked = 0;
        for &eta_prime in &[1.05, 1.3, 1.55, 1.8, 2.0, 2.5, 10.0] {
            for p in 0..3u32 {
                let d = CubicDeflection::new(p, eta_prime);
                // Values where the count changes: folds and the edge rays at γ = ±π/2.
                let special: Vec<f64> = [d.phi(FRAC_PI_2), d.phi(-FRAC_PI_2)]
                    .into_iter()
                    .chain(d.fold().into_iter().flat_map(|g| [d.phi(g), d.phi(-g)]))
                    .map(wrap_pi)
                    .collect();
                for k in 0..360 {
                    let phi = wrap_pi(-PI + (k as f64 + 0.37) * PI / 180.0);
                    if special.iter().any(|s| wrap_pi(phi - s).abs() < 1e-3) {
                        continue;
                    }
                    let roots = d.roots(phi);
                    for &g in roots.as_slice() {
                        assert!(
                            wrap_pi(d.phi(g) - phi).abs() < 1e-12,
                            "p {p} η′ {eta_prime} φ {phi}: root {g}"
                        );
                    }
                    assert_eq!(
                        roots.as_slice().len(),
                        dense_root_count(&d, phi),
                        "p {p} η′ {eta_prime} φ {phi}"
                    );
                    checked += 1;
                }
            }
        }
        assert!(checked > 7_000);
    }

    /// ∫ N dφ over the circle, from the back (φ = −π) round to the back; fine panels, since
    /// N has kinks where a polarisation turns totally reflecting (η″ < 1 at large θ_d).
    fn integral_over_phi(n: impl Fn(f64) -> DVec3) -> DVec3 {
        let c = |k: usize| composite(-PI, PI, 2048, |phi| n(phi)[k]);
        DVec3::new(c(0), c(1), c(2))
    }

    /// ½ ∫ A(p, h) dh.
    fn mean_attenuation(interface: &Interface, p: u32) -> DVec3 {
        let c = |k: usize| {
            composite(0.0, FRAC_PI_2, 512, |g| {
                interface.attenuation(p, g)[k] * g.cos()
            })
        };
        DVec3::new(c(0), c(1), c(2))
    }

    #[test]
    fn azimuthal_functions_integrate_to_the_mean_attenuation() {
        // Σ over roots of A / |2 dΦ̂/dh| is a change of variables from h to φ: whatever the
        // cubic's error, ∫ N_p dφ = ½ ∫ A dh when every root and its Jacobian are right.
        // (TRT without folds, η′ ≥ 2, so that N_P has no integrable singularity to resolve.)
        let mu_a = DVec3::new(0.0, 0.4, 1.5);
        for &(p, eta, theta_d) in &[
            (0, 1.55, 0.3),
            (1, 1.55, 0.0),
            (1, 1.3, -0.7),
            (2, 2.3, 0.2),
            (2, 1.55, 1.1),
        ] {
            let interface = Interface::new(eta, theta_d, mu_a);
            assert!(p < 2 || interface.deflection(2).fold().is_none());
            let got = integral_over_phi(|phi| azimuthal(p, &interface, phi));
            let want = mean_attenuation(&interface, p);
            assert!(
                (got - want).abs().max_element() < 1e-5 * want.max_element(),
                "p {p} η {eta}: {got} vs {want}"
            );
        }
    }

    #[test]
    fn glint_energy_against_the_caustics_it_replaces() {
        // With k_G = 0.5 each glint carries the ½ A Δh of the offsets it stands for; the
        // removal takes away a band of N_P around each caustic. Measured for the record.
        let interface = Interface::new(1.55, 0.0, DVec3::new(0.2, 0.3, 0.5));
        let params = MarschnerParams::default();
        let trt = integral_over_phi(|phi| azimuthal_trt(&interface, &params, phi)).x;
        let want = mean_attenuation(&interface, 2).x;
        eprintln!(
            "∫ N_TRT dφ / ½ ∫ A dh at η′ = 1.55, defaults: {:.3}",
            trt / want
        );
        assert!((0.5..0.6).contains(&(trt / want)));
    }

    #[test]
    fn trt_roots_switch_across_the_caustic() {
        // η′ = 1.8: three roots inside the caustic, one beyond it.
        let d = CubicDeflection::new(2, 1.8);
        let phi_c = wrap_pi(d.phi(d.fold().unwrap()));
        assert_eq!(d.roots(phi_c - 1e-4).as_slice().len(), 3);
        assert_eq!(d.roots(phi_c + 1e-4).as_slice().len(), 1);
        assert_eq!(d.roots(-phi_c - 1e-4).as_slice().len(), 1);
        // η′ = 1.55: the caustic lies beyond the edge ray 4c − π, so between them two roots
        // remain, and none beyond the caustic.
        let d = CubicDeflection::new(2, 1.55);
        let phi_c = wrap_pi(d.phi(d.fold().unwrap()));
        let edge = wrap_pi(d.phi(FRAC_PI_2)).abs();
        assert!(edge < phi_c);
        assert_eq!(d.roots(edge - 1e-4).as_slice().len(), 3);
        assert_eq!(d.roots(phi_c - 1e-4).as_slice().len(), 2);
        assert_eq!(d.roots(phi_c + 1e-4).as_slice().len(), 0);
    }

    #[test]
    fn caustic_fold_of_the_cubic_against_the_exact_one() {
        // The paper's h_c = √((4 − η′²)/3) is where the exact dΦ/dh vanishes; the cubic's
        // fold stays close to it.
        let (mut dh, mut dphi) = (0.0f64, 0.0f64);
        for k in 0..=80 {
            let eta_prime = 1.55 + 0.45 * k as f64 / 80.0 - 1e-9;
            let c = Caustic::new(eta_prime, &MarschnerParams::default());
            let h_exact = ((4.0 - eta_prime * eta_prime) / 3.0).sqrt();
            let phi_exact = wrap_pi(azimuthal_deflection(2, h_exact, eta_prime));
            dh = dh.max((c.gamma_c.sin() - h_exact).abs());
            dphi = dphi.max((c.phi_c - phi_exact).abs());
        }
        eprintln!("cubic vs exact caustic, η′ ∈ [1.55, 2): |Δh_c| ≤ {dh:.4}, |Δφ_c| ≤ {dphi:.4}");
        assert!(dh < 0.02 && dphi < 0.035);
    }

    fn n_trt(eta_prime: f64, phi: f64) -> DVec3 {
        let interface = Interface::new(eta_prime, 0.0, DVec3::new(0.2, 0.3, 0.5));
        azimuthal_trt(&interface, &MarschnerParams::default(), phi)
    }

    #[test]
    fn glint_is_finite_and_continuous() {
        for &eta_prime in &[1.3, 1.55, 1.8, 1.99] {
            let c = Caustic::new(eta_prime, &MarschnerParams::default());
            assert_eq!(c.t, 1.0);
            let at = n_trt(eta_prime, c.phi_c);
            assert!(at.is_finite() && at.min_element() >= 0.0);
            // Steps of 1e-6 across ±0.05 of the caustic: no jump above 1e-3 of the peak.
            let values: Vec<f64> = (-50_000..=50_000)
                .map(|k| n_trt(eta_prime, c.phi_c + k as f64 * 1e-6).x)
                .collect();
            let peak = values.iter().copied().fold(0.0, f64::max);
            let jump = values
                .windows(2)
                .map(|w| (w[1] - w[0]).abs())
                .fold(0.0, f64::max);
            assert!(values.iter().all(|v| v.is_finite()));
            assert!(
                jump < 1e-3 * peak,
                "η′ {eta_prime}: jump {jump} peak {peak}"
            );
        }
        // Continuous as the caustics merge at η′ = 2 and the glint fades.
        for &phi in &[0.0, 0.05, 0.3, -1.0] {
            let (below, above) = (n_trt(2.0 - 1e-7, phi), n_trt(2.0 + 1e-7, phi));
            assert!((below - above).abs().max_element() < 1e-4 * below.max_element().max(1e-3));
        }
        assert_eq!(Caustic::new(2.0 + 0.3, &MarschnerParams::default()).t, 0.0);
    }

    #[test]
    fn eccentricity_one_is_circular_and_other_values_change_trt_only() {
        // Xu et al. 2011 eq. 24 at η = 1.55, a = 0.9: η*₁ = 1.341, η*₂ = 1.80802.
        assert!((eta_star(1.55, 0.9, 0.0) - 1.341).abs() < 1e-12);
        assert!((eta_star(1.55, 0.9, PI) - (1.1 / 0.81 + 0.45)).abs() < 1e-12);
        assert_eq!(eta_star(1.55, 1.0, 0.7), 1.55);
        let circ = model(MarschnerParams::default());
        let ellip = model(MarschnerParams {
            eccentricity: 0.9,
            ..Default::default()
        });
        let mut trt_changed = 0;
        for k in 0..200 {
            let x = k as f64;
            let wi = FiberAngles::new(0.3 * (0.7 * x).sin(), wrap_pi(0.37 * x));
            let wo = FiberAngles::new(-0.25 + 0.2 * (1.3 * x).cos(), wrap_pi(1.11 * x));
            let (a, b) = (circ.eval(wi, wo), ellip.eval(wi, wo));
            assert_eq!(a[Lobe::R], b[Lobe::R]);
            assert_eq!(a[Lobe::TT], b[Lobe::TT]);
            if (a[Lobe::TRT] - b[Lobe::TRT]).abs().max_element() > 1e-6 * a[Lobe::TRT].max_element()
            {
                trt_changed += 1;
            }
            // The circle depends on φ_o − φ_i only.
            let shift = |w: FiberAngles| FiberAngles::new(w.theta, wrap_pi(w.phi + 1.0));
            let rotated = circ.eval(shift(wi), shift(wo));
            assert!(
                (rotated.total() - a.total()).abs().max_element()
                    < 1e-9 * a.total().max_element().max(1e-12)
            );
        }
        assert!(trt_changed > 150, "{trt_changed}");
    }

    #[test]
    fn reciprocal_in_marschners_units() {
        // Marschner's S (= ours / cos θ_o) is symmetric in ω_i and ω_o.
        let m = model(MarschnerParams {
            eccentricity: 0.9,
            ..Default::default()
        });
        for k in 0..300 {
            let x = k as f64;
            let a = FiberAngles::new(1.2 * (0.7 * x).sin(), wrap_pi(0.37 * x));
            let b = FiberAngles::new(1.3 * (1.3 * x).cos(), wrap_pi(1.11 * x + 0.5));
            let ab = m.eval(a, b).total() / b.theta.cos();
            let ba = m.eval(b, a).total() / a.theta.cos();
            assert!(
                (ab - ba).abs().max_element() <= 1e-9 * ab.max_element().max(1e-300),
                "{ab} {ba}"
            );
        }
    }

    #[test]
    fn sampling_matches_pdf_chi2() {
        let cases: [(f64, MarschnerParams); 6] = [
            (0.0, MarschnerParams::default()),
            (0.6, MarschnerParams::default()),
            (
                -1.0,
                MarschnerParams {
                    beta_r: 10f64.to_radians(),
                    alpha_r: -5f64.to_radians(),
                    mu_a: DVec3::ZERO,
                    ..Default::default()
                },
            ),
            (
                1.3,
                MarschnerParams {
                    beta_r: 5f64.to_radians(),
                    alpha_r: -10f64.to_radians(),
                    mu_a: DVec3::splat(2.0),
                    ..Default::default()
                },
            ),
            (
                -0.4,
                MarschnerParams {
                    beta_r: 2f64.to_radians(),
                    alpha_r: 0.0,
                    eta: 1.3,
                    glint_scale: 3.0,
                    ..Default::default()
                },
            ),
            (
                0.3,
                MarschnerParams {
                    beta_r: 0.5,
                    alpha_r: 10f64.to_radians(),
                    eccentricity: 0.85,
                    ..Default::default()
                },
            ),
        ];
        let start = std::time::Instant::now();
        for (n, (theta_i, params)) in cases.iter().enumerate() {
            let m = model(*params);
            let wi = FiberAngles::new(*theta_i, 0.25);
            let p = chi2_test(&m, wi, 1 << 19, 17 + n as u64, (32, 64), cases.len());
            eprintln!("χ² case {n} (θ_i = {theta_i}): {p:?}");
            p.unwrap();
            check_weights(&m, wi, 20_000, 99 + n as u64, 1e-4).unwrap();
        }
        eprintln!("χ² cases took {:?}", start.elapsed());
    }

    #[test]
    fn weights_average_to_the_integral_of_s() {
        // The estimator Σ weight / draws (a rejected draw counts 0) is unbiased only if the
        // sampling covers every direction where S > 0: compare it with quadrature of S.
        let m = model(MarschnerParams {
            mu_a: DVec3::new(0.1, 0.3, 0.9),
            ..Default::default()
        });
        let wi = FiberAngles::new(0.3, 0.0);
        let integral = composite(-FRAC_PI_2, FRAC_PI_2, 24, |theta_o| {
            theta_o.cos()
                * composite(-PI, PI, 24, |phi| {
                    m.eval(wi, FiberAngles::new(theta_o, phi)).total().y
                })
        });
        let mut rng = <rand_pcg::Pcg64Mcg as rand_core::SeedableRng>::seed_from_u64(5);
        let n = 1 << 18;
        let (mut sum, mut sum2) = (0.0, 0.0);
        for _ in 0..n {
            let w = m
                .sample(wi, crate::testing::uniform4(&mut rng))
                .map_or(0.0, |s| s.weight.y);
            sum += w;
            sum2 += w * w;
        }
        let mean = sum / n as f64;
        let sigma = ((sum2 / n as f64 - mean * mean) / n as f64).sqrt();
        eprintln!("Σ w / n = {mean:.5} ± {sigma:.5}, ∫ S dω = {integral:.5}");
        assert!((mean - integral).abs() < 4.0 * sigma + 1e-3 * integral);
    }

    #[test]
    fn parameters_are_validated_field_by_field() {
        assert!(MarschnerParams::default().validate().is_ok());
        let bad = |f: fn(&mut MarschnerParams)| {
            let mut p = MarschnerParams::default();
            f(&mut p);
            p.validate().unwrap_err()
        };
        for (name, f) in [
            (
                "eta",
                (|p: &mut MarschnerParams| p.eta = 1.0) as fn(&mut MarschnerParams),
            ),
            ("beta_r_deg", |p| p.beta_r = f64::NAN),
            ("mu_a", |p| p.mu_a.y = -1.0),
            ("alpha_r_deg", |p| p.alpha_r = 1.0),
            ("beta_r_deg", |p| p.beta_r = 0.0),
            ("eccentricity", |p| p.eccentricity = 0.5),
            ("eccentricity", |p| p.eccentricity = 1.42),
            ("caustic_width_deg", |p| p.caustic_width = 0.0),
            ("glint_scale", |p| p.glint_scale = -1.0),
            ("caustic_fade", |p| p.caustic_fade = 0.0),
            ("caustic_limit", |p| p.caustic_limit = 3.0),
        ] {
            let err = bad(f);
            assert_eq!(err.name, name, "{err}");
            assert!(err.to_string().starts_with(name));
        }
    }

    #[test]
    fn from_fiber_maps_the_shared_parameters() {
        let fiber = FiberParams::default();
        let m = Marschner2003::from_fiber(&fiber).unwrap();
        assert_eq!(m.params().eta, fiber.eta);
        assert_eq!(m.params().mu_a, fiber.mu_a);
        // The R lobe's cone and width in θ_o are d'Eon 2011's.
        let deon = crate::DEon2011::new(fiber).unwrap();
        for &theta_i in &[-0.7, 0.0, 0.4] {
            let cone = deon.longitudinal(0, theta_i);
            let lobe = m.lobes[0];
            assert!((-theta_i + 2.0 * lobe.alpha - cone.theta_cone).abs() < 1e-15);
            assert!((2.0 * lobe.beta - cone.v.sqrt()).abs() < 1e-15);
        }
        let extreme = FiberParams {
            alpha: 20f64.to_radians(),
            beta: 1.0,
            ..fiber
        };
        assert!(Marschner2003::from_fiber(&extreme).is_ok());
        let bad = FiberParams { eta: 0.9, ..fiber };
        assert!(matches!(
            Marschner2003::from_fiber(&bad),
            Err(e) if e.name == "eta"
        ));
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(512))]
        #[test]
        fn finite_and_non_negative_everywhere(
            theta_i in -FRAC_PI_2..=FRAC_PI_2,
            theta_o in -FRAC_PI_2..=FRAC_PI_2,
            phi_i in -PI..=PI,
            phi_o in -PI..=PI,
            beta_r in 0.001f64..=1.0,
            eta in 1.01f64..=3.0,
            mu_a in 0.0f64..=100.0,
            alpha_deg in -10.0f64..=10.0,
            eccentricity in 0.75f64..=1.3,
            u in prop::array::uniform4(0.0f64..1.0),
        ) {
            let m = model(MarschnerParams {
                eta,
                beta_r,
                alpha_r: alpha_deg.to_radians(),
                mu_a: DVec3::new(mu_a, 0.5 * mu_a, 0.0),
                eccentricity,
                ..Default::default()
            });
            let (wi, wo) = (FiberAngles::new(theta_i, phi_i), FiberAngles::new(theta_o, phi_o));
            for v in m.eval(wi, wo).0 {
                prop_assert!(v.is_finite() && v.min_element() >= 0.0, "eval {v}");
            }
            let pdf = m.pdf(wi, wo);
            prop_assert!(pdf.is_finite() && pdf >= 0.0, "pdf {pdf}");
            if let Some(s) = m.sample(wi, u) {
                prop_assert!(s.weight.is_finite() && s.weight.min_element() >= 0.0, "weight {}", s.weight);
                prop_assert!(s.pdf.is_finite() && s.pdf > 0.0);
                prop_assert!(s.wo.theta.abs() <= FRAC_PI_2 && s.wo.phi.abs() <= PI);
            }
        }
    }
}
