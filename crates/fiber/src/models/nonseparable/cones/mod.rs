//! Cone angles and widths of the non-separable lobes from the Nusselt analysis of d'Eon et al.
//! 2014 §2.2, and the offset h that selects TT's: the paper's forms, and the checked exits
//! through the full rotation sequence that the tilted model takes instead.

use crate::geometry::bravais::azimuthal_deflection;
use crate::geometry::nusselt::AtScale;
use crate::geometry::nusselt::{self, Blocked, Nusselt};
use crate::lobes::sine_lobe::{FULL_REACH, SineMoments, SkewedSine};
use crate::math::{asin_fast, sin_cos_quadrant, unit_normal_midpoints};
use crate::models::nonseparable::scales::attenuation::incident;
use crate::optics::fresnel::fresnel_dielectric;
use std::cell::Cell;
use std::f64::consts::{FRAC_1_SQRT_2, FRAC_PI_2, PI};
use std::sync::OnceLock;

/// θ_cone of R (d'Eon et al. 2014 §2.3): −asin(sin θ_i − 2 sin α (cos(φ/2) cos α cos θ_i + sin α
/// sin θ_i)).
pub fn cone_r(theta_i: f64, alpha: f64, phi: f64) -> f64 {
    let (sa, ca) = alpha.sin_cos();
    let x =
        theta_i.sin() - 2.0 * sa * ((0.5 * phi).cos() * ca * theta_i.cos() + sa * theta_i.sin());
    -x.clamp(-1.0, 1.0).asin()
}

/// v_R = 2β²(1 − h²) = 2β² cos²(φ/2) (d'Eon et al. 2014 eq. 6).
pub fn variance_r(beta: f64, phi: f64) -> f64 {
    2.0 * (beta * (0.5 * phi).cos()).powi(2)
}

/// θ_cone of TT as d'Eon et al. 2014 eq. 7 and §2.4 give it: the Nusselt rotations with every
/// tilt α, square roots clamped, and the pole −sign(θ_i) π/2 where |x_TT| > 1. The clamp makes
/// that test fire only near h = 0 (see [`tt_exit`]).
pub fn cone_tt(theta_i: f64, alpha: f64, eta: f64, h: f64) -> f64 {
    pole_where_beyond(
        theta_i,
        nusselt::exit_tt([alpha; 2], eta, incident(theta_i, h)),
    )
}

/// θ_cone of TRT (d'Eon et al. 2014 eq. 8), evaluated at h = 0, with §2.4's pole.
pub fn cone_trt(theta_i: f64, alpha: f64, eta: f64) -> f64 {
    pole_where_beyond(
        theta_i,
        nusselt::exit_trt([alpha; 3], eta, incident(theta_i, 0.0)),
    )
}

/// The cone of an exit whose sine is x: asin x, or §2.4's pole −sign(θ_i) π/2 where |x| > 1.
pub(crate) fn pole_where_beyond(theta_i: f64, x: f64) -> f64 {
    if x.abs() > 1.0 {
        -theta_i.signum() * 0.5 * PI
    } else {
        x.asin()
    }
}

/// θ_cone of TT for the tilted model: the same rotations, whose clamped value continues the
/// cone smoothly past the offsets where the exit is totally reflected. There the tilted A(1, h)
/// is zero, so the cone only places what roughness blurs across that edge; no pole.
pub fn cone_tt_tilted(theta_i: f64, alpha: f64, eta: f64, h: f64) -> f64 {
    let x = nusselt::exit_tt([alpha; 2], eta, incident(theta_i, h));
    x.clamp(-1.0, 1.0).asin()
}

/// The TT exit direction at offset h through the full rotation sequence, or why it has none:
/// [`Blocked::TotalInternalReflection`] where η²(x_m² + y²) ≥ 1 in the second scale's frame,
/// tested before the final rotation, at every h (d'Eon et al. 2014 §2.4: "x_TT may not be real").
pub fn tt_exit(theta_i: f64, alpha: f64, eta: f64, h: f64) -> Result<Nusselt, Blocked> {
    nusselt::exit_tt_checked([alpha; 2], eta, incident(theta_i, h))
}

/// The TRT exit direction at offset h, or why it has none (its internal reflection is total or
/// partial alike; only the exit can be totally reflected).
pub fn trt_exit(theta_i: f64, alpha: f64, eta: f64, h: f64) -> Result<Nusselt, Blocked> {
    nusselt::exit_trt_checked([alpha; 3], eta, incident(theta_i, h))
}

