//! Spherical radial basis functions (spherical Gaussians) as lights:
//! G(ω; ω_j, λ_j) = exp(2(ω·ω_j − 1)/λ_j²), Xu et al. 2011 eq. 1 and Table 1, with RGB coefficient
//! L_j. Writing κ = 2/λ² (the "sharpness"), G = exp(κ(ω·ω_j − 1)), and the closed forms follow from
//! ∫_{S²} exp(k ω·μ) dω = 4π sinh(k)/k.

use crate::EnvMap;
use cuticle_range::{End, Range};
use glam::{DVec3, Vec3};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Most SRBF lights a fit makes or a lights file may hold (shading costs grow with their number).
pub const MAX_LIGHTS: usize = 512;
/// The narrowest bandwidth λ a light may have, radians: a sun a pixel wide in a map 8,192
/// pixels tall, the finest a fit makes (`FitOptions`), is 2.3e-4.
pub const MIN_BANDWIDTH: f64 = 1e-4;
/// The widest bandwidth: beyond 4 a light is constant over the sphere to within 12 %.
pub const MAX_BANDWIDTH: f64 = 4.0;
/// A light's bandwidth λ_j.
pub const BANDWIDTH: Range = Range {
    name: "bandwidth",
    min: End::Closed(MIN_BANDWIDTH),
    max: End::Closed(MAX_BANDWIDTH),
    unit: "",
};
/// The largest coefficient (radiance at the centre): far beyond any measured sky (the sun is
/// about 1e9 in W m⁻² sr⁻¹), and small enough that shading sums stay finite in f32 images.
pub const MAX_COEFFICIENT: f64 = 1e20;
/// Each channel of a light's coefficient L_j.
pub const COEFFICIENT: Range = Range {
    name: "coefficient",
    min: End::Closed(0.0),
    max: End::Closed(MAX_COEFFICIENT),
    unit: "",
};
/// The brightest pixel a map may hold: the bound of a light's coefficient, so that what a fit
/// of any readable map writes, a lights file reader reads (issue 57 #12: a map of 3e38 gave
/// lights.json coefficients of 2e38 that `render --lights` refused).
pub const MAX_RADIANCE: f64 = MAX_COEFFICIENT;

/// One SRBF light: L_j G(ω; ω_j, λ_j) (Xu et al. 2011 eq. 1).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct SrbfLight {
    /// Unit centre ω_j (world space, +y up).
    pub direction: Vec3,
    /// Bandwidth λ_j, radians-like: G falls to 1/e about λ_j radians from the centre.
    pub bandwidth: f32,
    /// RGB coefficient L_j: the radiance at the centre.
    pub coefficient: Vec3,
}

/// The product of two SRBF bases, itself a scaled SRBF: G_a G_b = scale · exp(κ(ω·μ − 1)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SrbfProduct {
    pub scale: f64,
    /// Unit centre μ (arbitrary when `sharpness` is 0: then the product is the constant `scale`).
    pub direction: DVec3,
    /// κ = ‖κ_a μ_a + κ_b μ_b‖; the product's bandwidth is √(2/κ).
    pub sharpness: f64,
}

impl SrbfLight {
    /// Why this light cannot shine, if it cannot: a zero or non-finite direction, a bandwidth
    /// outside [[`MIN_BANDWIDTH`], [`MAX_BANDWIDTH`]], or a coefficient channel that is
    /// negative, non-finite or above [`MAX_COEFFICIENT`].
    pub fn fault(&self) -> Option<String> {
        let d = self.direction;
        if !d.is_finite() || d.length() < 1e-6 {
            return Some(format!("direction {:?} is not a direction", d.to_array()));
        }
        let channels = self.coefficient.to_array().map(f64::from);
        BANDWIDTH
            .check(self.bandwidth.into())
            .and_then(|_| COEFFICIENT.check_all(&channels))
            .err()
            .map(|e| e.to_string())
    }

    /// A light centred on `direction` (normalised here).
    pub fn new(direction: Vec3, bandwidth: f32, coefficient: Vec3) -> Self {
        Self {
            direction: direction.normalize(),
            bandwidth,
            coefficient,
        }
    }

    /// The centre as an exactly normalised double-precision vector.
    pub fn centre(&self) -> DVec3 {
        self.direction.as_dvec3().normalize()
    }

