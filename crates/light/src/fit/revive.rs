//! Freeing and reviving lights. Two lights on the same spot with about the same bandwidth are one
//! lobe the Levenberg–Marquardt refinement cannot pull apart; merging them frees one. NNLS often
//! leaves a few lights at zero (their centre lies where other
//! lobes already cover the map); each then moves to where the fit falls shortest, the sample with
//! the largest weighted squared positive residual w_p · max(lum(L_p − model_p), 0)², with a
//! bandwidth of twice that sample's angular size. Samples within that bandwidth of an earlier
//! revival are passed over, so several dead lights spread out. The caller re-solves coefficients,
//! which cannot raise the error (the old solution, with the revived lights at zero, is feasible).

use super::model::Basis;
use super::params::Params;
use super::target::Target;
use crate::color::luminance_f64;
use rayon::prelude::*;

/// Lights closer than this many (smaller) bandwidths count as duplicates...
const DUPLICATE_DISTANCE: f64 = 0.5;
/// ...when their bandwidths differ by less than this ratio.
const DUPLICATE_RATIO: f64 = 1.5;

/// Merges duplicate lights (the second's coefficient added to the first's, the second left dark);
/// returns how many were freed.
pub fn merge_duplicates(params: &mut Params) -> usize {
    let mut freed = 0;
    for a in 0..params.len() {
        for b in a + 1..params.len() {
            if params.coefs[a].max_element() <= 0.0 || params.coefs[b].max_element() <= 0.0 {
                continue;
            }
            let (la, lb) = (
                crate::srbf::bandwidth_of(params.kappas[a]),
                crate::srbf::bandwidth_of(params.kappas[b]),
            );
            let close =
                params.dirs[a].dot(params.dirs[b]) > (DUPLICATE_DISTANCE * la.min(lb)).cos();
            if close && la.max(lb) / la.min(lb) < DUPLICATE_RATIO {
                let moved = params.coefs[b];
                params.coefs[a] += moved;
                params.coefs[b] = glam::DVec3::ZERO;
                freed += 1;
            }
        }
    }
    freed
}

/// Moves every light with an all-zero coefficient; returns how many moved.
pub fn revive_dead_lights(target: &Target, params: &mut Params, kappa_range: (f64, f64)) -> usize {
    let dead: Vec<usize> = (0..params.len())
        .filter(|&j| params.coefs[j].max_element() <= 0.0)
        .collect();
    if dead.is_empty() {
        return 0;
    }
    let basis = Basis::new(target, params);
    let shortfall: Vec<f64> = (0..target.len())
        .into_par_iter()
        .map(|p| {
            let short = luminance_f64(target.values[p] - basis.model(p, &params.coefs)).max(0.0);
            target.weights[p] * short * short
        })
        .collect();
    let mut order: Vec<usize> = (0..target.len()).filter(|&p| shortfall[p] > 0.0).collect();
    order.sort_by(|&a, &b| shortfall[b].total_cmp(&shortfall[a]));
    let mut placed: Vec<(glam::DVec3, f64)> = Vec::new();
    for p in order {
        if placed.len() == dead.len() {
            break;
        }
        let dir = target.dirs[p];
        let bandwidth = 2.0 * target.weights[p].sqrt();
        if placed
            .iter()
            .all(|&(d, b)| dir.dot(d) < (b.max(bandwidth)).cos())
        {
            placed.push((dir, bandwidth));
        }
    }
    for (&j, &(dir, bandwidth)) in dead.iter().zip(&placed) {
        params.dirs[j] = dir;
        params.kappas[j] = crate::srbf::sharpness_of(bandwidth).clamp(kappa_range.0, kappa_range.1);
    }
    placed.len()
}
