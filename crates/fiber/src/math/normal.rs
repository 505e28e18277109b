//! The standard normal density and quantile, and erfc to full precision and to 1.2e-7 (also in
//! SIMD lanes).

use super::exp_log::{exp_fast, exp_lanes, ln_fast};
use std::f64::consts::PI;
use wide::f64x4;

/// The standard normal density.
pub fn normal_pdf(x: f64) -> f64 {
    (-0.5 * x * x).exp() / (2.0 * PI).sqrt()
}

/// [`normal_pdf`] through [`exp_fast`]: within 1e-14 relative of it (the bound of
/// `exp_fast_is_within_its_bound`), for the models' per-call Gaussians.
#[inline]
pub fn normal_pdf_fast(x: f64) -> f64 {
    exp_fast(-0.5 * x * x) * (1.0 / (2.0 * PI).sqrt())
}

/// The standard normal's `N` equal-probability midpoints Φ⁻¹((k + ½)/N), scaled so that their
/// own variance is exactly 1 (the midpoints alone fall a few per cent short): a quadrature
/// rule for an expectation over a Gaussian slope that keeps its variance.
pub fn unit_normal_midpoints<const N: usize>() -> [f64; N] {
    let q: [f64; N] = std::array::from_fn(|k| normal_quantile((k as f64 + 0.5) / N as f64));
    let sd = (q.iter().map(|x| x * x).sum::<f64>() / N as f64).sqrt();
    q.map(|x| x / sd)
}

/// The standard normal quantile Φ⁻¹(p) for p ∈ (0, 1): Acklam's rational approximation
/// followed by one Halley step on erfc, accurate to ~1e-15 relative.
pub fn normal_quantile(p: f64) -> f64 {
    let x = normal_quantile_fast(p);
    let p = p.clamp(1e-300, 1.0 - 1e-16);
    let e = 0.5 * erfc(-x / std::f64::consts::SQRT_2) - p;
    let u = e * (2.0 * PI).sqrt() * (0.5 * x * x).exp();
    x - u / (1.0 + 0.5 * x * u)
}

/// Acklam's rational approximation of Φ⁻¹(p) alone, without [`normal_quantile`]'s Halley
/// step: within 1.2e-9 relative of it (`normal_quantile_fast_is_within_its_bound`). Enough to
/// place a sampled offset, whose density the models report from their own evaluation.
#[inline]
pub fn normal_quantile_fast(p: f64) -> f64 {
    const A: [f64; 6] = [
        -39.69683028665376,
        220.9460984245205,
        -275.9285104469687,
        138.357751867269,
        -30.66479806614716,
        2.506628277459239,
    ];
    const B: [f64; 5] = [
        -54.47609879822406,
        161.5858368580409,
        -155.6989798598866,
        66.80131188771972,
        -13.28068155288572,
    ];
    const C: [f64; 6] = [
        -0.007784894002430293,
        -0.3223964580411365,
        -2.400758277161838,
        -2.549732539343734,
        4.374664141464968,
        2.938163982698783,
    ];
    const D: [f64; 4] = [
        0.007784695709041462,
        0.3224671290700398,
        2.445134137142996,
        3.754408661907416,
    ];
    let p = p.clamp(1e-300, 1.0 - 1e-16);
    let tail = |q: f64| {
        (((((C[0] * q + C[1]) * q + C[2]) * q + C[3]) * q + C[4]) * q + C[5])
            / ((((D[0] * q + D[1]) * q + D[2]) * q + D[3]) * q + 1.0)
    };
    if p < 0.02425 {
        tail((-2.0 * ln_fast(p)).sqrt())
    } else if p > 1.0 - 0.02425 {
        -tail((-2.0 * ln_fast(1.0 - p)).sqrt())
    } else {
        let q = p - 0.5;
        let r = q * q;
        (((((A[0] * r + A[1]) * r + A[2]) * r + A[3]) * r + A[4]) * r + A[5]) * q
            / (((((B[0] * r + B[1]) * r + B[2]) * r + B[3]) * r + B[4]) * r + 1.0)
    }
}

/// The complementary error function, to full double precision (the `libm` crate's port of
/// musl's rational approximations; a series of our own cost the renderer a third of its time).
#[inline]
pub fn erfc(x: f64) -> f64 {
    libm::erfc(x)
}

/// The coefficients of [`erfc_rel_1_2e7`]'s fit, lowest degree first.
pub(super) const ERFC_FIT: [f64; 10] = [
    -1.265_512_23,
    1.000_023_68,
    0.374_091_96,
    0.096_784_18,
    -0.186_288_06,
    0.278_868_07,
    -1.135_203_98,
    1.488_515_87,
    -0.822_152_23,
    0.170_872_77,
];