/// v_TT = (½ β D_TT)², D_TT = 2(ηz′ − z)/cos θ_d with x = sin θ_d, y = h cos θ_d (d'Eon et al. 2014
/// §2.4, corrected as the module docs explain).
pub fn variance_tt(beta: f64, eta: f64, theta_d: f64, h: f64) -> f64 {
    let (x, c) = theta_d.sin_cos();
    let y = h * c;
    let r2 = x * x + y * y;
    let z = (1.0 - r2).max(0.0).sqrt();
    let zp = (1.0 - r2 / (eta * eta)).max(0.0).sqrt();
    let d = 2.0 * (eta * zp - z) / c.max(1e-6);
    (0.5 * beta * d).powi(2)
}

/// A von Mises–Fisher lobe as the sine of its cone and its variance in θ: TT's in the paper's
/// form, TRT's in both.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CutLobe {
    pub sin_cone: f64,
    pub variance: f64,
}

/// TT's first-order lobe at offset h (d'Eon et al. 2014 §2.4): the Nusselt exit's sine before
/// any clamp and [`variance_tt`] at θ_d = −θ_i.
pub fn first_order_tt(theta_i: f64, alpha: f64, eta: f64, beta: f64, h: f64) -> CutLobe {
    CutLobe {
        sin_cone: nusselt::exit_tt([alpha; 2], eta, incident(theta_i, h)),
        variance: variance_tt(beta, eta, -theta_i, h),
    }
}

/// TT's lobe at offset h through tilted scales, to first order in the slopes: the exit's
/// sine x before any clamp, and the spread of x through the scales the path meets, each
/// scale's tilt α perturbed by a Beckmann slope along the axis (standard deviation
/// σ = β/√2): Var x = Σ_k ((x(α_k + σ) − x(α_k − σ))/2)² over the entry and exit scales, a
/// two-point Gauss–Hermite rule per scale, which is ½β² Σ_k (∂x/∂α_k)² where x is linear in
/// the tilts and stays bounded where the exit nears the critical angle and the derivative
/// diverges: the mean and variance of the tilted model's TT lobe, which is Gaussian in the
/// exit sine ([`crate::lobes::sine_lobe`]). Untilted and away from the pole, its variance as a lobe
/// variance in θ ([`variance_from_sine_spread`]) is [`variance_tt`] (d'Eon et al. 2014 §2.4,
/// whose θ_o is −θ_i) to first order; a
/// tilt moves the refractions' angles of incidence and the exit's, and with them the spread:
/// narrower for α < 0, wider for α > 0, as the simulation's TT is
/// (docs/departures/12-tt-width.md).
pub fn first_order_tt_tilted(theta_i: f64, alpha: f64, eta: f64, beta: f64, h: f64) -> SineMoments {
    let incident = incident(theta_i, h);
    let (mean, variance) = sine_spread(alpha, beta, |tilts: [f64; 2]| {
        nusselt::exit_tt(tilts, eta, incident)
    });
    SineMoments { mean, variance }
}

/// The exit sine x of a path through N scales tilted by α, and its spread to first order in
/// the slopes along the axis: Var x = Σ_k ((x(α_k + σ) − x(α_k − σ))/2)², σ = β/√2, a
/// two-point Gauss–Hermite rule per scale (see [`first_order_tt_tilted`]).
fn sine_spread<const N: usize>(
    alpha: f64,
    beta: f64,
    exit: impl Fn([f64; N]) -> f64,
) -> (f64, f64) {
    let sigma = beta * FRAC_1_SQRT_2;
    let half_difference = |k: usize| {
        let (mut up, mut down) = ([alpha; N], [alpha; N]);
        up[k] += sigma;
        down[k] -= sigma;
        0.5 * (exit(up) - exit(down))
    };
    let x = exit([alpha; N]);
    (x, (0..N).map(|k| half_difference(k).powi(2)).sum())
}

/// TRT's exit sine x at offset h through scales tilted by α, and the spread of x to first
/// order in the slopes at its entry, internal-reflection and exit scales ([`sine_spread`]).
fn trt_sine_spread(theta_i: f64, alpha: f64, eta: f64, beta: f64, h: f64) -> (f64, f64) {
    let incident = incident(theta_i, h);
    sine_spread(alpha, beta, |tilts: [f64; 3]| {
        nusselt::exit_trt(tilts, eta, incident)
    })
}

