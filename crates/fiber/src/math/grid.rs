//! Helpers every tabulated fast path shares: evenly spaced θ_i nodes, locating a coordinate
//! between nodes, bilinear taps, filling a grid's rows on every core, and a per-process cache of
//! tables keyed by the parameters they were built for.

use std::f64::consts::{FRAC_PI_2, PI};

/// How far inside ±π/2 the end nodes of an evenly spaced θ_i axis are evaluated: at the poles
/// the fiber's frame degenerates.
pub const GRAZING: f64 = 1e-4;

/// Node i of `nodes` evenly spaced over θ_i ∈ [−π/2, π/2], the ends [`GRAZING`] inside.
pub fn theta_i_node(i: usize, nodes: usize) -> f64 {
    (-FRAC_PI_2 + PI * i as f64 / (nodes - 1) as f64)
        .clamp(-FRAC_PI_2 + GRAZING, FRAC_PI_2 - GRAZING)
}

/// The lower node and the fraction toward the next for a coordinate t ∈ [0, 1] on n nodes.
#[inline]
pub fn locate(t: f64, n: usize) -> (usize, f32) {
    // t ≥ 0 (every coordinate is), so truncation is the floor. The clamp to the last cell
    // happens in f64 before the cast (NaN goes to the last cell, f64::min keeping the
    // number), and the cast's saturation sends any negative to node 0.
    let x = t * (n - 1) as f64;
    let i = x.min((n - 2) as f64) as u32 as usize;
    (i, (x - i as f64) as f32)
}

/// A per-process cache of tables keyed by the parameters they were built for.
pub type SharedTables<K, T> =
    std::sync::OnceLock<std::sync::Mutex<std::collections::HashMap<K, std::sync::Arc<T>>>>;

/// The table for `key` from `cache`, built by `build` the first time it is asked for. It is
/// built outside the lock, so that other keys need not wait for this one; two threads that
/// race for one key both build it and keep the first.
pub fn shared_table<K: std::hash::Hash + Eq, T>(
    cache: &SharedTables<K, T>,
    key: K,
    build: impl FnOnce() -> T,
) -> std::sync::Arc<T> {
    let cache = cache.get_or_init(Default::default);
    if let Some(found) = cache.lock().unwrap_or_else(|e| e.into_inner()).get(&key) {
        return found.clone();
    }
    let built = std::sync::Arc::new(build());
    let mut map = cache.lock().unwrap_or_else(|e| e.into_inner());
    map.entry(key).or_insert(built).clone()
}

/// Fills a row-major grid, `fill(row index, row)` for each row of `row_len` cells, the rows
/// shared out over every available core.
pub fn fill_rows<T: Send>(cells: &mut [T], row_len: usize, fill: impl Fn(usize, &mut [T]) + Sync) {
    let rows = cells.len() / row_len;
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let rows_per_thread = rows.div_ceil(threads).max(1);
    let fill = &fill;
    std::thread::scope(|s| {
        for (t, chunk) in cells.chunks_mut(rows_per_thread * row_len).enumerate() {
            s.spawn(move || {
                for (r, row) in chunk.chunks_mut(row_len).enumerate() {
                    fill(t * rows_per_thread + r, row);
                }
            });
        }
    });
}

/// The bilinear blend of a row-major grid of texels: cell `at` and its neighbours along the
/// row (`at + 1`) and the next row (`at + stride`), at fractions `f_row` across rows and
/// `f_col` along them.
#[inline]
pub fn bilinear<const N: usize>(
    texels: &[[f32; N]],
    at: usize,
    stride: usize,
    f_row: f32,
    f_col: f32,
) -> [f32; N] {
    let weights = [
        (1.0 - f_row) * (1.0 - f_col),
        (1.0 - f_row) * f_col,
        f_row * (1.0 - f_col),
        f_row * f_col,
    ];
    let taps = [at, at + 1, at + stride, at + stride + 1];
    let mut out = [0.0f32; N];
    for (tap, w) in taps.into_iter().zip(weights) {
        for (o, t) in out.iter_mut().zip(&texels[tap]) {
            *o += w * t;
        }
    }
    out
}
