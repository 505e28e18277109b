//! R off a tilted scale: the exact mirror direction at each offset h, and its inverse, the
//! offset whose mirror leaves at azimuth φ.
//!
//! d'Eon et al. 2014 §2.3 keeps Bravais' φ = −2γ_i = −2 asin h for R (and writes its cone as a
//! function of φ through cos(φ/2) = √(1 − h²)). A tilted normal bends the mirror's azimuth as
//! well as its inclination, little at normal incidence (0.2° at |φ| = 2.2, θ_i ≤ 1.1, α = 2°,
//! `cuticle-sim` `tests/tilt.rs`) but much at grazing incidence: at θ_i = 1.3, α = −4° the
//! offset h = 0.86 mirrors to φ = −2.60 where −2γ_i = −2.07, so the last reflections before the
//! scales cut R off land half a radian further round than Bravais puts them (the simulator's R
//! reaches |φ| = 2.85 there). The tilted model places R by this mapping instead.
//!
//! The inverse is on the model's every evaluation (R's N and M both need it), so it is solved
//! by Newton's method on γ with the mirror's analytic derivative, safeguarded by the bracket
//! where the azimuth changes sign ([`tilted_mirror_offset`]); [`tilted_mirror_offset_bisection`]
//! is its reference twin, the plain bisection the model first used.

use crate::geometry::frame::{FiberAngles, wrap_pi};
use crate::math::{asin_fast, atan2_fast, sin_cos_quadrant};
use glam::DVec3;
use std::f64::consts::{FRAC_PI_2, PI};

/// The mirror of ω_i = (sin θ_i, cos θ_i, 0) (φ_i = 0) at offset h about the scale normal tilted
/// by α (the simulator's sign: toward +u for α > 0): n_s = (sin α, cos α cos γ, −cos α sin γ) at
/// the surface point of azimuth −γ, h = sin γ. Its azimuth is unwrapped about −2γ, so that it
/// is continuous and decreasing in h over the whole fiber.
pub fn tilted_mirror(theta_i: f64, alpha: f64, h: f64) -> FiberAngles {
    let at = Mirror::new(theta_i, alpha).at(h.clamp(-1.0, 1.0).asin());
    FiberAngles::new(at.sin_theta.clamp(-1.0, 1.0).asin(), at.phi)
}

/// The offset whose tilted mirror leaves at a given azimuth, and what R needs there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MirrorOffset {
    /// The offset h = sin γ.
    pub h: f64,
    /// |dh/dφ| at that offset, the Jacobian of N_R.
    pub dh_dphi: f64,
    /// The mirror's inclination θ_o: R's cone.
    pub theta: f64,
    /// sin θ_o, which an evaluation of R's lobe takes without the angle.
    pub sin_theta: f64,
    /// How far θ_o moves per unit micro-normal slope at this azimuth (derived in `Mirror::spread`):
    /// R's longitudinal variance is ½β² spread² (½β² the variance of each Beckmann slope). At
    /// α = 0 it is 2 cos γ, and the variance eq. 6's 2β²(1 − h²).
    pub spread: f64,
}

/// The offset h whose tilted mirror leaves at azimuth φ (unwrapped, as [`tilted_mirror`] gives
/// it), with |dh/dφ| and the mirror's inclination there; `None` outside the range the fiber's
/// offsets reach. Newton's method on γ, where the mirror's azimuth decreases monotonically,
/// kept inside the bracket of the sign change (bisection where a step would leave it).
pub fn tilted_mirror_offset(theta_i: f64, alpha: f64, phi: f64) -> Option<MirrorOffset> {
    let mirror = Mirror::new(theta_i, alpha);
    mirror.offset(phi, mirror.reach())
}

/// Every offset whose mirror leaves at the wrapped azimuth φ, i.e. at φ, φ − 2π or φ + 2π
/// unwrapped, in that order, each where it exists (grazing mirrors run past the back of the
/// fiber, so near φ = ±π two offsets can send light the same way).
pub fn tilted_mirror_offsets(theta_i: f64, alpha: f64, phi: f64) -> [Option<MirrorOffset>; 3] {
    let mirror = Mirror::new(theta_i, alpha);
    let reach = mirror.reach();
    let phi = wrap_pi(phi);
    [0.0, -2.0 * PI, 2.0 * PI].map(|k| mirror.offset(phi + k, reach))
}

