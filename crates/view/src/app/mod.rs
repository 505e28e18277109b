//! The window: state, and what each UI frame does — collect finished frames and loads, draw the
//! controls ([`panel`]), the image ([`viewport`]) and the status line ([`status`]), then send the
//! worker the look if it changed (after checking it; a look that fails is undone with an error
//! shown, so the previous scene stays).

pub mod panel;
pub mod status;
pub mod viewport;

use crate::jobs::{self, Job, Loaded};
use crate::look::{Look, Revisions};
use crate::options::ViewOptions;
use crate::paint::brush::Brush;
use crate::paint::history::{History, PaintLayer};
use crate::shading::Backends;
use crate::worker::{Frame, Quality, Report, Request, Worker};
use cuticle_groom::Absorption;
use cuticle_light::ToneMap;
use cuticle_render::{Camera, Renderer, SceneSpec};
use std::path::PathBuf;
use std::sync::{Arc, Mutex};
use std::time::Instant;

/// Width of the controls panel, points.
pub const PANEL_WIDTH: f32 = 330.0;

/// The window's size for an image of the spec's size beside the panel.
pub fn window_size(spec: &SceneSpec) -> egui::Vec2 {
    egui::vec2(
        PANEL_WIDTH + spec.width.clamp(160, 1600) as f32 + 24.0,
        (spec.height.clamp(120, 1000) as f32 + 60.0).max(640.0),
    )
}

/// How `cuticle view --screenshot` ended, shared with the caller of `eframe::run_native`.
#[derive(Clone, Default)]
pub struct Outcome(Arc<Mutex<Option<Result<(), String>>>>);

impl Outcome {
    fn set(&self, r: Result<(), String>) {
        if let Ok(mut o) = self.0.lock() {
            o.get_or_insert(r);
        }
    }

    /// Whether the run has ended (a screenshot written, or an error).
    pub fn is_set(&self) -> bool {
        self.0.lock().map_or(true, |o| o.is_some())
    }

    /// Ok unless a screenshot run failed.
    pub fn result(&self) -> anyhow::Result<()> {
        match self.0.lock().ok().and_then(|o| o.clone()) {
            Some(Err(e)) => Err(anyhow::anyhow!(e)),
            _ => Ok(()),
        }
    }
}

/// What the pointer does on the image.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Tool {
    /// Drag to orbit, right- or middle-drag to pan, scroll to zoom.
    Camera,
    /// Drag to paint; right-drag orbits, scroll zooms.
    Paint,
}

/// How an absorption is entered.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum AbsorptionEdit {
    /// Each strand's own (the groom's; for all strands only).
    Own,
    /// μ_a per unit radius, RGB.
    MuA([f64; 3]),
    /// Eumelanin and pheomelanin concentrations.
    Melanin([f64; 2]),
    /// A target colour (linear RGB), through Chiang et al. 2016 eq. 9.
    Colour([f32; 3]),
}

/// Azimuthal roughness β_n at which a target colour is inverted into μ_a: the fiber crate's,
/// which USD grooms' colours use too.
pub use cuticle_fiber::optics::absorption::COLOUR_BETA_N;

impl AbsorptionEdit {
    /// The absorption this edit sets (`None` for the strands' own).
    pub fn absorption(&self) -> Option<Absorption> {
        match *self {
            Self::Own => None,
            Self::MuA(s) => Some(Absorption::MuA(s.map(|c| c as f32))),
            Self::Melanin([e, p]) => Some(Absorption::Melanin {
                eumelanin: e as f32,
                pheomelanin: p as f32,
            }),
            Self::Colour(c) => {
                let m = cuticle_fiber::optics::absorption::mu_a_from_color(
                    glam::Vec3::from_array(c).as_dvec3(),
                    COLOUR_BETA_N,
                );
                Some(crate::look::mu_a(m))
            }
        }
    }

