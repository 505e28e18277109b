//! Shaping a grown centreline: pulling it toward its clump's guide, then waves and curls.

use crate::geometry::vertex_tangents;
use glam::Vec3;
use std::f32::consts::TAU;

/// Distance from the root over which waves and curls fade in, so roots stay on the scalp.
const FADE_IN_CM: f32 = 2.5;

/// Pulls `points` toward `guide` (matched by fraction of the strand), not at all at the root
/// and by `strength` at the tip.
pub fn clump_toward(points: &mut [Vec3], guide: &[Vec3], strength: f32) {
    let last = (points.len() - 1).max(1) as f32;
    for (k, p) in points.iter_mut().enumerate() {
        let t = k as f32 / last;
        let weight = strength * t.sqrt();
        *p = p.lerp(sample_at_fraction(guide, t), weight);
    }
}

/// The point a fraction `t` ∈ [0, 1] of the way along a polyline's vertex sequence.
fn sample_at_fraction(polyline: &[Vec3], t: f32) -> Vec3 {
    let x = t * (polyline.len() - 1) as f32;
    let i = (x.floor() as usize).min(polyline.len().saturating_sub(2));
    let next = (i + 1).min(polyline.len() - 1);
    polyline[i].lerp(polyline[next], x - i as f32)
}

/// A periodic sideways displacement along the strand.
#[derive(Clone, Copy, Debug)]
pub struct Wave {
    /// Peak displacement, centimetres.
    pub amplitude: f32,
    /// Distance along the strand of one period, centimetres.
    pub wavelength: f32,
    pub phase: f32,
}

/// A helix around the strand's centreline.
#[derive(Clone, Copy, Debug)]
pub struct Curl {
    pub radius: f32,
    /// Distance along the strand of one turn, centimetres.
    pub pitch: f32,
    pub phase: f32,
}

/// Adds the wave (swinging along `side`) and the curl (circling the centreline) to `points`.
pub fn add_wave_and_curl(points: &mut [Vec3], side: Vec3, wave: Wave, curl: Curl) {
    if wave.amplitude == 0.0 && curl.radius == 0.0 {
        return;
    }
    let mut tangents = vec![Vec3::ZERO; points.len()];
    vertex_tangents(points, &mut tangents);
    let mut arc = 0.0;
    let mut previous = points[0];
    for (p, tangent) in points.iter_mut().zip(tangents) {
        arc += p.distance(previous);
        previous = *p;
        let fade = smoothstep(arc / FADE_IN_CM);
        let across = (side - tangent * side.dot(tangent))
            .try_normalize()
            .unwrap_or(side);
        let around = tangent.cross(across);
        let wave_angle = TAU * arc / wave.wavelength + wave.phase;
        let curl_angle = TAU * arc / curl.pitch + curl.phase;
        let swing = across * (wave.amplitude * wave_angle.sin());
        let coil = (across * curl_angle.cos() + around * curl_angle.sin()) * curl.radius;
        *p += (swing + coil) * fade;
    }
}

fn smoothstep(x: f32) -> f32 {
    let x = x.clamp(0.0, 1.0);
    x * x * (3.0 - 2.0 * x)
}
