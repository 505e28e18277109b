//! The renderer's benchmark (issue 5): N full frames of a scene and N re-renders after a
//! hair-parameter edit (absorption changed, tables and shadows kept), reported as medians of
//! each stage. The command line only builds the scene and prints or records the report.

use crate::frame::renderer::{Renderer, Timings};
use crate::scene::Scene;
use serde::Serialize;

/// Medians over the benchmark's frames.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BenchReport {
    /// Frames timed for each median.
    pub frames: usize,
    /// Visible points shaded per frame.
    pub visible_points: usize,
    /// Median seconds of each stage of a full frame (tables and fit are one-off costs).
    pub full: Timings,
    /// Median seconds of a full frame: drawing + shadows + shading + resolve.
    pub full_frame: f64,
    /// Median seconds of each stage of a re-render after a hair-parameter edit.
    pub rerender: Timings,
    /// Median seconds of a re-render: shading + resolve.
    pub rerender_frame: f64,
}

/// Renders `scene` `frames` times in full, and after each frame re-renders it with its
/// absorption edited, reusing that frame's visibility and shadows.
pub fn run(renderer: &Renderer, scene: &Scene, frames: usize) -> BenchReport {
    let frames = frames.max(1);
    let mut full = Vec::with_capacity(frames);
    let mut rerender = Vec::with_capacity(frames);
    let mut visible_points = 0;
    for i in 0..frames {
        let (_, prepared, timings) = renderer.render(scene);
        visible_points = prepared.points.len();
        full.push(timings);
        let edited = with_absorption_edit(scene, i);
        let mut t = Timings::default();
        renderer.rerender(&edited, &prepared, &mut t);
        rerender.push(t);
    }
    let full = median_timings(&full);
    let rerender = median_timings(&rerender);
    BenchReport {
        frames,
        visible_points,
        full_frame: full.drawing + full.shadows + full.shading + full.resolve,
        rerender_frame: rerender.shading + rerender.resolve,
        full,
        rerender,
    }
}

/// The scene with every strand's absorption set to a value that differs from frame to frame.
pub fn with_absorption_edit(scene: &Scene, frame: usize) -> Scene {
    let mut edited = scene.clone();
    let k = 0.5 + 0.25 * frame as f64;
    edited.spec.hair.mu_a = Some([k, 1.5 * k, 2.5 * k]);
    edited
}

/// The median of each field over `runs` (not empty).
pub fn median_timings(runs: &[Timings]) -> Timings {
    let m = |f: fn(&Timings) -> f64| median(runs.iter().map(f).collect());
    Timings {
        tables: m(|t| t.tables),
        srbf_fit: m(|t| t.srbf_fit),
        drawing: m(|t| t.drawing),
        shadows: m(|t| t.shadows),
        shading: m(|t| t.shading),
        resolve: m(|t| t.resolve),
    }
}

/// The median of `values` (not empty); the mean of the middle two for an even count.
pub fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    let n = values.len();
    if n % 2 == 1 {
        values[n / 2]
    } else {
        0.5 * (values[n / 2 - 1] + values[n / 2])
    }
}

#[cfg(test)]
mod tests {
    use super::median;

    #[test]
    fn median_of_odd_and_even_counts() {
        assert_eq!(median(vec![3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(vec![4.0, 1.0, 3.0, 2.0]), 2.5);
        assert_eq!(median(vec![7.0]), 7.0);
    }
}
