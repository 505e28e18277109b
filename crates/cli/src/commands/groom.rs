//! `cuticle groom`: look inside `.hair` and USD groom files (`info`) and write procedural grooms
//! (`make`), as a `.hair` folder set or one USD file.

use crate::output::OutDir;
use anyhow::{Context, Result};
use cuticle_groom::procedural::{GroomParams, Preset, generate};
use cuticle_groom::summary::{HairFileSummary, Stats};
use cuticle_groom::usd::{UsdFormat, to_usd_bytes};
use cuticle_groom::{Groom, GroomFormat, HairFile};
use cuticle_render::scene::STRANDS;
use cuticle_render::scene::memory::{Advice, MemoryNeed};
use serde_json::json;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

#[derive(clap::Args)]
pub struct Args {
    #[command(subcommand)]
    command: GroomCommand,
}

#[derive(clap::Subcommand)]
enum GroomCommand {
    /// Counts, bounds, strand lengths and arrays of a .hair or USD (.usda/.usdc/.usdz) groom.
    Info(InfoArgs),
    /// Generate a procedural groom and write it as a .hair file (with a JSON record beside it),
    /// or as one USD file (BasisCurves) when --out ends in .usda.
    Make(MakeArgs),
}

#[derive(clap::Args)]
struct InfoArgs {
    /// The groom file to describe (.hair, .usda, .usdc, .usdz).
    file: PathBuf,
    /// Print the summary as JSON on stdout instead of text.
    #[arg(long)]
    json: bool,
}

#[derive(clap::Args)]
struct MakeArgs {
    /// Hairstyle: straight (the built-in scene groom), wavy or curly.
    #[arg(long, default_value_t = Preset::default())]
    preset: Preset,
    /// Number of strands [default: the preset's, 10000].
    #[arg(long)]
    strands: Option<usize>,
    /// Random seed [default: the preset's, 1].
    #[arg(long)]
    seed: Option<u64>,
    /// Output folder: `groom.hair` and `groom.json` (the parameters), written as one set; or a
    /// file FILE.usda: the groom as USD BasisCurves, written whole (.usdc is refused: openusd
    /// 0.6's binary files do not open in Pixar's USD).
    #[arg(long)]
    out: PathBuf,
}

pub fn run(args: Args) -> Result<()> {
    match args.command {
        GroomCommand::Info(args) => info(&args),
        GroomCommand::Make(args) => make(&args),
    }
}

fn info(args: &InfoArgs) -> Result<()> {
    let context = || format!("cannot read {}", args.file.display());
    let file = match GroomFormat::of(&args.file) {
        GroomFormat::Hair => HairFile::read(&args.file).with_context(context)?,
        // A USD groom is described as the .hair file that would hold it.
        GroomFormat::Usd => {
            let groom = Groom::read(&args.file).with_context(context)?;
            HairFile::from_groom(&groom, "read from USD").with_context(context)?
        }
    };
    let summary = HairFileSummary::of(&file);
    let text = if args.json {
        let mut value = serde_json::to_value(&summary)?;
        value["file"] = json!(args.file.display().to_string());
        serde_json::to_string_pretty(&value)?
    } else {
        describe(&args.file, &summary)
    };
    writeln!(std::io::stdout(), "{text}")?;
    Ok(())
}

/// The groom file `make` writes into its folder.
pub const HAIR_FILE: &str = "groom.hair";

/// Bytes per point of a groom being made and encoded: the grown strands, the groom's arrays
/// and the `.hair` bytes.
const MAKE_BYTES_PER_POINT: u64 = 80;

fn make(args: &MakeArgs) -> Result<()> {
    let params = make_params(args);
    STRANDS.check_usize(params.strands)?;
    let points = (params.strands as u64).saturating_mul(params.max_points as u64);
    MemoryNeed {
        parts: vec![("the groom", points.saturating_mul(MAKE_BYTES_PER_POINT))],
    }
    .check_for(
        cuticle_render::scene::headroom::available(),
        Advice {
            what: "groom",
            lower: "lower --strands",
        },
    )?;
    if let Some(format) = usd_out(&args.out)? {
        return make_usd(args, &params, format);
    }
    let mut out = OutDir::create(&args.out, "groom")?;
    let start = Instant::now();
    let groom = generate(&params)?;
    let bytes = groom.to_hair_bytes(&format!("cuticle groom make --preset {}", args.preset))?;
    let seconds = start.elapsed().as_secs_f64();
    let hair = out.write(HAIR_FILE, &bytes)?;
    let record = json!({
        "params": { "preset": args.preset.name(), "groom": params },
        "strands": groom.strand_count(),
        "points": groom.point_count(),
        "bytes": bytes.len(),
        "seconds": seconds,
    });
    let record_path = out.finish(record)?;
    println!(
        "wrote {}: {} strands, {} points ({} preset, seed {}) in {:.3} s; parameters in {}",
        hair.display(),
        groom.strand_count(),
        groom.point_count(),
        args.preset,
        params.seed,
        seconds,
        record_path.display()
    );
    Ok(())
}

/// The USD format `--out` names by its extension, if any; `.usdz` is refused here, `.usdc` by
/// the writer.
fn usd_out(out: &Path) -> Result<Option<UsdFormat>> {
    match out.extension().and_then(|e| e.to_str()) {
        Some("usdz") => anyhow::bail!(
            "--out {}: .usdz is not written; name a .usda file",
            out.display()
        ),
        _ => Ok(UsdFormat::of_path(out)),
    }
}

