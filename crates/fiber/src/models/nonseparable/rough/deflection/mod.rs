//! TT's azimuth through a rough surface, offset by offset: where the light entering at h
//! leaves in φ, and how far it spreads there, in the mean over the micro-normals of both of
//! its events. The project's own extension of d'Eon et al. 2014, whose N_TT centres every
//! offset's light on the smooth path's Φ(1, h) with one azimuthal variance β²/2 (§2.4).
//!
//! Why: near the offsets where the smooth path is blocked or grazes, the light a rough surface
//! lets through keeps moving smoothly with h, and spreads wider in φ than β/√2
//! (docs/departures/20-tt-rough-azimuth.md). Checked against the simulator in
//! `crates/validate/tests/rough_tt_azimuth.rs`.
//!
//! The path: the entry's micro-normals refract the light into a spread of chords (a lattice
//! of slopes, `lattice_slopes`, each with Walter et al. 2007's transmission weight, as
//! [`crate::optics::rough_interface`] takes them); each chord meets the exit's scale
//! ([`AtScale::inside`]), whose micro-normals refract it out on a finer lattice. Each exit's
//! in-plane angles give its Φ = π + γ′ − γ_i + γ′ − γ_o, signed as
//! [`crate::models::nonseparable::scales::deflection`] takes them, and the weighted mean and
//! standard deviation over every (entry, exit) pair are the offset's. [`RoughTtTable`] holds them
//! over (θ_i, γ = asin h) for one fiber, read bilinearly; the model's N_TT, its azimuthal table and
//! its sampler all read that one table, so they agree with each other exactly.
//!
//! The same pairs give each exit's sine x = sin θ_o. TT's longitudinal lobe at a column φ is
//! the mean, spread and skewness of x over the light that reaches φ from every offset
//! ([`RoughTtTable::column_sine`]): each pair is followed from offset to offset (its weight,
//! x and φ linear between the table's nodes) and binned by the column it reaches (departures
//! 22 and 23). Near the edge an offset's light that lands away from its Φ left at another
//! inclination, which keeps the columns' lobes where the simulation has them though each
//! offset's mean x drifts toward the equator there; departure 21 took that as a bivariate
//! normal in (x, φ) per offset, which the pairs themselves replace. Where the lobe whose
//! moments those are misses the light itself (by `FIT_GOOD_ENOUGH` in L1), the column
//! holds instead the mean, spread and skewness whose lobe lies nearest it (`fit_column`;
//! departure 27): near the pole the light is cut, and matching the third moment lets the cut
//! tails set the whole lobe. The fit also sets where the lobe ends, its reach: the light that
//! would leave nearest the pole meets the exit's scale at grazing or from behind, so the
//! column's light stops short of the pole, more steeply than any one Gaussian tail falls
//! (departure 28).

use crate::geometry::bravais::{azimuthal_deflection, eta_prime};
use crate::geometry::nusselt::{self, AtScale, Nusselt, Tilt};
use crate::lobes::sine_lobe::{FULL_REACH, SineMoments, SkewedSine, SkewedSineLobe};
use crate::math::grid::{SharedTables, fill_rows, locate, shared_table};
use crate::math::{asin_fast, atan2_fast};
use crate::models::nonseparable::scales::attenuation::incident;
use crate::optics::rough_interface::{Slope, lattice_slopes, refraction_at};
use glam::DVec3;
use std::f64::consts::{FRAC_PI_2, PI};
use std::sync::{Arc, OnceLock};

/// The table's quadrature: 21 micro-normals at the entry and 144 at the exit, each a
/// Fibonacci lattice (`coarse_rule_follows_the_fine_one`).
pub const TABLE_RULE: Rule = Rule {
    entry: 21,
    exit: 144,
};

/// Micro-normals per event of a quadrature, entry × exit pairs: each set the rank-1 lattice
/// of that many points in the unit square whose generator is the nearest integer to n/φ (the
/// Fibonacci lattice where n is a Fibonacci number), mapped to slopes by `lattice_slopes`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Rule {
    pub entry: usize,
    pub exit: usize,
}

