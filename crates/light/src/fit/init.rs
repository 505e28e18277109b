//! Initial centres and bandwidths: spherical k-means of the map's energy (luminance × solid angle),
//! seeded by a deterministic farthest-energy rule (k-means++ taken greedily), then Lloyd
//! iterations. Each cluster's final centre and spread are weighted as the fit's objective weighs
//! errors, by Δω · luminance², so a cluster holding a compact sun gets a lobe centred on it and as
//! narrow as it; coefficients come later from NNLS.

use super::model::task_ranges;
use super::params::Params;
use super::target::Target;
use crate::color::luminance_f64;
use glam::DVec3;
use rayon::prelude::*;

/// Centres and bandwidths (as κ) for `lights` SRBFs; coefficients are zero.
pub fn kmeans_init(
    target: &Target,
    lights: usize,
    iterations: usize,
    kappa_range: (f64, f64),
) -> Params {
    let energy: Vec<f64> = target
        .values
        .iter()
        .zip(&target.weights)
        .map(|(v, w)| w * luminance_f64(*v).max(0.0) + 1e-12 * w)
        .collect();
    let mut centres = seeds(target, &energy, lights);
    for _ in 0..iterations {
        centres = lloyd_step(target, &energy, &centres).0;
    }
    let squared: Vec<f64> = target
        .values
        .iter()
        .zip(&target.weights)
        .map(|(v, w)| w * luminance_f64(*v).powi(2) + 1e-24 * w)
        .collect();
    let (centres, spread) = lloyd_step(target, &squared, &centres);
    let kappas = spread
        .iter()
        .map(|&r| kappa_from_resultant(r).clamp(kappa_range.0, kappa_range.1))
        .collect();
    Params {
        dirs: centres,
        kappas,
        coefs: vec![DVec3::ZERO; lights],
    }
}

/// Greedy k-means++: first the most energetic pixel, then each time the pixel maximising
/// energy × (1 − cos of the angle to its nearest seed).
fn seeds(target: &Target, energy: &[f64], count: usize) -> Vec<DVec3> {
    let mut nearest = vec![2.0f64; target.len()];
    let mut seeds = Vec::with_capacity(count);
    for _ in 0..count {
        let best = (0..target.len())
            .max_by(|&a, &b| (energy[a] * nearest[a]).total_cmp(&(energy[b] * nearest[b])))
            .expect("a target has pixels");
        let seed = target.dirs[best];
        seeds.push(seed);
        nearest
            .par_iter_mut()
            .zip(&target.dirs)
            .for_each(|(d, dir)| *d = d.min(1.0 - dir.dot(seed)));
    }
    seeds
}

/// One Lloyd iteration on the sphere: each pixel joins its nearest centre; each centre moves to
/// the normalised energy-weighted mean direction of its pixels. Also returns each cluster's mean
/// resultant length R̄ = ‖Σ e ω‖ / Σ e (1 for a point, smaller for a spread cluster).
fn lloyd_step(target: &Target, energy: &[f64], centres: &[DVec3]) -> (Vec<DVec3>, Vec<f64>) {
    let k = centres.len();
    let partial: Vec<(Vec<DVec3>, Vec<f64>)> = task_ranges(target.len())
        .into_par_iter()
        .map(|range| {
            let (mut sums, mut masses) = (vec![DVec3::ZERO; k], vec![0.0; k]);
            for p in range {
                let dir = target.dirs[p];
                let nearest = (0..k)
                    .max_by(|&a, &b| dir.dot(centres[a]).total_cmp(&dir.dot(centres[b])))
                    .unwrap_or(0);
                sums[nearest] += dir * energy[p];
                masses[nearest] += energy[p];
            }
            (sums, masses)
        })
        .collect();
    let (mut sums, mut masses) = (vec![DVec3::ZERO; k], vec![0.0; k]);
    for (s, m) in partial {
        sums.iter_mut().zip(s).for_each(|(a, b)| *a += b);
        masses.iter_mut().zip(m).for_each(|(a, b)| *a += b);
    }
    let centres = (0..k)
        .map(|i| {
            if sums[i].length() > 0.0 {
                sums[i].normalize()
            } else {
                centres[i]
            }
        })
        .collect();
    let resultant = (0..k)
        .map(|i| {
            if masses[i] > 0.0 {
                (sums[i].length() / masses[i]).min(1.0)
            } else {
                1.0
            }
        })
        .collect();
    (centres, resultant)
}

/// κ of an SRBF as wide as a cluster with mean resultant length R̄: a uniform cap of half-angle α
/// has 1 − R̄ = (1 − cos α)/2 ≈ α²/4, and λ = α/√2 (G = e⁻² at the cap's rim) gives κ = 2/λ² =
/// 1/(1 − R̄).
fn kappa_from_resultant(r: f64) -> f64 {
    1.0 / (1.0 - r).max(1e-12)
}
