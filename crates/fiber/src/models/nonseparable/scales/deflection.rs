//! Φ(p, h) through tilted scales: the azimuth at which the path entering at offset h leaves
//! after p internal chords, traced through the rotation sequence of d'Eon et al. 2014 §2.2.
//!
//! Bravais' Φ(p, h) = 2pγ_t − 2γ_i + pπ (d'Eon et al. 2014 eq. 3) holds for a smooth cylinder,
//! where every event meets the surface at the same in-plane angle. A tilted scale turns each
//! direction about the fiber's tangent, which changes its component along the normal but not
//! across it, so the in-plane angle atan(|y| / z) of each chord and of the exit changes, by
//! up to half a radian of Φ near the edges (docs/departures/09-tt-exit-azimuth.md;
//! `tests/tilted_tir.rs` checks this module against an exact 3D trace). The paper's model
//! keeps Bravais' Φ; the tilted model shifts TRT's azimuthal lobe by [`deflection_shift`]
//! (R has its exact mirror, [`crate::models::nonseparable::scales::mirror`]; TRRT measured worse
//! shifted; TT takes its shift and spread through the rough surface,
//! [`crate::models::nonseparable::rough::deflection`], which this smooth path is the β → 0 limit
//! of) and places TT's cone at [`tilted_tt_offset`].
//!
//! With γ_i the in-plane angle of the incident direction to the normal at entry, γ′_k that of
//! chord k (the same at both of its ends, by the circle's symmetry) and γ_o that of the exit
//! direction, each taken with the sign of h, the exit leaves at
//! Φ = pπ − γ_i − γ_o + 2 Σ_k γ′_k, which is Bravais' Φ where γ_o = γ_i and γ′_k = γ_t.

use crate::geometry::bravais::{azimuthal_deflection, eta_prime};
use crate::geometry::frame::wrap_pi;
use crate::geometry::nusselt::{self, AtScale, Nusselt, Tilt};
use crate::math::{asin_fast, atan2_fast};
use crate::models::nonseparable::scales::attenuation::incident;
use std::cell::Cell;
use std::f64::consts::PI;

/// The in-plane angle of a Nusselt direction to its normal: atan(|y| / z), z = √(1 − x² − y²).
fn in_plane((x, y): Nusselt) -> f64 {
    let z = (1.0 - x * x - y * y).max(0.0).sqrt();
    atan2_fast(y.abs(), z)
}

/// Where the smooth path entering at offset h through scales tilted by α leaves.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TiltedExit {
    /// Φ(p, h), unwrapped like [`azimuthal_deflection`].
    pub phi: f64,
    /// The sine of the exit's inclination θ_o.
    pub sin_theta: f64,
}

/// The exit of the path entering at offset h through scales tilted by α (the sign of
/// [`crate::geometry::nusselt`]) after p internal chords; `None` where a smooth surface blocks the
/// path ([`nusselt::Blocked`]: the back of a scale, the wrong side, or an exit totally reflected).
pub fn tilted_exit(p: u32, theta_i: f64, alpha: f64, eta: f64, h: f64) -> Option<TiltedExit> {
    let tilt = Tilt::new(alpha);
    let d = incident(theta_i, h);
    let gamma_i = in_plane(d);
    let entry = AtScale::outside(tilt, d).ok()?;
    if p == 0 {
        let exit = entry.reflect().ok()?;
        return Some(TiltedExit {
            phi: -h.signum() * (gamma_i + in_plane(exit)),
            sin_theta: exit.0,
        });
    }
    let mut chord = entry.refract(eta).ok()?;
    let mut chords = in_plane(chord);
    for _ in 1..p {
        chord = AtScale::inside(tilt, nusselt::propagate(chord))
            .ok()?
            .reflect()
            .ok()?;
        chords += in_plane(chord);
    }
    let exit = AtScale::inside(tilt, nusselt::propagate(chord))
        .ok()?
        .refract(eta)
        .ok()?;
    Some(TiltedExit {
        phi: p as f64 * PI + h.signum() * (2.0 * chords - gamma_i - in_plane(exit)),
        sin_theta: exit.0,
    })
}

/// Φ(p, h) of [`tilted_exit`].
pub fn tilted_deflection(p: u32, theta_i: f64, alpha: f64, eta: f64, h: f64) -> Option<f64> {
    tilted_exit(p, theta_i, alpha, eta, h).map(|exit| exit.phi)
}

