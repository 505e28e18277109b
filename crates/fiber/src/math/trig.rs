//! sin, cos, asin and atan2 without a library call: near-minimax polynomial fits on a reduced
//! range, each tested against the library's function (`asin_pair` takes two angles at once).

use super::polynomial::{estrin9, estrin9_pair, estrin12};
use std::f64::consts::PI;
use wide::{CmpLe, f64x2};

/// sin x / x and cos x as polynomials of degree 8 in t = x² on [0, (π/2)²]: near-minimax
/// Chebyshev fits (fit error 2e-19 and 4e-18; `crates/fiber/tools/chebyfit.py` makes them),
/// nine terms each where the Taylor series needs eleven and twelve.
#[allow(clippy::excessive_precision)]
pub(super) const SIN_FIT: [f64; 9] = [
    1.0,
    -0.16666666666666666,
    0.008333333333333186,
    -0.00019841269841208676,
    2.7557319211229606e-06,
    -2.505210689056952e-08,
    1.605894087848656e-10,
    -7.643026557971632e-13,
    2.7215749422983443e-15,
];
#[allow(clippy::excessive_precision)]
pub(super) const COS_FIT: [f64; 9] = [
    1.0,
    -0.4999999999999997,
    0.04166666666666388,
    -0.001388888888877299,
    2.4801587277414926e-05,
    -2.755731639102575e-07,
    2.0876561839933163e-09,
    -1.1462901901757276e-11,
    4.608977003001797e-14,
];

/// (sin x, cos x) for |x| ≤ π/2 — every inclination θ and every half-azimuth φ/2 — by the
/// polynomials [`SIN_FIT`] and [`COS_FIT`] in x², without the range reduction a general sine
/// needs; other x go to `f64::sin_cos`. Within 4e-16 of `f64::sin_cos`
/// (`sin_cos_quadrant_matches_the_library`).
#[inline]
pub fn sin_cos_quadrant(x: f64) -> (f64, f64) {
    if x.abs() > std::f64::consts::FRAC_PI_2 || x.is_nan() {
        return x.sin_cos();
    }
    let [sin_over_x, cos] = estrin9_pair(&SIN_FIT, &COS_FIT, x * x).to_array();
    (x * sin_over_x, cos)
}

/// cos x alone for |x| ≤ π/2, the cosine of [`sin_cos_quadrant`] (same polynomial, same bound).
#[inline]
pub fn cos_quadrant(x: f64) -> f64 {
    if x.abs() > std::f64::consts::FRAC_PI_2 || x.is_nan() {
        return x.cos();
    }
    estrin9(&COS_FIT, x * x)
}

/// (asin √t − √t) / (t √t) on t ∈ [0, ¼] as a polynomial of degree 11: a near-minimax
/// Chebyshev fit (fit error 2.3e-16 on a term that asin x = x + x t g(t) scales by t ≤ ¼;
/// `crates/fiber/tools/chebyfit.py`).
#[allow(clippy::excessive_precision)]
pub(super) const ASIN_FIT: [f64; 12] = [
    0.1666666666666665,
    0.07500000000020764,
    0.044642857103423646,
    0.03038194736709848,
    0.02237204763174451,
    0.017355259955786323,
    0.013929652902326633,
    0.011875494382636922,
    0.0078029494773533175,
    0.01603551434914882,
    -0.010749050339697808,
    0.028169218060881414,
];

/// π/2 − `FRAC_PI_2`, the part of π/2 a double leaves out.
pub(super) const FRAC_PI_2_LO: f64 = 6.123_233_995_736_766e-17;

/// asin x for |x| ≤ 1: x + x t g(t) with t = x² and g the fit [`ASIN_FIT`] for |x| ≤ ½, and
/// π/2 − 2 asin √((1 − |x|)/2) above (the half-angle identity, 1 − |x| exact there); NaN and
/// |x| > 1 go to `f64::asin`. No call, a third of the C library's instructions; within 4e-16
/// absolute and 7e-16 relative of `f64::asin` (`asin_fast_is_within_its_bound`; about three
/// ulp where the library has one half: √ and the subtraction from π/2 round uncompensated).
#[inline]
pub fn asin_fast(x: f64) -> f64 {
    let a = x.abs();
    if a > 1.0 || a.is_nan() {
        return x.asin();
    }
    let g = |t: f64| estrin12(&ASIN_FIT, t);
    let r = if a <= 0.5 {
        let t = a * a;
        a + a * t * g(t)
    } else {
        let t = 0.5 * (1.0 - a);
        let z = t.sqrt();
        std::f64::consts::FRAC_PI_2 - (2.0 * (z + z * t * g(t)) - FRAC_PI_2_LO)
    };
    r.copysign(x)
}

