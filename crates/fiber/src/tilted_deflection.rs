//! Φ(p, h) through tilted scales: the azimuth at which the path entering at offset h leaves
//! after p internal chords, traced through the rotation sequence of d'Eon et al. 2014 §2.2.
//!
//! Bravais' Φ(p, h) = 2pγ_t − 2γ_i + pπ (d'Eon et al. 2014 eq. 3) holds for a smooth cylinder,
//! where every event meets the surface at the same in-plane angle. A tilted scale turns each
//! direction about the fiber's tangent, which changes its component along the normal but not
//! across it, so the in-plane angle atan(|y| / z) of each chord and of the exit changes, by
//! up to half a radian of Φ near the edges (docs/validation.md, departure 9;
//! `tests/tilted_tir.rs` checks this module against an exact 3D trace). The paper's model
//! keeps Bravais' Φ; the tilted model shifts TT's azimuthal lobe by [`deflection_shift`]
//! (R has its exact mirror, [`crate::tilted_mirror`]; TRT measured worse shifted).
//!
//! With γ_i the in-plane angle of the incident direction to the normal at entry, γ′_k that of
//! chord k (the same at both of its ends, by the circle's symmetry) and γ_o that of the exit
//! direction, each taken with the sign of h, the exit leaves at
//! Φ = pπ − γ_i − γ_o + 2 Σ_k γ′_k, which is Bravais' Φ where γ_o = γ_i and γ′_k = γ_t.

use crate::bravais::{azimuthal_deflection, eta_prime};
use crate::nusselt::{self, AtScale, Nusselt, Tilt};
use crate::special::atan2_fast;
use crate::tilted_attenuation::incident;
use std::f64::consts::PI;

/// The in-plane angle of a Nusselt direction to its normal: atan(|y| / z), z = √(1 − x² − y²).
fn in_plane((x, y): Nusselt) -> f64 {
    let z = (1.0 - x * x - y * y).max(0.0).sqrt();
    atan2_fast(y.abs(), z)
}

/// Φ(p, h) of the path entering at offset h through scales tilted by α (the sign of
/// [`crate::nusselt`]), unwrapped like [`azimuthal_deflection`]; `None` where a smooth surface
/// blocks the path ([`nusselt::Blocked`]: the back of a scale, the wrong side, or an exit totally
/// reflected).
pub fn tilted_deflection(p: u32, theta_i: f64, alpha: f64, eta: f64, h: f64) -> Option<f64> {
    let tilt = Tilt::new(alpha);
    let d = incident(theta_i, h);
    let gamma_i = in_plane(d);
    let entry = AtScale::outside(tilt, d).ok()?;
    if p == 0 {
        let gamma_o = in_plane(entry.reflect().ok()?);
        return Some(-h.signum() * (gamma_i + gamma_o));
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
    Some(p as f64 * PI + h.signum() * (2.0 * chords - gamma_i - in_plane(exit)))
}

/// What the tilt adds to Bravais' Φ(p, h) taken with η′(θ_i): [`tilted_deflection`] less its
/// value at α = 0, and 0 untilted or where the smooth path is blocked. There the light a rough
/// surface lets through leaves by micro-normals far from the tilted scale's, which this
/// geometry does not describe, so it keeps Bravais' Φ. The tilted model adds the shift to the
/// Φ(p, h) of d'Eon et al. 2011's N_p, which takes η′ at θ_d, so that it is that N_p where α = 0.
pub fn deflection_shift(p: u32, theta_i: f64, alpha: f64, eta: f64, h: f64) -> f64 {
    if alpha == 0.0 {
        return 0.0;
    }
    match tilted_deflection(p, theta_i, alpha, eta, h) {
        Some(phi) => phi - azimuthal_deflection(p, h, eta_prime(eta, theta_i)),
        None => 0.0,
    }
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
                let mirror = crate::tilted_mirror::tilted_mirror(theta_i, alpha, h).phi;
                let Some(traced) = tilted_deflection(0, theta_i, alpha, 1.55, h) else {
                    continue;
                };
                compared += 1;
                assert!(
                    (crate::frame::wrap_pi(traced - mirror)).abs() < 1e-9,
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
                let a = deflection_shift(p, 0.75, -0.07, 1.55, h);
                let b = deflection_shift(p, 0.75, -0.07, 1.55, -h);
                assert!((a + b).abs() < 1e-12, "p {p} h {h}: {a} {b}");
                assert!(a.abs() > 1e-4, "the tilt moves Φ({p}, {h})");
                assert_eq!(deflection_shift(p, 0.75, 0.0, 1.55, h), 0.0);
            }
        }
    }
}
