//! The fit's unknowns: per light a unit centre ω_j, a sharpness κ_j = 2/λ_j² and a non-negative
//! RGB coefficient L_j, plus the local coordinates the Levenberg–Marquardt step moves them in.

use crate::SrbfLight;
use crate::srbf::bandwidth_of;
use glam::DVec3;

#[derive(Clone, Debug)]
pub struct Params {
    pub dirs: Vec<DVec3>,
    pub kappas: Vec<f64>,
    pub coefs: Vec<DVec3>,
}

/// An orthonormal tangent pair (t1, t2) at a centre: a step (a, b) moves ω_j to
/// normalise(ω_j + a t1 + b t2), so ∂ω_j/∂a = t1 and ∂ω_j/∂b = t2 at a = b = 0.
#[derive(Clone, Copy, Debug)]
pub struct Frame {
    pub t1: DVec3,
    pub t2: DVec3,
}

impl Frame {
    pub fn at(dir: DVec3) -> Self {
        let helper = if dir.y.abs() < 0.9 {
            DVec3::Y
        } else {
            DVec3::X
        };
        let t1 = helper.cross(dir).normalize();
        Self {
            t1,
            t2: dir.cross(t1),
        }
    }
}

/// The step of one light in local coordinates: tangent offsets (a, b), Δ ln κ, and ΔL_j.
#[derive(Clone, Copy, Debug, Default)]
pub struct LightStep {
    pub tangent: [f64; 2],
    pub log_kappa: f64,
    pub coef: DVec3,
}

/// Largest move of a centre in one step, radians (keeps the tangent-plane chart honest).
const MAX_TURN: f64 = 0.5;
/// Largest change of ln κ in one step.
const MAX_LOG_KAPPA_STEP: f64 = 2.0;

impl Params {
    pub fn len(&self) -> usize {
        self.dirs.len()
    }

    pub fn frames(&self) -> Vec<Frame> {
        self.dirs.iter().map(|&d| Frame::at(d)).collect()
    }

    /// These parameters moved by `steps`, with κ kept in `kappa_range` and coefficients ≥ 0.
    pub fn stepped(&self, frames: &[Frame], steps: &[LightStep], kappa_range: (f64, f64)) -> Self {
        let mut next = self.clone();
        for (j, step) in steps.iter().enumerate() {
            let [a, b] = step.tangent;
            let turn = (a * a + b * b).sqrt();
            let shrink = if turn > MAX_TURN {
                MAX_TURN / turn
            } else {
                1.0
            };
            let moved = self.dirs[j] + (frames[j].t1 * a + frames[j].t2 * b) * shrink;
            next.dirs[j] = moved.normalize();
            let d_log = step
                .log_kappa
                .clamp(-MAX_LOG_KAPPA_STEP, MAX_LOG_KAPPA_STEP);
            next.kappas[j] = (self.kappas[j] * d_log.exp()).clamp(kappa_range.0, kappa_range.1);
            next.coefs[j] = (self.coefs[j] + step.coef).max(DVec3::ZERO);
        }
        next
    }

    /// (centre, bandwidth λ) of every light that shines.
    pub fn lobes(&self) -> Vec<(DVec3, f64)> {
        (0..self.len())
            .filter(|&j| self.coefs[j].max_element() > 0.0)
            .map(|j| (self.dirs[j], bandwidth_of(self.kappas[j])))
            .collect()
    }

    pub fn to_lights(&self) -> Vec<SrbfLight> {
        (0..self.len())
            .map(|j| SrbfLight {
                direction: self.dirs[j].as_vec3().normalize(),
                bandwidth: bandwidth_of(self.kappas[j]) as f32,
                coefficient: self.coefs[j].as_vec3(),
            })
            .collect()
    }

    /// Lights sorted by decreasing power ∫ L_j G_j dω (luminance), which is how reports list them.
    pub fn to_sorted_lights(&self) -> Vec<SrbfLight> {
        let mut lights = self.to_lights();
        let power =
            |l: &SrbfLight| crate::color::luminance(l.coefficient) as f64 * l.basis_integral();
        lights.sort_by(|a, b| power(b).total_cmp(&power(a)));
        lights
    }
}