/// [`asin_fast`] of two numbers in |x| ≤ 1 at once, in the two lanes of one register: both
/// halves of the identity share the polynomial, so the pair costs about one scalar call. Same
/// bound as [`asin_fast`] (`asin_pair_is_asin_fast`); NaN stays NaN.
#[inline(always)]
pub fn asin_pair(x: f64x2) -> f64x2 {
    let a = x.abs();
    let small = a.cmp_le(f64x2::splat(0.5));
    let t_big = f64x2::splat(0.5) * (f64x2::ONE - a);
    let t = small.blend(a * a, t_big);
    let z = small.blend(a, t_big.sqrt());
    let c = |k: usize| f64x2::splat(ASIN_FIT[k]);
    let pair = |i: usize| c(i + 1).mul_add(t, c(i));
    let t2 = t * t;
    let t4 = t2 * t2;
    let q0 = pair(2).mul_add(t2, pair(0));
    let q1 = pair(6).mul_add(t2, pair(4));
    let q2 = pair(10).mul_add(t2, pair(8));
    let g = q2.mul_add(t4, q1).mul_add(t4, q0);
    let r = (z * t).mul_add(g, z);
    let big = f64x2::splat(std::f64::consts::FRAC_PI_2)
        - r.mul_add(f64x2::splat(2.0), f64x2::splat(-FRAC_PI_2_LO));
    small.blend(r, big).copysign(x)
}

/// (atan √t − √t) / (t √t) on t ∈ [0, tan²(π/12)] as a polynomial of degree 8: a near-minimax
/// Chebyshev fit (fit error 1.4e-17 on a term that atan x = x + x t g(t) scales by t ≤ 0.072;
/// `crates/fiber/tools/chebyfit.py`).
#[allow(clippy::excessive_precision)]
pub(super) const ATAN_FIT: [f64; 9] = [
    -0.3333333333333333,
    0.1999999999999688,
    -0.14285714284553813,
    0.11111110944516939,
    -0.09090897081592211,
    0.07691819638198708,
    -0.06654945053677658,
    0.05716329894442852,
    -0.03957893591546196,
];

/// atan2(y, x): the angle of the smaller component over the larger, r ∈ [0, 1], brought into
/// [0, tan(π/12)] by atan r = π/6 + atan((r√3 − 1)/(r + √3)) where it is larger, then
/// r + r t g(t) with t = r² and g the fit [`ATAN_FIT`], and the octant restored (π/2 and π
/// subtracted with their low parts). Zeros, infinities and NaN go to `f64::atan2`. No call,
/// under half the C library's instructions; within 5e-16 absolute of `f64::atan2`
/// (`atan2_fast_is_within_its_bound`).
#[inline]
pub fn atan2_fast(y: f64, x: f64) -> f64 {
    const SQRT_3: f64 = 1.732_050_807_568_877_2;
    const TAN_PI_12: f64 = 0.267_949_192_431_122_7;
    const PI_LO: f64 = 2.0 * FRAC_PI_2_LO;
    let (ay, ax) = (y.abs(), x.abs());
    let (small, large) = if ay > ax { (ax, ay) } else { (ay, ax) };
    if !(small > 0.0 && large < f64::INFINITY) {
        return y.atan2(x);
    }
    let r = small / large;
    let (r, base) = if r > TAN_PI_12 {
        (
            (r * SQRT_3 - 1.0) / (r + SQRT_3),
            std::f64::consts::FRAC_PI_6,
        )
    } else {
        (r, 0.0)
    };
    let t = r * r;
    let a = base + (r + r * t * estrin9(&ATAN_FIT, t));
    let a = if ay > ax {
        std::f64::consts::FRAC_PI_2 - (a - FRAC_PI_2_LO)
    } else {
        a
    };
    let a = if x < 0.0 { PI - (a - PI_LO) } else { a };
    a.copysign(y)
}

#[cfg(test)]
mod tests {
    use super::super::polynomial::estrin9;
    use super::*;

