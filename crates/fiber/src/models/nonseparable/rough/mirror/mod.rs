//! R's azimuth off the rough surface: N_R spread by the micro-normals' slopes, and turned
//! inward where an offset's incidence grazes (docs/departures/11-r-rough-azimuth.md).
//!
//! d'Eon et al. 2011, and d'Eon et al. 2014 §2.3 after it, leave R without azimuthal roughness:
//! N_R = ½ |dh/dφ| A(0, h) at the offset whose mirror leaves at φ. The simulated surface
//! reflects each offset's light about a micro-normal drawn from its Beckmann slopes, weighted
//! as Walter et al. 2007 eq. 41 weighs it (the micro-normal's visibility ω_i·m / ω_i·n, Smith's
//! G1 on both sides, Fresnel at ω_i·m), and loses what it sends below the macro surface. So
//! each offset's light leaves spread in φ about its mirror, and where the offset's incidence
//! grazes (toward the fiber's edges, and at grazing θ_i) the visible micro-normals are those
//! turned toward the light, which turn the reflection inward, toward φ = 0.
//!
//! The model, step by step:
//! 1. [`azimuth_spread`]: at one (θ_i, γ) the mean μ and standard deviation s of the reflected
//!    azimuth about the smooth mirror's, over a product grid of equal-probability slopes with
//!    the simulator's weights. [`RoughMirror`] holds them on a (θ_i, γ) grid.
//! 2. [`RoughMirror::build`], the mixture: per θ_i node, N_R(φ) = ½ ∫ w(h) g(φ − φ_m(h) − μ;
//!    s) dh, g a wrapped Gaussian, w the rough surface's A(0, h) of step 1 or R's selection
//!    probability (found at step 1's nodes and linear between them), on a periodic grid of φ
//!    nodes, and with it the mean and variance of sin θ_o there, each offset's light a
//!    bivariate Gaussian in (φ, sin θ_o) about its mirror
//!    ([`ReflectionMoments::sine_given_offset`]). Under the selection probability this is the
//!    sampling density; the rest places step 3's quadrature.
//! 3. [`RoughMirror::build`], R's column: per θ_i node and every fourth φ node, the light
//!    reflected to φ by quadrature in micro-normal space ([`column`]): its energy, which is
//!    N_R for S, and the mean and variance of sin θ_o, matched by the lobe that has them
//!    ([`ConeLobe::from_sine_moments`]). Step 2's mixture alone is too wide in θ_o where the
//!    offsets graze, and its Gaussians in φ misplace N_R there
//!    (docs/departures/18-r-column-lobe.md).
//! 4. [`RoughMirror::density`] reads N_R and [`RoughMirror::lobe`] R's lobe bilinear in
//!    (θ_i, φ); [`RoughMirror::sample_phi`] draws φ_m(h) + μ + s z for the sampler's offset h,
//!    so the sampled density is the one step 2's table holds up to its interpolation.
//!
//! R's energy is that of step 1's A(0, h), the simulator's own weights (step 3's columns
//! integrate to it; `density_keeps_the_energy`): where the smooth mirror
//! off a tilted scale leaves below the macro surface, the rough surface still sends part of
//! the light out (the simulated R reaches past the smooth one there), which the smooth-mirror
//! reflectance of [`crate::models::nonseparable::scales::attenuation`] counts as lost. The lobe
//! selection keeps that reflectance: it is a proposal, which need not follow S exactly, only cover
//! it.

use crate::lobes::longitudinal::ConeLobe;
pub use crate::lobes::sine_lobe::SineMoments;
use crate::math::grid::{bilinear, fill_rows, locate};
use crate::math::{asin_fast, normal_pdf_fast, normal_quantile_fast, unit_normal_midpoints};
use crate::models::deon2011::azimuthal::Weighting;
use crate::models::nonseparable::cones::{cone_r, variance_r};
use crate::models::nonseparable::scales::mirror::tilted_mirror;
use crate::optics::beckmann::smith_g1;
use crate::optics::fresnel::fresnel_dielectric;
use column::{ReflectedColumn, RoughSurface};
use glam::DVec3;
use std::f64::consts::{FRAC_1_SQRT_2, FRAC_PI_2, PI};
use std::sync::OnceLock;