/// `make` into one USD file, written whole (a temporary file renamed over it).
fn make_usd(args: &MakeArgs, params: &GroomParams, format: UsdFormat) -> Result<()> {
    anyhow::ensure!(
        format == UsdFormat::Usda,
        "--out {}: {}",
        args.out.display(),
        cuticle_groom::usd::write::NO_USDC
    );
    let groom = generate(params)?;
    let bytes =
        to_usd_bytes(&groom, format).with_context(|| format!("--out {}", args.out.display()))?;
    crate::output::write_file_atomic(&args.out, &bytes)?;
    println!(
        "wrote {}: {} strands, {} points ({} preset, seed {}) as USD BasisCurves",
        args.out.display(),
        groom.strand_count(),
        groom.point_count(),
        args.preset,
        params.seed
    );
    Ok(())
}

/// The preset's parameters with the strand count and seed the user asked for.
fn make_params(args: &MakeArgs) -> GroomParams {
    let preset = args.preset.params();
    GroomParams {
        strands: args.strands.unwrap_or(preset.strands),
        seed: args.seed.unwrap_or(preset.seed),
        ..preset
    }
}

/// A few lines a person reads: counts, arrays, defaults, bounds, lengths.
fn describe(path: &Path, s: &HairFileSummary) -> String {
    let d = &s.defaults;
    let mut lines = vec![
        format!(
            "{}: {} strands, {} points",
            path.display(),
            s.strands,
            s.points
        ),
        format!("arrays: {} (flags {:#x})", present_arrays(s), s.flags),
        format!(
            "defaults: segments {}, thickness {}, transparency {}, colour ({}, {}, {})",
            d.segments, d.thickness, d.transparency, d.color[0], d.color[1], d.color[2]
        ),
    ];
    if let Some(p) = &s.points_per_strand {
        lines.push(format!("points per strand: {}", stats_line(p)));
    }
    if let Some(b) = &s.bounds {
        let axis = |i: usize| format!("[{:.3}, {:.3}]", b.min[i], b.max[i]);
        lines.push(format!(
            "bounds: x {}  y {}  z {}",
            axis(0),
            axis(1),
            axis(2)
        ));
    }
    if let Some(l) = &s.strand_length {
        lines.push(format!("strand length: {}", stats_line(l)));
    }
    if !s.info.is_empty() {
        lines.push(format!("info: {:?}", s.info));
    }
    lines.join("\n")
}

fn present_arrays(s: &HairFileSummary) -> String {
    let a = &s.arrays;
    let names = [
        (a.segments, "segments"),
        (a.points, "points"),
        (a.thickness, "thickness"),
        (a.transparency, "transparency"),
        (a.colors, "colour"),
    ];
    let present: Vec<&str> = names
        .iter()
        .filter(|(on, _)| *on)
        .map(|(_, n)| *n)
        .collect();
    if present.is_empty() {
        "none".to_string()
    } else {
        present.join(", ")
    }
}

fn stats_line(s: &Stats) -> String {
    format!(
        "min {:.3}, median {:.3}, mean {:.3}, max {:.3}",
        s.min, s.median, s.mean, s.max
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn make_args(dir: &Path, strands: usize, seed: u64) -> MakeArgs {
        MakeArgs {
            preset: Preset::Wavy,
            strands: Some(strands),
            seed: Some(seed),
            out: dir.join("new folder").join("wavy"),
        }
    }

    #[test]
    fn make_writes_the_groom_asked_for_and_its_record() {
        let dir = tempfile::tempdir().unwrap();
        let args = make_args(dir.path(), 120, 9);
        make(&args).unwrap();
        let file = HairFile::read(args.out.join(HAIR_FILE)).unwrap();
        assert_eq!(file.strand_count, 120);
        let expected = generate(&make_params(&args)).unwrap();
        assert_eq!(file.point_count as usize, expected.point_count());
        let record: serde_json::Value =
            serde_json::from_slice(&std::fs::read(args.out.join("groom.json")).unwrap()).unwrap();
        assert_eq!(record["params"]["preset"], "wavy");
        assert_eq!(record["params"]["groom"]["seed"], 9);
        assert_eq!(record["strands"], 120);
    }

    #[test]
    fn info_describes_arrays_and_counts() {
        let dir = tempfile::tempdir().unwrap();
        let args = make_args(dir.path(), 30, 1);
        make(&args).unwrap();
        let path = args.out.join(HAIR_FILE);
        let summary = HairFileSummary::of(&HairFile::read(&path).unwrap());
        let text = describe(&path, &summary);
        assert!(
            text.contains(&format!("30 strands, {} points", summary.points)),
            "{text}"
        );
        assert!(
            text.contains("arrays: segments, points, thickness (flags 0x7)"),
            "{text}"
        );
        assert!(text.contains("strand length: min"), "{text}");
    }

    #[test]
    fn info_on_a_broken_file_says_why() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("junk.hair");
        std::fs::write(&path, b"HAIR but not really").unwrap();
        let err = info(&InfoArgs {
            file: path,
            json: false,
        })
        .unwrap_err();
        let message = format!("{err:#}");
        assert!(
            message.starts_with("cannot read ") && message.contains("128-byte header"),
            "{message}"
        );
    }
}
