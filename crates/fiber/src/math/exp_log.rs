//! eˣ and ln x without a library call, in one lane and in SIMD lanes (with a single-precision
//! polynomial where a fit is no better than that), and ln(1 − e⁻ˣ).

use super::polynomial::{estrin6, estrin7, estrin8_lanes, estrin8_lanes_f32, narrow, widen};
use bytemuck::cast;
use wide::{CmpLt, f32x4, f64x2, f64x4, u64x2, u64x4};

/// (atanh √t − √t) / (t √t) on t ∈ [0, ((√2 − 1)/(√2 + 1))²] as a polynomial of degree 6: a
/// near-minimax Chebyshev fit (fit error 1.6e-16 on a term that ln m = 2f + 2f t g(t) scales
/// by t ≤ 0.03; `crates/fiber/tools/chebyfit.py`).
#[allow(clippy::excessive_precision)]
pub(super) const LN_FIT: [f64; 7] = [
    0.3333333333333335,
    0.19999999999949752,
    0.14285714312987743,
    0.1111110556739754,
    0.09091444562630861,
    0.07665860800278021,
    0.07308224842521703,
];

/// ln x: x = 2ᵏ m with m ∈ [√½, √2) from the bits, ln m = 2 atanh f with f = (m − 1)/(m + 1),
/// |f| ≤ 0.172, as 2f + 2f t g(t), t = f², g the fit [`LN_FIT`], and k ln 2 added in two parts
/// (Cody & Waite 1980). Zero, negative, subnormal, infinite and NaN arguments go to `f64::ln`.
/// No call, about a third of the C library's instructions; within 2.5e-16 absolute or relative
/// (the larger) of `f64::ln`, and 5e-16 relative near 1 (`ln_fast_is_within_its_bound`).
#[inline]
pub fn ln_fast(x: f64) -> f64 {
    const LN2_HI: f64 = f64::from_bits(0x3fe6_2e42_fee0_0000);
    const LN2_LO: f64 = f64::from_bits(0x3dea_39ef_3579_3c76);
    if !(f64::MIN_POSITIVE..f64::INFINITY).contains(&x) {
        return x.ln();
    }
    let LnReduced { k, m } = ln_reduce(x);
    let f = (m - 1.0) / (m + 1.0);
    let t = f * f;
    k * LN2_HI + (2.0 * f + (2.0 * f * t * estrin7(&LN_FIT, t) + k * LN2_LO))
}

/// A positive normal x as 2ᵏ m, m ∈ (√½, √2]: [`ln_fast`]'s range reduction.
pub(super) struct LnReduced {
    k: f64,
    m: f64,
}

/// Splits a positive normal x into [`LnReduced`] without a branch: adding 2⁵² − M₊ to the bits,
/// M₊ the mantissa field just above √2's, carries into the exponent exactly where the mantissa
/// 1.M exceeds √2, and adding 0x3fe·2⁵² + M₊ to the low bits then gives back 1.M, or 1.M / 2 where
/// it carried. The same k and m as halving m > √2 by a test, which a random x mispredicts
/// half the time (the simulator's Beckmann sampler takes ln of a uniform variate).
#[inline(always)]
pub(super) fn ln_reduce(x: f64) -> LnReduced {
    const MANTISSA: u64 = 0x000f_ffff_ffff_ffff;
    const ABOVE_SQRT_2: u64 = (std::f64::consts::SQRT_2.to_bits() & MANTISSA) + 1;
    let bits = x.to_bits() + (MANTISSA + 1 - ABOVE_SQRT_2);
    LnReduced {
        k: (((bits >> 52) as i64) - 1023) as f64,
        m: f64::from_bits((bits & MANTISSA) + ((0x3fe << 52) | ABOVE_SQRT_2)),
    }
}

