//! The natural logarithm for the Beckmann sampler, shorter than the libm call: x = 2^e · m with
//! m ∈ (√½, √2], ln m = 2 atanh(s) = 2s Σ s^(2k)/(2k+1) with s = (m − 1)/(m + 1), |s| ≤ 0.172
//! (Abramowitz & Stegun 4.1.27), summed to s²¹ (truncation below 10⁻¹⁸).

use crate::poly::horner;
use std::f64::consts::{LN_2, SQRT_2};

/// 1/(2k + 1) for k = 0…10: the series of atanh(s)/s in s².
const ATANH_SERIES: [f64; 11] = [
    1.0,
    1.0 / 3.0,
    1.0 / 5.0,
    1.0 / 7.0,
    1.0 / 9.0,
    1.0 / 11.0,
    1.0 / 13.0,
    1.0 / 15.0,
    1.0 / 17.0,
    1.0 / 19.0,
    1.0 / 21.0,
];

/// ln x for normal x > 0.
#[inline]
pub fn ln(x: f64) -> f64 {
    let bits = x.to_bits();
    let mut e = ((bits >> 52) & 0x7ff) as i64 - 1023;
    let mut m = f64::from_bits((bits & ((1u64 << 52) - 1)) | (1023u64 << 52));
    if m > SQRT_2 {
        m *= 0.5;
        e += 1;
    }
    let s = (m - 1.0) / (m + 1.0);
    let z = s * s;
    let series = horner(z, &ATANH_SERIES);
    e as f64 * LN_2 + 2.0 * s * series
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_the_library_logarithm() {
        let mut x = 2f64.powi(-33);
        while x <= 1.0 {
            let (got, want) = (ln(x), x.ln());
            assert!(
                (got - want).abs() <= 4e-16 * want.abs().max(1.0),
                "ln({x}) = {got}, want {want}"
            );
            x *= 1.000_37;
        }
        for x in [1.0, 0.5, SQRT_2 / 2.0, 1.0 - 2f64.powi(-32), 3.0, 1e10] {
            assert!(
                (ln(x) - x.ln()).abs() <= 4e-16 * x.ln().abs().max(1.0),
                "ln({x})"
            );
        }
    }
}