/// Where TT's light entering at one offset leaves, in the mean over the micro-normals.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoughExit {
    /// The mean Φ(1, h), unwrapped like [`azimuthal_deflection`].
    pub phi: f64,
    /// The standard deviation of φ about it.
    pub sigma: f64,
    /// The mean exit sine sin θ_o.
    pub sin_theta: f64,
    /// The standard deviation of the exit sine.
    pub sin_theta_sd: f64,
    /// The covariance of the exit sine with φ.
    pub covariance: f64,
    /// The share of the light that reaches the exit and leaves there, unabsorbed (the
    /// quadrature's A(1, h) at μ_a = 0).
    pub transmitted: f64,
}

/// The in-plane angle of a Nusselt direction to its normal, signed by `sign`.
fn in_plane_signed((x, y): Nusselt, sign: f64) -> f64 {
    let z = (1.0 - x * x - y * y).max(0.0).sqrt();
    atan2_fast(y * sign, z)
}

/// The signs that make the chord's and the exit's in-plane angles positive on the smooth path
/// at a small offset of sign s, the convention in which Φ = π + s (2γ′ − γ_i − γ_o): (−s, −s),
/// wherever that path leaves (`in_plane_signs_follow_the_smooth_path`), and kept where it is
/// blocked, where the rough surface still lets light out.
fn in_plane_signs(s: f64) -> (f64, f64) {
    (-s, -s)
}

/// TT's exit at offset h through scales tilted by α on a surface of Beckmann roughness β, by
/// `rule` (module documentation); `None` where no light leaves.
pub fn rough_tt_exit(
    theta_i: f64,
    alpha: f64,
    eta: f64,
    beta: f64,
    h: f64,
    rule: Rule,
) -> Option<RoughExit> {
    let mut pairs = Vec::new();
    exit_pairs(theta_i, alpha, eta, beta, h, rule, &mut pairs);
    RoughExit::of_pairs(&pairs)
}

/// One (entry, exit) pair of micro-normals of [`exit_pairs`]: its weight, 0 where the light
/// does not leave, and where it leaves (x = sin θ_o, φ unwrapped like [`azimuthal_deflection`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct ExitPair {
    weight: f64,
    sin_theta: f64,
    phi: f64,
}

/// Every (entry, exit) pair of `rule` at offset h, in a fixed order (so that the pairs at two
/// offsets match one for one), into `pairs`; a pair whose light does not leave has weight 0,
/// and every pair has weight 0 where the light does not enter.
fn exit_pairs(
    theta_i: f64,
    alpha: f64,
    eta: f64,
    beta: f64,
    h: f64,
    rule: Rule,
    pairs: &mut Vec<ExitPair>,
) {
    pairs.clear();
    let count = rule.entry * rule.exit;
    let tilt = Tilt::new(alpha);
    let s = if h < 0.0 { -1.0 } else { 1.0 };
    let (chord_sign, exit_sign) = in_plane_signs(s);
    let d = incident(theta_i, h);
    let gamma_i = in_plane_signed(d, s);
    let Ok(entry) = AtScale::outside(tilt, d) else {
        pairs.resize(count, ExitPair::default());
        return;
    };
    let (entry_slopes, exit_slopes) = (lattice_slopes(rule.entry), lattice_slopes(rule.exit));
    // The micro-normal of unit-law slopes `m` on this surface.
    let sd = beta * std::f64::consts::FRAC_1_SQRT_2;
    let normal = |m: &Slope| DVec3::new(-sd * m.x, -sd * m.y, 1.0).normalize();
    // The chord an entry micro-normal refracts the light into, where it meets the exit's
    // scale, and the entry's weight.
    let chord_at = |m: &Slope| {
        let (into, w_in) = refraction_at(entry.arriving(), normal(m), beta, eta)?;
        let chord = entry.leaving(into).ok()?;
        let exit = AtScale::inside(tilt, nusselt::propagate(chord)).ok()?;
        Some((chord, exit, w_in * m.weight))
    };
    for m_in in entry_slopes.iter() {
        let Some((chord, exit, w_in)) = chord_at(m_in) else {
            pairs.extend(std::iter::repeat_n(ExitPair::default(), rule.exit));
            continue;
        };
        let twice_chord = 2.0 * in_plane_signed(chord, chord_sign);
        let leave = |m: &Slope| {
            let (out, w_out) = refraction_at(exit.arriving(), normal(m), beta, 1.0 / eta)?;
            let leaving = exit.leaving(out).ok()?;
            Some(ExitPair {
                weight: w_in * w_out * m.weight,
                sin_theta: leaving.0,
                phi: PI + s * (twice_chord - gamma_i - in_plane_signed(leaving, exit_sign)),
            })
        };
        pairs.extend(exit_slopes.iter().map(|m| leave(m).unwrap_or_default()));
    }
}

