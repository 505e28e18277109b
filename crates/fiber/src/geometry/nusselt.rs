//! Ray directions in Nusselt coordinates (d'Eon et al. 2014 §2.2): a direction relative to a
//! surface normal is kept as its components (x along the fiber axis, y across it); z = √(1 − x² −
//! y²) is implied. Tilting the normal by α is the rotation Q; reflection, refraction and the
//! propagation to the next interface are simple maps of (x, y). Square-root inputs are clamped
//! to be non-negative (d'Eon et al. 2014 §2.4), so a path that would be totally internally
//! reflected yields |x| > 1 rather than a NaN.
//!
//! Sign: with the rotations exactly as printed, R's cone comes out as −asin(x cos 2α + z sin 2α)
//! while d'Eon et al. 2014 §2.3 prints −asin(x cos 2α − z sin 2α) (expanded). The two differ only
//! in the sign of α; this module takes α in the sign of §2.3's closed form (a scale tilted so that
//! α > 0 raises the R cone, as in Marschner et al. 2003's α_R = 2α convention with α < 0 for
//! human hair tilting R toward the root), and tests that both agree.

use crate::math::sin_cos_quadrant;
use glam::DVec3;

/// A direction (x, y) in Nusselt coordinates.
pub type Nusselt = (f64, f64);

/// Q(α, x, y) = (x cos α − z sin α, y).
fn rotate(alpha: f64, (x, y): Nusselt) -> Nusselt {
    let z = (1.0 - x * x - y * y).max(0.0).sqrt();
    let (s, c) = sin_cos_quadrant(alpha);
    (x * c - z * s, y)
}

fn neg((x, y): Nusselt) -> Nusselt {
    (-x, -y)
}

fn scale((x, y): Nusselt, k: f64) -> Nusselt {
    (x * k, y * k)
}

/// R[α]: reflection from outside off a scale tilted by α (here α of §2.3's sign: see above).
pub fn reflect_outside(alpha: f64, d: Nusselt) -> Nusselt {
    let a = -alpha;
    rotate(a, neg(rotate(-a, d)))
}

/// R′[α]: reflection from inside.
pub fn reflect_inside(alpha: f64, d: Nusselt) -> Nusselt {
    let a = -alpha;
    rotate(-a, neg(rotate(a, d)))
}

/// T[α]: refraction into the fiber, a dilation by 1/η in the micro-normal's frame.
pub fn refract_in(alpha: f64, eta: f64, d: Nusselt) -> Nusselt {
    let a = -alpha;
    rotate(-a, scale(neg(rotate(-a, d)), 1.0 / eta))
}

/// T′[α]: refraction out of the fiber.
pub fn refract_out(alpha: f64, eta: f64, d: Nusselt) -> Nusselt {
    let a = -alpha;
    rotate(a, scale(neg(rotate(a, d)), eta))
}

/// P: from a transmitted direction to the incident direction at the next interface.
pub fn propagate(d: Nusselt) -> Nusselt {
    neg(d)
}

/// x of the R exit direction for scale tilts α₁ (F_R of §2.2).
pub fn exit_r(alpha: f64, incident: Nusselt) -> f64 {
    reflect_outside(alpha, incident).0
}

/// x of the TT exit direction for tilts α₁, α₂ (F_TT of §2.2).
pub fn exit_tt(alphas: [f64; 2], eta: f64, incident: Nusselt) -> f64 {
    let inside = propagate(refract_in(alphas[0], eta, incident));
    refract_out(alphas[1], eta, inside).0
}

/// x of the TRT exit direction for tilts α₁, α₂, α₃ (F_TRT of §2.2).
pub fn exit_trt(alphas: [f64; 3], eta: f64, incident: Nusselt) -> f64 {
    let inside = propagate(refract_in(alphas[0], eta, incident));
    let reflected = propagate(reflect_inside(alphas[1], inside));
    refract_out(alphas[2], eta, reflected).0
}

/// Why a step of the rotation sequence has no outgoing direction. The clamped maps above turn
/// each of these into a finite but unphysical (x, y); [`AtScale`] reports them instead.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Blocked {
    /// The arriving direction lies behind the tilted scale it meets (its cosine to the
    /// micro-normal is not positive): a shading normal has no light from behind.
    BackFacing,
    /// Reflected or refracted at the micro-normal, the direction points to the wrong side of
    /// the macro surface (outward for a refraction inward, and so on).
    WrongSide,
    /// Leaving the fiber, the transmitted direction is evanescent: η²(x_m² + y²) ≥ 1 in the
    /// scale's frame, before the final rotation back to the macro-normal.
    TotalInternalReflection,
}