/// TRT's first-order lobe through tilted scales at h = 0 ([`trt_sine_spread`]), the spread
/// as a lobe variance by [`variance_from_sine_spread`].
pub fn first_order_trt_tilted(theta_i: f64, alpha: f64, eta: f64, beta: f64) -> CutLobe {
    let (x, sine_variance) = trt_sine_spread(theta_i, alpha, eta, beta, 0.0);
    CutLobe {
        sin_cone: x,
        variance: variance_from_sine_spread(x, sine_variance),
    }
}

/// Offsets per half fiber (midpoints in γ = asin h) over which [`trt_lobe_tilted`] averages.
const TRT_OFFSETS: usize = 16;

/// TRT's lobe through tilted scales over the offsets (docs/departures/16-trt-width.md): the
/// cone at h = 0, as
/// d'Eon et al. 2014 §2.5 places it, and the spread of the exit's sine about it over the
/// offsets, weighted by `attenuation(h)` (TRT's A(2, h)) dh: E[Var x(h) + (x(h) − x(0))²],
/// each offset's spread by [`trt_sine_spread`], as a lobe variance by
/// [`variance_from_sine_spread`]. §2.5's D_TRT is the spread of an untilted fiber at
/// θ_d = −θ_i and h = 0, but under a tilt TRT leaves far from −θ_i (θ_o = −0.84 at θ_i = 1.1,
/// α = −2°), where that width is half again too wide, and the offsets near TRT's caustics,
/// which carry most of its light at small θ_i, spread less than h = 0. Only the offsets whose
/// smooth path leaves count; where they carry less than half of A(2, ·) (the scales block
/// most of TRT, α > 0 near grazing), the central path's spread is kept.
pub fn trt_lobe_over_offsets(
    theta_i: f64,
    alpha: f64,
    eta: f64,
    beta: f64,
    attenuation: impl Fn(f64) -> f64,
) -> CutLobe {
    let central = first_order_trt_tilted(theta_i, alpha, eta, beta);
    over_offsets(central, theta_i, alpha, eta, beta, attenuation)
}

/// [`trt_lobe_over_offsets`] about the `central` lobe its caller has found.
fn over_offsets(
    central: CutLobe,
    theta_i: f64,
    alpha: f64,
    eta: f64,
    beta: f64,
    attenuation: impl Fn(f64) -> f64,
) -> CutLobe {
    let (mut leaving, mut all, mut second_moment) = (0.0, 0.0, 0.0);
    for k in 0..TRT_OFFSETS {
        // A(2, h) and x(h) are even in h: the half fiber h ≥ 0 stands for both.
        let gamma = FRAC_PI_2 * (k as f64 + 0.5) / TRT_OFFSETS as f64;
        let h = gamma.sin();
        let weight = attenuation(h) * gamma.cos();
        if weight <= 0.0 {
            continue;
        }
        all += weight;
        if trt_exit(theta_i, alpha, eta, h).is_err() {
            continue;
        }
        let (x, sine_variance) = trt_sine_spread(theta_i, alpha, eta, beta, h);
        leaving += weight;
        second_moment += weight * (sine_variance + (x - central.sin_cone).powi(2));
    }
    if leaving <= 0.5 * all {
        return central;
    }
    CutLobe {
        sin_cone: central.sin_cone,
        variance: variance_from_sine_spread(central.sin_cone, second_moment / leaving),
    }
}

/// The tilted model's TRT lobe: [`trt_lobe_over_offsets`], then, as TT's [`tt_lobe_rough`],
/// its cone moved to the mean of the paths that leave at h = 0 and its width narrowed by the
/// ratio of their spread to the first order's ([`trt_axial_cut`], departure 17).
pub fn trt_lobe_tilted(
    theta_i: f64,
    alpha: f64,
    eta: f64,
    beta: f64,
    attenuation: impl Fn(f64) -> f64,
) -> CutLobe {
    let central = first_order_trt_tilted(theta_i, alpha, eta, beta);
    let averaged = over_offsets(central, theta_i, alpha, eta, beta, attenuation);
    let Some(cut) = trt_axial_cut(theta_i, alpha, eta, beta) else {
        return averaged;
    };
    CutLobe {
        sin_cone: averaged.sin_cone + (cut.sin_cone - central.sin_cone),
        variance: averaged.variance * (cut.variance / central.variance).min(1.0),
    }
}

