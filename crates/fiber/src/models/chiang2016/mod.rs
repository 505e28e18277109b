//! The production hair model of Chiang, Bitterli, Tappan and Burley 2016, *A Practical and
//! Controllable Hair and Fur Model for Production Path Tracing*, as pbrt-v4 (`HairBxDF`) and
//! Mitsuba 3 (`hair`) ship it: β_m, β_n, α, η and σ_a per unit radius (or melanin through
//! [`crate::optics::absorption::mu_a_from_melanin`]).
//!
//! # The near-field model
//! For the given direction ω_i and the offset h ∈ [−1, 1] at which the ray along −ω_i meets the
//! fiber (docs/conventions.md §2; the sign is fixed by
//! [`crate::geometry::bravais::azimuthal_deflection`]: Φ(0, h) = −2 asin h, i.e. h is minus the
//! hit's offset along w = u × v when v is ω_i's projection on the normal plane — the trace crate's
//! geometry test checks this), lobes p = 0 (R), 1 (TT), 2 (TRT) and the remainder p ≥ 3 are
//!
//!   S_h(ω_i, ω_o) = Σ_p M_p(θ_o) A_p(θ_i, h) N_p(φ; h), φ = φ_o − φ_i,
//!
//! - M_p the von Mises–Fisher marginal of d'Eon et al. 2011
//!   ([`crate::lobes::longitudinal::LongitudinalWidth`]) about the cone −θ_i + 2α (R), −θ_i − α
//!   (TT), −θ_i − 4α (TRT), −θ_i (remainder), with variances v_R = (0.726 β_m + 0.812 β_m² + 3.7
//!   β_m²⁰)², v_TT = v_R/4, v_TRT = v_rest = 4 v_R (Chiang et al. 2016 eq. 7, §4.1's tilts).
//!   pbrt-v4 writes the tilt as a shift of the given inclination; that is the same cone, so each
//!   M_p has unit integral ∫ M_p cos θ_o dθ_o = 1 for any α.
//! - A_p the attenuation of [`crate::optics::attenuation::attenuation`] (exact 3D Fresnel factor,
//!   T = exp(−2 σ_a cos γ_t / cos θ_t)); the remainder is Σ_{p≥3} A_p (Chiang et al. 2016 eq. 6).
//! - N_p(φ; h) the logistic of scale s = √(π/8)(0.265 β_n + 1.194 β_n² + 5.372 β_n²²)
//!   (Chiang et al. 2016 eq. 8) about Φ(p, h) = 2pγ_t − 2γ_i + pπ, trimmed to [−π, π] and
//!   renormalised there (eq. 10–11); the remainder is uniform, 1/2π.
//!
//! With σ_a = 0, Σ_p A_p = 1 and every M_p, N_p has unit integral, so ∫ S_h dω_o = 1 exactly at
//! every h: the white furnace holds per offset, not only on average.
//!
//! # The far-field S the crate's models share (docs/conventions.md §3)
//! A ray from ω_i meets the fiber at h uniformly distributed across its projected width, so the
//! fraction of intercepted power leaving per steradian is the average S = ½ ∫ S_h dh, which is
//! what [`FiberModel::eval`] and [`FiberModel::pdf`] return (a composite Gauss–Legendre rule in
//! γ_i = asin h, panels following the logistic's width, as [`crate::models::deon2011::azimuthal`]
//! does for d'Eon 2011). The path tracer knows the offset of every hit and calls the near-field
//! [`FiberModel::eval_at`], [`FiberModel::pdf_at`] and [`FiberModel::sample_at`] instead, with
//! ω_i the direction the ray arrived from; averaged over the hits a pixel sees, that is the
//! far-field model again.
//!
//! # Sampling
//! As Chiang et al. 2016 §4.3: a lobe by the channel mean of A_p(θ_i, h), θ_o from the vMF
//! exactly (d'Eon et al. 2013), φ = Φ(p, h) plus a trimmed-logistic draw (uniform for the
//! remainder). The density is closed form, Σ_p (A_p / Σ A) M_p N_p, so weights are S_h / pdf;
//! with σ_a = 0 they are exactly 1. The far-field [`FiberModel::sample`] first draws h uniformly.