impl RoughExit {
    /// The weighted moments of an offset's [`exit_pairs`]; `None` where no light leaves.
    fn of_pairs(pairs: &[ExitPair]) -> Option<Self> {
        let mut sums = [0.0; 6];
        for &ExitPair {
            weight: w,
            sin_theta: x,
            phi,
        } in pairs.iter().filter(|p| p.weight > 0.0)
        {
            sums[0] += w;
            sums[1] += w * phi;
            sums[2] += w * phi * phi;
            sums[3] += w * x;
            sums[4] += w * x * x;
            sums[5] += w * x * phi;
        }
        let [w, phi, phi2, sin, sin2, sin_phi] = sums;
        // w is a sum of non-negative weights: not positive means no light left (or NaN input).
        if w.is_nan() || w <= 0.0 {
            return None;
        }
        let (mean, sin_mean) = (phi / w, sin / w);
        Some(RoughExit {
            phi: mean,
            sigma: (phi2 / w - mean * mean).max(0.0).sqrt(),
            sin_theta: sin_mean,
            sin_theta_sd: (sin2 / w - sin_mean * sin_mean).max(0.0).sqrt(),
            covariance: sin_phi / w - sin_mean * mean,
            transmitted: w / pairs.len() as f64,
        })
    }
}

/// Nodes over θ_i ∈ [−π/2, π/2] and over γ = asin |h| ∈ [0, π/2].
const THETA_I_NODES: usize = 129;
const GAMMA_NODES: usize = 65;

/// What a rough surface makes of TT's azimuth at one (θ_i, h): the shift from Bravais' Φ(1, h)
/// at θ_d = −θ_i to the mean exit's φ, and the standard deviation in φ.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoughAzimuth {
    pub shift: f64,
    pub sigma: f64,
}

/// [`rough_tt_exit`] over (θ_i, γ = asin |h|) for one fiber (η, α, β), by [`TABLE_RULE`]: the
/// shift is odd in h, Φ is 2π less its value at −h, and the rest is even (the fiber is
/// symmetric about the plane of incidence), so γ runs over [0, π/2] alone.
#[derive(Clone, Debug)]
pub struct RoughTtTable {
    /// Per node, the shift and σ.
    texels: Vec<[f32; 2]>,
    /// The largest σ of any node: how far a lobe can reach.
    sigma_max: f64,
    /// Per θ_i node and column of |φ|, TT's lobe in the exit sine there ([`ColumnLobe`],
    /// [`RoughTtTable::column_sine`]).
    columns: Vec<[f32; 4]>,
}

/// A column's lobe as the table holds it: the mean, standard deviation and skewness of the
/// exit sine, and the lobe's reach (where it ends, [`SkewedSine::reach`]).
type ColumnLobe = [f64; 4];

/// Columns over |φ| ∈ [0, π] of [`RoughTtTable::column_sine`].
const COLUMNS: usize = 129;
/// Steps of γ between two nodes at which the pairs are followed into the columns.
const SUBSTEPS: usize = 2;
/// The least σ a node takes, as a share of the smooth surface's β/√2: where the rule's
/// slopes let one (entry, exit) pair through, the quadrature's own σ is 0.
const LEAST_SIGMA_SHARE: f64 = 0.25;
/// The least standard deviation of the exit sine a column reports.
const LEAST_SIN_SD: f64 = 1e-4;
/// The share of a row's brightest column's light below which a column of [`fill_columns`]
/// takes its nearest brighter neighbour's lobe: its own is of a few pairs' tails.
const DIM_SHARE: f64 = 1e-3;
/// The least standard deviation of a column's exit sine, as a share of its whole row's: a dim
/// column's few pairs can all leave at one inclination.
const LEAST_SD_SHARE: f64 = 0.25;