/// The variance v of a longitudinal lobe whose cone has sine x and whose directions' sines
/// spread with variance `sine_variance`. The lobe is a spherical Gaussian of variance v per
/// axis about its cone (d'Eon et al. 2011's M integrates one over the azimuth), so to second
/// order sin θ_o = x + cos θ_c δ_θ − ½x(δ_θ² + δ_φ²) and Var sin θ_o = v cos²θ_c + v² x²;
/// solved for v. Away from the pole this is the first order, Var sin θ_o / cos²θ_c; at the
/// pole it is √Var / |x|, where the first order diverges.
pub fn variance_from_sine_spread(x: f64, sine_variance: f64) -> f64 {
    let s2 = (x * x).min(1.0);
    let c2 = 1.0 - s2;
    // v = (√(c⁴ + 4 s² V) − c²) / (2 s²), written without the cancellation of that form.
    2.0 * sine_variance / ((c2 * c2 + 4.0 * s2 * sine_variance).sqrt() + c2)
}

/// Equal-probability scale tilts per event in [`axial_cut`]: 48² paths per θ_i.
const TT_TILTS: usize = 48;

/// The standard normal's [`TT_TILTS`] equal-probability midpoints of unit variance.
fn unit_tilts() -> &'static [f64; TT_TILTS] {
    static TILTS: OnceLock<[f64; TT_TILTS]> = OnceLock::new();
    TILTS.get_or_init(unit_normal_midpoints::<TT_TILTS>)
}

/// The tilted model's TT lobe at offset h, as the mean and variance of its exit sine: the
/// first-order lobe through the tilted scales ([`first_order_tt_tilted`]) moved and narrowed
/// as the rough exit cuts it at grazing incidence.
///
/// The cut: a path leaves only while its direction stays above the surface of the scale it
/// leaves through. At grazing incidence the TT cone comes within a few standard deviations of
/// the surface along the axis; the tilts that would send a path past it reflect it inside
/// instead, and Fresnel's transmission falls to 0 before they do, so what leaves is narrower
/// and further from the surface. [`axial_cut`] measures that at h = 0, where only the axial
/// tilts approach the surface, and the lobe at h takes its shift in sine and its ratio of
/// variances. At other offsets the azimuthal tilts, which this leaves out, move the bound
/// itself from path to path: the simulation's TT at |φ| near π/2 keeps the first-order
/// cone and width, where a cut in the axial tilts alone at that h would move it by a
/// standard deviation. This departs from d'Eon et al. 2014 §2.4, whose lobe is first order
/// alone.
pub fn tt_lobe_rough(theta_i: f64, alpha: f64, eta: f64, beta: f64, h: f64) -> SineMoments {
    let at_h = first_order_tt_tilted(theta_i, alpha, eta, beta, h);
    let Some(SkewedSine { moments: cut, .. }) = axial_cut_last(theta_i, alpha, eta, beta) else {
        return at_h;
    };
    let centre = first_order_tt_tilted(theta_i, alpha, eta, beta, 0.0);
    SineMoments {
        mean: at_h.mean + (cut.mean - centre.mean),
        variance: at_h.variance * (cut.variance / centre.variance).min(1.0),
    }
}

/// The skewness of TT's exit sine at θ_i: [`axial_cut`]'s at h = 0, which the lobe at every
/// offset takes, as it takes the cut's shift; 0 where no path leaves. To first order the exit
/// sine is linear in the slopes and has none; the second order and the cut give it one
/// (docs/departures/19-tt-sine-lobe.md).
pub fn tt_skewness(theta_i: f64, alpha: f64, eta: f64, beta: f64) -> f64 {
    axial_cut_last(theta_i, alpha, eta, beta).map_or(0.0, |cut| cut.skewness)
}

/// [`axial_cut`], kept for the last arguments on each thread: the lobe table asks for a whole
/// row of φ at one θ_i, and the cut depends on θ_i alone.
fn axial_cut_last(theta_i: f64, alpha: f64, eta: f64, beta: f64) -> Option<SkewedSine> {
    type Last = Option<([f64; 4], Option<SkewedSine>)>;
    thread_local! {
        static LAST: Cell<Last> = const { Cell::new(None) };
    }
    let key = [theta_i, alpha, eta, beta];
    LAST.with(|last| match last.get() {
        Some((k, cut)) if k == key => cut,
        _ => {
            let cut = axial_cut(theta_i, alpha, eta, beta);
            last.set(Some((key, cut)));
            cut
        }
    })
}

