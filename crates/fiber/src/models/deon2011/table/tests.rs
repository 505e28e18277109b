use super::*;
use crate::models::nonseparable::cuticle::{WithScales, surface_of};

/// Per lobe (TT, TRT, TRRT, rest) and for their sum: Σ|table − direct| / Σ direct over a
/// grid of (θ_i, θ_o, φ) that falls between the table's nodes.
fn relative_l1(beta: f64) -> [f64; 5] {
    let az = AzimuthalScattering::new(1.55, beta, DVec3::new(0.1, 0.4, 1.2));
    let table = AzimuthalTable::build(&az);
    let (mut err, mut mass) = ([0.0; 5], [0.0; 5]);
    for k in 0..17 {
        let theta_i = -1.45 + 2.9 * (k as f64 + 0.37) / 17.0;
        for theta_o in [-1.31, -0.52, 0.07, 0.66, 1.38] {
            let theta_d = 0.5 * (theta_o - theta_i);
            for f in 0..97 {
                let phi = -PI + 2.0 * PI * (f as f64 + 0.29) / 97.0;
                let (mut sum_direct, mut sum_fast) = (0.0, 0.0);
                for p in 1..5 {
                    let direct = az.eval(p, theta_i, theta_d, phi, Weighting::Attenuation).x;
                    let fast = table
                        .eval(p, theta_i, theta_d, phi, Weighting::Attenuation)
                        .x;
                    err[p - 1] += (direct - fast).abs();
                    mass[p - 1] += direct;
                    sum_direct += direct;
                    sum_fast += fast;
                }
                err[4] += (sum_direct - sum_fast).abs();
                mass[4] += sum_direct;
            }
        }
    }
    std::array::from_fn(|k| err[k] / mass[k])
}

/// Measured (quoted in BENCHMARKS.md): the sum of the tabulated lobes is within 0.5 % in L1
/// and TT within 0.1 %; TRT (2 %) and TRRT (7 % at β = 0.04) are coarser, because their
/// caustics move with η′(θ_d) faster than 32 nodes in 1/η′ follow.
#[test]
fn table_follows_direct_quadrature() {
    for beta in [0.04, 0.15, 0.3] {
        let e = relative_l1(beta);
        println!(
            "β {beta}: relative L1 TT {:.5} TRT {:.5} TRRT {:.5} rest {:.5} sum {:.5}",
            e[0], e[1], e[2], e[3], e[4]
        );
        assert!(e[0] < 0.002 && e[4] < 0.005, "β {beta}: {e:?}");
        assert!(e[1] < 0.03 && e[2] < 0.1 && e[3] < 0.01, "β {beta}: {e:?}");
    }
}

/// The square-root inverse against the axis it inverts, over every node and a dense grid
/// between them. In θ_i the round trip is within 1e-15; in the coordinate, within 4e-15
/// away from the ends and 1e-12 at them (the axis is flat at grazing, dθ_i/dx → 0, so a
/// rounding of θ_i moves x by more, as it would through an arcsine): far below the 6e-8
/// resolution of the table's f32 fractions.
#[test]
fn theta_i_coordinate_inverts_the_node_placement() {
    let (mut in_theta, mut inner, mut ends): (f64, f64, f64) = (0.0, 0.0, 0.0);
    let nodes = (0..THETA_I_NODES).map(|i| i as f64 / (THETA_I_NODES - 1) as f64);
    for c in (0..=100_000).map(|k| k as f64 / 100_000.0).chain(nodes) {
        let theta = theta_i_of_coord(c);
        let back = theta_i_coord(theta);
        in_theta = in_theta.max((theta_i_of_coord(back) - theta).abs());
        let e = (back - c).abs();
        if (c - 0.5).abs() < 0.49 {
            inner = inner.max(e);
        } else {
            ends = ends.max(e);
        }
    }
    eprintln!(
        "θ_i coordinate round trip: θ_i {in_theta:.2e}, coordinate {inner:.2e} inside, {ends:.2e} at the ends"
    );
    assert!(
        in_theta < 1e-15 && inner < 4e-15 && ends < 1e-12,
        "{in_theta:e} {inner:e} {ends:e}"
    );
    assert_eq!(theta_i_coord(2.0), 1.0);
    assert_eq!(theta_i_coord(-2.0), 0.0);
    assert_eq!(theta_i_coord(0.0), 0.5);
    // Denser toward grazing: the last cell is the narrowest, the middle one the widest.
    let cell = |i: usize| theta_i_at(i + 1) - theta_i_at(i);
    assert!(cell(THETA_I_NODES - 2) < cell(THETA_I_NODES / 2 - 1));
}

