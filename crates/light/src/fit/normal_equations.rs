//! The Gauss–Newton normal equations of the fit at the current parameters.
//!
//! Residuals r_pc = √w_p (Σ_j L_jc G_j(ω_p) − L_pc). Per light the unknowns are its three
//! coefficients and three geometric coordinates: tangent offsets (a, b) of the centre and s = ln κ,
//! with (G = exp(κ(ω·ω_j − 1)), Xu et al. 2011 eq. 1)
//!   ∂G/∂a = κ G (ω·t1),  ∂G/∂b = κ G (ω·t2),  ∂G/∂s = κ G (ω·ω_j − 1),
//! and for the blurred basis G̃ = r exp(κ'(ω·ω_j − 1)) of [`super::model`] (κ' = κr, r = 1/(1+κβ),
//! ∂κ'/∂s = κ' r, ∂ln r/∂s = −(1 − r)):
//!   ∂G̃/∂a = κ' G̃ (ω·t1),  ∂G̃/∂b = κ' G̃ (ω·t2),  ∂G̃/∂s = G̃ (κ' r (ω·ω_j − 1) − (1 − r)).
//! With v_p = [G_1 … G_J, ∂G_1/∂a, ∂G_1/∂b, ∂G_1/∂s, …] and M = Σ_p w_p v_p v_pᵀ, the
//! Gauss–Newton matrix H = JᵀJ has the blocks
//!   H[L_jc, L_kc] = M[G_j, G_k],  H[L_jc, x_k] = L_kc M[G_j, ∂_x G_k],
//!   H[x_j, y_k] = (Σ_c L_jc L_kc) M[∂_x G_j, ∂_y G_k],
//! so one accumulation of M (4J wide) gives the whole 6J × 6J system.

use super::model::{
    BATCH, Basis, NEGLIGIBLE, add_gram_upper, add_vectors, filtered_basis, mirror_upper,
    task_ranges,
};
use super::params::{Frame, Params};
use super::target::Target;
use rayon::prelude::*;

/// H and g = Jᵀr in the unknown order [L_0 (r,g,b), …, L_{J−1}, (a, b, s)_0, …, (a, b, s)_{J−1}].
pub struct NormalEquations {
    pub size: usize,
    pub hessian: Vec<f64>,
    pub gradient: Vec<f64>,
}

/// Index of coefficient channel `c` of light `j`.
pub fn coef_index(j: usize, c: usize) -> usize {
    3 * j + c
}

/// Index of geometric coordinate `k` (0 = a, 1 = b, 2 = ln κ) of light `j` among `lights`.
pub fn geom_index(lights: usize, j: usize, k: usize) -> usize {
    3 * lights + 3 * j + k
}

/// The normal equations at `params`, whose bases `basis` holds.
pub fn normal_equations(
    target: &Target,
    basis: &Basis,
    params: &Params,
    frames: &[Frame],
) -> NormalEquations {
    let n = params.len();
    let width = 4 * n;
    let acc = task_ranges(target.len())
        .into_par_iter()
        .map(|range| accumulate(target, basis, params, frames, range))
        .collect::<Vec<_>>()
        .into_iter()
        .fold(vec![0.0; width * width + 6 * n], add_vectors);
    let (m, gradient) = acc.split_at(width * width);
    let mut m = m.to_vec();
    mirror_upper(&mut m, width);
    NormalEquations {
        size: 6 * n,
        hessian: assemble(&m, params),
        gradient: gradient.to_vec(),
    }
}

