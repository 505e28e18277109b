//! `cuticle.Fiber`: one model of the fiber crate's registry ([`ModelId`]) for one fiber,
//! checked by [`ModelSpec::build`] (the command line's check), evaluated, sampled and drawn as
//! lat-long images on NumPy arrays. Each call copies its arrays, releases the GIL and works
//! on rayon's pool (all cores).

use crate::arrays::{
    Directions, Floats, broadcast, f64_channels, matrix, par_rows, rgb_image, uniforms,
};
use crate::errors::value_error;
use crate::rgb::rgb_argument;
use cuticle_fiber::furnace::{self, FurnaceRule};
use cuticle_fiber::lobe::LobeValues;
use cuticle_fiber::models::nonseparable::DEFAULT_ITERATIONS;
use cuticle_fiber::params::DEFAULT_ALPHA_DEG;
use cuticle_fiber::ranges;
use cuticle_fiber::spec::absorption;
use cuticle_fiber::{BuildOptions, FiberModel, FiberParams, Lobe, ModelId, ModelSpec, Tabulation};
use cuticle_validate::pixel_integral::{LOBE_WIDTH, lobe_grid, lobe_images, total};
use glam::DVec3;
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// A hair fiber's scattering function S (sr⁻¹; ∫ S dω_o is the albedo) under one model.
///
/// Fiber(model="nonseparable", *, beta=0.04, alpha_deg=-2.0, eta=1.55, mu_a=None,
///       eumelanin=None, pheomelanin=None, iterations=6, tabulated=True)
///
/// model: "nonseparable" (this project's non-separable model with tilted, rough scales),
///     "nonseparable-paper" (d'Eon et al. 2014 as published), "deon2011", "marschner",
///     "chiang2016" (cuticle.MODELS lists them).
/// beta: longitudinal roughness β (Beckmann, as the simulator uses it), radians,
///     in [0.0001, 1].
/// alpha_deg: scale tilt α, degrees, in [-20, 20] (human hair: about -2 to -4).
/// eta: relative index of refraction η, in (1, 10].
/// mu_a: interior absorption per unit radius, one number or (r, g, b), each in [0, 1000];
///     default (0.12, 0.25, 0.5).
/// eumelanin, pheomelanin: melanin concentrations in [0, 50] instead of mu_a
///     (d'Eon et al. 2011's coefficients); give mu_a or melanin, not both.
/// iterations: fixed-point iterations per sample of the non-separable models, in 1..=1000.
/// tabulated: read the tables built once for these parameters (fast; what renderers use), or
///     integrate at every call (the reference the tables are measured against).
///
/// The ranges are the command line's (cuticle.RANGES); a value outside raises ValueError with
/// the command line's message.
///
/// Directions are float arrays of shape (N, 3), or (3,) for one direction shared by every row,
/// in the fiber frame of docs/conventions.md: x = sin θ along the fiber, φ = atan2(z, y);
/// wi points toward the light, wo toward the viewer. Each must be a unit vector (within 1e-5).
#[pyclass(frozen, module = "cuticle")]
pub struct Fiber {
    spec: ModelSpec,
    alpha_deg: f64,
    model: Box<dyn FiberModel>,
}