use crate::geometry::frame::{FiberAngles, wrap_pi};
use crate::lobe::{Lobe, LobeValues, channel_mean};
use crate::lobes::longitudinal::{LongitudinalLobe, ShiftedCones};
use crate::math::{
    GaussLegendre, asin_fast, asin_pair, exp_fast, exp_lanes_f32, ln_fast, sin_cos_quadrant,
};
use crate::model::weighted_sample;
use crate::model::{FiberModel, FiberSample, select_and_remap};
use crate::optics::attenuation::{Inclination, attenuation_at};
use crate::params::{FiberParams, ParamError};
use crate::ranges;
use glam::DVec3;
use std::f64::consts::PI;
use wide::{f64x2, f64x4};

/// Nodes per panel of the far-field rule in γ_i.
const PANEL_NODES: usize = 16;
/// The most panels of the far-field rule (β_n ≈ 0.003 reaches it).
const MAX_PANELS: usize = 1024;
/// Lobes with their own M and N: R, TT, TRT, and the remainder p ≥ 3.
const LOBES: usize = 4;

/// The Chiang et al. 2016 fiber model. `FiberParams::beta` is the longitudinal roughness β_m.
#[derive(Clone, Debug)]
pub struct Chiang2016 {
    params: FiberParams,
    beta_n: f64,
    /// M_p per lobe (R, TT, TRT, remainder): its variance and its cone's offset from −θ_i.
    cones: ShiftedCones,
    /// N_p's trimmed logistic.
    logistic: TrimmedLogistic,
}

/// The values the lobes share at one offset h: attenuation and deflection geometry.
struct Offset {
    /// A_p for R, TT, TRT and the remainder.
    a: [DVec3; LOBES],
    /// γ_i = asin h and γ_t = asin(h / η′), shared by every lobe's Φ(p, h).
    gamma_i: f64,
    gamma_t: f64,
    /// sin θ_i and cos θ_i.
    sin_cos_i: (f64, f64),
}

impl Chiang2016 {
    /// The model for `params` (β = β_m) and azimuthal roughness `beta_n`, both in (0, 1].
    pub fn new(params: FiberParams, beta_n: f64) -> Result<Self, ParamError> {
        params.validate()?;
        ranges::BETA.named("beta_n").check(beta_n)?;
        let v_r = longitudinal_variance(params.beta);
        let v = [v_r, 0.25 * v_r, 4.0 * v_r, 4.0 * v_r];
        let a = params.alpha;
        let cone_shift = [2.0 * a, -a, -4.0 * a, 0.0];
        Ok(Self {
            params,
            beta_n,
            cones: ShiftedCones::new(v, cone_shift),
            logistic: TrimmedLogistic::new(logistic_scale(beta_n)),
        })
    }

    pub fn params(&self) -> &FiberParams {
        &self.params
    }

    /// β_m, the longitudinal roughness.
    pub fn beta_m(&self) -> f64 {
        self.params.beta
    }

    pub fn beta_n(&self) -> f64 {
        self.beta_n
    }

    /// The logistic scale s of N_p (Chiang et al. 2016 eq. 8).
    pub fn logistic_scale(&self) -> f64 {
        self.logistic.s
    }

    /// The longitudinal lobe of lobe `p` (0 R, 1 TT, 2 TRT, 3 the remainder) for light at θ_i.
    pub fn longitudinal(&self, p: usize, theta_i: f64) -> LongitudinalLobe {
        self.cones.lobe(p, theta_i)
    }

    /// M_p(θ_o) for every lobe.
    fn m_all(&self, theta_i: f64, theta_o: f64) -> [f64; LOBES] {
        let (si, ci) = sin_cos_quadrant(theta_i);
        self.m_from(si, ci, theta_o)
    }