/// TT's lobe at h = 0 from the paths that leave: each scale's tilt α + δ, δ the Beckmann slope
/// along the axis (standard deviation β/√2, the convention of [`variance_tt`]), on a product
/// grid of equal-probability tilts at entry and exit, followed through the rotation sequence,
/// weighted by both Fresnel transmissions and the cosines that make a micro-normal more or
/// less visible, the paths the exit totally reflects left out. The mean, variance and
/// skewness of the exit sine: [`first_order_tt_tilted`] to first order, with no skew. `None`
/// where no path leaves, and faded to first order where almost none does (`FADE`). The
/// skewness is damped where the exit cuts much (below).
pub fn axial_cut(theta_i: f64, alpha: f64, eta: f64, beta: f64) -> Option<SkewedSine> {
    let sigma = beta * FRAC_1_SQRT_2;
    let incident = incident(theta_i, 0.0);
    let (mut sums, mut arriving) = (SineSums::default(), 0.0);
    for &d1 in unit_tilts() {
        let Some((inward, t1)) = enter(alpha + sigma * d1, eta, incident) else {
            continue;
        };
        for &d2 in unit_tilts() {
            let Ok(at) = AtScale::inside(alpha + sigma * d2, nusselt::propagate(inward)) else {
                continue;
            };
            arriving += t1 * at.cos;
            let Ok((x, _)) = at.refract(eta) else {
                continue;
            };
            sums.add(
                t1 * at.cos * (1.0 - fresnel_dielectric(at.cos, 1.0 / eta)),
                x,
            );
        }
    }
    let cut = sums.moments()?;
    // Where the exit lets out under FADE of what arrives there, the few paths left decide
    // the moments, and the last to go would leave a jump to `None`: fade to first order.
    let fade = (sums.weight / (arriving * FADE)).min(1.0);
    let first = first_order_tt_tilted(theta_i, alpha, eta, beta, 0.0);
    Some(SkewedSine {
        moments: SineMoments {
            mean: first.mean + fade * (cut.mean - first.mean),
            variance: first.variance + fade * (cut.variance - first.variance),
        },
        // The cut's own skew, which trims the side toward the pole, is found at h = 0 on the
        // axial slopes alone, and overshoots the simulation's where the exit cuts much (the
        // azimuthal slopes and the other offsets blur its edge): it counts by the square of
        // the share that leaves (departure 19).
        skewness: fade * sums.skewness() * (sums.weight / arriving).powi(2),
        reach: FULL_REACH,
    })
}

/// Equal-probability scale tilts per event in [`trt_axial_cut`]: 16³ paths per θ_i.
const TRT_TILTS: usize = 16;

/// TRT's lobe at h = 0 from the paths that leave, as [`axial_cut`] finds TT's
/// (docs/departures/17-trt-cut.md): each of its three scales tilted by α + σδ, σ = β/√2,
/// over [`TRT_TILTS`] equal-probability δ of the standard normal, each path weighted by the
/// projected micro-normal and its Fresnel transmissions in and out and internal reflectance;
/// the moments of the exit sine over the paths that leave. At grazing incidence the exit's
/// total reflection trims the side of the lobe toward the pole, and the simulated TRT is
/// narrower than the first order ([`first_order_trt_tilted`]; 0.13 against 0.17 in θ at
/// θ_i = 1.1, α = 0, β = 0.04). `None` where none leaves.
pub fn trt_axial_cut(theta_i: f64, alpha: f64, eta: f64, beta: f64) -> Option<CutLobe> {
    static TILTS: OnceLock<[f64; TRT_TILTS]> = OnceLock::new();
    let tilts = TILTS.get_or_init(unit_normal_midpoints::<TRT_TILTS>);
    let sigma = beta * FRAC_1_SQRT_2;
    let incident = incident(theta_i, 0.0);
    let mut sums = SineSums::default();
    for &d1 in tilts {
        let Some((inward, t1)) = enter(alpha + sigma * d1, eta, incident) else {
            continue;
        };
        for &d2 in tilts {
            let Ok(at) = AtScale::inside(alpha + sigma * d2, nusselt::propagate(inward)) else {
                continue;
            };
            let Ok(reflected) = at.reflect() else {
                continue;
            };
            let r2 = t1 * at.cos * fresnel_dielectric(at.cos, 1.0 / eta);
            for &d3 in tilts {
                let Ok(out) = AtScale::inside(alpha + sigma * d3, nusselt::propagate(reflected))
                else {
                    continue;
                };
                let Ok((x, _)) = out.refract(eta) else {
                    continue;
                };
                sums.add(
                    r2 * out.cos * (1.0 - fresnel_dielectric(out.cos, 1.0 / eta)),
                    x,
                );
            }
        }
    }
    sums.lobe()
}

