//! The Fresnel factors of a rough dielectric interface, averaged over its micro-normals: the
//! albedos ρ_r(v) and ρ_t(v) of Walter et al. 2007's rough dielectric BSDF (eqs. 20–21, with the
//! Beckmann D and the separable Smith G of [`crate::optics::beckmann`]) for light arriving at the
//! angle θ_v to the (shading) normal, from outside (relative index η) and from inside (1/η). It is
//! the interface `cuticle-sim` traces, seen in the mean.
//!
//! Why the fiber models need it: inside a fiber light meets the surface at the same angle at
//! every event (Bravais), and at grazing incidence that angle comes close to the critical angle
//! (38° at θ_i = 1.3 against 40° for η = 1.55). A smooth surface lets it all out; micro-normals
//! a few degrees off totally reflect a part of it back inside at every exit, which moves power
//! from TT and TRT to the long paths. The smooth Fresnel factor of d'Eon et al. 2011's A(p, h)
//! misses this; [`crate::models::nonseparable::scales::attenuation`] takes A(p, h) event by event
//! with ρ_r and ρ_t in place of F and 1 − F. 1 − ρ_r − ρ_t is what the micro-surface shadows
//! (Smith's G) and what a micro-normal sends to the wrong side.
//!
//! The mean is taken over the slopes, which are normal with variance β²/2 per axis (D(m) m·n
//! dω_m is that density in slope space), on a Fibonacci lattice of slopes drawn from a wider
//! law and weighted back to the slopes' own (`lattice_slopes`): it reaches the tails, whose
//! micro-normals alone let light out past the critical angle, and it is robust at the
//! total-internal-reflection edge, where a Gauss–Hermite rule would ring. The table is over
//! cos θ_v, read linearly.

use crate::math::grid::{SharedTables, shared_table};
use crate::math::normal_quantile;
use crate::optics::beckmann::smith_g1;
use crate::optics::fresnel::fresnel_dielectric;
use glam::DVec3;
use std::sync::{Arc, OnceLock};

/// Micro-normals per table entry, a Fibonacci number ([`lattice_slopes`]). A product grid of
/// 48² equal-probability slopes stopped at 2.3 standard deviations per axis.
const ALBEDO_SLOPES: usize = 2584;
/// Table entries over cos θ_v ∈ [0, 1].
const ENTRIES: usize = 1024;
/// The directions [`RoughInterface::refractions`] gives: the micro-normals of a Fibonacci
/// lattice (`lattice_slopes`). A product grid of 4² equal-probability slopes stopped at
/// 1.15 standard deviations per axis, short of the steep entries whose light alone leaves
/// where TT's exit is past the critical angle (docs/departures/26-tt-grazing-energy.md).
pub const REFRACTIONS: usize = 21;

/// How much wider than the slopes' own normal law the lattice's slopes are drawn
/// ([`lattice_slopes`]): the exit's cut (total internal reflection past the critical angle)
/// acts on the slopes' tails, which is where TT's skew and the light that escapes past the
/// critical angle come from, and a lattice in the law
/// itself reaches only Φ⁻¹(1/2n) of them.
const WIDENING: f64 = 1.5;
/// A micro-normal's slopes along the axis and around it, and its quadrature weight.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Slope {
    pub x: f64,
    pub y: f64,
    pub weight: f64,
}

/// `n` micro-normals' slopes in units of the slope law's deviation β/√2 (a Beckmann surface's
/// slopes are normal, variance β²/2 per axis), as a quadrature: the rank-1 lattice (Sloan &
/// Joe 1994) u_k = {(k + ½)(1, g)/n}, g the nearest integer to n/φ (the Fibonacci lattice
/// where n is a Fibonacci number), shifted by half a step so that it is centrally symmetric
/// (u_{n−1−k} = 1 − u_k), mapped through the normal quantile of a law [`WIDENING`] times
/// wider, each weighted by the ratio of the slopes' density to that law's, the weights scaled
/// to a mean of 1. A product grid of equal-probability midpoints (departure 22's rule) cut the
/// tails at Φ⁻¹(1/2n) per axis and missed TT's skewness by half (departure 23). The same
/// for every β, so found once per n and shared.
pub(crate) fn lattice_slopes(n: usize) -> Arc<Vec<Slope>> {
    static CACHE: SharedTables<usize, Vec<Slope>> = OnceLock::new();
    shared_table(&CACHE, n, || unit_lattice(n))
}

