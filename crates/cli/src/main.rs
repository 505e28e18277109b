//! `cuticle`: the command line. Thin by design: each subcommand parses its flags, calls one
//! library function, and writes its files through [`output`] (atomically, with a JSON record).

mod commands;
mod latlong_io;
mod output;
mod progress;
mod svg_plot;

use clap::{Parser, Subcommand};

#[derive(Parser)]
#[command(
    name = "cuticle",
    version,
    about = "Physically based hair: fiber models, ground truth, rendering"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Lat-long images of a fiber model's lobes (and, with --samples, of its importance sampling).
    Lobes(commands::lobes::Args),
    /// Albedo ∫S dω of a fiber model over a grid of incident angles (white furnace).
    Furnace(commands::furnace::Args),
    /// Hair grooms: describe a .hair file (info) or write a procedural one (make).
    Groom(commands::groom::Args),
    /// Monte Carlo ground truth of a rough fiber: lobe images, azimuthal.csv, sim.json.
    Sim(commands::sim::Args),
    /// The ground-truth simulation over a grid of configurations, resumable and shardable.
    Sweep(commands::sweep::Args),
    /// Environment light: fit an environment map with J SRBF lights (fit).
    Env(commands::env::Args),
    /// Render a groom under environment light (Xu et al. 2011's SRBF renderer, or --method brute).
    Render(Box<commands::render::Args>),
    /// The path tracer's scene for pbrt-v4 or Mitsuba 3 (Chiang et al. 2016 hair): the flags of
    /// `render --method path`, written as those renderers load it.
    Export(Box<commands::export::Args>),
    /// Two renders' output folders against each other over the hair: per-channel means, ratio,
    /// relative RMSE, for the whole hair and its bottom fifth (compare.json).
    Compare(commands::compare::Args),
    /// The live look-development window: edit the hair, lighting and camera, paint colour onto
    /// strands.
    View(Box<commands::view::Args>),
    /// Every simulated configuration of a sweep against the models: error tables, plot, sheets.
    Validate(commands::validate::Args),
    /// Benchmarks: the renderer on the paper's workload (render).
    #[command(subcommand)]
    Bench(commands::render::Bench),
}

fn main() {
    die_quietly_on_a_closed_pipe();
    quiet_vulkan_device_select();
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Lobes(args) => commands::lobes::run(args),
        Command::Furnace(args) => commands::furnace::run(args),
        Command::Groom(args) => commands::groom::run(args),
        Command::Sim(args) => commands::sim::run(args),
        Command::Sweep(args) => commands::sweep::run(args),
        Command::Env(args) => commands::env::run(args),
        Command::Render(args) => commands::render::run(*args),
        Command::Export(args) => commands::export::run(*args),
        Command::Validate(args) => commands::validate::run(args),
        Command::Compare(args) => commands::compare::run(args),
        Command::View(args) => commands::view::run(*args),
        Command::Bench(command) => commands::render::bench(command),
    };
    if let Err(err) = result {
        eprintln!("error: {}", one_line(&err));
        std::process::exit(1);
    }
}

/// `cuticle compare A B | head -1` closes the pipe before the summary is written: Rust ignores
/// SIGPIPE, so `println!` then panics on the broken pipe. Like every Unix filter, end instead,
/// silently, by the signal's default action (exit status 128 + SIGPIPE to the shell).
fn die_quietly_on_a_closed_pipe() {
    // SAFETY: called first in `main`, before any thread starts; it only restores the signal's
    // default disposition.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}

/// The error and its causes on one line, each cause once: a message that already quotes its
/// cause (as `#[error("…: {source}")]` does) does not repeat it, and a cause spread over lines
/// (a parser's excerpt) is joined.
fn one_line(err: &anyhow::Error) -> String {
    let mut line = String::new();
    for cause in err.chain() {
        let text = cause
            .to_string()
            .lines()
            .map(str::trim)
            .filter(|l| !l.is_empty())
            .collect::<Vec<_>>()
            .join("; ");
        if text.is_empty() || line.contains(&text) {
            continue;
        }
        if !line.is_empty() {
            line.push_str(": ");
        }
        line.push_str(&text);
    }
    line
}

/// Mesa's implicit Vulkan layer `VK_LAYER_MESA_device_select` connects to a display server to
/// order the adapters and, on a headless machine (no XDG_RUNTIME_DIR), prints "error:
/// XDG_RUNTIME_DIR is invalid" whenever a GPU is probed. The device is chosen by its type here,
/// not by that layer, so it is switched off unless the user asked for it.
fn quiet_vulkan_device_select() {
    if std::env::var_os("XDG_RUNTIME_DIR").is_none()
        && std::env::var_os("NODEVICE_SELECT").is_none()
    {
        // SAFETY: called first thing in main, before any thread exists.
        unsafe { std::env::set_var("NODEVICE_SELECT", "1") };
    }
}