/// 2^(j/32), j = 0…31, correctly rounded (50-digit decimal arithmetic): [`exp_fast`]'s table.
#[allow(clippy::excessive_precision)]
pub(super) const EXP2_32THS: [f64; 32] = [
    1.0,
    1.0218971486541166,
    1.0442737824274138,
    1.0671404006768237,
    1.0905077326652577,
    1.1143867425958924,
    1.1387886347566916,
    1.1637248587775775,
    1.189207115002721,
    1.215247359980469,
    1.241857812073484,
    1.2690509571917332,
    1.2968395546510096,
    1.3252366431597413,
    1.3542555469368927,
    1.383909881963832,
    std::f64::consts::SQRT_2,
    1.4451808069770467,
    1.4768261459394993,
    1.5091644275934228,
    1.5422108254079407,
    1.5759808451078865,
    1.6104903319492543,
    1.645755478153965,
    1.681792830507429,
    1.718619298122478,
    1.7562521603732995,
    1.7947090750031072,
    1.8340080864093424,
    1.8741676341103,
    1.9152065613971474,
    1.9571441241754002,
];

/// eˣ to 1e-14 relative (`exp_fast_is_within_its_bound`): x = (32m + j) ln 2 / 32 + r with
/// |r| ≤ ln 2 / 64 (ln 2 split in two so the product is exact, Cody & Waite 1980), e^r by its
/// Taylor series to r⁵ (the first term dropped, r⁶/6!, is 2.2e-15), 2^(j/32) from a table and
/// 2ᵐ put in the exponent bits: no call, about half the instructions of the C library's
/// `exp`. Outside (−708, 709), where the result leaves the normal range, and for NaN it
/// defers to `f64::exp`.
#[inline]
pub fn exp_fast(x: f64) -> f64 {
    if !(x > -708.0 && x < 709.0) {
        return x.exp();
    }
    // Adding 1.5·2⁵² rounds to the nearest integer, which then sits in the low mantissa bits.
    const ROUND: f64 = 6_755_399_441_055_744.0;
    // fdlibm's split of ln 2: the high part has 32 significant bits, so k · it is exact.
    const LN2_HI_32: f64 = f64::from_bits(0x3fe6_2e42_fee0_0000) / 32.0;
    const LN2_LO_32: f64 = f64::from_bits(0x3dea_39ef_3579_3c76) / 32.0;
    let shifted = x * (32.0 * std::f64::consts::LOG2_E) + ROUND;
    let n = shifted.to_bits() as u32 as i32;
    let k = shifted - ROUND;
    let r = (x - k * LN2_HI_32) - k * LN2_LO_32;
    const TAYLOR: [f64; 6] = [1.0, 1.0, 0.5, 1.0 / 6.0, 1.0 / 24.0, 1.0 / 120.0];
    let p = estrin6(&TAYLOR, r);
    let m = (n >> 5) as i64;
    // 2^(j/32) · 2ᵐ (exact) beside the polynomial, so the result waits for one product.
    p * (EXP2_32THS[(n & 31) as usize] * f64::from_bits(((m + 1023) as u64) << 52))
}

/// The body of [`exp_lanes`] and [`exp_pair`] for one lane type: [`exp_fast`]'s reduction
/// without its table, x = n ln 2 + r with |r| ≤ ln 2 / 2 (Cody & Waite 1980's split of ln 2)
/// and e^r by its Taylor series to r⁷ in Estrin's order (the remainder, at most (r⁸/8!) e^{|r|},
/// is 7.4e-9 relative), 2ⁿ put in the exponent bits; SIMD registers throughout, no table and
/// no branch. Below −708, where eˣ leaves the normal range, it gives 0; above 709 it gives
/// e⁷⁰⁹; NaN stays NaN. One body, so that every lane of either width does the same arithmetic.
macro_rules! exp_in_lanes {
    ($x:expr, $float:ty, $bits:ty) => {{
        let x: $float = $x;
        // Adding 1.5·2⁵² rounds to the nearest integer, which then sits in the low mantissa bits.
        const ROUND: f64 = 6_755_399_441_055_744.0;
        const LN2_HI: f64 = f64::from_bits(0x3fe6_2e42_fee0_0000);
        const LN2_LO: f64 = f64::from_bits(0x3dea_39ef_3579_3c76);
        const TAYLOR: [f64; 8] = {
            let mut c = [1.0; 8];
            let mut k = 1;
            while k < 8 {
                c[k] = c[k - 1] / k as f64;
                k += 1;
            }
            c
        };
        let splat = <$float>::splat;
        let low = x.cmp_lt(splat(-708.0));
        let xc = x.fast_max(splat(-708.0)).fast_min(splat(709.0));
        let shifted = xc.mul_add(splat(std::f64::consts::LOG2_E), splat(ROUND));
        let n = shifted - splat(ROUND);
        let r = n.mul_neg_add(splat(LN2_HI), xc);
        let r = n.mul_neg_add(splat(LN2_LO), r);
        let p = estrin8_lanes(&TAYLOR, r);
        let bits: $bits = cast(shifted);
        let exponent = (bits - <$bits>::splat(ROUND.to_bits() - 1023)) << 52;
        let e = low.blend(<$float>::ZERO, p * cast::<$bits, $float>(exponent));
        x.is_nan().blend(x, e)
    }};
}