    /// The edit showing `a`.
    pub fn of(a: Option<Absorption>) -> Self {
        match a {
            None => Self::Own,
            Some(Absorption::MuA(s)) => Self::MuA(s.map(f64::from)),
            Some(Absorption::Melanin {
                eumelanin,
                pheomelanin,
            }) => Self::Melanin([eumelanin as f64, pheomelanin as f64]),
        }
    }
}

/// Text fields and other control state that is not part of the look.
pub struct Controls {
    pub tool: Tool,
    pub brush: Brush,
    pub brush_edit: AbsorptionEdit,
    pub all_edit: AbsorptionEdit,
    /// The μ_a text of the all-strands editor ("r, g, b" or one value).
    pub sigma_text: String,
    /// The μ_a text of the brush's editor.
    pub brush_sigma_text: String,
    pub groom_text: String,
    pub strands: usize,
    pub env_text: String,
    pub lights: usize,
    pub out_text: String,
}

/// The frame on screen.
pub struct Shown {
    pub frame: Frame,
    pub texture: egui::TextureHandle,
}

/// What was last sent to the worker.
#[derive(Clone, Debug, PartialEq)]
struct Fingerprint {
    spec: SceneSpec,
    all_strands: Option<Absorption>,
    paint_serial: u64,
    revisions: Revisions,
}

/// The application.
pub struct ViewApp {
    options: ViewOptions,
    outcome: Outcome,
    ctx: egui::Context,
    /// The look, once the first scene has loaded.
    pub look: Option<Look>,
    /// The last look that passed its checks (what a failed edit returns to).
    valid: Option<Look>,
    pub controls: Controls,
    worker: Worker,
    scene_job: Option<Job>,
    groom_job: Option<Job>,
    fit_job: Option<Job>,
    next_id: u64,
    sent: Option<(Fingerprint, bool)>,
    /// Id of the latest request.
    latest_id: u64,
    pub shown: Option<Shown>,
    /// The latest full-quality frame of the current look.
    pub full: Option<Frame>,
    tone: Option<(u64, ToneMap)>,
    /// Errors to show, newest last.
    pub errors: Vec<String>,
    pub notes: Vec<String>,
    pub history: History,
    paint_serial: u64,
    stroke: Option<PaintLayer>,
    last_dab: Option<egui::Pos2>,
    /// The image's rectangle on screen, points.
    pub image_rect: Option<egui::Rect>,
    /// UI frames since the first full frame was shown (for `--screenshot`).
    frames_after_full: usize,
    screenshot_sent: bool,
    /// The back ends shade on the GPU.
    gpu: bool,
}

impl ViewApp {
    /// The app on the back ends `options.device` asks for (the CPU renderer, with the error
    /// shown, when there are none), starting to load `options.spec` in the background.
    pub fn new(ctx: &egui::Context, options: ViewOptions, outcome: Outcome) -> Self {
        let renderer = Renderer::new();
        let (backends, error) = match Backends::choose(options.device, &renderer) {
            Ok(b) => (b, None),
            Err(e) => (
                Backends::cpu(&renderer),
                Some(format!("--device: {e}; shading on the CPU")),
            ),
        };
        let mut app = Self::with_backends(ctx, options, outcome, backends);
        app.errors.extend(error);
        app
    }