/// The corner-weight taps against the nested lerps, at points between the nodes, on the
/// nodes and at the table's far corners: within 1e-6 of the largest texel involved (f32
/// arithmetic in another order).
#[test]
fn selection_taps_are_the_taps_selection() {
    let az = AzimuthalScattering::new(1.55, 0.1, DVec3::new(0.2, 0.5, 1.1));
    let table = AzimuthalTable::build(&az);
    let mut compared = 0;
    for k in 0..23 {
        let theta_i = (k as f64 / 22.0 - 0.5) * 0.9999 * PI;
        for eta_ratio in [0.0, 0.13, 0.5, 0.77, 1.0] {
            for f in 0..41 {
                let phi = -PI + 2.0 * PI * f as f64 / 40.0;
                let at = table.point(theta_i, eta_ratio, phi);
                let full = table.taps(at).map(|t| t.w);
                assert_eq!(table.selection_taps(at), full, "θ_i {theta_i} φ {phi}");
                compared += 1;
            }
        }
    }
    assert_eq!(compared, 23 * 5 * 41);
}

#[test]
fn corner_weights_match_the_nested_lerps() {
    let az = AzimuthalScattering::new(1.55, 0.1, DVec3::new(0.2, 0.5, 1.1));
    let table = AzimuthalTable::build(&az);
    let mut worst: f32 = 0.0;
    for k in 0..23 {
        let theta_i = (k as f64 / 22.0 - 0.5) * 0.9999 * PI;
        for (d, eta_ratio) in [0.0, 0.13, 0.5, 0.77, 1.0].into_iter().enumerate() {
            for f in 0..41 {
                let phi = -PI + 2.0 * PI * (f as f64 + 0.1 * d as f64) / 40.0;
                let at = table.point(theta_i, eta_ratio, phi);
                let (fast, nested) = (table.taps(at), table.taps_nested(at));
                for (a, b) in fast.iter().zip(&nested) {
                    let scale = a.abs().max(b.abs()).max_element().max(1e-3);
                    worst = worst.max((*a - *b).abs().max_element() / scale);
                }
            }
        }
    }
    eprintln!("corner-weight taps vs nested lerps: ≤ {worst:.2e} of the texel");
    assert!(worst < 1e-6, "{worst:e}");
}

/// The locate of the simplified clamp against its twin by floor and min: the same cell
/// and the same fraction (bit for bit) on every coordinate in [0, 1]; NaN stays in the
/// table (the last cell, f64::min keeping the number).
#[test]
fn locate_matches_floor_and_min() {
    for n in [THETA_D_NODES, THETA_I_NODES, 1024] {
        for k in 0..=20_011 {
            let t = k as f64 / 20_011.0;
            let x = t * (n - 1) as f64;
            let i = (x.floor() as usize).min(n - 2);
            assert_eq!(locate(t, n), (i, (x - i as f64) as f32), "n {n} t {t}");
        }
        assert_eq!(locate(1.0, n), (n - 2, 1.0));
        assert_eq!(locate(f64::NAN, n).0, n - 2);
    }
}

/// The Gaussian stepped along the columns by its ratio recurrence against the Gaussian at
/// every column, for widths of one to forty columns (the table's lobes are one to six wide)
/// and centres whose images wrap past 0 and π: within 1e-12 of the peak up to six columns,
/// 1e-10 at forty (the rounding of e^(−s²/σ²) compounds over the 16σ/s steps), far below
/// the table's f32 texels.
#[test]
fn splat_recurrence_matches_the_gaussian_at_every_column() {
    let columns = 1024;
    let step = PI / (columns - 1) as f64;
    for (sigma, bound) in [
        (step, 1e-12),
        (2.7 * step, 1e-12),
        (6.0 * step, 1e-12),
        (40.0 * step, 1e-10),
    ] {
        let splat = Splat::new(sigma, columns);
        assert!(splat.ratio_step.is_some());
        for center in [1e-3 - PI, -0.01, 0.0, 0.37, 1.5 + 0.3 * step, PI, PI - 1e-3] {
            let value = [1.0, 0.5, -2.0, 3.0];
            let (mut fast, mut direct) = (vec![[0.0; 4]; columns], vec![[0.0; 4]; columns]);
            splat.add(center, value, &mut fast);
            splat.add_direct(center, value, &mut direct);
            let peak = 3.0 / (sigma * (2.0 * PI).sqrt());
            let worst = fast
                .iter()
                .flatten()
                .zip(direct.iter().flatten())
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            assert!(
                worst < bound * peak,
                "σ {sigma} centre {center}: {:e}",
                worst / peak
            );
            assert!(direct.iter().flatten().any(|v| v.abs() > 1e-3 * peak));
        }
    }
    assert!(Splat::new(0.5 * step, columns).ratio_step.is_none());
}