/// The reference twin of [`tilted_mirror_offset`]: bisection on γ to 1e-13, the slope by a
/// central difference (the model's first form; its accuracy is the fast one's bound).
pub fn tilted_mirror_offset_bisection(theta_i: f64, alpha: f64, phi: f64) -> Option<MirrorOffset> {
    let at = |g: f64| tilted_mirror(theta_i, alpha, g.sin()).phi;
    let (mut lo, mut hi) = (-FRAC_PI_2, FRAC_PI_2);
    if !(phi <= at(lo) && phi >= at(hi)) {
        return None;
    }
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if at(mid) > phi {
            lo = mid;
        } else {
            hi = mid;
        }
        if hi - lo < 1e-13 {
            break;
        }
    }
    let gamma = 0.5 * (lo + hi);
    // dh/dφ = cos γ / (dφ/dγ), the derivative by a central difference on γ.
    let e = 1e-6;
    let slope = (at((gamma + e).min(FRAC_PI_2)) - at((gamma - e).max(-FRAC_PI_2)))
        / ((gamma + e).min(FRAC_PI_2) - (gamma - e).max(-FRAC_PI_2));
    let theta = tilted_mirror(theta_i, alpha, gamma.sin()).theta;
    let mirror = Mirror::new(theta_i, alpha);
    (slope < 0.0).then(|| MirrorOffset {
        h: gamma.sin(),
        dh_dphi: gamma.cos() / -slope,
        theta,
        sin_theta: theta.sin(),
        spread: mirror.spread(mirror.mirror(gamma), slope),
    })
}

/// Steps after which the bracketed solve stops (it needs 3–5 for tilts of a few degrees).
const MAX_STEPS: usize = 64;
/// Steps after which Newton's fast path gives up for the bracketed solve.
const NEWTON_STEPS: usize = 12;
/// Newton step in γ below which the solve has converged: the error left after a step s is
/// about s² (quadratic convergence), 1e-14 here, inside the 1e-12 that
/// `newton_matches_the_bisection` allows.
const CONVERGED: f64 = 1e-7;

/// The sines and cosines a mirror at any offset needs, found once per incidence.
#[derive(Clone, Copy, Debug)]
struct Mirror {
    sin_theta: f64,
    cos_theta: f64,
    sin_alpha: f64,
    cos_alpha: f64,
}

/// The mirror at one angle γ of the surface point.
#[derive(Clone, Copy, Debug)]
struct MirrorAt {
    /// sin θ_o of the mirror.
    sin_theta: f64,
    /// Its azimuth, unwrapped about −2γ.
    phi: f64,
    /// dφ/dγ.
    slope: f64,
    /// sin γ and cos γ: the offset h and the Jacobian's cos γ.
    sin_gamma: f64,
    cos_gamma: f64,
}

/// The mirror direction at one γ: x = sin θ_o, and y, z across the fiber with dy/dγ, dz/dγ.
#[derive(Clone, Copy, Debug)]
struct Reflected {
    x: f64,
    y: f64,
    z: f64,
    dy: f64,
    dz: f64,
    /// sin γ and cos γ, found on the way.
    sin_gamma: f64,
    cos_gamma: f64,
}

/// The azimuths the mirror reaches, at γ = π/2 (least) and −π/2 (greatest).
#[derive(Clone, Copy, Debug)]
struct Reach {
    least: f64,
    greatest: f64,
}

impl Mirror {
    fn new(theta_i: f64, alpha: f64) -> Self {
        let (sin_theta, cos_theta) = sin_cos_quadrant(theta_i);
        let (sin_alpha, cos_alpha) = sin_cos_quadrant(alpha);
        Self {
            sin_theta,
            cos_theta,
            sin_alpha,
            cos_alpha,
        }
    }

    /// r = 2(ω_i·n)n − ω_i with n = (sin α, cos α cos γ, −cos α sin γ): its x and its
    /// components across the fiber with their derivatives in γ.
    #[inline]
    fn mirror(&self, gamma: f64) -> Reflected {
        let (sg, cg) = sin_cos_quadrant(gamma);
        let (sa, ca) = (self.sin_alpha, self.cos_alpha);
        let d = self.sin_theta * sa + self.cos_theta * ca * cg;
        let dd = -self.cos_theta * ca * sg;
        Reflected {
            x: 2.0 * d * sa - self.sin_theta,
            y: 2.0 * d * ca * cg - self.cos_theta,
            z: -2.0 * d * ca * sg,
            dy: 2.0 * ca * (dd * cg - d * sg),
            dz: -2.0 * ca * (dd * sg + d * cg),
            sin_gamma: sg,
            cos_gamma: cg,
        }
    }

