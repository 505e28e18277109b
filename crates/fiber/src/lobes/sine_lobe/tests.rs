use super::*;
use crate::math::GaussLegendre;

/// Near a pole the truncation moves a lobe's mean toward the equator; the matched lobe's
/// truncated moments are the target's (two deviations or more from the pole), the plain
/// split's are not. `truncated_moments` is checked against the lobe's own density
/// integrated over [−1, 1].
#[test]
fn matched_lobe_has_the_target_moments_after_its_truncation() {
    // The mixture alone, the mixture passing to the two-piece, and the two-piece alone,
    // at the pole and at a reach short of it (the same distance to the end).
    for skewness in [0.2, 0.3, 0.6] {
        matched_lobe_has_the_target_moments(skewness, FULL_REACH);
        matched_lobe_has_the_target_moments(skewness, 0.99);
    }
}

fn matched_lobe_has_the_target_moments(skewness: f64, reach: f64) {
    let target = SkewedSine {
        moments: SineMoments {
            mean: -0.93 + (1.0 - reach),
            variance: 0.03f64.powi(2),
        },
        skewness,
        reach,
    };
    let integrated = |lobe: &SkewedSineLobe| {
        let n = 200_000;
        let mut m = [0.0f64; 3];
        for k in 0..n {
            let x = -1.0 + 2.0 * (k as f64 + 0.5) / n as f64;
            let f = lobe.eval(x) * 2.0 / n as f64;
            m = [m[0] + f, m[1] + f * x, m[2] + f * x * x];
        }
        SineMoments {
            mean: m[1] / m[0],
            variance: m[2] / m[0] - (m[1] / m[0]).powi(2),
        }
    };
    let plain = SkewedSineLobe::new(target);
    let matched = SkewedSineLobe::new(SkewedSine {
        moments: SkewedSineLobe::matched(target),
        ..target
    });
    for lobe in [&plain, &matched] {
        let (closed, summed) = (lobe.truncated_moments(), integrated(lobe));
        assert!(
            (closed.mean - summed.mean).abs() < 1e-7,
            "{closed:?} {summed:?}"
        );
        assert!((closed.variance / summed.variance - 1.0).abs() < 1e-4);
    }
    let got = integrated(&matched);
    assert!((got.mean - target.moments.mean).abs() < 2e-6, "{got:?}");
    assert!(
        (got.variance / target.moments.variance - 1.0).abs() < 2e-3,
        "{got:?}"
    );
    // The plain lobe misses: by more than 1e-4 as the mixture; the two-piece, whose steep
    // side faces the pole at this skew, loses less to the cut, but still ten times the
    // matched lobe's error.
    let missed = integrated(&plain);
    let (missed_by, got_by) = (
        (missed.mean - target.moments.mean).abs(),
        (got.mean - target.moments.mean).abs(),
    );
    let least = if skewness <= TWO_PIECE_FROM {
        1e-4
    } else {
        10.0 * got_by
    };
    assert!(missed_by > least, "γ {skewness}: {missed:?}");
    // Within one deviation of the pole the match is the target itself.
    let near = SkewedSine {
        moments: SineMoments {
            mean: -0.98,
            ..target.moments
        },
        ..target
    };
    assert_eq!(SkewedSineLobe::matched(near), near.moments);
}

/// Lobes in the middle of [−1, 1], at an end, past it and wide enough to meet both.
fn lobes() -> Vec<SineLobe> {
    [
        (-0.3, 0.02),
        (0.7, 0.05),
        (-0.98, 0.03),
        (1.0, 0.01),
        (-1.0, 0.2),
        (0.1, 0.8),
        (0.5, 1e-4),
    ]
    .into_iter()
    .map(|(mean, sd): (f64, f64)| {
        SineLobe::new(SineMoments {
            mean,
            variance: sd * sd,
        })
    })
    .collect()
}

/// ∫ M cos θ_o dθ_o = ∫ M dx over [−1, 1] is 1 within the bound of Φ at the ends (module
/// docs), also where the truncation cuts half of the Gaussian; a lobe without Z would
/// integrate to 0.5 at the ends.
#[test]
fn integrates_to_one_over_the_sphere() {
    let rule = GaussLegendre::cached(64);
    for lobe in lobes() {
        let (lo, hi) = (
            (lobe.mean - 12.0 * lobe.sd).max(-1.0),
            (lobe.mean + 12.0 * lobe.sd).min(1.0),
        );
        let panels = 64;
        let step = (hi - lo) / panels as f64;
        let total: f64 = (0..panels)
            .map(|k| {
                let a = lo + step * k as f64;
                rule.integrate(a, a + step, |x| lobe.eval(x))
            })
            .sum();
        assert!((total - 1.0).abs() < 3e-7, "{lobe:?}: {total}");
    }
}

