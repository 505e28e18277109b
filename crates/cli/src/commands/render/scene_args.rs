//! The scene flags `render`, `view` and `export` share, laid over a scene file
//! ([`cuticle_render::scene::overrides::SceneOverrides`]), and the lights file `--lights` reads.

use anyhow::{Context, Result};
use cuticle_light::SrbfLight;
use cuticle_render::scene::overrides::SceneOverrides;
use cuticle_render::{Scene, SceneSpec};
use serde_json::Value;
use std::path::{Path, PathBuf};

/// The scene flags `render` and `view` share.
#[derive(clap::Args, Clone, Debug)]
pub struct SceneArgs {
    /// A TOML scene file (keys as in SceneSpec); flags override it.
    #[arg(long)]
    scene: Option<PathBuf>,
    /// A groom preset (straight, wavy, curly), a .hair file or a USD groom (.usda, .usdc, .usdz).
    #[arg(long)]
    groom: Option<String>,
    /// Strands of a preset groom.
    #[arg(long)]
    strands: Option<usize>,
    /// `default` (procedural sky), `constant:R,G,B` (uniform) or an .hdr/.exr lat-long map.
    #[arg(long)]
    env: Option<String>,
    /// Number J of SRBF lights to fit, or a lights.json from `cuticle env fit`.
    #[arg(long)]
    lights: Option<String>,
    /// srbf (Xu et al. 2011), brute (exact model, 6 n² directional lights) or path (the path
    /// tracer, flags --spp, --seed, --max-depth, --model and the fiber flags).
    #[arg(long, value_parser = ["srbf", "brute", "path"])]
    method: Option<String>,
    /// Segments m of the linear quadrature.
    #[arg(long)]
    quadrature: Option<usize>,
    /// Single scattering only.
    #[arg(long)]
    no_multiple: bool,
    #[arg(long)]
    width: Option<usize>,
    #[arg(long)]
    height: Option<usize>,
    /// Subsamples per pixel along each axis.
    #[arg(long)]
    supersampling: Option<usize>,
    /// n of the brute force's 6 n² lights.
    #[arg(long)]
    brute_grid: Option<usize>,
    /// Index of refraction η.
    #[arg(long, allow_negative_numbers = true)]
    eta: Option<f64>,
    /// Longitudinal shift α_R, degrees.
    #[arg(long, allow_negative_numbers = true)]
    alpha_r_deg: Option<f64>,
    /// Longitudinal width β_R, degrees.
    #[arg(long, allow_negative_numbers = true)]
    beta_r_deg: Option<f64>,
    /// Absorption μ_a per unit radius for every strand: one value or r,g,b.
    #[arg(long, allow_negative_numbers = true)]
    mu_a: Option<String>,
    /// Eccentricity a.
    #[arg(long, allow_negative_numbers = true)]
    eccentricity: Option<f64>,
    /// TRT caustic width w_c, degrees.
    #[arg(long, allow_negative_numbers = true)]
    caustic_width_deg: Option<f64>,
}

impl SceneArgs {
    /// The `--method` given, if any.
    pub(crate) fn method(&self) -> Option<&str> {
        self.method.as_deref()
    }

    /// The `--lights` given (a count or a file), if any.
    pub(crate) fn lights(&self) -> Option<&str> {
        self.lights.as_deref()
    }
}

/// The scene file (if any) with the flags laid over it ([`SceneOverrides`]), and lights read
/// from a file.
pub fn spec_from(args: &SceneArgs) -> Result<(SceneSpec, Option<Vec<SrbfLight>>)> {
    let spec = match &args.scene {
        Some(path) => SceneSpec::from_toml_file(path)?,
        None => SceneSpec::default(),
    };
    let (lights, light_file) = match &args.lights {
        None => (None, None),
        Some(s) => match s.parse::<usize>() {
            Ok(n) => (Some(n), None),
            Err(_) => (None, Some(read_lights(Path::new(s))?)),
        },
    };
    let overrides = SceneOverrides {
        groom: args.groom.clone(),
        strands: args.strands,
        env: args.env.clone(),
        lights,
        method: args
            .method
            .as_deref()
            .map(str::parse)
            .transpose()
            .map_err(anyhow::Error::msg)?,
        quadrature: args.quadrature,
        multiple: args.no_multiple.then_some(false),
        width: args.width,
        height: args.height,
        supersampling: args.supersampling,
        brute_grid: args.brute_grid,
        eta: args.eta,
        alpha_r_deg: args.alpha_r_deg,
        beta_r_deg: args.beta_r_deg,
        mu_a: args.mu_a.as_deref().map(parse_rgb).transpose()?,
        eccentricity: args.eccentricity,
        caustic_width_deg: args.caustic_width_deg,
    };
    Ok((overrides.apply(spec), light_file))
}

fn parse_rgb(s: &str) -> Result<[f64; 3]> {
    let v: Vec<f64> = s
        .split(',')
        .map(|x| x.trim().parse::<f64>())
        .collect::<std::result::Result<_, _>>()
        .with_context(|| format!("--mu-a takes one number or r,g,b, got {s}"))?;
    match v.as_slice() {
        [x] => Ok([*x; 3]),
        [r, g, b] => Ok([*r, *g, *b]),
        _ => anyhow::bail!("--mu-a takes one number or r,g,b, got {s}"),
    }
}

/// The largest lights file read (512 lights take under 200 kB).
const MAX_LIGHTS_FILE: u64 = 4 << 20;

/// The `"lights"` array of a lights.json written by `cuticle env fit`, each light checked.
fn read_lights(path: &Path) -> Result<Vec<SrbfLight>> {
    let size = std::fs::metadata(path)
        .with_context(|| format!("cannot read {}", path.display()))?
        .len();
    if size > MAX_LIGHTS_FILE {
        anyhow::bail!(
            "{} is {size} bytes, more than a lights file of {} lights takes",
            path.display(),
            cuticle_light::MAX_LIGHTS
        );
    }
    let text = cuticle_light::file::read_regular_text(path, MAX_LIGHTS_FILE)
        .with_context(|| format!("cannot read {}", path.display()))?;
    let value: Value =
        serde_json::from_str(&text).with_context(|| format!("{} is not JSON", path.display()))?;
    let lights = value
        .get("lights")
        .cloned()
        .with_context(|| format!("{} has no \"lights\" array", path.display()))?;
    let lights: Vec<SrbfLight> = serde_json::from_value(lights)
        .with_context(|| format!("{}: \"lights\" is not a list of lights", path.display()))?;
    cuticle_light::validate_lights(&lights).with_context(|| path.display().to_string())?;
    Ok(lights)
}

/// The scene, loaded once what it needs in memory is known to fit
/// ([`cuticle_render::scene::headroom::load_within_memory`]).
pub fn load_within_memory(spec: SceneSpec, lights: Option<Vec<SrbfLight>>) -> Result<Scene> {
    Ok(cuticle_render::scene::headroom::load_within_memory(
        spec, lights,
    )?)
}