/// A path's refraction into the fiber through a scale tilted by `tilt`: the inward direction
/// and its weight, the projected micro-normal times Fresnel's transmission; `None` where the
/// scale is blocked.
fn enter(tilt: f64, eta: f64, incident: Nusselt) -> Option<(Nusselt, f64)> {
    let entry = AtScale::outside(tilt, incident).ok()?;
    let inward = entry.refract(eta).ok()?;
    Some((
        inward,
        entry.cos * (1.0 - fresnel_dielectric(entry.cos, eta)),
    ))
}

/// The weighted sums of the exit sines of the paths a cut keeps.
#[derive(Clone, Copy, Debug, Default)]
struct SineSums {
    weight: f64,
    sum: f64,
    sum_of_squares: f64,
    sum_of_cubes: f64,
}

impl SineSums {
    fn add(&mut self, weight: f64, x: f64) {
        self.weight += weight;
        self.sum += weight * x;
        self.sum_of_squares += weight * x * x;
        self.sum_of_cubes += weight * x * x * x;
    }

    /// E[(x − μ)³] / σ³ of the exit sines; 0 where they have no spread.
    fn skewness(&self) -> f64 {
        let Some(SineMoments { mean, variance }) = self.moments() else {
            return 0.0;
        };
        if variance <= 0.0 {
            return 0.0;
        }
        let third = self.sum_of_cubes / self.weight - 3.0 * mean * variance - mean.powi(3);
        third / variance.powf(1.5)
    }

    /// The mean and variance of the exit sines; `None` where no path left.
    fn moments(&self) -> Option<SineMoments> {
        if self.weight <= 0.0 {
            return None;
        }
        let mean = self.sum / self.weight;
        let variance = (self.sum_of_squares / self.weight - mean * mean).max(0.0);
        Some(SineMoments { mean, variance })
    }

    /// The von Mises–Fisher lobe at their mean, its variance from their spread
    /// ([`variance_from_sine_spread`]); `None` where no path left.
    fn lobe(&self) -> Option<CutLobe> {
        let SineMoments { mean, variance } = self.moments()?;
        Some(CutLobe {
            sin_cone: mean,
            variance: variance_from_sine_spread(mean, variance),
        })
    }
}

/// The share of the power arriving at TT's exit that must leave for [`axial_cut`]'s moments
/// to count in full; below it they fade linearly to the first-order lobe, so that the lobe
/// stays continuous in θ_i where TT goes dark.
const FADE: f64 = 0.05;

/// TRT's azimuthal variance in the tilted model: β², where d'Eon et al. 2014 §2.5 takes 2β²
/// (d'Eon et al. 2011's v_{2,N}). To first order, a Beckmann slope across the fiber
/// (standard deviation β/√2) at each of TRT's three events turns its exit azimuth by about
/// 0.9, 0.8 and −0.6 times the slope at h = 0 (θ_i = 0.25), and by 1, 0 and −1 at the caustic
/// that shapes the lobe at small θ_i, so its spread is about β there, not √2 β
/// (`tests/tilted_tir.rs` measures it on an exact trace;
/// docs/departures/13-trt-trrt-azimuthal-width.md). Untilted; a tilt, other offsets and the
/// caustics of steeper incidence add the axial slopes' share and more, which a constant leaves out.
pub fn trt_azimuthal_variance(beta: f64) -> f64 {
    beta * beta
}

/// TRRT's azimuthal variance in the tilted model: 12 β², where d'Eon et al. 2014 keeps
/// d'Eon et al. 2011's 2β². With two internal reflections, the slopes at TRRT's four events
/// spread its exit azimuth by 3.3–3.7 β to first order (θ_i from 0.25 to 0.75, h ≤ 0.6, an
/// exact trace in `tests/tilted_tir.rs`; docs/departures/13-trt-trrt-azimuthal-width.md), so the
/// model takes (2√3 β)², not (√2 β)².
pub fn trrt_azimuthal_variance(beta: f64) -> f64 {
    12.0 * beta * beta
}