    /// M_p(θ_o) for every lobe, from sin θ_i and cos θ_i.
    #[inline]
    fn m_from(&self, si: f64, ci: f64, theta_o: f64) -> [f64; LOBES] {
        let (so, co) = sin_cos_quadrant(theta_o);
        self.cones.eval(si, ci, so, co)
    }

    /// What every lobe shares at offset h for light at θ_i: one sine and cosine of θ_i, the
    /// attenuation through the prepared [`Inclination`], and γ_i, γ_t for the deflections.
    fn offset(&self, theta_i: f64, h: f64) -> Offset {
        let h = h.clamp(-1.0, 1.0);
        let (si, ci) = sin_cos_quadrant(theta_i);
        let inc = Inclination::from_sin_cos(si, ci, self.params.eta);
        let att = attenuation_at(inc, h, self.params.mu_a);
        // γ_i = asin h and γ_t = asin(h / η′) (crate::geometry::bravais::gamma_t) together.
        let [gamma_i, gamma_t] =
            asin_pair(f64x2::new([h, (h * inc.inv_eta_prime).clamp(-1.0, 1.0)])).to_array();
        Offset {
            a: [att.0[0], att.0[1], att.0[2], att.0[3] + att.0[4]],
            gamma_i,
            gamma_t,
            sin_cos_i: (si, ci),
        }
    }

    /// N_p(φ; h) for every lobe: R, TT and TRT in three lanes, the remainder uniform. φ may
    /// be any azimuth difference: the lanes wrap φ − Φ(p, h) themselves.
    fn n_all(&self, at: &Offset, phi: f64) -> [f64; LOBES] {
        // φ − Φ(p, h) with Φ(p, h) = 2pγ_t − 2γ_i + pπ (Offset::deflection) per lane.
        let x = f64x4::splat(at.gamma_t).mul_neg_add(
            f64x4::new([0.0, 2.0, 4.0, 0.0]),
            f64x4::splat(phi + 2.0 * at.gamma_i) - f64x4::new([0.0, PI, 2.0 * PI, 0.0]),
        );
        let [r, tt, trt, _] = self.logistic.density_lanes(x).to_array();
        [r, tt, trt, 0.5 / PI]
    }

    /// M_p at θ_o for the θ_i of an offset.
    fn m_at(&self, at: &Offset, theta_o: f64) -> [f64; LOBES] {
        let (si, ci) = at.sin_cos_i;
        self.m_from(si, ci, theta_o)
    }

    /// The near-field lobes at offset h (module documentation).
    fn near(&self, wi: FiberAngles, wo: FiberAngles, at: &Offset) -> LobeValues {
        let m = self.m_at(at, wo.theta);
        let n = self.n_all(at, wo.phi - wi.phi);
        near_lobes(&m, &n, &at.a)
    }

    /// The near-field sampling density at offset h.
    fn near_pdf(&self, wi: FiberAngles, wo: FiberAngles, at: &Offset) -> f64 {
        let m = self.m_at(at, wo.theta);
        let n = self.n_all(at, wo.phi - wi.phi);
        near_density(&m, &n, &at.a)
    }

    /// Calls `f(h, weight)` at the nodes of the rule whose weighted sum of f is ½ ∫ f dh over
    /// [−1, 1] (composite Gauss–Legendre in γ_i, dh = cos γ_i dγ_i).
    fn for_offsets(&self, mut f: impl FnMut(f64, f64)) {
        let rule = GaussLegendre::cached(PANEL_NODES);
        let panels = self.panel_count();
        let width = PI / panels as f64;
        for k in 0..panels {
            let mid = -0.5 * PI + (k as f64 + 0.5) * width;
            for (x, w) in rule.nodes.iter().zip(&rule.weights) {
                let gamma = mid + 0.5 * width * x;
                f(gamma.sin(), w * gamma.cos() * 0.25 * width);
            }
        }
    }