/// One θ_i row of the table while it is built.
#[derive(Clone, Copy)]
struct Row {
    texels: [[f32; 2]; GAMMA_NODES],
    columns: [[f32; 4]; COLUMNS],
}

impl RoughTtTable {
    /// The table for (η, α, β), built once per process and shared.
    pub fn shared(eta: f64, alpha: f64, beta: f64) -> Arc<Self> {
        static CACHE: SharedTables<(u64, u64, u64), RoughTtTable> = OnceLock::new();
        let key = (eta.to_bits(), alpha.to_bits(), beta.to_bits());
        shared_table(&CACHE, key, || Self::build(eta, alpha, beta))
    }

    /// Every node's pairs by [`exit_pairs`] with [`TABLE_RULE`], the rows of θ_i shared among
    /// the available cores: each node's shift and σ from its pairs' moments, and the row's
    /// columns from every pair followed between nodes ([`fill_columns`]). Where no light
    /// leaves, the node keeps Bravais' Φ at the specular cone and the smooth spread β/√2 (it
    /// carries no power); elsewhere σ is at least a quarter of that (`LEAST_SIGMA_SHARE`).
    pub fn build(eta: f64, alpha: f64, beta: f64) -> Self {
        let empty = Row {
            texels: [[0.0; 2]; GAMMA_NODES],
            columns: [[0.0; 4]; COLUMNS],
        };
        let mut rows = vec![empty; THETA_I_NODES];
        let smooth_sigma = beta * std::f64::consts::FRAC_1_SQRT_2;
        fill_rows(&mut rows, 1, |i, row| {
            let theta_i = theta_i_at(i);
            let mut pairs = vec![Vec::new(); GAMMA_NODES];
            for (k, (texel, pairs)) in row[0].texels.iter_mut().zip(&mut pairs).enumerate() {
                let h = gamma_at(k).sin();
                exit_pairs(theta_i, alpha, eta, beta, h, TABLE_RULE, pairs);
                *texel = match RoughExit::of_pairs(pairs) {
                    Some(exit) => [
                        exit.phi - bravais(eta, theta_i, h),
                        exit.sigma.max(LEAST_SIGMA_SHARE * smooth_sigma),
                    ],
                    None => [0.0, smooth_sigma],
                }
                .map(|x| x as f32);
            }
            let smooth = [-theta_i.sin(), smooth_sigma, 0.0, FULL_REACH];
            fill_columns(&pairs, smooth, &mut row[0].columns);
        });
        let texels: Vec<[f32; 2]> = rows.iter().flat_map(|r| r.texels).collect();
        Self {
            sigma_max: texels.iter().fold(0.0f64, |m, t| m.max(t[1] as f64)),
            texels,
            columns: rows.iter().flat_map(|r| r.columns).collect(),
        }
    }

    fn row(theta_i: f64) -> (usize, f32) {
        locate((theta_i + FRAC_PI_2) / PI, THETA_I_NODES)
    }

    /// The shift and spread at (θ_i, h), blended bilinearly in (θ_i, γ).
    #[inline]
    pub fn at(&self, theta_i: f64, h: f64) -> RoughAzimuth {
        let gamma = asin_fast(h.abs().min(1.0));
        let column = locate(gamma / FRAC_PI_2, GAMMA_NODES);
        let [shift, sigma] = blend(&self.texels, GAMMA_NODES, Self::row(theta_i), column);
        RoughAzimuth {
            shift: if h < 0.0 { -shift } else { shift },
            sigma,
        }
    }

