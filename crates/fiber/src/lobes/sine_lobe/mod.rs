//! A longitudinal lobe that is Gaussian in x = sin θ_o, truncated to [−1, 1]: the shape of the
//! light a refraction sends out when x, not θ_o, is what the micro-normal slopes move linearly.
//! Where the light ends short of the pole, the lobe is truncated to [−e, e] instead, e its
//! reach ([`SkewedSine::reach`]); everything below holds with e for 1.
//!
//! d'Eon et al. 2014 §2.2 follows a path in Nusselt coordinates, where the exit direction's
//! x = sin θ_o is, to first order, linear in the slope of each scale the path meets: Gaussian
//! slopes give a Gaussian x. The von Mises–Fisher lobe of [`crate::lobes::longitudinal`] with the
//! same mean and variance of x is Gaussian in θ_o instead, symmetric about its cone; the arcsine
//! that takes a symmetric x to θ_o skews it toward the pole, as the simulated TT is
//! (docs/departures/19-tt-sine-lobe.md).
//!
//! Like M, it is a density per unit sin θ_o (∫ M cos θ_o dθ_o = 1), so the truncation is its
//! only normalisation:
//! M(x) = φ((x − μ)/σ) / (σ Z), Z = Φ((1 − μ)/σ) − Φ((−1 − μ)/σ),
//! φ and Φ the standard normal density and distribution function. Sampling inverts Φ on the
//! truncated range. Φ at the ends comes from an erfc within 1.3e-7 relative
//! ([`erfc_lanes`]), and M and its draws share it, so M integrates to 1 within that.

use crate::lobes::longitudinal::MIN_VARIANCE;
use crate::math::{erfc_lanes, exp_fast, exp_pair, normal_quantile_fast};
use std::f64::consts::{FRAC_1_SQRT_2, PI};
use wide::{f64x2, f64x4};

/// The mean and variance of sin θ_o over some light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SineMoments {
    pub mean: f64,
    pub variance: f64,
}

/// [`SineMoments`] with the standardised third central moment of sin θ_o, E[(x − μ)³]/σ³,
/// and the lobe's reach: the |x| it ends at, [`FULL_REACH`] where nothing but the pole stops
/// it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SkewedSine {
    pub moments: SineMoments,
    pub skewness: f64,
    pub reach: f64,
}

/// The reach of a lobe that only the poles end: x ∈ [−1, 1].
pub const FULL_REACH: f64 = 1.0;

/// Standard deviations between the mean and the nearer end of [−e, e] beyond which the
/// truncation is below f64's resolution of Z (Φ(−8.3) = 5e-17).
const UNTRUNCATED: f64 = 8.3;

/// Φ(−d) for the distances d (in standard deviations, d ≥ 0) in four lanes: the mass a
/// truncation at that distance cuts.
#[inline]
fn cut_beyond(distance: f64x4) -> f64x4 {
    f64x4::splat(0.5) * erfc_lanes(distance * f64x4::splat(FRAC_1_SQRT_2))
}

/// A lobe Gaussian in sin θ_o (module docs), with the parts of M that depend on the lobe alone.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SineLobe {
    /// μ, clamped to [−reach, reach].
    pub mean: f64,
    /// σ, at least √[`MIN_VARIANCE`].
    pub sd: f64,
    inv_sd: f64,
    /// Z: the Gaussian's mass inside [−1, 1].
    mass: f64,
    /// M at the mean, 1/(σ Z √(2π)).
    peak: f64,
    /// Φ at the nearer end, −(e − |μ|)/σ: the mass the truncation cuts there.
    cut_near: f64,
    /// e: the lobe is truncated to [−e, e], e ≤ 1.
    reach: f64,
}

impl SineLobe {
    /// What a lobe holds where the mixture has no share.
    const UNUSED: Self = Self {
        mean: 0.0,
        sd: 1.0,
        inv_sd: 1.0,
        mass: 1.0,
        peak: 0.0,
        cut_near: 0.0,
        reach: FULL_REACH,
    };

    /// The lobe with mean μ and variance σ² of its untruncated Gaussian, truncated to
    /// [−1, 1].
    #[inline]
    pub fn new(moments: SineMoments) -> Self {
        Self::with_sd(moments.mean, moments.variance.max(0.0).sqrt(), FULL_REACH)
    }

