//! Errors as Python sees them: a bad value is a `ValueError` carrying the one-line message the
//! command line prints for it (an error and its causes, joined by ": ").

use pyo3::PyErr;
use pyo3::exceptions::PyValueError;
use std::error::Error;
use std::fmt::Display;

/// A `ValueError` with `message` (a library error's `Display`, as the command line prints it).
pub fn value_error(message: impl Display) -> PyErr {
    PyValueError::new_err(message.to_string())
}

/// An error and each of its causes not already in the line, joined by ": ", as the command
/// line's `error:` line shows them.
pub fn error_line(error: &dyn Error) -> String {
    let mut line = error.to_string();
    let mut cause = error.source();
    while let Some(e) = cause {
        let text = e.to_string();
        if !line.contains(&text) {
            line = format!("{line}: {text}");
        }
        cause = e.source();
    }
    line
}
