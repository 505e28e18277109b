//! What each kind of edit makes the render worker redo, counted (never timed): a hair-parameter
//! edit or a paint stroke re-runs shading and resolve only — no preparation (drawing, shadows)
//! and no table but the ones its parameter feeds, and a paint stroke only the painted strands'
//! points —, a camera move re-runs drawing but not the
//! shadows, and the preview really is smaller, with fewer lights and quadrature segments. A small
//! scene (300 strands, 160 × 120, 12 SRBF lights, more than a preview keeps) on the CPU renderer.

use cuticle_groom::Absorption;
use cuticle_render::{Image, Renderer, Scene, SceneSpec, TableBuilds};
use cuticle_view::look::Look;
use cuticle_view::orbit;
use cuticle_view::preview::{PREVIEW_LIGHTS, PREVIEW_QUADRATURE, preview_scene};
use cuticle_view::shading::Backends;
use cuticle_view::worker::{Frame, Quality, Report, Request, Worker};
use std::sync::mpsc::{Receiver, channel};
use std::time::{Duration, Instant};

fn look() -> Look {
    let mut spec = SceneSpec {
        strands: 300,
        width: 160,
        height: 120,
        lights: 12,
        supersampling: 2,
        ..SceneSpec::default()
    };
    spec.shadows.resolution = 64;
    Look::from_scene(Scene::load(spec, None).expect("the test scene loads"))
}

/// The worker on the CPU renderer, with the renderer whose table builds it counts.
struct Bench {
    renderer: Renderer,
    worker: Worker,
    notified: Receiver<()>,
    id: u64,
}

impl Bench {
    fn new() -> Self {
        let renderer = Renderer::new();
        let backends = Backends::cpu(&renderer);
        let (tx, notified) = channel();
        let worker = Worker::start(backends.preview, backends.full, move || {
            let _ = tx.send(());
        });
        Self {
            renderer,
            worker,
            notified,
            id: 0,
        }
    }

    /// The frames of `look` up to its full-quality one, and the tables built meanwhile.
    fn frames(&mut self, look: &Look) -> (Vec<Frame>, TableBuilds) {
        let before = self.renderer.table_builds();
        self.id += 1;
        self.worker.submit(Request {
            id: self.id,
            scene: look.scene(),
            revisions: look.revisions,
            interacting: false,
            issued: Instant::now(),
        });
        let mut frames = Vec::new();
        loop {
            let _ = self.notified.recv_timeout(Duration::from_secs(300));
            for r in self.worker.reports() {
                match r {
                    Report::Frame(f) if f.id == self.id => {
                        let full = f.quality == Quality::Full;
                        frames.push(*f);
                        if full {
                            let after = self.renderer.table_builds();
                            let built = TableBuilds {
                                lobes: after.lobes - before.lobes,
                                back_scattering: after.back_scattering - before.back_scattering,
                                preview_back_scattering: after.preview_back_scattering
                                    - before.preview_back_scattering,
                            };
                            return (frames, built);
                        }
                    }
                    Report::Failed { message, .. } => panic!("{message}"),
                    _ => {}
                }
            }
        }
    }
}

fn full(frames: &[Frame]) -> &Image {
    &frames.last().expect("a full frame").image
}

/// Whether the full-quality frame re-ran the preparation (a preview re-runs drawing whenever
/// the worker resizes it to its time budget, which depends on the machine's load).
fn prepared(frames: &[Frame]) -> bool {
    frames.last().expect("a full frame").prepared
}

/// Points the full-quality frame shaded (the CPU back end counts them).
fn points_shaded(frames: &[Frame]) -> usize {
    frames
        .last()
        .and_then(|f| f.points_shaded)
        .expect("the CPU back end counts the points it shades")
}

/// Whole-groom shadow passes of both back ends so far.
fn shadow_passes(frames: &[Frame]) -> u64 {
    frames.iter().map(|f| f.shadow_passes).sum()
}

const NONE: TableBuilds = TableBuilds {
    lobes: 0,
    back_scattering: 0,
    preview_back_scattering: 0,
};

