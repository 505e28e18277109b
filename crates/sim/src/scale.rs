//! Tilted cuticle scales as a shading frame: the micro-normal distribution is centred on the
//! macro normal tilted by α along the fiber axis (d'Eon et al. 2014 §2.1–2.2).

use glam::{DVec2, DVec3};

/// The tilt, with sin α and cos α precomputed. Positive α tilts the outward normal toward +u,
/// which is the sign under which a mirror at the tilted normal gives d'Eon et al. 2014 §2.3's
/// θ_cone_R = −asin(sin θ_i − 2 sin α (cos(φ/2) cos α cos θ_i + sin α sin θ_i)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tilt {
    sin: f64,
    cos: f64,
}

impl Tilt {
    pub fn new(alpha: f64) -> Self {
        let (sin, cos) = alpha.sin_cos();
        Self { sin, cos }
    }

    /// The shading frame of the outward side at surface point p = (y, z): with macro normal
    /// (0, y, z), the normal is n_s = (sin α, cos α·y, cos α·z), the tangent along the axis
    /// t = (cos α, −sin α·y, −sin α·z), and the tangent round the fiber b = (0, −z, y).
    pub fn frame_at(&self, p: DVec2) -> ShadingFrame {
        ShadingFrame {
            t: DVec3::new(self.cos, -self.sin * p.x, -self.sin * p.y),
            b: DVec3::new(0.0, -p.y, p.x),
            n: DVec3::new(self.sin, self.cos * p.x, self.cos * p.y),
        }
    }
}

/// An orthonormal frame around a shading normal n (tangents t, b).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadingFrame {
    pub t: DVec3,
    pub b: DVec3,
    pub n: DVec3,
}

impl ShadingFrame {
    /// The same surface seen from the other side (inside the fiber): n → −n.
    pub fn flipped(self) -> Self {
        Self { n: -self.n, ..self }
    }

    /// A local vector (x along t, y along b, z along n) in world coordinates.
    pub fn to_world(&self, local: DVec3) -> DVec3 {
        self.t * local.x + self.b * local.y + self.n * local.z
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_is_orthonormal_and_tilts_toward_plus_u() {
        let p = DVec2::new(0.6, -0.8);
        let f = Tilt::new(0.07).frame_at(p);
        for (a, b) in [(f.t, f.b), (f.t, f.n), (f.b, f.n)] {
            assert!(a.dot(b).abs() < 1e-15);
        }
        for v in [f.t, f.b, f.n] {
            assert!((v.length() - 1.0).abs() < 1e-15);
        }
        assert!(f.n.x > 0.0);
        assert!((f.n.dot(DVec3::new(0.0, p.x, p.y)) - 0.07f64.cos()).abs() < 1e-15);
    }
}
