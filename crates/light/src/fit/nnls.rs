//! Non-negative least squares in normal-equation form: min ½xᵀAx − bᵀx subject to x ≥ 0, for a
//! symmetric positive semi-definite A. This is Lawson & Hanson's (1974) active-set algorithm
//! written on AᵀA and Aᵀb, as Bro & de Jong (1997) do, so that the fit never forms its residuals.

use super::linalg::{Cholesky, submatrix};

/// The minimiser x ≥ 0 of ½xᵀAx − bᵀx; `a` is row-major `n × n`.
pub fn nnls(a: &[f64], b: &[f64], n: usize) -> Vec<f64> {
    let scale = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let mut x = vec![0.0; n];
    if scale == 0.0 {
        return x;
    }
    let tol = 1e-12 * scale;
    let mut passive = vec![false; n];
    let mut excluded = vec![false; n];
    for _ in 0..3 * n + 10 {
        let w = gradient(a, b, &x, n);
        let Some(j) = (0..n)
            .filter(|&i| !passive[i] && !excluded[i] && w[i] > tol)
            .max_by(|&p, &q| w[p].total_cmp(&w[q]))
        else {
            break;
        };
        passive[j] = true;
        if !inner_loop(a, b, n, &mut x, &mut passive, j) {
            excluded[j] = true;
        } else {
            excluded.iter_mut().for_each(|e| *e = false);
        }
    }
    x
}

/// b − A x: the negative gradient, positive where raising x_i lowers the objective.
fn gradient(a: &[f64], b: &[f64], x: &[f64], n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| b[i] - super::linalg::dot(&a[i * n..(i + 1) * n], x))
        .collect()
}

/// Lawson–Hanson's inner loop after `entering` joined the passive set: solve on the passive set,
/// step back toward feasibility until the solution is positive. Returns false (and undoes the
/// entry) when the entering variable cannot become positive, which only rounding causes.
fn inner_loop(
    a: &[f64],
    b: &[f64],
    n: usize,
    x: &mut [f64],
    passive: &mut [bool],
    entering: usize,
) -> bool {
    for round in 0..n + 1 {
        let s = passive_solution(a, b, n, passive);
        if round == 0 && s[entering] <= 0.0 {
            passive[entering] = false;
            return false;
        }
        if (0..n).all(|i| !passive[i] || s[i] > 0.0) {
            x.copy_from_slice(&s);
            return true;
        }
        let alpha = (0..n)
            .filter(|&i| passive[i] && s[i] <= 0.0)
            .map(|i| x[i] / (x[i] - s[i]))
            .fold(f64::INFINITY, f64::min);
        for i in 0..n {
            x[i] += alpha * (s[i] - x[i]);
            if passive[i] && x[i] <= 1e-300 {
                passive[i] = false;
                x[i] = 0.0;
            }
        }
    }
    true
}

/// Solution of A_PP s_P = b_P on the passive set P, zero elsewhere; a relative ridge of 1e-12
/// keeps coincident basis functions solvable.
fn passive_solution(a: &[f64], b: &[f64], n: usize, passive: &[bool]) -> Vec<f64> {
    let idx: Vec<usize> = (0..n).filter(|&i| passive[i]).collect();
    let mut sub = submatrix(a, n, &idx);
    let m = idx.len();
    let ridge = 1e-12 * (0..m).map(|i| sub[i * m + i]).fold(0.0, f64::max) + 1e-300;
    (0..m).for_each(|i| sub[i * m + i] += ridge);
    let rhs: Vec<f64> = idx.iter().map(|&i| b[i]).collect();
    let mut s = vec![0.0; n];
    if let Some(chol) = Cholesky::new(&sub, m) {
        for (k, v) in chol.solve(&rhs).into_iter().enumerate() {
            s[idx[k]] = v;
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A = MᵀM for a fixed tall M, b = Mᵀy.
    fn problem(y: &[f64]) -> (Vec<f64>, Vec<f64>, usize) {
        let (rows, n) = (y.len(), 5);
        let m: Vec<f64> = (0..rows * n)
            .map(|i| (((i * 37) % 17) as f64 / 17.0) + if i % (n + 1) == 0 { 1.0 } else { 0.0 })
            .collect();
        let a = (0..n * n)
            .map(|ij| {
                (0..rows)
                    .map(|r| m[r * n + ij / n] * m[r * n + ij % n])
                    .sum()
            })
            .collect();
        let b = (0..n)
            .map(|i| (0..rows).map(|r| m[r * n + i] * y[r]).sum())
            .collect();
        (a, b, n)
    }

    fn objective(a: &[f64], b: &[f64], x: &[f64], n: usize) -> f64 {
        let ax: Vec<f64> = (0..n)
            .map(|i| (0..n).map(|j| a[i * n + j] * x[j]).sum())
            .collect();
        0.5 * (0..n).map(|i| x[i] * ax[i]).sum::<f64>() - (0..n).map(|i| b[i] * x[i]).sum::<f64>()
    }

    #[test]
    fn satisfies_the_kkt_conditions() {
        let y: Vec<f64> = (0..9).map(|i| ((i * 5) % 7) as f64 - 3.0).collect();
        let (a, b, n) = problem(&y);
        let x = nnls(&a, &b, n);
        let w = gradient(&a, &b, &x, n);
        assert!(x.contains(&0.0), "the test wants an active bound");
        for i in 0..n {
            assert!(x[i] >= 0.0);
            if x[i] > 0.0 {
                assert!(w[i].abs() < 1e-9, "free variable {i} has gradient {}", w[i]);
            } else {
                assert!(w[i] <= 1e-9, "bound variable {i} wants to grow: {}", w[i]);
            }
        }
    }

    #[test]
    fn beats_every_nearby_feasible_point() {
        let y: Vec<f64> = (0..9).map(|i| ((i * 3) % 5) as f64 - 1.5).collect();
        let (a, b, n) = problem(&y);
        let x = nnls(&a, &b, n);
        let best = objective(&a, &b, &x, n);
        for k in 0..n {
            for delta in [-0.1, 0.1] {
                let mut z = x.clone();
                z[k] = (z[k] + delta).max(0.0);
                assert!(objective(&a, &b, &z, n) >= best - 1e-12);
            }
        }
    }

    #[test]
    fn unconstrained_optimum_is_returned_when_positive() {
        let (a, _, n) = problem(&[1.0; 9]);
        let x_true = [0.5, 1.0, 2.0, 0.25, 3.0];
        let b: Vec<f64> = (0..n)
            .map(|i| (0..n).map(|j| a[i * n + j] * x_true[j]).sum())
            .collect();
        let x = nnls(&a, &b, n);
        for (u, v) in x.iter().zip(x_true) {
            assert!((u - v).abs() < 1e-8, "{u} vs {v}");
        }
    }
}