/// [`lattice_slopes`] computed.
fn unit_lattice(n: usize) -> Vec<Slope> {
    let generator = (n as f64 / ((1.0 + 5f64.sqrt()) / 2.0)).round() as usize;
    let mut slopes: Vec<Slope> = (0..n)
        .map(|k| {
            let u = (k as f64 + 0.5) / n as f64;
            let v = ((k as f64 + 0.5) * generator as f64 / n as f64).fract();
            let (zx, zy) = (normal_quantile(u), normal_quantile(v));
            // N(s; 1) / N(s; k) per axis, in the lattice's own standard normal z = s / k.
            let r2 = zx * zx + zy * zy;
            Slope {
                x: WIDENING * zx,
                y: WIDENING * zy,
                weight: (-0.5 * r2 * (WIDENING * WIDENING - 1.0)).exp(),
            }
        })
        .collect();
    let mean = slopes.iter().map(|s| s.weight).sum::<f64>() / n as f64;
    slopes.iter_mut().for_each(|s| s.weight /= mean);
    // Each axis centred and scaled to unit variance under the weights, so that where
    // the exit is linear in the slopes its mean and spread are exact.
    let moments = |axis: fn(&Slope) -> f64| {
        let m = slopes.iter().map(|s| s.weight * axis(s)).sum::<f64>() / n as f64;
        let v = slopes
            .iter()
            .map(|s| s.weight * (axis(s) - m).powi(2))
            .sum::<f64>()
            / n as f64;
        (m, if v > 0.0 { 1.0 / v.sqrt() } else { 1.0 })
    };
    let ((mx, kx), (my, ky)) = (moments(|s| s.x), moments(|s| s.y));
    for s in &mut slopes {
        (s.x, s.y) = ((s.x - mx) * kx, (s.y - my) * ky);
    }
    slopes
}

/// Where the power arriving at the interface goes, in the mean over its micro-normals.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Albedo {
    /// ρ_r: reflected back to the side it came from (total internal reflection included).
    pub reflected: f64,
    /// ρ_t: refracted through.
    pub transmitted: f64,
    /// The mean cosine to the normal of the reflected light, weighted by its power: cos θ_v
    /// for a smooth surface, less where the micro-normals that reflect most (past the critical
    /// angle) turn the light toward the surface.
    pub reflected_cos: f64,
}

impl Albedo {
    /// Shadowed or masked by the micro-surface, or sent by a micro-normal to the wrong side.
    pub fn lost(&self) -> f64 {
        (1.0 - self.reflected - self.transmitted).max(0.0)
    }

    /// The smooth interface's: F and 1 − F.
    pub fn smooth(cos_v: f64, eta: f64) -> Self {
        let f = fresnel_dielectric(cos_v, eta);
        Self {
            reflected: f,
            transmitted: 1.0 - f,
            reflected_cos: cos_v,
        }
    }
}

/// One side's albedos over cos θ_v.
#[derive(Clone, Debug)]
struct AlbedoTable {
    entries: Vec<Albedo>,
}

impl AlbedoTable {
    fn new(beta: f64, eta: f64, slopes: &[Slope]) -> Self {
        let entries = (0..=ENTRIES)
            .map(|k| albedo_by_quadrature(k as f64 / ENTRIES as f64, beta, eta, slopes))
            .collect();
        Self { entries }
    }

    fn at(&self, cos_v: f64) -> Albedo {
        let x = cos_v.clamp(0.0, 1.0) * ENTRIES as f64;
        let k = (x as usize).min(ENTRIES - 1);
        let t = x - k as f64;
        let (a, b) = (self.entries[k], self.entries[k + 1]);
        Albedo {
            reflected: a.reflected + t * (b.reflected - a.reflected),
            transmitted: a.transmitted + t * (b.transmitted - a.transmitted),
            reflected_cos: a.reflected_cos + t * (b.reflected_cos - a.reflected_cos),
        }
    }
}

/// The rough interface of a fiber of index η and Beckmann roughness β, both sides tabulated.
#[derive(Clone, Debug)]
pub struct RoughInterface {
    beta: f64,
    eta: f64,
    /// The coarse slope grid of [`RoughInterface::refractions`].
    /// The micro-normals' slopes of [`RoughInterface::refractions`], at this β.
    refraction_slopes: Vec<Slope>,
    outside: AlbedoTable,
    /// From inside, after 0, 1, … [`SPREAD_REFLECTIONS`] internal reflections.
    inside: Vec<AlbedoTable>,
}