/// M (upper triangle, 4J × 4J) followed by the gradient (6J) over the pixels of `range`.
fn accumulate(
    target: &Target,
    basis: &Basis,
    params: &Params,
    frames: &[Frame],
    range: std::ops::Range<usize>,
) -> Vec<f64> {
    let n = params.len();
    let width = 4 * n;
    let mut m = vec![0.0; width * width];
    let mut grad = vec![0.0; 6 * n];
    let mut v = vec![0.0; width * BATCH];
    let mut peak = vec![0.0f64; n];
    for start in range.clone().step_by(BATCH) {
        let end = (start + BATCH).min(range.end);
        v.iter_mut().for_each(|x| *x = 0.0);
        peak.iter_mut().for_each(|x| *x = 0.0);
        for (i, p) in (start..end).enumerate() {
            let (dir, w, blur) = (target.dirs[p], target.weights[p], target.blur[p]);
            let g = basis.row(p);
            peak.iter_mut().zip(g).for_each(|(p, g)| *p = p.max(*g));
            let model: glam::DVec3 = (0..n).map(|j| params.coefs[j] * g[j]).sum();
            let r = model - target.values[p];
            let sw = w.sqrt();
            for j in 0..n {
                let cos = dir.dot(params.dirs[j]);
                let f = filtered_basis(params.kappas[j], blur, cos);
                let kg = f.kappa * f.value;
                let d = [
                    kg * dir.dot(frames[j].t1),
                    kg * dir.dot(frames[j].t2),
                    f.value * (f.kappa * f.ratio * (cos - 1.0) - (1.0 - f.ratio)),
                ];
                v[j * BATCH + i] = sw * g[j];
                let wg = w * g[j];
                grad[coef_index(j, 0)] += wg * r.x;
                grad[coef_index(j, 1)] += wg * r.y;
                grad[coef_index(j, 2)] += wg * r.z;
                let q = w * params.coefs[j].dot(r);
                for (k, dk) in d.iter().enumerate() {
                    v[(n + 3 * j + k) * BATCH + i] = sw * dk;
                    grad[geom_index(n, j, k)] += q * dk;
                }
            }
        }
        add_gram_upper(&mut m, &v, width, BATCH, &active_features(&peak));
    }
    m.extend(grad);
    m
}

/// The rows of v (ascending) that belong to lights whose basis reaches [`NEGLIGIBLE`] in the batch.
fn active_features(peak: &[f64]) -> Vec<usize> {
    let n = peak.len();
    let lights: Vec<usize> = (0..n).filter(|&j| peak[j] > NEGLIGIBLE).collect();
    let values = lights.iter().copied();
    let derivatives = lights
        .iter()
        .flat_map(|&j| (0..3).map(move |k| n + 3 * j + k));
    values.chain(derivatives).collect()
}

