//! The fiber model with non-separable lobes (d'Eon et al. 2014 §2.2–2.5) and its fixed-point
//! importance sampling (§3), in two forms: [`Scales::Paper`], the model as the paper specifies
//! it, and [`Scales::Tilted`] (the default), this project's extension that carries what tilted
//! and rough cuticle scales do to the energy.
//!
//! The pipeline, per (ω_i, ω_o):
//! 1. N_p, the azimuthal terms of d'Eon 2011 (eq. 4, [`crate::models::deon2011::azimuthal`]), with
//!    A(p, h), Φ(p, h) and TT's spread taken through the tilted scales ([`scales`]) and the
//!    rough surface ([`rough`]) in the tilted form;
//! 2. M_p, the longitudinal lobes (`longitudinal.rs`): cone angles and widths from the Nusselt
//!    analysis of §2.2 ([`cones`]); R's vary with φ (§2.3), TT's with the offset h that
//!    Φ(1, h) = φ selects (§2.4), TRT's with θ_d (§2.5); TRRT and the p ≥ 4 remainder keep
//!    d'Eon 2011's lobes;
//! 3. S = Σ_p M_p N_p, and the sampler's fixed point in (θ_o, φ) (§3).
//!
//! The fast path ([`NonSeparable::tabulated`]) reads N_p from d'Eon 2011's table and M_p's
//! cones, widths, R's mirrors, the tilt's shifts and the lobe-selection densities from
//! `tables/`; the model without tables is the reference they are measured against. The model
//! is not reciprocal, like d'Eon 2011. Where the tilted form departs from the paper, and
//! why, is `docs/nonseparable.md`; each departure, with its figure, is a file in
//! `docs/departures/`.
//!
//! Erratum (both forms): d'Eon et al. 2014 §2.4 prints
//! D_TT = (−2√(1−x²−y²) − η√(1 − (x²+y²)/η²)) / cos θ_d. The first-order derivatives it gives
//! in §2.2, dx_TT/dα₁,₂ = ηz′ − z, lead instead to D_TT = 2(ηz′ − z) / cos θ_d, which agrees
//! with eq. 6's convention for R (per-axis Beckmann slope deviation β/√2) and with a numerical
//! derivative of the rotation sequence; that is the form used here (see the test
//! `tt_width_is_the_first_order_spread_of_the_exit_angle`).

pub mod cones;
pub mod cuticle;
mod longitudinal;
pub mod rough;
pub mod scales;
mod tables;
mod tt_offsets;

use crate::geometry::bravais::{azimuthal_deflection, eta_prime};
use crate::geometry::frame::{FiberAngles, wrap_pi};
use crate::lobe::{Lobe, LobeValues};
use crate::lobes::longitudinal::ConeLobe;
use crate::math::{asin_fast, sin_cos_quadrant};
use crate::model::weighted_sample;
use crate::model::{FiberModel, FiberSample, select_and_remap};
use crate::models::deon2011::azimuthal::{AzimuthalScattering, ROffset, Weighting};
use crate::models::deon2011::{DEon2011, azimuthal_offset, sample_phi};
use crate::models::nonseparable::scales::attenuation::{Surface, TiltedAttenuation, energy_budget};
use crate::models::nonseparable::scales::mirror::{MirrorOffset, tilted_mirror};
use crate::params::{FiberParams, ParamError};
pub use cones::{
    CutLobe, cone_r, cone_trt, cone_tt, cone_tt_tilted, first_order_tt, trt_exit, tt_exit,
    tt_lobe_rough, tt_offset, variance_r, variance_trt, variance_tt,
};
use cuticle::TiltedCuticle;
use glam::DVec3;
use rough::deflection::RoughTtTable;
use rough::mirror::RoughMirror;
use std::sync::{Arc, OnceLock};
use tables::mirrors::MirrorTable;
use tables::selection::SelectionTable;
use tables::shifts::ShiftTable;
use tables::sine_lobes::LobeTable;
use tt_offsets::TtOffsets;

/// No R offsets: the paper's form, or a lobe other than R.
const NO_MIRRORS: [Option<MirrorOffset>; 3] = [None; 3];

