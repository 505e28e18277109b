//! The interface every fiber model offers: evaluate S per lobe, sample an outgoing direction,
//! and report the density of that sampling.

use crate::geometry::frame::FiberAngles;
use crate::lobe::{Lobe, LobeValues};
use glam::DVec3;

/// One importance sample of an outgoing direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FiberSample {
    pub wo: FiberAngles,
    /// S(ω_i, ω_o) / pdf(ω_o): the Monte Carlo weight of the sample (RGB).
    pub weight: DVec3,
    /// Density of ω_o per steradian, as [`FiberModel::pdf`] reports it.
    pub pdf: f64,
    /// The lobe the sample was drawn from.
    pub lobe: Lobe,
    /// Fixed-point iterations the sample needed (1 where sampling is direct).
    pub iterations: u32,
}

/// A fiber scattering model in the units of docs/conventions.md §3: S in sr⁻¹, with ∫ S dω_o the
/// albedo. Angles follow docs/conventions.md §2; ω_i points toward the light, ω_o toward the
/// viewer.
pub trait FiberModel: Send + Sync {
    /// Short name as the command line spells it.
    fn name(&self) -> &'static str;

    /// S per lobe, RGB.
    fn eval(&self, wi: FiberAngles, wo: FiberAngles) -> LobeValues;

    /// An outgoing direction drawn from four uniform numbers in [0, 1); `None` when the draw
    /// carries no energy.
    fn sample(&self, wi: FiberAngles, u: [f64; 4]) -> Option<FiberSample>;

    /// The density (per steradian) with which [`FiberModel::sample`] draws ω_o.
    fn pdf(&self, wi: FiberAngles, wo: FiberAngles) -> f64;

    /// Switches the model to its tabulated fast path (the tables built once for its
    /// parameters), as each model's own `tabulated` does; a model without tables keeps
    /// evaluating directly.
    fn tabulate(&mut self) {}

    /// S at a known offset h ∈ [−1, 1] of the ray from ω_i across the fiber's projected width
    /// (docs/conventions.md §2): the near field, whose average over h is [`FiberModel::eval`].
    /// A far-field model (every model but Chiang 2016) has no h and returns its S.
    fn eval_at(&self, wi: FiberAngles, wo: FiberAngles, _h: f64) -> LobeValues {
        self.eval(wi, wo)
    }

    /// The density with which [`FiberModel::sample_at`] draws ω_o at offset h.
    fn pdf_at(&self, wi: FiberAngles, wo: FiberAngles, _h: f64) -> f64 {
        self.pdf(wi, wo)
    }

    /// An outgoing direction at offset h, weight [`FiberModel::eval_at`] / [`FiberModel::pdf_at`].
    fn sample_at(&self, wi: FiberAngles, _h: f64, u: [f64; 4]) -> Option<FiberSample> {
        self.sample(wi, u)
    }
}

/// Converts a density in (θ, φ) to a density per steradian.
pub fn per_steradian(pdf_theta_phi: f64, theta_o: f64) -> f64 {
    pdf_theta_phi / crate::math::cos_quadrant(theta_o).max(1e-300)
}

/// Remaps a uniform number that selected slot `k` of a discrete distribution back to [0, 1),
/// so it can drive a further choice (stratified reuse).
pub fn select_and_remap(probs: &[f64], u: f64) -> (usize, f64) {
    let mut lo = 0.0;
    for (k, &p) in probs.iter().enumerate() {
        if p > 0.0 && (u < lo + p || k == probs.len() - 1) {
            return (k, ((u - lo) / p).clamp(0.0, 1.0 - f64::EPSILON));
        }
        lo += p;
    }
    let k = probs.iter().rposition(|&p| p > 0.0).unwrap_or(0);
    (k, 0.5)
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

    #[test]
    fn select_and_remap_partitions_the_unit_interval() {
        let probs = [0.2, 0.0, 0.5, 0.3];
        assert_eq!(select_and_remap(&probs, 0.1), (0, 0.5));
        let (k, u) = select_and_remap(&probs, 0.45);
        assert_eq!(k, 2);
        assert!((u - 0.5).abs() < 1e-12);
        assert_eq!(select_and_remap(&probs, 0.999).0, 3);
    }
}