    /// The app on `backends`, starting to load `options.spec` in the background.
    pub fn with_backends(
        ctx: &egui::Context,
        options: ViewOptions,
        outcome: Outcome,
        backends: Backends,
    ) -> Self {
        let notify = repaint(ctx);
        let gpu = backends.gpu;
        let worker = Worker::start(backends.preview, backends.full, notify);
        let spec = options.spec.clone();
        let controls = Controls {
            tool: Tool::Camera,
            brush: Brush::default(),
            brush_edit: AbsorptionEdit::of(Some(Brush::default().absorption)),
            all_edit: AbsorptionEdit::Own,
            sigma_text: String::new(),
            brush_sigma_text: String::new(),
            groom_text: spec.groom.clone(),
            strands: spec.strands,
            env_text: spec.env.clone(),
            lights: spec.lights,
            out_text: options.out.display().to_string(),
        };
        let scene_job = Some(jobs::load_scene(spec, options.lights.clone(), repaint(ctx)));
        Self {
            options,
            outcome,
            ctx: ctx.clone(),
            look: None,
            valid: None,
            controls,
            worker,
            scene_job,
            groom_job: None,
            fit_job: None,
            next_id: 1,
            sent: None,
            latest_id: 0,
            shown: None,
            full: None,
            tone: None,
            errors: Vec::new(),
            notes: Vec::new(),
            history: History::default(),
            paint_serial: 0,
            stroke: None,
            last_dab: None,
            image_rect: None,
            frames_after_full: 0,
            screenshot_sent: false,
            gpu,
        }
    }

    /// Whether the GPU back end shades (it renders the SRBF method only).
    pub fn on_gpu(&self) -> bool {
        self.gpu
    }

    /// Whether nothing is loading or rendering and the full frame of the current look is shown.
    pub fn settled(&self) -> bool {
        self.scene_job.is_none()
            && self.groom_job.is_none()
            && self.fit_job.is_none()
            && self.sent.as_ref().is_some_and(|s| !s.1)
            && self
                .shown
                .as_ref()
                .is_some_and(|s| s.frame.quality == Quality::Full && s.frame.id == self.latest_id)
    }

    /// Whether a background load is running.
    pub fn loading(&self) -> Option<(String, f32)> {
        [&self.scene_job, &self.groom_job, &self.fit_job]
            .into_iter()
            .flatten()
            .next()
            .map(|j| (j.what.clone(), j.progress()))
    }

    /// Shows `e` in the window; a `--screenshot` run, which nobody watches, ends with it
    /// instead (issue 57 #4: a render that failed left it waiting for a frame forever).
    fn error(&mut self, e: impl Into<String>) {
        let e = e.into();
        if self.options.screenshot.is_some() {
            self.outcome.set(Err(e.clone()));
            self.ctx.send_viewport_cmd(egui::ViewportCommand::Close);
        }
        if self.errors.last() != Some(&e) {
            self.errors.push(e);
        }
    }

    /// Takes finished loads into the look.
    fn collect_jobs(&mut self) {
        if let Some(r) = self.scene_job.as_ref().and_then(Job::poll) {
            self.scene_job = None;
            match r {
                Ok(Loaded::Scene(look)) => {
                    self.controls.all_edit = AbsorptionEdit::of(look.all_strands);
                    self.look = Some(*look);
                }
                Ok(_) => {}
                Err(e) => self.error(e),
            }
        }
        if let Some(r) = self.groom_job.as_ref().and_then(Job::poll) {
            self.groom_job = None;
            match r {
                Ok(Loaded::Groom { name, groom }) => self.take_groom(name, *groom),
                Ok(_) => {}
                Err(e) => self.error(e),
            }
        }
        if let Some(r) = self.fit_job.as_ref().and_then(Job::poll) {
            self.fit_job = None;
            match r {
                Ok(Loaded::Lights {
                    env,
                    lights,
                    fit_error,
                }) => {
                    if let Some(look) = &mut self.look {
                        look.spec.env = self.controls.env_text.clone();
                        look.spec.lights = lights.len().max(1);
                        look.env = Arc::new(*env);
                        look.lights = Arc::new(lights);
                        look.fit_error = Some(fit_error);
                        look.revisions.lights += 1;
                    }
                }
                Ok(_) => {}
                Err(e) => self.error(e),
            }
        }
    }

