//! The render worker: one thread that turns the latest request into frames, so the window never
//! waits on the renderer.
//!
//! - A request replaces any that is waiting (stale edits are never rendered) and cancels a
//!   full-quality frame in progress.
//! - Each request is shown first as a preview ([`Quality::Preview`], [`crate::preview`]: fewer
//!   pixels, lights and quadrature segments, sized from the last preview that built no table so
//!   that shading takes about [`crate::preview::PREVIEW_BUDGET_S`]); a request made while input
//!   moves stops there, any other is refined to the full image when nothing newer waits.
//! - Each quality keeps its own preparation and re-runs it only when the camera, image size,
//!   groom geometry, lights or shadow settings change; any other edit re-runs shading only.

use crate::look::Revisions;
use crate::preview::{next_scale, preview_scene};
use crate::shading::{Shading, StrandBuffer};
use cuticle_render::{Camera, Image, Method, Scene, ShadowOptions};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{Receiver, Sender, channel};
use std::sync::{Arc, Condvar, Mutex};
use std::thread::JoinHandle;
use std::time::Instant;

/// How a frame was made.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Quality {
    /// Reduced resolution, one subsample per pixel, fewer lights ([`crate::preview`]).
    Preview,
    /// The scene's own resolution and supersampling.
    Full,
}

/// What the window asks for.
pub struct Request {
    /// Increases with every request.
    pub id: u64,
    pub scene: Scene,
    pub revisions: Revisions,
    /// Input is still moving: a preview is enough.
    pub interacting: bool,
    pub issued: Instant,
}

/// A finished frame.
#[derive(Clone, Debug)]
pub struct Frame {
    /// The request it answers.
    pub id: u64,
    pub quality: Quality,
    pub image: Image,
    pub strands: Arc<StrandBuffer>,
    /// Whether it re-ran the preparation (false when the kept one served).
    pub prepared: bool,
    /// Seconds of the preparation it needed (0 when the kept one served).
    pub prepare_s: f64,
    /// Seconds of shading and resolve.
    pub shade_s: f64,
    /// Seconds from the request to this frame.
    pub latency_s: f64,
    /// Which back end shaded it.
    pub backend: String,
    /// Strand records its shading re-uploaded for paint (the GPU back end).
    pub strands_updated: usize,
    /// Whole-groom shadow computations its back end has made so far (the CPU back end; see
    /// [`Shading::shadow_passes`]).
    pub shadow_passes: u64,
    /// Points this frame's shading computed ([`Shading::points_shaded`]).
    pub points_shaded: Option<usize>,
}

/// What the worker reports.
pub enum Report {
    Frame(Box<Frame>),
    /// A frame could not be made (the back end's error, or the message of a panic in it).
    Failed {
        id: u64,
        message: String,
    },
}

/// What a preparation depends on.
#[derive(Clone, Debug, PartialEq)]
struct PrepareKey {
    revisions: Revisions,
    camera: Option<Camera>,
    width: usize,
    height: usize,
    supersampling: usize,
    shadows: ShadowOptions,
    method: Method,
    brute_grid: usize,
}

impl PrepareKey {
    /// Whether `next` differs from this key in its lights alone.
    fn lights_only(&self, next: &Self) -> bool {
        let same_but_lights = Self {
            revisions: Revisions {
                lights: next.revisions.lights,
                ..self.revisions
            },
            ..self.clone()
        };
        self.revisions.lights != next.revisions.lights && same_but_lights == *next
    }

    fn of(scene: &Scene, revisions: Revisions) -> Self {
        let s = &scene.spec;
        Self {
            revisions,
            camera: Some(scene.camera),
            width: s.width,
            height: s.height,
            supersampling: s.supersampling,
            shadows: s.shadows,
            method: s.method,
            brute_grid: s.brute_grid,
        }
    }
}

/// One quality's back end and what it last prepared.
struct Slot {
    shading: Box<dyn Shading>,
    key: Option<PrepareKey>,
    strands: Arc<StrandBuffer>,
}

impl Slot {
    fn new(shading: Box<dyn Shading>) -> Self {
        Self {
            shading,
            key: None,
            strands: Arc::default(),
        }
    }