pub mod column;

/// Nodes over θ_i ∈ [−π/2, π/2] (as the selection table's) and over γ ∈ [−π/2, π/2].
const THETA_I_NODES: usize = 129;
const GAMMA_NODES: usize = 129;
/// Periodic nodes over φ ∈ [−π, π) for step 2's mixture, and for step 3's columns (every fourth).
const PHI_NODES: usize = 1024;
const COLUMN_PHI_NODES: usize = PHI_NODES / 4;
/// Standard deviations of sin θ_o on either side of its mean over which step 3 integrates a
/// column, the least standard deviation it takes, and how often it may set the range again.
const COLUMN_REACH: f64 = 8.0;
const LEAST_SINE_SD: f64 = 1e-5;
const COLUMN_PASSES: usize = 4;
/// The end nodes of θ_i are evaluated this far inside ±π/2, where the incident ray grazes.
const GRAZING: f64 = 1e-4;
/// Equal-probability slopes per axis in [`azimuth_spread`].
const SLOPES: usize = 16;
/// Standard deviations of a spread within which [`RoughMirror::build`] adds its Gaussian.
const REACH: f64 = 7.0;
/// Steps in γ of [`RoughMirror::energy`]'s rule: eight per node interval.
const ENERGY_STEPS: usize = 8 * (GAMMA_NODES - 1);

/// t taken modulo 1: t itself for the wrapped azimuths the model passes (t ∈ [0, 1)), without
/// the library's `fmod` there.
#[inline]
fn unit_period(t: f64) -> f64 {
    if (0.0..1.0).contains(&t) {
        t
    } else {
        t.rem_euclid(1.0)
    }
}

/// Roughness below which the spread is narrower than two φ nodes (s ≈ √2 β at normal
/// incidence): N_R stays the smooth mirror's there.
pub const LEAST_BETA: f64 = 0.01;

/// What R leaves with at one offset: how much, and its azimuth about the smooth mirror's.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AzimuthSpread {
    /// The share of the light reaching the offset that leaves by R (the micro-normal mean of
    /// Fresnel's reflectance, less what the micro-surface shadows or sends below the macro
    /// surface): A(0, h) off the rough surface.
    pub albedo: f64,
    /// Mean offset μ from the smooth mirror's azimuth (radians).
    pub mean: f64,
    /// Standard deviation s (radians).
    pub sd: f64,
}

/// The albedo-weighted sums over the slope grid of [`reflection_moments`], each divided by the
/// number of slopes: the albedo and the moments of the azimuth offset d from the smooth mirror's
/// and of z = sin θ_o. Linear in the weights, so a blend of two offsets' sums is the sums of
/// the two offsets' light together.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ReflectionMoments {
    /// A(0, h) off the rough surface: Σ w / n.
    pub albedo: f64,
    /// Σ w d / n.
    pub d: f64,
    /// Σ w d² / n.
    pub dd: f64,
    /// Σ w z / n.
    pub z: f64,
    /// Σ w z² / n.
    pub zz: f64,
    /// Σ w d z / n.
    pub dz: f64,
}

impl ReflectionMoments {
    /// The azimuth's albedo, mean and standard deviation; `None` where nothing reflects.
    pub fn spread(&self) -> Option<AzimuthSpread> {
        (self.albedo > 0.0).then(|| {
            let mean = self.d / self.albedo;
            AzimuthSpread {
                albedo: self.albedo,
                mean,
                sd: (self.dd / self.albedo - mean * mean).max(0.0).sqrt(),
            }
        })
    }

    /// The sums of `self` and `other` blended by `f` (0 gives `self`).
    fn lerp(&self, other: &Self, f: f64) -> Self {
        let l = |a: f64, b: f64| a + f * (b - a);
        Self {
            albedo: l(self.albedo, other.albedo),
            d: l(self.d, other.d),
            dd: l(self.dd, other.dd),
            z: l(self.z, other.z),
            zz: l(self.zz, other.zz),
            dz: l(self.dz, other.dz),
        }
    }

