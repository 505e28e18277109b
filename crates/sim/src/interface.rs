//! One event at the rough fiber surface: sample a micro-normal, choose reflection or refraction
//! in proportion to Fresnel, and weight the result (Walter et al. 2007 §5.3).

use crate::beckmann::{sample_normal, smith_g1};
use crate::dielectric::{fresnel, reflect, refract};
use crate::rng::Sampler;
use crate::scale::ShadingFrame;
use glam::DVec3;

/// The rough dielectric surface seen from one side: Beckmann roughness β and relative index
/// η = η_t/η_i (the far side's index over the near side's).
#[derive(Clone, Copy, Debug)]
pub struct Surface {
    beta: f64,
    eta: f64,
    inv_eta: f64,
}

/// What happened at the surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Event {
    /// The ray leaves the surface along `dir`, its weight multiplied by `factor`.
    Scattered {
        dir: DVec3,
        factor: f64,
        refracted: bool,
    },
    /// The ray met the back of a tilted scale (it lies behind the shading normal): all lost.
    BackFacing,
    /// Shadowed or masked by the micro-surface, or sent to the wrong side of the macro surface.
    Shadowed,
}

impl Surface {
    pub fn new(beta: f64, eta: f64) -> Self {
        Self {
            beta,
            eta,
            inv_eta: 1.0 / eta,
        }
    }

    /// Scatters the ray arriving from direction `wi` (pointing back toward where it came from)
    /// at a surface point with macro normal `ng` and shading frame `frame`, both on wi's side.
    ///
    /// Micro-normals are drawn from D(m)|m·n_s| and the weight is
    /// |i·m| G1(i,m) G1(o,m) / (|i·n_s| |m·n_s|) (Walter 2007 eq. 41 with the separable Smith
    /// G of eq. 23); reflection is chosen with probability F (eq. 22), refraction otherwise.
    /// A direction on the wrong side of the macro surface counts as shadowed.
    pub fn scatter(&self, wi: DVec3, ng: DVec3, frame: &ShadingFrame, rng: &mut Sampler) -> Event {
        let cos_i = wi.dot(frame.n);
        if cos_i <= 0.0 {
            return Event::BackFacing;
        }
        let local = sample_normal(self.beta, rng.uniform(), rng.disk());
        let m = frame.to_world(local);
        let c = wi.dot(m);
        if c <= 0.0 {
            return Event::Shadowed;
        }
        let f = fresnel(c, self.eta);
        let refracted = !f.reflects(rng.uniform());
        let dir = if refracted {
            refract(wi, m, c, f.g, self.inv_eta)
        } else {
            reflect(wi, m)
        };
        if (dir.dot(ng) < 0.0) != refracted {
            return Event::Shadowed;
        }
        let g = smith_g1(cos_i, c, self.beta) * smith_g1(dir.dot(frame.n), dir.dot(m), self.beta);
        if g == 0.0 {
            return Event::Shadowed;
        }
        Event::Scattered {
            dir,
            factor: c * g / (cos_i * local.z),
            refracted,
        }
    }
}