/// Internal reflections after which the spread of directions they add is no longer followed.
const SPREAD_REFLECTIONS: usize = 6;
/// Equal-probability deviations per axis of the spread that internal reflections add.
const SPREAD_STEPS: usize = 16;

impl RoughInterface {
    /// Builds both sides' tables; [`RoughInterface::shared`] keeps one per (β, η).
    pub fn new(beta: f64, eta: f64) -> Self {
        // The lattice of n micro-normals at this β's slope deviation β/√2.
        let sd = beta * std::f64::consts::FRAC_1_SQRT_2;
        let scaled = |n: usize| -> Vec<Slope> {
            lattice_slopes(n)
                .iter()
                .map(|m| Slope {
                    x: m.x * sd,
                    y: m.y * sd,
                    weight: m.weight,
                })
                .collect()
        };
        let slopes = scaled(ALBEDO_SLOPES);
        Self {
            beta,
            eta,
            refraction_slopes: scaled(REFRACTIONS),
            outside: AlbedoTable::new(beta, eta, &slopes),
            inside: inside_tables(AlbedoTable::new(beta, 1.0 / eta, &slopes), beta),
        }
    }

    /// The interface for (β, η), built once per process and shared.
    pub fn shared(beta: f64, eta: f64) -> Arc<Self> {
        static CACHE: SharedTables<(u64, u64), RoughInterface> = OnceLock::new();
        shared_table(&CACHE, (beta.to_bits(), eta.to_bits()), || {
            Self::new(beta, eta)
        })
    }

    pub fn eta(&self) -> f64 {
        self.eta
    }

    /// Light arriving from outside the fiber at cos θ_v to the normal.
    pub fn outside(&self, cos_v: f64) -> Albedo {
        self.outside.at(cos_v)
    }

    /// Light arriving from inside the fiber at cos θ_v to the normal, after `reflections`
    /// internal reflections off the rough surface, each of which turned it by twice a
    /// micro-normal's slope: the albedo averaged over the spread of arriving directions that
    /// adds (variance 4kβ²/2 per axis after k), so that a path whose mean direction meets the
    /// exit short of the critical angle still partly reflects, as the paths it stands for do.
    pub fn inside_after(&self, cos_v: f64, reflections: usize) -> Albedo {
        self.inside[reflections.min(SPREAD_REFLECTIONS)].at(cos_v)
    }
}

/// A direction of travel a micro-normal refracts the arriving light into, with the share of
/// the arriving power it carries there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Refraction {
    /// In the frame of the arriving direction's (shading) normal, z < 0.
    pub travel: DVec3,
    pub weight: f64,
}

impl RoughInterface {
    /// The light refracted into the fiber, spread over the directions of a lattice of
    /// micro-normals ([`REFRACTIONS`]), each with its quadrature weight times
    /// `albedo_by_quadrature`'s transmitted term (0 where a micro-normal sends nothing in):
    /// where the mean of [`RoughInterface::outside`] keeps one direction, these keep how the
    /// entry's micro-normal tilts the path inside, which decides how near the critical angle
    /// each part meets the exit. `arriving` points away from the surface, z > 0.
    pub fn refractions(&self, arriving: DVec3) -> [Refraction; REFRACTIONS] {
        std::array::from_fn(|k| {
            let slope = &self.refraction_slopes[k];
            let m = DVec3::new(-slope.x, -slope.y, 1.0).normalize();
            match refraction_at(arriving, m, self.beta, self.eta) {
                Some((travel, weight)) => Refraction {
                    travel,
                    weight: weight * slope.weight / REFRACTIONS as f64,
                },
                None => Refraction {
                    travel: -DVec3::Z,
                    weight: 0.0,
                },
            }
        })
    }
}

/// The direction light arriving along `v` (pointing away, v.z > 0) refracts into through the
/// micro-normal m of a surface of relative index η, and its weight (v·m) G1(v, m) G1(t, m)
/// (1 − F) / (v.z m.z); none where m faces away, totally reflects, or sends it to the wrong
/// side.
pub(crate) fn refraction_at(v: DVec3, m: DVec3, beta: f64, eta: f64) -> Option<(DVec3, f64)> {
    let c = v.dot(m);
    if c <= 0.0 {
        return None;
    }
    let f = fresnel_dielectric(c, eta);
    if f >= 1.0 {
        return None;
    }
    let g = (eta * eta - 1.0 + c * c).sqrt();
    let travel = ((c - g) * m - v) / eta;
    if travel.z >= 0.0 {
        return None;
    }
    let weight = c * smith_g1(v.z, c, beta) * smith_g1(travel.z, travel.dot(m), beta) * (1.0 - f)
        / (v.z * m.z);
    Some((travel, weight))
}

