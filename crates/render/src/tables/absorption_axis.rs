//! The absorption axis every per-channel table of the renderer shares (lobe table,
//! back-scattering tables, exact half-circle averages): x = ln(1 + μ_a/0.02) over the
//! parameters' validated μ_a ∈ [0, 1000], linear where hair is nearly transparent (where the
//! averages change fastest) and logarithmic beyond, so per-strand absorption needs no rebuild.

/// Largest μ_a tabulated (the parameters' validated range).
pub const MU_A_MAX: f64 = 1000.0;
/// The axis is linear below this μ_a and logarithmic above.
pub const MU_A_SCALE: f64 = 0.02;

/// x of μ_a (negative μ_a reads 0).
pub fn coordinate(mu_a: f64) -> f64 {
    (mu_a.max(0.0) / MU_A_SCALE).ln_1p()
}

/// μ_a of x, the inverse of [`coordinate`].
pub fn mu_a(x: f64) -> f64 {
    MU_A_SCALE * x.exp_m1()
}

/// x of [`MU_A_MAX`], the axis' end.
pub fn max_coordinate() -> f64 {
    coordinate(MU_A_MAX)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The two directions invert each other, and the axis starts at μ_a = 0.
    #[test]
    fn coordinate_and_sigma_invert_each_other() {
        assert_eq!(coordinate(0.0), 0.0);
        for &s in &[0.0, 0.01, 0.3, 7.0, 1000.0] {
            assert!((mu_a(coordinate(s)) - s).abs() <= 1e-12 * s.max(1.0));
        }
        assert!((mu_a(max_coordinate()) - MU_A_MAX).abs() < 1e-9);
    }
}