/// A draw increases with u, across μ = 0 too.
#[test]
fn draws_increase_with_u_and_stay_continuous_in_the_mean() {
    let lobe = |mean: f64| {
        SineLobe::new(SineMoments {
            mean,
            variance: 0.04,
        })
    };
    for k in 1..100 {
        let u = k as f64 / 100.0;
        let (below, above) = (lobe(-1e-12).sample_sin(u), lobe(1e-12).sample_sin(u));
        assert!(
            (below - above).abs() < 1e-9,
            "u {u}: {below} against {above}"
        );
        assert!(lobe(0.3).sample_sin(u) > lobe(0.3).sample_sin(u - 0.01));
    }
}

/// The draws of `sample` over 400,000 stratified u against `eval`'s integral over each of
/// 40 bins across [lo, hi], within 2 % of the largest bin's share (the draws are
/// stratified, so the bins miss only by the strata they straddle).
fn assert_draws_follow(
    eval: impl Fn(f64) -> f64,
    sample: impl Fn(f64) -> f64,
    (lo, hi): (f64, f64),
    what: &str,
) {
    let rule = GaussLegendre::cached(16);
    let (draws, bins) = (400_000, 40);
    let width = (hi - lo) / bins as f64;
    let mut counts = vec![0.0; bins];
    for k in 0..draws {
        let x = sample((k as f64 + 0.5) / draws as f64);
        assert!((-1.0..=1.0).contains(&x), "{what}: drew {x}");
        let b = ((x - lo) / width).floor();
        if (0.0..bins as f64).contains(&b) {
            counts[b as usize] += 1.0 / draws as f64;
        }
    }
    let want: Vec<f64> = (0..bins)
        .map(|b| {
            let a = lo + width * b as f64;
            rule.integrate(a, a + width, &eval)
        })
        .collect();
    let largest = want.iter().cloned().fold(0.0, f64::max);
    for (b, (got, want)) in counts.iter().zip(&want).enumerate() {
        assert!(
            (got - want).abs() < 0.02 * largest,
            "{what} bin {b}: drawn {got} against {want}"
        );
    }
}

/// The draws follow M, at the ends as in the middle.
#[test]
fn draws_follow_the_density() {
    for lobe in lobes() {
        let range = (
            (lobe.mean - 6.0 * lobe.sd).max(-1.0),
            (lobe.mean + 6.0 * lobe.sd).min(1.0),
        );
        assert_draws_follow(
            |x| lobe.eval(x),
            |u| lobe.sample_sin(u),
            range,
            &format!("{lobe:?}"),
        );
    }
}

/// The skewed lobes of [`skewed_lobe_keeps_its_moments`], one cut by the pole, and three
/// cut short of it by their reach: the mixture, the two-piece, and the blend of both.
fn skewed_lobes() -> Vec<(SkewedSine, SkewedSineLobe)> {
    [
        (-0.5, 0.03, -LARGEST_SKEWNESS, FULL_REACH),
        (-0.5, 0.03, -0.3, FULL_REACH),
        (-0.5, 0.03, 0.0, FULL_REACH),
        (0.2, 0.05, 0.3, FULL_REACH),
        (0.2, 0.05, LARGEST_SKEWNESS, FULL_REACH),
        (0.2, 0.05, 0.7, FULL_REACH),
        (-0.4, 0.05, -0.9, FULL_REACH),
        (-0.97, 0.03, -0.5, FULL_REACH),
        (-0.93, 0.03, 0.1, 0.99),
        (-0.93, 0.03, 0.5, 0.98),
        (0.9, 0.05, -0.3, 0.95),
    ]
    .into_iter()
    .map(|(mean, sd, skewness, reach): (f64, f64, f64, f64)| {
        let skewed = SkewedSine {
            moments: SineMoments {
                mean,
                variance: sd * sd,
            },
            skewness,
            reach,
        };
        (skewed, SkewedSineLobe::new(skewed))
    })
    .collect()
}

/// Away from the ends the lobe has the mean, variance and skewness it is built with, as
/// the mixture, passing to the two-piece, and as the two-piece; a skewness past the
/// two-piece's largest is clamped to it.
#[test]
fn skewed_lobe_keeps_its_moments() {
    let rule = GaussLegendre::cached(64);
    for (skewed, lobe) in skewed_lobes().into_iter().take(7) {
        let SineMoments { mean, variance } = skewed.moments;
        let sd = variance.sqrt();
        let panels = 32;
        // Panels on either side of the two-piece's mode, where its curvature jumps.
        let mode = lobe.two_piece.mode;
        let moment = |k: i32| -> f64 {
            let f = |x: f64| lobe.eval(x) * (x - mean).powi(k);
            let side = |a: f64, b: f64| -> f64 {
                let step = (b - a) / panels as f64;
                (0..panels)
                    .map(|p| rule.integrate(a + step * p as f64, a + step * (p + 1) as f64, f))
                    .sum()
            };
            side(mean - 12.0 * sd, mode) + side(mode, mean + 12.0 * sd)
        };
        assert!((moment(0) - 1.0).abs() < 1e-9, "{skewed:?}");
        assert!(moment(1).abs() < 1e-9 * sd, "{skewed:?}: {}", moment(1));
        assert!((moment(2) / variance - 1.0).abs() < 1e-9, "{skewed:?}");
        let skewness = moment(3) / variance.powf(1.5);
        assert!(
            (skewness - skewed.skewness).abs() < 1e-9,
            "{skewed:?}: {skewness}"
        );
        let back = lobe.moments();
        assert!((back.mean - mean).abs() < 1e-12 && (back.variance / variance - 1.0).abs() < 1e-9);
    }
    let clamped = SkewedSineLobe::new(SkewedSine {
        moments: SineMoments {
            mean: 0.0,
            variance: 1e-4,
        },
        skewness: 3.0,
        reach: FULL_REACH,
    });
    let largest = SkewedSineLobe::new(SkewedSine {
        moments: SineMoments {
            mean: 0.0,
            variance: 1e-4,
        },
        skewness: TWO_PIECE_LARGEST,
        reach: FULL_REACH,
    });
    assert_eq!(clamped, largest);
}

