//! The per-strand absorption file: a JSON sidecar beside a `.hair` file, for what the cyHair
//! format cannot hold (its colour array is a display colour per point, not an absorption). The
//! live window's Save writes one for a painted groom, and a scene names it as
//! `strand_absorption`.
//!
//! ```json
//! { "format": "cuticle-strand-absorption", "version": 1, "strands": 3,
//!   "absorption": [ {"mu_a": [0.3, 0.5, 0.9]},
//!                   {"melanin": {"eumelanin": 1.3, "pheomelanin": 0.2}},
//!                   null ] }
//! ```
//!
//! One entry per strand, in the groom's strand order: μ_a per unit radius (RGB), melanin
//! concentrations, or `null` for a strand that keeps the renderer's default. Numbers are f32 and
//! written in their shortest exact form, so a file read back gives the same bits.

use crate::appearance::Absorption;
use crate::groom::Groom;
use crate::hair_file::MAX_STRANDS;
use serde::{Deserialize, Serialize};
use std::path::Path;
use thiserror::Error;

/// The `"format"` value of the file.
pub const FORMAT: &str = "cuticle-strand-absorption";
/// The `"version"` this reader and writer speak.
pub const VERSION: u32 = 1;
/// Largest file read: ample for [`MAX_STRANDS`] entries of about 60 bytes.
const MAX_BYTES: u64 = 60 * MAX_STRANDS as u64;

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    format: String,
    version: u32,
    strands: usize,
    absorption: Vec<Option<Absorption>>,
}

/// Why a strand absorption file cannot be used.
#[derive(Debug, Error)]
pub enum StrandAbsorptionError {
    #[error("cannot read it: {0}")]
    Io(#[from] std::io::Error),
    #[error("it is {0} bytes, larger than any groom's absorption file")]
    TooLarge(u64),
    #[error("not a strand absorption file: {0}")]
    Json(#[from] serde_json::Error),
    #[error("its format is {format:?} version {version}, not {FORMAT:?} version {VERSION}")]
    Format { format: String, version: u32 },
    #[error("it holds {found} strands (says {claimed}), the groom has {groom}")]
    StrandCount {
        claimed: usize,
        found: usize,
        groom: usize,
    },
    #[error("strand {strand}'s absorption {value:?} is not finite and ≥ 0")]
    Unphysical { strand: usize, value: Absorption },
}

/// The file's bytes for each strand's absorption of `groom`.
pub fn to_bytes(groom: &Groom) -> Vec<u8> {
    let file = File {
        format: FORMAT.into(),
        version: VERSION,
        strands: groom.strand_count(),
        absorption: groom.appearance().iter().map(|a| a.absorption).collect(),
    };
    // A Vec of plain numbers, options and enums always serialises.
    serde_json::to_vec(&file).unwrap_or_default()
}

/// Each strand's absorption from the file's bytes, checked against a groom of `strands`.
pub fn from_bytes(
    bytes: &[u8],
    strands: usize,
) -> Result<Vec<Option<Absorption>>, StrandAbsorptionError> {
    let file: File = serde_json::from_slice(bytes)?;
    if file.format != FORMAT || file.version != VERSION {
        return Err(StrandAbsorptionError::Format {
            format: file.format,
            version: file.version,
        });
    }
    if file.strands != strands || file.absorption.len() != strands {
        return Err(StrandAbsorptionError::StrandCount {
            claimed: file.strands,
            found: file.absorption.len(),
            groom: strands,
        });
    }
    for (strand, a) in file.absorption.iter().enumerate() {
        if let Some(value) = *a
            && !physical(value)
        {
            return Err(StrandAbsorptionError::Unphysical { strand, value });
        }
    }
    Ok(file.absorption)
}

fn physical(a: Absorption) -> bool {
    let values: &[f32] = match &a {
        Absorption::MuA(s) => s,
        Absorption::Melanin {
            eumelanin,
            pheomelanin,
        } => &[*eumelanin, *pheomelanin],
    };
    values.iter().all(|v| v.is_finite() && *v >= 0.0)
}

impl Groom {
    /// This groom with each strand's absorption read from the file at `path`.
    pub fn with_strand_absorption(
        mut self,
        path: impl AsRef<Path>,
    ) -> Result<Self, StrandAbsorptionError> {
        let path = path.as_ref();
        let len = crate::hair_file::read::regular_file_len(path)?;
        if len > MAX_BYTES {
            return Err(StrandAbsorptionError::TooLarge(len));
        }
        let absorption = from_bytes(&std::fs::read(path)?, self.strand_count())?;
        for (appearance, a) in self.appearance_mut().iter_mut().zip(absorption) {
            appearance.absorption = a;
        }
        Ok(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::procedural::{GroomParams, Preset, generate};

    fn groom() -> Groom {
        let params = GroomParams {
            strands: 40,
            ..Preset::Straight.params()
        };
        generate(&params).unwrap()
    }

    /// Written and read back, every strand's absorption keeps its bits, a painted μ_a and an
    /// unset strand included.
    #[test]
    fn round_trip_is_exact() {
        let mut g = groom();
        g.appearance_mut()[3].absorption = Some(Absorption::MuA([0.1f32 / 3.0, 0.7, 1e-7]));
        g.appearance_mut()[5].absorption = None;
        let bytes = to_bytes(&g);
        let back = from_bytes(&bytes, g.strand_count()).unwrap();
        let want: Vec<_> = g.appearance().iter().map(|a| a.absorption).collect();
        assert_eq!(back, want);
    }

    /// Files written before absorption was named `mu_a` everywhere said `sigma_a`; they still
    /// read, and a key that is neither is refused.
    #[test]
    fn the_old_key_sigma_a_still_reads() {
        let old = r#"{"format":"cuticle-strand-absorption","version":1,"strands":2,"absorption":[{"sigma_a":[0.25,0.5,1]},null]}"#;
        let back = from_bytes(old.as_bytes(), 2).unwrap();
        assert_eq!(back, vec![Some(Absorption::MuA([0.25, 0.5, 1.0])), None]);
        let other = old.replace("sigma_a", "sigma_b");
        assert!(matches!(
            from_bytes(other.as_bytes(), 2),
            Err(StrandAbsorptionError::Json(_))
        ));
    }

    #[test]
    fn wrong_count_format_or_values_are_refused() {
        let g = groom();
        let bytes = to_bytes(&g);
        assert!(matches!(
            from_bytes(&bytes, g.strand_count() + 1),
            Err(StrandAbsorptionError::StrandCount { .. })
        ));
        let text = String::from_utf8(bytes).unwrap();
        let other = text.replace(FORMAT, "something-else");
        assert!(matches!(
            from_bytes(other.as_bytes(), g.strand_count()),
            Err(StrandAbsorptionError::Format { .. })
        ));
        let negative = r#"{"format":"cuticle-strand-absorption","version":1,"strands":1,"absorption":[{"mu_a":[0.1,-1,0]}]}"#;
        assert!(matches!(
            from_bytes(negative.as_bytes(), 1),
            Err(StrandAbsorptionError::Unphysical { strand: 0, .. })
        ));
        assert!(matches!(
            from_bytes(&text.as_bytes()[..text.len() / 2], g.strand_count()),
            Err(StrandAbsorptionError::Json(_))
        ));
    }
}
