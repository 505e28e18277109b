//! Dense linear algebra for the fit's small symmetric systems (a few hundred unknowns at most):
//! Cholesky factorisation and solve, and a dot product written for the auto-vectoriser.

/// Lower-triangular Cholesky factor L of a symmetric positive definite matrix, A = L Lᵀ.
pub struct Cholesky {
    n: usize,
    l: Vec<f64>,
}

impl Cholesky {
    /// Factorises the row-major `n × n` matrix `a` (only its lower triangle is read); `None` when
    /// it is not numerically positive definite.
    pub fn new(a: &[f64], n: usize) -> Option<Self> {
        let mut l = vec![0.0; n * n];
        for i in 0..n {
            for j in 0..=i {
                let s = a[i * n + j] - dot(&l[i * n..i * n + j], &l[j * n..j * n + j]);
                if i == j {
                    if s <= 0.0 || !s.is_finite() {
                        return None;
                    }
                    l[i * n + i] = s.sqrt();
                } else {
                    l[i * n + j] = s / l[j * n + j];
                }
            }
        }
        Some(Self { n, l })
    }

    /// x with A x = b.
    pub fn solve(&self, b: &[f64]) -> Vec<f64> {
        let n = self.n;
        let mut y = vec![0.0; n];
        for i in 0..n {
            y[i] = (b[i] - dot(&self.l[i * n..i * n + i], &y[..i])) / self.l[i * n + i];
        }
        let mut x = vec![0.0; n];
        for i in (0..n).rev() {
            let s: f64 = (i + 1..n).map(|k| self.l[k * n + i] * x[k]).sum();
            x[i] = (y[i] - s) / self.l[i * n + i];
        }
        x
    }
}

/// Σ a_i b_i with eight independent partial sums (vectorises; the order differs from a plain
/// left fold only by rounding).
pub fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut acc = [0.0; 8];
    let (ca, cb) = (a.chunks_exact(8), b.chunks_exact(8));
    let tail: f64 = ca
        .remainder()
        .iter()
        .zip(cb.remainder())
        .map(|(x, y)| x * y)
        .sum();
    for (x, y) in ca.zip(cb) {
        for k in 0..8 {
            acc[k] += x[k] * y[k];
        }
    }
    acc.iter().sum::<f64>() + tail
}

/// The `idx × idx` submatrix of the row-major `n × n` matrix `a`.
pub fn submatrix(a: &[f64], n: usize, idx: &[usize]) -> Vec<f64> {
    idx.iter()
        .flat_map(|&i| idx.iter().map(move |&j| a[i * n + j]))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cholesky_solves_a_spd_system() {
        let n = 13;
        let m: Vec<f64> = (0..n * n)
            .map(|i| ((i * 7919) % 23) as f64 / 23.0 - 0.4)
            .collect();
        let mut a = vec![0.0; n * n];
        for i in 0..n {
            for j in 0..n {
                a[i * n + j] = (0..n).map(|k| m[i * n + k] * m[j * n + k]).sum::<f64>();
            }
            a[i * n + i] += 0.1;
        }
        let x_true: Vec<f64> = (0..n).map(|i| i as f64 - 6.0).collect();
        let b: Vec<f64> = (0..n)
            .map(|i| dot(&a[i * n..(i + 1) * n], &x_true))
            .collect();
        let x = Cholesky::new(&a, n).unwrap().solve(&b);
        for (u, v) in x.iter().zip(&x_true) {
            assert!((u - v).abs() < 1e-9, "{u} vs {v}");
        }
    }

    #[test]
    fn cholesky_refuses_an_indefinite_matrix() {
        assert!(Cholesky::new(&[1.0, 2.0, 2.0, 1.0], 2).is_none());
    }

    #[test]
    fn dot_matches_a_plain_sum() {
        let a: Vec<f64> = (0..37).map(|i| i as f64 * 0.5).collect();
        let b: Vec<f64> = (0..37).map(|i| 3.0 - i as f64).collect();
        let plain: f64 = a.iter().zip(&b).map(|(x, y)| x * y).sum();
        assert!((dot(&a, &b) - plain).abs() < 1e-9);
    }
}