    fn take_groom(&mut self, name: String, groom: cuticle_groom::Groom) {
        let Some(look) = &mut self.look else { return };
        let b = groom.bounds();
        look.spec.groom = name;
        look.spec.strands = self.controls.strands;
        look.spec.strand_absorption = None;
        look.spec.camera = Some(Camera::framing(b.min, b.max, true));
        look.paint = vec![None; groom.strand_count()];
        look.groom = Arc::new(groom);
        look.revisions.groom += 1;
        self.history.clear();
        self.paint_serial += 1;
    }

    /// Starts loading a groom (preset, `.hair` or USD).
    pub fn load_groom(&mut self) {
        let name = self.controls.groom_text.trim().to_string();
        self.groom_job = Some(jobs::load_groom(
            name,
            self.controls.strands,
            repaint(&self.ctx),
        ));
    }

    /// Starts loading the environment in the text field and fitting the light count to it.
    pub fn load_env(&mut self) {
        self.refit(false);
    }

    /// Starts a background re-fit: of the current map (`same_map`) or of the one named.
    pub fn refit(&mut self, same_map: bool) {
        let Some(look) = &self.look else { return };
        let current = same_map.then(|| look.env.clone());
        if !same_map {
            self.controls.env_text = self.controls.env_text.trim().to_string();
        }
        self.fit_job = Some(jobs::fit_lights(
            self.controls.env_text.clone(),
            current,
            look.spec.env_rotate_deg,
            self.controls.lights.max(1),
            repaint(&self.ctx),
        ));
    }

    /// Takes the worker's frames onto the screen, newest wins.
    fn collect_frames(&mut self, ctx: &egui::Context) {
        for report in self.worker.reports() {
            match report {
                Report::Frame(frame) => self.show(ctx, *frame),
                Report::Failed { message, .. } => self.error(format!("render failed: {message}")),
            }
        }
    }

    fn tone(&mut self) -> ToneMap {
        let Some(look) = &self.look else {
            return ToneMap { exposure: 1.0 };
        };
        let rev = look.revisions.lights;
        match self.tone {
            Some((r, t)) if r == rev => t,
            _ => {
                let t = ToneMap::for_map(&look.env);
                self.tone = Some((rev, t));
                t
            }
        }
    }

    fn show(&mut self, ctx: &egui::Context, frame: Frame) {
        if self.shown.as_ref().is_some_and(|s| s.frame.id > frame.id) {
            return;
        }
        let tone = self.tone();
        let img = &frame.image;
        let pixels = img
            .pixels
            .iter()
            .map(|p| {
                let [r, g, b] = tone.apply(p.as_vec3());
                egui::Color32::from_rgb(r, g, b)
            })
            .collect();
        let color = egui::ColorImage::new([img.width, img.height], pixels);
        let options = egui::TextureOptions::LINEAR;
        let texture = match self.shown.take() {
            Some(mut s) => {
                s.texture.set(color, options);
                s.texture
            }
            None => ctx.load_texture("frame", color, options),
        };
        if frame.quality == Quality::Full && frame.id == self.latest_id {
            self.full = Some(frame.clone());
        }
        self.shown = Some(Shown { frame, texture });
    }

    /// Sends the look to the worker if it changed or input stopped; a look that fails its
    /// checks is replaced by the last one that passed, with the error shown.
    fn submit(&mut self, interacting: bool) {
        let Some(look) = &self.look else { return };
        let fingerprint = Fingerprint {
            spec: look.spec.clone(),
            all_strands: look.all_strands,
            paint_serial: self.paint_serial,
            revisions: look.revisions,
        };
        let changed = self.sent.as_ref().is_none_or(|s| s.0 != fingerprint);
        let released = self.sent.as_ref().is_some_and(|s| s.1) && !interacting;
        if !changed && !released {
            return;
        }
        if let Err(e) = check(look) {
            self.error(e);
            match &self.valid {
                Some(valid) => {
                    self.look = Some(valid.clone());
                    self.controls.all_edit = AbsorptionEdit::of(valid.all_strands);
                }
                None => self.look = None,
            }
            return;
        }
        self.valid = Some(look.clone());
        let id = self.next_id;
        self.next_id += 1;
        self.latest_id = id;
        self.full = None;
        self.worker.submit(Request {
            id,
            scene: look.scene(),
            revisions: look.revisions,
            interacting,
            issued: Instant::now(),
        });
        self.sent = Some((fingerprint, interacting));
    }