/// The direction light arriving along `v` (pointing away, v.z > 0) reflects into off the
/// micro-normal m of a surface of relative index η (1/η from inside), and its weight
/// (v·m) G1(v, m) G1(r, m) F / (v.z m.z), the reflecting twin of [`refraction_at`] (Walter et
/// al. 2007 eq. 41 with the micro-normal drawn from D(m) m·n); none where m faces away or the
/// mirror direction r = 2(v·m)m − v points into the surface.
pub(crate) fn reflection_at(v: DVec3, m: DVec3, beta: f64, eta: f64) -> Option<(DVec3, f64)> {
    let c = v.dot(m);
    if c <= 0.0 {
        return None;
    }
    let r = 2.0 * c * m - v;
    if r.z <= 0.0 {
        return None;
    }
    let f = fresnel_dielectric(c, eta);
    let weight = c * smith_g1(v.z, c, beta) * smith_g1(r.z, c, beta) * f / (v.z * m.z);
    Some((r, weight))
}

/// The inside table after 0…[`SPREAD_REFLECTIONS`] reflections: the first averaged over the
/// arriving directions a spread of 2·slope per reflection gives.
fn inside_tables(base: AlbedoTable, beta: f64) -> Vec<AlbedoTable> {
    let mut tables = vec![];
    for k in 1..=SPREAD_REFLECTIONS {
        let deviations = slope_quantiles(2.0 * beta * (k as f64).sqrt(), SPREAD_STEPS);
        tables.push(base.spread(&deviations));
    }
    tables.insert(0, base);
    tables
}

impl AlbedoTable {
    /// This table averaged over arriving directions turned by the small angles `deviations`
    /// (in and out of the plane of incidence, a product grid).
    fn spread(&self, deviations: &[f64]) -> Self {
        let n = (deviations.len() * deviations.len()) as f64;
        let entries = (0..=ENTRIES)
            .map(|k| {
                let c = k as f64 / ENTRIES as f64;
                let s = (1.0 - c * c).max(0.0).sqrt();
                let mut sum = Albedo::default();
                for &dx in deviations {
                    for &dy in deviations {
                        // v turned by dx toward the normal's plane tangent and dy across it.
                        let v = DVec3::new(s + dx * c, dy, c - dx * s).normalize();
                        let a = self.at(v.z.max(0.0));
                        sum.reflected += a.reflected;
                        sum.transmitted += a.transmitted;
                        // The turn the micro-normals add, carried from v's own angle.
                        sum.reflected_cos += a.reflected * (a.reflected_cos - v.z + c);
                    }
                }
                Albedo {
                    reflected: sum.reflected / n,
                    transmitted: sum.transmitted / n,
                    reflected_cos: mean_cos(sum, c).clamp(0.0, 1.0),
                }
            })
            .collect();
        Self { entries }
    }
}

/// Slopes of equal probability under the normal law of variance β²/2: the midpoints of `n`
/// equal bins of probability.
pub(crate) fn slope_quantiles(beta: f64, n: usize) -> Vec<f64> {
    let sigma = beta * std::f64::consts::FRAC_1_SQRT_2;
    (0..n)
        .map(|k| sigma * normal_quantile((k as f64 + 0.5) / n as f64))
        .collect()
}

