//! The modified Bessel function I0: ln I0 stable for any argument, I0 by its series and by
//! Abramowitz & Stegun's fits (also in f32 lanes), and its scaled asymptotic expansion.

use super::polynomial::{estrin7_lanes_f32, estrin9_lanes_f32, horner, to_f32};
use std::f64::consts::PI;
use wide::f32x4;

/// ln I0(x) for x ≥ 0, accurate to ~1e-12 relative everywhere: the power series below 20, the
/// asymptotic expansion I0(x) ~ eˣ/√(2πx) Σ ((2k−1)!!)² / (k! (8x)ᵏ) above (d'Eon 2013 notes
/// that M must be evaluated in log space for small v, where x = cos θ cos θ′ / v is huge).
pub fn log_i0(x: f64) -> f64 {
    let x = x.abs();
    if x < I0_SERIES_MAX {
        i0_series(x).ln()
    } else {
        x + (asymptotic_sum(x) / (2.0 * PI * x).sqrt()).ln()
    }
}

/// Where [`log_i0`] and [`i0_horner`] leave the power series for the asymptotic expansion.
pub const I0_SERIES_MAX: f64 = 20.0;

/// Terms of the power series Σ (x²/4)ᵏ / (k!)² that [`i0_horner`] keeps: at x = 20 the first
/// term dropped, 100³⁸ / (38!)², is 2e-16 of I0(20).
pub(super) const I0_TERMS: usize = 38;

/// 1 / (k!)², k = 0…37: the power series' coefficients in q = x²/4.
pub(super) const I0_COEFFS: [f64; I0_TERMS] = {
    let mut c = [0.0; I0_TERMS];
    c[0] = 1.0;
    let mut k = 1;
    while k < I0_TERMS {
        c[k] = c[k - 1] / ((k * k) as f64);
        k += 1;
    }
    c
};

/// I0(x) for |x| ≤ 20 by the same power series as [`i0_series`], as a polynomial in x²/4 with
/// fixed coefficients and as many terms as the argument needs (no division, two Horner chains
/// in (x²/4)²): within 2e-15 relative of [`i0_series`] (`i0_horner_matches_the_series`
/// measures it).
#[inline]
pub fn i0_horner(x: f64) -> f64 {
    let q = 0.25 * x * x;
    // Terms needed for a relative error below 1e-17 at the top of each band of q.
    let n = if q <= 1.0 {
        14
    } else if q <= 16.0 {
        26
    } else {
        I0_TERMS
    };
    let q2 = q * q;
    let (mut even, mut odd) = (0.0, 0.0);
    let mut k = n;
    while k >= 2 {
        k -= 2;
        even = even * q2 + I0_COEFFS[k];
        odd = odd * q2 + I0_COEFFS[k + 1];
    }
    even + q * odd
}

/// Where [`i0_as`] leaves Abramowitz & Stegun 9.8.1 for 9.8.2.
pub const I0_AS_SPLIT: f64 = 3.75;

/// I0(x) for |x| ≤ 3.75 by Abramowitz & Stegun 1964 eq. 9.8.1, a polynomial of degree 6 in
/// (x/3.75)²: within 2e-7 relative of [`i0_series`] (`i0_as_is_within_its_bound` measures it).
/// The fast path of [`crate::lobes::longitudinal::LongitudinalWidth::eval`], six multiply-adds
/// where the series takes up to 38.
#[inline]
pub fn i0_as(x: f64) -> f64 {
    let t = x * (1.0 / I0_AS_SPLIT);
    horner(&I0_AS_COEFFS, t * t)
}

/// Abramowitz & Stegun 1964 eq. 9.8.1's coefficients, in (x/3.75)².
pub(super) const I0_AS_COEFFS: [f64; 7] = [
    1.0,
    3.515_622_9,
    3.089_942_4,
    1.206_749_2,
    0.265_973_2,
    0.036_076_8,
    0.004_581_3,
];

/// Abramowitz & Stegun 1964 eq. 9.8.2's coefficients, in 3.75/x.
pub(super) const I0_SCALED_AS_COEFFS: [f64; 9] = [
    0.398_942_28,
    0.013_285_92,
    0.002_253_19,
    -0.001_575_65,
    0.009_162_81,
    -0.020_577_06,
    0.026_355_37,
    -0.016_476_33,
    0.003_923_77,
];

/// e^{−x} I0(x) for x ≥ 3.75 by Abramowitz & Stegun 1964 eq. 9.8.2, √x e^{−x} I0(x) as a
/// polynomial of degree 8 in 3.75/x: within 6e-7 relative of the exact function
/// (`i0_as_is_within_its_bound`).
#[inline]
pub fn i0_scaled_as(x: f64) -> f64 {
    horner(&I0_SCALED_AS_COEFFS, I0_AS_SPLIT / x) / x.sqrt()
}

/// [`i0_as`] in each of four lanes, in single precision: within 5e-7 relative of it
/// (`i0_lanes_f32_are_the_scalar_fits`).
#[inline(always)]
pub fn i0_as_lanes_f32(x: f32x4) -> f32x4 {
    let t = x * f32x4::splat((1.0 / I0_AS_SPLIT) as f32);
    const COEFFS: [f32; 7] = to_f32(I0_AS_COEFFS);
    estrin7_lanes_f32(&COEFFS, t * t)
}