    /// The lobe with mean μ and standard deviation σ of its untruncated Gaussian, truncated
    /// to [−e, e] (e the reach, at most 1 and at least `LEAST_REACH`).
    #[inline]
    pub fn with_sd(mean: f64, sd: f64, reach: f64) -> Self {
        let sd = sd.max(MIN_VARIANCE.sqrt());
        let inv_sd = 1.0 / sd;
        let reach = clamp_reach(reach);
        let mean = mean.clamp(-reach, reach);
        let [near, far] = end_distances(mean, inv_sd, reach);
        let [cut_near, cut_far, _, _] = cut_beyond(f64x4::from([near, far, 0.0, 0.0])).into();
        Self::with_cuts(mean, sd, inv_sd, [cut_near, cut_far], reach)
    }

    /// The lobe of mean μ in [−e, e], σ at least √[`MIN_VARIANCE`] and its reciprocal, whose
    /// Gaussian the ends ±e cut by `[near, far]` ([`end_distances`], [`cut_beyond`]).
    #[inline]
    fn with_cuts(
        mean: f64,
        sd: f64,
        inv_sd: f64,
        [cut_near, cut_far]: [f64; 2],
        reach: f64,
    ) -> Self {
        let mass = 1.0 - cut_near - cut_far;
        Self {
            mean,
            sd,
            inv_sd,
            mass,
            peak: inv_sd / ((2.0 * PI).sqrt() * mass),
            cut_near,
            reach,
        }
    }

    /// The mean and variance of this part as it is, truncated to [−e, e]
    /// ([`SkewedSineLobe::truncated_moments`]).
    fn truncated_moments(&self) -> SineMoments {
        let density = |z: f64| (-0.5 * z * z).exp() / (2.0 * PI).sqrt();
        let (low, high) = (
            (-self.reach - self.mean) * self.inv_sd,
            (self.reach - self.mean) * self.inv_sd,
        );
        let (d_low, d_high) = (density(low), density(high));
        let shift = (d_low - d_high) / self.mass;
        let spread = 1.0 + (low * d_low - high * d_high) / self.mass - shift * shift;
        SineMoments {
            mean: self.mean + self.sd * shift,
            variance: self.sd * self.sd * spread.max(0.0),
        }
    }

    /// M at sin θ_o = `sin_o`: 0 beyond the reach.
    #[inline]
    pub fn eval(&self, sin_o: f64) -> f64 {
        if sin_o.abs() > self.reach {
            return 0.0;
        }
        let z = (sin_o - self.mean) * self.inv_sd;
        self.peak * exp_fast(-0.5 * z * z)
    }

    /// sin θ_o drawn with density M from one uniform number, increasing in it: Φ⁻¹ of a uniform
    /// point between Φ at the two ends, taken with the nearer end below (the lobe mirrored,
    /// and u with it, where μ > 0), where Φ is small and its quantile keeps its precision. The
    /// fixed-point sampler redraws with the same u as the lobe moves, so the draw stays
    /// continuous where μ changes sign.
    #[inline]
    pub fn sample_sin(&self, u: f64) -> f64 {
        let (mirrored, u) = match self.mean > 0.0 {
            true => (-self.mean, 1.0 - u),
            false => (self.mean, u),
        };
        let x = mirrored + self.sd * normal_quantile_fast(self.cut_near + u * self.mass);
        let x = x.clamp(-self.reach, self.reach);
        if self.mean > 0.0 { -x } else { x }
    }
}

/// The distances in standard deviations from μ to the nearer end of [−e, e] and to the
/// farther.
#[inline]
fn end_distances(mean: f64, inv_sd: f64, reach: f64) -> [f64; 2] {
    [(reach - mean.abs()) * inv_sd, (reach + mean.abs()) * inv_sd]
}

/// The least reach a lobe takes: a guard for degenerate input (the fitted reaches lie beyond
/// their lobes' |mean|, near 1).
const LEAST_REACH: f64 = 0.01;

/// A reach in [`LEAST_REACH`], [`FULL_REACH`] (NaN to the full reach).
#[inline]
fn clamp_reach(reach: f64) -> f64 {
    match reach.is_nan() {
        true => FULL_REACH,
        false => reach.clamp(LEAST_REACH, FULL_REACH),
    }
}