    /// Panels in γ_i such that Φ (slope at most 2 in γ_i for p ≤ 2 and η′ > 1) moves by at
    /// most a third of the logistic's standard deviation πs/√3 between nodes.
    fn panel_count(&self) -> usize {
        let sigma = PI * self.logistic.s / 3f64.sqrt();
        let per_panel = PANEL_NODES as f64 * sigma / 3.0;
        ((2.0 * PI / per_panel).ceil() as usize).clamp(2, MAX_PANELS)
    }

    /// The near-field sample at offset h from three uniform numbers (module documentation).
    fn sample_near(&self, wi: FiberAngles, at: &Offset, u: [f64; 3]) -> Option<FiberSample> {
        let (p, u_phi) = select_and_remap(&selection(&at.a), u[0]);
        let (si, ci) = at.sin_cos_i;
        let sin_o = self.cones.sample_sin(p, si, ci, u[1], u[2]);
        let theta_o = asin_fast(sin_o);
        let phi = match p {
            3 => 2.0 * PI * u_phi - PI,
            _ => at.deflection(p) + self.logistic.sample(u_phi),
        };
        let wo = FiberAngles::new(theta_o, wrap_pi(wi.phi + phi));
        // M and N once for both the density and S (near_pdf's and near's arithmetic).
        let m = self.m_at(at, wo.theta);
        let n = self.n_all(at, wo.phi - wi.phi);
        let pdf = near_density(&m, &n, &at.a);
        let lobe = if p == 3 {
            Lobe::Rest
        } else {
            Lobe::from_index(p)
        };
        weighted_sample(wo, near_lobes(&m, &n, &at.a).total(), pdf, lobe, 1)
    }
}

impl Chiang2016 {
    /// The far-field S (all lobes) and pdf from one pass over the offsets: the arithmetic of
    /// [`FiberModel::eval`] and [`FiberModel::pdf`], so the same results.
    fn far_eval_and_pdf(&self, wi: FiberAngles, wo: FiberAngles) -> (DVec3, f64) {
        let m = self.m_all(wi.theta, wo.theta);
        let phi = wrap_pi(wo.phi - wi.phi);
        let mut sum = [DVec3::ZERO; LOBES];
        let mut density = [0.0; LOBES];
        self.for_offsets(|h, w| {
            let at = self.offset(wi.theta, h);
            let n = self.n_all(&at, phi);
            let probs = selection(&at.a);
            for p in 0..LOBES {
                sum[p] += at.a[p] * (n[p] * w);
                density[p] += probs[p] * n[p] * w;
            }
        });
        let s = near_lobes(&m, &[1.0; LOBES], &sum).total();
        (s, (0..LOBES).map(|p| density[p] * m[p]).sum())
    }
}

impl Offset {
    /// Φ(p, h) = 2pγ_t − 2γ_i + pπ (d'Eon et al. 2014 eq. 3), as
    /// [`crate::geometry::bravais::azimuthal_deflection`] computes it, from the shared γ_i and γ_t.
    fn deflection(&self, p: usize) -> f64 {
        let p = p as f64;
        2.0 * p * self.gamma_t - 2.0 * self.gamma_i + p * PI
    }
}

/// Σ_p (A_p / Σ A) M_p N_p, the near-field sampling density.
fn near_density(m: &[f64; LOBES], n: &[f64; LOBES], a: &[DVec3; LOBES]) -> f64 {
    let probs = selection(a);
    (0..LOBES).map(|p| probs[p] * m[p] * n[p]).sum()
}

/// v_R of Chiang et al. 2016 eq. 7.
pub fn longitudinal_variance(beta_m: f64) -> f64 {
    (0.726 * beta_m + 0.812 * beta_m.powi(2) + 3.7 * beta_m.powi(20)).powi(2)
}

/// s of Chiang et al. 2016 eq. 8.
pub fn logistic_scale(beta_n: f64) -> f64 {
    (PI / 8.0).sqrt() * (0.265 * beta_n + 1.194 * beta_n.powi(2) + 5.372 * beta_n.powi(22))
}

