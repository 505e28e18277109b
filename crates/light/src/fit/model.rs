//! The model the fit adjusts, Σ_j L_j G_j(ω) (Xu et al. 2011 eq. 1), evaluated over a target: basis
//! values, the weighted sum of squared errors, and the batching the accumulations share.
//!
//! A sample that stands for a cell of several pixels is compared with the model's mean over the
//! cell, not its value at the centre (else a narrow lobe could fit a coarse cell's mean with a
//! spike). Near its centre G = exp(κ(cos θ − 1)) ≈ exp(−κθ²/2), a 2D Gaussian of variance 1/κ
//! per axis; a box of variance β per axis convolves it into r·exp(κ'(cos θ − 1)) with
//! κ' = κ/(1 + κβ) and r = κ'/κ, which keeps ∫G dω and is G itself when β = 0.

use super::params::Params;
use super::target::Target;
use glam::DVec3;
use rayon::prelude::*;

/// Pixels per batch in the accumulations (rows of the batched matrices).
pub const BATCH: usize = 64;
/// Batches per parallel task.
pub const BATCHES_PER_TASK: usize = 8;

/// The basis blurred by β, with what its derivatives need.
#[derive(Clone, Copy, Debug)]
pub struct Filtered {
    /// r · exp(κ'(ω·ω_j − 1)).
    pub value: f64,
    /// κ' = κ/(1 + κβ).
    pub kappa: f64,
    /// r = 1/(1 + κβ).
    pub ratio: f64,
}

/// Exponents below this give 0 (e⁻⁶⁰ ≈ 1e-26 of the lobe's peak; it also spares `exp` its
/// slow underflow path, which narrow lobes would otherwise take at almost every sample).
const EXPONENT_CUTOFF: f64 = -60.0;

/// G_j blurred by a box of variance `blur` per axis, at cosine `cos` = ω·ω_j (module docs).
pub fn filtered_basis(kappa: f64, blur: f64, cos: f64) -> Filtered {
    let ratio = 1.0 / (1.0 + kappa * blur);
    let kappa = kappa * ratio;
    let exponent = kappa * (cos - 1.0);
    let value = if exponent < EXPONENT_CUTOFF {
        0.0
    } else {
        ratio * exponent.exp()
    };
    Filtered {
        value,
        kappa,
        ratio,
    }
}

/// The blurred bases G̃_j at every sample, computed once per parameter set and shared by the
/// error, the coefficient solve and the normal equations (the exponentials dominate otherwise).
pub struct Basis {
    pub lights: usize,
    /// Row-major samples × lights.
    pub values: Vec<f64>,
}

impl Basis {
    pub fn new(target: &Target, params: &Params) -> Self {
        let lights = params.len();
        let mut values = vec![0.0; target.len() * lights];
        values
            .par_chunks_mut(lights.max(1) * BATCH)
            .enumerate()
            .for_each(|(chunk, rows)| {
                for (i, row) in rows.chunks_mut(lights.max(1)).enumerate() {
                    let p = chunk * BATCH + i;
                    let (dir, blur) = (target.dirs[p], target.blur[p]);
                    for (j, g) in row.iter_mut().enumerate() {
                        *g = filtered_basis(params.kappas[j], blur, dir.dot(params.dirs[j])).value;
                    }
                }
            });
        Self { lights, values }
    }

    /// G̃_j(ω_p) for every j.
    pub fn row(&self, p: usize) -> &[f64] {
        &self.values[p * self.lights..(p + 1) * self.lights]
    }

    /// Σ_j L_j G̃_j(ω_p).
    pub fn model(&self, p: usize, coefs: &[DVec3]) -> DVec3 {
        self.row(p).iter().zip(coefs).map(|(g, c)| *c * *g).sum()
    }

    /// Σ_p w_p ‖Σ_j L_j G̃_j(ω_p) − L_p‖² for coefficients `coefs`.
    pub fn sse(&self, target: &Target, coefs: &[DVec3]) -> f64 {
        let partial: Vec<f64> = task_ranges(target.len())
            .into_par_iter()
            .map(|range| {
                range
                    .map(|p| {
                        target.weights[p]
                            * (self.model(p, coefs) - target.values[p]).length_squared()
                    })
                    .sum()
            })
            .collect();
        partial.iter().sum()
    }
}

/// Σ_p w_p ‖Σ_j L_j G̃_j(ω_p) − L_p‖².
pub fn sum_squared_error(target: &Target, params: &Params) -> f64 {
    Basis::new(target, params).sse(target, &params.coefs)
}

/// The sample ranges of the parallel tasks: fixed, so that partial sums combine in the same
/// order on any number of threads and a fit is reproducible to the last bit.
pub fn task_ranges(len: usize) -> Vec<std::ops::Range<usize>> {
    let step = BATCH * BATCHES_PER_TASK;
    (0..len.div_ceil(step))
        .map(|t| t * step..((t + 1) * step).min(len))
        .collect()
}

/// A light whose basis stays below this over a whole batch is left out of that batch's
/// Gauss–Newton matrix (its terms there are < 1e-8 of its own peak terms).
pub const NEGLIGIBLE: f64 = 1e-8;

/// Adds Σ_i v_a(i) v_b(i) to `m[a·n + b]` for b ≥ a and a, b in `active` (ascending), where `v`
/// holds `n` rows of `width` samples (row-major): one batch's contribution to a Gram matrix's
/// upper triangle.
pub fn add_gram_upper(m: &mut [f64], v: &[f64], n: usize, width: usize, active: &[usize]) {
    for (i, &a) in active.iter().enumerate() {
        let va = &v[a * width..(a + 1) * width];
        for &b in &active[i..] {
            m[a * n + b] += super::linalg::dot(va, &v[b * width..(b + 1) * width]);
        }
    }
}

/// Copies the upper triangle of a row-major `n × n` matrix into its lower triangle.
pub fn mirror_upper(m: &mut [f64], n: usize) {
    for a in 0..n {
        for b in 0..a {
            m[a * n + b] = m[b * n + a];
        }
    }
}

/// Element-wise sum of two equally long vectors (the reduction of the parallel accumulations).
pub fn add_vectors(mut a: Vec<f64>, b: Vec<f64>) -> Vec<f64> {
    a.iter_mut().zip(b).for_each(|(x, y)| *x += y);
    a
}
