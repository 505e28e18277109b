//! The linear half of the fit: for fixed centres and bandwidths, the coefficients minimising
//! Σ_p w_p ‖Σ_j L_j G_j(ω_p) − L_p‖² with L_j ≥ 0, one NNLS problem per channel on the Gram
//! matrix A_jk = Σ_p w_p G_j G_k and right-hand side b_j = Σ_p w_p G_j L_p.

use super::model::{BATCH, Basis, add_gram_upper, add_vectors, mirror_upper, task_ranges};
use super::nnls::nnls;
use super::params::Params;
use super::target::Target;
use glam::DVec3;
use rayon::prelude::*;

/// Replaces `params.coefs` by the non-negative least-squares coefficients for its geometry.
pub fn solve_coefficients(target: &Target, params: &mut Params) {
    let basis = Basis::new(target, params);
    solve_coefficients_with(target, &basis, params);
}

/// [`solve_coefficients`] with the bases of `params` already evaluated.
pub fn solve_coefficients_with(target: &Target, basis: &Basis, params: &mut Params) {
    let n = params.len();
    let (mut gram, rhs) = gram_and_rhs(target, basis);
    mirror_upper(&mut gram, n);
    let channels: Vec<Vec<f64>> = (0..3)
        .into_par_iter()
        .map(|c| {
            let b: Vec<f64> = (0..n).map(|j| rhs[3 * j + c]).collect();
            nnls(&gram, &b, n)
        })
        .collect();
    for (j, coef) in params.coefs.iter_mut().enumerate() {
        *coef = DVec3::new(channels[0][j], channels[1][j], channels[2][j]);
    }
}

/// The Gram matrix (upper triangle, row-major n × n) and the right-hand sides (n × 3).
fn gram_and_rhs(target: &Target, basis: &Basis) -> (Vec<f64>, Vec<f64>) {
    let n = basis.lights;
    let all: Vec<usize> = (0..n).collect();
    let joined = task_ranges(target.len())
        .into_par_iter()
        .map(|range| {
            let mut gram = vec![0.0; n * n];
            let mut rhs = vec![0.0; 3 * n];
            let mut v = vec![0.0; n * BATCH];
            for start in range.clone().step_by(BATCH) {
                let end = (start + BATCH).min(range.end);
                v.iter_mut().for_each(|x| *x = 0.0);
                for (i, p) in (start..end).enumerate() {
                    let g = basis.row(p);
                    let w = target.weights[p];
                    let sw = w.sqrt();
                    let value = target.values[p];
                    for j in 0..n {
                        v[j * BATCH + i] = sw * g[j];
                        let wg = w * g[j];
                        rhs[3 * j] += wg * value.x;
                        rhs[3 * j + 1] += wg * value.y;
                        rhs[3 * j + 2] += wg * value.z;
                    }
                }
                add_gram_upper(&mut gram, &v, n, BATCH, &all);
            }
            gram.extend(rhs);
            gram
        })
        .collect::<Vec<_>>()
        .into_iter()
        .fold(vec![0.0; n * n + 3 * n], add_vectors);
    let (gram, rhs) = joined.split_at(n * n);
    (gram.to_vec(), rhs.to_vec())
}
