//! The renderer's benchmark (issues 5 and 52): N full frames of a scene, and after each the
//! full-quality re-render that each kind of look-development edit costs ([`Edit`]), reported as
//! medians of each stage. The command line only builds the scene and prints or records the
//! report.

use crate::frame::renderer::{Renderer, Timings};
use crate::scene::Scene;
use glam::DVec3;
use serde::Serialize;

/// An edit a look-development session makes, and what its re-render redoes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Edit {
    /// Every strand's μ_a (a colour or paint edit): shading only; no table is rebuilt.
    Absorption,
    /// β_R and α_R: shading, with the back-scattering tables rebuilt.
    Roughness,
    /// η: shading, with the lobe table and the back-scattering tables rebuilt.
    Eta,
    /// The camera orbits the target: drawing, shadows of the newly visible points, shading.
    Camera,
}

impl Edit {
    pub const ALL: [Edit; 4] = [Edit::Absorption, Edit::Roughness, Edit::Eta, Edit::Camera];

    /// `scene` with this edit applied, different for each `frame` (so no cache serves it).
    pub fn apply(self, scene: &Scene, frame: usize) -> Scene {
        let mut edited = scene.clone();
        let k = frame as f64;
        let hair = &mut edited.spec.hair;
        match self {
            Edit::Absorption => return with_absorption_edit(scene, frame),
            Edit::Roughness => {
                hair.beta_r_deg *= 1.1 + 0.05 * k;
                hair.alpha_r_deg *= 0.9 - 0.05 * k;
            }
            Edit::Eta => hair.eta += 0.02 * (1.0 + k),
            Edit::Camera => edited.camera = orbit(&scene.camera, 10.0 * (1.0 + k)),
        }
        edited
    }
}

/// A camera turned about its up axis through the target by `degrees`.
fn orbit(camera: &crate::Camera, degrees: f64) -> crate::Camera {
    let (target, up) = (
        DVec3::from(camera.target),
        DVec3::from(camera.up).normalize(),
    );
    let offset = DVec3::from(camera.eye) - target;
    let turned = glam::DQuat::from_axis_angle(up, degrees.to_radians()) * offset;
    crate::Camera {
        eye: (target + turned).to_array(),
        ..*camera
    }
}

/// The median re-render after one kind of edit.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct EditTimings {
    pub edit: Edit,
    /// Median seconds of each stage the re-render ran (the others 0).
    pub timings: Timings,
    /// Median seconds of the re-render: drawing + shadows + shading + resolve.
    pub frame: f64,
}

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
    /// The re-render after each [`Edit`], in [`Edit::ALL`]'s order.
    pub edits: Vec<EditTimings>,
}

impl BenchReport {
    /// The re-render after `edit`.
    pub fn edit(&self, edit: Edit) -> &EditTimings {
        self.edits
            .iter()
            .find(|e| e.edit == edit)
            .expect("every edit is timed")
    }
}

/// Renders `scene` `frames` times in full, and after each frame re-renders it after each
/// [`Edit`]: hair edits reuse that frame's visibility and shadows, a camera move draws anew.
pub fn run(renderer: &Renderer, scene: &Scene, frames: usize) -> BenchReport {
    let frames = frames.max(1);
    let mut full = Vec::with_capacity(frames);
    let mut edits = vec![Vec::with_capacity(frames); Edit::ALL.len()];
    let mut visible_points = 0;
    for i in 0..frames {
        let (_, prepared, timings) = renderer.render(scene);
        visible_points = prepared.points.len();
        full.push(timings);
        for (runs, edit) in edits.iter_mut().zip(Edit::ALL) {
            let edited = edit.apply(scene, i);
            let mut t = Timings::default();
            if edit == Edit::Camera {
                let moved = renderer.prepare(&edited, &mut t);
                renderer.rerender(&edited, &moved, &mut t);
            } else {
                renderer.rerender(&edited, &prepared, &mut t);
            }
            runs.push(t);
        }
    }
    let full = median_timings(&full);
    BenchReport {
        frames,
        visible_points,
        full_frame: frame_seconds(&full),
        full,
        edits: Edit::ALL
            .iter()
            .zip(&edits)
            .map(|(&edit, runs)| {
                let timings = median_timings(runs);
                EditTimings {
                    edit,
                    frame: frame_seconds(&timings),
                    timings,
                }
            })
            .collect(),
    }
}

/// drawing + shadows + shading + resolve.
fn frame_seconds(t: &Timings) -> f64 {
    t.drawing + t.shadows + t.shading + t.resolve
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