/// The logistic of scale s trimmed to [−π, π] and renormalised there (Chiang et al. 2016
/// eq. 10–11), N_p's shape about its deflection. What every call shares (1/s, the mass on
/// [−π, π] and the CDF at −π) is found once, so a density costs one exponential and one
/// division and a draw one logarithm and one division.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TrimmedLogistic {
    /// The scale s.
    s: f64,
    inv_s: f64,
    /// The untrimmed CDF at −π.
    cdf_lo: f64,
    /// The untrimmed logistic's mass on [−π, π].
    mass: f64,
    /// 1 / (s · mass): the density's factor.
    norm: f64,
}

impl TrimmedLogistic {
    pub fn new(s: f64) -> Self {
        let cdf_lo = logistic_cdf(-PI, s);
        let mass = logistic_cdf(PI, s) - cdf_lo;
        Self {
            s,
            inv_s: 1.0 / s,
            cdf_lo,
            mass,
            norm: 1.0 / (s * mass),
        }
    }

    /// The density at x ∈ [−π, π]: e^{−|x|/s} / (s (1 + e^{−|x|/s})²) / mass, the form
    /// stable for any x.
    #[inline]
    pub fn density(&self, x: f64) -> f64 {
        let e = exp_fast(-x.abs() * self.inv_s);
        e * self.norm / ((1.0 + e) * (1.0 + e))
    }

    /// [`TrimmedLogistic::density`] at four x at once, each any real number wrapped to
    /// [−π, π] here (x − 2π round(x / 2π)): the exponential by [`exp_lanes_f32`], so within
    /// 4e-7 relative of the scalar density (`density_lanes_is_the_density`).
    #[inline(always)]
    pub fn density_lanes(&self, x: f64x4) -> f64x4 {
        const ROUND: f64 = 6_755_399_441_055_744.0;
        let turns = x.mul_add(f64x4::splat(0.5 / PI), f64x4::splat(ROUND)) - f64x4::splat(ROUND);
        let wrapped = turns.mul_neg_add(f64x4::splat(2.0 * PI), x);
        let e = exp_lanes_f32(-wrapped.abs() * f64x4::splat(self.inv_s));
        let one_plus = f64x4::ONE + e;
        e * f64x4::splat(self.norm) / (one_plus * one_plus)
    }

    /// A draw by inverting the CDF at u ∈ [0, 1].
    #[inline]
    pub fn sample(&self, u: f64) -> f64 {
        let c = (u * self.mass + self.cdf_lo).clamp(1e-300, 1.0 - 1e-16);
        (-self.s * ln_fast(1.0 / c - 1.0)).clamp(-PI, PI)
    }
}

/// The untrimmed logistic's CDF.
fn logistic_cdf(x: f64, s: f64) -> f64 {
    1.0 / (1.0 + (-x / s).exp())
}

/// Lobe choice ∝ the channel mean of A_p; R alone when nothing is left.
fn selection(a: &[DVec3; LOBES]) -> [f64; LOBES] {
    let m = a.map(channel_mean);
    let total: f64 = m.iter().sum();
    if total > 0.0 {
        let inv_total = 1.0 / total;
        m.map(|x| x * inv_total)
    } else {
        [1.0, 0.0, 0.0, 0.0]
    }
}

/// M_p A_p N_p in the crate's lobe slots; Chiang's remainder p ≥ 3 is reported as `rest`
/// (TRRT is part of it, so the TRRT slot stays zero).
fn near_lobes(m: &[f64; LOBES], n: &[f64; LOBES], a: &[DVec3; LOBES]) -> LobeValues {
    let lobe = |p: usize| a[p] * (m[p] * n[p]);
    LobeValues([lobe(0), lobe(1), lobe(2), DVec3::ZERO, lobe(3)])
}