/// Absorption edits (all strands, and paint on some) and d_b re-run neither the preparation
/// nor any table, yet change the image; β_R rebuilds the back-scattering tables only, η the
/// lobe table too; a camera move re-prepares (drawing) but builds no table and keeps the
/// shadows, which new shadow settings recompute.
#[test]
fn each_edit_redoes_only_what_it_changes() {
    let mut bench = Bench::new();
    let mut look = look();
    let (first, _) = bench.frames(&look);
    assert!(prepared(&first), "the first request prepares");
    assert_eq!(shadow_passes(&first), 2, "one shadow pass per quality");
    assert_eq!(first[0].quality, Quality::Preview);

    look.all_strands = Some(Absorption::Melanin {
        eumelanin: 3.0,
        pheomelanin: 0.2,
    });
    let (absorbed, built) = bench.frames(&look);
    assert!(!prepared(&absorbed), "an absorption edit re-prepared");
    assert_eq!(built, NONE, "an absorption edit rebuilt a table");
    assert_ne!(full(&absorbed), full(&first), "the absorption edit shows");

    for s in 0..look.paint.len() / 3 {
        look.paint[s] = Some(Absorption::MuA([0.1, 2.0, 4.0]));
    }
    let (painted, built) = bench.frames(&look);
    assert_eq!((prepared(&painted), built), (false, NONE), "a paint stroke");
    assert_ne!(full(&painted), full(&absorbed), "the paint shows");
    assert!(
        points_shaded(&painted) < points_shaded(&absorbed),
        "a paint stroke re-shades its strands' points alone at full quality: {} of {}",
        points_shaded(&painted),
        points_shaded(&absorbed)
    );
    assert!(
        points_shaded(&painted) > 0,
        "the painted strands are visible"
    );

    look.spec.hair.beta_r_deg += 2.0;
    let (widened, built) = bench.frames(&look);
    assert!(!prepared(&widened), "a β_R edit re-prepared");
    assert_eq!(
        built,
        TableBuilds {
            lobes: 0,
            back_scattering: 1,
            preview_back_scattering: 1,
        },
        "β_R feeds the back-scattering tables only (the preview builds its coarse ones)"
    );

    look.spec.hair.d_b *= 0.5;
    let (dimmer, built) = bench.frames(&look);
    assert_eq!(
        (prepared(&dimmer), built),
        (false, NONE),
        "d_b enters after the lookup"
    );
    assert_ne!(full(&dimmer), full(&widened), "the d_b edit shows");

    look.spec.hair.eta += 0.05;
    let (refracted, built) = bench.frames(&look);
    assert_eq!(
        built,
        TableBuilds {
            lobes: 1,
            back_scattering: 1,
            preview_back_scattering: 1,
        },
        "η feeds both tables (the lobe table shared by both qualities)"
    );

    assert_eq!(shadow_passes(&refracted), 2, "hair edits computed shadows");
    let c = look.spec.camera.expect("a look has a camera");
    look.spec.camera = Some(orbit::orbit(&c, 20.0, 0.0));
    let (moved, built) = bench.frames(&look);
    assert!(prepared(&moved), "a camera move re-prepares");
    assert_eq!(built, NONE, "a camera move rebuilt a table");
    assert_eq!(
        shadow_passes(&moved),
        2,
        "a camera move recomputed the shadows"
    );
    assert_ne!(full(&moved), full(&refracted), "the camera move shows");

    look.spec.shadows.density = 0.5;
    let (thinner, _) = bench.frames(&look);
    assert_eq!(
        shadow_passes(&thinner),
        4,
        "new shadow settings recompute them"
    );
}

/// The shadows kept across a camera move give the image a fresh renderer makes: the frame
/// after an orbit is bit for bit the one-shot render of the orbited scene.
#[test]
fn kept_shadows_render_what_a_fresh_renderer_renders() {
    let mut look = look();
    let mut bench = Bench::new();
    bench.frames(&look);
    let c = look.spec.camera.expect("a look has a camera");
    look.spec.camera = Some(orbit::orbit(&c, 30.0, 10.0));
    let (moved, _) = bench.frames(&look);
    let (fresh, _, _) = Renderer::new().render(&look.scene());
    assert_eq!(full(&moved), &fresh);
}

/// The preview the worker shows first has fewer pixels than the full frame and one subsample,
/// and its scene the frame's lights merged into a few and a coarser quadrature.
#[test]
fn the_preview_is_cheaper_than_the_full_frame() {
    let look = look();
    let scene = look.scene();
    assert!(scene.lights.len() > PREVIEW_LIGHTS);
    let preview = preview_scene(&scene, 2);
    assert_eq!((preview.spec.width, preview.spec.height), (80, 60));
    assert_eq!(preview.spec.supersampling, 1);
    assert_eq!(preview.lights.len(), PREVIEW_LIGHTS);
    assert_eq!(
        preview.spec.quadrature,
        scene.spec.quadrature.min(PREVIEW_QUADRATURE)
    );
    assert!(preview.spec.quadrature < scene.spec.quadrature);

    let mut bench = Bench::new();
    let (frames, _) = bench.frames(&look);
    let (p, f) = (&frames[0].image, full(&frames));
    assert_eq!(frames[0].quality, Quality::Preview);
    assert!(p.width < f.width && p.height < f.height);
    assert_eq!((f.width, f.height), (160, 120));
}