/// Rows of a fiber with tilted, rough scales at β = 0.005, whose narrow lobes need more
/// quadrature nodes than [`TRACED_OFFSETS`], built with A(p, h) interpolated between the
/// traced offsets against the same rows with A traced at every node.
#[test]
fn interpolated_attenuation_follows_the_traced_one() {
    let beta = 0.005;
    let az = AzimuthalScattering::new(1.55, beta, DVec3::new(0.1, 0.4, 1.2))
        .with_scale_tilt((-4.0f64).to_radians())
        .with_rough_surface(beta);
    let panels = BLURRED
        .iter()
        .map(|&p| az.panel_count(p, az.eta))
        .max()
        .unwrap();
    assert!(
        panels * PANEL_NODES > TRACED_OFFSETS,
        "the rows must interpolate"
    );
    let phi_nodes = MAX_PHI_NODES;
    let slab = THETA_D_NODES * phi_nodes;
    let (mut err, mut mass, mut worst, mut peak) =
        ([0.0f64; 3], [0.0f64; 3], [0.0f64; 3], [0.0f64; 3]);
    for i in [4, 20, 33, 47, 58, 62] {
        let theta_i = theta_i_at(i);
        let (mut fast, mut traced) = (vec![[Vec4::ZERO; 3]; slab], vec![[Vec4::ZERO; 3]; slab]);
        fill_row(&az, None, theta_i, phi_nodes, &mut fast);
        let nodes = row_nodes_on(&az, None, theta_i, panels, |_, h| {
            az.attenuation(theta_i, h)
        });
        splat_row(&az, theta_i, &nodes, phi_nodes, &mut traced);
        for (f, t) in fast.iter().zip(&traced) {
            for l in 0..3 {
                let (a, b) = (f[l].x as f64, t[l].x as f64);
                err[l] += (a - b).abs();
                mass[l] += b;
                worst[l] = worst[l].max((a - b).abs());
                peak[l] = peak[l].max(b);
            }
        }
    }
    let l1: [f64; 3] = std::array::from_fn(|l| err[l] / mass[l]);
    let max: [f64; 3] = std::array::from_fn(|l| worst[l] / peak[l]);
    eprintln!(
        "interpolated A: relative L1 {l1:?}, largest error {max:?} of the peak (TT, TRT, TRRT)"
    );
    assert!(
        l1.iter().all(|e| *e < 1e-4) && max.iter().all(|e| *e < 5e-4),
        "{l1:?} {max:?}"
    );
}

/// Between two θ_i rows where TT's energy falls by a factor of 10 (its exit through
/// scales tilted by 4° passes the critical angle, β = 0.02), the table's N_TT integrated
/// over φ, at three θ_d, against ½ ∫ A(1, h) dh traced at that θ_i itself: within 2 %
/// (measured 1.0 %), where a linear blend of the rows' energies is a quarter too bright
/// and more ([`energy`]).
#[test]
fn energy_follows_the_lobe_between_the_nodes() {
    let beta = 0.02;
    let az = AzimuthalScattering::new(1.55, beta, DVec3::ZERO)
        .with_scale_tilt(4f64.to_radians())
        .with_rough_surface(beta);
    let table = AzimuthalTable::build(&az);
    let (lo, hi) = (theta_i_at(45), theta_i_at(46));
    let energy = |theta_i: f64| {
        crate::models::nonseparable::scales::attenuation::energy_budget(
            theta_i,
            surface_of(&az),
            DVec3::ZERO,
        )
        .lobes
        .0[1]
            .x
    };
    assert!(energy(lo) > 10.0 * energy(hi), "the rows must differ");
    let columns = 8192;
    let mut worst = 0.0f64;
    for theta_i in [1.07, 1.085, 1.1] {
        let exact = energy(theta_i);
        let t = (theta_i_coord(theta_i) * (THETA_I_NODES - 1) as f64).fract();
        let blend = energy(lo) + t * (energy(hi) - energy(lo));
        assert!(blend > 1.25 * exact, "θ_i {theta_i}: {blend} {exact}");
        for theta_d in [-theta_i, -0.3, 0.2] {
            let integral: f64 = (0..columns)
                .map(|f| {
                    let phi = -PI + 2.0 * PI * (f as f64 + 0.5) / columns as f64;
                    table
                        .eval(1, theta_i, theta_d, phi, Weighting::Attenuation)
                        .x
                })
                .sum::<f64>()
                * 2.0
                * PI
                / columns as f64;
            worst = worst.max((integral / exact - 1.0).abs());
        }
    }
    eprintln!("TT's energy between the rows: within {worst:.2e}");
    assert!(worst < 0.02, "{worst:e}");
}

#[test]
fn selection_and_attenuation_tables_agree_for_a_grey_lossless_fiber() {
    let az = AzimuthalScattering::new(1.55, 0.1, DVec3::ZERO);
    let table = AzimuthalTable::build(&az);
    for phi in [-2.9, -0.4, 0.0, 1.3, 3.1] {
        let a = table.eval(1, 0.4, -0.3, phi, Weighting::Attenuation).x;
        let s = table.eval(1, 0.4, -0.3, phi, Weighting::Selection).x;
        assert!((a - s).abs() < 1e-5 * a.max(1e-3), "{a} {s}");
    }
}