impl FiberModel for Chiang2016 {
    fn name(&self) -> &'static str {
        "chiang2016"
    }

    /// The far-field S = ½ ∫ S_h dh.
    fn eval(&self, wi: FiberAngles, wo: FiberAngles) -> LobeValues {
        let m = self.m_all(wi.theta, wo.theta);
        let phi = wrap_pi(wo.phi - wi.phi);
        let mut sum = [DVec3::ZERO; LOBES];
        self.for_offsets(|h, w| {
            let at = self.offset(wi.theta, h);
            let n = self.n_all(&at, phi);
            (0..LOBES).for_each(|p| sum[p] += at.a[p] * (n[p] * w));
        });
        near_lobes(&m, &[1.0; LOBES], &sum)
    }

    /// h uniform in [−1, 1] from `u[0]`, then the near-field sample; weight and pdf far-field
    /// (one pass over the offsets for both).
    fn sample(&self, wi: FiberAngles, u: [f64; 4]) -> Option<FiberSample> {
        let at = self.offset(wi.theta, 2.0 * u[0] - 1.0);
        let near = self.sample_near(wi, &at, [u[1], u[2], u[3]])?;
        let (s, pdf) = self.far_eval_and_pdf(wi, near.wo);
        weighted_sample(near.wo, s, pdf, near.lobe, 1)
    }

    fn pdf(&self, wi: FiberAngles, wo: FiberAngles) -> f64 {
        let m = self.m_all(wi.theta, wo.theta);
        let phi = wrap_pi(wo.phi - wi.phi);
        let mut sum = [0.0; LOBES];
        self.for_offsets(|h, w| {
            let at = self.offset(wi.theta, h);
            let n = self.n_all(&at, phi);
            let probs = selection(&at.a);
            (0..LOBES).for_each(|p| sum[p] += probs[p] * n[p] * w);
        });
        (0..LOBES).map(|p| sum[p] * m[p]).sum()
    }

    fn eval_at(&self, wi: FiberAngles, wo: FiberAngles, h: f64) -> LobeValues {
        self.near(wi, wo, &self.offset(wi.theta, h))
    }

    fn pdf_at(&self, wi: FiberAngles, wo: FiberAngles, h: f64) -> f64 {
        self.near_pdf(wi, wo, &self.offset(wi.theta, h))
    }

    /// The near-field sample at h from `u[1..4]` (`u[0]`, the far-field's offset, is unused).
    fn sample_at(&self, wi: FiberAngles, h: f64, u: [f64; 4]) -> Option<FiberSample> {
        self.sample_near(wi, &self.offset(wi.theta, h), [u[1], u[2], u[3]])
    }
}

/// [`Chiang2016`] at one offset h, as a far-field model: the near-field functions with h fixed,
/// so the crate's furnace and χ² checks (and `lobes`) can examine the near field directly.
#[derive(Clone, Debug)]
pub struct AtOffset<'a> {
    pub model: &'a Chiang2016,
    pub h: f64,
}