    /// The mean, variance and skewness of TT's lobe in the exit sine at azimuth φ for light at
    /// θ_i, and its reach: the light's own moments (reaching the pole) or fitted to it
    /// (`fill_columns`), blended bilinearly (the standard deviation is what is blended).
    pub fn column_sine(&self, theta_i: f64, phi: f64) -> SkewedSine {
        let column = locate(crate::geometry::frame::wrap_pi(phi).abs() / PI, COLUMNS);
        let lobe = blend(&self.columns, COLUMNS, Self::row(theta_i), column);
        column_sine_of(lobe)
    }

    /// The largest spread of any offset.
    pub fn sigma_max(&self) -> f64 {
        self.sigma_max
    }
}

/// One θ_i row's columns from the pairs at its γ nodes (h ≥ 0; −h's light is the mirror
/// image, which lands in the same column of |φ|): the mean, standard deviation and skewness of
/// the exit sine over the light that reaches each column, reaching the pole, or where the lobe
/// they give misses that light by more than [`FIT_GOOD_ENOUGH`], those and the reach fitted to
/// it ([`fit_column`]). Between two nodes each pair is
/// followed [`SUBSTEPS`] times, its weight, exit sine and φ linear between its values there
/// (a pair whose light leaves at one node alone keeps that node's exit and fades), weighted by
/// dh = cos γ dγ and split between the two columns about its |φ|. A column with less than
/// [`DIM_SHARE`] of the brightest column's light takes the lobe of the nearest column with
/// more (the model's N_TT, Gaussian per offset, still sends it some light), and every
/// column's deviation is at least [`LEAST_SD_SHARE`] of the row's; a row with no light at
/// all takes `smooth`.
fn fill_columns(pairs: &[Vec<ExitPair>], smooth: ColumnLobe, row: &mut [[f32; 4]]) {
    let mut sums = [[0.0f64; 4]; COLUMNS];
    // The largest |x| of each column's light: where the fit's reach starts.
    let mut extents = [0.0f64; COLUMNS];
    walk_pairs(pairs, |column, w, x| {
        let sum = &mut sums[column];
        sum[0] += w;
        sum[1] += w * x;
        sum[2] += w * x * x;
        sum[3] += w * x * x * x;
        if w > 0.0 {
            extents[column] = extents[column].max(x.abs());
        }
    });
    let brightest = sums.iter().fold(0.0f64, |m, s| m.max(s[0]));
    if brightest <= 0.0 {
        row.fill(smooth.map(|x| x as f32));
        return;
    }
    let row_sums = sums
        .iter()
        .fold([0.0; 4], |acc, s| std::array::from_fn(|l| acc[l] + s[l]));
    let least_sd = (LEAST_SD_SHARE * sine_moments(&row_sums)[1]).max(LEAST_SIN_SD);
    let lit: Vec<bool> = sums.iter().map(|s| s[0] > DIM_SHARE * brightest).collect();
    // Each lit column's moments, and its light binned about its mean in its deviation.
    let moments: Vec<ColumnLobe> = sums
        .iter()
        .zip(&lit)
        .map(|(s, &lit)| match lit {
            true => {
                let [mean, sd, skewness] = sine_moments(s);
                [mean, sd.max(least_sd), skewness, FULL_REACH]
            }
            false => smooth,
        })
        .collect();
    let mut light = vec![[0.0f64; FIT_BINS]; COLUMNS];
    walk_pairs(pairs, |column, w, x| {
        if let Some(bin) = fit_bin(moments[column], x).filter(|_| lit[column]) {
            light[column][bin] += w / sums[column][0];
        }
    });
    let fitted: Vec<ColumnLobe> = (0..COLUMNS)
        .map(|j| match lit[j] {
            true => fit_column(moments[j], extents[j], &light[j]),
            false => moments[j],
        })
        .collect();
    for (j, column) in row.iter_mut().enumerate() {
        let nearest = (0..COLUMNS)
            .filter(|&l| lit[l])
            .min_by_key(|&l| l.abs_diff(j));
        // The brightest column is lit, so there is a nearest one.
        let [mean, sd, skewness, reach] = nearest.map_or(smooth, |l| fitted[l]);
        *column = [mean, sd.max(least_sd), skewness, reach].map(|x| x as f32);
    }
}

