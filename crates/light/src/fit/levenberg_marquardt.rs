//! The non-linear half of the fit: a projected Levenberg–Marquardt refinement of every light's
//! centre, bandwidth and coefficients together (after Tsai & Shih 2006 and Ren et al. 2010, who
//! refine SRBF lights by non-linear least squares). Coefficients stay ≥ 0 by an active set (a
//! coefficient at 0 whose gradient pushes it negative is held) and projection; after each
//! accepted step the coefficients are re-solved exactly by NNLS for the new geometry, so the
//! error on a given target never rises. When a lobe becomes narrower than the samples around it,
//! or the fit better than the detail the target hides, the adaptive target is refined and the
//! error measured afresh.

use super::adaptive_target::{AdaptiveTarget, DETAIL_SHARE};
use super::coefficients::solve_coefficients_with;
use super::linalg::{Cholesky, submatrix};
use super::model::Basis;
use super::normal_equations::{NormalEquations, coef_index, geom_index, normal_equations};
use super::params::{LightStep, Params};
use super::target::Target;
use glam::DVec3;

pub struct LmSettings {
    pub max_iterations: usize,
    /// Stop after three accepted steps in a row that each lower the error by less than this
    /// fraction.
    pub tolerance: f64,
    pub kappa_range: (f64, f64),
}

pub struct LmOutcome {
    pub params: Params,
    pub sse: f64,
    pub iterations: usize,
}

const INITIAL_DAMPING: f64 = 1e-3;
const MAX_DAMPING: f64 = 1e10;
const MAX_ATTEMPTS: usize = 12;

/// Refines `params` (coefficients already NNLS-optimal for its geometry); `progress` hears the
/// iteration number and the current weighted squared error after each iteration.
pub fn refine(
    adaptive: &mut AdaptiveTarget,
    mut params: Params,
    settings: &LmSettings,
    progress: &mut dyn FnMut(usize, f64),
) -> LmOutcome {
    let mut basis = Basis::new(adaptive.target(), &params);
    let mut sse = basis.sse(adaptive.target(), &params.coefs);
    let mut damping = INITIAL_DAMPING;
    let mut small_steps = 0;
    let mut iterations = 0;
    while iterations < settings.max_iterations && sse > 0.0 {
        iterations += 1;
        let target = adaptive.target();
        let frames = params.frames();
        let ne = normal_equations(target, &basis, &params, &frames);
        let mut improved = None;
        for _ in 0..MAX_ATTEMPTS {
            if let Some(steps) = damped_step(&ne, &params, damping) {
                let trial = params.stepped(&frames, &steps, settings.kappa_range);
                let trial_basis = Basis::new(target, &trial);
                let trial_sse = trial_basis.sse(target, &trial.coefs);
                if trial_sse < sse {
                    improved = Some(polished(target, trial, trial_basis, trial_sse));
                    damping = (damping / 3.0).max(1e-12);
                    break;
                }
            }
            damping *= 4.0;
            if damping > MAX_DAMPING {
                break;
            }
        }
        let Some((next, next_basis, next_sse)) = improved else {
            break;
        };
        let decrease = (sse - next_sse) / sse;
        small_steps = if decrease < settings.tolerance {
            small_steps + 1
        } else {
            0
        };
        params = next;
        basis = next_basis;
        sse = next_sse;
        let detailed = adaptive.refine_detail(DETAIL_SHARE * sse);
        if adaptive.resolve_lobes(&params.lobes()) || detailed {
            basis = Basis::new(adaptive.target(), &params);
            solve_coefficients_with(adaptive.target(), &basis, &mut params);
            sse = basis.sse(adaptive.target(), &params.coefs);
            small_steps = 0;
        }
        progress(iterations, sse);
        if small_steps >= 3 {
            break;
        }
    }
    LmOutcome {
        params,
        sse,
        iterations,
    }
}

/// The trial with its coefficients re-solved by NNLS, if that lowers the error further (the
/// bases depend on the geometry only, so they stay valid).
fn polished(target: &Target, trial: Params, basis: Basis, trial_sse: f64) -> (Params, Basis, f64) {
    let mut nnls = trial.clone();
    solve_coefficients_with(target, &basis, &mut nnls);
    let nnls_sse = basis.sse(target, &nnls.coefs);
    if nnls_sse <= trial_sse {
        (nnls, basis, nnls_sse)
    } else {
        (trial, basis, trial_sse)
    }
}

/// Solves (H_FF + μ diag H_FF) δ_F = −g_F on the free unknowns F and returns δ per light;
/// `None` when the damped matrix is not positive definite.
fn damped_step(ne: &NormalEquations, params: &Params, damping: f64) -> Option<Vec<LightStep>> {
    let free = free_unknowns(ne, params);
    let n = ne.size;
    let mut h = submatrix(&ne.hessian, n, &free);
    let m = free.len();
    let floor = 1e-15 * (0..m).map(|i| h[i * m + i]).fold(0.0, f64::max) + 1e-300;
    for i in 0..m {
        h[i * m + i] += damping * h[i * m + i].max(floor);
    }
    let rhs: Vec<f64> = free.iter().map(|&i| -ne.gradient[i]).collect();
    let solution = Cholesky::new(&h, m)?.solve(&rhs);
    let mut delta = vec![0.0; n];
    for (k, &i) in free.iter().enumerate() {
        delta[i] = solution[k];
    }
    Some(to_light_steps(&delta, params.len()))
}

/// Unknowns the step may move: coefficients except those at 0 whose gradient is positive
/// (descent would take them negative), and the geometry of lights that still shine.
fn free_unknowns(ne: &NormalEquations, params: &Params) -> Vec<usize> {
    let lights = params.len();
    let mut free = Vec::with_capacity(ne.size);
    for j in 0..lights {
        for c in 0..3 {
            let i = coef_index(j, c);
            if params.coefs[j][c] > 0.0 || ne.gradient[i] < 0.0 {
                free.push(i);
            }
        }
    }
    for j in 0..lights {
        if params.coefs[j].max_element() > 0.0 {
            free.extend((0..3).map(|k| geom_index(lights, j, k)));
        }
    }
    free
}

fn to_light_steps(delta: &[f64], lights: usize) -> Vec<LightStep> {
    (0..lights)
        .map(|j| LightStep {
            coef: DVec3::new(
                delta[coef_index(j, 0)],
                delta[coef_index(j, 1)],
                delta[coef_index(j, 2)],
            ),
            tangent: [
                delta[geom_index(lights, j, 0)],
                delta[geom_index(lights, j, 1)],
            ],
            log_kappa: delta[geom_index(lights, j, 2)],
        })
        .collect()
}