#[pymethods]
impl Fiber {
    #[new]
    #[pyo3(signature = (
        model = "nonseparable",
        *,
        beta = FiberParams::default().beta,
        alpha_deg = DEFAULT_ALPHA_DEG,
        eta = FiberParams::default().eta,
        mu_a = None,
        eumelanin = None,
        pheomelanin = None,
        iterations = i64::from(DEFAULT_ITERATIONS),
        tabulated = true,
    ))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        model: &str,
        beta: f64,
        alpha_deg: f64,
        eta: f64,
        mu_a: Option<&Bound<'_, PyAny>>,
        eumelanin: Option<f64>,
        pheomelanin: Option<f64>,
        iterations: i64,
        tabulated: bool,
    ) -> PyResult<Self> {
        let iterations = ranges::ITERATIONS
            .check_signed(iterations)
            .map_err(value_error)? as u32;
        let id: ModelId = model.parse().map_err(value_error)?;
        let mu_a = mu_a.map(|v| rgb_argument("mu_a", v)).transpose()?;
        let mu_a = absorption(mu_a, eumelanin, pheomelanin, FiberParams::default().mu_a)
            .map_err(value_error)?;
        let spec = ModelSpec {
            model: id,
            params: FiberParams {
                eta,
                beta,
                alpha: alpha_deg.to_radians(),
                mu_a,
            },
            options: BuildOptions {
                tabulation: match tabulated {
                    true => Tabulation::Tabulated,
                    false => Tabulation::Direct,
                },
                iterations,
                beta_n: None,
            },
        };
        let model = py.detach(|| spec.build()).map_err(value_error)?;
        Ok(Fiber {
            spec,
            alpha_deg,
            model,
        })
    }

    /// The model's name, as `cuticle lobes --model` spells it.
    #[getter]
    fn model(&self) -> &'static str {
        self.spec.model.name()
    }

    /// Longitudinal roughness β, radians.
    #[getter]
    fn beta(&self) -> f64 {
        self.spec.params.beta
    }

    /// Scale tilt α, degrees.
    #[getter]
    fn alpha_deg(&self) -> f64 {
        self.alpha_deg
    }

    /// Relative index of refraction η.
    #[getter]
    fn eta(&self) -> f64 {
        self.spec.params.eta
    }

    /// Interior absorption μ_a per unit radius, (r, g, b) (from melanin where that was given).
    #[getter]
    fn mu_a(&self) -> (f64, f64, f64) {
        self.spec.params.mu_a.into()
    }

    fn __repr__(&self) -> String {
        let p = &self.spec.params;
        format!(
            "Fiber(model={:?}, beta={}, alpha_deg={}, eta={}, mu_a=({}, {}, {}))",
            self.model(),
            p.beta,
            self.alpha_deg,
            p.eta,
            p.mu_a.x,
            p.mu_a.y,
            p.mu_a.z
        )
    }

    /// S(wi, wo), all lobes summed, RGB, sr⁻¹: an array of shape (N, 3).
    fn eval<'py>(
        &self,
        py: Python<'py>,
        wi: Floats<'py>,
        wo: Floats<'py>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let values = self.per_pair(py, &wi, &wo, |s| s.total().to_array())?;
        Ok(matrix(py, values, 3).into_any())
    }

    /// S(wi, wo) per lobe: a dict of arrays of shape (N, 3) keyed "R", "TT", "TRT", "TRRT",
    /// "rest" (p ≥ 4), whose sum is `eval`'s.
    fn lobes<'py>(
        &self,
        py: Python<'py>,
        wi: Floats<'py>,
        wo: Floats<'py>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let values = self.per_pair(py, &wi, &wo, |s: LobeValues| {
            let mut row = [0.0; 15];
            for (k, v) in s.0.iter().enumerate() {
                row[3 * k..3 * k + 3].copy_from_slice(&v.to_array());
            }
            row
        })?;
        let dict = PyDict::new(py);
        for lobe in Lobe::ALL {
            let k = lobe.index();
            let column: Vec<f64> = values
                .chunks_exact(15)
                .flat_map(|row| row[3 * k..3 * k + 3].iter().copied())
                .collect();
            dict.set_item(lobe.name(), matrix(py, column, 3))?;
        }
        Ok(dict)
    }

    /// The density per steradian with which `sample` draws wo: an array of shape (N,).
    fn pdf<'py>(
        &self,
        py: Python<'py>,
        wi: Floats<'py>,
        wo: Floats<'py>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let (wi, wo) = (Directions::read("wi", &wi)?, Directions::read("wo", &wo)?);
        let n = broadcast(("wi", wi.0.len()), ("wo", wo.0.len()))?;
        let model = self.model.as_ref();
        let values = py.detach(|| par_rows(n, |k| [model.pdf(wi.angles(k), wo.angles(k))]));
        Ok(PyArray1::from_vec(py, values))
    }

    /// Importance samples: for each row of `u` (shape (N, 4), uniform numbers in [0, 1), the
    /// model's four) an outgoing direction drawn for `wi` ((N, 3) or (3,)). Returns
    /// (wo (N, 3), weight (N, 3) = S / pdf, pdf (N,)); a draw that carries no energy has
    /// wo = weight = 0 and pdf = 0, so the mean weight estimates the albedo.
    fn sample<'py>(
        &self,
        py: Python<'py>,
        wi: Floats<'py>,
        u: Floats<'py>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>, Bound<'py, PyAny>)> {
        let wi = Directions::read("wi", &wi)?;
        let u = uniforms("u", &u)?;
        let n = broadcast(("wi", wi.0.len()), ("u", u.len()))?;
        let model = self.model.as_ref();
        let rows = py.detach(|| {
            par_rows(n, |k| {
                let mut row = [0.0; 7];
                if let Some(s) = model.sample(wi.angles(k), u[if u.len() == 1 { 0 } else { k }]) {
                    row[..3].copy_from_slice(&s.wo.to_dir().to_array());
                    row[3..6].copy_from_slice(&s.weight.to_array());
                    row[6] = s.pdf;
                }
                row
            })
        });
        let column = |range: std::ops::Range<usize>| -> Vec<f64> {
            rows.chunks_exact(7)
                .flat_map(|r| r[range.clone()].iter().copied())
                .collect()
        };
        Ok((
            matrix(py, column(0..3), 3).into_any(),
            matrix(py, column(3..6), 3).into_any(),
            PyArray1::from_vec(py, column(6..7)).into_any(),
        ))
    }

    /// The lobes as lat-long images (docs/conventions.md §4) for light at inclination
    /// `theta_i` (radians, in (-π/2, π/2)), exactly as `cuticle lobes` writes them
    /// (its EXRs hold these values rounded to float32): `width` in 8..=4000, a multiple of 4,
    /// `height` a quarter of it (the default; the grid of `cuticle lobes`); each pixel the mean
    /// of S over the pixel.
    ///
    /// Returns a dict: "R", "TT", "TRT", "TRRT", "rest", "total" → float64 arrays of shape
    /// (height, width, 3), row 0 at θ_o = +π/2 and column 0 at φ = -π; "energy" → dict of
    /// each lobe's and the "total" albedo ∫ S dω_o (RGB arrays of shape (3,), from the white
    /// furnace's quadrature, lobes.json's "energy"); "energy_error_estimate" → (3,).
    #[pyo3(signature = (theta_i, width = 400, height = None))]
    fn latlong<'py>(
        &self,
        py: Python<'py>,
        theta_i: f64,
        width: i64,
        height: Option<i64>,
    ) -> PyResult<Bound<'py, PyDict>> {
        ranges::THETA_I.check(theta_i).map_err(value_error)?;
        let width = LOBE_WIDTH.check_signed(width).map_err(value_error)?;
        let grid = lobe_grid(width as usize).map_err(value_error)?;
        if let Some(h) = height.filter(|&h| h != grid.height as i64) {
            return Err(value_error(format!(
                "height must be width / 4 = {} (the grid of `cuticle lobes`), got {h}",
                grid.height
            )));
        }
        let rule = FurnaceRule::for_fiber(self.spec.params.beta, self.alpha_deg);
        let model = self.model.as_ref();
        let (lobes, energy) = py.detach(|| {
            (
                lobe_images(model, theta_i, grid, rule),
                furnace::albedo(model, theta_i, rule),
            )
        });
        let dict = PyDict::new(py);
        let energies = PyDict::new(py);
        for (lobe, image) in Lobe::ALL.into_iter().zip(&lobes) {
            dict.set_item(
                lobe.name(),
                rgb_image(py, grid.width, grid.height, &image.pixels, f64_channels),
            )?;
            energies.set_item(lobe.name(), rgb(py, energy.per_lobe[lobe]))?;
        }
        let sum = total(&lobes);
        dict.set_item(
            "total",
            rgb_image(py, grid.width, grid.height, &sum.pixels, f64_channels),
        )?;
        energies.set_item("total", rgb(py, energy.albedo))?;
        dict.set_item("energy", energies)?;
        dict.set_item("energy_error_estimate", rgb(py, energy.error_estimate))?;
        Ok(dict)
    }
}

impl Fiber {
    /// `f` of S at each pair of directions, in parallel without the GIL.
    fn per_pair<const W: usize>(
        &self,
        py: Python<'_>,
        wi: &Floats,
        wo: &Floats,
        f: impl Fn(LobeValues) -> [f64; W] + Sync + Send,
    ) -> PyResult<Vec<f64>> {
        let (wi, wo) = (Directions::read("wi", wi)?, Directions::read("wo", wo)?);
        let n = broadcast(("wi", wi.0.len()), ("wo", wo.0.len()))?;
        let model = self.model.as_ref();
        Ok(py.detach(|| par_rows(n, |k| f(model.eval(wi.angles(k), wo.angles(k))))))
    }
}

/// An RGB value as a float64 array of shape (3,).
pub fn rgb(py: Python<'_>, v: DVec3) -> Bound<'_, PyArray1<f64>> {
    PyArray1::from_slice(py, &v.to_array())
}