/// Secant steps of [`SkewedSineLobe::matched`].
const MATCHING_STEPS: usize = 8;
/// Deviations from the nearer pole beyond which [`SkewedSineLobe::matched`] matches in full;
/// within one it gives the target itself.
const MATCHED_FROM: f64 = 2.0;

/// The weight of the mixture's second part ([`SkewedSineLobe`]), on the side of its skew.
const SKEW_WEIGHT: f64 = 0.2;
/// The largest skewness the mixture of [`SkewedSineLobe`] takes: the most at which it stays
/// log-concave, one hump with no shoulder. Two Gaussians of one width σ_c whose means are d
/// apart make a log-concave mixture for any weights exactly when d ≤ 2σ_c ((ln M)″ =
/// (w₁w₂d²/σ_c² − 1)/σ_c² with w₁, w₂ the parts' shares at x, whose product reaches ¼); with
/// σ_c² = σ² − w(1 − w)d² that is d² = 4σ²/(1 + 4w(1 − w)), γ = w(1 − w)(1 − 2w)(d/σ)³
/// (`largest_skew_is_log_concave`). Past it the lobe is the two-piece normal alone.
const LARGEST_SKEWNESS: f64 = 0.365_675_15;
/// The skewness from which [`SkewedSineLobe`] passes from the mixture to the two-piece normal,
/// reached in full at [`LARGEST_SKEWNESS`] (departure 24).
const TWO_PIECE_FROM: f64 = 0.2;
/// The largest skewness the two-piece normal takes: it reaches 0.9953 only as one side's
/// deviation goes to 0.
const TWO_PIECE_LARGEST: f64 = 0.95;

/// How [`SkewedSineLobe`] splits a lobe of standard deviation σ for a skewness γ, in units of
/// σ: the mixture's distance d/σ between its parts' means and their deviation σ_c/σ, the
/// two-piece normal's asymmetry r (`TwoPiece`), and the two-piece's share of the lobe. The
/// table of TT's lobes holds the offset, r and the share ([`SkewSplit::from_channels`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SkewSplit {
    pub offset: f64,
    pub part_sd: f64,
    pub asymmetry: f64,
    pub two_piece: f64,
}

impl SkewSplit {
    /// The split for skewness γ: the mixture's clamped to ±[`LARGEST_SKEWNESS`], the
    /// two-piece's to ±[`TWO_PIECE_LARGEST`], the two-piece's share a smoothstep in |γ| from
    /// [`TWO_PIECE_FROM`] to [`LARGEST_SKEWNESS`]. Both carry γ itself wherever both have a
    /// share, so the lobe's skewness is γ up to the two-piece's clamp.
    pub fn new(skewness: f64) -> Self {
        let offset = Self::mixture_offset(skewness);
        let t = ((skewness.abs() - TWO_PIECE_FROM) / (LARGEST_SKEWNESS - TWO_PIECE_FROM))
            .clamp(0.0, 1.0);
        let share = t * t * (3.0 - 2.0 * t);
        let asymmetry = match share > 0.0 {
            true => TwoPiece::asymmetry_for(skewness.clamp(-TWO_PIECE_LARGEST, TWO_PIECE_LARGEST)),
            false => 0.0,
        };
        Self::from_channels(offset, asymmetry, share)
    }

    /// The split of a mixture offset, a two-piece asymmetry and the two-piece's share; the
    /// mixture's parts' deviation is what keeps its variance, so that a table that blends
    /// offsets keeps the variance too.
    #[inline]
    pub fn from_channels(offset: f64, asymmetry: f64, two_piece: f64) -> Self {
        let w = SKEW_WEIGHT;
        Self {
            offset,
            part_sd: (1.0 - w * (1.0 - w) * offset * offset).max(0.0).sqrt(),
            asymmetry,
            two_piece: two_piece.clamp(0.0, 1.0),
        }
    }

    /// The mixture's distance between its parts' means, over σ, for skewness γ clamped to
    /// ±[`LARGEST_SKEWNESS`]: d = ∛(γ / (w(1 − w)(1 − 2w))).
    fn mixture_offset(skewness: f64) -> f64 {
        let w = SKEW_WEIGHT;
        let gamma = skewness.clamp(-LARGEST_SKEWNESS, LARGEST_SKEWNESS);
        (gamma / (w * (1.0 - w) * (1.0 - 2.0 * w))).cbrt()
    }

