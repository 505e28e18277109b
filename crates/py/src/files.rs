//! Images on disk: `cuticle.read_exr` reads the EXRs the command line writes (lobe images,
//! renders) through the reader the command line itself uses (`cuticle_light::image_file`).

use crate::arrays::{f32_channels, rgb_image};
use crate::errors::value_error;
use numpy::PyArray3;
use pyo3::prelude::*;
use std::path::PathBuf;

/// The R, G, B channels of an OpenEXR file (alpha ignored) as a float32 array of shape
/// (height, width, 3), row 0 at the top. A file that is not a readable RGB EXR, or holds a
/// NaN or infinite pixel, raises ValueError.
#[pyfunction]
pub fn read_exr(py: Python<'_>, path: PathBuf) -> PyResult<Bound<'_, PyArray3<f32>>> {
    let image = py
        .detach(|| cuticle_light::image_file::read_rgb_exr(&path))
        .map_err(value_error)?;
    Ok(rgb_image(
        py,
        image.width,
        image.height,
        &image.pixels,
        f32_channels,
    ))
}
