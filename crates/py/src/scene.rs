//! Grooms, light and rendering: `cuticle.load_groom`, `cuticle.render` and `cuticle.fit_env`,
//! through the library calls `cuticle render` and `cuticle env fit` make (the scene's
//! [`SceneOverrides`] over its defaults or a TOML file, loaded within the memory available,
//! rendered on the CPU), so a render gives the command's pixels.

use crate::arrays::{f32_channels, rgb_image};
use crate::errors::{error_line, value_error};
use crate::rgb::rgb_argument;
use cuticle_fiber::ranges::CountRange;
use cuticle_light::{FitOptions, fit_srbf, load_or_default};
use cuticle_render::scene::headroom::load_within_memory;
use cuticle_render::scene::overrides::SceneOverrides;
use cuticle_render::scene::{Method, STRANDS, load_groom as load};
use cuticle_render::{Image, Renderer, SceneSpec};
use cuticle_trace::{StrandModels, TraceOptions};
use numpy::ndarray::Array;
use numpy::{IntoPyArray, PyArray1, PyArray3};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;
use std::sync::OnceLock;

/// The renderer's tables, built once per process (what a `Renderer` holds between frames).
fn renderer() -> &'static Renderer {
    static RENDERER: OnceLock<Renderer> = OnceLock::new();
    RENDERER.get_or_init(Renderer::new)
}

/// A count argument as the scene takes it: a negative one refused with the range's message.
fn count(range: CountRange, value: Option<i64>) -> PyResult<Option<usize>> {
    value
        .map(|v| range.check_signed(v).map(|n| n as usize))
        .transpose()
        .map_err(value_error)
}

/// A non-negative count (the scene checks its range): a negative one refused.
fn size(name: &'static str, value: Option<i64>) -> PyResult<Option<usize>> {
    let any = CountRange {
        name,
        min: 0,
        max: u64::MAX,
    };
    count(any, value)
}

/// Renders a groom under an environment as `cuticle render --device cpu` does, with the
/// same scene keys (defaults: the scene's, or those of the TOML file `scene`; each range the
/// command line's, a value outside raising ValueError with its message).
///
/// groom: a preset ("straight", "wavy", "curly") or a .hair file.
/// env: "default" (the procedural sky), "constant:R,G,B", or an .hdr/.exr lat-long map.
/// method: "srbf" (Xu et al. 2011), "brute" (exact model, 6 n² directional lights) or
///     "path" (the path tracer, with the scene's Marschner 2003 hair: `--model marschner`).
/// width, height: the image in pixels; supersampling: subsamples per pixel along each axis.
/// strands: strands of a preset groom; lights: the number J of SRBF lights to fit.
/// quadrature: segments m of the linear quadrature; multiple: dual scattering on or off;
/// brute_grid: n of the brute force's 6 n² lights.
/// spp, seed, max_depth: the path tracer's samples per pixel (1..=1048576), seed and most
///     scattering events of a path (1..=100000); method "path" only.
/// eta, alpha_r_deg (degrees), beta_r_deg (degrees), mu_a (one number or (r, g, b), per
///     unit radius), eccentricity, caustic_width_deg (degrees): the hair (Marschner 2003).
///
/// Returns the linear radiance as a float32 array of shape (height, width, 3): the pixels
/// of the command's image.exr.
#[pyfunction]
#[pyo3(signature = (
    *, groom = None, env = None, method = None, width = None, height = None,
    supersampling = None, strands = None, lights = None, quadrature = None, multiple = None,
    brute_grid = None, spp = None, seed = None, max_depth = None, eta = None,
    alpha_r_deg = None, beta_r_deg = None, mu_a = None, eccentricity = None,
    caustic_width_deg = None, scene = None,
))]
#[allow(clippy::too_many_arguments)]
pub fn render<'py>(
    py: Python<'py>,
    groom: Option<String>,
    env: Option<String>,
    method: Option<String>,
    width: Option<i64>,
    height: Option<i64>,
    supersampling: Option<i64>,
    strands: Option<i64>,
    lights: Option<i64>,
    quadrature: Option<i64>,
    multiple: Option<bool>,
    brute_grid: Option<i64>,
    spp: Option<i64>,
    seed: Option<u64>,
    max_depth: Option<i64>,
    eta: Option<f64>,
    alpha_r_deg: Option<f64>,
    beta_r_deg: Option<f64>,
    mu_a: Option<&Bound<'py, PyAny>>,
    eccentricity: Option<f64>,
    caustic_width_deg: Option<f64>,
    scene: Option<PathBuf>,
) -> PyResult<Bound<'py, PyArray3<f32>>> {
    let method = method
        .map(|m| m.parse::<Method>())
        .transpose()
        .map_err(value_error)?;
    let overrides = SceneOverrides {
        groom,
        strands: size("strands", strands)?,
        env,
        lights: size("lights", lights)?,
        method,
        quadrature: size("quadrature", quadrature)?,
        multiple,
        width: size("width", width)?,
        height: size("height", height)?,
        supersampling: size("supersampling", supersampling)?,
        brute_grid: size("brute_grid", brute_grid)?,
        eta,
        alpha_r_deg,
        beta_r_deg,
        mu_a: mu_a.map(|v| rgb_argument("mu_a", v)).transpose()?,
        eccentricity,
        caustic_width_deg,
    };
    let defaults = TraceOptions::default();
    let path = PathRequest {
        given: spp.is_some() || seed.is_some() || max_depth.is_some(),
        spp: size("spp", spp)?.map_or(defaults.spp.into(), |n| n as u64),
        seed: seed.unwrap_or(defaults.seed),
        max_depth: size("max_depth", max_depth)?
            .map_or(defaults.path.max_depth.into(), |n| n as u64),
    };
    let image = py.detach(|| render_scene(scene.as_deref(), &overrides, &path));
    let image = image.map_err(value_error)?;
    Ok(rgb_image(
        py,
        image.width,
        image.height,
        &image.pixels,
        f32_channels,
    ))
}

