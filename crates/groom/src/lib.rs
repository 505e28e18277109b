//! Hair geometry for cuticle: the cyHair `.hair` format ([`HairFile`]), USD `BasisCurves`
//! grooms ([`usd`]), one reader for both ([`Groom::read`]), the in-memory
//! [`Groom`] a renderer reads (flat point arrays, strand offsets, tangents, bounds, per-strand
//! [`Appearance`]), and procedural grooms ([`procedural`]).
//!
//! Conventions:
//! - Positions and thickness share one unit. `.hair` files keep theirs; procedural grooms and
//!   USD grooms (converted by their `metersPerUnit`) are in centimetres.
//! - Procedural grooms are **+z up**, like the cyHair models: the head
//!   is centred at the origin and the face looks toward **+y** (as in `straight.hair`, whose
//!   hairline is high on the +y side), so the person's right is +x. A camera in front of the
//!   face sits on the +y axis looking along −y, with −x to its right.
//! - Thickness is the fiber's diameter at a point.
//! - Appearance units follow docs/conventions.md §5 (μ_a per unit radius, α in degrees).

pub mod appearance;
pub mod error;
pub mod geometry;
pub mod groom;
pub mod hair_file;
pub mod procedural;
pub mod read;
pub mod strand_absorption;
pub mod summary;
pub mod usd;

mod convert;

pub use appearance::{Absorption, Appearance};
pub use error::{GroomError, HairArray, HairFileError, ParamsError};
pub use geometry::Aabb;
pub use groom::{Groom, GroomParts, Strand};
pub use hair_file::{ArrayFlags, HairDefaults, HairFile, HairInfo};
pub use read::{GroomFormat, GroomReadError};
pub use strand_absorption::StrandAbsorptionError;
pub use usd::UsdError;
