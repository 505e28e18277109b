//! `cuticle.simulate`: the Monte Carlo ground truth of a rough fiber (d'Eon et al. 2014 §2.1)
//! through `cuticle_sim::simulate`, the function `cuticle sim` calls, on the same
//! [`SimParams`] (defaults and ranges its own), so a seed gives the command's images.

use crate::arrays::{f64_channels, rgb_image};
use crate::errors::value_error;
use crate::fiber::rgb;
use crate::rgb::rgb_argument;
use cuticle_fiber::LatLongImage;
use cuticle_sim::{LOBE_NAMES, SimParams, SimResult, simulate as run_simulation};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Traces `rays` paths of light arriving at inclination `theta_i` through a rough fiber, as
/// `cuticle sim` does (same defaults and ranges; a seed gives the same images on any number
/// of threads).
///
/// theta_i: incident inclination θ_i, radians, in (-π/2, π/2) (φ_i = 0).
/// alpha_deg: scale tilt α, degrees, in [-20, 20] (positive tilts the surface normal toward
///     +x, the fiber tangent).
/// beta: Beckmann roughness β, in [0.0001, 1].
/// eta: relative index of refraction η, in (1, 10].
/// mu_a: interior absorption per unit radius, one number or (r, g, b), each in [0, 1000].
/// rays: paths to trace, in 1..=1000000000 (about 10 million per second per core).
/// seed: the random seed.
///
/// Returns a dict: "R", "TT", "TRT", "TRRT", "rest", "total" → S in sr⁻¹ as float64 arrays of
/// shape (100, 400, 3) (docs/conventions.md §4; `cuticle sim`'s EXRs hold them rounded to
/// float32); "energy" → dict of each lobe's and the "total" ∫ S dω (RGB, shape (3,));
/// "lost" → dict "shadowing", "backfacing", "cutoff" (RGB fractions of the intercepted
/// power); "absorbed" (RGB); "rays"; "seconds".
#[pyfunction]
#[pyo3(signature = (
    *,
    theta_i = SimParams::default().theta_i,
    alpha_deg = SimParams::default().alpha.to_degrees(),
    beta = SimParams::default().beta,
    eta = SimParams::default().eta,
    mu_a = None,
    rays = SimParams::default().rays as i64,
    seed = SimParams::default().seed,
))]
#[allow(clippy::too_many_arguments)]
pub fn simulate<'py>(
    py: Python<'py>,
    theta_i: f64,
    alpha_deg: f64,
    beta: f64,
    eta: f64,
    mu_a: Option<&Bound<'py, PyAny>>,
    rays: i64,
    seed: u64,
) -> PyResult<Bound<'py, PyDict>> {
    let rays = cuticle_sim::params::RAYS
        .check_signed(rays)
        .map_err(value_error)?;
    let params = SimParams {
        theta_i,
        alpha: alpha_deg.to_radians(),
        beta,
        eta,
        mu_a: match mu_a {
            Some(v) => rgb_argument("mu_a", v)?,
            None => SimParams::default().mu_a,
        },
        rays,
        seed,
        ..SimParams::default()
    };
    params.validate().map_err(value_error)?;
    let result = py
        .detach(|| run_simulation(&params, &|_, _| {}))
        .map_err(value_error)?;
    result_dict(py, &result)
}

fn result_dict<'py>(py: Python<'py>, r: &SimResult) -> PyResult<Bound<'py, PyDict>> {
    let dict = PyDict::new(py);
    let image = |img: &LatLongImage| {
        rgb_image(
            py,
            img.grid.width,
            img.grid.height,
            &img.pixels,
            f64_channels,
        )
    };
    let energy = PyDict::new(py);
    for ((name, lobe), e) in LOBE_NAMES.iter().zip(&r.lobes).zip(&r.energy) {
        dict.set_item(*name, image(lobe))?;
        energy.set_item(*name, rgb(py, *e))?;
    }
    dict.set_item("total", image(&r.total()))?;
    energy.set_item("total", rgb(py, r.albedo()))?;
    dict.set_item("energy", energy)?;
    let lost = PyDict::new(py);
    lost.set_item("shadowing", rgb(py, r.lost_shadowing))?;
    lost.set_item("backfacing", rgb(py, r.lost_backfacing))?;
    lost.set_item("cutoff", rgb(py, r.lost_cutoff))?;
    dict.set_item("lost", lost)?;
    dict.set_item("absorbed", rgb(py, r.absorbed()))?;
    dict.set_item("rays", r.rays)?;
    dict.set_item("seconds", r.seconds)?;
    Ok(dict)
}
