//! The absorption axis every per-channel table of the renderer shares (lobe table,
//! back-scattering tables, exact half-circle averages): x = ln(1 + μ_a/0.02) over the
//! parameters' validated μ_a ∈ [0, 1000], linear where hair is nearly transparent (where the
//! averages change fastest) and logarithmic beyond, so per-strand absorption needs no rebuild.

/// Largest μ_a tabulated (the parameters' validated range).
pub const SIGMA_MAX: f64 = 1000.0;
/// The axis is linear below this μ_a and logarithmic above.
pub const SIGMA_SCALE: f64 = 0.02;

/// x of μ_a (negative μ_a reads 0).
pub fn coordinate(mu_a: f64) -> f64 {
    (mu_a.max(0.0) / SIGMA_SCALE).ln_1p()
}

/// μ_a of x, the inverse of [`coordinate`].
pub fn sigma(x: f64) -> f64 {
    SIGMA_SCALE * x.exp_m1()
}

/// x of [`SIGMA_MAX`], the axis' end.
pub fn max_coordinate() -> f64 {
    coordinate(SIGMA_MAX)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The two directions invert each other, and the axis starts at μ_a = 0.
    #[test]
    fn coordinate_and_sigma_invert_each_other() {
        assert_eq!(coordinate(0.0), 0.0);
        for &s in &[0.0, 0.01, 0.3, 7.0, 1000.0] {
            assert!((sigma(coordinate(s)) - s).abs() <= 1e-12 * s.max(1.0));
        }
        assert!((sigma(max_coordinate()) - SIGMA_MAX).abs() < 1e-9);
    }
}
