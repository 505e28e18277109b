//! The per-lobe figures: zero for a model against itself, the expected values for a scaled or
//! shifted copy and for the histogram of the model's own importance samples, and a known shift
//! of the peak in θ found to within a tenth of a row.

use cuticle_fiber::lobe::channel_mean;
use cuticle_fiber::{FiberAngles, FiberModel, FiberParams, LatLongGrid, LatLongImage};
use cuticle_validate::peak::peak_theta_error;
use cuticle_validate::{ModelId, PixelRule, build_model, integrate_lobes, lobe_figures};
use glam::DVec3;
use std::f64::consts::PI;

fn params(beta: f64) -> FiberParams {
    FiberParams {
        eta: 1.55,
        beta,
        alpha: (-2.0f64).to_radians(),
        mu_a: DVec3::splat(0.25),
    }
}

fn lobes(kind: ModelId, beta: f64, grid: LatLongGrid) -> [LatLongImage; 5] {
    let p = params(beta);
    let m = build_model(kind, &p).unwrap();
    integrate_lobes(
        m.as_ref(),
        0.5,
        grid,
        &PixelRule::for_fiber(p.eta, p.alpha, p.beta),
    )
}

#[test]
fn a_model_against_itself_has_zero_error() {
    let img = lobes(ModelId::NonSeparable, 0.04, LatLongGrid::default());
    for lobe in &img {
        let f = lobe_figures(lobe, lobe);
        assert_eq!(f.relative_l1, Some(0.0));
        assert_eq!(f.energy_difference(), 0.0);
        assert_eq!(f.peak_theta_error, Some(0.0));
    }
}

#[test]
fn a_scaled_copy_has_the_scale_as_error() {
    let img = lobes(ModelId::DEon2011, 0.04, LatLongGrid::default());
    for lobe in &img {
        let mut sim = lobe.clone();
        sim.scale(0.8);
        let f = lobe_figures(lobe, &sim);
        assert!((f.relative_l1.unwrap() - 0.25).abs() < 1e-12);
        assert!((f.energy_difference() - 0.2 * channel_mean(lobe.energy())).abs() < 1e-12);
        assert!(f.peak_theta_error.unwrap() < 1e-12);
    }
}

/// The image shifted down by `rows` rows (toward −θ), black rows entering at the top.
fn shift_rows(img: &LatLongImage, rows: usize) -> LatLongImage {
    let w = img.grid.width;
    let mut out = LatLongImage::zeros(img.grid);
    out.pixels[rows * w..].copy_from_slice(&img.pixels[..img.pixels.len() - rows * w]);
    out
}

#[test]
fn a_shift_by_one_row_is_found_as_one_row() {
    let img = lobes(ModelId::DEon2011, 0.04, LatLongGrid::default());
    let row = PI / 100.0;
    for lobe in &img[..3] {
        let shifted = shift_rows(lobe, 1);
        let f = lobe_figures(&shifted, lobe);
        assert!(
            (f.peak_theta_error.unwrap() - row).abs() < 1e-9,
            "{:?}",
            f.peak_theta_error
        );
        assert!(
            f.relative_l1.unwrap() > 0.2,
            "a one-row shift of a lobe two rows wide is a large L1 error"
        );
    }
}

/// A Gaussian lobe in θ around `centre` (width `sigma`), the same in every column.
fn gaussian_lobe(grid: LatLongGrid, centre: f64, sigma: f64) -> LatLongImage {
    let mut img = LatLongImage::zeros(grid);
    for k in 0..grid.height {
        let t = grid.theta_center(k);
        let v = (-0.5 * ((t - centre) / sigma).powi(2)).exp();
        for j in 0..grid.width {
            img.pixels[k * grid.width + j] = DVec3::splat(v);
        }
    }
    img
}

#[test]
fn a_sub_row_shift_of_the_peak_is_found() {
    let grid = LatLongGrid::new(40, 100);
    let row = PI / 100.0;
    for shift_rows in [0.1, 0.3, 0.45, 1.7] {
        let a = gaussian_lobe(grid, -0.3, 1.5 * row);
        let b = gaussian_lobe(grid, -0.3 + shift_rows * row, 1.5 * row);
        let found = peak_theta_error(&b, &a).unwrap() / row;
        assert!(
            (found - shift_rows).abs() < 0.02,
            "shift {shift_rows} rows found as {found}"
        );
    }
}

/// Histogram of `n` importance samples of `model`, in the units of S (docs/conventions.md §3).
fn sample_histogram(
    model: &dyn FiberModel,
    theta_i: f64,
    grid: LatLongGrid,
    n: u64,
) -> LatLongImage {
    let mut state = 0x9E37_79B9_7F4A_7C15u64;
    let mut uniform = || {
        state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut img = LatLongImage::zeros(grid);
    let wi = FiberAngles::new(theta_i, 0.0);
    for _ in 0..n {
        let u = [uniform(), uniform(), uniform(), uniform()];
        if let Some(s) = model.sample(wi, u) {
            let (j, k) = grid.pixel_of(s.wo.theta, s.wo.phi);
            img.pixels[k * grid.width + j] += s.weight / (n as f64 * grid.pixel_solid_angle(k));
        }
    }
    img
}

#[test]
fn the_histogram_of_a_models_samples_matches_it_and_not_a_rougher_model() {
    let grid = LatLongGrid::new(100, 25);
    let p = params(0.08);
    let model = build_model(ModelId::DEon2011, &p).unwrap();
    let total = |imgs: [LatLongImage; 5]| cuticle_validate::sheet::total(&imgs);
    let sim = sample_histogram(model.as_ref(), 0.5, grid, 1_000_000);
    let same = total(lobes(ModelId::DEon2011, 0.08, grid));
    let rougher = total(lobes(ModelId::DEon2011, 0.16, grid));
    let e_same = lobe_figures(&same, &sim).relative_l1.unwrap();
    let e_rough = lobe_figures(&rougher, &sim).relative_l1.unwrap();
    assert!(
        e_same < 0.05,
        "sampling noise alone should stay below 5 %, got {e_same}"
    );
    assert!(
        e_rough > 3.0 * e_same,
        "a twice rougher model ({e_rough}) should be far off ({e_same})"
    );
}
