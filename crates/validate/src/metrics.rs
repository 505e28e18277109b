//! The per-lobe figures of one model against one simulation (issue 3): relative L1 error
//! Σ|model − sim| Ω / Σ|sim| Ω, the energy difference ∫ model − ∫ sim, and the error in θ of
//! the lobe's peak ([`crate::peak`]). Channel means throughout (docs/conventions.md §5).

use crate::peak::peak_theta_error;
use cuticle_fiber::LatLongImage;
use cuticle_fiber::lobe::channel_mean;
use serde::Serialize;

/// The figures of one lobe.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct LobeFigures {
    /// Σ|model − sim| Ω / Σ|sim| Ω; `None` where the simulated lobe is black.
    pub relative_l1: Option<f64>,
    /// ∫ S dω of the model's image.
    pub energy_model: f64,
    /// ∫ S dω of the simulation's image.
    pub energy_sim: f64,
    /// Error in θ of the peak, radians; `None` where either lobe is black.
    pub peak_theta_error: Option<f64>,
    /// The relative L1 between two simulations with different seeds, where the validation has
    /// two ([`crate::noise`]); `None` otherwise.
    pub seed_to_seed_l1: Option<f64>,
}

impl LobeFigures {
    /// energy_model − energy_sim.
    pub fn energy_difference(&self) -> f64 {
        self.energy_model - self.energy_sim
    }

    /// The relative L1 a perfect model would score against the reference: half the
    /// seed-to-seed L1, the reference being the mean of the two runs ([`crate::noise`]).
    pub fn noise_floor(&self) -> Option<f64> {
        self.seed_to_seed_l1.map(|s| 0.5 * s)
    }

    /// The model's own error with the noise floor taken out in quadrature,
    /// √max(L1² − floor², 0) ([`crate::noise`] says why and how far to trust it); NaN where
    /// the L1 is (a model that returned NaN must not read as a perfect one).
    pub fn residual_l1(&self) -> Option<f64> {
        let (l1, floor) = (self.relative_l1?, self.noise_floor()?);
        let excess = l1 * l1 - floor * floor;
        Some(if excess.is_nan() {
            f64::NAN
        } else {
            excess.max(0.0).sqrt()
        })
    }
}

/// Σ|a − b| Ω and Σ|b| Ω over the sphere (channel mean).
pub fn l1_sums(a: &LatLongImage, b: &LatLongImage) -> (f64, f64) {
    let g = b.grid;
    let (mut diff, mut norm) = (0.0, 0.0);
    for k in 0..g.height {
        let omega = g.pixel_solid_angle(k);
        for j in 0..g.width {
            diff += omega * channel_mean((a.at(j, k) - b.at(j, k)).abs());
            norm += omega * channel_mean(b.at(j, k).abs());
        }
    }
    (diff, norm)
}

/// The figures of `model` against `sim` (same grid).
pub fn lobe_figures(model: &LatLongImage, sim: &LatLongImage) -> LobeFigures {
    assert_eq!(model.grid, sim.grid, "images on different grids");
    let (diff, norm) = l1_sums(model, sim);
    LobeFigures {
        relative_l1: (norm > 0.0).then(|| diff / norm),
        energy_model: channel_mean(model.energy()),
        energy_sim: channel_mean(sim.energy()),
        peak_theta_error: peak_theta_error(model, sim),
        seed_to_seed_l1: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The residual takes the floor out, clips at 0, and keeps a NaN model NaN: `f64::max`
    /// alone returns 0 for NaN, which read as a perfect model in `validation.csv`.
    #[test]
    fn residual_clips_at_zero_and_keeps_nan() {
        let figures = |l1: f64| LobeFigures {
            relative_l1: Some(l1),
            energy_model: 1.0,
            energy_sim: 1.0,
            peak_theta_error: None,
            seed_to_seed_l1: Some(0.06),
        };
        assert!((figures(0.05).residual_l1().unwrap() - 0.04).abs() < 1e-12);
        assert_eq!(figures(0.01).residual_l1(), Some(0.0));
        assert!(figures(f64::NAN).residual_l1().unwrap().is_nan());
    }
}