/// eˣ in each of four lanes, to 8e-9 relative: what the models' M needs, whose I0 by
/// Abramowitz & Stegun is good to 6e-7 (`exp_lanes_is_within_its_bound` measures its error
/// against `f64::exp`). The arithmetic is [`exp_in_lanes`]'s.
#[inline(always)]
pub fn exp_lanes(x: f64x4) -> f64x4 {
    exp_in_lanes!(x, f64x4, u64x4)
}

/// [`exp_lanes`] in two lanes, for a caller with two exponentials: the same bits lane by lane
/// (`exp_pair_is_exp_lanes`) at half the instructions where the target's registers hold two.
#[inline(always)]
pub fn exp_pair(x: f64x2) -> f64x2 {
    exp_in_lanes!(x, f64x2, u64x2)
}

/// eˣ split for a polynomial in single precision: x = n ln 2 + r with |r| ≤ ln 2 / 2 reduced in
/// double precision (as [`exp_lanes`]), so that eˣ = `scale` · e^r with `scale` = 2ⁿ exact and
/// only e^r — a number in [0.7, 1.42] — left to [`exp_reduced_f32`]. The relative error then does
/// not grow with |x|. `scale` is 0 below −708 and NaN stays NaN (through r); x must be at most 709.
#[inline(always)]
pub fn exp_split(x: f64x4) -> ExpSplit {
    const ROUND: f64 = 6_755_399_441_055_744.0;
    const LN2_HI: f64 = f64::from_bits(0x3fe6_2e42_fee0_0000);
    const LN2_LO: f64 = f64::from_bits(0x3dea_39ef_3579_3c76);
    // The clamp's first operand is the bound, so a NaN x passes through it.
    let xc = f64x4::splat(-708.0).fast_max(x);
    let shifted = xc.mul_add(f64x4::splat(std::f64::consts::LOG2_E), f64x4::splat(ROUND));
    let n = shifted - f64x4::splat(ROUND);
    let r = n.mul_neg_add(f64x4::splat(LN2_HI), xc);
    let r = n.mul_neg_add(f64x4::splat(LN2_LO), r);
    let bits: u64x4 = cast(shifted);
    let two_n: f64x4 = cast((bits - u64x4::splat(ROUND.to_bits() - 1023)) << 52);
    ExpSplit {
        scale: x.cmp_lt(f64x4::splat(-708.0)).blend(f64x4::ZERO, two_n),
        r: narrow(r),
    }
}

/// eˣ in each of four lanes for x ≤ 709, the reference [`exp_lanes`]'s reduction in double
/// precision and its polynomial in single: [`exp_split`] then [`exp_reduced_f32`], within 3e-7
/// relative (`exp_lanes_f32_is_within_its_bound`); e⁰ is exactly 1.
#[inline(always)]
pub fn exp_lanes_f32(x: f64x4) -> f64x4 {
    let ExpSplit { scale, r } = exp_split(x);
    widen(exp_reduced_f32(r)) * scale
}

/// The two factors of [`exp_split`].
#[derive(Clone, Copy, Debug)]
pub struct ExpSplit {
    /// 2ⁿ, or 0 where eˣ leaves the normal range.
    pub scale: f64x4,
    /// x − n ln 2, in single precision.
    pub r: f32x4,
}

/// e^r for |r| ≤ ln 2 / 2 in single precision: Taylor's series to r⁷ (remainder at most
/// (r⁸/8!) e^{|r|} = 7.4e-9 relative, below single precision's rounding).
#[inline(always)]
pub fn exp_reduced_f32(r: f32x4) -> f32x4 {
    const TAYLOR: [f32; 8] = [
        1.0,
        1.0,
        1.0 / 2.0,
        1.0 / 6.0,
        1.0 / 24.0,
        1.0 / 120.0,
        1.0 / 720.0,
        1.0 / 5040.0,
    ];
    estrin8_lanes_f32(&TAYLOR, r)
}