    /// sin θ_o of the light leaving at azimuth offset `d_at` from the smooth mirror, as a
    /// bivariate Gaussian in (d, z) has it: its mean z̄ + (c/s²)(d_at − d̄) and variance
    /// Var z − c²/s², for the covariance c of d and z and the azimuth's variance s² (`sd`,
    /// which the caller may have widened). `None` where nothing reflects.
    fn sine_given_offset(&self, d_at: f64, sd: f64) -> Option<SineMoments> {
        (self.albedo > 0.0).then(|| {
            let z = self.z / self.albedo;
            let d = self.d / self.albedo;
            let covariance = self.dz / self.albedo - d * z;
            let slope = covariance / (sd * sd);
            SineMoments {
                mean: z + slope * (d_at - d),
                variance: (self.zz / self.albedo - z * z - slope * covariance).max(0.0),
            }
        })
    }
}

/// What R reflects from the surface point at angle γ (h = sin γ) for light at θ_i, scales
/// tilted by α, Beckmann roughness β: the micro-normal m = n + s_t t + s_b b (normalised) for
/// slopes s_t, s_b of variance β²/2 each on an equal-probability grid, weighted by
/// (ω_i·m) G1(ω_i) G1(ω_o) F(ω_i·m) / ((ω_i·n)(m·n)), the reflections below the macro surface
/// left out. `None` where the light meets the back of the scale.
pub fn reflection_moments(
    theta_i: f64,
    alpha: f64,
    beta: f64,
    eta: f64,
    gamma: f64,
) -> Option<ReflectionMoments> {
    let (sa, ca) = alpha.sin_cos();
    let (sg, cg) = gamma.sin_cos();
    let n = DVec3::new(sa, ca * cg, -ca * sg);
    let t = DVec3::new(ca, -sa * cg, sa * sg);
    let b = DVec3::new(0.0, sg, cg);
    let macro_normal = DVec3::new(0.0, cg, -sg);
    let wi = DVec3::new(theta_i.sin(), theta_i.cos(), 0.0);
    let cos_i = wi.dot(n);
    if cos_i <= 0.0 {
        return None;
    }
    let mirror = 2.0 * cos_i * n - wi;
    let phi_m = mirror.z.atan2(mirror.y);
    let sigma = beta * FRAC_1_SQRT_2;
    let slopes = unit_slopes();
    let mut sums = ReflectionMoments::default();
    for &st in slopes {
        for &sb in slopes {
            let m = (n + sigma * (st * t + sb * b)).normalize();
            let c = wi.dot(m);
            if c <= 0.0 {
                continue;
            }
            let o = 2.0 * c * m - wi;
            if o.dot(macro_normal) <= 0.0 {
                continue;
            }
            let g = smith_g1(cos_i, c, beta) * smith_g1(o.dot(n), o.dot(m), beta);
            let w = c * g * fresnel_dielectric(c, eta) / (cos_i * m.dot(n));
            let d = crate::geometry::frame::wrap_pi(o.z.atan2(o.y) - phi_m);
            sums.albedo += w;
            sums.d += w * d;
            sums.dd += w * d * d;
            sums.z += w * o.x;
            sums.zz += w * o.x * o.x;
            sums.dz += w * d * o.x;
        }
    }
    let n = (SLOPES * SLOPES) as f64;
    Some(ReflectionMoments {
        albedo: sums.albedo / n,
        d: sums.d / n,
        dd: sums.dd / n,
        z: sums.z / n,
        zz: sums.zz / n,
        dz: sums.dz / n,
    })
}

/// The mean and standard deviation of the azimuth R leaves at ([`reflection_moments`]), and
/// its albedo. `None` where nothing reflects.
pub fn azimuth_spread(
    theta_i: f64,
    alpha: f64,
    beta: f64,
    eta: f64,
    gamma: f64,
) -> Option<AzimuthSpread> {
    reflection_moments(theta_i, alpha, beta, eta, gamma)?.spread()
}

