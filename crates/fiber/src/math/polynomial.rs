//! Polynomials by Horner's rule and Estrin's scheme, in one lane or in SIMD lanes of f64 and
//! f32, and the conversions between those lanes: what every fit in [`crate::math`] is evaluated
//! with.

use wide::{f32x4, f64x2, f64x4};

/// Σ cₖ xᵏ by Horner's rule from the highest coefficient (lowest first in `c`, at least one):
/// starting from the last coefficient rather than from 0 saves the multiply-add by zero that
/// the compiler may not drop (0 · x is not 0 for every x).
#[inline(always)]
pub(super) fn horner(c: &[f64], x: f64) -> f64 {
    let (last, rest) = c.split_last().expect("a coefficient");
    rest.iter().rev().fold(*last, |acc, c| acc * x + c)
}

/// Σ cₖ xᵏ (k < 9) by Estrin's scheme (Estrin 1960): pairs c₂ₖ + c₂ₖ₊₁x, then pairs of those
/// in x², then x⁴ and x⁸: a dependency chain of four multiply-adds where Horner's is eight,
/// for a few more multiplications. The scalar functions on every model's critical path
/// ([`sin_cos_quadrant`], [`asin_fast`], [`atan2_fast`], [`ln_fast`], [`exp_fast`]) take it,
/// or its twins [`estrin6`], [`estrin7`] and [`estrin12`] (`estrin_is_horners_polynomial`).
#[inline(always)]
pub(super) fn estrin9(c: &[f64; 9], x: f64) -> f64 {
    let pair = |i: usize| c[i] + c[i + 1] * x;
    let x2 = x * x;
    let x4 = x2 * x2;
    let low = pair(0) + pair(2) * x2;
    let high = pair(4) + pair(6) * x2;
    (low + high * x4) + c[8] * (x4 * x4)
}

/// [`estrin9`] for seven coefficients.
#[inline(always)]
pub(super) fn estrin7(c: &[f64; 7], x: f64) -> f64 {
    let pair = |i: usize| c[i] + c[i + 1] * x;
    let x2 = x * x;
    let low = pair(0) + pair(2) * x2;
    let high = pair(4) + c[6] * x2;
    low + high * (x2 * x2)
}

/// [`estrin9`] for six coefficients.
#[inline(always)]
pub(super) fn estrin6(c: &[f64; 6], x: f64) -> f64 {
    let pair = |i: usize| c[i] + c[i + 1] * x;
    let x2 = x * x;
    (pair(0) + pair(2) * x2) + pair(4) * (x2 * x2)
}

/// [`estrin9`] for twelve coefficients.
#[inline(always)]
pub(super) fn estrin12(c: &[f64; 12], x: f64) -> f64 {
    let pair = |i: usize| c[i] + c[i + 1] * x;
    let x2 = x * x;
    let x4 = x2 * x2;
    let q0 = pair(0) + pair(2) * x2;
    let q1 = pair(4) + pair(6) * x2;
    let q2 = pair(8) + pair(10) * x2;
    q0 + (q1 + q2 * x4) * x4
}

/// Two polynomials of [`estrin9`] at one x, one in each lane of a register: the same
/// operations in the same order (multiplies and adds, never fused), so each lane is bit for
/// bit its scalar twin (`sin_cos_quadrant_matches_the_library`), for about the cost of one.
#[inline(always)]
pub(super) fn estrin9_pair(a: &[f64; 9], b: &[f64; 9], x: f64) -> f64x2 {
    let c = |i: usize| f64x2::new([a[i], b[i]]);
    let x = f64x2::splat(x);
    let pair = |i: usize| c(i) + c(i + 1) * x;
    let x2 = x * x;
    let x4 = x2 * x2;
    let low = pair(0) + pair(2) * x2;
    let high = pair(4) + pair(6) * x2;
    (low + high * x4) + c(8) * (x4 * x4)
}

/// Coefficients rounded to single precision when the crate compiles: as constants, the lanes'
/// splats load them from memory where an array rounded at run time went through the stack.
pub(super) const fn to_f32<const N: usize>(c: [f64; N]) -> [f32; N] {
    let mut out = [0.0; N];
    let mut i = 0;
    while i < N {
        out[i] = c[i] as f32;
        i += 1;
    }
    out
}

/// Four doubles rounded to single precision.
#[inline(always)]
pub fn narrow(x: f64x4) -> f32x4 {
    f32x4::new(x.to_array().map(|v| v as f32))
}

/// Four singles widened to double precision (exactly).
#[inline(always)]
pub fn widen(x: f32x4) -> f64x4 {
    f64x4::new(x.to_array().map(f64::from))
}

/// A four-lane double mask (each lane all ones or all zeros) as a single-precision mask.
#[inline(always)]
pub fn narrow_mask(m: f64x4) -> f32x4 {
    f32x4::new(m.to_array().map(|v| f32::from_bits(v.to_bits() as u32)))
}

/// Double-precision lanes of either width, for the polynomials both take.
pub(super) trait F64Lanes: Copy + std::ops::Mul<Output = Self> {
    fn splat(x: f64) -> Self;
    fn mul_add(self, m: Self, a: Self) -> Self;
}

macro_rules! f64_lanes {
    ($($lanes:ty),*) => {$(
        impl F64Lanes for $lanes {
            #[inline(always)]
            fn splat(x: f64) -> Self {
                <$lanes>::splat(x)
            }
            #[inline(always)]
            fn mul_add(self, m: Self, a: Self) -> Self {
                <$lanes>::mul_add(self, m, a)
            }
        }
    )*};
}
f64_lanes!(f64x2, f64x4);

