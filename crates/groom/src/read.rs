//! [`Groom::read`]: one entry for every groom file, dispatched on its extension, then its first
//! bytes: cyHair `.hair`, or a USD stage (`.usda`, `.usdc`, `.usdz`, `.usd`).

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
    /// The format of the file at `path`: its extension (`.hair`; `.usda`, `.usdc`, `.usdz`,
    /// `.usd`), else its magic bytes (`HAIR`; `PXR-USDC`, `#usda`, a zip's `PK`); anything
    /// else is taken for `.hair`, whose reader says what is wrong with it. A `.hair` file is
    /// always read as one, so its errors are what they were before USD.
    pub fn of(path: &Path) -> Self {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .unwrap_or("")
            .to_ascii_lowercase();
        if ext == "hair" {
            return Self::Hair;
        }
        if usd::EXTENSIONS.contains(&ext.as_str()) {
            return Self::Usd;
        }
        let mut head = [0u8; 8];
        let n = crate::hair_file::read::regular_file_len(path)
            .ok()
            .and_then(|_| std::fs::File::open(path).ok())
            .and_then(|mut f| f.read(&mut head).ok())
            .unwrap_or(0);
        let head = &head[..n];
        if head.starts_with(b"PXR-USDC") || head.starts_with(b"#usda") || head.starts_with(b"PK") {
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