/// A direction arriving at a scale tilted by α, in that scale's frame: (x_m, y) and the cosine
/// z_m = √(1 − x_m² − y²) to the micro-normal kept with its sign, which the rotation Q drops.
/// The arriving direction points away from the surface, on the side the ray comes from (the
/// Nusselt convention of d'Eon et al. 2014 §2.2), with z > 0 to the macro-normal on that side.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AtScale {
    pub x: f64,
    pub y: f64,
    /// Cosine to the micro-normal: the Fresnel factor's argument.
    pub cos: f64,
    tilt: Tilt,
    inside: bool,
}

/// A scale tilt α with its sine and cosine, found once for every event of a path (a path
/// through [`crate::models::nonseparable::scales::attenuation`] meets dozens of scales, each turned
/// into and out of).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tilt {
    sin: f64,
    cos: f64,
}

impl Tilt {
    pub fn new(alpha: f64) -> Self {
        let (sin, cos) = sin_cos_quadrant(alpha);
        Self { sin, cos }
    }

    /// Q with the normal component kept, turning by α (`forward`) or by −α: the rotation
    /// (x, z) → (x cos α − z sin α, x sin α + z cos α).
    fn rotate(self, forward: bool, x: f64, z: f64) -> (f64, f64) {
        let s = if forward { self.sin } else { -self.sin };
        (x * self.cos - z * s, x * s + z * self.cos)
    }
}

impl From<f64> for Tilt {
    fn from(alpha: f64) -> Self {
        Self::new(alpha)
    }
}

impl AtScale {
    /// `d` arriving from outside at a scale tilted by α (the sign of §2.3, as the maps above).
    pub fn outside(alpha: impl Into<Tilt>, d: Nusselt) -> Result<Self, Blocked> {
        Self::new(alpha.into(), d, false)
    }

    /// `d` arriving from inside the fiber.
    pub fn inside(alpha: impl Into<Tilt>, d: Nusselt) -> Result<Self, Blocked> {
        Self::new(alpha.into(), d, true)
    }

    fn new(tilt: Tilt, (x, y): Nusselt, inside: bool) -> Result<Self, Blocked> {
        let z = (1.0 - x * x - y * y).max(0.0).sqrt();
        // Outside the micro frame is the macro frame turned by α (reflect_outside's inner
        // rotation), inside by −α.
        let (xm, cos) = tilt.rotate(!inside, x, z);
        if cos <= 0.0 {
            return Err(Blocked::BackFacing);
        }
        Ok(Self {
            x: xm,
            y,
            cos,
            tilt,
            inside,
        })
    }

    /// From the scale's frame back to the macro-normal's on `inside`'s side of the surface;
    /// `WrongSide` where the direction points through the macro surface.
    fn in_macro_frame(&self, (x, y): Nusselt, z: f64, inside: bool) -> Result<Nusselt, Blocked> {
        let (x, z) = self.tilt.rotate(inside, x, z);
        if z <= 0.0 {
            return Err(Blocked::WrongSide);
        }
        Ok((x, y))
    }

    /// The arriving direction in the scale's frame: (x_m, y, cos), pointing away from the surface.
    pub fn arriving(&self) -> DVec3 {
        DVec3::new(self.x, self.y, self.cos)
    }

    /// A direction of travel `d` in the scale's frame (z toward the arriving side), sent on
    /// through the scale (refracted, z < 0) or back (reflected, z > 0) by some micro-normal:
    /// the Nusselt direction on its side of the macro surface, or `WrongSide`.
    pub fn leaving(&self, d: DVec3) -> Result<Nusselt, Blocked> {
        let through = d.z < 0.0;
        self.in_macro_frame((d.x, d.y), d.z.abs(), self.inside != through)
    }

    /// The mirror direction (R[α] from outside, R′[α] from inside), on the arriving side.
    pub fn reflect(&self) -> Result<Nusselt, Blocked> {
        self.in_macro_frame((-self.x, -self.y), self.cos, self.inside)
    }

    /// The refracted direction on the far side (T[α] going in, T′[α] going out): the scale's
    /// tangential components scaled by n_near / n_far, `TotalInternalReflection` where they
    /// leave no real normal component.
    pub fn refract(&self, eta: f64) -> Result<Nusselt, Blocked> {
        let k = if self.inside { eta } else { 1.0 / eta };
        let (x, y) = (-self.x * k, -self.y * k);
        let z2 = 1.0 - x * x - y * y;
        if z2 <= 0.0 {
            return Err(Blocked::TotalInternalReflection);
        }
        self.in_macro_frame((x, y), z2.sqrt(), !self.inside)
    }
}

/// The TT exit direction for tilts α₁, α₂ through the full rotation sequence, or why there is
/// none: the checked twin of [`exit_tt`].
pub fn exit_tt_checked(alphas: [f64; 2], eta: f64, incident: Nusselt) -> Result<Nusselt, Blocked> {
    let inside = propagate(AtScale::outside(alphas[0], incident)?.refract(eta)?);
    AtScale::inside(alphas[1], inside)?.refract(eta)
}

