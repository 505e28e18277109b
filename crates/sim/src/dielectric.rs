//! A smooth dielectric interface seen from one micro-normal m: exact unpolarised Fresnel
//! reflectance, mirror reflection and refraction (Walter et al. 2007, §5).

use glam::DVec3;

/// Fresnel reflectance at one micro-facet, kept as a fraction so that choosing reflection needs
/// no division, with g = √(η² − 1 + c²) for the refracted direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fresnel {
    num: f64,
    den: f64,
    /// g = η |t·m|; 0 under total internal reflection.
    pub g: f64,
}

impl Fresnel {
    /// Unpolarised reflectance F ∈ [0, 1]; 1 under total internal reflection.
    pub fn reflectance(&self) -> f64 {
        (self.num / self.den).min(1.0)
    }

    /// Whether a uniform u ∈ [0, 1) picks reflection, which has probability F.
    #[inline]
    pub fn reflects(&self, u: f64) -> bool {
        u * self.den < self.num
    }
}

/// F(i, m) = ½ (g−c)²/(g+c)² · (1 + (c(g+c)−1)²/(c(g−c)+1)²) with c = |i·m|,
/// g² = η² − 1 + c² and η = η_t/η_i (Walter 2007 eq. 22); g² ≤ 0 is total internal reflection.
pub fn fresnel(c: f64, eta: f64) -> Fresnel {
    let g2 = eta * eta - 1.0 + c * c;
    if g2 <= 0.0 {
        return Fresnel {
            num: 1.0,
            den: 1.0,
            g: 0.0,
        };
    }
    let g = g2.sqrt();
    let (gm, gp) = (g - c, g + c);
    let (bn, bd) = (c * gp - 1.0, c * gm + 1.0);
    Fresnel {
        num: gm * gm * (bd * bd + bn * bn),
        den: 2.0 * gp * gp * bd * bd,
        g,
    }
}

/// Mirror reflection of i (pointing away from the surface) about m: o = 2(i·m)m − i
/// (Walter 2007 eq. 39).
pub fn reflect(i: DVec3, m: DVec3) -> DVec3 {
    2.0 * i.dot(m) * m - i
}

/// Refraction of i (pointing away from the surface, c = i·m > 0) through m, given 1/η = η_i/η_t
/// and g = √(η² − 1 + c²) of [`fresnel`]: t = ((c − g) m − i)/η (Walter 2007 eq. 40, whose
/// √(1 + η⁻²(c² − 1)) is g/η).
pub fn refract(i: DVec3, m: DVec3, c: f64, g: f64, inv_eta: f64) -> DVec3 {
    ((c - g) * m - i) * inv_eta
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The s/p form of the Fresnel equations (Born & Wolf §1.5), a different route to eq. 22.
    fn fresnel_sp(cos_i: f64, eta: f64) -> f64 {
        let sin_t = (1.0 - cos_i * cos_i).sqrt() / eta;
        if sin_t >= 1.0 {
            return 1.0;
        }
        let cos_t = (1.0 - sin_t * sin_t).sqrt();
        let rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
        let rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
        0.5 * (rs * rs + rp * rp)
    }

    #[test]
    fn walter_form_agrees_with_s_and_p_form() {
        for eta in [1.55, 1.0 / 1.55, 1.33, 1.55 / 1.33] {
            for k in 0..=100 {
                let c = k as f64 / 100.0;
                let f = fresnel(c, eta).reflectance();
                assert!((f - fresnel_sp(c, eta)).abs() < 1e-12, "η {eta} c {c}");
            }
        }
        assert!((fresnel(1.0, 1.5).reflectance() - 0.04).abs() < 1e-12);
        assert_eq!(
            fresnel(0.1, 1.0 / 1.55).reflectance(),
            1.0,
            "total internal reflection"
        );
        let f = fresnel(0.3, 1.55);
        let picked = (0..10_000)
            .filter(|k| f.reflects((*k as f64 + 0.5) / 1e4))
            .count();
        assert!((picked as f64 / 1e4 - f.reflectance()).abs() < 1e-4);
    }

    #[test]
    fn refraction_obeys_snell_and_stays_unit() {
        let m = DVec3::Z;
        let i = DVec3::new(0.6, 0.0, 0.8);
        let eta = 1.55;
        let f = fresnel(i.dot(m), eta);
        let t = refract(i, m, i.dot(m), f.g, 1.0 / eta);
        assert!((t.length() - 1.0).abs() < 1e-12);
        assert!(t.z < 0.0);
        assert!((t.x.abs() * eta - 0.6).abs() < 1e-12, "sin θ_t η = sin θ_i");
        assert!(t.x < 0.0, "refracted ray continues across the normal");
        let r = reflect(i, m);
        assert!((r - DVec3::new(-0.6, 0.0, 0.8)).length() < 1e-15);
    }
}