/// What an evaluation at one (ω_i, ω_o) needs under either weighting: θ_d, φ, what N_R reads
/// and M_p at θ_o.
struct Pair {
    theta_d: f64,
    phi: f64,
    r: RPair,
    m: [f64; 4],
}

/// What N_R needs of one pair, found with R's lobe.
enum RPair {
    /// S's N_R from the rough mirror (departure 11), read with R's lobe.
    Rough { n_r: f64 },
    /// R's offsets: solved where the scales tilt and no rough mirror answers, none in the
    /// paper's form. Only this variant carries them, so a rough pair is not a copy of three.
    Mirrors([Option<MirrorOffset>; 3]),
}

/// Fixed-point iterations per sample unless set otherwise (d'Eon et al. 2014 Figure 7 uses 6).
pub const DEFAULT_ITERATIONS: u32 = 6;
/// Change in θ_o (radians) below which the fixed-point iteration counts as converged.
const CONVERGED: f64 = 1e-6;

/// How the model treats tilted scales.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scales {
    /// d'Eon et al. 2014 as printed: A(p, h) of the untilted fiber, the TT and TRT cones sent to
    /// the pole where the clamped |x| > 1.
    Paper,
    /// A(p, h) through the tilted scales, with their losses (see the module docs).
    Tilted,
}

/// The non-separable fiber model of d'Eon et al. 2014.
#[derive(Clone, Debug)]
pub struct NonSeparable {
    params: FiberParams,
    scales: Scales,
    deon: DEon2011,
    /// The tilted model's scales, which `deon`'s N_p is taken through; `None` in the paper's.
    cuticle: Option<Arc<TiltedCuticle>>,
    iterations: u32,
    /// TT's offset for each azimuth, tabulated on first use.
    tt_offsets: OnceLock<TtOffsets>,
    /// The lobe-selection probabilities over (θ_i, h) of the tilted model's fast path.
    selection: Option<Arc<SelectionTable>>,
    /// TT's and TRT's longitudinal lobes of the fast path.
    lobes: Option<Arc<LobeTable>>,
    /// R's mirror cone and spread of the tilted model's fast path.
    mirror_cones: Option<Arc<MirrorTable>>,
    /// TT's and TRT's deflection shift through tilted scales, for the fast path's sampler.
    shifts: Option<Arc<ShiftTable>>,
    /// N_R off the rough surface, built on first use (tilted model, β ≥
    /// [`rough::mirror::LEAST_BETA`]).
    rough_mirror: OnceLock<Arc<RoughMirror>>,
}

impl NonSeparable {
    /// The tilted model (`nonseparable` on the command line).
    pub fn new(params: FiberParams) -> Result<Self, ParamError> {
        Self::with_scales(params, Scales::Tilted)
    }

    /// The model exactly as d'Eon et al. 2014 specifies it (`nonseparable-paper`).
    pub fn paper(params: FiberParams) -> Result<Self, ParamError> {
        Self::with_scales(params, Scales::Paper)
    }

    pub fn with_scales(params: FiberParams, scales: Scales) -> Result<Self, ParamError> {
        let az = AzimuthalScattering::new(params.eta, params.beta, params.mu_a);
        let cuticle = (scales == Scales::Tilted)
            .then(|| Arc::new(TiltedCuticle::rough(params.eta, params.alpha, params.beta)));
        let az = match &cuticle {
            None => az,
            Some(cuticle) => az
                .with_cuticle(cuticle.clone())
                .with_azimuthal_variance(2, cones::trt_azimuthal_variance(params.beta))
                .with_azimuthal_variance(3, cones::trrt_azimuthal_variance(params.beta)),
        };
        Ok(Self {
            params,
            scales,
            deon: DEon2011::with_azimuthal(params, az)?,
            cuticle,
            iterations: DEFAULT_ITERATIONS,
            tt_offsets: OnceLock::new(),
            selection: None,
            lobes: None,
            mirror_cones: None,
            shifts: None,
            rough_mirror: OnceLock::new(),
        })
    }

