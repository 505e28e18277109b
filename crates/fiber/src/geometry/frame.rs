//! The fiber frame and its angles (docs/conventions.md §2).
//!
//! `u` is the fiber tangent; `v` and `w` span the normal plane. For a direction ω,
//! `sin θ = ω·u` and `φ = atan2(ω·w, ω·v)`, so θ ∈ [−π/2, π/2] and φ ∈ (−π, π].

use glam::DVec3;
use std::f64::consts::PI;

/// Longitudinal inclination θ and azimuth φ of a direction in the fiber frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FiberAngles {
    pub theta: f64,
    pub phi: f64,
}

impl FiberAngles {
    pub const fn new(theta: f64, phi: f64) -> Self {
        Self { theta, phi }
    }

    /// The unit direction in the canonical frame (u = x, v = y, w = z).
    pub fn to_dir(self) -> DVec3 {
        let (st, ct) = self.theta.sin_cos();
        let (sp, cp) = self.phi.sin_cos();
        DVec3::new(st, ct * cp, ct * sp)
    }

    /// The angles of a unit direction given in the canonical frame (u = x, v = y, w = z).
    pub fn from_dir(d: DVec3) -> Self {
        Self {
            theta: d.x.clamp(-1.0, 1.0).asin(),
            phi: d.z.atan2(d.y),
        }
    }
}

/// An orthonormal fiber frame: tangent `u`, normal-plane axes `v`, `w`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FiberFrame {
    pub u: DVec3,
    pub v: DVec3,
    pub w: DVec3,
}

impl FiberFrame {
    /// The canonical frame u = x, v = y, w = z.
    pub const CANONICAL: Self = Self {
        u: DVec3::X,
        v: DVec3::Y,
        w: DVec3::Z,
    };

    /// A frame around `tangent` whose `v` axis is the part of `toward` normal to the fiber
    /// (so that a direction `toward` has φ = 0); any perpendicular when `toward` is parallel.
    pub fn from_tangent(tangent: DVec3, toward: DVec3) -> Self {
        let u = tangent.normalize();
        let normal = toward - u * u.dot(toward);
        let v = if normal.length_squared() > 1e-24 {
            normal.normalize()
        } else {
            u.any_orthonormal_vector()
        };
        Self {
            u,
            v,
            w: u.cross(v),
        }
    }

    pub fn angles(&self, d: DVec3) -> FiberAngles {
        FiberAngles::from_dir(self.local(d))
    }

    /// `d` in this frame's coordinates (u, v, w).
    pub fn local(&self, d: DVec3) -> DVec3 {
        DVec3::new(d.dot(self.u), d.dot(self.v), d.dot(self.w))
    }

    pub fn dir(&self, a: FiberAngles) -> DVec3 {
        let c = a.to_dir();
        self.u * c.x + self.v * c.y + self.w * c.z
    }
}

/// Wraps an angle to (−π, π]. Angles within one turn of that range (a difference of two
/// azimuths, a deflection plus an offset) take one addition; others a remainder.
#[inline]
pub fn wrap_pi(x: f64) -> f64 {
    if x > -PI && x <= PI {
        x
    } else if x > PI && x <= 3.0 * PI {
        x - 2.0 * PI
    } else if x > -3.0 * PI && x <= -PI {
        x + 2.0 * PI
    } else {
        wrap_pi_remainder(x)
    }
}

#[cold]
fn wrap_pi_remainder(x: f64) -> f64 {
    let y = (x + PI).rem_euclid(2.0 * PI) - PI;
    if y == -PI { PI } else { y }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn angles_round_trip_through_directions() {
        for &theta in &[-1.5, -0.7, 0.0, 0.3, 1.2] {
            for &phi in &[-3.0, -1.0, 0.0, 0.5, 2.9, PI] {
                let a = FiberAngles::new(theta, phi);
                let back = FiberAngles::from_dir(a.to_dir());
                assert!(
                    (back.theta - theta).abs() < 1e-12 && (wrap_pi(back.phi - phi)).abs() < 1e-12
                );
            }
        }
    }

    #[test]
    fn frame_from_tangent_puts_toward_at_phi_zero() {
        let f = FiberFrame::from_tangent(DVec3::new(0.0, 0.0, 2.0), DVec3::new(1.0, 0.0, 0.5));
        let a = f.angles(DVec3::new(1.0, 0.0, 0.5).normalize());
        assert!(a.phi.abs() < 1e-12);
        assert!((a.theta - (0.5f64 / 1.25f64.sqrt()).asin()).abs() < 1e-12);
        assert!((f.u.cross(f.v) - f.w).length() < 1e-12);
    }

    #[test]
    fn wrap_pi_lands_in_half_open_range() {
        assert_eq!(wrap_pi(-PI), PI);
        assert!((wrap_pi(3.0 * PI + 0.1) - (-PI + 0.1)).abs() < 1e-12);
        assert!((wrap_pi(-0.2) + 0.2).abs() < 1e-15);
        // Each branch lands in (−π, π] and agrees with the remainder to rounding.
        for k in -2000..=2000 {
            let x = k as f64 * 0.0137 + 0.001;
            let y = wrap_pi(x);
            assert!(y > -PI && y <= PI, "{x} -> {y}");
            assert!((y - wrap_pi_remainder(x)).abs() < 1e-14, "{x}: {y}");
        }
        assert_eq!(wrap_pi(3.0 * PI), PI);
        assert!(wrap_pi(f64::NAN).is_nan());
    }
}
