//! The energy-conserving model of d'Eon et al. 2011 (d'Eon et al. 2014 eq. 4–5), with the
//! importance sampling of d'Eon et al. 2013.
//!
//! Each lobe p is M(v_p, θ_cone,p, θ_o) · N_p(φ). The lobes are separable: v_p and the cone
//! shift are constants of the fiber. They are the first-order Nusselt perturbations of d'Eon et al.
//! 2014 §2.2 at normal incidence (h = 0, θ = 0), so that the model and the non-separable one agree
//! there: with Beckmann roughness β the per-axis micro-normal slope deviation is β/√2, and
//! the lobe widths are √v = β√2 (R), β(η − 1) (TT), β(2η − 1) (TRT), β(3η − 1) (TRRT and rest);
//! the cone shifts are 2α (R), −2(η − 1)α (TT), −(4η − 2)α (TRT), −(6η − 2)α (TRRT, rest).
//!
//! A(p, h) depends on θ_i alone, so sampling first picks h and p, then θ_o, then φ, each
//! exactly; the sampled density is Σ_p M_p · N_p with A replaced by the selection probability
//! of p (see [`Weighting::Selection`]), and every sample's weight is S / pdf.
//!
//! Reciprocity: M with a cone at −θ_i + shift is not symmetric under exchanging ω_i and ω_o
//! (d'Eon et al. 2014 says so of eq. 5), and A is taken at θ_i: the model is not reciprocal.

pub mod azimuthal;
pub mod table;

use crate::geometry::bravais::{azimuthal_deflection, eta_prime};
use crate::geometry::frame::{FiberAngles, wrap_pi};
use crate::lobe::{Lobe, LobeValues};
use crate::lobes::longitudinal::{LongitudinalLobe, ShiftedCones};
use crate::math::{asin_fast, cos_quadrant, normal_quantile_fast, sin_cos_quadrant};
use crate::model::{FiberModel, FiberSample, select_and_remap, weighted_sample};
use crate::models::deon2011::azimuthal::{AzimuthalScattering, Weighting, selection_from};
use crate::models::deon2011::table::{AzimuthalTable, ThetaICell};
use crate::optics::attenuation::{Inclination, attenuation_at, r_selection_at_h_sq};
use crate::optics::fresnel::fresnel_dielectric;
use crate::params::{FiberParams, ParamError};
use glam::{DVec3, Vec4};
use std::f64::consts::PI;
use std::sync::Arc;

/// The d'Eon et al. 2011 fiber model.
#[derive(Clone, Debug)]
pub struct DEon2011 {
    params: FiberParams,
    azimuthal: AzimuthalScattering,
    /// M_p of R, TT, TRT and TRRT (the remainder shares TRRT's): variance v_p, cone at
    /// −θ_i + shift_p.
    cones: ShiftedCones,
    table: Option<Arc<AzimuthalTable>>,
}

impl DEon2011 {
    pub fn new(params: FiberParams) -> Result<Self, ParamError> {
        let azimuthal = AzimuthalScattering::new(params.eta, params.beta, params.mu_a);
        Self::with_azimuthal(params, azimuthal)
    }

    /// The model's lobes with other azimuthal terms (the non-separable model's, whose A(p, h)
    /// may be taken through tilted scales).
    pub(crate) fn with_azimuthal(
        params: FiberParams,
        azimuthal: AzimuthalScattering,
    ) -> Result<Self, ParamError> {
        params.validate()?;
        let (b, e, a) = (params.beta, params.eta, params.alpha);
        let width = [
            std::f64::consts::SQRT_2,
            e - 1.0,
            2.0 * e - 1.0,
            3.0 * e - 1.0,
        ];
        let shift = [2.0, -2.0 * (e - 1.0), -(4.0 * e - 2.0), -(6.0 * e - 2.0)];
        Ok(Self {
            params,
            azimuthal,
            cones: ShiftedCones::new(width.map(|w| (b * w).powi(2)), shift.map(|s| s * a)),
            table: None,
        })
    }

    pub fn params(&self) -> &FiberParams {
        &self.params
    }

    pub(crate) fn azimuthal_scattering(&self) -> &AzimuthalScattering {
        &self.azimuthal
    }