    /// The paint layer is about to change: a stroke records it once.
    pub fn begin_edit(&mut self) {
        if self.stroke.is_none()
            && let Some(look) = &self.look
        {
            self.stroke = Some(look.paint.clone());
        }
    }

    /// The stroke is over: it becomes an undo step if it changed anything.
    pub fn end_edit(&mut self) {
        if let (Some(before), Some(look)) = (self.stroke.take(), &self.look)
            && before != look.paint
        {
            self.history.record(before);
        }
        self.last_dab = None;
    }

    pub fn undo(&mut self) {
        if let Some(look) = &mut self.look
            && let Some(layer) = self.history.undo(&look.paint)
        {
            look.paint = layer;
            self.paint_serial += 1;
        }
    }

    pub fn redo(&mut self) {
        if let Some(look) = &mut self.look
            && let Some(layer) = self.history.redo(&look.paint)
        {
            look.paint = layer;
            self.paint_serial += 1;
        }
    }

    /// Removes all paint (an undoable step).
    pub fn clear_paint(&mut self) {
        let Some(look) = &mut self.look else { return };
        if look.paint.iter().all(Option::is_none) {
            return;
        }
        let cleared = vec![None; look.paint.len()];
        self.history
            .record(std::mem::replace(&mut look.paint, cleared));
        self.paint_serial += 1;
    }

    /// Paints one dab at full-resolution image position (x, y) on the strands of the frame on
    /// screen; returns the number of strands changed.
    pub fn dab(&mut self, x: f64, y: f64) -> usize {
        let Some(target) = self.controls.brush_edit.absorption() else {
            return 0;
        };
        let to = cuticle_render::scene::hair::mu_a_of(target);
        let range = cuticle_fiber::ranges::MU_A;
        if !to.to_array().iter().all(|&c| range.contains(c)) {
            self.error(format!("the brush's μ_a {to} is outside {range}"));
            return 0;
        }
        let (Some(look), Some(shown)) = (&mut self.look, &self.shown) else {
            return 0;
        };
        let brush = Brush {
            absorption: target,
            ..self.controls.brush
        };
        let mut changed = 0;
        for (s, w) in brush.dab(&shown.frame.strands, look.spec.width, x, y) {
            let s = s as usize;
            let new = crate::paint::brush::blend(look.mu_a(s), to, w);
            let new = Some(crate::look::mu_a(new));
            if s < look.paint.len() && look.paint[s] != new {
                look.paint[s] = new;
                changed += 1;
            }
        }
        if changed > 0 {
            self.paint_serial += 1;
        }
        changed
    }

    /// Saves the look into the output folder's `look/`.
    pub fn save(&mut self) {
        let Some(look) = &self.look else { return };
        let dir = PathBuf::from(self.controls.out_text.trim()).join("look");
        match crate::save::save_look(look, &dir) {
            Ok(scene) => self.notes.push(format!("saved {}", scene.display())),
            Err(e) => self.error(e),
        }
    }

    /// Writes the full-quality frame on screen as PNG and EXR into the output folder.
    pub fn screenshot(&mut self) {
        let Some(frame) = self.full.clone() else {
            self.error("no full-quality frame yet: wait for the image to refine");
            return;
        };
        let tone = self.tone();
        let dir = PathBuf::from(self.controls.out_text.trim());
        let written = std::fs::create_dir_all(&dir)
            .map_err(|e| format!("cannot create {}: {e}", dir.display()))
            .and_then(|_| {
                let n = (1..10_000)
                    .find(|n| !dir.join(format!("frame-{n:04}.png")).exists())
                    .unwrap_or(0);
                let stem = dir.join(format!("frame-{n:04}"));
                let png = frame.image.png_bytes(tone).map_err(|e| e.to_string())?;
                let exr = frame.image.exr_bytes().map_err(|e| e.to_string())?;
                crate::image_file::write_atomic(&stem.with_extension("exr"), &exr)?;
                crate::image_file::write_atomic(&stem.with_extension("png"), &png)?;
                Ok(stem)
            });
        match written {
            Ok(stem) => self
                .notes
                .push(format!("wrote {}.png and .exr", stem.display())),
            Err(e) => self.error(e),
        }
    }