/// [`SLOPES`] equal-probability slopes of unit variance.
fn unit_slopes() -> &'static [f64; SLOPES] {
    static SLOPES_ONCE: OnceLock<[f64; SLOPES]> = OnceLock::new();
    SLOPES_ONCE.get_or_init(unit_normal_midpoints::<SLOPES>)
}

/// The sums of [`reflection_moments`] at θ_i node `i`, linear in γ.
fn moments_at_node(moments: &[ReflectionMoments], i: usize, gamma: f64) -> ReflectionMoments {
    let (k0, fk) = locate((gamma + FRAC_PI_2) / PI, GAMMA_NODES);
    let at = i * GAMMA_NODES + k0;
    moments[at].lerp(&moments[at + 1], fk as f64)
}

/// N_R off the rough surface on (θ_i, φ) grids, S's and the sampler's, with R's longitudinal
/// lobe, and the spreads the sampler draws with on a (θ_i, γ) grid.
#[derive(Clone, Debug)]
pub struct RoughMirror {
    alpha: f64,
    /// [θ_i][γ] → (A, μ, s, R's selection probability).
    spreads: Vec<[f32; 4]>,
    /// [θ_i][φ] → N_R with R's selection probability (step 2).
    selection: Vec<[f32; 1]>,
    /// [θ_i][φ, every fourth node] → (the sine of R's cone plus sin θ_i, R's variance, N_R
    /// with A(0, h)) (step 3). The sine is stored about −sin θ_i, which it follows to within
    /// the scales' and the surface's deflection, so that the blend in θ_i is exact for the
    /// specular cone itself.
    columns: Vec<[f32; 3]>,
}

/// What step 2 leaves at one φ node: the mixture's N_R under R's selection probability, and
/// its mean and variance of sin θ_o (under A(0, h)) for step 3.
#[derive(Clone, Copy, Debug, Default)]
struct Texel {
    selection: f32,
    sine: Option<SineMoments>,
}

fn theta_i_node(i: usize) -> f64 {
    (-FRAC_PI_2 + PI * i as f64 / (THETA_I_NODES - 1) as f64)
        .clamp(-FRAC_PI_2 + GRAZING, FRAC_PI_2 - GRAZING)
}

fn gamma_node(k: usize) -> f64 {
    -FRAC_PI_2 + PI * k as f64 / (GAMMA_NODES - 1) as f64
}

/// Channels `c` of a table over θ_i nodes × `phi_nodes` periodic φ nodes, bilinear.
#[inline]
fn blend<const K: usize, const N: usize>(
    table: &[[f32; K]],
    phi_nodes: usize,
    theta_i: f64,
    phi: f64,
    c: [usize; N],
) -> [f64; N] {
    let (i0, fi) = locate((theta_i + FRAC_PI_2) / PI, THETA_I_NODES);
    let x = unit_period((phi + PI) / (2.0 * PI)) * phi_nodes as f64;
    let j0 = (x as usize).min(phi_nodes - 1);
    let fj = (x - j0 as f64) as f32;
    let j1 = (j0 + 1) % phi_nodes;
    // The four texels once, then each channel: a loop, not `c.map`, whose closure the
    // compiler left as a call per channel.
    let (low, high) = (i0 * phi_nodes, (i0 + 1) * phi_nodes);
    let [a, b, d, e] = [low + j0, low + j1, high + j0, high + j1].map(|at| &table[at]);
    let mut out = [0.0; N];
    for (o, &k) in out.iter_mut().zip(&c) {
        let row_low = a[k] + fj * (b[k] - a[k]);
        let row_high = d[k] + fj * (e[k] - d[k]);
        *o = (row_low + fi * (row_high - row_low)) as f64;
    }
    out
}