/// ρ_r and ρ_t at cos θ_v by the quadrature `slopes` (each weighted): the mean over micro-normals m
/// (density D(m) m·n) of (v·m)⁺ G1(v, m) G1(o, m) / (v·n m·n) times F(v·m) for the mirror
/// direction o and 1 − F for the refracted one (the weight `cuticle-sim` gives each sampled
/// micro-normal, Walter et al. 2007 eq. 41), where o lies on its own side of the surface.
fn albedo_by_quadrature(cos_v: f64, beta: f64, eta: f64, slopes: &[Slope]) -> Albedo {
    if cos_v <= 0.0 {
        return Albedo {
            reflected: 1.0,
            transmitted: 0.0,
            reflected_cos: 0.0,
        };
    }
    let v = DVec3::new((1.0 - cos_v * cos_v).max(0.0).sqrt(), 0.0, cos_v);
    let mut sum = Albedo::default();
    for slope in slopes {
        {
            let m = DVec3::new(-slope.x, -slope.y, 1.0).normalize();
            let c = v.dot(m);
            if c <= 0.0 {
                continue;
            }
            let g_in = smith_g1(cos_v, c, beta);
            let weight = slope.weight * c * g_in / (cos_v * m.z);
            let f = fresnel_dielectric(c, eta);
            let reflected = 2.0 * c * m - v;
            if reflected.z > 0.0 {
                let power = weight * f * smith_g1(reflected.z, reflected.dot(m), beta);
                sum.reflected += power;
                sum.reflected_cos += power * reflected.z;
            }
            if let Some((_, transmitted)) = refraction_at(v, m, beta, eta) {
                sum.transmitted += slope.weight * transmitted;
            }
        }
    }
    let n = slopes.len() as f64;
    Albedo {
        reflected: sum.reflected / n,
        transmitted: sum.transmitted / n,
        reflected_cos: mean_cos(sum, cos_v),
    }
}

/// The power-weighted mean cosine out of a sum whose `reflected_cos` holds Σ power × cosine.
fn mean_cos(sum: Albedo, fallback: f64) -> f64 {
    if sum.reflected > 0.0 {
        sum.reflected_cos / sum.reflected
    } else {
        fallback
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// As β → 0 the rough interface is the smooth one, on both sides, away from the critical
    /// angle (where the smooth factor jumps).
    #[test]
    fn a_nearly_smooth_interface_has_the_smooth_fresnel_factors() {
        let rough = RoughInterface::new(1e-4, 1.55);
        let critical = (1.0 - 1.0 / (1.55f64 * 1.55)).sqrt();
        for k in 1..100 {
            let c = k as f64 / 100.0;
            let smooth_out = Albedo::smooth(c, 1.55);
            let out = rough.outside(c);
            assert!(
                (out.reflected - smooth_out.reflected).abs() < 2e-3,
                "out {c}: {out:?}"
            );
            assert!((out.transmitted - smooth_out.transmitted).abs() < 2e-3);
            if (c - critical).abs() > 0.01 {
                let smooth_in = Albedo::smooth(c, 1.0 / 1.55);
                let inside = rough.inside_after(c, 0);
                assert!(
                    (inside.reflected - smooth_in.reflected).abs() < 2e-3,
                    "in {c}: {inside:?} vs {smooth_in:?}"
                );
            }
        }
    }

    /// A rougher surface lets out some light beyond the smooth critical angle and reflects some
    /// short of it: near the critical angle inside, ρ_r moves from F toward its mean over the
    /// micro-normals. Also the table agrees with a finer grid (the rule has converged).
    #[test]
    fn roughness_blurs_the_critical_angle_and_the_grid_has_converged() {
        let (beta, eta) = (0.04, 1.55);
        let rough = RoughInterface::new(beta, eta);
        let critical = (1.0 - 1.0 / (eta * eta)).sqrt();
        // cos θ_v just under the critical cosine: past the critical angle, where a smooth
        // surface reflects everything; just over it: short of it, where a smooth one lets most out.
        let past = rough.inside_after(critical - 0.01, 0);
        let short = rough.inside_after(critical + 0.01, 0);
        assert!(past.transmitted > 0.02, "{past:?}");
        assert!(short.reflected > Albedo::smooth(critical + 0.01, 1.0 / eta).reflected + 0.02);
        // A product grid of 200² equal-probability slopes, each of weight 1.
        let axis = slope_quantiles(beta, 200);
        let fine: Vec<Slope> = axis
            .iter()
            .flat_map(|&x| axis.iter().map(move |&y| Slope { x, y, weight: 1.0 }))
            .collect();
        for c in [0.2, critical - 0.01, critical + 0.01, 0.9] {
            for (side, e) in [
                (rough.outside(c), eta),
                (rough.inside_after(c, 0), 1.0 / eta),
            ] {
                let want = albedo_by_quadrature(c, beta, e, &fine);
                assert!(
                    (side.reflected - want.reflected).abs() < 3e-3
                        && (side.transmitted - want.transmitted).abs() < 3e-3,
                    "cos {c} η {e}: {side:?} vs {want:?}"
                );
            }
        }
    }
}