    /// The same model with its azimuthal terms tabulated (see [`DEon2011::tabulated`]), TT's
    /// and TRT's lobes (`tables/sine_lobes.rs`) and, where A(p, h) is a trace through tilted or
    /// rough scales (the tilted model, at any α), its lobe selection (`tables/selection.rs`):
    /// without it a sample traces A(p, h) at its offset, and R's rough mirror at every node. The
    /// tilted model also tabulates R's mirror (`tables/mirrors.rs`) where R's lobe is not the rough
    /// mirror's (β < [`rough::mirror::LEAST_BETA`]), which it otherwise solves by Newton's
    /// method at every evaluation, and, with tilted scales, TT's and TRT's tilt shift
    /// for the sampler (`tables/shifts.rs`), which it otherwise traces at every draw.
    pub fn tabulated(mut self) -> Self {
        // R's spread weighs offsets by the selection this builds.
        self.rough_mirror = OnceLock::new();
        let lobes = LobeTable::build(
            |theta_i, phi| self.tt_shape(theta_i, phi),
            |theta_i| self.lobe_shape(2, theta_i, 0.0),
        );
        self.lobes = Some(Arc::new(lobes));
        // R's lobe is the rough mirror's where there is one.
        if self.scales == Scales::Tilted && self.params.beta < rough::mirror::LEAST_BETA {
            self.mirror_cones = Some(Arc::new(MirrorTable::build(self.params.alpha)));
        }
        if self.azimuthal().tilted() {
            let az = self.azimuthal();
            let table = ShiftTable::build(|p, theta_i, h| az.deflection_shift(p, theta_i, h));
            self.shifts = Some(Arc::new(table));
        }
        if self.azimuthal().is_flat_and_smooth() {
            self.deon = self.deon.tabulated();
            return self;
        }
        let table = Arc::new(SelectionTable::build(self.azimuthal()));
        let selection = |theta_i: f64, h: f64| table.at(theta_i, h);
        self.deon = self.deon.tabulated_with_selection(&selection);
        self.selection = Some(table);
        self
    }

