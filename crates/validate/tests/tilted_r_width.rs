//! R's longitudinal width through tilted scales (docs/departures/10-r-width-tilted.md,
//! 18-r-column-lobe.md): at a fixed azimuth the simulator's R spreads in θ_o as the tilted
//! non-separable model's lobe says (the moments of the light its rough surface reflects to that
//! azimuth), not as d'Eon et al. 2014 eq. 6's v_R = 2β²(1 − h²), which is exact only for untilted
//! scales.
//!
//! The simulator (`cuticle-sim`, fixed seed) fills a lat-long grid with tall columns and short
//! rows (64 × 512: 0.098 rad in φ, 0.006 rad in θ); in each column where R is bright the
//! standard deviation of θ_o over the column (the pixels' quantisation taken out) is compared
//! with the model's √v_R at the column's centre, and with eq. 6's. Within the column the cone
//! moves by under 0.007 rad, which adds under 1 % to a width of 0.015.

mod common;

use common::{model, model_images, simulated};
use cuticle_fiber::models::nonseparable::scales::mirror::{MirrorOffset, tilted_mirror_offset};
use cuticle_fiber::{LatLongGrid, LatLongImage};
use cuticle_sim::SimResult;
use std::ops::RangeInclusive;

const BETA: f64 = 0.04;
/// About 10⁴ paths in each compared column: its standard deviation to under 1 %.
const PATHS: u64 = 8_000_000;

/// The standard deviation of θ over column `j` of `image` (channel x), the rows' quantisation
/// (height²/12) taken out.
fn column_spread(image: &LatLongImage, j: usize) -> f64 {
    let grid = image.grid;
    let (mut m0, mut m1, mut m2) = (0.0, 0.0, 0.0);
    for k in 0..grid.height {
        let w = image.at(j, k).x * grid.pixel_solid_angle(k);
        let theta = grid.theta_center(k);
        m0 += w;
        m1 += w * theta;
        m2 += w * theta * theta;
    }
    let mean = m1 / m0;
    let row = std::f64::consts::PI / grid.height as f64;
    (m2 / m0 - mean * mean - row * row / 12.0).sqrt()
}

/// The simulator's lobes, [`PATHS`] paths of a lossless fiber on `grid`.
fn simulated_r(theta_i: f64, alpha: f64, beta: f64, grid: LatLongGrid, seed: u64) -> SimResult {
    simulated(theta_i, alpha, beta, grid, PATHS, seed)
}

/// The columns of `grid` whose |φ| lies in `band`, with their φ.
fn columns(grid: LatLongGrid, band: RangeInclusive<f64>) -> impl Iterator<Item = (usize, f64)> {
    (0..grid.width)
        .map(move |j| (j, grid.phi_center(j)))
        .filter(move |(_, phi)| band.contains(&phi.abs()))
}

/// The worst relative gaps between the simulated width and the model's, and between the
/// simulated width and eq. 6's, over the bright columns at 1.2 ≤ |φ| ≤ 2.6.
fn widths(theta_i: f64, alpha_deg: f64) -> (f64, f64) {
    let alpha = alpha_deg.to_radians();
    let grid = LatLongGrid {
        width: 64,
        height: 512,
    };
    let sim = simulated_r(theta_i, alpha, BETA, grid, 10);
    let model = model(alpha, BETA);
    let (mut worst_model, mut worst_eq6) = (0.0f64, 0.0f64);
    println!("θ_i {theta_i} α {alpha_deg}°: φ, h, width simulated / model / eq. 6");
    for (j, phi) in columns(grid, 1.2..=2.6) {
        let Some(m @ MirrorOffset { h, .. }) = tilted_mirror_offset(theta_i, alpha, phi) else {
            continue;
        };
        let simulated = column_spread(&sim.lobes[0], j);
        let ours = model.longitudinal(0, theta_i, phi).v.sqrt();
        let eq6 = (2.0 * BETA * BETA * (1.0 - h * h)).sqrt();
        let smooth = (0.5 * BETA * BETA).sqrt() * m.spread;
        println!(
            "{phi:+.3} {h:+.3} {simulated:.4} / {ours:.4} / {eq6:.4} (smooth mirror {smooth:.4})"
        );
        worst_model = worst_model.max((ours / simulated - 1.0).abs());
        worst_eq6 = worst_eq6.max((eq6 / simulated - 1.0).abs());
    }
    (worst_model, worst_eq6)
}