    /// The mixture's split alone (no two-piece share), for skewness γ.
    #[cfg(test)]
    fn mixture(skewness: f64) -> Self {
        Self::from_channels(Self::mixture_offset(skewness), 0.0, 0.0)
    }
}

/// √(2/π), the mean of a unit half-normal.
const HALF_NORMAL_MEAN: f64 = 0.797_884_560_802_865_4;

/// A two-piece normal in sin θ_o (John 1982): Gaussian of deviation σ₁ below its mode and σ₂
/// above it, continuous at the mode, truncated to [−e, e] (e its reach) and normalised there:
/// M(x) = e^{−z²/2} / Z, z = (x − mode)/σ_side, Z = Σ σ_side √(2π) (½ − Φ(−d_side/σ_side)),
/// d_side the distance from the mode to that side's end. With sides a = 1 − r and b = 1 + r
/// (r its asymmetry), mean − mode = √(2/π)(b − a), variance (1 − 2/π)(b − a)² + ab and third
/// central moment √(2/π)(b − a)((4/π − 1)(b − a)² + ab); it keeps one log-concave hump at
/// any skewness.
#[derive(Clone, Copy, Debug, PartialEq)]
struct TwoPiece {
    /// The mode, clamped to [−e, e].
    mode: f64,
    /// σ below and above the mode, and their reciprocals.
    sides: [f64; 2],
    inv_sides: [f64; 2],
    /// Φ(−d/σ) per side: the mass of that side's Gaussian beyond its end.
    cuts: [f64; 2],
    /// The share of the light below the mode.
    below: f64,
    /// 1/Z.
    peak: f64,
    /// e.
    reach: f64,
}

impl TwoPiece {
    /// What a lobe holds where the two-piece has no share.
    const UNUSED: Self = Self {
        mode: 0.0,
        sides: [1.0; 2],
        inv_sides: [1.0; 2],
        cuts: [0.0; 2],
        below: 0.5,
        peak: 0.0,
        reach: FULL_REACH,
    };

    /// The skewness of asymmetry r (the moments in the type's documentation).
    fn skewness_of(r: f64) -> f64 {
        let (d, ab) = (2.0 * r, 1.0 - r * r);
        let variance = (1.0 - 2.0 / PI) * d * d + ab;
        HALF_NORMAL_MEAN * d * ((4.0 / PI - 1.0) * d * d + ab) / variance.powf(1.5)
    }

    /// The asymmetry whose skewness is γ (|γ| < 0.995), by bisection: γ(r) increases with r.
    fn asymmetry_for(gamma: f64) -> f64 {
        let (mut low, mut high) = (-1.0f64, 1.0f64);
        for _ in 0..60 {
            let mid = 0.5 * (low + high);
            match Self::skewness_of(mid) < gamma {
                true => low = mid,
                false => high = mid,
            }
        }
        0.5 * (low + high)
    }

    /// The two-piece normal of untruncated mean μ, deviation σ and asymmetry r, truncated to
    /// [−e, e] (e already clamped).
    #[inline]
    fn new(mean: f64, sd: f64, r: f64, reach: f64) -> Self {
        let r = r.clamp(-0.999, 0.999);
        let (d, ab) = (2.0 * r, 1.0 - r * r);
        let scale = sd / ((1.0 - 2.0 / PI) * d * d + ab).sqrt();
        let mode = (mean - HALF_NORMAL_MEAN * d * scale).clamp(-reach, reach);
        let sides = [(1.0 - r) * scale, (1.0 + r) * scale].map(|s| s.max(MIN_VARIANCE.sqrt()));
        let inv_sides = sides.map(|s| 1.0 / s);
        let distances = [(mode + reach) * inv_sides[0], (reach - mode) * inv_sides[1]];
        let cuts: [f64; 2] = match distances[0].min(distances[1]) > UNTRUNCATED {
            true => [0.0; 2],
            false => {
                let [a, b, _, _] =
                    cut_beyond(f64x4::from([distances[0], distances[1], 0.0, 0.0])).into();
                [a, b]
            }
        };
        let masses = [0, 1].map(|k| sides[k] * (0.5 - cuts[k]));
        let total = masses[0] + masses[1];
        Self {
            mode,
            sides,
            inv_sides,
            cuts,
            below: masses[0] / total,
            peak: 1.0 / ((2.0 * PI).sqrt() * total),
            reach,
        }
    }