    /// Prepares `scene` unless the kept preparation serves; the seconds it took, `None` when it
    /// served.
    fn prepare(&mut self, scene: &Scene, revisions: Revisions) -> Result<Option<f64>, String> {
        let key = PrepareKey::of(scene, revisions);
        if self.key.as_ref() == Some(&key) {
            return Ok(None);
        }
        let start = Instant::now();
        let relight = self.key.as_ref().is_some_and(|k| k.lights_only(&key));
        self.key = None;
        if relight {
            self.shading.relight(scene)?;
        } else {
            self.shading.prepare(scene)?;
        }
        self.strands = Arc::new(self.shading.strands());
        self.key = Some(key);
        Ok(Some(start.elapsed().as_secs_f64()))
    }
}

struct Mailbox {
    pending: Mutex<Option<Request>>,
    wake: Condvar,
    cancel: AtomicBool,
    stop: AtomicBool,
}

/// The handle the window keeps.
pub struct Worker {
    mailbox: Arc<Mailbox>,
    reports: Receiver<Report>,
    thread: Option<JoinHandle<()>>,
}

impl Worker {
    /// Starts the thread with one back end per quality; `notify` is called after each report
    /// (the window's repaint).
    pub fn start(
        preview: Box<dyn Shading>,
        full: Box<dyn Shading>,
        notify: impl Fn() + Send + 'static,
    ) -> Self {
        let mailbox = Arc::new(Mailbox {
            pending: Mutex::new(None),
            wake: Condvar::new(),
            cancel: AtomicBool::new(false),
            stop: AtomicBool::new(false),
        });
        let (tx, reports) = channel();
        let m = mailbox.clone();
        let thread = std::thread::Builder::new()
            .name("cuticle-view render".into())
            .spawn(move || {
                Loop {
                    mailbox: m,
                    reports: tx,
                    notify: Box::new(notify),
                    preview: Slot::new(preview),
                    full: Slot::new(full),
                    scale: 2,
                }
                .run()
            })
            .ok();
        Self {
            mailbox,
            reports,
            thread,
        }
    }

    /// Replaces the waiting request and cancels a full frame in progress.
    pub fn submit(&self, request: Request) {
        if let Ok(mut pending) = self.mailbox.pending.lock() {
            *pending = Some(request);
            self.mailbox.cancel.store(true, Ordering::SeqCst);
            self.mailbox.wake.notify_one();
        }
    }

    /// Reports since the last call, oldest first.
    pub fn reports(&self) -> Vec<Report> {
        self.reports.try_iter().collect()
    }

    /// Whether the thread is running.
    pub fn alive(&self) -> bool {
        self.thread.as_ref().is_some_and(|t| !t.is_finished())
    }
}

impl Drop for Worker {
    fn drop(&mut self) {
        self.mailbox.stop.store(true, Ordering::SeqCst);
        self.mailbox.cancel.store(true, Ordering::SeqCst);
        self.mailbox.wake.notify_one();
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

struct Loop {
    mailbox: Arc<Mailbox>,
    reports: Sender<Report>,
    notify: Box<dyn Fn() + Send>,
    preview: Slot,
    full: Slot,
    /// Current preview reduction along each axis.
    scale: usize,
}

impl Loop {
    fn run(mut self) {
        while let Some(request) = self.next() {
            let id = request.id;
            let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                self.serve(&request);
            }));
            if let Err(panic) = outcome {
                let message = panic
                    .downcast_ref::<String>()
                    .cloned()
                    .or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()))
                    .unwrap_or_else(|| "the renderer failed".into());
                self.preview.key = None;
                self.full.key = None;
                self.send(Report::Failed { id, message });
            }
        }
    }

    /// Waits for the next request (None once stopped); clears the cancel flag as it takes one.
    fn next(&self) -> Option<Request> {
        let mut pending = self.mailbox.pending.lock().ok()?;
        loop {
            if self.mailbox.stop.load(Ordering::SeqCst) {
                return None;
            }
            if let Some(r) = pending.take() {
                self.mailbox.cancel.store(false, Ordering::SeqCst);
                return Some(r);
            }
            pending = self.mailbox.wake.wait(pending).ok()?;
        }
    }

    fn newer_waiting(&self) -> bool {
        self.mailbox.pending.lock().map_or(true, |p| p.is_some())
    }

    fn send(&self, report: Report) {
        let _ = self.reports.send(report);
        (self.notify)();
    }

    /// A preview of the request, then its full frame unless input moves or a newer one waits.
    fn serve(&mut self, request: &Request) {
        let preview = preview_scene(&request.scene, self.scale);
        let never = AtomicBool::new(false);
        let builds = self.preview.shading.table_builds();
        match render(
            &mut self.preview,
            &preview,
            request,
            Quality::Preview,
            &never,
        ) {
            Ok(Some(frame)) => {
                // A table built on the way (a new η, β_R, ...) is no measure of shading.
                if self.preview.shading.table_builds() == builds {
                    self.scale = next_scale(self.scale, frame.shade_s);
                }
                self.send(Report::Frame(Box::new(frame)));
            }
            Ok(None) => {}
            Err(message) => return self.fail(request.id, message),
        }
        if request.interacting || self.newer_waiting() {
            return;
        }
        let cancel = &self.mailbox.cancel;
        match render(
            &mut self.full,
            &request.scene,
            request,
            Quality::Full,
            cancel,
        ) {
            Ok(Some(frame)) => self.send(Report::Frame(Box::new(frame))),
            Ok(None) => {}
            Err(message) => self.fail(request.id, message),
        }
    }

    fn fail(&self, id: u64, message: String) {
        self.send(Report::Failed { id, message });
    }
}