/// The bin of [`fit_column`]'s distance that exit sine x falls in, for a column of
/// `[mean, sd, ..]`; none beyond ±[`FIT_REACH`] deviations.
fn fit_bin([mean, sd, ..]: ColumnLobe, x: f64) -> Option<usize> {
    let at = ((x - mean) / sd + FIT_REACH) / (2.0 * FIT_REACH) * FIT_BINS as f64;
    (at >= 0.0 && at < FIT_BINS as f64).then_some(at as usize)
}

/// Bins of a column's light for [`fit_column`]'s distance, over ±[`FIT_REACH`] of its
/// deviation about its mean.
const FIT_BINS: usize = 40;
const FIT_REACH: f64 = 5.0;
/// Rounds of [`fit_column`]'s coordinate search: each tries a step either way along each
/// parameter, and halves the steps where none is better.
const FIT_ROUNDS: usize = 10;
/// The L1 distance of the moments' lobe to the column's light below which it is kept: well
/// above an exact lobe's distance to its own binned light (the midpoint rule's error,
/// `the_fit_finds_the_lobe_the_light_comes_from`), so that only the columns whose moments
/// miss their light pay the fit's cost in the table's build.
const FIT_GOOD_ENOUGH: f64 = 0.02;

/// The (mean, deviation, skewness, reach) whose lobe ([`SkewedSineLobe`] through
/// [`SkewedSineLobe::matched`], as the model builds it) has the least L1 distance to the
/// column's light `target` (its share per bin, [`fit_bin`]), by a coordinate search from its
/// moments `start` (reaching the pole) on, the reach from the light's `extent`, its largest
/// |x|. The reach stays between |mean| and the pole.
fn fit_column(start: ColumnLobe, extent: f64, target: &[f64; FIT_BINS]) -> ColumnLobe {
    let sd0 = start[1];
    let l1 = |c: ColumnLobe| fit_distance(c, start, target);
    let at_start = l1(start);
    if at_start < FIT_GOOD_ENOUGH {
        return start;
    }
    let from = [
        start[0],
        start[1],
        start[2],
        extent.min(FULL_REACH).max(start[0].abs()),
    ];
    let mut best = (l1(from), from);
    if at_start < best.0 {
        best = (at_start, start);
    }
    let mut step = [0.1 * sd0, 0.05 * sd0, 0.08, 0.1 * sd0];
    for _ in 0..FIT_ROUNDS {
        let mut improved = false;
        for i in 0..4 {
            for d in [-1.0, 1.0] {
                let mut c = best.1;
                c[i] += d * step[i];
                if c[1] <= 0.0 || c[3] > FULL_REACH || c[3] < c[0].abs() {
                    continue;
                }
                let v = l1(c);
                if v < best.0 {
                    best = (v, c);
                    improved = true;
                }
            }
        }
        if !improved {
            step = step.map(|s| 0.5 * s);
        }
    }
    best.1
}

/// The L1 distance between the lobe of column parameters `lobe` ([`SkewedSineLobe::of_column`])
/// and light binned about `start` ([`fit_bin`]), the lobe's mass per bin taken at the middle of
/// the bin's part within the lobe's reach.
fn fit_distance(lobe: ColumnLobe, start: ColumnLobe, target: &[f64; FIT_BINS]) -> f64 {
    let reach = lobe[3];
    let lobe = SkewedSineLobe::of_column(column_sine_of(lobe));
    let width = 2.0 * FIT_REACH * start[1] / FIT_BINS as f64;
    target
        .iter()
        .enumerate()
        .map(|(k, &h)| {
            let a = start[0] + (k as f64 - 0.5 * FIT_BINS as f64) * width;
            let (a, b) = (a.max(-reach), (a + width).min(reach));
            let mass = match b > a {
                true => lobe.eval(0.5 * (a + b)) * (b - a),
                false => 0.0,
            };
            (mass - h).abs()
        })
        .sum::<f64>()
}

