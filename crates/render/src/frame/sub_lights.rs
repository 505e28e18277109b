//! Wide SRBF lights as sums of narrower ones, so that each light's shadow is taken where the
//! shading draws its light from.
//!
//! Xu et al. 2011 eq. 2 takes the transmittance out of the light × BCSDF integral:
//! ∫ G_j S T dω ≈ T̃_j ∫ G_j S dω, which holds when T̃_j is T averaged over the lobe *weighted by
//! G_j S*. One map along the light's centre, filtered to its bandwidth (Ren et al. 2010's
//! convolution optical depth), gives instead T near ω_j. For a narrow light the two agree; for a
//! wide one they do not: the fitted ground of a sky (λ ≈ 2.6, a whole hemisphere and more) has
//! its centre straight below, along hanging strands, where a map sees almost no fiber, while a
//! fiber's BCSDF takes light from the cone around θ_i ≈ −θ_o (Marschner et al. 2003's M_p),
//! nearly across the strands, where the groom is dense.
//!
//! Choice: every light wider than √2 λ_s ([`SPLIT_BANDWIDTH`]) is replaced by sub-lights of
//! bandwidth λ_s on one spherical Fibonacci set of directions spaced ≈ λ_s apart, shared by all
//! the wide lights (so they add up to at most that set's size, each with its own opacity map):
//! light j gives direction ω_k the coefficient ∝ L_j G(ω_k; ω_j, λ′), λ′² = λ_j² − λ_s² (a
//! Gaussian of width λ′ blurred by one of width λ_s is one of width λ_j in the narrow limit),
//! scaled so that its sub-lights carry exactly its energy. Eq. 2 applied to each sub-light
//! then weighs each sub-direction's transmittance by ∫ G_k S dω: the G_j S-weighted mean of T
//! as a sum, T̄_j = Σ_k T_k ∫G_k S / Σ_k ∫G_k S. Lights up to √2 λ_s keep their own map (λ′
//! would be narrower than the set's spacing). Every renderer that shades the frame's list of
//! lights (the CPU's SRBF path and the GPU's) gets this without a change to its shading.
//!
//! The width λ_s: T seen from a point on the side of the hair that faces the camera is nearly a
//! step, about 1 in front of the hair's tangent plane and small behind it, and TT (Marschner
//! et al. 2003's N_TT, ±100° wide in azimuth about the back) takes its light from just behind
//! that step. A sub-light whose Gaussian straddles the step brings the light of its centre's
//! side, at that side's T, across it; so TT's shadowed light comes out too bright by an amount
//! that falls only linearly with λ_s (tests/wide_light.rs, docs/multiple-scattering.md "The
//! wide-light excess is the horizon's"). Finer sub-lights in a band about the horizon alone do
//! not pay: a set of sub-lights narrower than a light's footprint must cover all of it, so a
//! finer band carries a seam, and removing the seam costs the finer set nearly everywhere.
//! [`SPLIT_BANDWIDTH`] is the compromise between that error and the sub-lights' number (the
//! maps and the shading grow with it).

use cuticle_light::SrbfLight;
use glam::{DVec3, Vec3};
use std::f64::consts::PI;

/// Bandwidth λ_s of the sub-lights (lights wider than √2 λ_s are split).
pub const SPLIT_BANDWIDTH: f64 = 0.3;

/// Sub-lights below this fraction of a light's largest one are dropped (their energy goes
/// to the others).
const FLOOR: f64 = 1e-3;

/// The size of the shared set: at most this many sub-lights replace all the wide lights.
pub fn max_sub_lights(lambda_s: f64) -> usize {
    (4.0 * PI / (lambda_s * lambda_s)).ceil() as usize
}

/// Whether a light of bandwidth `lambda` is split into sub-lights of `lambda_s`.
pub fn is_wide(lambda: f64, lambda_s: f64) -> bool {
    lambda > std::f64::consts::SQRT_2 * lambda_s
}

/// `lights` with the wide ones replaced by their shared sub-lights (appended after the narrow
/// lights, the sub-lights that no wide light reaches left out).
pub fn split_wide(lights: &[SrbfLight], lambda_s: f64) -> Vec<SrbfLight> {
    let wide = |l: &SrbfLight| is_wide(l.bandwidth as f64, lambda_s) && l.coefficient != Vec3::ZERO;
    let mut out: Vec<SrbfLight> = lights.iter().filter(|l| !wide(l)).copied().collect();
    if !lights.iter().any(wide) {
        return out;
    }
    let set = fibonacci_sphere(max_sub_lights(lambda_s));
    let mut coefficients = vec![DVec3::ZERO; set.len()];
    for light in lights.iter().filter(|l| wide(l)) {
        for (c, w) in coefficients.iter_mut().zip(weights(light, &set, lambda_s)) {
            *c += light.coefficient.as_dvec3() * w;
        }
    }
    out.extend(
        set.iter()
            .zip(&coefficients)
            .filter(|(_, c)| **c != DVec3::ZERO)
            .map(|(d, c)| SrbfLight::new(d.as_vec3(), lambda_s as f32, c.as_vec3())),
    );
    out
}

