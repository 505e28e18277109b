//! [`Groom::read`]: one entry for every groom file, dispatched on its first bytes, then its
//! extension: cyHair `.hair`, or a USD stage (`.usda`, `.usdc`, `.usdz`, `.usd`).

use crate::error::HairFileError;
use crate::groom::Groom;
use crate::usd::{self, UsdError};
use std::io::Read;
use std::path::Path;
use thiserror::Error;

/// Why a groom file could not be read: its format's own error.
#[derive(Debug, Error)]
pub enum GroomReadError {
    #[error(transparent)]
    Hair(#[from] HairFileError),
    #[error(transparent)]
    Usd(#[from] UsdError),
}

/// The formats a groom file may be in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GroomFormat {
    Hair,
    Usd,
}

impl GroomFormat {
    /// The format of the file at `path`: its magic bytes (`HAIR`, `PXR-USDC`, `#usda`, a zip's
    /// `PK`), else its extension; anything unrecognised is taken for `.hair`, whose reader
    /// says what is wrong with it.
    pub fn of(path: &Path) -> Self {
        let mut head = [0u8; 8];
        let n = crate::hair_file::read::regular_file_len(path)
            .ok()
            .and_then(|_| std::fs::File::open(path).ok())
            .and_then(|mut f| f.read(&mut head).ok())
            .unwrap_or(0);
        let head = &head[..n];
        if head.starts_with(b"HAIR") {
            return Self::Hair;
        }
        if head.starts_with(b"PXR-USDC") || head.starts_with(b"#usda") || head.starts_with(b"PK") {
            return Self::Usd;
        }
        let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("");
        if usd::EXTENSIONS.contains(&ext.to_ascii_lowercase().as_str()) {
            Self::Usd
        } else {
            Self::Hair
        }
    }
}

impl Groom {
    /// Reads a groom file: `.hair`, or every `BasisCurves` prim of a USD stage (see
    /// [`crate::usd`]), by [`GroomFormat::of`].
    pub fn read(path: impl AsRef<Path>) -> Result<Groom, GroomReadError> {
        let path = path.as_ref();
        match GroomFormat::of(path) {
            GroomFormat::Hair => Ok(Groom::read_hair(path)?),
            GroomFormat::Usd => Ok(usd::read(path)?),
        }
    }
}