    /// M at sin θ_o within the reach: one Gaussian, of the side it lies on.
    #[inline]
    fn eval(&self, sin_o: f64) -> f64 {
        let side = usize::from(sin_o > self.mode);
        let z = (sin_o - self.mode) * self.inv_sides[side];
        self.peak * exp_fast(-0.5 * z * z)
    }

    /// A draw from one uniform number, increasing in it: a side by u, then Φ⁻¹ of u rescaled
    /// within that side's mass, taken from the side's end, where Φ is small.
    #[inline]
    fn sample_sin(&self, u: f64) -> f64 {
        let x = if u < self.below {
            let t = u / self.below;
            self.mode
                + self.sides[0] * normal_quantile_fast(self.cuts[0] + t * (0.5 - self.cuts[0]))
        } else {
            let t = (1.0 - u) / (1.0 - self.below);
            self.mode
                - self.sides[1] * normal_quantile_fast(self.cuts[1] + t * (0.5 - self.cuts[1]))
        };
        x.clamp(-self.reach, self.reach)
    }

    /// The mean and mean square as truncated, each side a normal about the mode cut to
    /// [−e, mode] or [mode, e] (Johnson, Kotz & Balakrishnan 1994 §10.1, as
    /// [`SkewedSineLobe::truncated_moments`]), the sides weighted by their light.
    fn truncated_raw_moments(&self) -> [f64; 2] {
        let density = |z: f64| (-0.5 * z * z).exp() / (2.0 * PI).sqrt();
        let side = |k: usize| -> [f64; 2] {
            let (sd, mass) = (self.sides[k], 0.5 - self.cuts[k]);
            let (alpha, beta) = match k {
                0 => ((-self.reach - self.mode) / sd, 0.0),
                _ => (0.0, (self.reach - self.mode) / sd),
            };
            let (da, db) = (density(alpha), density(beta));
            let shift = (da - db) / mass;
            let spread = 1.0 + (alpha * da - beta * db) / mass - shift * shift;
            let mean = self.mode + sd * shift;
            [mean, sd * sd * spread.max(0.0) + mean * mean]
        };
        let weights = [self.below, 1.0 - self.below];
        let mut raw = [0.0; 2];
        for (k, &w) in weights.iter().enumerate() {
            if w > 0.0 {
                let m = side(k);
                raw = [raw[0] + w * m[0], raw[1] + w * m[1]];
            }
        }
        raw
    }
}

/// A lobe in sin θ_o with a mean, variance and skewness. Up to a skewness of
/// [`TWO_PIECE_FROM`] it is a mixture of two [`SineLobe`]s of one width, weighted 1 − w and w
/// (w = [`SKEW_WEIGHT`]) with means μ₁ and μ₂ = μ₁ + d. The mixture's variance is
/// σ_c² + w(1 − w)d² and its third central moment w(1 − w)(1 − 2w)d³, so for skewness γ
/// d = ∛(γ / (w(1 − w)(1 − 2w))) σ, σ_c² = σ² − w(1 − w)d², and μ₁ = μ − wd keeps the mean
/// ([`SkewSplit`]). From [`TWO_PIECE_FROM`] to [`LARGEST_SKEWNESS`] it passes to a two-piece
/// normal of the same mean, variance and skewness (`TwoPiece`; the blend of two densities
/// with the same moments has them too), which alone carries a larger skew: the mixture there
/// would grow a shoulder, and the light near grazing incidence, skewed that much, stops short
/// of the pole as the two-piece's steep side does (departure 24). γ = 0 is the [`SineLobe`].
/// The moments are those of the untruncated parts, and each part is normalised over [−e, e],
/// e the lobe's reach, so the lobe integrates to 1. The reach is the pole ([`FULL_REACH`])
/// unless the light ends short of it: TT's, where the exit's tilted scale hides the
/// directions nearest the pole (departure 28).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SkewedSineLobe {
    parts: [SineLobe; 2],
    two_piece: TwoPiece,
    /// The two-piece's share: 0 the mixture alone, 1 the two-piece alone.
    share: f64,
    /// The untruncated mean and standard deviation.
    mean: f64,
    sd: f64,
    /// e: M is 0 where |x| > e.
    reach: f64,
}

