//! The noise floor of a validation (issue 14): how much of a model's error against the
//! simulation is the simulation's own Monte Carlo noise.
//!
//! Two simulations A and B of one configuration with different seeds and the same number of
//! paths have independent noise ε_A, ε_B of one distribution per pixel. The validation then
//! compares the models with their mean Ā = (A + B)/2, whose noise (ε_A + ε_B)/2 has the same
//! distribution as (A − B)/2 = (ε_A − ε_B)/2 wherever ε is symmetric (many paths per pixel).
//! So a perfect model scores against Ā, in expectation, exactly half the seed-to-seed L1
//! Σ|A − B|Ω / Σ|Ā|Ω: that half is the **noise floor** of each model figure.
//!
//! The **residual** √max(L1² − floor², 0) takes the floor out in quadrature. For squared
//! errors that is exact (E|m − Ā|² = |m − T|² + E|Ā − T|²); for L1 it lies between the two
//! extremes, L1 − floor (model error and noise in different pixels) and L1 (noise small beside
//! the model error in every pixel where either lives), and is the figure to compare with the
//! floor: a residual under the floor is a model error the noise hides.

use cuticle_fiber::LatLongImage;
use cuticle_fiber::lobe::channel_mean;

/// (A + B)/2 per pixel, for each lobe.
pub fn mean_of(a: &[LatLongImage; 5], b: &[LatLongImage; 5]) -> [LatLongImage; 5] {
    std::array::from_fn(|p| {
        assert_eq!(a[p].grid, b[p].grid, "two runs on different grids");
        LatLongImage {
            grid: a[p].grid,
            pixels: a[p]
                .pixels
                .iter()
                .zip(&b[p].pixels)
                .map(|(x, y)| 0.5 * (*x + *y))
                .collect(),
        }
    })
}

/// Σ|A − B|Ω / Σ|(A + B)/2|Ω for each lobe (channel mean), `None` where both are black.
pub fn seed_to_seed_l1(a: &[LatLongImage; 5], b: &[LatLongImage; 5]) -> [Option<f64>; 5] {
    std::array::from_fn(|p| {
        let g = a[p].grid;
        let (mut diff, mut norm) = (0.0, 0.0);
        for k in 0..g.height {
            let omega = g.pixel_solid_angle(k);
            for j in 0..g.width {
                let (x, y) = (a[p].at(j, k), b[p].at(j, k));
                diff += omega * channel_mean((x - y).abs());
                norm += omega * channel_mean((0.5 * (x + y)).abs());
            }
        }
        (norm > 0.0).then(|| diff / norm)
    })
}
