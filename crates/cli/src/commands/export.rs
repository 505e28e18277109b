//! `cuticle export --format pbrt|mitsuba`: the scene `render --method path --model chiang2016`
//! renders (same flags, same scene loading), written for pbrt-v4 or Mitsuba 3 by the crate
//! cuticle-export, as one set with `export.json` (the scene's parameters, the hair's, and what
//! was written).

use crate::commands::render::path::PathArgs;
use crate::commands::render::{SceneArgs, spec_from};
use crate::output::OutDir;
use anyhow::{Result, bail};
use cuticle_export::{Absorption, ChiangHair, Format, HairLook, RenderSettings};
use cuticle_fiber::ModelId;
use cuticle_render::Method;
use serde_json::json;
use std::path::PathBuf;

#[derive(clap::Args, Clone, Debug)]
pub struct Args {
    /// pbrt (pbrt-v4: scene.pbrt) or mitsuba (Mitsuba 3: scene.xml).
    #[arg(long, value_parser = ["pbrt", "mitsuba"])]
    format: String,
    #[command(flatten)]
    scene: SceneArgs,
    #[command(flatten)]
    path: PathArgs,
    /// Output folder.
    #[arg(long, default_value = "out/export")]
    out: PathBuf,
}

pub fn run(args: Args) -> Result<()> {
    let format = match args.format.as_str() {
        "pbrt" => Format::Pbrt,
        _ => Format::Mitsuba,
    };
    if args.scene.lights().is_some() {
        bail!("--lights is for --method srbf and brute; export writes the environment map itself");
    }
    let (mut spec, _) = spec_from(&args.scene)?;
    if let Some(method) = args.scene.method().filter(|m| *m != "path") {
        bail!("export writes the path tracer's scene; --method {method} does not apply");
    }
    spec.method = Method::Path;
    if !spec.multiple {
        bail!(
            "--no-multiple (scene key multiple = false) is not exported: pbrt-v4 and Mitsuba 3 trace every order"
        );
    }
    if args.path.model != ModelId::Chiang2016 {
        bail!(
            "export writes Chiang et al. 2016 hair, the model pbrt-v4 and Mitsuba 3 ship: give \
             --model chiang2016 (not {})",
            args.path.model.name()
        );
    }
    let options = args.path.options()?;
    args.path.check(&spec)?;
    let (fiber, beta_n) = args.path.chiang(&spec)?;
    let scene = crate::commands::render::path::load(spec)?;
    let look = HairLook {
        fiber: ChiangHair {
            beta_m: fiber.beta,
            beta_n,
            alpha_deg: fiber.alpha.to_degrees(),
            eta: fiber.eta,
        },
        // `--model chiang2016` gives every strand the scene's one absorption.
        sigma_a: Absorption::Uniform(fiber.mu_a),
    };
    let settings = RenderSettings {
        spp: options.spp,
        seed: options.seed,
        max_depth: options.path.max_depth,
    };
    let mut out = OutDir::create(&args.out, "export")?;
    let export = cuticle_export::export(&scene, &look, &settings, format)?;
    for file in &export.files {
        out.write(&file.name, &file.bytes)?;
    }
    let s = &export.summary;
    out.finish(json!({
        "params": serde_json::to_value(&scene.spec)?,
        "format": format,
        "path": args.path.json(&scene)?,
        "camera": scene.camera,
        "export": s,
    }))?;
    println!(
        "{}: {} for {} ({} strands, {} control points, {} material(s); environment {}x{}){}",
        args.out.display(),
        s.scene_file,
        match format {
            Format::Pbrt => "pbrt-v4",
            Format::Mitsuba => "Mitsuba 3",
        },
        s.strands,
        s.points,
        s.materials,
        s.env_width,
        s.env_height,
        if s.skipped_strands > 0 {
            format!("; {} strands of one point left out", s.skipped_strands)
        } else {
            String::new()
        }
    );
    Ok(())
}