    /// The same model with N_p read from an [`AzimuthalTable`] built once for these parameters
    /// (the fast path; see the table for its resolution and measured error).
    pub fn tabulated(mut self) -> Self {
        self.table = Some(Arc::new(AzimuthalTable::build(&self.azimuthal)));
        self
    }

    /// [`DEon2011::tabulated`] with the table's selection densities from `selection`
    /// ([`AzimuthalTable::build_with_selection`]), for a model that samples lobes with it.
    pub(crate) fn tabulated_with_selection(
        mut self,
        selection: crate::models::deon2011::table::Selection,
    ) -> Self {
        self.table = Some(Arc::new(AzimuthalTable::build_with_selection(
            &self.azimuthal,
            Some(selection),
        )));
        self
    }

    /// The table, when the model has one.
    pub fn table(&self) -> Option<&AzimuthalTable> {
        self.table.as_deref()
    }

    /// N_p(φ) for every lobe, from the table when there is one, else by quadrature.
    pub(crate) fn azimuthal_all(
        &self,
        theta_i: f64,
        theta_d: f64,
        phi: f64,
        weighting: Weighting,
    ) -> [DVec3; 5] {
        match &self.table {
            Some(t) => t.eval_all(theta_i, theta_d, phi, weighting),
            None => {
                std::array::from_fn(|p| self.azimuthal.eval(p, theta_i, theta_d, phi, weighting))
            }
        }
    }

    /// N_p for TT, TRT, TRRT and the remainder (R is the caller's): from the table when there
    /// is one, else by quadrature.
    pub(crate) fn azimuthal_beyond_r(
        &self,
        theta_i: f64,
        theta_d: f64,
        phi: f64,
        weighting: Weighting,
    ) -> [DVec3; 4] {
        match &self.table {
            Some(t) => t.eval_beyond_r(theta_i, theta_d, phi, weighting),
            None => std::array::from_fn(|k| {
                self.azimuthal.eval(k + 1, theta_i, theta_d, phi, weighting)
            }),
        }
    }

    /// [`DEon2011::azimuthal_beyond_r`] under the selection weighting, whose N_p are grey: one
    /// number per lobe, the first channel of each (the same bits), for a density that adds
    /// numbers where the lobes' total adds colours.
    pub(crate) fn selection_beyond_r(&self, theta_i: f64, theta_d: f64, phi: f64) -> [f64; 4] {
        match &self.table {
            Some(t) => t.selection_beyond_r(theta_i, theta_d, phi),
            None => std::array::from_fn(|k| {
                self.azimuthal
                    .eval(k + 1, theta_i, theta_d, phi, Weighting::Selection)
                    .x
            }),
        }
    }

    /// [`DEon2011::azimuthal_beyond_r`] under both weightings, (attenuation, selection): the
    /// table's texels read once.
    pub(crate) fn azimuthal_beyond_r_both(
        &self,
        theta_i: f64,
        theta_d: f64,
        phi: f64,
    ) -> ([DVec3; 4], [DVec3; 4]) {
        match &self.table {
            Some(t) => t.eval_beyond_r_both(theta_i, theta_d, phi),
            None => (
                self.azimuthal_beyond_r(theta_i, theta_d, phi, Weighting::Attenuation),
                self.azimuthal_beyond_r(theta_i, theta_d, phi, Weighting::Selection),
            ),
        }
    }

    /// Σ_p M_p N_p per lobe; the p ≥ 4 remainder shares TRRT's longitudinal lobe.
    fn density(&self, wi: FiberAngles, wo: FiberAngles, weighting: Weighting) -> LobeValues {
        let theta_d = 0.5 * (wo.theta - wi.theta);
        let n = self.azimuthal_all(wi.theta, theta_d, wrap_pi(wo.phi - wi.phi), weighting);
        LobeValues::separable(self.m_all(wi, wo), n)
    }

    /// S and the sampling density together: M_p and the table coordinates found once, the
    /// table's (RGB, selection) texels read once. The same arithmetic as [`FiberModel::eval`]
    /// and [`FiberModel::pdf`], so the results are identical to theirs.
    fn eval_and_pdf(&self, wi: FiberAngles, wo: FiberAngles) -> (DVec3, f64) {
        if let Some(pair) = self.tabulated_pair(wi, wo) {
            return self.pair_eval_and_pdf(&pair);
        }
        let theta_d = 0.5 * (wo.theta - wi.theta);
        let phi = wrap_pi(wo.phi - wi.phi);
        let s = self.azimuthal_all(wi.theta, theta_d, phi, Weighting::Attenuation);
        let sel = self.azimuthal_all(wi.theta, theta_d, phi, Weighting::Selection);
        let m = self.m_all(wi, wo);
        let pdf = LobeValues::separable(m, sel).total().x;
        (LobeValues::separable(m, s).total(), pdf)
    }

