//! Gauss–Legendre rules on [−1, 1], computed once per order and cached.

use std::f64::consts::PI;
use std::sync::OnceLock;

/// A Gauss–Legendre rule on [−1, 1]: nodes and weights.
#[derive(Clone, Debug)]
pub struct GaussLegendre {
    pub nodes: Vec<f64>,
    pub weights: Vec<f64>,
}

impl GaussLegendre {
    /// The n-point rule, nodes found by Newton's method on Pₙ from the Tricomi initial guesses.
    pub fn new(n: usize) -> Self {
        let mut nodes = vec![0.0; n];
        let mut weights = vec![0.0; n];
        for i in 0..n.div_ceil(2) {
            let mut x = (PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            let mut dp = 1.0;
            for _ in 0..100 {
                let (p, d) = legendre_and_derivative(n, x);
                dp = d;
                let dx = p / d;
                x -= dx;
                if dx.abs() < 1e-15 {
                    break;
                }
            }
            let (_, d) = legendre_and_derivative(n, x);
            dp = if d != 0.0 { d } else { dp };
            let w = 2.0 / ((1.0 - x * x) * dp * dp);
            nodes[i] = -x;
            nodes[n - 1 - i] = x;
            weights[i] = w;
            weights[n - 1 - i] = w;
        }
        Self { nodes, weights }
    }

    /// A shared rule of `n` points, built once per size in the cache of common sizes.
    pub fn cached(n: usize) -> &'static GaussLegendre {
        static RULES: OnceLock<Vec<GaussLegendre>> = OnceLock::new();
        let rules = RULES.get_or_init(|| (0..=MAX_CACHED).map(GaussLegendre::new).collect());
        &rules[n.clamp(1, MAX_CACHED)]
    }

    /// ∫ₐᵇ f by this rule.
    pub fn integrate(&self, a: f64, b: f64, mut f: impl FnMut(f64) -> f64) -> f64 {
        let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
        self.nodes
            .iter()
            .zip(&self.weights)
            .map(|(x, w)| w * f(mid + half * x))
            .sum::<f64>()
            * half
    }

    /// (node, weight) pairs of this rule on every panel between consecutive `breaks`.
    pub fn panel_nodes(&self, breaks: &[f64]) -> Vec<(f64, f64)> {
        breaks
            .windows(2)
            .flat_map(|w| {
                let (mid, half) = (0.5 * (w[0] + w[1]), 0.5 * (w[1] - w[0]));
                self.nodes
                    .iter()
                    .zip(&self.weights)
                    .map(move |(x, wt)| (mid + half * x, wt * half))
            })
            .collect()
    }
}

/// The largest rule [`GaussLegendre::cached`] holds.
pub const MAX_CACHED: usize = 128;

pub(super) fn legendre_and_derivative(n: usize, x: f64) -> (f64, f64) {
    let (mut p0, mut p1) = (1.0, x);
    for k in 2..=n {
        let k = k as f64;
        let p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
    }
    if n == 0 {
        return (1.0, 0.0);
    }
    let d = n as f64 * (x * p1 - p0) / (x * x - 1.0);
    (p1, d)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gauss_legendre_integrates_polynomials_exactly() {
        let rule = GaussLegendre::new(70);
        let exact = 2.0 / 139.0; // ∫ x^138 over [−1, 1]
        assert!((rule.integrate(-1.0, 1.0, |x| x.powi(138)) - exact).abs() < 1e-14);
        assert!((rule.weights.iter().sum::<f64>() - 2.0).abs() < 1e-13);
        assert!((GaussLegendre::cached(7).integrate(0.0, PI, f64::sin) - 2.0).abs() < 1e-6);
    }
}
