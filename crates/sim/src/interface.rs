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
    #[inline(always)]
    pub fn scatter(&self, wi: DVec3, ng: DVec3, frame: &ShadingFrame, rng: &mut Sampler) -> Event {
        let cos_i = wi.dot(frame.n);
        if cos_i <= 0.0 {
            return Event::BackFacing;
        }
        let (xi, choice) = rng.pair();
        let local = sample_normal(self.beta, xi, rng.disk());
        let m = frame.to_world(local);
        let c = wi.dot(m);
        if c <= 0.0 {
            return Event::Shadowed;
        }
        let f = fresnel(c, self.eta);
        let refracted = !f.reflects(choice);
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::beckmann::distribution;
    use crate::dielectric::fresnel;
    use std::f64::consts::PI;

    /// Reflection and transmission albedos ∫ f |o·n| dω_o of a flat rough interface (n = +z) by
    /// quadrature of Walter 2007's BSDF: f_r = F G D / (4 |i·n||o·n|) (eq. 20) and
    /// f_t = |i·h||o·h| η² (1 − F) G D / (|i·n||o·n| (i·h + η o·h)²) (eq. 21, η = η_o/η_i).
    fn albedos(wi: DVec3, beta: f64, eta: f64) -> (f64, f64) {
        let g = |v: DVec3, m: DVec3| smith_g1(v.z, v.dot(m), beta);
        let (nt, np) = (1500, 600);
        let (dt, dp) = (PI / nt as f64, 2.0 * PI / np as f64);
        let (mut rho_r, mut rho_t) = (0.0, 0.0);
        for a in 0..nt {
            let t = (a as f64 + 0.5) * dt;
            for b in 0..np {
                let p = (b as f64 + 0.5) * dp;
                let o = DVec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos());
                let d_omega = t.sin() * dt * dp;
                if o.z > 0.0 {
                    let h = (wi + o).normalize();
                    let f = fresnel(wi.dot(h), eta).reflectance();
                    let fr = f * g(wi, h) * g(o, h) * distribution(h.z, beta) / (4.0 * wi.z * o.z);
                    rho_r += fr * o.z * d_omega;
                } else {
                    let mut h = -(wi + eta * o).normalize();
                    if h.z < 0.0 {
                        h = -h;
                    }
                    let (ih, oh) = (wi.dot(h), o.dot(h));
                    if ih <= 0.0 || oh >= 0.0 {
                        continue;
                    }
                    let f = fresnel(ih, eta).reflectance();
                    let denom = (ih + eta * oh).powi(2);
                    let ft = ih
                        * oh.abs()
                        * eta
                        * eta
                        * (1.0 - f)
                        * g(wi, h)
                        * g(o, h)
                        * distribution(h.z, beta)
                        / (wi.z * o.z.abs() * denom);
                    rho_t += ft * o.z.abs() * d_omega;
                }
            }
        }
        (rho_r, rho_t)
    }

    /// The sampled weights (eq. 41) average to the same albedos as the BSDF they stand for,
    /// reflection and transmission apart, entering and leaving the denser medium: this catches a
    /// wrong Jacobian, a wrong G or a wrong Fresnel split, which the fiber's energy balance cannot.
    #[test]
    fn sampled_weights_reproduce_walter_albedos() {
        let frame = ShadingFrame {
            t: DVec3::X,
            b: DVec3::Y,
            n: DVec3::Z,
        };
        for (beta, eta, theta) in [(0.3, 1.55, 1.0), (0.3, 1.0 / 1.55, 0.5), (0.1, 1.55, 1.3)] {
            let wi = DVec3::new(f64::sin(theta), 0.0, f64::cos(theta));
            let surface = Surface::new(beta, eta);
            let mut rng = Sampler::for_chunk(17, 0);
            let n = 2_000_000;
            let (mut mc_r, mut mc_t) = (0.0, 0.0);
            for _ in 0..n {
                if let Event::Scattered {
                    factor, refracted, ..
                } = surface.scatter(wi, DVec3::Z, &frame, &mut rng)
                {
                    if refracted {
                        mc_t += factor
                    } else {
                        mc_r += factor
                    }
                }
            }
            let (mc_r, mc_t) = (mc_r / n as f64, mc_t / n as f64);
            let (q_r, q_t) = albedos(wi, beta, eta);
            assert!(
                (mc_r - q_r).abs() < 0.01 * q_r + 5e-4 && (mc_t - q_t).abs() < 0.01 * q_t + 5e-4,
                "β {beta} η {eta} θ {theta}: sampled R {mc_r:.5} T {mc_t:.5}, quadrature R {q_r:.5} T {q_t:.5}"
            );
        }
    }
}