/// The [`SkewedSine`] of a column's lobe.
fn column_sine_of([mean, sd, skewness, reach]: ColumnLobe) -> SkewedSine {
    SkewedSine {
        moments: SineMoments {
            mean,
            variance: sd * sd,
        },
        skewness,
        reach,
    }
}

/// Every pair of one θ_i row's nodes followed between them (see [`fill_columns`]): the
/// column of |φ| it reaches, its weight times dh, and its exit sine, each pair split between
/// the two columns about its |φ|.
fn walk_pairs(pairs: &[Vec<ExitPair>], mut add: impl FnMut(usize, f64, f64)) {
    for k in 0..GAMMA_NODES - 1 {
        for j in 0..SUBSTEPS {
            let t = (j as f64 + 0.5) / SUBSTEPS as f64;
            let dh = (gamma_at(k) * (1.0 - t) + gamma_at(k + 1) * t).cos();
            for (a, b) in pairs[k].iter().zip(&pairs[k + 1]) {
                let (from, to) = match (a.weight > 0.0, b.weight > 0.0) {
                    (false, false) => continue,
                    (true, true) => (a, b),
                    (true, false) => (a, &ExitPair { weight: 0.0, ..*a }),
                    (false, true) => (&ExitPair { weight: 0.0, ..*b }, b),
                };
                let lerp = |u: f64, v: f64| u + t * (v - u);
                let (weight, x, phi) = (
                    lerp(from.weight, to.weight) * dh,
                    lerp(from.sin_theta, to.sin_theta),
                    lerp(from.phi, to.phi),
                );
                let at = crate::geometry::frame::wrap_pi(phi).abs() / PI * (COLUMNS - 1) as f64;
                let c = (at as usize).min(COLUMNS - 2);
                let f = (at - c as f64).clamp(0.0, 1.0);
                add(c, weight * (1.0 - f), x);
                add(c + 1, weight * f, x);
            }
        }
    }
}

/// The mean, standard deviation and skewness of x from the sums of w, w x, w x² and w x³
/// (w > 0 summed); skewness 0 where x does not spread.
fn sine_moments([w, wx, wxx, wxxx]: &[f64; 4]) -> [f64; 3] {
    let mean = wx / w;
    let variance = (wxx / w - mean * mean).max(0.0);
    let third = wxxx / w - mean * (3.0 * variance + mean * mean);
    let sd = variance.sqrt();
    let skewness = match sd > LEAST_SIN_SD {
        true => third / (variance * sd),
        false => 0.0,
    };
    [mean, sd, skewness]
}

/// Every channel of `texels` (rows of `stride`) at the cells (i, f_i) and (k, f_k), blended
/// bilinearly in f64.
#[inline]
fn blend<const N: usize>(
    texels: &[[f32; N]],
    stride: usize,
    (i, fi): (usize, f32),
    (k, fk): (usize, f32),
) -> [f64; N] {
    let at = i * stride + k;
    let (fi, fk) = (fi as f64, fk as f64);
    let node = |n: usize, l: usize| texels[n][l] as f64;
    let mut out = [0.0; N];
    for (l, o) in out.iter_mut().enumerate() {
        let low = node(at, l) + fk * (node(at + 1, l) - node(at, l));
        let high = node(at + stride, l) + fk * (node(at + stride + 1, l) - node(at + stride, l));
        *o = low + fi * (high - low);
    }
    out
}

/// Bravais' Φ(1, h) at θ_d = −θ_i, from which the table's shift is measured: where N_TT reads
/// it whatever θ_o ([`crate::models::deon2011::azimuthal::AzimuthalScattering::lobe_eta_prime`]).
fn bravais(eta: f64, theta_i: f64, h: f64) -> f64 {
    azimuthal_deflection(1, h, eta_prime(eta, theta_i))
}

fn theta_i_at(i: usize) -> f64 {
    crate::math::grid::theta_i_node(i, THETA_I_NODES)
}

fn gamma_at(k: usize) -> f64 {
    (FRAC_PI_2 * k as f64 / (GAMMA_NODES - 1) as f64).min(FRAC_PI_2 - crate::math::grid::GRAZING)
}

#[cfg(test)]
mod tests;