/// The path tracer's arguments of [`render`], checked once the method is known.
struct PathRequest {
    given: bool,
    spp: u64,
    seed: u64,
    max_depth: u64,
}

/// The scene (a TOML file's or the defaults, `overrides` laid over it) rendered as
/// `cuticle render --device cpu` renders it.
fn render_scene(
    file: Option<&std::path::Path>,
    overrides: &SceneOverrides,
    path: &PathRequest,
) -> Result<Image, String> {
    let spec = match file {
        Some(f) => SceneSpec::from_toml_file(f).map_err(|e| error_line(&e))?,
        None => SceneSpec::default(),
    };
    let spec = overrides.apply(spec);
    if spec.method != Method::Path {
        if path.given {
            return Err("spp, seed and max_depth are for method path".into());
        }
        let scene = load_within_memory(spec, None).map_err(|e| error_line(&e))?;
        let (image, _, _) = renderer().render(&scene);
        image.check_finite("an image").map_err(|e| error_line(&e))?;
        return Ok(image);
    }
    if !spec.multiple {
        return Err(
            "multiple = False is for methods srbf and brute; the path tracer's single \
                    scattering is max_depth = 1"
                .into(),
        );
    }
    let options =
        TraceOptions::checked(path.spp, path.seed, path.max_depth).map_err(|e| error_line(&e))?;
    let scene = load_within_memory(spec, None).map_err(|e| error_line(&e))?;
    let models = StrandModels::marschner(&scene)
        .map_err(|e| format!("Marschner 2003 parameters: {}", error_line(&e)))?;
    let traced = cuticle_trace::render(&scene, &models, &options, &|_, _| {});
    traced
        .image
        .check_finite("an image")
        .map_err(|e| error_line(&e))?;
    Ok(traced.image)
}

/// A groom as the renderer loads it: a preset ("straight", "wavy", "curly", with `strands`
/// strands) or a .hair file. Returns a dict: "strands" (the count), "points" (float32 array of
/// shape (P, 3), every strand's points one after another, world units, +z up),
/// "offsets" (int64 array of shape (strands + 1,): strand s is points[offsets[s]:offsets[s+1]]),
/// "thickness" (float32 (P,)).
#[pyfunction]
#[pyo3(signature = (groom, strands = None))]
pub fn load_groom<'py>(
    py: Python<'py>,
    groom: String,
    strands: Option<i64>,
) -> PyResult<Bound<'py, PyDict>> {
    let strands = count(STRANDS, strands)?.unwrap_or(SceneSpec::default().strands);
    let loaded = py
        .detach(|| load(&groom, strands))
        .map_err(|e| value_error(error_line(&e)))?;
    let dict = PyDict::new(py);
    let points: Vec<f32> = loaded
        .positions()
        .iter()
        .flat_map(|p| p.to_array())
        .collect();
    let offsets: Vec<i64> = loaded.strand_offsets().iter().map(|&o| o.into()).collect();
    dict.set_item("strands", loaded.strand_count())?;
    let points = Array::from_shape_vec((points.len() / 3, 3), points).expect("3 a point");
    dict.set_item("points", points.into_pyarray(py))?;
    dict.set_item("offsets", PyArray1::from_vec(py, offsets))?;
    dict.set_item("thickness", PyArray1::from_slice(py, loaded.thickness()))?;
    Ok(dict)
}

/// Fits `lights` SRBF lights (Xu et al. 2011 §4.1) to an environment ("default", the
/// procedural sky, or an .hdr/.exr lat-long map), as `cuticle env fit` does. Returns a dict:
/// "directions" (float32 (J, 3), unit centres, +y up), "bandwidths" (float32 (J,)),
/// "coefficients" (float32 (J, 3), RGB radiance at each centre), "relative_l2" (the fit's
/// relative L2 error on the full map).
#[pyfunction]
#[pyo3(signature = (env, lights = FitOptions::default().lights as i64))]
pub fn fit_env<'py>(py: Python<'py>, env: String, lights: i64) -> PyResult<Bound<'py, PyDict>> {
    let options = FitOptions {
        lights: size("lights", Some(lights))?.unwrap_or_default(),
        ..FitOptions::default()
    };
    let report = py
        .detach(|| load_or_default(&env).and_then(|map| fit_srbf(&map, &options)))
        .map_err(|e| value_error(error_line(&e)))?;
    let dict = PyDict::new(py);
    let column = |f: &dyn Fn(&cuticle_light::SrbfLight) -> Vec<f32>| -> Vec<f32> {
        report.lights.iter().flat_map(f).collect()
    };
    let directions = column(&|l| l.direction.to_array().to_vec());
    let coefficients = column(&|l| l.coefficient.to_array().to_vec());
    let n = report.lights.len();
    dict.set_item(
        "directions",
        Array::from_shape_vec((n, 3), directions)
            .expect("3 a light")
            .into_pyarray(py),
    )?;
    dict.set_item(
        "bandwidths",
        PyArray1::from_vec(py, column(&|l| vec![l.bandwidth])),
    )?;
    dict.set_item(
        "coefficients",
        Array::from_shape_vec((n, 3), coefficients)
            .expect("3 a light")
            .into_pyarray(py),
    )?;
    dict.set_item("relative_l2", report.relative_l2)?;
    Ok(dict)
}