    /// The surface A(p, h) meets: the tilted cuticle's, or the paper's smooth, untilted one.
    fn surface(&self) -> Surface<'_> {
        match &self.cuticle {
            Some(cuticle) => cuticle.surface(),
            None => Surface::smooth(self.params.eta, 0.0),
        }
    }

    /// TT's exit per offset through the rough surface (the tilted model's).
    fn rough_tt(&self) -> Option<&RoughTtTable> {
        self.cuticle.as_ref()?.rough_tt.as_deref()
    }

    /// N_R off the rough surface ([`rough_mirror`]), in the tilted model where the spread is
    /// wide enough to tabulate; `None` keeps the smooth mirror's N_R.
    fn rough_mirror(&self) -> Option<&RoughMirror> {
        let FiberParams {
            eta, beta, alpha, ..
        } = self.params;
        if self.scales != Scales::Tilted || beta < rough::mirror::LEAST_BETA {
            return None;
        }
        let table = self.rough_mirror.get_or_init(|| {
            Arc::new(RoughMirror::build(alpha, beta, eta, |theta_i, h| {
                self.lobe_selection(theta_i, h)[0]
            }))
        });
        Some(table)
    }

    /// The probabilities of choosing each lobe at offset h: the table's where there is one.
    fn lobe_selection(&self, theta_i: f64, h: f64) -> [f64; 5] {
        match &self.selection {
            Some(table) => table.at(theta_i, h),
            None => self.azimuthal().selection(theta_i, h),
        }
    }

    /// The same model sampling with at most `n` (≥ 1) fixed-point iterations.
    pub fn with_iterations(mut self, n: u32) -> Self {
        self.iterations = n.max(1);
        self
    }

    pub fn params(&self) -> &FiberParams {
        &self.params
    }

    pub fn scales(&self) -> Scales {
        self.scales
    }

    fn azimuthal(&self) -> &AzimuthalScattering {
        self.deon.azimuthal_scattering()
    }

    /// Where the power intercepted at θ_i goes through the smooth mirror of each micro-normal
    /// mean: ½ ∫ A(p, h) dh per lobe and what the scales remove. The paper's form loses
    /// nothing. S integrates to these, except R's where the rough mirror carries it
    /// ([`Self::lobe_energies`]).
    pub fn energy_budget(&self, theta_i: f64) -> TiltedAttenuation {
        let az = self.azimuthal();
        energy_budget(theta_i, self.surface(), az.mu_a)
    }

    /// What each lobe of S integrates to at θ_i, ∫ S_p dω_o (every M integrates to 1, and
    /// N_TT is the same at every θ_d): the budget's ½ ∫ A(p, h) dh ([`Self::energy_budget`]),
    /// but R's off the rough surface where the rough mirror carries it
    /// ([`RoughMirror::energy`]), which sends out part of the light that the smooth mirror's
    /// budget loses below the macro surface, as the simulator's surface does. The white
    /// furnace finds these.
    pub fn lobe_energies(&self, theta_i: f64) -> LobeValues {
        let mut lobes = self.energy_budget(theta_i).lobes;
        if let Some(rough) = self.rough_mirror() {
            lobes.0[0] = DVec3::splat(rough.energy(theta_i));
        }
        lobes
    }

    /// N_p for every lobe, R's from its solved offsets where the scales tilt it.
    fn azimuthal_at(&self, pair: &Pair, theta_i: f64, weighting: Weighting) -> [DVec3; 5] {
        let [tt, trt, trrt, rest] =
            self.deon
                .azimuthal_beyond_r(theta_i, pair.theta_d, pair.phi, weighting);
        [
            self.azimuthal_r(pair, theta_i, weighting),
            tt,
            trt,
            trrt,
            rest,
        ]
    }

    /// N_R, from its solved offsets where the scales tilt it.
    fn azimuthal_r(&self, pair: &Pair, theta_i: f64, weighting: Weighting) -> DVec3 {
        let mirrors = match (&pair.r, weighting) {
            (&RPair::Rough { n_r }, Weighting::Attenuation) => return DVec3::splat(n_r),
            (RPair::Rough { .. }, Weighting::Selection) => {
                let rough = self
                    .rough_mirror()
                    .expect("a rough pair has the rough mirror");
                return DVec3::splat(rough.density(theta_i, pair.phi, weighting));
            }
            (RPair::Mirrors(mirrors), _) => mirrors,
        };
        let az = self.azimuthal();
        if az.tilted() {
            match (&self.selection, weighting) {
                // R's share of the offsets that reach φ, as the sampler chooses it.
                (Some(table), Weighting::Selection) => DVec3::splat(
                    mirrors
                        .iter()
                        .flatten()
                        .map(|m| 0.5 * m.dh_dphi * table.at(theta_i, m.h)[0])
                        .sum(),
                ),
                _ => {
                    az.eval_r_at_offsets(theta_i, &mirrors.map(|m| m.map(ROffset::from)), weighting)
                }
            }
        } else {
            az.eval(0, theta_i, pair.theta_d, pair.phi, weighting)
        }
    }

    /// What one (ω_i, ω_o) pair needs under either weighting, found once.
    fn pair(&self, wi: FiberAngles, wo: FiberAngles) -> Pair {
        let theta_d = 0.5 * (wo.theta - wi.theta);
        let phi = wrap_pi(wo.phi - wi.phi);
        let (sin_o, cos_o) = sin_cos_quadrant(wo.theta);
        // Only R's lobe reads the offsets.
        let lobe = |p| self.cone_lobe(p, wi.theta, phi, &NO_MIRRORS);
        // R's lobe and its N_R from one read of the rough mirror's columns.
        let (r, r_pair) = match self.rough_mirror() {
            Some(rough) => {
                let (r, n_r) = rough.column_at(wi.theta, sin_cos_quadrant(wi.theta).0, phi);
                (r, RPair::Rough { n_r })
            }
            None => {
                let mirrors = match self.needs_mirrors() {
                    true => self.mirrors(wi.theta, phi),
                    false => NO_MIRRORS,
                };
                let r = self.cone_lobe(0, wi.theta, phi, &mirrors);
                (r, RPair::Mirrors(mirrors))
            }
        };
        let trt = lobe(2);
        let m = match self.scales {
            // TT's lane holds TRT's lobe again, and TT's sine lobe replaces it.
            Scales::Tilted => {
                let mut m = ConeLobe::eval_four([r, trt, trt, lobe(3)], sin_o, cos_o);
                m[1] = self.tt_sine_lobe(wi.theta, phi).eval(sin_o);
                m
            }
            Scales::Paper => ConeLobe::eval_four([r, lobe(1), trt, lobe(3)], sin_o, cos_o),
        };
        Pair {
            theta_d,
            phi,
            r: r_pair,
            m,
        }
    }

    /// S and the sampling density of one pair together, R's offsets and the M_p found once: the
    /// same arithmetic as [`FiberModel::eval`] and [`FiberModel::pdf`], so identical results.
    fn eval_and_pdf(&self, wi: FiberAngles, wo: FiberAngles) -> (LobeValues, f64) {
        let pair = self.pair(wi, wo);
        let (s, sel) = self
            .deon
            .azimuthal_beyond_r_both(wi.theta, pair.theta_d, pair.phi);
        let lobes = |weighting, [tt, trt, trrt, rest]: [DVec3; 4]| {
            let r = self.azimuthal_r(&pair, wi.theta, weighting);
            LobeValues::separable(pair.m, [r, tt, trt, trrt, rest])
        };
        let pdf = self.density_total(&pair, wi.theta, sel.map(|n| n.x));
        (lobes(Weighting::Attenuation, s), pdf)
    }

    /// The sampling density Σ_p M_p N_p from TT's, TRT's, TRRT's and the remainder's selection
    /// densities `beyond_r`, R's found here: under the selection weighting every N_p is grey,
    /// so the density adds numbers, in the order [`LobeValues::total`] adds the lobes.
    #[inline]
    fn density_total(&self, pair: &Pair, theta_i: f64, beyond_r: [f64; 4]) -> f64 {
        let r = self.azimuthal_r(pair, theta_i, Weighting::Selection).x;
        let [tt, trt, trrt, rest] = beyond_r;
        let m = pair.m;
        m[0] * r + m[1] * tt + m[2] * trt + m[3] * trrt + m[3] * rest
    }

    /// What tilted scales add to Φ(p, h) of TT and TRT
    /// ([`AzimuthalScattering::deflection_shift`]): from the shift table where it answers,
    /// else traced.
    #[inline]
    fn deflection_shift(&self, p: usize, theta_i: f64, h: f64) -> f64 {
        self.shifts
            .as_deref()
            .filter(|_| matches!(p, 1 | 2))
            .and_then(|table| table.at(p, theta_i, h))
            .unwrap_or_else(|| self.azimuthal().deflection_shift(p, theta_i, h))
    }

    /// θ_o and φ for TT or TRT by the fixed-point iteration of §3: guess θ_o = −θ_i, then
    /// alternately sample φ given θ_d and θ_o given φ with the same random numbers. Where TT's
    /// N does not depend on θ_d ([`AzimuthalScattering::lobe_eta_prime`], departure 21) φ is
    /// drawn once and θ_o from M_TT given it: a direct draw of S_TT = N_TT(φ) M_TT(θ_o | φ), no
    /// fixed point to find.
    fn sample_fixed_point(
        &self,
        wi: FiberAngles,
        p: usize,
        h: f64,
        u_phi: f64,
        u_m: [f64; 2],
    ) -> (f64, f64, u32) {
        let mut theta_o = -wi.theta;
        let mut phi = 0.0;
        let az = self.azimuthal();
        // φ = Φ(p, h; η′(θ_d)) + the tilt's shift + the Gaussian offset, as `sample_phi` draws
        // it: only Φ changes from one iteration to the next.
        let fixed =
            self.deflection_shift(p, wi.theta, h) + azimuthal_offset(az, p, wi.theta, h, u_phi);
        if !az.deflection_reads_theta_d(p) {
            let eta_p = az.lobe_eta_prime(p, wi.theta, eta_prime(az.eta, -wi.theta));
            let phi = azimuthal_deflection(p as u32, h, eta_p) + fixed;
            let theta_o = asin_fast(self.sample_lobe_sin(p, wi.theta, wrap_pi(phi), u_m));
            return (theta_o, phi, 1);
        }
        for iteration in 1..=self.iterations {
            let theta_d = 0.5 * (theta_o - wi.theta);
            let eta_p = az.lobe_eta_prime(p, wi.theta, eta_prime(az.eta, theta_d));
            phi = azimuthal_deflection(p as u32, h, eta_p) + fixed;
            let next = asin_fast(self.sample_lobe_sin(p, wi.theta, wrap_pi(phi), u_m));
            let step = (next - theta_o).abs();
            theta_o = next;
            if step < CONVERGED {
                // This step only confirmed the previous one: that one was the last needed.
                return (theta_o, phi, (iteration - 1).max(1));
            }
        }
        (theta_o, phi, self.iterations)
    }
}