    /// The mirror's azimuth atan2(r_z, r_y) and its derivative (r_y r_z′ − r_z r_y′)/(r_y² + r_z²).
    fn at(&self, gamma: f64) -> MirrorAt {
        self.at_mirror(gamma, &self.mirror(gamma))
    }

    /// [`Mirror::at`] of an already reflected direction.
    #[inline]
    fn at_mirror(&self, gamma: f64, r: &Reflected) -> MirrorAt {
        let bravais = -2.0 * gamma;
        MirrorAt {
            sin_theta: r.x,
            phi: bravais + wrap_pi(atan2_fast(r.z, r.y) - bravais),
            slope: (r.y * r.dz - r.z * r.dy) / (r.y * r.y + r.z * r.z),
            sin_gamma: r.sin_gamma,
            cos_gamma: r.cos_gamma,
        }
    }

    /// At the fiber's edges γ = ±π/2 the micro-normal is (sin α, 0, ∓cos α), and the mirror
    /// leaves at φ = ∓(π − δ) with δ = atan2(sin θ_i sin 2α, cos θ_i): one arctangent for
    /// what [`Mirror::at`] gives at both ends (the test `reach_is_the_mirror_at_the_edges`).
    fn reach(&self) -> Reach {
        let sin_2alpha = 2.0 * self.sin_alpha * self.cos_alpha;
        let delta = atan2_fast(self.sin_theta * sin_2alpha, self.cos_theta);
        Reach {
            least: -PI + delta,
            greatest: PI - delta,
        }
    }

    fn offset(&self, phi: f64, reach: Reach) -> Option<MirrorOffset> {
        if !(phi <= reach.greatest && phi >= reach.least) {
            return None;
        }
        self.offset_newton(phi)
            .or_else(|| self.offset_bracketed(phi))
    }

    /// The fast path: Newton's method on g(γ) = r_z cos φ − r_y sin φ, the mirror's component
    /// across the target azimuth, which needs no arctangent per step (its zeros are where the
    /// mirror leaves at φ or at φ + π). Converged, the one arctangent of [`Mirror::finish`]
    /// checks that it found φ itself; `None` sends the solve to [`Mirror::offset_bracketed`].
    fn offset_newton(&self, phi: f64) -> Option<MirrorOffset> {
        let (sin_phi, cos_phi) = if phi.abs() <= PI {
            let (s, c) = sin_cos_quadrant(0.5 * phi);
            (2.0 * s * c, 1.0 - 2.0 * s * s)
        } else {
            phi.sin_cos()
        };
        let mut gamma = (-0.5 * phi).clamp(-FRAC_PI_2, FRAC_PI_2);
        for _ in 0..NEWTON_STEPS {
            let r = self.mirror(gamma);
            let step = (r.z * cos_phi - r.y * sin_phi) / (r.dz * cos_phi - r.dy * sin_phi);
            gamma -= step;
            if gamma.abs() > FRAC_PI_2 || gamma.is_nan() {
                return None;
            }
            if step.abs() < CONVERGED {
                return self.finish(gamma, phi);
            }
        }
        None
    }

    /// The safeguarded solve for what Newton's fast path leaves: Newton on the azimuth itself,
    /// kept inside the bracket where it changes sign.
    fn offset_bracketed(&self, phi: f64) -> Option<MirrorOffset> {
        // φ(lo) ≥ φ ≥ φ(hi) throughout; Bravais' root is the first guess.
        let (mut lo, mut hi) = (-FRAC_PI_2, FRAC_PI_2);
        let mut gamma = (-0.5 * phi).clamp(lo, hi);
        let mut at = self.at(gamma);
        let mut step = hi - lo;
        for _ in 0..MAX_STEPS {
            let miss = at.phi - phi;
            if miss > 0.0 {
                lo = gamma;
            } else {
                hi = gamma;
            }
            let newton = gamma - miss / at.slope;
            // Newton's step where it stays in the bracket and is under half the step before
            // last (near the pole the azimuth turns fast, and plain Newton there can bounce
            // between two sides of the root for ever); else bisection (Press et al. 2007's
            // `rtsafe`).
            let step_before = step;
            let converged =
                if newton > lo && newton < hi && 2.0 * (newton - gamma).abs() < step_before {
                    step = (newton - gamma).abs();
                    gamma = newton;
                    // Quadratic convergence: a step this small leaves an error near 1e-14.
                    step < CONVERGED
                } else {
                    let mid = 0.5 * (lo + hi);
                    step = (mid - gamma).abs();
                    gamma = mid;
                    hi - lo < 1e-14
                };
            at = self.at(gamma);
            if converged {
                break;
            }
        }
        self.finish(gamma, phi)
    }

