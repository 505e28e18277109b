//! The benchmark on a tiny scene: it runs, and its medians are finite, positive and consistent:
//! each edit's re-render runs exactly the stages that edit needs (a hair edit neither draws nor
//! casts shadows, a camera move does), and each edit changes only what it names.

mod common;

use common::tiny_scene;
use cuticle_render::Renderer;
use cuticle_render::bench::{self, BenchReport, Edit};

fn stages(report: &BenchReport) -> Vec<f64> {
    let f = &report.full;
    let mut all = vec![f.drawing, f.shadows, f.shading, f.resolve];
    for e in &report.edits {
        let t = &e.timings;
        all.extend([t.drawing, t.shadows, t.shading, t.resolve, e.frame]);
    }
    all
}

#[test]
fn bench_reports_consistent_medians() {
    let report = bench::run(&Renderer::new(), &tiny_scene(), 1);
    assert_eq!(report.frames, 1);
    assert!(report.visible_points > 0, "the tiny groom must be visible");
    assert!(stages(&report).iter().all(|s| s.is_finite() && *s >= 0.0));
    assert!(report.full_frame > 0.0);
    let f = &report.full;
    let full_sum = f.drawing + f.shadows + f.shading + f.resolve;
    assert!((report.full_frame - full_sum).abs() < 1e-12);
    let kinds: Vec<Edit> = report.edits.iter().map(|e| e.edit).collect();
    assert_eq!(kinds, Edit::ALL);
    for edit in [Edit::Absorption, Edit::Roughness, Edit::Eta] {
        let t = &report.edit(edit).timings;
        assert_eq!(t.drawing, 0.0, "{edit:?}: a hair edit draws nothing");
        assert_eq!(t.shadows, 0.0, "{edit:?}: a hair edit keeps the shadows");
        assert!(t.shading > 0.0, "{edit:?}");
    }
    let camera = &report.edit(Edit::Camera).timings;
    assert!(camera.drawing > 0.0 && camera.shadows > 0.0 && camera.shading > 0.0);
}

/// Each edit changes what it names and nothing else, and differs from frame to frame.
#[test]
fn each_edit_changes_only_what_it_names() {
    let scene = tiny_scene();
    for edit in Edit::ALL {
        let (a, b) = (edit.apply(&scene, 0), edit.apply(&scene, 1));
        let (mut back_a, mut back_b) = (a.spec.clone(), b.spec.clone());
        match edit {
            Edit::Absorption => {
                assert_ne!(a.spec.hair.mu_a, b.spec.hair.mu_a);
                back_a.hair.mu_a = scene.spec.hair.mu_a;
                back_b.hair.mu_a = scene.spec.hair.mu_a;
            }
            Edit::Roughness => {
                assert_ne!(a.spec.hair.beta_r_deg, scene.spec.hair.beta_r_deg);
                assert_ne!(a.spec.hair.alpha_r_deg, b.spec.hair.alpha_r_deg);
                for h in [&mut back_a.hair, &mut back_b.hair] {
                    h.beta_r_deg = scene.spec.hair.beta_r_deg;
                    h.alpha_r_deg = scene.spec.hair.alpha_r_deg;
                }
            }
            Edit::Eta => {
                assert_ne!(a.spec.hair.eta, b.spec.hair.eta);
                back_a.hair.eta = scene.spec.hair.eta;
                back_b.hair.eta = scene.spec.hair.eta;
            }
            Edit::Camera => {
                assert_ne!(a.camera.eye, b.camera.eye);
                let distance = |c: &cuticle_render::Camera| {
                    (glam::DVec3::from(c.eye) - glam::DVec3::from(c.target)).length()
                };
                assert!((distance(&a.camera) - distance(&scene.camera)).abs() < 1e-9);
                assert_eq!(a.camera.target, scene.camera.target);
            }
        }
        if edit != Edit::Camera {
            assert_eq!(a.camera.eye, scene.camera.eye, "{edit:?}");
        }
        assert_eq!(back_a, scene.spec, "{edit:?}");
        assert_eq!(back_b, scene.spec, "{edit:?}");
    }
}