    /// The table when the tabulated fast path applies: a table and untilted scales.
    #[inline]
    fn fast_table(&self) -> Option<&AzimuthalTable> {
        let table = self.table.as_deref()?;
        (!self.azimuthal.tilted()).then_some(table)
    }

    /// What the tabulated path needs of θ_i alone: its sine and cosine, the prepared
    /// inclination of A(p, h) and the table's θ_i cell, found once per call (sample shares
    /// them between its lobe choice, its θ_o draw and its weight).
    #[inline(always)]
    fn incident(&self, theta_i: f64) -> Incident {
        let (si, ci) = sin_cos_quadrant(theta_i);
        Incident {
            si,
            ci,
            inclination: Inclination::from_sin_cos(si, ci, self.params.eta),
            cell: AzimuthalTable::theta_i_cell(theta_i),
        }
    }

    /// The tabulated fast path's shared values for one (ω_i, ω_o), when the model has a table
    /// and untilted scales (see [`DEon2011::pair_at`]).
    #[inline(always)]
    fn tabulated_pair(&self, wi: FiberAngles, wo: FiberAngles) -> Option<Pair> {
        let table = self.fast_table()?;
        let inc = self.incident(wi.theta);
        let (so, co) = sin_cos_quadrant(wo.theta);
        let eta_ratio = table.eta_ratio_from_cos_2d(inc.ci * co + inc.si * so);
        Some(self.pair_at(table, &inc, so, co, eta_ratio, wrap_pi(wo.phi - wi.phi)))
    }

    /// [`DEon2011::tabulated_pair`] with the table's selection channels alone
    /// ([`AzimuthalTable::selection_taps`]), for the density. Written out beside it rather
    /// than generic over the taps: the generic form slowed eval by half in the loop harness
    /// (code generation; BENCHMARKS.md).
    #[inline(always)]
    fn tabulated_selection_pair(&self, wi: FiberAngles, wo: FiberAngles) -> Option<Pair<[f32; 4]>> {
        let table = self.fast_table()?;
        let inc = self.incident(wi.theta);
        let (so, co) = sin_cos_quadrant(wo.theta);
        let eta_ratio = table.eta_ratio_from_cos_2d(inc.ci * co + inc.si * so);
        let phi = wrap_pi(wo.phi - wi.phi);
        let point = table.point_in_row(inc.cell, eta_ratio, phi);
        Some(Pair {
            m: self.m_from(inc.si, inc.ci, so, co),
            taps: table.selection_taps(point),
            inclination: inc.inclination,
            cos_half_phi: cos_quadrant(0.5 * phi).max(0.0),
        })
    }

    /// M_p from the sines and cosines of θ_i and θ_o, the table point from η/η′ (found from
    /// cos(θ_o − θ_i) by the half-angle identities) and φ, and R's root h = −sin(φ/2) from
    /// cos(φ/2) alone.
    #[inline(always)]
    fn pair_at(
        &self,
        table: &AzimuthalTable,
        inc: &Incident,
        so: f64,
        co: f64,
        eta_ratio: f64,
        phi: f64,
    ) -> Pair {
        let point = table.point_in_row(inc.cell, eta_ratio, phi);
        let cos_half_phi = cos_quadrant(0.5 * phi).max(0.0);
        Pair {
            m: self.m_from(inc.si, inc.ci, so, co),
            taps: table.taps(point),
            inclination: inc.inclination,
            cos_half_phi,
        }
    }

    /// Σ_p M_p N_p with N_p weighted by lobe selection: R's selection probability
    /// f / mean(Σ_p A_p) at its root from the closed-form total (no lobe-by-lobe attenuation).
    #[inline]
    fn pair_pdf(&self, pair: &Pair<[f32; 4]>) -> f64 {
        self.pair_pdf_with(pair, pair.taps, pair.fresnel_r())
    }