/// The largest (ln M)″ over ±4 deviations of a lobe of deviation 0.01 about 0.
fn most_curved(lobe: SkewedSineLobe) -> f64 {
    let ln = |x: f64| lobe.eval(x).ln();
    let h = 1e-4;
    (-400..=400)
        .map(|k| k as f64 * 1e-4)
        .map(|x| (ln(x + h) - 2.0 * ln(x) + ln(x - h)) / (h * h))
        .fold(f64::MIN, f64::max)
}

/// At the mixture's largest skewness its parts' means are two of their deviations apart,
/// where it stops being log-concave: (ln M)″ ≤ 0 everywhere there, and not past it. The
/// lobe at every skewness, the mixture passing to the two-piece included, stays
/// log-concave.
#[test]
fn largest_skew_is_log_concave() {
    let split = SkewSplit::mixture(LARGEST_SKEWNESS);
    assert!(
        (split.offset / split.part_sd - 2.0).abs() < 1e-7,
        "{split:?}"
    );
    let at_the_cap = most_curved(SkewedSineLobe::split(0.0, 0.01, split, FULL_REACH));
    assert!(at_the_cap < 1e-3, "{at_the_cap}");
    let beyond = SkewSplit::from_channels(1.2 * split.offset, 0.0, 0.0);
    let bulge = most_curved(SkewedSineLobe::split(0.0, 0.01, beyond, FULL_REACH));
    assert!(bulge > 100.0, "{bulge}");
    for skewness in [0.1, 0.25, 0.3, LARGEST_SKEWNESS, 0.6, 0.9] {
        let lobe = SkewedSineLobe::new(SkewedSine {
            moments: SineMoments {
                mean: 0.0,
                variance: 1e-4,
            },
            skewness,
            reach: FULL_REACH,
        });
        let curved = most_curved(lobe);
        assert!(curved < 1e-3, "γ {skewness}: {curved}");
    }
}

/// The skewed lobe integrates to 1 where the pole or its reach cuts it, its draws follow
/// it, and it is 0 beyond its reach.
#[test]
fn skewed_draws_follow_the_density() {
    let rule = GaussLegendre::cached(64);
    for (skewed, lobe) in skewed_lobes() {
        let SineMoments { mean, variance } = skewed.moments;
        let e = skewed.reach;
        let range = (
            (mean - 8.0 * variance.sqrt()).max(-e),
            (mean + 8.0 * variance.sqrt()).min(e),
        );
        if e < FULL_REACH {
            let beyond = mean.signum() * (e + 1e-9);
            assert_eq!(lobe.eval(beyond), 0.0, "{skewed:?}");
            assert!(lobe.eval(mean.signum() * (e - 1e-9)) > 0.0, "{skewed:?}");
        }
        let panels = 32;
        let step = (range.1 - range.0) / panels as f64;
        let total: f64 = (0..panels)
            .map(|p| {
                let a = range.0 + step * p as f64;
                rule.integrate(a, a + step, |x| lobe.eval(x))
            })
            .sum();
        assert!((total - 1.0).abs() < 3e-7, "{skewed:?}: {total}");
        assert_draws_follow(
            |x| lobe.eval(x),
            |u| lobe.sample_sin(u),
            range,
            &format!("{skewed:?}"),
        );
    }
}

/// Far from the ends the lobe is the untruncated Gaussian: mean μ and variance σ² of x.
#[test]
fn away_from_the_ends_it_keeps_its_moments() {
    let lobe = SineLobe::new(SineMoments {
        mean: -0.68,
        variance: 0.0265f64.powi(2),
    });
    let rule = GaussLegendre::cached(64);
    let (lo, hi) = (lobe.mean - 10.0 * lobe.sd, lobe.mean + 10.0 * lobe.sd);
    let moment = |k: i32| rule.integrate(lo, hi, |x| lobe.eval(x) * x.powi(k));
    let mean = moment(1);
    let variance = moment(2) - mean * mean;
    assert!((mean + 0.68).abs() < 1e-12, "{mean}");
    assert!(
        (variance / 0.0265f64.powi(2) - 1.0).abs() < 1e-9,
        "{variance}"
    );
}
