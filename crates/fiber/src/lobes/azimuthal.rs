//! The azimuthal lobe shape the models share: a Gaussian wrapped on the circle of azimuths
//! (d'Eon et al. 2011 eq. 9's D_p, Marschner et al. 2003's N_p blur), in a fast form that
//! skips the images whose density underflows, a core form for densities bounded below, and
//! the reference sum over every image.

use crate::math::normal_pdf_fast;
use std::f64::consts::PI;

/// A wrapped Gaussian of variance `v` on the circle, evaluated at `x`: the images at
/// x − 2πk for |k| ≤ ⌈3σ/2π⌉ + 1, less those farther than [`UNDERFLOW_SIGMAS`] standard
/// deviations, whose density is exactly 0 in f64 (so the sum is the same to the bit; for a
/// narrow lobe that leaves two or three of the five images, and no exponential underflows
/// into the C library's slow path). [`wrapped_gaussian_reference`] is its twin over every image.
pub fn wrapped_gaussian(x: f64, v: f64) -> f64 {
    let sigma = v.sqrt();
    let x = crate::geometry::frame::wrap_pi(x);
    // ⌈3σ/2π⌉ without the C library's `ceil` (x86-64's baseline has no rounding instruction).
    let third = 3.0 * sigma / (2.0 * PI);
    let images = third as i32 + i32::from((third as i32 as f64) < third) + 1;
    let reach = UNDERFLOW_SIGMAS * sigma;
    let mut sum = 0.0;
    for k in -images..=images {
        let d = x - 2.0 * PI * k as f64;
        if d.abs() < reach {
            sum += normal_pdf_fast(d / sigma);
        }
    }
    sum / sigma
}

/// [`wrapped_gaussian`] of standard deviation `sigma` less the images beyond 12σ
/// (`NEGLIGIBLE_SIGMAS`), each below e^{−72} ≈ 5e-32 of the lobe's peak: for a caller that
/// adds it to a density bounded below (a proposal with a uniform share), where they are lost
/// to rounding. Most x need one image, where [`wrapped_gaussian`] takes three to five.
pub fn wrapped_gaussian_core(x: f64, sigma: f64) -> f64 {
    let x = crate::geometry::frame::wrap_pi(x);
    let reach = NEGLIGIBLE_SIGMAS * sigma;
    let mut sum = 0.0;
    if x.abs() < reach {
        sum += normal_pdf_fast(x / sigma);
    }
    // Images k ≠ 0 lie at least 2π|k| − π from x ∈ (−π, π].
    let images = ((reach + PI) / (2.0 * PI)) as i32;
    for k in 1..=images {
        let shift = 2.0 * PI * k as f64;
        for d in [x - shift, x + shift] {
            if d.abs() < reach {
                sum += normal_pdf_fast(d / sigma);
            }
        }
    }
    sum / sigma
}

/// Standard deviations within which [`wrapped_gaussian_core`] keeps an image.
const NEGLIGIBLE_SIGMAS: f64 = 12.0;

/// Standard deviations beyond which the normal density underflows to 0 in f64
/// (e^{−40²/2} = e^{−800}, below the least subnormal e^{−745}).
const UNDERFLOW_SIGMAS: f64 = 40.0;

/// [`wrapped_gaussian`] summed over every image |k| ≤ ⌈3σ/2π⌉ + 1: its reference twin.
pub fn wrapped_gaussian_reference(x: f64, v: f64) -> f64 {
    let sigma = v.sqrt();
    let x = crate::geometry::frame::wrap_pi(x);
    let images = (3.0 * sigma / (2.0 * PI)).ceil() as i32 + 1;
    (-images..=images)
        .map(|k| normal_pdf_fast((x - 2.0 * PI * k as f64) / sigma))
        .sum::<f64>()
        / sigma
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::GaussLegendre;

    /// The images it leaves out are exactly 0: the same density to the bit as summing every
    /// image, from needle-thin lobes to ones wider than the circle.
    #[test]
    fn wrapped_gaussian_is_its_reference_to_the_bit() {
        for &sigma in &[1e-4, 0.003, 0.05, 0.17, 0.4, 1.0, 2.5, 7.0] {
            for k in 0..=1000 {
                let x = -7.0 + 14.0 * k as f64 / 1000.0;
                let v = sigma * sigma;
                assert_eq!(
                    wrapped_gaussian(x, v).to_bits(),
                    wrapped_gaussian_reference(x, v).to_bits(),
                    "σ {sigma} x {x}"
                );
            }
        }
    }

    /// The images it leaves out are below e^{−72} of the peak, and it keeps every image
    /// within 12σ (a wrong image count would miss one by a wide margin); the rest is the
    /// order of summation. Up to σ = 2.5: wider, the reference's ⌈3σ/2π⌉ + 1 images are the
    /// ones that fall short.
    #[test]
    fn wrapped_gaussian_core_leaves_out_only_negligible_images() {
        for &sigma in &[1e-4, 0.003, 0.05, 0.17, 0.305, 0.4, 1.0, 1.6, 2.5] {
            let peak = 1.0 / (sigma * (2.0 * PI).sqrt());
            for k in 0..=1000 {
                let x = -7.0 + 14.0 * k as f64 / 1000.0;
                let got = wrapped_gaussian_core(x, sigma);
                let want = wrapped_gaussian_reference(x, sigma * sigma);
                assert!(
                    (want - got).abs() <= 1e-31 * peak + 1e-15 * want,
                    "σ {sigma} x {x}: {got} vs {want}"
                );
            }
        }
    }

    #[test]
    fn wrapped_gaussian_has_unit_mass_for_narrow_and_wide_lobes() {
        let rule = GaussLegendre::cached(128);
        for &v in &[0.01, 0.5, 4.0] {
            let m: f64 = (0..16)
                .map(|k| {
                    let a = -PI + 2.0 * PI * k as f64 / 16.0;
                    rule.integrate(a, a + PI / 8.0, |x| wrapped_gaussian(x, v))
                })
                .sum();
            assert!((m - 1.0).abs() < 1e-9, "v {v}: {m}");
        }
    }
}