    /// [`DEon2011::pair_pdf`] for the taps' selection channels `selection` and R's Fresnel
    /// factor f already found.
    #[inline]
    fn pair_pdf_with<T>(&self, pair: &Pair<T>, selection: [f32; 4], f: f64) -> f64 {
        let c = pair.cos_half_phi;
        let h_sq = (1.0 - c * c).clamp(0.0, 1.0);
        let sel_r = r_selection_at_h_sq(pair.inclination, f, h_sq, self.params.mu_a);
        let [t1, t2, t3, rest] = selection;
        let m = pair.m;
        m[0] * (0.25 * c * sel_r)
            + m[1] * t1 as f64
            + m[2] * t2 as f64
            + m[3] * t3 as f64
            + m[3] * rest as f64
    }

    /// S (all lobes) and the sampling density of a pair, R's Fresnel factor found once: the
    /// arithmetic of [`Pair::lobes`] and [`DEon2011::pair_pdf`].
    #[inline]
    fn pair_eval_and_pdf(&self, pair: &Pair) -> (DVec3, f64) {
        let f = pair.fresnel_r();
        let selection = pair.taps.map(|t| t.w);
        (
            pair.lobes_with(f).total(),
            self.pair_pdf_with(pair, selection, f),
        )
    }

    /// The tabulated sample (d'Eon et al. 2013's procedure, as [`FiberModel::sample`] states
    /// it): θ_i's sine, cosine, inclination and table cell found once for the lobe choice,
    /// the θ_o draw and the weight; η′(θ_d) of the φ draw from the η/η′ the table lookup of
    /// the weight uses. S and pdf are [`FiberModel::eval`]'s and [`FiberModel::pdf`]'s
    /// arithmetic on the drawn ω_o, so the same bits.
    fn sample_tabulated(
        &self,
        table: &AzimuthalTable,
        wi: FiberAngles,
        u: [f64; 4],
    ) -> Option<FiberSample> {
        let inc = self.incident(wi.theta);
        let h = 2.0 * u[0] - 1.0;
        let a = attenuation_at(inc.inclination, h, self.params.mu_a);
        let (p, u_phi) = select_and_remap(&selection_from(&a), u[1]);
        let (si, ci) = (inc.si, inc.ci);
        let theta_o = asin_fast(self.cones.sample_sin(p.min(3), si, ci, u[2], u[3]));
        let (so, co) = sin_cos_quadrant(theta_o);
        let eta_ratio = table.eta_ratio_from_cos_2d(ci * co + si * so);
        let eta_p = self.azimuthal.eta / eta_ratio;
        let phi = sample_phi_at(&self.azimuthal, p, wi.theta, h, eta_p, u_phi);
        let wo = FiberAngles::new(theta_o, wrap_pi(wi.phi + phi));
        let pair = self.pair_at(table, &inc, so, co, eta_ratio, wrap_pi(wo.phi - wi.phi));
        let (s, pdf) = self.pair_eval_and_pdf(&pair);
        weighted_sample(wo, s, pdf, Lobe::from_index(p), 1)
    }

    /// M_p(θ_o) of R, TT, TRT and TRRT (the remainder shares TRRT's).
    fn m_all(&self, wi: FiberAngles, wo: FiberAngles) -> [f64; 4] {
        let (si, ci) = sin_cos_quadrant(wi.theta);
        let (so, co) = sin_cos_quadrant(wo.theta);
        self.m_from(si, ci, so, co)
    }

    /// M_p from sin θ_i, cos θ_i, sin θ_o, cos θ_o.
    #[inline]
    fn m_from(&self, si: f64, ci: f64, so: f64, co: f64) -> [f64; 4] {
        self.cones.eval(si, ci, so, co)
    }

    /// The longitudinal lobe of mode p for light at θ_i (the remainder, p ≥ 4, has TRRT's).
    pub fn longitudinal(&self, p: usize, theta_i: f64) -> LongitudinalLobe {
        self.cones.lobe(p.min(3), theta_i)
    }
}

impl FiberModel for DEon2011 {
    fn tabulate(&mut self) {
        *self = self.clone().tabulated();
    }