impl FiberModel for NonSeparable {
    fn tabulate(&mut self) {
        *self = self.clone().tabulated();
    }

    fn name(&self) -> &'static str {
        match self.scales {
            Scales::Tilted => "nonseparable",
            Scales::Paper => "nonseparable-paper",
        }
    }

    fn eval(&self, wi: FiberAngles, wo: FiberAngles) -> LobeValues {
        let pair = self.pair(wi, wo);
        let n = self.azimuthal_at(&pair, wi.theta, Weighting::Attenuation);
        LobeValues::separable(pair.m, n)
    }

    /// Samples h and p as d'Eon 2013 does; R, TRRT and the remainder are then sampled directly,
    /// TT and TRT by the fixed-point iteration. The weight is S / [`NonSeparable::pdf`].
    fn sample(&self, wi: FiberAngles, u: [f64; 4]) -> Option<FiberSample> {
        let h = 2.0 * u[0] - 1.0;
        let selection = self.lobe_selection(wi.theta, h);
        if selection.iter().all(|&p| p == 0.0) {
            // Tilted scales lose everything entering at this h: pdf counts none of it.
            return None;
        }
        let (p, u_phi) = select_and_remap(&selection, u[1]);
        let (theta_o, phi, iterations) = match p {
            1 | 2 => self.sample_fixed_point(wi, p, h, u_phi, [u[2], u[3]]),
            0 => {
                let phi = match self.scales {
                    Scales::Tilted => {
                        let mirror = tilted_mirror(wi.theta, self.params.alpha, h).phi;
                        match self.rough_mirror() {
                            Some(rough) => rough.sample_phi(wi.theta, h, mirror, u_phi),
                            None => mirror,
                        }
                    }
                    Scales::Paper => azimuthal_deflection(0, h, self.params.eta),
                };
                (
                    asin_fast(
                        self.sampling_lobe(0, wi.theta, wrap_pi(phi))
                            .sample_sin(u[2], u[3]),
                    ),
                    phi,
                    1,
                )
            }
            _ => {
                let theta_o = self.deon.longitudinal(p, wi.theta).sample(u[2], u[3]);
                (
                    theta_o,
                    sample_phi(
                        self.azimuthal(),
                        p,
                        wi.theta,
                        h,
                        self.azimuthal().deflection_shift(p, wi.theta, h),
                        0.5 * (theta_o - wi.theta),
                        u_phi,
                    ),
                    1,
                )
            }
        };
        let wo = FiberAngles::new(theta_o, wrap_pi(wi.phi + phi));
        let (s, pdf) = self.eval_and_pdf(wi, wo);
        weighted_sample(wo, s.total(), pdf, Lobe::from_index(p), iterations)
    }

    /// The density the sampling procedure is built to realise: Σ_p M_p N_p with A replaced by
    /// the lobe-selection probability. R, TRT, TRRT and the remainder realise it exactly (their
    /// M does not depend on φ, or their N not on θ_o); TT's M depends on φ while its N depends
    /// on θ_d, so the iteration realises it only up to the residual of d'Eon et al. 2014 Appendix
    /// A, −(∂P_M/∂φ)(∂P_N/∂θ). The gap is measured by `fixed_point_sampling_gap_and_iterations`
    /// below. Offsets whose every path the tilted scales lose are never drawn, so there the
    /// density integrates to the share of offsets that send light somewhere, below 1.
    fn pdf(&self, wi: FiberAngles, wo: FiberAngles) -> f64 {
        let pair = self.pair(wi, wo);
        let beyond_r = self
            .deon
            .selection_beyond_r(wi.theta, pair.theta_d, pair.phi);
        self.density_total(&pair, wi.theta, beyond_r)
    }
}

#[cfg(test)]
mod tests;
