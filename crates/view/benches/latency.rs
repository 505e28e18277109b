//! Latency of the window's CPU path, without a window: the worker as `cuticle view` drives it,
//! on the default scene (or `--strands N --width W --height H`), timing from a request to its
//! first frame (the preview) and to its full-quality frame, for edits of the hair (absorption,
//! β_R) and paint strokes (shading only) and for camera moves (preparation again). Medians of
//! `--edits K`, with the preparations the edits re-ran and the tables they rebuilt (counts).
//! `--preview-only` asks as a window does while input moves (the worker stops at the
//! preview), so that each edit's time is the first updated frame's alone.
//!
//! `cargo bench -p cuticle-view --bench latency -- --edits 5 [--device cpu|gpu|auto]
//! [--preview-only]` (the CPU renderer unless `--device` says otherwise).

use cuticle_render::{Renderer, Scene, SceneSpec};
use cuticle_view::look::Look;
use cuticle_view::orbit;
use cuticle_view::shading::Backends;
use cuticle_view::worker::{Quality, Report, Request, Worker};
use std::sync::mpsc::channel;
use std::time::{Duration, Instant};

fn arg(name: &str, default: usize) -> usize {
    let args: Vec<String> = std::env::args().collect();
    args.iter()
        .position(|a| a == name)
        .and_then(|i| args.get(i + 1))
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Seconds from the request to its preview and to its full frame (none with
/// `--preview-only`), the preview's size, and how many of the frames re-ran the preparation.
struct Latency {
    preview: f64,
    /// Seconds of the preview's shading and resolve (the rest of `preview` is its scene,
    /// preparation when it re-ran, and hand-over).
    preview_shade: f64,
    full: Option<f64>,
    preview_size: (usize, usize),
    prepared: usize,
}

fn main() {
    let defaults = SceneSpec::default();
    let spec = SceneSpec {
        strands: arg("--strands", defaults.strands),
        width: arg("--width", defaults.width),
        height: arg("--height", defaults.height),
        ..defaults
    };
    let edits = arg("--edits", 5).max(1);
    let preview_only = std::env::args().any(|a| a == "--preview-only");
    let look = Look::from_scene(Scene::load(spec, None).expect("the default scene loads"));
    let renderer = Renderer::new();
    let args: Vec<String> = std::env::args().collect();
    let device = args
        .iter()
        .position(|a| a == "--device")
        .and_then(|i| args.get(i + 1))
        .map_or(Ok(cuticle_gpu::Choice::Cpu), |d| d.parse())
        .expect("--device takes auto, gpu or cpu");
    let backends = Backends::choose(device, &renderer).expect("the device opens");
    println!(
        "{} strands at {}x{}, shading on {}",
        look.groom.strand_count(),
        look.spec.width,
        look.spec.height,
        backends.full.backend()
    );
    let (tx, rx) = channel::<()>();
    let worker = Worker::start(backends.preview, backends.full, move || {
        let _ = tx.send(());
    });
    let mut id = 0;
    let mut run = |look: &Look| -> Latency {
        id += 1;
        worker.submit(Request {
            id,
            scene: look.scene(),
            revisions: look.revisions,
            interacting: preview_only,
            issued: Instant::now(),
        });
        let mut preview = None;
        let mut prepared = 0;
        loop {
            let _ = rx.recv_timeout(Duration::from_secs(120));
            for r in worker.reports() {
                match r {
                    Report::Frame(f) if f.id == id => {
                        prepared += usize::from(f.prepared);
                        match f.quality {
                            Quality::Preview if preview_only => {
                                return Latency {
                                    preview: f.latency_s,
                                    preview_shade: f.shade_s,
                                    full: None,
                                    preview_size: (f.image.width, f.image.height),
                                    prepared,
                                };
                            }
                            Quality::Preview => {
                                preview =
                                    Some((f.latency_s, f.shade_s, (f.image.width, f.image.height)))
                            }
                            Quality::Full => {
                                let (p, shade, size) = preview.expect("the preview comes first");
                                return Latency {
                                    preview: p,
                                    preview_shade: shade,
                                    full: Some(f.latency_s),
                                    preview_size: size,
                                    prepared,
                                };
                            }
                        }
                    }
                    Report::Failed { message, .. } => panic!("{message}"),
                    _ => {}
                }
            }
        }
    };
    let mut look = look;
    let ms = |s: Option<f64>| s.map_or("-".to_string(), |s| format!("{:.0} ms", 1e3 * s));
    let first = run(&look);
    println!(
        "first frame (tables kept, preparation of both qualities): preview {:.0} ms, full {}",
        1e3 * first.preview,
        ms(first.full)
    );
    let mut report = |name: &str, edit: &dyn Fn(&mut Look, usize)| {
        let (mut p, mut ps, mut f, mut size, mut prepared) =
            (Vec::new(), Vec::new(), Vec::new(), (0, 0), 0);
        let builds = renderer.table_builds();
        for k in 0..edits {
            edit(&mut look, k);
            let l = run(&look);
            p.push(l.preview);
            ps.push(l.preview_shade);
            f.extend(l.full);
            size = l.preview_size;
            prepared += l.prepared;
        }
        let after = renderer.table_builds();
        let frames = if preview_only { edits } else { 2 * edits };
        let full = (!f.is_empty()).then(|| median(f));
        println!(
            "{name}: median of {edits}: first updated frame {:.0} ms (preview {}x{}, its shading {:.0} ms), full-quality frame {}; \
             {prepared} of {frames} frames re-prepared, {} lobe-table, {} back-scattering and {} preview back-scattering builds",
            1e3 * median(p),
            size.0,
            size.1,
            1e3 * median(ps),
            ms(full),
            after.lobes - builds.lobes,
            after.back_scattering - builds.back_scattering,
            after.preview_back_scattering - builds.preview_back_scattering,
        );
    };
    report("absorption edit", &|l, k| {
        l.all_strands = Some(cuticle_groom::Absorption::Melanin {
            eumelanin: 0.5 + k as f32,
            pheomelanin: 0.2,
        })
    });
    report("beta_R edit", &|l, k| {
        l.spec.hair.beta_r_deg = 5.0 + k as f64
    });
    report("paint stroke", &|l, k| {
        // A tenth of the strands, as a wide stroke across the hair paints.
        let n = l.paint.len();
        for s in (k * n / 10)..((k + 1) * n / 10) {
            l.paint[s] = Some(cuticle_groom::Absorption::Melanin {
                eumelanin: 0.3,
                pheomelanin: 1.0 + k as f32,
            });
        }
    });
    report("camera orbit", &|l, _| {
        let c = l.spec.camera.expect("a look has a camera");
        l.spec.camera = Some(orbit::orbit(&c, 15.0, 0.0));
    });
}