    fn name(&self) -> &'static str {
        "deon2011"
    }

    fn eval(&self, wi: FiberAngles, wo: FiberAngles) -> LobeValues {
        match self.tabulated_pair(wi, wo) {
            Some(pair) => pair.lobes(),
            None => self.density(wi, wo, Weighting::Attenuation),
        }
    }

    fn sample(&self, wi: FiberAngles, u: [f64; 4]) -> Option<FiberSample> {
        if let Some(table) = self.fast_table() {
            return self.sample_tabulated(table, wi, u);
        }
        let h = 2.0 * u[0] - 1.0;
        let (p, u_phi) = select_and_remap(&self.azimuthal.selection(wi.theta, h), u[1]);
        let (si, ci) = sin_cos_quadrant(wi.theta);
        let theta_o = asin_fast(self.cones.sample_sin(p.min(3), si, ci, u[2], u[3]));
        let theta_d = 0.5 * (theta_o - wi.theta);
        let shift = self.azimuthal.deflection_shift(p, wi.theta, h);
        let phi = sample_phi(&self.azimuthal, p, wi.theta, h, shift, theta_d, u_phi);
        let wo = FiberAngles::new(theta_o, wrap_pi(wi.phi + phi));
        let (s, pdf) = self.eval_and_pdf(wi, wo);
        weighted_sample(wo, s, pdf, Lobe::from_index(p), 1)
    }

    fn pdf(&self, wi: FiberAngles, wo: FiberAngles) -> f64 {
        match self.tabulated_selection_pair(wi, wo) {
            Some(pair) => self.pair_pdf(&pair),
            None => self.density(wi, wo, Weighting::Selection).total().x,
        }
    }
}

/// What the tabulated path needs of θ_i alone ([`DEon2011::incident`]).
struct Incident {
    si: f64,
    ci: f64,
    inclination: Inclination,
    /// The table's θ_i cells.
    cell: ThetaICell,
}

/// What eval and pdf share for one (ω_i, ω_o) on the tabulated path, with the table's taps
/// of TT, TRT, TRRT and the remainder: (r, g, b, selection) each for S, or the selection
/// alone for the density.
struct Pair<T = [Vec4; 4]> {
    m: [f64; 4],
    taps: T,
    inclination: Inclination,
    /// cos(φ/2): R's single root h = −sin(φ/2) has cos γ_i = cos(φ/2).
    cos_half_phi: f64,
}

impl<T> Pair<T> {
    /// A(0, h) = f at R's root, whose 3D incidence cosine is cos θ_i cos γ_i = cos θ_i cos(φ/2).
    #[inline]
    fn fresnel_r(&self) -> f64 {
        fresnel_dielectric(
            self.inclination.cos_theta * self.cos_half_phi,
            self.inclination.eta,
        )
    }
}

impl Pair {
    /// S per lobe: N_R = ¼ cos(φ/2) A(0, h) (d'Eon et al. 2014 §2.3), the rest from the table.
    #[inline]
    fn lobes(&self) -> LobeValues {
        self.lobes_with(self.fresnel_r())
    }

    /// [`Pair::lobes`] for R's Fresnel factor f already found.
    #[inline]
    fn lobes_with(&self, f: f64) -> LobeValues {
        let c = self.cos_half_phi;
        let [t1, t2, t3, rest] = self.taps;
        let n_r = DVec3::splat(0.25 * c * f);
        LobeValues::separable(
            self.m,
            [
                n_r,
                t1.truncate().as_dvec3(),
                t2.truncate().as_dvec3(),
                t3.truncate().as_dvec3(),
                rest.truncate().as_dvec3(),
            ],
        )
    }
}

/// φ for lobe p entering at h: Φ(p, h) plus a wrapped-Gaussian offset (d'Eon 2013); R has
/// no offset and the p ≥ 4 remainder is uniform. `shift` is what tilted scales add to Φ(p, h),
/// [`AzimuthalScattering::deflection_shift`] (found once by a caller that draws φ repeatedly
/// at one offset).
pub(crate) fn sample_phi(
    az: &AzimuthalScattering,
    p: usize,
    theta_i: f64,
    h: f64,
    shift: f64,
    theta_d: f64,
    u: f64,
) -> f64 {
    let eta_p = if matches!(p, 1..=3) {
        eta_prime(az.eta, theta_d)
    } else {
        az.eta
    };
    sample_phi_at(az, p, theta_i, h, eta_p, u) + shift
}