/// Row i of R's columns (step 3): at every fourth φ node, the column's energy and moments of
/// sin θ_o by quadrature ([`column_about`]), and the lobe that has them. Where no light
/// reaches the node, no energy, and d'Eon et al. 2014 §2.3's cone and eq. 6's variance.
fn fill_column_row(surface: &RoughSurface, i: usize, texels: &[Texel], row: &mut [[f32; 3]]) {
    let theta_i = theta_i_node(i);
    let sin_i = theta_i.sin();
    for (j, cell) in row.iter_mut().enumerate() {
        let phi = -PI + 2.0 * PI * j as f64 / COLUMN_PHI_NODES as f64;
        let column = texels[j * (PHI_NODES / COLUMN_PHI_NODES)]
            .sine
            .and_then(|guess| column_about(surface, theta_i, phi, guess));
        let lobe = match column {
            Some(c) => ConeLobe::from_sine_moments(c.sine.mean, c.sine.variance),
            None => ConeLobe::from_sin(
                variance_r(surface.beta, phi),
                cone_r(theta_i, surface.alpha, phi).sin(),
            ),
        };
        let energy = column.map_or(0.0, |c| c.energy);
        *cell = [lobe.sin_cone + sin_i, lobe.v, energy].map(|x| x as f32);
    }
}

/// The column at φ by [`RoughSurface::column`] over [`COLUMN_REACH`] standard deviations of
/// sin θ_o about its mean: first step 2's mixture's, then the quadrature's own, until the
/// range fits the column (its standard deviation within 30 % of the one that set the range
/// and its mean within one of them, so that the range spans 6 to 11 of its own standard
/// deviations): a range too wide under-resolves a narrow column, one too narrow cuts it, and
/// the mixture errs both ways where the offsets graze. Standard deviations are taken at least
/// [`LEAST_SINE_SD`].
fn column_about(
    surface: &RoughSurface,
    theta_i: f64,
    phi: f64,
    guess: SineMoments,
) -> Option<ReflectedColumn> {
    let (mut mean, mut sd) = (guess.mean, guess.variance.sqrt().max(LEAST_SINE_SD));
    let mut column = None;
    for _ in 0..COLUMN_PASSES {
        let reach = COLUMN_REACH * sd;
        let lo = (mean - reach).clamp(-1.0, 1.0).asin();
        let hi = (mean + reach).clamp(-1.0, 1.0).asin();
        let Some(c) = surface.column(theta_i, phi, lo, hi) else {
            break;
        };
        column = Some(c);
        let settled = c.sine.variance.sqrt().max(LEAST_SINE_SD);
        let done = (0.7..1.3).contains(&(settled / sd)) && (c.sine.mean - mean).abs() < sd;
        (mean, sd) = (c.sine.mean, settled);
        if done {
            break;
        }
    }
    column
}

impl RoughMirror {
    /// The tables for scales tilted by `alpha`, roughness `beta`, index `eta`, with R's
    /// selection probability given at (θ_i, h).
    pub fn build(
        alpha: f64,
        beta: f64,
        eta: f64,
        selection: impl Fn(f64, f64) -> f64 + Sync,
    ) -> Self {
        let nominal = std::f64::consts::SQRT_2 * beta;
        let mut moments = vec![ReflectionMoments::default(); THETA_I_NODES * GAMMA_NODES];
        fill_rows(&mut moments, GAMMA_NODES, |i, row| {
            let theta_i = theta_i_node(i);
            for (k, cell) in row.iter_mut().enumerate() {
                let gamma = gamma_node(k);
                *cell = reflection_moments(theta_i, alpha, beta, eta, gamma).unwrap_or_default();
            }
        });
        let spreads = moments
            .iter()
            .enumerate()
            .map(|(at, m)| {
                let s = m.spread().unwrap_or(AzimuthSpread {
                    albedo: 0.0,
                    mean: 0.0,
                    sd: nominal,
                });
                let sd = s.sd.max(0.25 * nominal);
                let (i, k) = (at / GAMMA_NODES, at % GAMMA_NODES);
                let chosen = selection(theta_i_node(i), gamma_node(k).sin());
                [s.albedo, s.mean, sd, chosen].map(|x| x as f32)
            })
            .collect();
        let mut table = Self {
            alpha,
            spreads,
            selection: Vec::new(),
            columns: vec![[0.0f32; 3]; THETA_I_NODES * COLUMN_PHI_NODES],
        };
        // Offsets fine enough that neighbouring mirrors (2Δγ apart) lie well inside the
        // narrowest spread.
        let offsets = ((8.0 * PI / nominal).ceil() as usize).clamp(256, 4096);
        let mut texels = vec![Texel::default(); THETA_I_NODES * PHI_NODES];
        fill_rows(&mut texels, PHI_NODES, |i, row| {
            table.fill_mixture_row(i, offsets, &moments, row);
        });
        let surface = RoughSurface::new(alpha, beta, eta);
        let mut columns = std::mem::take(&mut table.columns);
        fill_rows(&mut columns, COLUMN_PHI_NODES, |i, row| {
            let texels = &texels[i * PHI_NODES..(i + 1) * PHI_NODES];
            fill_column_row(&surface, i, texels, row);
        });
        table.columns = columns;
        table.selection = texels.iter().map(|t| [t.selection]).collect();
        table
    }