impl SkewedSineLobe {
    pub fn new(skewed: SkewedSine) -> Self {
        let SineMoments { mean, variance } = skewed.moments;
        Self::split(
            mean,
            variance.max(0.0).sqrt(),
            SkewSplit::new(skewed.skewness),
            skewed.reach,
        )
    }

    /// The lobe whose truncation to its reach has `column`'s mean and variance, split as its
    /// skewness says ([`Self::matched`]).
    pub fn of_column(column: SkewedSine) -> Self {
        Self::new(SkewedSine {
            moments: Self::matched(column),
            ..column
        })
    }

    /// The lobe of mean μ and standard deviation σ split as `split` says, truncated to
    /// [−e, e] (e the reach, at most 1 and at least `LEAST_REACH`).
    #[inline]
    pub fn split(mean: f64, sd: f64, split: SkewSplit, reach: f64) -> Self {
        let reach = clamp_reach(reach);
        // Each family built only where it has a share: the other is never read.
        let share = split.two_piece;
        let two_piece = match share > 0.0 {
            true => TwoPiece::new(mean, sd, split.asymmetry, reach),
            false => TwoPiece::UNUSED,
        };
        let parts = match share < 1.0 {
            true => Self::mixture_parts(mean, sd, split, reach),
            false => [SineLobe::UNUSED; 2],
        };
        Self {
            parts,
            two_piece,
            share,
            mean,
            sd,
            reach,
        }
    }

    /// The mixture's two parts for mean μ, deviation σ and `split`'s offset, within reach e.
    #[inline]
    fn mixture_parts(mean: f64, sd: f64, split: SkewSplit, reach: f64) -> [SineLobe; 2] {
        let d = split.offset * sd;
        let part_sd = (split.part_sd * sd).max(MIN_VARIANCE.sqrt());
        let inv_sd = 1.0 / part_sd;
        let means = [mean - SKEW_WEIGHT * d, mean + (1.0 - SKEW_WEIGHT) * d]
            .map(|m| m.clamp(-reach, reach));
        // Both parts' ends in one set of lanes, where any is near enough to cut.
        let [a, b] = means.map(|m| end_distances(m, inv_sd, reach));
        let cuts: [f64; 4] = match a[0].min(b[0]) > UNTRUNCATED {
            true => [0.0; 4],
            false => cut_beyond(f64x4::from([a[0], a[1], b[0], b[1]])).into(),
        };
        [
            SineLobe::with_cuts(means[0], part_sd, inv_sd, [cuts[0], cuts[1]], reach),
            SineLobe::with_cuts(means[1], part_sd, inv_sd, [cuts[2], cuts[3]], reach),
        ]
    }

    /// The untruncated mean and variance whose lobe, split as `skewed`'s skewness says and
    /// truncated to its reach [−e, e], has `skewed`'s mean and variance: near an end the cut
    /// takes a Gaussian's tail off and moves the truncated mean toward the equator, so the
    /// untruncated mean and deviation are set apart from the target by what the cut takes
    /// ([`Self::truncated_moments`], secant steps).
    pub fn matched(skewed: SkewedSine) -> SineMoments {
        let target = skewed.moments;
        let split = SkewSplit::new(skewed.skewness);
        let reach = clamp_reach(skewed.reach);
        let target_sd = target.variance.max(0.0).sqrt();
        let (mut mean, mut sd) = (target.mean.clamp(-reach, reach), target_sd);
        // Secant steps in each: the truncated mean moves by less than the untruncated one
        // near a pole (by about half at 1.7 deviations from it), so a plain step undershoots.
        let mut last: Option<([f64; 2], [f64; 2])> = None;
        for _ in 0..MATCHING_STEPS {
            let got = Self::split(mean, sd, split, reach).truncated_moments();
            let got = [got.mean, got.variance.sqrt()];
            if !(got[1] > 0.0 && got[0].is_finite()) {
                break;
            }
            let at = [mean, sd];
            let slope = |l: usize| {
                let (before, got_before) = last?;
                let s = (got[l] - got_before[l]) / (at[l] - before[l]);
                (s.is_finite() && s > 0.1).then_some(s)
            };
            let mean_slope = slope(0).unwrap_or(1.0);
            let sd_slope = slope(1).unwrap_or(got[1] / sd);
            last = Some((at, got));
            mean = (mean + (target.mean - got[0]) / mean_slope).clamp(-reach, reach);
            sd = (sd + (target_sd - got[1]) / sd_slope).max(0.25 * target_sd);
        }
        // Within a deviation or two of an end no untruncated lobe inside [−e, e] has the
        // target's moments: there the match fades to the target itself, smoothly in the
        // distance, so that a table of it stays smooth.
        let distance = (reach - target.mean.abs()) / target_sd.max(f64::MIN_POSITIVE);
        let t = ((distance - 1.0) / (MATCHED_FROM - 1.0)).clamp(0.0, 1.0);
        let share = t * t * (3.0 - 2.0 * t);
        let sd = target_sd + share * (sd - target_sd);
        SineMoments {
            mean: target.mean + share * (mean - target.mean),
            variance: sd * sd,
        }
    }

