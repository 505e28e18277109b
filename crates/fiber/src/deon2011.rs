//! The energy-conserving model of d'Eon et al. 2011 (d'Eon et al. 2014 eq. 4–5), with the importance
//! sampling of d'Eon et al. 2013.
//!
//! Each lobe p is M(v_p, θ_cone,p, θ_o) · N_p(φ). The lobes are separable: v_p and the cone
//! shift are constants of the fiber. They are the first-order Nusselt perturbations of d'Eon et al. 2014
//! §2.2 at normal incidence (h = 0, θ = 0), so that the model and the non-separable one agree
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

use crate::azimuthal::{AzimuthalScattering, Weighting};
use crate::bravais::{azimuthal_deflection, eta_prime};
use crate::frame::{FiberAngles, wrap_pi};
use crate::lobe::{Lobe, LobeValues};
use crate::longitudinal::{LongitudinalLobe, LongitudinalWidth};
use crate::model::{FiberModel, FiberSample, select_and_remap};
use crate::params::{FiberParams, ParamError};
use crate::special::normal_quantile;
use crate::table::AzimuthalTable;
use glam::DVec3;
use std::f64::consts::PI;
use std::sync::Arc;

/// The d'Eon et al. 2011 fiber model.
#[derive(Clone, Debug)]
pub struct DEon2011 {
    params: FiberParams,
    azimuthal: AzimuthalScattering,
    /// Per lobe: longitudinal variance v_p and cone shift added to −θ_i.
    longitudinal: [(f64, f64); 5],
    /// The same lobes prepared for evaluation: width, and sine and cosine of the shift.
    prepared: [(LongitudinalWidth, f64, f64); 4],
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
        let lobe = |width: f64, shift: f64| ((b * width).powi(2), shift * a);
        let trrt = lobe(3.0 * e - 1.0, -(6.0 * e - 2.0));
        let longitudinal = [
            lobe(std::f64::consts::SQRT_2, 2.0),
            lobe(e - 1.0, -2.0 * (e - 1.0)),
            lobe(2.0 * e - 1.0, -(4.0 * e - 2.0)),
            trrt,
            trrt,
        ];
        let prepared = std::array::from_fn(|p| {
            let (v, shift) = longitudinal[p];
            let (sin_shift, cos_shift) = shift.sin_cos();
            (LongitudinalWidth::new(v), sin_shift, cos_shift)
        });
        Ok(Self {
            params,
            azimuthal,
            longitudinal,
            prepared,
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
        let theta_d = 0.5 * (wo.theta - wi.theta);
        let phi = wrap_pi(wo.phi - wi.phi);
        let (s, sel) = match &self.table {
            Some(t) => t.eval_all_both(wi.theta, theta_d, phi),
            None => (
                self.azimuthal_all(wi.theta, theta_d, phi, Weighting::Attenuation),
                self.azimuthal_all(wi.theta, theta_d, phi, Weighting::Selection),
            ),
        };
        let m = self.m_all(wi, wo);
        let pdf = LobeValues::separable(m, sel).total().x;
        (LobeValues::separable(m, s).total(), pdf)
    }

    /// M_p(θ_o) of R, TT, TRT and TRRT (the remainder shares TRRT's).
    fn m_all(&self, wi: FiberAngles, wo: FiberAngles) -> [f64; 4] {
        let (si, ci) = wi.theta.sin_cos();
        let (so, co) = wo.theta.sin_cos();
        // The cone −θ_i + shift, by the angle-sum identities.
        std::array::from_fn(|p| {
            let (width, ss, cs) = self.prepared[p];
            width.eval(-si * cs + ci * ss, ci * cs + si * ss, so, co)
        })
    }

    /// The longitudinal lobe of mode p for light at θ_i.
    pub fn longitudinal(&self, p: usize, theta_i: f64) -> LongitudinalLobe {
        let (v, shift) = self.longitudinal[p];
        LongitudinalLobe::new(v, -theta_i + shift)
    }
}

impl FiberModel for DEon2011 {
    fn name(&self) -> &'static str {
        "deon2011"
    }

    fn eval(&self, wi: FiberAngles, wo: FiberAngles) -> LobeValues {
        self.density(wi, wo, Weighting::Attenuation)
    }

    fn sample(&self, wi: FiberAngles, u: [f64; 4]) -> Option<FiberSample> {
        let h = 2.0 * u[0] - 1.0;
        let (p, u_phi) = select_and_remap(&self.azimuthal.selection(wi.theta, h), u[1]);
        let theta_o = self.longitudinal(p, wi.theta).sample(u[2], u[3]);
        let theta_d = 0.5 * (theta_o - wi.theta);
        let phi = sample_phi(&self.azimuthal, p, h, theta_d, u_phi);
        let wo = FiberAngles::new(theta_o, wrap_pi(wi.phi + phi));
        let (s, pdf) = self.eval_and_pdf(wi, wo);
        weighted_sample(wo, s, pdf, Lobe::from_index(p), 1)
    }

    fn pdf(&self, wi: FiberAngles, wo: FiberAngles) -> f64 {
        self.density(wi, wo, Weighting::Selection).total().x
    }
}

/// φ for lobe p entering at h: Φ(p, h) plus a wrapped-Gaussian offset (d'Eon 2013); R has
/// no offset and the p ≥ 4 remainder is uniform.
pub(crate) fn sample_phi(az: &AzimuthalScattering, p: usize, h: f64, theta_d: f64, u: f64) -> f64 {
    match p {
        0 => azimuthal_deflection(0, h, az.eta),
        4 => 2.0 * PI * u - PI,
        _ => {
            let offset = az.v_n[p].sqrt() * normal_quantile(u.clamp(1e-16, 1.0 - 1e-16));
            azimuthal_deflection(p as u32, h, eta_prime(az.eta, theta_d)) + offset
        }
    }
}

/// Completes a sample with its density and weight S / pdf; `None` where either vanishes.
pub(crate) fn finish_sample(
    model: &dyn FiberModel,
    wi: FiberAngles,
    wo: FiberAngles,
    lobe: Lobe,
    iterations: u32,
) -> Option<FiberSample> {
    let pdf = model.pdf(wi, wo);
    if !(pdf > 0.0 && pdf.is_finite()) {
        return None;
    }
    weighted_sample(wo, model.eval(wi, wo).total(), pdf, lobe, iterations)
}

/// A sample of S (all lobes, RGB) drawn with density `pdf`: weight S / pdf; `None` where the
/// density vanishes or the weight is not finite. For models that find S and pdf together.
pub(crate) fn weighted_sample(
    wo: FiberAngles,
    s: DVec3,
    pdf: f64,
    lobe: Lobe,
    iterations: u32,
) -> Option<FiberSample> {
    if !(pdf > 0.0 && pdf.is_finite()) {
        return None;
    }
    let weight = s / pdf;
    weight.is_finite().then_some(FiberSample {
        wo,
        weight,
        pdf,
        lobe,
        iterations,
    })
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