/// Σ cₖ xᵏ (k < 8) in each of two or four lanes, lowest coefficient first, by Estrin's scheme
/// (Estrin 1960): pairs c₂ₖ + c₂ₖ₊₁x, then pairs of those in x², then in x⁴, three levels
/// where Horner's chain is seven multiply-adds long (the lanes' latency, not their count,
/// bounds the models' M). [`estrin8_lanes_f32`] is the same in single precision, and
/// [`estrin7_lanes_f32`] and [`estrin9_lanes_f32`] take one coefficient fewer and one more, so
/// no multiply-add by a zero coefficient is spent.
#[inline(always)]
pub(super) fn estrin8_lanes<L: F64Lanes>(c: &[f64; 8], x: L) -> L {
    let pair = |i: usize| L::splat(c[i + 1]).mul_add(x, L::splat(c[i]));
    let x2 = x * x;
    let low = pair(2).mul_add(x2, pair(0));
    let high = pair(6).mul_add(x2, pair(4));
    high.mul_add(x2 * x2, low)
}

/// [`estrin8_lanes`] in single precision.
#[inline(always)]
pub(super) fn estrin8_lanes_f32(c: &[f32; 8], x: f32x4) -> f32x4 {
    let pair = |i: usize| f32x4::splat(c[i + 1]).mul_add(x, f32x4::splat(c[i]));
    let x2 = x * x;
    let low = pair(2).mul_add(x2, pair(0));
    let high = pair(6).mul_add(x2, pair(4));
    high.mul_add(x2 * x2, low)
}

/// [`estrin8_lanes_f32`] for seven coefficients.
#[inline(always)]
pub(super) fn estrin7_lanes_f32(c: &[f32; 7], x: f32x4) -> f32x4 {
    let pair = |i: usize| f32x4::splat(c[i + 1]).mul_add(x, f32x4::splat(c[i]));
    let x2 = x * x;
    let low = pair(2).mul_add(x2, pair(0));
    let high = f32x4::splat(c[6]).mul_add(x2, pair(4));
    high.mul_add(x2 * x2, low)
}

/// [`estrin8_lanes_f32`] for nine coefficients.
#[inline(always)]
pub(super) fn estrin9_lanes_f32(c: &[f32; 9], x: f32x4) -> f32x4 {
    let pair = |i: usize| f32x4::splat(c[i + 1]).mul_add(x, f32x4::splat(c[i]));
    let x2 = x * x;
    let x4 = x2 * x2;
    let low = pair(2).mul_add(x2, pair(0));
    let high = pair(6).mul_add(x2, pair(4));
    f32x4::splat(c[8]).mul_add(x4 * x4, high.mul_add(x4, low))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Estrin's scheme for scalars against Horner's rule, for the four lengths it takes.
    #[test]
    fn estrin_is_horners_polynomial() {
        let c: [f64; 12] = std::array::from_fn(|k| (-0.7f64).powi(k as i32) / (1.0 + k as f64));
        for j in 0..=200 {
            let x = -1.3 + 2.6 * j as f64 / 200.0;
            let got = [
                (6, estrin6(c[..6].try_into().unwrap(), x)),
                (7, estrin7(c[..7].try_into().unwrap(), x)),
                (9, estrin9(c[..9].try_into().unwrap(), x)),
                (12, estrin12(&c, x)),
            ];
            for (n, g) in got {
                let want = horner(&c[..n], x);
                assert!(
                    (g - want).abs() <= 1e-14 * want.abs().max(1.0),
                    "{n} terms, x {x}: {g} vs {want}"
                );
            }
        }
    }

    /// Estrin's scheme in lanes against Horner's rule in each lane, for the four forms the
    /// lanes take: the same polynomial to rounding (single precision's, for the f32 lanes).
    #[test]
    fn estrin_lanes_is_horners_polynomial() {
        let c: [f64; 9] = std::array::from_fn(|k| (-0.7f64).powi(k as i32) / (1.0 + k as f64));
        let c32 = c.map(|c| c as f32);
        let (c7, c8) = (c32[..7].try_into().unwrap(), c32[..8].try_into().unwrap());
        for j in 0..50 {
            let x: [f64; 4] = std::array::from_fn(|l| -1.3 + 2.6 * (4 * j + l) as f64 / 199.0);
            let x32 = f32x4::new(x.map(|x| x as f32));
            let double = estrin8_lanes(c[..8].try_into().unwrap(), f64x4::new(x)).to_array();
            let single = [
                (7, estrin7_lanes_f32(&c7, x32)),
                (8, estrin8_lanes_f32(&c8, x32)),
                (9, estrin9_lanes_f32(&c32, x32)),
            ];
            for (k, x) in x.into_iter().enumerate() {
                let want = horner(&c[..8], x);
                assert!(
                    (double[k] - want).abs() <= 1e-14 * want.abs().max(1.0),
                    "x {x}"
                );
                for (n, g) in single {
                    // The argument and coefficients round to single precision, too.
                    let want = horner(
                        &c32[..n].iter().map(|&c| f64::from(c)).collect::<Vec<_>>(),
                        f64::from(x as f32),
                    );
                    let g = f64::from(g.to_array()[k]);
                    assert!(
                        (g - want).abs() <= 1e-6 * want.abs().max(1.0),
                        "{n} terms, x {x}: {g} vs {want}"
                    );
                }
            }
        }
    }
}