/// Scales tilted toward the root at grazing incidence narrow R toward the fiber's edges, to
/// three quarters of eq. 6's width at |φ| = 2.5; the model follows within 5 %, where eq. 6
/// misses by more than a quarter.
#[test]
fn r_narrows_through_scales_tilted_at_grazing_incidence() {
    let (model, eq6) = widths(1.1, -4.0);
    assert!(model < 0.05, "model's width off by {model:.3}");
    assert!(
        eq6 > 0.25,
        "eq. 6 within {eq6:.3}: the test does not tell them apart"
    );
}

/// Tilted the other way, R widens toward the edges instead; the model follows it too, where
/// eq. 6 is too narrow by more than 15 %.
#[test]
fn r_widens_through_scales_tilted_toward_the_tip() {
    let (model, eq6) = widths(0.75, 4.0);
    assert!(model < 0.05, "model's width off by {model:.3}");
    assert!(
        eq6 > 0.15,
        "eq. 6 within {eq6:.3}: the test does not tell them apart"
    );
}

/// Untilted, the spread is eq. 6's, and both follow the simulation.
#[test]
fn r_width_is_eq_6_untilted() {
    for &h in &[-0.9, -0.3, 0.0, 0.6, 0.95] {
        let phi = -2.0 * f64::asin(h);
        let m = tilted_mirror_offset(0.8, 0.0, phi).unwrap();
        assert!(
            (m.spread - 2.0 * (1.0 - h * h).sqrt()).abs() < 1e-9,
            "h {h}"
        );
    }
    let (model, _) = widths(1.1, 0.0);
    assert!(model < 0.05, "model's width off by {model:.3}");
}

/// Where the reflecting offsets graze (θ_i = 1.1, scales tilted toward the root, the roughest
/// fiber of the grid) the light one offset's slopes carry to a neighbouring azimuth leaves by
/// that azimuth's micro-normals, so the column at |φ| near π is half as wide as the smooth
/// mirror's spread there, and its mean sits on neither the smooth mirror's cone nor eq. 6's.
/// The model's R, pixel-integrated on the simulator's grid, follows the simulated column
/// means to 0.003 rad (a column's mean carries about 0.001 of noise), widths to 6 % and
/// energies to 3 % over 1.2 ≤ |φ| ≤ 2.75; the smooth mirror's lobe, the model's before
/// departure 18, misses the widths by 38 % at |φ| = 2.7 and the means by 0.01 rad, and the
/// mixture of offsets' Gaussians in φ, N_R before it, the energies by 3–5 % at |φ| ≈ 1.7
/// and 2.7.
#[test]
fn r_follows_the_simulated_columns_where_the_offsets_graze() {
    use cuticle_validate::moments::column_moments;
    let (theta_i, alpha, beta) = (1.1, f64::to_radians(-4.0), 0.08);
    let grid = LatLongGrid {
        width: 64,
        height: 256,
    };
    let sim = simulated_r(theta_i, alpha, beta, grid, 11);
    let images = model_images(&model(alpha, beta).tabulated(), theta_i, grid);
    let (mut worst_mean, mut worst_width, mut worst_energy) = (0.0f64, 0.0f64, 0.0f64);
    println!("φ: mean θ simulated / model, width simulated / model, energy model ÷ simulated");
    for (j, phi) in columns(grid, 1.2..=2.75) {
        let (Some(s), Some(m)) = (
            column_moments(&sim.lobes[0], j),
            column_moments(&images[0], j),
        ) else {
            panic!("φ {phi}: an empty R column");
        };
        println!(
            "{phi:+.3}: {:.4} / {:.4}, {:.4} / {:.4}, {:.3}",
            s.mean,
            m.mean,
            s.std_dev,
            m.std_dev,
            m.energy / s.energy
        );
        worst_mean = worst_mean.max((m.mean - s.mean).abs());
        worst_width = worst_width.max((m.std_dev / s.std_dev - 1.0).abs());
        worst_energy = worst_energy.max((m.energy / s.energy - 1.0).abs());
    }
    assert!(
        worst_mean < 0.003,
        "column means off by {worst_mean:.4} rad"
    );
    assert!(worst_width < 0.06, "column widths off by {worst_width:.3}");
    assert!(
        worst_energy < 0.03,
        "column energies off by {worst_energy:.3}"
    );
}
