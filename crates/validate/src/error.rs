//! What can go wrong reading a sweep or building a model, each as one sentence.

use std::path::PathBuf;
use thiserror::Error;

#[derive(Debug, Error)]
pub enum ValidateError {
    #[error("simulation folder {0} does not exist or is not a folder")]
    MissingFolder(PathBuf),
    #[error("{0} holds no sim.json: not a finished simulation (run `cuticle sweep` to finish it)")]
    NoRecord(PathBuf),
    #[error("{path}: {message}")]
    BadRecord { path: PathBuf, message: String },
    #[error("{path}: {source}")]
    Io {
        path: PathBuf,
        source: std::io::Error,
    },
    #[error(
        "unknown model '{0}' (expected nonseparable, nonseparable-paper, deon2011 or marschner)"
    )]
    UnknownModel(String),
    #[error("model {model}: {message}")]
    Model {
        model: &'static str,
        message: String,
    },
    #[error("no simulated configuration found under {0}")]
    Empty(PathBuf),
}
