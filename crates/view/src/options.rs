//! What `cuticle view` is started with.

use cuticle_gpu::Choice;
use cuticle_light::SrbfLight;
use cuticle_render::SceneSpec;
use std::path::PathBuf;

/// The window's start-up settings.
#[derive(Clone, Debug)]
pub struct ViewOptions {
    /// The scene to open (flags already laid over a scene file).
    pub spec: SceneSpec,
    /// Lights read from a `lights.json` instead of fitted.
    pub lights: Option<Vec<SrbfLight>>,
    /// Save the window's contents here once the first full-quality frame is shown, and exit.
    pub screenshot: Option<PathBuf>,
    /// UI frames to wait after that frame before the screenshot.
    pub after_frames: usize,
    /// Where Save and the screenshot button write.
    pub out: PathBuf,
    /// Which back end shades (`--device`; the CPU renderer unless asked).
    pub device: Choice,
}

impl Default for ViewOptions {
    fn default() -> Self {
        Self {
            spec: SceneSpec::default(),
            lights: None,
            screenshot: None,
            after_frames: 2,
            out: PathBuf::from("out/view"),
            device: Choice::Cpu,
        }
    }
}