/// What the tilt adds to Bravais' Φ(p, h): [`tilted_deflection`] less Bravais' Φ with η′ at
/// the θ_d where the lobe's N_p is read, and 0 untilted or where the smooth path is blocked.
/// d'Eon et al. 2011's N_p takes η′ at the θ_d it is evaluated at, so Bravais' Φ plus this
/// shift is the traced Φ there; [`ReadAt`] says where that is. Where the path is blocked, the
/// light a rough surface lets through leaves by micro-normals far from the tilted scale's,
/// which this geometry does not describe, so it keeps Bravais' Φ.
pub fn deflection_shift(
    p: u32,
    theta_i: f64,
    alpha: f64,
    eta: f64,
    h: f64,
    read_at: ReadAt,
) -> f64 {
    if alpha == 0.0 {
        return 0.0;
    }
    let Some(exit) = tilted_exit(p, theta_i, alpha, eta, h) else {
        return 0.0;
    };
    let sin_theta_o = match read_at {
        ReadAt::OwnExit => exit.sin_theta,
        ReadAt::CentralExit => central_exit_last(p, theta_i, alpha, eta)
            .map_or(exit.sin_theta, |central| central.sin_theta),
    };
    let theta_d = 0.5 * (asin_fast(sin_theta_o.clamp(-1.0, 1.0)) - theta_i);
    exit.phi - azimuthal_deflection(p, h, eta_prime(eta, theta_d))
}

/// [`tilted_exit`] at h = 0, kept for the last arguments on each thread: a table's row, the
/// quadrature and a sampler's fixed point ask for it at every offset of one θ_i.
fn central_exit_last(p: u32, theta_i: f64, alpha: f64, eta: f64) -> Option<TiltedExit> {
    type Last = Option<([f64; 4], Option<TiltedExit>)>;
    thread_local! {
        static LAST: Cell<Last> = const { Cell::new(None) };
    }
    let key = [p as f64, theta_i, alpha, eta];
    LAST.with(|last| match last.get() {
        Some((k, found)) if k == key => found,
        _ => {
            let found = tilted_exit(p, theta_i, alpha, eta, 0.0);
            last.set(Some((key, found)));
            found
        }
    })
}

/// Where a lobe's N_p is read for the path entering at h: the θ_d = (θ_o − θ_i) / 2 of its
/// longitudinal cone. Untilted both are Bravais' own θ_d = −θ_i.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ReadAt {
    /// The cone follows each path's own exit (TT's, at the offset that leaves at φ).
    OwnExit,
    /// The cone is the path at h = 0's (TRT's, d'Eon et al. 2014 §2.5). The smooth path's:
    /// near grazing incidence the tilted model moves TRT's cone by what its rough exit cuts
    /// (up to 0.02 in sine at θ_i = 1.3; docs/departures/17-trt-cut.md), which this
    /// leaves out.
    CentralExit,
}

/// The offset h whose TT path through scales tilted by α leaves at azimuth φ (h takes φ's
/// sign, as Bravais' offset does): the root of [`tilted_deflection`]`(1, h) = |φ|` among the
/// offsets whose smooth path leaves, the last of them where |φ| lies beyond their reach.
/// `None` where the path at h = 0 is blocked. The tilted model places TT's cone here
/// (docs/departures/14-tt-cone-offset.md), where the exit it describes leaves.
pub fn tilted_tt_offset(theta_i: f64, alpha: f64, eta: f64, phi: f64) -> Option<f64> {
    let deflection = |h: f64| tilted_deflection(1, theta_i, alpha, eta, h);
    let Reach {
        edge,
        deflection_at_edge,
    } = reach_last(theta_i, alpha, eta)?;
    let target = wrap_pi(phi);
    let a = target.abs();
    let h = if a <= deflection_at_edge {
        edge
    } else {
        // Φ(1, h) falls from π at h = 0 to its value at the edge.
        let (mut low, mut high) = (0.0, edge);
        for _ in 0..OFFSET_BISECTIONS {
            let mid = 0.5 * (low + high);
            match deflection(mid) {
                Some(d) if d > a => low = mid,
                _ => high = mid,
            }
        }
        0.5 * (low + high)
    };
    Some(h.copysign(target))
}