/// ln(1 − e^{−x}) for x > 0 without cancellation; where e^{−x} < 1e-8 (x > 18.4, every
/// lobe narrower than v ≈ 0.1) the series −e − e²/2 with e = [`exp_fast`](−x), whose first
/// term dropped, e³/3, is below 4e-25 (`log1m_exp_neg_matches_the_library`).
pub fn log1m_exp_neg(x: f64) -> f64 {
    if x < std::f64::consts::LN_2 {
        return (-(-x).exp_m1()).ln();
    }
    let e = exp_fast(-x);
    if e < 1e-8 {
        -e - 0.5 * e * e
    } else {
        (-e).ln_1p()
    }
}

#[cfg(test)]
mod tests {
    use super::super::normal::{normal_pdf, normal_pdf_fast};
    use super::*;

    #[test]
    fn log1m_exp_neg_matches_the_library() {
        let mut worst: f64 = 0.0;
        for k in 1..=4000 {
            let x = 0.01 * k as f64;
            let exact = (-(-x).exp()).ln_1p();
            worst = worst.max(((log1m_exp_neg(x) - exact) / exact).abs());
        }
        eprintln!("log1m_exp_neg within {worst:.1e} relative of ln_1p(−e^−x)");
        assert!(worst < 2e-14, "{worst}");
    }

    /// The worst relative error of an eˣ in lanes against `f64::exp` on [−708, 709], and that
    /// it keeps the edges: 0 below the normal range, NaN as NaN, e⁰ exactly 1.
    fn exp_in_lanes_error(name: &str, exp: fn(f64x4) -> f64x4) -> f64 {
        let mut worst: f64 = 0.0;
        for k in (-1_416_000..1_417_996).step_by(4) {
            let x = std::array::from_fn(|j| (k + j as i64) as f64 * 5.0e-4 + 1.3e-7);
            for (got, x) in exp(f64x4::new(x)).to_array().into_iter().zip(x) {
                worst = worst.max((got / x.exp() - 1.0).abs());
            }
        }
        eprintln!("{name} vs f64::exp on [−708, 709]: relative error ≤ {worst:.2e}");
        let edges = exp(f64x4::new([-708.5, f64::NEG_INFINITY, f64::NAN, 0.0])).to_array();
        assert_eq!(edges[..2], [0.0, 0.0], "{name}");
        assert!(edges[2].is_nan(), "{name}: {edges:?}");
        assert_eq!(edges[3], 1.0, "{name}");
        worst
    }

    #[test]
    fn exp_lanes_is_within_its_bound() {
        let worst = exp_in_lanes_error("exp_lanes", exp_lanes);
        assert!(worst < 8e-9, "{worst:e}");
    }

    #[test]
    fn exp_pair_is_exp_lanes() {
        // Lane by lane the same bits, over the range and at its edges.
        let edges = [
            -708.5,
            f64::NEG_INFINITY,
            f64::NAN,
            0.0,
            709.5,
            -1e-300,
            1.0,
            -0.3,
        ];
        let grid = (-141_600..=141_800).map(|k| k as f64 * 5.0e-3 + 1.3e-7);
        let xs: Vec<f64> = grid.chain(edges).collect();
        for x in xs.chunks_exact(4) {
            let four = exp_lanes(f64x4::new(x.try_into().unwrap())).to_array();
            let two = [0, 2].map(|j| exp_pair(f64x2::new([x[j], x[j + 1]])).to_array());
            let two = [two[0][0], two[0][1], two[1][0], two[1][1]];
            assert_eq!(four.map(f64::to_bits), two.map(f64::to_bits), "{x:?}");
        }
    }

    #[test]
    fn exp_lanes_f32_is_within_its_bound() {
        let worst = exp_in_lanes_error("exp_lanes_f32", exp_lanes_f32);
        assert!(worst < 3e-7, "{worst:e}");
    }