/// The TRT exit direction for tilts α₁, α₂, α₃, or why there is none: the checked twin of
/// [`exit_trt`]. A totally reflected second event is a reflection like any other here (its
/// Fresnel factor is 1).
pub fn exit_trt_checked(alphas: [f64; 3], eta: f64, incident: Nusselt) -> Result<Nusselt, Blocked> {
    let inside = propagate(AtScale::outside(alphas[0], incident)?.refract(eta)?);
    let reflected = propagate(AtScale::inside(alphas[1], inside)?.reflect()?);
    AtScale::inside(alphas[2], reflected)?.refract(eta)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn untilted_paths_leave_on_the_specular_cone() {
        let d = (0.4, 0.3);
        assert!((exit_r(0.0, d) + 0.4).abs() < 1e-15);
        assert!((exit_tt([0.0; 2], 1.55, d) + 0.4).abs() < 1e-15);
        assert!((exit_trt([0.0; 3], 1.55, d) + 0.4).abs() < 1e-15);
    }

    #[test]
    fn first_order_derivatives_match_section_2_2() {
        // dx_R/dα₁ = −2z, dx_TT/dα_k = ηz′ − z, dx_TRT/dα = [ηz′ − z, 2ηz′, ηz′ − z], in the
        // rotation's own sign (α here is §2.3's, i.e. the negative: flip the expected signs).
        let (eta, x, y): (f64, f64, f64) = (1.55, 0.35, 0.5);
        let z = (1.0 - x * x - y * y).sqrt();
        let zp = (1.0 - (x * x + y * y) / (eta * eta)).sqrt();
        let e = 1e-6;
        let d = |f: &dyn Fn(f64) -> f64| (f(e) - f(-e)) / (2.0 * e);
        assert!((d(&|a| exit_r(a, (x, y))) - 2.0 * z).abs() < 1e-8);
        let tt0 = d(&|a| exit_tt([a, 0.0], eta, (x, y)));
        let tt1 = d(&|a| exit_tt([0.0, a], eta, (x, y)));
        assert!((tt0 + (eta * zp - z)).abs() < 1e-7 && (tt1 + (eta * zp - z)).abs() < 1e-7);
        let trt1 = d(&|a| exit_trt([0.0, a, 0.0], eta, (x, y)));
        assert!((trt1 + 2.0 * eta * zp).abs() < 1e-7, "{trt1}");
    }

    /// Where nothing blocks the path, the checked sequence is the paper's.
    #[test]
    fn checked_sequences_agree_with_the_clamped_ones_where_the_path_is_open() {
        let eta = 1.55;
        let mut open = 0;
        for (alpha, x, y) in [
            (0.03, 0.4, 0.3),
            (-0.07, -0.8, 0.1),
            (0.05, 0.9, -0.2),
            (0.0, 0.2, 0.9),
            (0.02, -0.3, -0.6),
        ] {
            let alphas = [alpha; 3];
            if let Ok(tt) = exit_tt_checked([alpha; 2], eta, (x, y)) {
                assert!((tt.0 - exit_tt([alpha; 2], eta, (x, y))).abs() < 1e-14);
                assert!((tt.1 + y).abs() < 1e-14, "y is reversed");
                open += 1;
            }
            if let Ok(trt) = exit_trt_checked(alphas, eta, (x, y)) {
                assert!((trt.0 - exit_trt(alphas, eta, (x, y))).abs() < 1e-14);
                open += 1;
            }
            let r = AtScale::outside(alpha, (x, y)).unwrap().reflect().unwrap();
            assert!((r.0 - exit_r(alpha, (x, y))).abs() < 1e-14);
        }
        assert!(open >= 6, "{open}");
    }

    /// The clamp hides an evanescent exit: at θ_i = 1.1, α = 2°, h = 0.8 the TT exit is totally
    /// reflected, yet the clamped x stays within [−1, 1].
    #[test]
    fn the_clamp_hides_total_internal_reflection_that_the_checked_sequence_reports() {
        let (eta, alpha, theta, h) = (1.55, 2f64.to_radians(), 1.1f64, 0.8);
        let incident = (theta.sin(), h * theta.cos());
        assert!(exit_tt([alpha; 2], eta, incident).abs() <= 1.0);
        assert_eq!(
            exit_tt_checked([alpha; 2], eta, incident),
            Err(Blocked::TotalInternalReflection)
        );
        // A scale tilted toward +u is met from behind by light grazing from −u.
        assert_eq!(
            AtScale::outside(0.2, (-0.99, 0.0)),
            Err(Blocked::BackFacing)
        );
    }
}
