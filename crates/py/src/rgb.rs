//! RGB arguments: one number (grey) or three, as the command line's `--mu-a` takes them.

use crate::errors::value_error;
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;

/// `value` (the argument `name`) as (r, g, b): a number is grey.
pub fn rgb_argument(name: &str, value: &Bound<'_, PyAny>) -> PyResult<[f64; 3]> {
    if let Ok(v) = value.extract::<f64>() {
        return Ok([v; 3]);
    }
    let values: Vec<f64> = value.extract().map_err(|_| {
        PyTypeError::new_err(format!("{name} must be a number or (r, g, b) numbers"))
    })?;
    values.try_into().map_err(|v: Vec<f64>| {
        value_error(format!(
            "{name} takes one number or r, g, b, got {} numbers",
            v.len()
        ))
    })
}