    /// The mean and variance of the lobe as it is, each part truncated to [−e, e]
    /// (Johnson, Kotz & Balakrishnan 1994 §10.1: a normal of mean μ and deviation σ cut to
    /// [a, b] has mean μ + σ (φ(α) − φ(β)) / Z and variance
    /// σ² (1 + (α φ(α) − β φ(β)) / Z − ((φ(α) − φ(β)) / Z)²), α = (a − μ)/σ, β = (b − μ)/σ).
    pub fn truncated_moments(&self) -> SineMoments {
        let w = SKEW_WEIGHT;
        let mixture = match self.share < 1.0 {
            true => {
                let [a, b] = self.parts.map(|p| p.truncated_moments());
                [
                    (1.0 - w) * a.mean + w * b.mean,
                    (1.0 - w) * (a.variance + a.mean * a.mean) + w * (b.variance + b.mean * b.mean),
                ]
            }
            false => [0.0; 2],
        };
        let two_piece = match self.share > 0.0 {
            true => self.two_piece.truncated_raw_moments(),
            false => [0.0; 2],
        };
        let t = self.share;
        let [mean, second] = [0, 1].map(|k| (1.0 - t) * mixture[k] + t * two_piece[k]);
        SineMoments {
            mean,
            variance: (second - mean * mean).max(0.0),
        }
    }

    /// The mean and variance of the untruncated lobe.
    pub fn moments(&self) -> SineMoments {
        SineMoments {
            mean: self.mean,
            variance: self.sd * self.sd,
        }
    }

    /// M at sin θ_o = `sin_o`: the mixture's two Gaussians in one set of lanes, the
    /// two-piece's one, each where it has a share; 0 beyond the reach.
    #[inline]
    pub fn eval(&self, sin_o: f64) -> f64 {
        if sin_o.abs() > self.reach {
            return 0.0;
        }
        let t = self.share;
        let two_piece = match t > 0.0 {
            true => t * self.two_piece.eval(sin_o),
            false => 0.0,
        };
        if t >= 1.0 {
            return two_piece;
        }
        let [a, b] = self.parts;
        let za = (sin_o - a.mean) * a.inv_sd;
        let zb = (sin_o - b.mean) * b.inv_sd;
        let [ea, eb] = exp_pair(f64x2::new([-0.5 * za * za, -0.5 * zb * zb])).to_array();
        (1.0 - t) * ((1.0 - SKEW_WEIGHT) * a.peak * ea + SKEW_WEIGHT * b.peak * eb) + two_piece
    }

    /// sin θ_o drawn with density M from one uniform number: the mixture or the two-piece by
    /// their shares, then a part of the mixture, each with u rescaled
    /// ([`SineLobe::sample_sin`], `TwoPiece::sample_sin`).
    #[inline]
    pub fn sample_sin(&self, u: f64) -> f64 {
        let mixture = 1.0 - self.share;
        if u >= mixture {
            return self.two_piece.sample_sin((u - mixture) / self.share);
        }
        let u = u / mixture;
        let first = 1.0 - SKEW_WEIGHT;
        if u < first {
            self.parts[0].sample_sin(u / first)
        } else {
            self.parts[1].sample_sin((u - first) / SKEW_WEIGHT)
        }
    }
}

#[cfg(test)]
mod tests;
