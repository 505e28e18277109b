//! `import cuticle`: the project's science on NumPy arrays (issue 55). The pipeline, one room
//! per module, each a thin layer over the library the command line uses, so a call gives the
//! command's numbers:
//! - [`arrays`]: NumPy arguments checked (shapes, unit directions, uniform numbers) and
//!   results built; [`rgb`]: one-or-three-number arguments; [`errors`]: a bad value is a
//!   `ValueError` with the command line's message;
//! - [`fiber`]: `cuticle.Fiber`, a model of the fiber crate's registry: `eval`, `lobes`,
//!   `pdf`, `sample` and `latlong` (`cuticle lobes`);
//! - [`sim`]: `cuticle.simulate` (`cuticle sim`);
//! - [`scene`]: `cuticle.load_groom`, `cuticle.render` (`cuticle render`) and
//!   `cuticle.fit_env` (`cuticle env fit`);
//! - [`files`]: `cuticle.read_exr`, the command line's EXRs read back.
//!
//! The work runs with the GIL released, on rayon's global pool (all cores).

mod arrays;
mod errors;
mod fiber;
mod files;
mod rgb;
mod scene;
mod sim;

use cuticle_fiber::ModelId;
use cuticle_fiber::ranges::{self, CountRange, Range};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Every range the bindings check, by parameter name, as the command line prints it (e.g.
/// "(1, 10]"): the fiber crate's (`cuticle_fiber::ranges`) and the simulator's.
fn ranges_dict(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let dict = PyDict::new(py);
    let reals: [Range; 6] = [
        ranges::ETA,
        ranges::BETA,
        ranges::ALPHA_DEG,
        ranges::MU_A,
        ranges::MELANIN,
        ranges::THETA_I,
    ];
    for r in reals {
        dict.set_item(r.name, r.to_string())?;
    }
    let counts: [CountRange; 3] = [
        ranges::ITERATIONS,
        cuticle_sim::params::RAYS,
        cuticle_validate::pixel_integral::LOBE_WIDTH,
    ];
    for r in counts {
        dict.set_item(r.name, r.to_string())?;
    }
    Ok(dict)
}

/// Physically based hair: cuticle's fiber models, its Monte Carlo simulator and its renderers
/// on NumPy arrays. `help(cuticle.Fiber)` to start; MODELS lists the models, RANGES every
/// parameter's range.
#[pymodule(name = "cuticle")]
fn cuticle_module(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<fiber::Fiber>()?;
    m.add_function(wrap_pyfunction!(sim::simulate, m)?)?;
    m.add_function(wrap_pyfunction!(files::read_exr, m)?)?;
    m.add_function(wrap_pyfunction!(scene::render, m)?)?;
    m.add_function(wrap_pyfunction!(scene::load_groom, m)?)?;
    m.add_function(wrap_pyfunction!(scene::fit_env, m)?)?;
    m.add("MODELS", ModelId::names().to_vec())?;
    m.add("RANGES", ranges_dict(m.py())?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