/// Bisection steps of [`tilted_tt_offset`]: h to 1e-15.
const OFFSET_BISECTIONS: usize = 50;

/// The last offset h ≥ 0 whose smooth TT path leaves, and where it leaves.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Reach {
    edge: f64,
    deflection_at_edge: f64,
}

/// TT's [`Reach`], the blocked offsets taken as one band at the fiber's edge; `None` where
/// the path at h = 0 is blocked too.
fn reach(theta_i: f64, alpha: f64, eta: f64) -> Option<Reach> {
    const NEAR_EDGE: f64 = 1.0 - 1e-9;
    let deflection = |h: f64| tilted_deflection(1, theta_i, alpha, eta, h);
    deflection(0.0)?;
    let edge = if deflection(NEAR_EDGE).is_some() {
        NEAR_EDGE
    } else {
        let (mut low, mut high) = (0.0, NEAR_EDGE);
        for _ in 0..OFFSET_BISECTIONS {
            let mid = 0.5 * (low + high);
            if deflection(mid).is_some() {
                low = mid;
            } else {
                high = mid;
            }
        }
        low
    };
    Some(Reach {
        edge,
        deflection_at_edge: deflection(edge)?,
    })
}

/// [`reach`], kept for the last arguments on each thread: the lobe table asks for a whole row
/// of φ at one θ_i.
fn reach_last(theta_i: f64, alpha: f64, eta: f64) -> Option<Reach> {
    type Last = Option<([f64; 3], Option<Reach>)>;
    thread_local! {
        static LAST: Cell<Last> = const { Cell::new(None) };
    }
    let key = [theta_i, alpha, eta];
    LAST.with(|last| match last.get() {
        Some((k, found)) if k == key => found,
        _ => {
            let found = reach(theta_i, alpha, eta);
            last.set(Some((key, found)));
            found
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn untilted_deflection_is_bravais() {
        for p in 0..4 {
            for theta_i in [-1.3, -0.4, 0.0, 0.75, 1.2] {
                for k in 0..=40 {
                    let h = -0.999 + 1.998 * k as f64 / 40.0;
                    let traced = tilted_deflection(p, theta_i, 0.0, 1.55, h).unwrap();
                    let bravais = azimuthal_deflection(p, h, eta_prime(1.55, theta_i));
                    assert!(
                        (traced - bravais).abs() < 1e-9,
                        "p {p} θ_i {theta_i} h {h}: {traced} vs {bravais}"
                    );
                }
            }
        }
    }

    #[test]
    fn r_follows_the_exact_mirror() {
        for (theta_i, alpha_deg) in [(0.3, -2.0), (0.75, 4.0), (1.1, -4.0), (-1.1, 2.0)] {
            let alpha = f64::to_radians(alpha_deg);
            let mut compared = 0;
            for k in 0..=20 {
                let h = -0.95 + 1.9 * k as f64 / 20.0;
                let mirror =
                    crate::models::nonseparable::scales::mirror::tilted_mirror(theta_i, alpha, h)
                        .phi;
                let Some(traced) = tilted_deflection(0, theta_i, alpha, 1.55, h) else {
                    continue;
                };
                compared += 1;
                assert!(
                    (crate::geometry::frame::wrap_pi(traced - mirror)).abs() < 1e-9,
                    "θ_i {theta_i} α {alpha_deg}° h {h}: {traced} vs mirror {mirror}"
                );
            }
            assert!(
                compared >= 15,
                "θ_i {theta_i} α {alpha_deg}°: {compared} offsets reflect"
            );
        }
    }

    #[test]
    fn shift_is_odd_in_h_and_vanishes_without_tilt() {
        for p in 1..4 {
            for h in [0.1, 0.5, 0.9] {
                for read_at in [ReadAt::OwnExit, ReadAt::CentralExit] {
                    let a = deflection_shift(p, 0.75, -0.07, 1.55, h, read_at);
                    let b = deflection_shift(p, 0.75, -0.07, 1.55, -h, read_at);
                    assert!((a + b).abs() < 1e-12, "p {p} h {h}: {a} {b}");
                    assert!(a.abs() > 1e-4, "the tilt moves Φ({p}, {h})");
                    assert_eq!(deflection_shift(p, 0.75, 0.0, 1.55, h, read_at), 0.0);
                }
            }
        }
    }
}