    /// Row i of step 2's mixture: each offset's Gaussian added at the φ nodes within [`REACH`]
    /// standard deviations of its centre, wrapped; and the mean and variance of sin θ_o over
    /// the light that reaches each node, each offset's light a bivariate Gaussian in
    /// (φ, sin θ_o) ([`ReflectionMoments::sine_given_offset`]).
    fn fill_mixture_row(
        &self,
        i: usize,
        offsets: usize,
        moments: &[ReflectionMoments],
        row: &mut [Texel],
    ) {
        let theta_i = theta_i_node(i);
        let d_gamma = PI / offsets as f64;
        let d_phi = 2.0 * PI / PHI_NODES as f64;
        // Per node: N_R under both weightings, then Σ w g E[z | φ] and Σ w g E[z² | φ].
        let mut sums = vec![[0.0f64; 4]; PHI_NODES];
        for g in 0..offsets {
            let gamma = -FRAC_PI_2 + (g as f64 + 0.5) * d_gamma;
            let h = gamma.sin();
            let half_dh = 0.5 * gamma.cos() * d_gamma;
            let (AzimuthSpread { albedo, mean, sd }, chosen) = self.spread_at_node(i, gamma);
            let w = [albedo, chosen];
            if w == [0.0, 0.0] {
                continue;
            }
            let sums_here = moments_at_node(moments, i, gamma);
            let mirror = tilted_mirror(theta_i, self.alpha, h).phi;
            let centre = mirror + mean;
            let first = ((centre - REACH * sd + PI) / d_phi).ceil() as i64;
            let last = ((centre + REACH * sd + PI) / d_phi).floor() as i64;
            for k in first..=last {
                let phi = -PI + k as f64 * d_phi;
                let g = normal_pdf_fast((phi - centre) / sd) / sd * half_dh;
                let cell = &mut sums[k.rem_euclid(PHI_NODES as i64) as usize];
                cell[0] += w[0] * g;
                cell[1] += w[1] * g;
                if let Some(z) = sums_here.sine_given_offset(phi - mirror, sd) {
                    cell[2] += w[0] * g * z.mean;
                    cell[3] += w[0] * g * (z.variance + z.mean * z.mean);
                }
            }
        }
        for (cell, sum) in row.iter_mut().zip(sums) {
            let mean = sum[2] / sum[0];
            *cell = Texel {
                selection: sum[1] as f32,
                sine: (sum[0] > 0.0).then(|| SineMoments {
                    mean,
                    variance: (sum[3] / sum[0] - mean * mean).max(0.0),
                }),
            };
        }
    }