    /// κ = 2/λ².
    pub fn sharpness(&self) -> f64 {
        sharpness_of(self.bandwidth as f64)
    }

    /// G(ω; ω_j, λ_j) = exp(2(ω·ω_j − 1)/λ_j²) for a unit ω (Xu et al. 2011 eq. 1), evaluated as
    /// exp(−κ‖ω − ω_j‖²/2) (equal for unit vectors): ω·ω_j − 1 cancels catastrophically for
    /// narrow lobes (κ ~ 10⁵ for a sun one pixel wide turns an f32 direction's rounding into
    /// percent errors), the chord does not. Exactly 0 below e⁻⁷⁰⁰.
    pub fn basis(&self, dir: DVec3) -> f64 {
        let chord2 = (dir - self.centre()).length_squared();
        let exponent = -0.5 * self.sharpness() * chord2;
        if exponent < -700.0 {
            0.0
        } else {
            exponent.exp()
        }
    }

    /// L_j G_j(ω).
    pub fn radiance(&self, dir: DVec3) -> DVec3 {
        self.coefficient.as_dvec3() * self.basis(dir)
    }

    /// ∫ G dω = 2π(1 − e^{−2κ})/κ = πλ²(1 − e^{−4/λ²}).
    pub fn basis_integral(&self) -> f64 {
        sphere_integral(self.sharpness())
    }

    /// ∫ L_j G_j dω per channel.
    pub fn integral(&self) -> DVec3 {
        self.coefficient.as_dvec3() * self.basis_integral()
    }

    /// G_a G_b = e^{κ_m − κ_a − κ_b} exp(κ_m(ω·μ_m − 1)) with κ_m μ_m = κ_a μ_a + κ_b μ_b.
    pub fn basis_product(&self, other: &SrbfLight) -> SrbfProduct {
        let (ka, kb) = (self.sharpness(), other.sharpness());
        let sum = self.centre() * ka + other.centre() * kb;
        let km = sum.length();
        let direction = if km > 0.0 { sum / km } else { DVec3::Y };
        SrbfProduct {
            scale: (km - ka - kb).exp(),
            direction,
            sharpness: km,
        }
    }

    /// ∫ G_a G_b dω = e^{κ_m − κ_a − κ_b} · 2π(1 − e^{−2κ_m})/κ_m.
    pub fn basis_inner_product(&self, other: &SrbfLight) -> f64 {
        self.basis_product(other).integral()
    }

    /// ∫ (L_a G_a)(L_b G_b) dω per channel.
    pub fn inner_product(&self, other: &SrbfLight) -> DVec3 {
        (self.coefficient * other.coefficient).as_dvec3() * self.basis_inner_product(other)
    }
}

/// Checks a list of lights read from outside (a lights file): 1 to [`MAX_LIGHTS`] of them,
/// each without a [`SrbfLight::fault`].
pub fn validate_lights(lights: &[SrbfLight]) -> Result<(), crate::LightError> {
    if lights.is_empty() || lights.len() > MAX_LIGHTS {
        return Err(crate::LightError::LightCount(lights.len()));
    }
    match lights
        .iter()
        .enumerate()
        .find_map(|(i, l)| l.fault().map(|f| (i, f)))
    {
        Some((index, message)) => Err(crate::LightError::Light { index, message }),
        None => Ok(()),
    }
}

impl SrbfProduct {
    /// scale · exp(−κ‖ω − μ‖²/2) for a unit ω (the chord form, as in [`SrbfLight::basis`]).
    pub fn evaluate(&self, dir: DVec3) -> f64 {
        self.scale * (-0.5 * self.sharpness * (dir - self.direction).length_squared()).exp()
    }

    /// ∫ scale · exp(κ(ω·μ − 1)) dω.
    pub fn integral(&self) -> f64 {
        self.scale * sphere_integral(self.sharpness)
    }

    /// √(2/κ) (infinite for a constant product).
    pub fn bandwidth(&self) -> f64 {
        (2.0 / self.sharpness).sqrt()
    }
}

/// κ = 2/λ².
pub(crate) fn sharpness_of(bandwidth: f64) -> f64 {
    2.0 / (bandwidth * bandwidth)
}