    /// `--screenshot`: once the first full frame has been on screen for the frames asked,
    /// asks for the window's pixels, writes them, and closes.
    fn screenshot_mode(&mut self, ctx: &egui::Context) {
        let Some(path) = self.options.screenshot.clone() else {
            return;
        };
        if self.outcome.is_set() {
            ctx.send_viewport_cmd(egui::ViewportCommand::Close);
            return;
        }
        if self.full.is_none() || self.screenshot_sent {
            // The worker wakes the window when a frame arrives. Repainting every UI frame while
            // waiting took half of a two-core machine's CPU from the renderer (a UI frame in
            // software GL under xvfb costs tens of milliseconds), and every 100 ms a third.
            ctx.request_repaint_after(SCREENSHOT_POLL);
            return;
        }
        if self.frames_after_full < self.options.after_frames {
            self.frames_after_full += 1;
            ctx.request_repaint();
            return;
        }
        self.screenshot_sent = true;
        let outcome = self.outcome.clone();
        let waker = ctx.clone();
        ctx.request_screenshot(move |image| {
            outcome.set(write_color_image(&path, &image));
            waker.request_repaint();
        });
    }
}

/// The checks a look must pass before it is rendered: the scene's own validation (every range
/// stated once, in the render crate).
fn check(look: &Look) -> Result<(), String> {
    let mut spec = look.spec.clone();
    if let Some(a) = look.all_strands {
        let s = cuticle_render::scene::hair::mu_a_of(a);
        spec.hair.mu_a = Some(s.to_array());
    }
    spec.validate().map_err(|e| e.to_string())
}

fn write_color_image(path: &std::path::Path, image: &egui::ColorImage) -> Result<(), String> {
    let [w, h] = image.size;
    // The window is opaque: its alpha is 255 everywhere.
    let rgb: Vec<u8> = image
        .pixels
        .iter()
        .flat_map(|c| [c.r(), c.g(), c.b()])
        .collect();
    let png = cuticle_light::image_file::png_bytes(w, h, rgb)
        .map_err(|e| format!("the screenshot: {e}"))?;
    crate::image_file::write_atomic(path, &png)
}

/// How often `--screenshot` looks for the first full frame (or its written file) unasked.
const SCREENSHOT_POLL: std::time::Duration = std::time::Duration::from_secs(1);

/// A callback that asks `ctx` for a repaint.
fn repaint(ctx: &egui::Context) -> impl Fn() + Send + 'static {
    let ctx = ctx.clone();
    move || ctx.request_repaint()
}

impl ViewApp {
    /// One UI frame of the window (eframe calls it through [`eframe::App`]; tests directly).
    pub fn show_ui(&mut self, ui: &mut egui::Ui) {
        let ctx = ui.ctx().clone();
        self.collect_jobs();
        self.collect_frames(&ctx);
        status::show(self, ui);
        panel::show(self, ui);
        viewport::show(self, ui);
        let interacting = ctx.input(|i| i.pointer.any_down()) || ctx.dragged_id().is_some();
        self.submit(interacting);
        if self.loading().is_some() {
            ctx.request_repaint_after(std::time::Duration::from_millis(100));
        }
        self.screenshot_mode(&ctx);
    }
}

impl eframe::App for ViewApp {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        self.show_ui(ui);
    }
}
