//! `cuticle view`: the live look-development window of Xu et al. 2011 §5 ("interactive hair
//! rendering and appearance editing"): a groom under environment light whose hair parameters,
//! lighting and camera are edited while watching, with colour painted onto strands.
//!
//! # The rooms
//! - [`app`]: the eframe application — its panel of controls ([`app::panel`]), the image and
//!   what the pointer does on it ([`app::viewport`]), the status line ([`app::status`]).
//! - [`look`]: the edited scene and its absorption layers (paint, all strands, the groom's own).
//! - [`worker`]: the render thread: latest request only, preview then full quality, stale
//!   frames cancelled; [`preview`]: what its quick first frame leaves out.
//! - [`shading`]: the back-end trait the worker drives, and its CPU and GPU implementations.
//! - [`jobs`]: background loads: the first scene, grooms, environment maps and SRBF re-fits.
//! - [`paint`]: the brush, picking strands through the visibility buffer, undo history.
//! - [`orbit`]: camera orbit, pan, zoom. [`presets`]: named hair colours.
//! - [`save`]: a look as files that reopen it; [`image_file`]: PNG and EXR of a frame.

pub mod app;
pub mod image_file;
pub mod jobs;
pub mod look;
pub mod options;
pub mod orbit;
pub mod paint;
pub mod presets;
pub mod preview;
pub mod save;
pub mod shading;
pub mod worker;

pub use app::ViewApp;
pub use options::ViewOptions;

/// Opens the window and runs it until it is closed; with `--screenshot`, until the screenshot
/// is written (an error choosing the device, loading the scene or writing the file is
/// returned).
pub fn run(options: ViewOptions) -> anyhow::Result<()> {
    let renderer = cuticle_render::Renderer::new();
    let backends = shading::Backends::choose(options.device, &renderer)
        .map_err(|e| anyhow::anyhow!("--device: {e}"))?;
    let backends = std::sync::Mutex::new(Some(backends));
    let size = app::window_size(&options.spec);
    let native = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_title("cuticle view")
            .with_inner_size(size),
        renderer: eframe::Renderer::Wgpu,
        ..Default::default()
    };
    let outcome = app::Outcome::default();
    let kept = outcome.clone();
    eframe::run_native(
        "cuticle view",
        native,
        Box::new(move |cc| {
            let backends = backends
                .lock()
                .ok()
                .and_then(|mut b| b.take())
                .ok_or("the window was created twice")?;
            Ok(Box::new(ViewApp::with_backends(
                &cc.egui_ctx,
                options,
                kept,
                backends,
            )))
        }),
    )
    .map_err(|e| anyhow::anyhow!("cannot open the window: {e}"))?;
    outcome.result()
}