    /// The offset at a converged γ, if the mirror there leaves at φ with the azimuth falling:
    /// at grazing incidence the mirror can pass behind the pole, where its azimuth jumps by 2π
    /// instead of crossing φ, and the bracket then closes on the jump, which no offset sends
    /// light through.
    fn finish(&self, gamma: f64, phi: f64) -> Option<MirrorOffset> {
        let r = self.mirror(gamma);
        let at = self.at_mirror(gamma, &r);
        let (h, cos_gamma) = (at.sin_gamma, at.cos_gamma);
        let sin_theta = at.sin_theta.clamp(-1.0, 1.0);
        (at.slope < 0.0 && (at.phi - phi).abs() < 1e-9).then(|| MirrorOffset {
            h,
            dh_dphi: cos_gamma / -at.slope,
            theta: asin_fast(sin_theta),
            sin_theta,
            spread: self.spread(r, at.slope),
        })
    }

    /// R's longitudinal spread at a fixed azimuth: how far θ_o moves per unit slope of the
    /// micro-normal, over the two slope axes in quadrature. A slope s along the scale's
    /// tangent t (toward the axis) or across it, b = (0, sin γ, cos γ), turns the normal by
    /// dn = s t or s b and the mirror by dr = 2((ω_i·dn) n + (ω_i·n) dn), which moves θ_o by
    /// dr_x / cos θ_o and φ by (r_y dr_z − r_z dr_y) / cos²θ_o. The light that leaves at φ
    /// after that turn is the mirror of a neighbouring offset, whose cone differs by
    /// (dθ/dφ) Δφ along the curve of mirrors, so at fixed φ θ_o spreads by
    /// Δθ − (dθ/dφ) Δφ per unit slope.
    ///
    /// Untilted, only the axial slope moves θ_o, by 2 cos γ, and the curve is flat (θ_o = −θ_i),
    /// which is d'Eon et al. 2014 eq. 6. A tilt lets the in-plane slope move θ_o (the normal
    /// has an axial part sin α that ω_i·n scales), changes ω_i·n and cos θ_o, and tilts the
    /// curve. The simulation's R follows it where eq. 6 misses by a quarter
    /// (`crates/validate/tests/tilted_r_width.rs`; docs/departures/10-r-width-tilted.md).
    fn spread(&self, r: Reflected, slope: f64) -> f64 {
        let (sa, ca) = (self.sin_alpha, self.cos_alpha);
        let (sg, cg) = (r.sin_gamma, r.cos_gamma);
        let n = DVec3::new(sa, ca * cg, -ca * sg);
        let wi = DVec3::new(self.sin_theta, self.cos_theta, 0.0);
        let wn = wi.dot(n);
        let inv_cos_o = (r.y * r.y + r.z * r.z).max(1e-300).sqrt().recip();
        // Along the curve of mirrors: dθ/dγ = (dr_x/dγ) / cos θ_o, dr_x/dγ = 2 (ω_i·dn/dγ) sin α.
        let dtheta_dphi = 2.0 * sa * (-self.cos_theta * ca * sg) * inv_cos_o / slope;
        // Δθ − (dθ/dφ) Δφ, both over cos θ_o once more than dr.
        let at_fixed_phi = |dn: DVec3| {
            let dr = 2.0 * (wi.dot(dn) * n + wn * dn);
            (dr.x - dtheta_dphi * (r.y * dr.z - r.z * dr.y) * inv_cos_o) * inv_cos_o
        };
        let axial = at_fixed_phi(DVec3::new(ca, -sa * cg, sa * sg));
        let across = at_fixed_phi(DVec3::new(0.0, sg, cg));
        (axial * axial + across * across).sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::nusselt;
    use crate::models::nonseparable::scales::attenuation::incident;

    #[test]
    fn flat_scales_mirror_by_bravais_and_tilted_ones_agree_with_the_rotations() {
        for &(theta, h) in &[(0.3, 0.4), (1.3, -0.9), (-1.0, 0.2)] {
            let flat = tilted_mirror(theta, 0.0, h);
            assert!((flat.phi + 2.0 * f64::asin(h)).abs() < 1e-12);
            assert!((flat.theta + theta).abs() < 1e-12);
            let alpha = -0.07;
            let tilted = tilted_mirror(theta, alpha, h);
            let x = nusselt::exit_r(alpha, incident(theta, h));
            assert!((tilted.theta - x.asin()).abs() < 1e-12, "θ {theta} h {h}");
        }
        // The grazing case of the module docs.
        let m = tilted_mirror(1.3, (-4f64).to_radians(), 0.86);
        assert!((m.phi + 2.601).abs() < 1e-3, "{}", m.phi);
    }

    #[test]
    fn the_offset_inverts_the_mirror_and_its_slope_is_the_derivative() {
        let (theta, alpha) = (1.3, (-4f64).to_radians());
        for &h in &[-0.95, -0.5, 0.0, 0.3, 0.86] {
            let phi = tilted_mirror(theta, alpha, h).phi;
            let MirrorOffset {
                h: back,
                dh_dphi: dh,
                theta: cone,
                ..
            } = tilted_mirror_offset(theta, alpha, phi).unwrap();
            assert!((back - h).abs() < 1e-9, "h {h}: {back}");
            assert!((cone - tilted_mirror(theta, alpha, h).theta).abs() < 1e-9);
            let e = 1e-5;
            let numeric = 2.0 * e
                / (tilted_mirror(theta, alpha, h - e).phi - tilted_mirror(theta, alpha, h + e).phi);
            assert!(
                (dh - numeric).abs() < 1e-4 * numeric,
                "h {h}: {dh} vs {numeric}"
            );
        }
        // Untilted, |dh/dφ| = ½ cos(φ/2).
        let m = tilted_mirror_offset(0.5, 0.0, 1.0).unwrap();
        assert!((m.h + 0.5f64.sin()).abs() < 1e-9 && (m.dh_dphi - 0.5 * 0.5f64.cos()).abs() < 1e-6);
    }

    /// Newton's solve against its reference twin, the bisection, over θ_i × α × φ (grazing
    /// incidence and both tilt signs, the azimuths past ±π included): the same offsets to 1e-12,
    /// the same Jacobian and spread to the twin's central difference (1e-7 relative), the same
    /// reach; except where the azimuth jumps (see [`Mirror::offset`]; at θ_i = ±1.5 with |α| ≥ 4°
    /// the whole front half), which the bisection reports as a root of vanishing Jacobian
    /// and Newton's solve as none.
    #[test]
    fn newton_matches_the_bisection() {
        let mut worst_h: f64 = 0.0;
        let mut worst_jacobian: f64 = 0.0;
        let (mut solved, mut jumps) = (0, 0);
        let mut widest: f64 = 0.0;
        for &theta in &[-1.5, -1.3, -0.75, 0.0, 0.4, 1.1, 1.3, 1.5] {
            for &alpha_deg in &[-6.0, -4.0, -2.0, 0.0, 2.0, 4.0, 6.0] {
                let alpha = f64::to_radians(alpha_deg);
                for k in 0..=400 {
                    let phi = -3.3 + 6.6 * k as f64 / 400.0;
                    let fast = tilted_mirror_offset(theta, alpha, phi);
                    let reference = tilted_mirror_offset_bisection(theta, alpha, phi);
                    if fast.is_none() && reference.is_none() {
                        continue;
                    }
                    let (Some(f), Some(r)) = (fast, reference) else {
                        // Only where the bisection closed on a jump of the azimuth (the mirror
                        // passing behind the pole at grazing incidence), which it reports as
                        // an offset of vanishing Jacobian.
                        assert!(
                            fast.is_none() && reference.is_some_and(|r| r.dh_dphi < 1e-5),
                            "θ {theta} α {alpha_deg} φ {phi}: {fast:?} {reference:?}"
                        );
                        jumps += 1;
                        continue;
                    };
                    solved += 1;
                    widest = widest.max(f.spread);
                    // Beyond eq. 6's largest (2) only where the mirror passes the pole.
                    assert!(
                        f.spread < 3.0 || f.theta.abs() > 1.5,
                        "θ {theta} α {alpha_deg} φ {phi}"
                    );
                    worst_h = worst_h
                        .max((f.h - r.h).abs())
                        .max((f.theta - r.theta).abs());
                    worst_jacobian = worst_jacobian
                        .max((f.dh_dphi - r.dh_dphi).abs() / r.dh_dphi)
                        .max((f.spread - r.spread).abs() / r.spread.max(1e-3));
                }
            }
        }
        eprintln!(
            "{solved} solves: h and θ within {worst_h:.1e}, dh/dφ within {worst_jacobian:.1e} \
             relative; {jumps} jumps; spread at most {widest:.3}"
        );
        assert!(solved > 18_000, "{solved} {jumps}");
        assert!(worst_h < 1e-12, "{worst_h}");
        assert!(worst_jacobian < 1e-7, "{worst_jacobian}");
        assert!(widest.is_finite() && widest < 8.0, "{widest}");
    }

    /// The spread at fixed φ against a numerical derivative that knows nothing of its algebra:
    /// turn the micro-normal by a small slope along the scale's tangent or across it, reflect,
    /// and measure how far the new direction's θ_o lies from the cone of the mirror that leaves
    /// at its φ (found by [`tilted_mirror_offset`]).
    #[test]
    fn spread_is_the_numerical_change_of_theta_at_fixed_phi() {
        let mut compared = 0;
        for &theta in &[-0.9f64, 0.3, 1.1, 1.3] {
            for &alpha_deg in &[-4.0, 0.0, 2.0, 5.0] {
                let alpha = f64::to_radians(alpha_deg);
                for &h in &[-0.85, -0.3, 0.0, 0.5, 0.9] {
                    let gamma = f64::asin(h);
                    let n = DVec3::new(alpha.sin(), alpha.cos() * gamma.cos(), -alpha.cos() * h);
                    let tangent =
                        DVec3::new(alpha.cos(), -alpha.sin() * gamma.cos(), alpha.sin() * h);
                    let across = DVec3::new(0.0, h, gamma.cos());
                    let wi = DVec3::new(theta.sin(), theta.cos(), 0.0);
                    let phi = tilted_mirror(theta, alpha, h).phi;
                    let Some(m) = tilted_mirror_offset(theta, alpha, phi) else {
                        continue;
                    };
                    // θ_o off the curve of mirrors after turning the normal by slope s along dm.
                    let off_curve = |dm: DVec3, s: f64| {
                        let micro = (n + s * dm).normalize();
                        let r = 2.0 * wi.dot(micro) * micro - wi;
                        let phi_r = phi + wrap_pi(r.z.atan2(r.y) - phi);
                        let curve = tilted_mirror_offset(theta, alpha, phi_r).unwrap();
                        r.x.asin() - curve.theta
                    };
                    let e = 1e-5;
                    let d = |dm| (off_curve(dm, e) - off_curve(dm, -e)) / (2.0 * e);
                    let numeric = d(tangent).hypot(d(across));
                    assert!(
                        (m.spread - numeric).abs() < 1e-6 * numeric.max(0.1),
                        "θ {theta} α {alpha_deg} h {h}: {} vs {numeric}",
                        m.spread
                    );
                    if alpha == 0.0 {
                        assert!((m.spread - 2.0 * gamma.cos()).abs() < 1e-12);
                    }
                    compared += 1;
                }
            }
        }
        assert!(compared >= 70, "{compared}");
    }

    #[test]
    fn reach_is_the_mirror_at_the_edges() {
        for &theta in &[-1.5, -0.7, 0.0, 0.3, 1.2, 1.5] {
            for &alpha_deg in &[-6.0, -2.0, 0.0, 3.0] {
                let mirror = Mirror::new(theta, f64::to_radians(alpha_deg));
                let reach = mirror.reach();
                let (least, greatest) = (mirror.at(FRAC_PI_2).phi, mirror.at(-FRAC_PI_2).phi);
                assert!(
                    (reach.least - least).abs() < 1e-14,
                    "θ {theta} α {alpha_deg}"
                );
                assert!(
                    (reach.greatest - greatest).abs() < 1e-14,
                    "θ {theta} α {alpha_deg}"
                );
            }
        }
    }

    /// The offsets at a wrapped φ are those of φ, φ − 2π and φ + 2π, each where it exists.
    #[test]
    fn offsets_gather_every_branch() {
        let (theta, alpha) = (1.3, f64::to_radians(-4.0));
        for k in 0..100 {
            let phi = -std::f64::consts::PI + 2.0 * std::f64::consts::PI * (k as f64 + 0.5) / 100.0;
            let all: Vec<_> = tilted_mirror_offsets(theta, alpha, phi)
                .into_iter()
                .flatten()
                .collect();
            let each: Vec<_> = [0.0, -2.0, 2.0]
                .iter()
                .filter_map(|n| tilted_mirror_offset(theta, alpha, phi + n * std::f64::consts::PI))
                .collect();
            assert_eq!(all, each);
            assert!(!all.is_empty(), "φ {phi}");
        }
    }
}