    #[test]
    fn ln_fast_is_within_its_bound() {
        let mut worst: f64 = 0.0;
        let mut check = |x: f64| {
            let (got, want) = (ln_fast(x), x.ln());
            worst = worst.max((got - want).abs() / want.abs().max(1.0));
        };
        // Every binade's mantissa finely, around 1 very finely, and the ends of the range.
        for k in 0..=400_000 {
            let m = 1.0 + k as f64 / 400_000.0;
            for e in [-1022, -300, -2, -1, 0, 1, 7, 300, 1023] {
                check(m * 2f64.powi(e));
            }
            check(1.0 + (k as f64 - 200_000.0) * 1e-9);
        }
        check(f64::MIN_POSITIVE);
        check(f64::MAX);
        eprintln!("ln_fast vs f64::ln: ≤ {worst:.2e} absolute or relative");
        assert!(worst < 2.5e-16, "{worst:e}");
        // Near 1, where ln x is small, relative to it.
        let mut near_one: f64 = 0.0;
        for k in 1..=100_000 {
            for x in [
                1.0 + k as f64 * 3e-9,
                1.0 - k as f64 * 3e-9,
                1.0 + k as f64 * 4e-6,
            ] {
                near_one = near_one.max((ln_fast(x) / x.ln() - 1.0).abs());
            }
        }
        eprintln!("ln_fast near 1: ≤ {near_one:.2e} relative");
        assert!(near_one < 5e-16, "{near_one:e}");
        for x in [0.0, -1.0, 1e-310, f64::INFINITY] {
            assert_eq!(ln_fast(x).to_bits(), x.ln().to_bits(), "{x}");
        }
        assert!(ln_fast(f64::NAN).is_nan());
    }

    /// The branch-free reduction splits at √2 as the test it replaces did, and is exact.
    #[test]
    fn ln_reduce_splits_exactly_above_sqrt_2() {
        let sqrt2 = std::f64::consts::SQRT_2;
        let at = |x: f64| {
            let r = ln_reduce(x);
            (r.k, r.m)
        };
        assert_eq!(at(sqrt2), (0.0, sqrt2));
        assert_eq!(at(sqrt2.next_up()), (1.0, sqrt2.next_up() / 2.0));
        assert_eq!(at(1.0), (0.0, 1.0));
        assert_eq!(at(2.0f64.next_down()), (1.0, 2.0f64.next_down() / 2.0));
        let mut s = 0x2545_f491_4f6c_dd1du64;
        for _ in 0..100_000 {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            // Exponent fields 3..=2044 (2ᵏ stays normal), any mantissa.
            let x = f64::from_bits(((3 + s % 2042) << 52) | (s >> 12));
            let (k, m) = at(x);
            assert!(m > sqrt2 / 2.0 && m <= sqrt2, "{x:e}: m {m}");
            assert_eq!(m * 2f64.powi(k as i32), x, "{x:e}");
        }
    }

    #[test]
    fn exp_fast_is_within_its_bound() {
        let mut worst: f64 = 0.0;
        for k in -1_400_000..=1_400_000 {
            let x = k as f64 * 5.0e-4 + 1.3e-7;
            worst = worst.max((exp_fast(x) / x.exp() - 1.0).abs());
        }
        for x in [-707.9, -1e-300, 0.0, 1e-300, 708.9] {
            worst = worst.max((exp_fast(x) / x.exp() - 1.0).abs());
        }
        eprintln!("exp_fast vs f64::exp on [−700, 700]: relative error ≤ {worst:.2e}");
        for k in 0..=3700 {
            let x = k as f64 * 1e-2;
            let want = normal_pdf(x);
            worst = worst.max((normal_pdf_fast(x) / want - 1.0).abs());
        }
        assert!(worst < 1e-14, "{worst:e}");
        assert_eq!(exp_fast(-800.0), 0.0);
        assert_eq!(exp_fast(800.0), f64::INFINITY);
        assert_eq!(exp_fast(f64::NEG_INFINITY), 0.0);
        assert!(exp_fast(f64::NAN).is_nan());
    }

    #[test]
    fn log1m_exp_neg_is_accurate_at_both_ends() {
        assert!((log1m_exp_neg(1e-10) - (1e-10f64).ln()).abs() < 1e-9);
        assert!((log1m_exp_neg(50.0) + (-50.0f64).exp()).abs() < 1e-30);
    }
}