    /// (A, μ, s) and R's selection probability at θ_i node `i`, linear in γ.
    fn spread_at_node(&self, i: usize, gamma: f64) -> (AzimuthSpread, f64) {
        let (k0, fk) = locate((gamma + FRAC_PI_2) / PI, GAMMA_NODES);
        let at = i * GAMMA_NODES + k0;
        let [a, b] = [self.spreads[at], self.spreads[at + 1]];
        let lerp = |k: usize| (a[k] + fk * (b[k] - a[k])) as f64;
        let spread = AzimuthSpread {
            albedo: lerp(0),
            mean: lerp(1),
            sd: lerp(2),
        };
        (spread, lerp(3))
    }

    /// R's energy at θ_i, ½ ∫ A(0, h) dh with step 1's albedo (bilinear in its table), by the
    /// midpoint rule in γ, eight steps per node interval: what S's N_R integrates to over φ.
    pub fn energy(&self, theta_i: f64) -> f64 {
        let d_gamma = PI / ENERGY_STEPS as f64;
        (0..ENERGY_STEPS)
            .map(|k| {
                let gamma = -FRAC_PI_2 + (k as f64 + 0.5) * d_gamma;
                self.spread(theta_i, gamma).albedo * gamma.cos()
            })
            .sum::<f64>()
            * 0.5
            * d_gamma
    }

    /// (A, μ, s) at (θ_i, γ), bilinear.
    fn spread(&self, theta_i: f64, gamma: f64) -> AzimuthSpread {
        let (i0, fi) = locate((theta_i + FRAC_PI_2) / PI, THETA_I_NODES);
        let (k0, fk) = locate((gamma + FRAC_PI_2) / PI, GAMMA_NODES);
        let [albedo, mean, sd, _] =
            bilinear(&self.spreads, i0 * GAMMA_NODES + k0, GAMMA_NODES, fi, fk);
        AzimuthSpread {
            albedo: albedo as f64,
            mean: mean as f64,
            sd: sd as f64,
        }
    }

    /// N_R at (θ_i, φ) under `weighting`, bilinear in θ_i and φ.
    #[inline]
    pub fn density(&self, theta_i: f64, phi: f64, weighting: Weighting) -> f64 {
        match weighting {
            Weighting::Attenuation => blend(&self.columns, COLUMN_PHI_NODES, theta_i, phi, [2])[0],
            Weighting::Selection => blend(&self.selection, PHI_NODES, theta_i, phi, [0])[0],
        }
    }

    /// R's longitudinal lobe at (θ_i, φ), bilinear in θ_i and φ, for light whose sin θ_i is
    /// `sin_theta_i`: the cone and variance that give it the mean and variance of sin θ_o over
    /// the light the rough surface reflects to φ.
    #[inline]
    pub fn lobe(&self, theta_i: f64, sin_theta_i: f64, phi: f64) -> ConeLobe {
        let [x, v] = blend(&self.columns, COLUMN_PHI_NODES, theta_i, phi, [0, 1]);
        ConeLobe::from_sin(v, x - sin_theta_i)
    }

    /// [`RoughMirror::lobe`] and S's N_R ([`RoughMirror::density`] under A(0, h)) from one
    /// read of the columns, for an evaluation that needs both.
    #[inline]
    pub fn column_at(&self, theta_i: f64, sin_theta_i: f64, phi: f64) -> (ConeLobe, f64) {
        let [x, v, n_r] = blend(&self.columns, COLUMN_PHI_NODES, theta_i, phi, [0, 1, 2]);
        (ConeLobe::from_sin(v, x - sin_theta_i), n_r)
    }

    /// R's azimuth for the sampler's offset h, whose smooth mirror leaves at `mirror_phi`:
    /// φ_m + μ + s Φ⁻¹(u).
    #[inline]
    pub fn sample_phi(&self, theta_i: f64, h: f64, mirror_phi: f64, u: f64) -> f64 {
        let AzimuthSpread { mean, sd, .. } = self.spread(theta_i, asin_fast(h.clamp(-1.0, 1.0)));
        mirror_phi + mean + sd * normal_quantile_fast(u.clamp(1e-16, 1.0 - 1e-16))
    }
}

#[cfg(test)]
mod tests;