/// λ = √(2/κ).
pub(crate) fn bandwidth_of(sharpness: f64) -> f64 {
    (2.0 / sharpness).sqrt()
}

/// ∫_{S²} exp(κ(ω·μ − 1)) dω = 2π(1 − e^{−2κ})/κ, → 4π as κ → 0.
pub(crate) fn sphere_integral(kappa: f64) -> f64 {
    if kappa < 1e-9 {
        4.0 * PI * (1.0 - kappa)
    } else {
        -2.0 * PI * (-2.0 * kappa).exp_m1() / kappa
    }
}

/// Σ_j L_j G_j(ω): the radiance a set of SRBF lights gives direction `dir` (Xu et al. 2011 eq. 1).
pub fn evaluate_lights(lights: &[SrbfLight], dir: DVec3) -> DVec3 {
    lights.iter().map(|l| l.radiance(dir)).sum()
}

/// Relative L2 error of `lights` against every pixel of `map`, solid-angle weighted:
/// √(Σ_p Δω_p ‖L_p − Σ_j L_j G_j(ω_p)‖²) / √(Σ_p Δω_p ‖L_p‖²), RGB channels pooled.
pub fn relative_l2_error(map: &EnvMap, lights: &[SrbfLight]) -> f64 {
    let (err, norm) = (0..map.height())
        .into_par_iter()
        .map(|row| {
            let w = map.solid_angle(row);
            let (mut err, mut norm) = (0.0, 0.0);
            for column in 0..map.width() {
                let truth = map.pixel(column, row).as_dvec3();
                let model = evaluate_lights(lights, map.direction(column, row));
                err += w * (truth - model).length_squared();
                norm += w * truth.length_squared();
            }
            (err, norm)
        })
        .collect::<Vec<_>>()
        .into_iter()
        .fold((0.0, 0.0), |a, b| (a.0 + b.0, a.1 + b.1));
    if norm > 0.0 {
        (err / norm).sqrt()
    } else {
        err.sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::latlong::direction_from_angles;

    /// Every light that would shade NaN, inf or negative pixels is refused with its index; an
    /// empty or oversized list is refused too.
    #[test]
    fn hostile_lights_are_refused() {
        let good = SrbfLight::new(Vec3::Y, 0.5, Vec3::ONE);
        assert!(validate_lights(&[good]).is_ok());
        let spoiled: [fn(&mut SrbfLight); 8] = [
            |l| l.bandwidth = 0.0,
            |l| l.bandwidth = f32::INFINITY,
            |l| l.bandwidth = f32::NAN,
            |l| l.direction = Vec3::ZERO,
            |l| l.direction.x = f32::NAN,
            |l| l.coefficient.y = f32::INFINITY,
            |l| l.coefficient.z = -1.0,
            |l| l.coefficient.x = 1e30,
        ];
        for spoil in spoiled {
            let mut bad = good;
            spoil(&mut bad);
            let e = validate_lights(&[good, bad]).unwrap_err().to_string();
            assert!(e.starts_with("light 1: "), "{e}");
        }
        assert!(validate_lights(&[]).is_err());
        assert!(validate_lights(&vec![good; MAX_LIGHTS + 1]).is_err());
    }

    /// ∫_{S²} f dω by a product rule: Gauss–Legendre-free midpoint in z = sin θ (exact measure)
    /// and φ, fine enough for lobes down to λ = 0.05.
    fn quadrature(f: impl Fn(DVec3) -> f64) -> f64 {
        let (nz, nphi) = (4000, 4000);
        let mut sum = 0.0;
        for i in 0..nz {
            let z = -1.0 + (i as f64 + 0.5) * 2.0 / nz as f64;
            let theta = z.asin();
            for j in 0..nphi {
                let phi = -PI + (j as f64 + 0.5) * 2.0 * PI / nphi as f64;
                sum += f(direction_from_angles(theta, phi));
            }
        }
        sum * (2.0 / nz as f64) * (2.0 * PI / nphi as f64)
    }

    fn light(theta: f64, phi: f64, bandwidth: f32) -> SrbfLight {
        SrbfLight::new(
            direction_from_angles(theta, phi).as_vec3(),
            bandwidth,
            Vec3::new(1.0, 0.5, 2.0),
        )
    }

    #[test]
    fn basis_is_the_seed_formula() {
        let l = light(0.4, 1.0, 0.3);
        let d = direction_from_angles(0.1, 0.8);
        let expected = (2.0 * (d.dot(l.direction.as_dvec3()) - 1.0) / (0.3f64 * 0.3)).exp();
        assert!((l.basis(d) - expected).abs() < 1e-6 * expected);
        assert!((l.basis(l.direction.as_dvec3()) - 1.0).abs() < 1e-6);
    }

    #[test]
    fn a_one_pixel_lobe_keeps_its_shape_despite_f32_storage() {
        let l = light(0.4, 2.0, 0.004);
        let kappa = l.sharpness();
        assert!(kappa > 1e5);
        let centre = l.centre();
        assert!((l.basis(centre) - 1.0).abs() < 1e-12);
        let axis = centre.any_orthonormal_vector();
        for theta in [0.001f64, 0.003, 0.006] {
            let d = centre * theta.cos() + axis * theta.sin();
            let expected = (-2.0 * kappa * (theta / 2.0).sin().powi(2)).exp();
            let got = l.basis(d);
            assert!(
                (got - expected).abs() < 1e-9 * expected.max(1e-30),
                "θ={theta}"
            );
        }
    }

    #[test]
    fn relative_error_is_zero_for_the_lights_and_one_half_for_twice_them() {
        let lights = [light(0.3, 1.0, 0.4), light(-0.5, -2.0, 0.8)];
        let exact = EnvMap::from_fn(64, 32, |d| evaluate_lights(&lights, d).as_vec3());
        assert!(relative_l2_error(&exact, &lights) < 1e-6);
        let twice = EnvMap::from_fn(64, 32, |d| (evaluate_lights(&lights, d) * 2.0).as_vec3());
        assert!((relative_l2_error(&twice, &lights) - 0.5).abs() < 1e-6);
    }

    #[test]
    fn integral_matches_quadrature() {
        for &lambda in &[0.08f32, 0.3, 1.0, 3.0, 20.0] {
            let l = light(0.7, -2.1, lambda);
            let numeric = quadrature(|d| l.basis(d));
            let closed = l.basis_integral();
            assert!(
                (numeric - closed).abs() < 1e-4 * closed,
                "λ={lambda}: {numeric} vs {closed}"
            );
        }
    }

    #[test]
    fn product_is_an_srbf_and_its_integral_matches_quadrature() {
        let pairs = [
            (light(0.7, -2.1, 0.2), light(0.5, -1.9, 0.35)),
            (light(0.0, 0.0, 0.5), light(0.3, 2.5, 1.5)),
            (light(1.2, 1.0, 0.9), light(-1.2, -2.1, 0.9)),
            (light(0.2, 0.3, 2.0), light(0.2, 0.3, 0.1)),
        ];
        for (a, b) in pairs {
            let product = a.basis_product(&b);
            for &(t, p) in &[(0.6, -2.0), (0.0, 1.0), (-0.5, 2.9), (0.2, 0.31)] {
                let d = direction_from_angles(t, p);
                let direct = a.basis(d) * b.basis(d);
                assert!((product.evaluate(d) - direct).abs() <= 1e-9 + 1e-6 * direct);
            }
            let numeric = quadrature(|d| a.basis(d) * b.basis(d));
            let closed = a.basis_inner_product(&b);
            assert!(
                (numeric - closed).abs() < 1e-4 * closed,
                "{numeric} vs {closed}"
            );
            let rgb = a.inner_product(&b);
            assert!((rgb.z - closed * 4.0).abs() < 1e-9 * closed.max(1.0));
        }
    }

    #[test]
    fn opposite_equal_lobes_multiply_to_a_constant() {
        let a = light(0.3, 0.2, 0.7);
        let b = SrbfLight::new(-a.direction, 0.7, Vec3::ONE);
        let product = a.basis_product(&b);
        assert!(product.sharpness < 1e-5);
        let expected = (-2.0 * a.sharpness()).exp();
        assert!((product.evaluate(DVec3::X) - expected).abs() < 1e-6 * expected);
        assert!((product.integral() - 4.0 * PI * expected).abs() < 1e-5 * expected);
    }
}