/// H from M by the block rules in the module docs.
fn assemble(m: &[f64], params: &Params) -> Vec<f64> {
    let n = params.len();
    let width = 4 * n;
    let size = 6 * n;
    let mut h = vec![0.0; size * size];
    let feat_g = |j: usize| j;
    let feat_d = |j: usize, k: usize| n + 3 * j + k;
    for j in 0..n {
        for l in 0..n {
            let mgg = m[feat_g(j) * width + feat_g(l)];
            let cross = params.coefs[j].dot(params.coefs[l]);
            for c in 0..3 {
                h[coef_index(j, c) * size + coef_index(l, c)] = mgg;
                for k in 0..3 {
                    let mgd = m[feat_g(j) * width + feat_d(l, k)] * params.coefs[l][c];
                    h[coef_index(j, c) * size + geom_index(n, l, k)] = mgd;
                    h[geom_index(n, l, k) * size + coef_index(j, c)] = mgd;
                }
            }
            for k in 0..3 {
                for q in 0..3 {
                    h[geom_index(n, j, k) * size + geom_index(n, l, q)] =
                        cross * m[feat_d(j, k) * width + feat_d(l, q)];
                }
            }
        }
    }
    h
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::latlong::direction_from_angles;
    use crate::srbf::sharpness_of;
    use glam::DVec3;

    /// A small target with varied blur, and three lights with positive coefficients.
    fn setup() -> (Target, Params) {
        let (w, h) = (24, 12);
        let mut dirs = Vec::new();
        let mut values = Vec::new();
        let mut blur = Vec::new();
        for k in 0..h {
            for j in 0..w {
                let d = direction_from_angles(
                    crate::latlong::theta_center(k, h),
                    crate::latlong::phi_center(j, w),
                );
                dirs.push(d);
                values.push(DVec3::new(1.0 + d.x, 0.5 + d.y * d.y, 2.0 * (1.0 + d.z)));
                blur.push(if (j + k) % 3 == 0 {
                    0.0
                } else {
                    0.002 * (j % 5) as f64
                });
            }
        }
        let weights = (0..w * h)
            .map(|i| crate::latlong::pixel_solid_angle(i / w, w, h))
            .collect();
        let target = Target::new(dirs, weights, values, blur);
        let params = Params {
            dirs: vec![
                direction_from_angles(0.3, 0.5),
                direction_from_angles(-0.4, 2.0),
                direction_from_angles(1.2, -1.0),
            ],
            kappas: vec![sharpness_of(0.6), sharpness_of(0.3), sharpness_of(1.1)],
            coefs: vec![
                DVec3::new(1.0, 0.4, 0.7),
                DVec3::new(0.3, 0.9, 0.5),
                DVec3::new(0.6, 0.2, 1.5),
            ],
        };
        (target, params)
    }

    /// The parameters moved by `h` along unknown `index` (in the normal equations' order).
    fn moved(params: &Params, frames: &[Frame], index: usize, h: f64) -> Params {
        let n = params.len();
        let mut steps = vec![super::super::params::LightStep::default(); n];
        if index < 3 * n {
            steps[index / 3].coef[index % 3] = h;
        } else {
            let (j, k) = ((index - 3 * n) / 3, (index - 3 * n) % 3);
            match k {
                0 => steps[j].tangent[0] = h,
                1 => steps[j].tangent[1] = h,
                _ => steps[j].log_kappa = h,
            }
        }
        params.stepped(frames, &steps, (1e-6, 1e9))
    }

    /// Residuals √w (model − L) per sample and channel.
    fn residuals(target: &Target, params: &Params) -> Vec<f64> {
        let basis = Basis::new(target, params);
        (0..target.len())
            .flat_map(|p| {
                let r =
                    (basis.model(p, &params.coefs) - target.values[p]) * target.weights[p].sqrt();
                [r.x, r.y, r.z]
            })
            .collect()
    }

    #[test]
    fn gradient_and_gauss_newton_matrix_match_finite_differences() {
        let (target, params) = setup();
        let frames = params.frames();
        let basis = Basis::new(&target, &params);
        let ne = normal_equations(&target, &basis, &params, &frames);
        let h = 1e-6;
        let size = ne.size;
        let jacobian: Vec<Vec<f64>> = (0..size)
            .map(|i| {
                let plus = residuals(&target, &moved(&params, &frames, i, h));
                let minus = residuals(&target, &moved(&params, &frames, i, -h));
                plus.iter()
                    .zip(&minus)
                    .map(|(a, b)| (a - b) / (2.0 * h))
                    .collect()
            })
            .collect();
        let r0 = residuals(&target, &params);
        for i in 0..size {
            let g: f64 = jacobian[i].iter().zip(&r0).map(|(a, b)| a * b).sum();
            let tol = 1e-5 * (1.0 + g.abs());
            assert!(
                (ne.gradient[i] - g).abs() < tol,
                "g[{i}]: {} vs {g}",
                ne.gradient[i]
            );
            for k in 0..size {
                let jtj: f64 = jacobian[i]
                    .iter()
                    .zip(&jacobian[k])
                    .map(|(a, b)| a * b)
                    .sum();
                let got = ne.hessian[i * size + k];
                assert!(
                    (got - jtj).abs() < 1e-5 * (1.0 + jtj.abs()),
                    "H[{i},{k}]: {got} vs {jtj}"
                );
            }
        }
    }
}
