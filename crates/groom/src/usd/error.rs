//! Why a USD groom could not be read or written: one variant per kind of fault, each message
//! one line for the person who handed us the file.

use crate::error::GroomError;
use thiserror::Error;

/// Why a USD stage gave no groom, or a groom could not be written as USD.
#[derive(Debug, Error)]
pub enum UsdError {
    #[error("cannot read it: {0}")]
    Io(#[from] std::io::Error),

    #[error("{what} is {bytes} bytes, more than the {limit} a groom's USD layer may be")]
    TooLarge {
        what: String,
        bytes: u64,
        limit: u64,
    },

    #[error("not a readable USD file: {0}")]
    Open(String),

    #[error("a broken .usdc file: {0}")]
    Crate(String),

    #[error("the stage holds no BasisCurves prim, so no hair")]
    NoCurves,

    #[error("{prim}: {fault}")]
    Prim { prim: String, fault: PrimFault },

    #[error(
        "the stage's curves make {points} polyline points, more than the {limit} a groom holds"
    )]
    TooManyPoints { points: u64, limit: u64 },

    #[error("the stage's {field} is {value}; {rule}")]
    StageMetadata {
        field: &'static str,
        value: String,
        rule: &'static str,
    },

    #[error("the curves do not form a groom: {0}")]
    Groom(#[from] GroomError),

    #[error("the USD library failed on this file ({0}); it is likely broken")]
    Panicked(String),

    #[error("cannot write USD: {0}")]
    Write(String),
}

/// What is wrong with one `BasisCurves` prim.
#[derive(Debug, Error, PartialEq)]
pub enum PrimFault {
    #[error("it has no {0}")]
    Missing(&'static str),

    #[error("{attribute} is {value:?}; this reader takes {takes}")]
    Unsupported {
        attribute: &'static str,
        value: String,
        takes: &'static str,
    },

    #[error("{attribute} holds {found}, not {wants}")]
    WrongType {
        attribute: String,
        found: String,
        wants: &'static str,
    },

    #[error("curve {curve} has {count} vertices; a {kind} curve needs {needs}")]
    TooFewPoints {
        curve: usize,
        count: i64,
        kind: String,
        needs: &'static str,
    },

    #[error("curveVertexCounts add up to {sum} but there are {points} points")]
    CountMismatch { sum: u64, points: usize },

    #[error(
        "{attribute} has {actual} values; {interpolation} interpolation over these curves needs {expected}"
    )]
    Length {
        attribute: String,
        interpolation: String,
        expected: usize,
        actual: usize,
    },

    #[error("{attribute} holds index {index}, outside its {values} values")]
    Index {
        attribute: String,
        index: i64,
        values: usize,
    },

    #[error("{attribute} value {index} is {value}, not a finite number")]
    NonFinite {
        attribute: String,
        index: usize,
        value: f64,
    },

    #[error("{attribute} value {index} is {value}; it must be ≥ 0")]
    Negative {
        attribute: String,
        index: usize,
        value: f64,
    },

    #[error("{attribute} value {index} is {value}; it must be in [0, 1]")]
    NotAFraction {
        attribute: String,
        index: usize,
        value: f64,
    },

    #[error("its transform is {0}")]
    Transform(String),
}
