//! Where a lobe peaks in θ. Definition used by the validation: for every φ column where the
//! reference lobe is bright (its density in φ, ∫ S cos θ dθ, at least [`BRIGHT`] of the
//! brightest column's), the θ of the column's maximum, refined below the row spacing by the
//! three-point Gaussian fit (a parabola through the logarithms of the brightest row and its
//! neighbours, exact for a Gaussian in θ). The peak error of a model is the mean of
//! |θ_peak,model − θ_peak,reference| over those columns, weighted by the reference's density.

use cuticle_fiber::LatLongImage;
use cuticle_fiber::lobe::channel_mean;

/// Share of the brightest column's density above which a column's peak counts.
pub const BRIGHT: f64 = 0.2;

/// θ of column `j`'s peak (radians), or `None` where the column is black.
pub fn column_peak(img: &LatLongImage, j: usize) -> Option<f64> {
    let g = img.grid;
    let value = |k: usize| channel_mean(img.at(j, k));
    let (k, top) = (0..g.height)
        .map(|k| (k, value(k)))
        .max_by(|a, b| a.1.total_cmp(&b.1))?;
    if top <= 0.0 {
        return None;
    }
    let offset = if k > 0 && k + 1 < g.height {
        sub_row_offset(value(k - 1), top, value(k + 1))
    } else {
        0.0
    };
    let row_height = g.theta_top(0) - g.theta_top(1);
    Some(g.theta_center(k) - offset * row_height)
}

/// The vertex of the parabola through (−1, ln a), (0, ln b), (1, ln c), in rows (positive
/// toward c, i.e. downward in θ), within ±½; 0 where a neighbour is black.
fn sub_row_offset(a: f64, b: f64, c: f64) -> f64 {
    if a <= 0.0 || c <= 0.0 {
        return 0.0;
    }
    let (la, lb, lc) = (a.ln(), b.ln(), c.ln());
    let curvature = la - 2.0 * lb + lc;
    if curvature >= 0.0 {
        return 0.0;
    }
    (0.5 * (la - lc) / curvature).clamp(-0.5, 0.5)
}

/// The bright columns of `reference` with their density in φ (channel mean).
pub fn bright_columns(reference: &LatLongImage) -> Vec<(usize, f64)> {
    let density: Vec<f64> = reference
        .azimuthal()
        .into_iter()
        .map(channel_mean)
        .collect();
    let max = density.iter().copied().fold(0.0, f64::max);
    if max <= 0.0 {
        return Vec::new();
    }
    density
        .into_iter()
        .enumerate()
        .filter(|&(_, d)| d >= BRIGHT * max)
        .collect()
}

/// Mean |θ_peak(model) − θ_peak(reference)| in radians over the reference's bright columns,
/// weighted by its density; `None` when the reference is black or the model is black in
/// every bright column.
pub fn peak_theta_error(model: &LatLongImage, reference: &LatLongImage) -> Option<f64> {
    let (mut sum, mut weight) = (0.0, 0.0);
    for (j, w) in bright_columns(reference) {
        if let (Some(m), Some(r)) = (column_peak(model, j), column_peak(reference, j)) {
            sum += w * (m - r).abs();
            weight += w;
        }
    }
    (weight > 0.0).then(|| sum / weight)
}
