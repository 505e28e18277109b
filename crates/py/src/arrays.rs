//! NumPy arrays in and out. In: directions of shape (N, 3) or (3,) (a single one is broadcast
//! against the other argument's N), each a finite unit vector in the fiber frame of
//! docs/conventions.md §2 (x = sin θ along the fiber), and uniform numbers of shape (N, 4) in
//! [0, 1); any dtype NumPy casts to float64 is taken. Out: float64 arrays of N rows, filled in
//! parallel on rayon's pool with the GIL released by the caller.

use crate::errors::value_error;
use cuticle_fiber::FiberAngles;
use glam::DVec3;
use numpy::ndarray::{Array, Ix2, Ix3};
use numpy::{
    AllowTypeChange, Element, IntoPyArray, PyArray, PyArrayLikeDyn, PyUntypedArrayMethods,
};
use pyo3::prelude::*;
use rayon::prelude::*;

/// An array argument as NumPy hands it over, cast to float64.
pub type Floats<'py> = PyArrayLikeDyn<'py, f64, AllowTypeChange>;

/// How far from 1 a direction's length may be: a unit vector normalised in float32 is within
/// about 1e-7 of it.
pub const UNIT_TOLERANCE: f64 = 1e-5;

/// Rows handed to one rayon task: enough that the task's overhead vanishes beside the model's
/// work.
const MIN_ROWS_PER_TASK: usize = 256;

/// Rows of `columns` numbers each, copied out of a NumPy array of shape (N, columns) or, where
/// `single` allows, (columns,) (N = 1).
pub struct Rows {
    pub values: Vec<f64>,
    pub columns: usize,
}

impl Rows {
    pub fn len(&self) -> usize {
        self.values.len() / self.columns
    }

    pub fn row(&self, k: usize) -> &[f64] {
        &self.values[k * self.columns..(k + 1) * self.columns]
    }

    /// Reads `array` (the argument `name`) as rows of `columns`.
    pub fn read(name: &str, array: &Floats, columns: usize, single: bool) -> PyResult<Rows> {
        let shape = array.shape();
        let fits = match shape {
            [n] => single && *n == columns,
            [_, c] => *c == columns,
            _ => false,
        };
        if !fits {
            let single = if single {
                format!(" or ({columns},)")
            } else {
                String::new()
            };
            return Err(value_error(format!(
                "{name} must have shape (N, {columns}){single}, got {}",
                python_shape(shape)
            )));
        }
        let values = match array.as_slice() {
            Ok(s) => s.to_vec(),
            Err(_) => array.as_array().iter().copied().collect(),
        };
        Ok(Rows { values, columns })
    }
}

/// Unit directions of shape (N, 3) or (3,).
pub struct Directions(pub Vec<DVec3>);

impl Directions {
    /// Reads and checks `array`: every row a finite unit vector (within [`UNIT_TOLERANCE`]).
    pub fn read(name: &str, array: &Floats) -> PyResult<Directions> {
        let rows = Rows::read(name, array, 3, true)?;
        let dirs: Vec<DVec3> = (0..rows.len())
            .into_par_iter()
            .with_min_len(MIN_ROWS_PER_TASK)
            .map(|k| DVec3::from_slice(rows.row(k)))
            .collect();
        let bad = dirs
            .par_iter()
            .with_min_len(MIN_ROWS_PER_TASK)
            .position_first(|d| !is_unit(*d));
        if let Some(k) = bad {
            let d = dirs[k];
            return Err(value_error(format!(
                "{name}[{k}] = ({}, {}, {}) is not a finite unit vector (length {})",
                d.x,
                d.y,
                d.z,
                d.length()
            )));
        }
        Ok(Directions(dirs))
    }

    /// The angles of row `k`, the single row broadcast.
    pub fn angles(&self, k: usize) -> FiberAngles {
        let d = if self.0.len() == 1 {
            self.0[0]
        } else {
            self.0[k]
        };
        FiberAngles::from_dir(d)
    }
}

/// Whether `d` is finite and of length 1 within [`UNIT_TOLERANCE`].
fn is_unit(d: DVec3) -> bool {
    let error = (d.length() - 1.0).abs();
    error.is_finite() && error <= UNIT_TOLERANCE
}

/// The rows two arguments share: equal counts, or one of them a single row.
pub fn broadcast(first: (&str, usize), second: (&str, usize)) -> PyResult<usize> {
    match (first.1, second.1) {
        (a, b) if a == b => Ok(a),
        (1, b) => Ok(b),
        (a, 1) => Ok(a),
        (a, b) => Err(value_error(format!(
            "{} has {a} rows and {} has {b}: give the same number, or one row",
            first.0, second.0
        ))),
    }
}

/// Uniform numbers of shape (N, 4), each in [0, 1).
pub fn uniforms(name: &str, array: &Floats) -> PyResult<Vec<[f64; 4]>> {
    let rows = Rows::read(name, array, 4, false)?;
    let bad = rows
        .values
        .par_iter()
        .position_first(|u| !(0.0..1.0).contains(u));
    if let Some(i) = bad {
        return Err(value_error(format!(
            "{name} must lie in [0, 1), got {name}[{}, {}] = {}",
            i / 4,
            i % 4,
            rows.values[i]
        )));
    }
    Ok((0..rows.len())
        .map(|k| rows.row(k).try_into().expect("4 columns"))
        .collect())
}

/// `f(k)` for every row `k` < `n`, in parallel, as `n` rows of `W` numbers.
pub fn par_rows<const W: usize>(n: usize, f: impl Fn(usize) -> [f64; W] + Sync) -> Vec<f64> {
    let mut out = vec![0.0; n * W];
    out.par_chunks_mut(W)
        .with_min_len(MIN_ROWS_PER_TASK)
        .enumerate()
        .for_each(|(k, row)| row.copy_from_slice(&f(k)));
    out
}

/// `values` (rows of `columns`) as a float64 array of shape (N, columns).
pub fn matrix(py: Python<'_>, values: Vec<f64>, columns: usize) -> Bound<'_, PyArray<f64, Ix2>> {
    let rows = values.len() / columns;
    Array::from_shape_vec((rows, columns), values)
        .expect("whole rows")
        .into_pyarray(py)
}

/// RGB pixels, row-major, as an array of shape (height, width, 3) of what `channels` makes
/// of each: float64 ([`f64_channels`]) or float32 as the command line's EXRs store them
/// ([`f32_channels`]).
pub fn rgb_image<'py, T: Element>(
    py: Python<'py>,
    width: usize,
    height: usize,
    pixels: &[DVec3],
    channels: fn(&DVec3) -> [T; 3],
) -> Bound<'py, PyArray<T, Ix3>> {
    let flat: Vec<T> = pixels.iter().flat_map(channels).collect();
    Array::from_shape_vec((height, width, 3), flat)
        .expect("width × height pixels")
        .into_pyarray(py)
}

/// A pixel's channels as float64.
pub fn f64_channels(p: &DVec3) -> [f64; 3] {
    p.to_array()
}

/// A pixel's channels rounded to float32, as the command line's EXRs store them.
pub fn f32_channels(p: &DVec3) -> [f32; 3] {
    p.as_vec3().to_array()
}

/// A shape as Python prints it: `(3, 2)`, `(4,)`.
fn python_shape(shape: &[usize]) -> String {
    match shape {
        [n] => format!("({n},)"),
        _ => {
            let dims: Vec<String> = shape.iter().map(usize::to_string).collect();
            format!("({})", dims.join(", "))
        }
    }
}