impl FiberModel for AtOffset<'_> {
    fn name(&self) -> &'static str {
        "chiang2016-at-offset"
    }

    fn eval(&self, wi: FiberAngles, wo: FiberAngles) -> LobeValues {
        self.model.eval_at(wi, wo, self.h)
    }

    fn sample(&self, wi: FiberAngles, u: [f64; 4]) -> Option<FiberSample> {
        self.model.sample_at(wi, self.h, u)
    }

    fn pdf(&self, wi: FiberAngles, wo: FiberAngles) -> f64 {
        self.model.pdf_at(wi, wo, self.h)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::furnace::{FurnaceRule, albedo};
    use crate::optics::attenuation::attenuation;
    use crate::testing::{check_weights, chi2_test};

    fn model(beta_m: f64, beta_n: f64, alpha_deg: f64, mu_a: DVec3) -> Chiang2016 {
        let params = FiberParams {
            eta: 1.55,
            beta: beta_m,
            alpha: alpha_deg.to_radians(),
            mu_a,
        };
        Chiang2016::new(params, beta_n).unwrap()
    }

    #[test]
    fn samples_carry_exactly_the_eval_and_pdf_they_report() {
        // sample finds S and pdf in one pass (far field) or from one M and N (near field):
        // the same arithmetic as eval and pdf, so the same bits.
        let m = model(0.3, 0.3, 2.0, DVec3::new(0.54, 0.91, 1.78));
        let wi = FiberAngles::new(0.4, 0.1);
        check_weights(&m, wi, 300, 41, 0.0).unwrap();
        check_weights(&AtOffset { model: &m, h: 0.3 }, wi, 5_000, 42, 0.0).unwrap();
    }

    fn rule(m: &Chiang2016) -> FurnaceRule {
        FurnaceRule {
            beta: m.cones.variance(1).sqrt(),
            max_shift: 4.0 * m.params.alpha.abs(),
            resolution: 1,
        }
    }

    /// The white furnace per offset: with σ_a = 0, ∫ S_h dω_o = 1 within 0.2 % at every h,
    /// inclination, roughness and tilt tried (the integration rule's own error under 0.1 %).
    #[test]
    fn lossless_fiber_is_white_at_every_offset() {
        for (beta_m, beta_n, alpha_deg) in [(0.3, 0.3, 0.0), (0.1, 0.1, 2.0), (0.6, 0.8, -3.0)] {
            let m = model(beta_m, beta_n, alpha_deg, DVec3::ZERO);
            for h in [-0.95, 0.3, 0.999] {
                for theta_i in [0.0, -1.3] {
                    let est = albedo(&AtOffset { model: &m, h }, theta_i, rule(&m));
                    assert!(est.error_estimate.x < 1e-3, "{est:?}");
                    assert!(
                        (est.albedo.x - 1.0).abs() < 2e-3,
                        "β_m {beta_m} β_n {beta_n} α {alpha_deg} h {h} θ_i {theta_i}: {}",
                        est.albedo.x
                    );
                }
            }
        }
    }

    /// The far field (S averaged over h by quadrature) is white too, and an absorbing fiber's
    /// albedo is the mean attenuation ½ ∫ Σ_p A_p dh, channel by channel.
    #[test]
    fn far_field_albedo_is_the_mean_attenuation() {
        let white = model(0.5, 0.6, 2.0, DVec3::ZERO);
        let est = albedo(&white, 0.4, rule(&white));
        assert!((est.albedo.x - 1.0).abs() < 2e-3, "{est:?}");
        let mu_a = DVec3::new(0.2, 0.6, 1.5);
        let brown = model(0.5, 0.6, 2.0, mu_a);
        let est = albedo(&brown, 0.4, rule(&brown));
        let mut mean = DVec3::ZERO;
        brown.for_offsets(|h, w| mean += attenuation(0.4, h, 1.55, mu_a).total() * w);
        assert!(
            (est.albedo - mean).abs().max_element() < 2e-3,
            "{} vs {mean}",
            est.albedo
        );
        assert!(mean.x > mean.y && mean.y > mean.z && mean.z < 0.9);
    }

    /// χ² of the near-field sampling at fixed offsets, and of the far-field sampling (h drawn
    /// first) against the quadrature pdf; every weight is S / pdf.
    #[test]
    fn sampling_follows_pdf_chi2() {
        let cases = [
            (0.3, 0.3, 0.3, 2.0, DVec3::ZERO, 0.2),
            (-1.1, 0.2, 0.5, -3.0, DVec3::new(0.3, 0.8, 2.0), -0.7),
            (1.2, 0.1, 0.1, 2.0, DVec3::splat(0.1), 0.95),
            (0.0, 0.6, 0.9, 0.0, DVec3::new(2.0, 1.0, 0.0), 0.0),
        ];
        let family = cases.len() + 1;
        for (n, &(theta, bm, bn, a, mu, h)) in cases.iter().enumerate() {
            let m = model(bm, bn, a, mu);
            let near = AtOffset { model: &m, h };
            let wi = FiberAngles::new(theta, -0.4);
            let p = chi2_test(&near, wi, 1 << 19, 11 + n as u64, (32, 64), family);
            assert!(p.is_ok(), "case {n}: {p:?}");
            check_weights(&near, wi, 5_000, 3 + n as u64, 1e-9).unwrap();
        }
        let m = model(0.4, 0.6, 2.0, DVec3::new(0.2, 0.4, 0.8));
        let wi = FiberAngles::new(0.5, 0.1);
        let p = chi2_test(&m, wi, 1 << 17, 99, (16, 32), family);
        assert!(p.is_ok(), "far field: {p:?}");
        check_weights(&m, wi, 500, 5, 1e-6).unwrap();
    }

    /// With σ_a = 0 every near-field weight is exactly 1 (S_h and the density coincide).
    #[test]
    fn lossless_weights_are_one() {
        let m = model(0.3, 0.3, 2.0, DVec3::ZERO);
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = move || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..2000 {
            let wi = FiberAngles::new(3.0 * next() - 1.5, 0.0);
            let s = m.sample_at(wi, 2.0 * next() - 1.0, [0.0, next(), next(), next()]);
            let s = s.expect("a lossless fiber always scatters");
            assert!((s.weight - DVec3::ONE).abs().max_element() < 1e-9, "{s:?}");
        }
    }

    #[test]
    fn trimmed_logistic_is_normalised_and_sampled_by_its_inverse() {
        for s in [0.01, 0.12, 1.5] {
            let n = TrimmedLogistic::new(s);
            let rule = GaussLegendre::cached(64);
            let mass: f64 = (0..64)
                .map(|k| {
                    let a = -PI + 2.0 * PI * k as f64 / 64.0;
                    rule.integrate(a, a + PI / 32.0, |x| n.density(x))
                })
                .sum();
            assert!((mass - 1.0).abs() < 1e-9, "s {s}: {mass}");
            // Pointwise, the textbook form e^{−x/s} / (s (1 + e^{−x/s})²) over the mass.
            let trim = logistic_cdf(PI, s) - logistic_cdf(-PI, s);
            for x in [-3.0, -0.4, 0.0, 0.05, 1.0, 3.1] {
                let e = (-x / s).exp();
                let want = e / (s * (1.0 + e) * (1.0 + e)) / trim;
                let got = n.density(x);
                assert!(
                    (got - want).abs() <= 1e-13 * want,
                    "s {s} x {x}: {got} vs {want}"
                );
            }
            // The inverse CDF: the draw at u has CDF u.
            for u in [0.01, 0.3, 0.5, 0.9] {
                let x = n.sample(u);
                let lo = logistic_cdf(-PI, s);
                let cdf = (logistic_cdf(x, s) - lo) / (logistic_cdf(PI, s) - lo);
                assert!((cdf - u).abs() < 1e-9, "s {s} u {u}: {cdf}");
            }
        }
    }

    /// The lanes' density is the scalar one at the wrapped argument, for arguments up to the
    /// ±6π that φ − Φ(p, h) reaches and widths from sharp to broad.
    #[test]
    fn density_lanes_is_the_density() {
        let mut worst: f64 = 0.0;
        for s in [0.002, 0.03, 0.3, 1.5] {
            let n = TrimmedLogistic::new(s);
            for k in 0..3000 {
                let x: [f64; 4] = std::array::from_fn(|j| {
                    -6.0 * PI + 12.0 * PI * (4 * k + j) as f64 / 12000.0 + 1e-7
                });
                let got = n.density_lanes(f64x4::new(x)).to_array();
                for (g, x) in got.into_iter().zip(x) {
                    let want = n.density(wrap_pi(x));
                    if want > 1e-300 {
                        worst = worst.max((g / want - 1.0).abs());
                    } else {
                        assert!(g < 1e-290, "s {s} x {x}: {g}");
                    }
                }
            }
        }
        eprintln!("trimmed logistic in lanes vs scalar: relative error ≤ {worst:.2e}");
        assert!(worst < 4e-7, "{worst:e}");
    }

    #[test]
    fn azimuthal_roughness_is_validated() {
        let p = FiberParams::default();
        assert!(Chiang2016::new(p, 0.3).is_ok());
        for bad in [0.0, -0.1, 1.5, f64::NAN] {
            assert!(Chiang2016::new(p, bad).is_err(), "{bad}");
        }
    }
}