/// [`sample_phi`] for η′(θ_d) already found (R and the remainder do not use it), without a
/// tilt's shift (the tabulated path is untilted).
fn sample_phi_at(
    az: &AzimuthalScattering,
    p: usize,
    theta_i: f64,
    h: f64,
    eta_p: f64,
    u: f64,
) -> f64 {
    match p {
        0 => azimuthal_deflection(0, h, az.eta),
        4 => 2.0 * PI * u - PI,
        _ => {
            let eta_p = az.lobe_eta_prime(p, theta_i, eta_p);
            azimuthal_deflection(p as u32, h, eta_p) + azimuthal_offset(az, p, theta_i, h, u)
        }
    }
}

/// The wrapped-Gaussian offset of a sampled φ for lobes 1 to 3, √v_N Φ⁻¹(u): what
/// [`sample_phi`] adds to Φ(p, h), for a fixed-point sampler that draws φ at one u repeatedly
/// and finds it once.
#[inline]
pub(crate) fn azimuthal_offset(
    az: &AzimuthalScattering,
    p: usize,
    theta_i: f64,
    h: f64,
    u: f64,
) -> f64 {
    az.azimuthal_sigma(p, theta_i, h) * normal_quantile_fast(u.clamp(1e-16, 1.0 - 1e-16))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::{check_weights, chi2_test};

    fn model(theta_beta_alpha_mu: (f64, f64, f64, DVec3)) -> DEon2011 {
        let (_, beta, alpha_deg, mu_a) = theta_beta_alpha_mu;
        DEon2011::new(FiberParams {
            eta: 1.55,
            beta,
            alpha: alpha_deg.to_radians(),
            mu_a,
        })
        .unwrap()
        .tabulated()
    }

    /// χ² over a grid of θ_i, β, α and μ_a (issue 2); samples come from the exact d'Eon 2013
    /// procedure, the expected counts from the tabulated pdf, so the table is checked too.
    #[test]
    fn sampling_follows_pdf_chi2() {
        let cases = [
            (0.3, 0.05, 0.0, DVec3::ZERO),
            (-1.1, 0.2, -3.0, DVec3::new(0.3, 0.8, 2.0)),
            (1.2, 0.1, 2.0, DVec3::splat(0.1)),
            (0.0, 0.3, -2.0, DVec3::new(2.0, 1.0, 0.0)),
            (0.8, 0.02, 4.0, DVec3::ZERO),
        ];
        for (n, case) in cases.iter().enumerate() {
            let m = model(*case);
            let wi = FiberAngles::new(case.0, -0.4);
            let p = chi2_test(&m, wi, 1 << 19, 31 + n as u64, (32, 64), cases.len());
            assert!(p.is_ok(), "case {n}: {p:?}");
            check_weights(&m, wi, 5_000, 7 + n as u64, 1e-4).unwrap();
        }
    }

    #[test]
    fn samples_carry_exactly_the_eval_and_pdf_they_report() {
        // sample reads S and pdf from one pass over the table (or the quadrature): the same
        // arithmetic as eval and pdf, so the same bits.
        let case = (0.0, 0.3, 2.0, DVec3::new(0.54, 0.91, 1.78));
        let wi = FiberAngles::new(-0.7, 0.2);
        check_weights(&model(case), wi, 5_000, 3, 0.0).unwrap();
        let direct = DEon2011::new(FiberParams {
            beta: 0.3,
            ..FiberParams::default()
        })
        .unwrap();
        check_weights(&direct, wi, 200, 4, 0.0).unwrap();
    }

    #[test]
    fn a_wrong_pdf_fails_the_chi2_test() {
        struct Skewed(DEon2011);
        impl FiberModel for Skewed {
            fn name(&self) -> &'static str {
                "skewed"
            }
            fn eval(&self, wi: FiberAngles, wo: FiberAngles) -> LobeValues {
                self.0.eval(wi, wo)
            }
            fn sample(&self, wi: FiberAngles, u: [f64; 4]) -> Option<FiberSample> {
                self.0.sample(wi, u)
            }
            fn pdf(&self, wi: FiberAngles, wo: FiberAngles) -> f64 {
                self.0.pdf(wi, wo) * (1.0 + 0.05 * wo.phi.cos())
            }
        }
        let m = Skewed(model((0.3, 0.1, 0.0, DVec3::ZERO)));
        assert!(chi2_test(&m, FiberAngles::new(0.3, 0.0), 1 << 18, 5, (32, 64), 1).is_err());
    }
}
