//! The stage: opened through the guard, its `BasisCurves` prims found, and each prim's
//! composed world transform and the stage's units turned into one matrix to cuticle's frame
//! (+z up, centimetres).

use super::error::{PrimFault, UsdError};
use super::guard::{GuardedResolver, catch_quietly};
use glam::{DMat3, DMat4, DVec3};
use openusd::schemas::geom::{Imageable, Xformable};
use openusd::usd::{self, Prim, PrimPredicate, SchemaBase, SchemaKind, Stage, TimeCode};
use std::path::Path;

/// The time every value is read at: the first time sample where an attribute has samples,
/// else its default value (what a DCC's rest frame holds).
pub const READ_TIME: TimeCode = TimeCode::EARLIEST;

/// Opens the stage at `path`, with every layer guarded, refusing one whose composition failed
/// (a cycle of references, a missing layer).
pub fn open(path: &Path) -> Result<Stage, UsdError> {
    let text = path
        .to_str()
        .ok_or_else(|| UsdError::Open("its path is not valid UTF-8".into()))?;
    let stage = catch_quietly(|| {
        usd::Stage::builder()
            .resolver(GuardedResolver::default())
            .open(text)
    })?
    .map_err(|e| UsdError::Open(one_line(&e)))?;
    Ok(stage)
}

/// The paths of every `BasisCurves` prim (active, defined, instance proxies included), in
/// traversal order; then the stage's composition errors, if any, refuse it.
pub fn basis_curves(stage: &Stage) -> Result<Vec<Prim>, UsdError> {
    let mut paths = Vec::new();
    catch_quietly(|| stage.traverse(PrimPredicate::DEFAULT_PROXIES, |p| paths.push(p.clone())))?
        .map_err(|e| UsdError::Open(one_line(&e)))?;
    let mut prims = Vec::new();
    for path in paths {
        let prim = stage.prim(path);
        let ty = prim.type_name().map_err(|e| UsdError::Open(one_line(&e)))?;
        if ty.as_deref() == Some("BasisCurves") {
            prims.push(prim);
        }
    }
    if let Some(e) = stage.composition_errors().first() {
        return Err(UsdError::Open(format!("its composition failed: {e}")));
    }
    Ok(prims)
}

/// `e`'s causes on one line.
pub fn one_line(e: &anyhow::Error) -> String {
    format!("{e:#}").replace('\n', " ")
}

/// The stage's frame: units and up axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StageFrame {
    /// `metersPerUnit` (USD's fallback: 0.01, centimetres).
    pub meters_per_unit: f64,
    /// `upAxis` is `Y` (USD's fallback) rather than `Z`.
    pub y_up: bool,
}

impl StageFrame {
    /// The stage's `metersPerUnit` and `upAxis`, each checked.
    pub fn of(stage: &Stage) -> Result<Self, UsdError> {
        let meta = |field: &str| {
            stage
                .stage_metadata(field)
                .map_err(|e| UsdError::Open(one_line(&e)))
        };
        let meters_per_unit = match meta("metersPerUnit")? {
            None => 0.01,
            Some(v) => v
                .clone()
                .cast::<f64>()
                .map_err(|_| bad_units(format!("{v:?}")))?,
        };
        if !(meters_per_unit.is_finite() && (1e-9..=1e6).contains(&meters_per_unit)) {
            return Err(bad_units(meters_per_unit.to_string()));
        }
        let y_up = match meta("upAxis")? {
            None => true,
            Some(v) => match v.clone().cast::<String>().ok().as_deref() {
                Some("Y") => true,
                Some("Z") => false,
                _ => {
                    return Err(UsdError::StageMetadata {
                        field: "upAxis",
                        value: format!("{v:?}"),
                        rule: "it must be \"Y\" or \"Z\"",
                    });
                }
            },
        };
        Ok(Self {
            meters_per_unit,
            y_up,
        })
    }

    /// Stage units, up axis as stated → centimetres, +z up. A Y-up stage turns +90° about x,
    /// (x, y, z) ↦ (x, −z, y), the turn Blender and Maya apply between the two conventions.
    pub fn to_cuticle(&self) -> DMat4 {
        let scale = DMat4::from_scale(DVec3::splat(self.meters_per_unit * 100.0));
        let turn = if self.y_up {
            DMat4::from_rotation_x(std::f64::consts::FRAC_PI_2)
        } else {
            DMat4::IDENTITY
        };
        turn * scale
    }
}

fn bad_units(value: String) -> UsdError {
    UsdError::StageMetadata {
        field: "metersPerUnit",
        value,
        rule: "it must be a finite number in [1e-9, 1e6]",
    }
}

/// Any prim seen as `Xformable`, to compose its `xformOp`s.
struct AnyXformable(Prim);

impl SchemaBase for AnyXformable {
    const KIND: SchemaKind = SchemaKind::ConcreteTyped;
    fn prim(&self) -> &Prim {
        &self.0
    }
}
impl Imageable for AnyXformable {}
impl Xformable for AnyXformable {}

/// The prim's local-to-world transform (column vectors): its own `xformOp`s and every
/// ancestor's, up to the root or a `!resetXformStack!`.
pub fn world_transform(stage: &Stage, prim: &Prim) -> Result<DMat4, PrimFault> {
    let mut world = DMat4::IDENTITY;
    let mut at = Some(prim.path().clone());
    while let Some(path) = at {
        if path.as_str() == "/" {
            break;
        }
        let x = AnyXformable(stage.prim(path.clone()));
        let local = x
            .local_to_parent_transform(READ_TIME)
            .map_err(|e| PrimFault::Transform(one_line(&e)))?;
        // openusd's matrices are row-major for row vectors: the same numbers, read column-major,
        // are the column-vector matrix.
        world = DMat4::from_cols_array(&local.0) * world;
        if x.resets_xform_stack().unwrap_or(false) {
            break;
        }
        at = path.parent();
    }
    if !world.is_finite() {
        return Err(PrimFault::Transform("not finite".into()));
    }
    Ok(world)
}

/// How a transform scales lengths: the cube root of its linear part's |determinant| (exact for
/// uniform scales; the mean for others).
pub fn length_scale(m: &DMat4) -> f64 {
    DMat3::from_mat4(*m).determinant().abs().cbrt()
}
