//! Errors of the light crate: each names the file and what is wrong with it, in one line.

use std::path::PathBuf;
use thiserror::Error;

#[derive(Debug, Error)]
pub enum LightError {
    #[error("cannot read environment map {path}")]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("{path} is neither a Radiance .hdr nor an OpenEXR file (unrecognised header)")]
    UnknownFormat { path: PathBuf },
    #[error("cannot decode environment map {path}: {message}")]
    Decode { path: PathBuf, message: String },
    #[error(
        "{path} is {width}x{height}, not a lat-long map: width must be about twice the height (2:1 ± 5%)"
    )]
    NotLatLong {
        path: PathBuf,
        width: usize,
        height: usize,
    },
    #[error("{path}: pixel (column {column}, row {row}) has a non-finite value {value}")]
    NonFinite {
        path: PathBuf,
        column: usize,
        row: usize,
        value: f32,
    },
    #[error(
        "{path}: pixel (column {column}, row {row}) has radiance {value:e}, above the {max:e} a \
         map may hold",
        max = crate::srbf::MAX_RADIANCE
    )]
    TooBright {
        path: PathBuf,
        column: usize,
        row: usize,
        value: f32,
    },
    #[error("cannot read {path}: {message}")]
    Image { path: PathBuf, message: String },
    #[error("cannot encode {0}")]
    Encode(String),
    #[error("invalid fit options: {0}")]
    FitOptions(String),
    #[error("light {index}: {message}")]
    Light { index: usize, message: String },
    #[error("a list of lights holds 1 to {max} lights, got {0}", max = crate::srbf::MAX_LIGHTS)]
    LightCount(usize),
}
