//! `cuticle view`: the live look-development window (crate cuticle-view) on a scene from the
//! same flags and scene file as `render`; `--screenshot FILE` saves the window once its first
//! full-quality frame is shown, and exits.

use crate::commands::render::{SceneArgs, spec_from};
use anyhow::Result;
use cuticle_fiber::ranges::CountRange;
use std::path::PathBuf;

#[derive(clap::Args, Clone, Debug)]
pub struct Args {
    #[command(flatten)]
    scene: SceneArgs,
    /// Save the window's contents as PNG here once the first full-quality frame is shown, then
    /// exit.
    #[arg(long)]
    screenshot: Option<PathBuf>,
    /// UI frames to wait after the first full-quality frame before the screenshot (0 to 1000).
    #[arg(long, default_value_t = 2)]
    after_frames: usize,
    /// Where the window's Save and screenshot buttons write.
    #[arg(long, default_value = "out/view")]
    out: PathBuf,
    /// auto (a hardware GPU where one exists, else the CPU), gpu (any adapter, a software one
    /// included) or cpu.
    #[arg(long, default_value = "auto")]
    device: cuticle_gpu::Choice,
}

/// Frames `--screenshot` waits: a few let the interface settle; a billion never end.
const AFTER_FRAMES: CountRange = CountRange {
    name: "after_frames",
    min: 0,
    max: 1000,
};

pub fn run(args: Args) -> Result<()> {
    let (spec, lights) = spec_from(&args.scene)?;
    spec.validate()?;
    AFTER_FRAMES.check_usize(args.after_frames)?;
    // The window's first frame needs what `render`'s does: refused before the window opens.
    spec.memory_need(lights.as_ref().map(Vec::len), rayon::current_num_threads())
        .check(cuticle_render::scene::headroom::available())?;
    if spec.method == cuticle_render::Method::Path {
        anyhow::bail!(
            "the window shades with srbf or brute; --method path is for `cuticle render`"
        );
    }
    if spec.method != cuticle_render::Method::Srbf && args.device == cuticle_gpu::Choice::Gpu {
        anyhow::bail!(
            "--method {:?} runs on the CPU only: use --device cpu or auto",
            spec.method
        );
    }
    // The brute force shades on the CPU (auto never takes the GPU for it).
    let device = match spec.method {
        cuticle_render::Method::Srbf => args.device,
        _ => cuticle_gpu::Choice::Cpu,
    };
    if let Some(path) = &args.screenshot
        && let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty())
        && !dir.is_dir()
    {
        anyhow::bail!(
            "--screenshot {}: no folder {}",
            path.display(),
            dir.display()
        );
    }
    cuticle_view::run(cuticle_view::ViewOptions {
        spec,
        lights,
        screenshot: args.screenshot,
        after_frames: args.after_frames,
        out: args.out,
        device,
    })
}
