//! Polynomial evaluation by Horner's rule.

/// c₀ + c₁x + c₂x² + … by Horner's rule, from the highest coefficient down: the same operations
/// in the same order as the nested form, so results are identical to it.
#[inline(always)]
pub fn horner(x: f64, coefficients: &[f64]) -> f64 {
    coefficients.iter().rev().fold(0.0, |acc, &c| acc * x + c)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn evaluates_lowest_degree_first() {
        assert_eq!(horner(2.0, &[1.0, -3.0, 0.5]), 1.0 - 6.0 + 2.0);
        assert_eq!(horner(7.0, &[]), 0.0);
    }
}