/// v_TRT = ¼ β² D_TRT², D_TRT = (−2 cos θ_d + 4η √(1 − sin²θ_d/η²)) / cos θ_d (d'Eon et al. 2014
/// §2.5).
pub fn variance_trt(beta: f64, eta: f64, theta_d: f64) -> f64 {
    let (s, c) = theta_d.sin_cos();
    let d = (-2.0 * c + 4.0 * eta * (1.0 - s * s / (eta * eta)).max(0.0).sqrt()) / c.max(1e-6);
    0.25 * (beta * d).powi(2)
}

/// The offset h whose TT path leaves at azimuth φ: the root of Φ(1, h) = φ (unique: Φ(1, ·)
/// decreases from 2π − 2c at h = −1 to 2c at h = 1, c = asin(1/η′)); clamped to ±1 outside.
/// Newton's method on γ_i, safeguarded by the bracket where Φ − φ changes sign, with Φ and its
/// slope written in γ_i (no asin of sin γ_i) and the fast sine, cosine and arcsine of
/// [`crate::math`]; [`tt_offset_reference`] is its twin in the library's functions.
pub fn tt_offset(phi: f64, eta_prime: f64) -> f64 {
    let target = phi.rem_euclid(2.0 * PI);
    let (mut lo, mut hi) = (-0.5 * PI, 0.5 * PI);
    // Φ(1, γ) − φ and dΦ/dγ = 2 cos γ / (η′ cos γ_t) − 2.
    let miss_and_slope = |g: f64| {
        let (sg, cg) = sin_cos_quadrant(g);
        let st = sg / eta_prime;
        let gt = asin_fast(st);
        let ct = (1.0 - st * st).max(1e-300).sqrt();
        (
            2.0 * gt - 2.0 * g + PI - target,
            2.0 * cg / (eta_prime * ct) - 2.0,
        )
    };
    if target >= miss_and_slope(lo).0 + target {
        return -1.0;
    }
    if target <= miss_and_slope(hi).0 + target {
        return 1.0;
    }
    let mut g = (0.5 * (PI - target) / (1.0 - 1.0 / eta_prime)).clamp(lo, hi);
    for _ in 0..TT_OFFSET_STEPS {
        let (f, slope) = miss_and_slope(g);
        if f > 0.0 {
            lo = g
        } else {
            hi = g
        }
        let newton = g - f / slope;
        if newton > lo && newton < hi {
            // Quadratic convergence: a step this small leaves an error below 1e-16.
            let converged = (newton - g).abs() < 1e-9;
            g = newton;
            if converged {
                break;
            }
        } else {
            g = 0.5 * (lo + hi);
            if hi - lo < 1e-14 {
                break;
            }
        }
    }
    sin_cos_quadrant(g).0
}

/// Newton steps after which [`tt_offset`] stops (it takes about four).
const TT_OFFSET_STEPS: usize = 64;

/// [`tt_offset`]'s reference twin: the same safeguarded Newton on γ_i through
/// [`azimuthal_deflection`] and the library's `sin`, `asin` and `cos`, to a step of 1e-13.
pub fn tt_offset_reference(phi: f64, eta_prime: f64) -> f64 {
    let target = phi.rem_euclid(2.0 * PI);
    let (mut lo, mut hi) = (-0.5 * PI, 0.5 * PI);
    let deflection = |g: f64| azimuthal_deflection(1, g.sin(), eta_prime);
    if target >= deflection(lo) {
        return -1.0;
    }
    if target <= deflection(hi) {
        return 1.0;
    }
    let mut g = 0.5 * (PI - target) / (1.0 - 1.0 / eta_prime);
    g = g.clamp(lo, hi);
    for _ in 0..50 {
        let f = deflection(g) - target;
        if f > 0.0 {
            lo = g
        } else {
            hi = g
        }
        let gt = (g.sin() / eta_prime).asin();
        let slope = 2.0 * g.cos() / (eta_prime * gt.cos()) - 2.0;
        let mut next = g - f / slope;
        if !(next > lo && next < hi) {
            next = 0.5 * (lo + hi);
        }
        if (next - g).abs() < 1e-13 {
            g = next;
            break;
        }
        g = next;
    }
    g.sin()
}

#[cfg(test)]
mod tests;