/// erfc(x) to a fractional error below 1.2·10⁻⁷ for every real x: the Chebyshev fit of Press
/// et al., *Numerical Recipes* (2nd ed., §6.2, `erfcc`), one division and one `exp`. The
/// simulator's Smith shadowing term uses it, where speed counts and 1.2e-7 is far below the
/// Monte Carlo noise; [`erfc`] is the full-precision one.
#[inline]
pub fn erfc_rel_1_2e7(x: f64) -> f64 {
    let z = x.abs();
    let t = 1.0 / (1.0 + 0.5 * z);
    // Horner's rule from the highest coefficient down.
    let poly = ERFC_FIT.iter().rev().fold(0.0, |acc, &c| acc * t + c);
    let r = t * (-z * z + poly).exp();
    if x >= 0.0 { r } else { 2.0 - r }
}

/// erfc(x) for x ≥ 0 in each of four lanes: [`erfc_rel_1_2e7`]'s fit through [`exp_lanes`],
/// within 1.3e-7 relative (`erfc_lanes_is_within_its_bound`); 0 where erfc(x) leaves the
/// normal range. For a lobe's truncation at both ends of two lobes at once.
#[inline]
pub fn erfc_lanes(x: f64x4) -> f64x4 {
    let t = f64x4::ONE / x.mul_add(f64x4::splat(0.5), f64x4::ONE);
    let poly = ERFC_FIT
        .iter()
        .rev()
        .fold(f64x4::ZERO, |acc, &c| acc.mul_add(t, f64x4::splat(c)));
    t * exp_lanes(x.mul_neg_add(x, poly))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn erfc_rel_1_2e7_is_within_its_bound_of_the_exact_one() {
        // Its name's bound, against the full-precision erfc, over the range where erfc(x)
        // is a normal number and at reference values (Abramowitz & Stegun table 7.1).
        let mut worst: f64 = 0.0;
        for k in -6000..=26_000 {
            let x = k as f64 * 1e-3;
            let want = erfc(x);
            worst = worst.max(((erfc_rel_1_2e7(x) - want) / want).abs());
        }
        eprintln!("erfc_rel_1_2e7 vs erfc on [−6, 26]: relative error ≤ {worst:.2e}");
        assert!(worst < 1.2e-7, "{worst:e}");
        for (x, want) in [
            (0.5, 0.479_500_122_186_953_5),
            (2.0, 0.004_677_734_981_047_266),
            (-1.0, 1.842_700_792_949_715),
        ] {
            assert!(((erfc_rel_1_2e7(x) - want) / want).abs() < 1.2e-7);
        }
    }

    #[test]
    fn erfc_lanes_is_within_its_bound() {
        // Its doc's bound, against the full-precision erfc, over x ≥ 0 where erfc(x) is a
        // normal number (x < 26.5), and 0 beyond.
        let mut worst: f64 = 0.0;
        for k in 0..6600 {
            let x = [0.0, 1.0, 2.0, 3.0].map(|j| (4.0 * k as f64 + j) * 1e-3);
            let got: [f64; 4] = erfc_lanes(f64x4::from(x)).into();
            for (x, got) in x.iter().zip(got) {
                worst = worst.max((got / erfc(*x) - 1.0).abs());
            }
        }
        eprintln!("erfc_lanes vs erfc on [0, 26.4]: relative error ≤ {worst:.2e}");
        assert!(worst < 1.3e-7, "{worst:e}");
        let beyond: [f64; 4] = erfc_lanes(f64x4::from([30.0, 40.0, 1e3, f64::INFINITY])).into();
        assert_eq!(beyond, [0.0; 4]);
    }

    #[test]
    fn normal_quantile_inverts_the_cdf() {
        for &p in &[1e-12, 1e-5, 0.01, 0.3, 0.5, 0.77, 0.999, 1.0 - 1e-9] {
            let x = normal_quantile(p);
            let cdf = 0.5 * erfc(-x / std::f64::consts::SQRT_2);
            assert!(
                (cdf - p).abs() < 1e-14 * p.max(1e-3) / 1e-3,
                "p {p} x {x} cdf {cdf}"
            );
        }
        assert!((erfc(1.0) - 0.157_299_207_050_285_13).abs() < 1e-15);
        assert!((erfc(0.3) - 0.671_373_240_540_872_8).abs() < 1e-15);
    }

    #[test]
    fn normal_quantile_fast_is_within_its_bound() {
        let mut worst: f64 = 0.0;
        for k in 1..100_000 {
            let p = k as f64 / 100_000.0;
            for p in [p, p * 1e-6] {
                let want = normal_quantile(p);
                if want.abs() > 1e-3 {
                    worst = worst.max((normal_quantile_fast(p) / want - 1.0).abs());
                }
            }
        }
        eprintln!("normal_quantile_fast vs normal_quantile: relative error ≤ {worst:.2e}");
        assert!(worst < 1.2e-9, "{worst:e}");
    }
}