/// [`i0_scaled_as`] in each of four lanes, in single precision, with one division: q = 1/x,
/// P(3.75 q) √q. Within 5e-7 relative of it (`i0_lanes_f32_are_the_scalar_fits`).
#[inline(always)]
pub fn i0_scaled_as_lanes_f32(x: f32x4) -> f32x4 {
    let q = f32x4::ONE / x;
    let y = q * f32x4::splat(I0_AS_SPLIT as f32);
    const COEFFS: [f32; 9] = to_f32(I0_SCALED_AS_COEFFS);
    estrin9_lanes_f32(&COEFFS, y) * q.sqrt()
}

/// e^{−x} I0(x) for x ≥ 20, the asymptotic expansion of [`log_i0`] without its logarithm.
#[inline]
pub fn i0_scaled_asymptotic(x: f64) -> f64 {
    asymptotic_sum(x) / (2.0 * PI * x).sqrt()
}

/// Σ ((2k−1)!!)² / (k! (8x)ᵏ), summed while its terms still shrink (x ≥ 20: to ~1e-16).
pub(super) fn asymptotic_sum(x: f64) -> f64 {
    let (mut term, mut sum) = (1.0f64, 1.0f64);
    for k in 1..60 {
        let next = term * ((2 * k - 1) as f64).powi(2) / (k as f64 * 8.0 * x);
        if next >= term || next < 1e-17 {
            break;
        }
        term = next;
        sum += term;
    }
    sum
}

/// I0(x) by its power series Σ (x²/4)ᵏ / (k!)², summed until the terms stop mattering.
pub fn i0_series(x: f64) -> f64 {
    let q = 0.25 * x * x;
    let (mut term, mut sum, mut k) = (1.0, 1.0, 1.0);
    while term > 1e-17 * sum {
        term *= q / (k * k);
        sum += term;
        k += 1.0;
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn log_i0_is_continuous_across_the_switch_and_matches_the_series() {
        for &x in &[0.0, 0.1, 1.0, 5.0, 19.999] {
            assert!((log_i0(x) - i0_series(x).ln()).abs() < 1e-13);
        }
        // Both branches agree just across the switch point, and the series is valid at 40.
        assert!((log_i0(20.0) - i0_series(20.0).ln()).abs() < 1e-12);
        assert!((log_i0(40.0) - i0_series(40.0).ln()).abs() < 1e-11);
        assert!(log_i0(1e6).is_finite());
    }

    #[test]
    fn i0_horner_matches_the_series() {
        // The bound i0_horner's documentation states, over a dense grid of [0, 20] and at
        // every band edge of its term count.
        let mut worst: f64 = 0.0;
        let edges = [0.0, 2.0, 8.0, 20.0];
        for x in (0..=20_000).map(|k| k as f64 * 1e-3).chain(edges) {
            let want = i0_series(x);
            worst = worst.max(((i0_horner(x) - want) / want).abs());
        }
        eprintln!("i0_horner vs i0_series on [0, 20]: relative error ≤ {worst:.2e}");
        assert!(worst < 2e-15, "{worst:e}");
        assert!((i0_scaled_asymptotic(30.0).ln() + 30.0 - log_i0(30.0)).abs() < 1e-13);
    }

    /// Abramowitz & Stegun's fits in single-precision lanes against the same fits in double
    /// precision, on both sides of the split and far into 9.8.2's range.
    #[test]
    fn i0_lanes_f32_are_the_scalar_fits() {
        let (mut low, mut high): (f64, f64) = (0.0, 0.0);
        for k in 0..4000 {
            let x = 3.75 * k as f64 / 4000.0;
            let got = i0_as_lanes_f32(f32x4::splat(x as f32)).to_array()[0];
            low = low.max((f64::from(got) / i0_as(f64::from(x as f32)) - 1.0).abs());
            let y = 3.75 * 1.003f64.powi(k);
            let got = i0_scaled_as_lanes_f32(f32x4::splat(y as f32)).to_array()[0];
            high = high.max((f64::from(got) / i0_scaled_as(f64::from(y as f32)) - 1.0).abs());
        }
        eprintln!("A&S fits in f32 lanes: 9.8.1 ≤ {low:.2e}, 9.8.2 ≤ {high:.2e} relative");
        assert!(low < 5e-7 && high < 5e-7, "{low:e} {high:e}");
    }

    #[test]
    fn i0_as_is_within_its_bound() {
        // The bounds i0_as's and i0_scaled_as's documentation states, against the series
        // below 20 and the asymptotic expansion above, over every argument M meets.
        let (mut small, mut large): (f64, f64) = (0.0, 0.0);
        for k in 0..=3750 {
            let x = k as f64 * 1e-3;
            small = small.max((i0_as(x) / i0_series(x) - 1.0).abs());
        }
        for k in 0..=200_000 {
            let x = I0_AS_SPLIT * (1.0 + k as f64 * 1e-3).powi(3);
            let want = if x < I0_SERIES_MAX {
                i0_series(x) * (-x).exp()
            } else {
                i0_scaled_asymptotic(x)
            };
            large = large.max((i0_scaled_as(x) / want - 1.0).abs());
        }
        eprintln!("A&S 9.8.1 vs the series: {small:.2e}; 9.8.2 vs exact: {large:.2e}");
        assert!(small < 2e-7 && large < 6e-7, "{small:e} {large:e}");
        // And the split is continuous to the same order.
        let x = I0_AS_SPLIT;
        assert!((i0_as(x) * (-x).exp() / i0_scaled_as(x) - 1.0).abs() < 8e-7);
    }
}