/// One frame of `scene` by `slot`'s back end (`None` when cancelled).
fn render(
    slot: &mut Slot,
    scene: &Scene,
    request: &Request,
    quality: Quality,
    cancel: &AtomicBool,
) -> Result<Option<Frame>, String> {
    let prepare_s = slot.prepare(scene, request.revisions)?;
    let start = Instant::now();
    let Some(image) = slot.shading.shade(scene, cancel)? else {
        return Ok(None);
    };
    Ok(Some(Frame {
        id: request.id,
        quality,
        image,
        strands: slot.strands.clone(),
        prepared: prepare_s.is_some(),
        prepare_s: prepare_s.unwrap_or(0.0),
        shade_s: start.elapsed().as_secs_f64(),
        latency_s: request.issued.elapsed().as_secs_f64(),
        backend: slot.shading.backend(),
        strands_updated: slot.shading.strands_updated(),
        shadow_passes: slot.shading.shadow_passes(),
        points_shaded: slot.shading.points_shaded(),
    }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use cuticle_render::SceneSpec;
    use std::sync::atomic::AtomicUsize;

    /// Counts the preparations and relightings it is asked for.
    #[derive(Clone, Default)]
    struct Counting {
        prepares: Arc<AtomicUsize>,
        relights: Arc<AtomicUsize>,
    }

    impl Shading for Counting {
        fn backend(&self) -> String {
            "counting".into()
        }
        fn prepare(&mut self, _: &Scene) -> Result<(), String> {
            self.prepares.fetch_add(1, Ordering::SeqCst);
            Ok(())
        }
        fn relight(&mut self, _: &Scene) -> Result<(), String> {
            self.relights.fetch_add(1, Ordering::SeqCst);
            Ok(())
        }
        fn shade(&mut self, _: &Scene, _: &AtomicBool) -> Result<Option<Image>, String> {
            Ok(None)
        }
        fn strands(&self) -> StrandBuffer {
            StrandBuffer::default()
        }
    }

    /// New lights alone relight the kept preparation; new lights with anything else, or a
    /// first request, prepare; nothing new does neither.
    #[test]
    fn only_new_lights_relight() {
        let spec = SceneSpec {
            strands: 4,
            width: 16,
            height: 12,
            lights: 2,
            ..SceneSpec::default()
        };
        let mut scene = Scene::load(spec, None).expect("the test scene loads");
        let counting = Counting::default();
        let mut slot = Slot::new(Box::new(counting.clone()));
        let counts = || {
            (
                counting.prepares.load(Ordering::SeqCst),
                counting.relights.load(Ordering::SeqCst),
            )
        };
        let mut revisions = Revisions::default();
        slot.prepare(&scene, revisions).unwrap();
        assert_eq!(counts(), (1, 0), "a first request prepares");
        slot.prepare(&scene, revisions).unwrap();
        assert_eq!(counts(), (1, 0), "nothing new");
        revisions.lights += 1;
        slot.prepare(&scene, revisions).unwrap();
        assert_eq!(counts(), (1, 1), "new lights relight");
        revisions.lights += 1;
        scene.spec.width += 1;
        slot.prepare(&scene, revisions).unwrap();
        assert_eq!(counts(), (2, 1), "new lights and a new size prepare");
        revisions.lights += 1;
        revisions.groom += 1;
        slot.prepare(&scene, revisions).unwrap();
        assert_eq!(counts(), (3, 1), "new lights and a new groom prepare");
    }
}
