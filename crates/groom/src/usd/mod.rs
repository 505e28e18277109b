//! USD grooms: `BasisCurves` read from `.usda`, `.usdc` and `.usdz` stages, and written back.
//!
//! Reading ([`read`]), in order:
//! 1. the stage is opened through [`guard`]: every layer a regular file of bounded size, every
//!    `.usdc` layer's declared counts checked against its bytes, panics of the USD library
//!    caught; a stage whose composition failed (a reference cycle, a missing layer) is refused;
//! 2. every `BasisCurves` prim (active, defined, instance proxies included) is found, in
//!    traversal order, and each is read at [`stage::READ_TIME`] (its first time sample, else
//!    its default);
//! 3. its `type`, `basis`, `wrap` and `curveVertexCounts` are checked ([`curves::Layout`]); the
//!    polyline points all prims will make are counted and bounded before any is made;
//! 4. each curve becomes a polyline by [`basis`]'s subdivision rule, its `widths` (diameters,
//!    like the groom's thickness) expanded from constant, uniform, varying or vertex;
//! 5. points move by the prim's composed world transform, then into cuticle's frame
//!    ([`stage::StageFrame`]: `metersPerUnit` to centimetres, a Y-up stage turned +z up);
//!    widths scale with both;
//! 6. each strand's absorption comes from its primvars ([`absorption`]).
//!
//! Writing ([`write`]): one `BasisCurves` prim, linear, Z-up, centimetres, vertex widths, and
//! each strand's absorption as uniform primvars, as `.usda` text (`.usdc` is refused: see
//! [`write`]).

pub mod absorption;
pub mod basis;
pub mod curves;
pub mod error;
pub mod guard;
pub mod stage;
pub mod values;
pub mod write;

pub use error::{PrimFault, UsdError};
pub use write::{UsdFormat, to_usd_bytes};

use crate::appearance::{Absorption, Appearance};
use crate::groom::{Groom, GroomParts};
use crate::hair_file::MAX_POINTS;
use curves::{Layout, Polylines};
use glam::DVec3;
use openusd::usd::Prim;
use stage::StageFrame;
use std::path::Path;

/// The extensions read as USD.
pub const EXTENSIONS: [&str; 4] = ["usda", "usdc", "usdz", "usd"];

/// One prim, checked, before its polylines are made.
struct PrimPlan {
    prim: Prim,
    layout: Layout,
    control: Vec<DVec3>,
}

/// Reads every `BasisCurves` prim of the stage at `path` into one groom.
pub fn read(path: impl AsRef<Path>) -> Result<Groom, UsdError> {
    let path = path.as_ref();
    // The library reads values lazily, so any step may meet a broken one.
    guard::catch_quietly(|| read_stage(path))?
}

fn read_stage(path: &Path) -> Result<Groom, UsdError> {
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("");
    // The library picks a layer's format by its extension.
    if !EXTENSIONS.contains(&ext) {
        return Err(UsdError::Open(format!(
            "a USD stage is read by its extension, and {ext:?} is none of {EXTENSIONS:?}"
        )));
    }
    crate::hair_file::read::regular_file_len(path)?;
    let stage = stage::open(path)?;
    let frame = StageFrame::of(&stage)?;
    let prims = stage::basis_curves(&stage)?;
    if prims.is_empty() {
        return Err(UsdError::NoCurves);
    }
    let mut plans = Vec::with_capacity(prims.len());
    let mut total = 0u64;
    for prim in prims {
        let plan = plan(prim)?;
        total += plan.layout.out_points;
        if total > u64::from(MAX_POINTS) {
            return Err(UsdError::TooManyPoints {
                points: total,
                limit: MAX_POINTS.into(),
            });
        }
        plans.push(plan);
    }
    let to_cuticle = frame.to_cuticle();
    let mut parts = GroomParts {
        strand_offsets: vec![0],
        ..GroomParts::default()
    };
    let mut appearance = Vec::new();
    for plan in plans {
        let at = |fault| prim_error(&plan.prim, fault);
        let world = stage::world_transform(&stage, &plan.prim).map_err(at)?;
        let to_world = to_cuticle * world;
        let scale = stage::length_scale(&to_world);
        let lines = curves::polylines(&plan.prim, &plan.layout, &plan.control, to_world, scale)
            .map_err(at)?;
        let absorption = absorption::read(&plan.prim, &plan.layout).map_err(at)?;
        append(&mut parts, &lines);
        appearance.extend(absorption.into_iter().map(with_absorption));
    }
    Ok(Groom::from_parts(parts)?.with_appearance(appearance)?)
}

/// A prim's layout and control points, checked.
fn plan(prim: Prim) -> Result<PrimPlan, UsdError> {
    let at = |fault| prim_error(&prim, fault);
    let kind = curves::Kind::of(&prim).map_err(at)?;
    let counts = values::raw(&prim, "curveVertexCounts")
        .map_err(at)?
        .ok_or(PrimFault::Missing("curveVertexCounts"))
        .and_then(|v| values::ints("curveVertexCounts", v))
        .map_err(at)?;
    let control = values::raw(&prim, "points")
        .map_err(at)?
        .ok_or(PrimFault::Missing("points"))
        .and_then(|v| values::vec3s("points", v))
        .map_err(at)?;
    let layout = Layout::new(kind, &counts, control.len()).map_err(at)?;
    Ok(PrimPlan {
        prim,
        layout,
        control,
    })
}

fn prim_error(prim: &Prim, fault: PrimFault) -> UsdError {
    UsdError::Prim {
        prim: prim.path().as_str().to_string(),
        fault,
    }
}

fn append(parts: &mut GroomParts, lines: &Polylines) {
    parts
        .positions
        .extend(lines.positions.iter().map(|p| p.as_vec3()));
    parts
        .thickness
        .extend(lines.widths.iter().map(|&w| w as f32));
    let mut end = *parts.strand_offsets.last().unwrap_or(&0);
    for &n in &lines.counts {
        end += n as u32;
        parts.strand_offsets.push(end);
    }
}

fn with_absorption(absorption: Option<Absorption>) -> Appearance {
    Appearance {
        absorption,
        ..Appearance::default()
    }
}