/// Light j's share of each direction of `set`: G(ω_k; ω_j, λ′) scaled so that
/// Σ_k w_k ∫G(λ_s) = ∫G(λ_j), those below [`FLOOR`] of the largest zero.
fn weights(light: &SrbfLight, set: &[DVec3], lambda_s: f64) -> Vec<f64> {
    let lambda = light.bandwidth as f64;
    let inner = SrbfLight::new(
        light.direction,
        (lambda * lambda - lambda_s * lambda_s).sqrt() as f32,
        Vec3::ONE,
    );
    let mut w: Vec<f64> = set.iter().map(|&d| inner.basis(d)).collect();
    let largest = w.iter().copied().fold(0.0, f64::max);
    w.iter_mut()
        .filter(|x| **x < FLOOR * largest)
        .for_each(|x| *x = 0.0);
    let sub_integral = SrbfLight::new(Vec3::Z, lambda_s as f32, Vec3::ONE).basis_integral();
    let scale = light.basis_integral() / (w.iter().sum::<f64>() * sub_integral);
    w.iter_mut().for_each(|x| *x *= scale);
    w
}

/// n directions spread evenly over the sphere (a spherical Fibonacci set, +y its axis).
pub fn fibonacci_sphere(n: usize) -> Vec<DVec3> {
    let golden = PI * (3.0 - 5f64.sqrt());
    (0..n)
        .map(|i| {
            let y = 1.0 - (2 * i + 1) as f64 / n as f64;
            let r = (1.0 - y * y).max(0.0).sqrt();
            let (s, c) = (golden * i as f64).sin_cos();
            DVec3::new(r * c, y, r * s)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::{SPLIT_BANDWIDTH, fibonacci_sphere, max_sub_lights, split_wide};
    use cuticle_light::{SrbfLight, evaluate_lights};
    use glam::{DVec3, Vec3};

    /// Each wide light alone, in several directions: the sub-lights' radiance matches it over
    /// the sphere within 10 % of its peak (RMS within 2 %), their energy exactly.
    #[test]
    fn sub_lights_sum_to_the_wide_light() {
        let dirs = fibonacci_sphere(4001);
        for lambda in [0.75, 1.0, 1.3, 2.6] {
            for centre in [
                Vec3::new(0.1, -0.9, 0.3),
                Vec3::Y,
                Vec3::new(0.7, 0.2, -0.5),
            ] {
                let light = SrbfLight::new(centre.normalize(), lambda, Vec3::new(1.0, 0.5, 0.25));
                let subs = split_wide(&[light], SPLIT_BANDWIDTH);
                assert!(subs.len() > 1 && subs.len() <= max_sub_lights(SPLIT_BANDWIDTH));
                assert!(subs.iter().all(|s| s.bandwidth == SPLIT_BANDWIDTH as f32));
                let energy: DVec3 = subs.iter().map(|s| s.integral()).sum();
                assert!(
                    (energy - light.integral()).abs().max_element() < 1e-4 * light.integral().x
                );
                let (mut worst, mut sq) = (0.0f64, 0.0);
                for &d in &dirs {
                    let e = evaluate_lights(&subs, d).x - light.radiance(d).x;
                    worst = worst.max(e.abs());
                    sq += e * e;
                }
                let rms = (sq / dirs.len() as f64).sqrt();
                assert!(
                    worst < 0.1 && rms < 0.02,
                    "λ {lambda} {centre}: {worst} {rms}"
                );
            }
        }
    }

    /// Narrow lights pass unchanged and first; wide lights share one set of sub-lights.
    #[test]
    fn narrow_lights_stay_and_wide_ones_share_the_set() {
        let narrow = SrbfLight::new(Vec3::Y, 1.3 * SPLIT_BANDWIDTH as f32, Vec3::ONE);
        let wide = [
            SrbfLight::new(Vec3::Y, 2.6, Vec3::ONE),
            SrbfLight::new(Vec3::X, 1.3, Vec3::ONE),
        ];
        let out = split_wide(&[narrow, wide[0], wide[1]], SPLIT_BANDWIDTH);
        assert_eq!(out[0], narrow);
        assert!(out.len() <= 1 + max_sub_lights(SPLIT_BANDWIDTH));
        let energy: DVec3 = out[1..].iter().map(|s| s.integral()).sum();
        let want: DVec3 = wide.iter().map(|s| s.integral()).sum();
        assert!((energy - want).abs().max_element() < 1e-4 * want.x);
    }
}