    #[test]
    fn sin_cos_quadrant_matches_the_library() {
        let mut worst: f64 = 0.0;
        let half = std::f64::consts::FRAC_PI_2;
        for k in -100_000..=100_000 {
            let x = half * k as f64 / 100_000.0;
            let (s, c) = sin_cos_quadrant(x);
            assert_eq!(c, cos_quadrant(x));
            assert_eq!(s, x * estrin9(&SIN_FIT, x * x));
            let (ws, wc) = x.sin_cos();
            worst = worst.max((s - ws).abs()).max((c - wc).abs());
        }
        eprintln!("sin_cos_quadrant vs f64::sin_cos on [−π/2, π/2]: ≤ {worst:.2e}");
        assert!(worst < 4e-16, "{worst:e}");
        assert_eq!(sin_cos_quadrant(2.0), 2f64.sin_cos());
        assert!(sin_cos_quadrant(f64::NAN).0.is_nan());
    }

    #[test]
    fn asin_fast_is_within_its_bound() {
        // A dense grid of [−1, 1], both sides of the switch at ½, the ends and tiny arguments.
        let (mut abs, mut rel): (f64, f64) = (0.0, 0.0);
        let edges = [
            0.5,
            0.5 + 1e-16,
            0.5 - 1e-16,
            1.0,
            1.0 - 1e-16,
            1e-300,
            1e-8,
            0.0,
        ];
        for x in (-200_000..=200_000)
            .map(|k| k as f64 / 200_000.0)
            .chain(edges)
            .chain(edges.map(|x| -x))
        {
            let (got, want) = (asin_fast(x), x.asin());
            abs = abs.max((got - want).abs());
            if want != 0.0 {
                rel = rel.max(((got - want) / want).abs());
            }
            assert_eq!(got.is_sign_negative(), want.is_sign_negative(), "{x}");
        }
        eprintln!("asin_fast vs f64::asin on [−1, 1]: ≤ {abs:.2e} absolute, {rel:.2e} relative");
        assert!(abs < 4e-16 && rel < 7e-16, "{abs:e} {rel:e}");
        assert!(asin_fast(1.5).is_nan() && asin_fast(f64::NAN).is_nan());
    }

    /// The pair in lanes is [`asin_fast`] on each lane, to a rounding of its last
    /// multiply-adds (fused only where the CPU has FMA), both sides of ½ in one register.
    #[test]
    fn asin_pair_is_asin_fast() {
        let mut worst: f64 = 0.0;
        for k in -100_000..=100_000 {
            let x = [k as f64 / 100_000.0, -0.73 * k as f64 / 100_000.0];
            let got = asin_pair(f64x2::new(x)).to_array();
            for (g, x) in got.into_iter().zip(x) {
                let want = asin_fast(x);
                worst = worst.max((g - want).abs());
                assert_eq!(g.is_sign_negative(), want.is_sign_negative(), "{x}");
            }
        }
        assert!(worst <= 2.3e-16, "{worst:e}");
        let edges = asin_pair(f64x2::new([f64::NAN, -1.0])).to_array();
        assert!(
            edges[0].is_nan() && edges[1] == -std::f64::consts::FRAC_PI_2,
            "{edges:?}"
        );
    }

    #[test]
    fn atan2_fast_is_within_its_bound() {
        let mut worst: f64 = 0.0;
        for k in -200_000..=200_000 {
            let angle = PI * k as f64 / 200_000.0 + 1e-9;
            for scale in [1e-300, 1e-3, 1.0, 7.5e4, 1e300] {
                let (y, x) = (scale * angle.sin(), scale * angle.cos());
                worst = worst.max((atan2_fast(y, x) - y.atan2(x)).abs());
            }
        }
        // Near the axes and the octant lines, and the edge cases the library takes.
        for (y, x) in [
            (1e-20, 1.0),
            (1.0, 1e-20),
            (-1e-20, -1.0),
            (1.0, 1.0),
            (-3.0, 3.0000001),
        ] {
            worst = worst.max((atan2_fast(y, x) - y.atan2(x)).abs());
        }
        eprintln!("atan2_fast vs f64::atan2 around the circle: ≤ {worst:.2e} absolute");
        assert!(worst < 5e-16, "{worst:e}");
        for (y, x) in [
            (0.0, -1.0),
            (-0.0, -1.0),
            (0.0, 0.0),
            (1.0, f64::INFINITY),
            (f64::INFINITY, -2.0),
        ] {
            assert_eq!(atan2_fast(y, x).to_bits(), y.atan2(x).to_bits(), "{y} {x}");
        }
        assert!(atan2_fast(f64::NAN, 1.0).is_nan() && atan2_fast(1.0, f64::NAN).is_nan());
    }
}
