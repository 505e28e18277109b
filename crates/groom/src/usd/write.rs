//! A groom as a USD layer: `/Groom/Hair`, one `BasisCurves` prim of `linear` curves (the
//! groom's polylines, unchanged), Z-up, `metersPerUnit` 0.01 (centimetres), `widths` per vertex
//! (diameters, the groom's thickness), and, where any strand has its own absorption, uniform
//! (per-curve) primvars:
//! - `sigma_a` (`float3[]`): μ_a per unit radius for every strand (melanin strands: μ_a of their
//!   concentrations; strands without their own: 0);
//! - `eumelanin`, `pheomelanin` (`float[]`), and Blender's `melanin`, `melanin_redness`, where
//!   any strand came with melanin (0 for the others);
//! - `cuticle:absorption_source` (`int[]`): which of those each strand's absorption is (0 none,
//!   1 `sigma_a`, 2 melanin), so that cuticle reads back exactly what it wrote.
//!
//! Numbers are f32 as in the groom, so a written groom reads back bit for bit.
//!
//! Only text (`.usda`) is written: openusd 0.6's binary writer makes `.usdc` files that Pixar's
//! own library refuses ("Invalid children found in primChildren field": its prims' children do
//! not decode), so a `.usdc` request is refused rather than answered with a file Houdini or
//! Blender cannot open. `.usdc` files are read.

use super::absorption::{
    EUMELANIN, MELANIN, MELANIN_REDNESS, PHEOMELANIN, SIGMA_A, SOURCE, SOURCE_MELANIN, SOURCE_NONE,
    SOURCE_SIGMA_A,
};
use super::error::UsdError;
use crate::appearance::Absorption;
use crate::groom::Groom;
use cuticle_fiber::optics::absorption::mu_a_from_melanin;
use openusd::gf;
use openusd::sdf::{self, ChildrenKey, FieldKey, SpecType, Specifier, Value, Variability};
use std::path::Path;

/// The two USD encodings a groom may be asked for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UsdFormat {
    /// Text: written.
    Usda,
    /// Binary ("crate"): refused (see the module doc).
    Usdc,
}

/// Why `.usdc` is not written, in one line.
pub const NO_USDC: &str = "cuticle writes USD as text (.usda): the .usdc files openusd 0.6 \
    writes are refused by Pixar's USD (their prims' children do not decode); name a .usda file";

impl UsdFormat {
    /// The format a path's extension names (`.usda`, `.usdc`), if either.
    pub fn of_path(path: &Path) -> Option<Self> {
        match path.extension()?.to_str()? {
            "usda" => Some(Self::Usda),
            "usdc" => Some(Self::Usdc),
            _ => None,
        }
    }
}

const PRIM: &str = "/Groom/Hair";

/// The bytes of a USD layer holding `groom`.
pub fn to_usd_bytes(groom: &Groom, format: UsdFormat) -> Result<Vec<u8>, UsdError> {
    if format == UsdFormat::Usdc {
        return Err(UsdError::Write(NO_USDC.into()));
    }
    let data = layer(groom)?;
    let mut out = std::io::Cursor::new(Vec::new());
    openusd::usda::TextWriter::write(&data, &mut out)
        .map_err(|e| UsdError::Write(super::stage::one_line(&e)))?;
    Ok(out.into_inner())
}

fn path(text: &str) -> sdf::Path {
    // The writer's own constant paths, valid by construction.
    sdf::path(text).unwrap_or_else(|_| sdf::Path::abs_root())
}

/// The layer's specs.
fn layer(groom: &Groom) -> Result<sdf::Data, UsdError> {
    if let Some(strand) = groom.strands().position(|s| s.point_count() < 2) {
        return Err(UsdError::Write(format!(
            "strand {strand} has one point; a USD linear curve needs at least 2"
        )));
    }
    let mut data = sdf::Data::new();
    let root = data.create_spec(sdf::Path::abs_root(), SpecType::PseudoRoot);
    root.add(
        ChildrenKey::PrimChildren,
        Value::TokenVec(vec!["Groom".into()]),
    );
    root.add(FieldKey::DefaultPrim, Value::Token("Groom".into()));
    root.add("metersPerUnit", Value::Double(0.01));
    root.add("upAxis", Value::Token("Z".into()));
    root.add(
        FieldKey::Documentation,
        Value::String("A hair groom written by cuticle".into()),
    );
    let groom_spec = data.create_spec(path("/Groom"), SpecType::Prim);
    groom_spec.add(FieldKey::Specifier, Value::Specifier(Specifier::Def));
    groom_spec.add(FieldKey::TypeName, Value::Token("Xform".into()));
    groom_spec.add(
        ChildrenKey::PrimChildren,
        Value::TokenVec(vec!["Hair".into()]),
    );

    let mut attributes = vec![
        Attr::uniform("type", "token", Value::Token("linear".into())),
        Attr::uniform("wrap", "token", Value::Token("nonperiodic".into())),
        Attr::new("curveVertexCounts", "int[]", Value::IntVec(counts(groom))),
        Attr::new(
            "points",
            "point3f[]",
            vec3s(groom.positions().iter().map(|p| p.to_array())),
        ),
        Attr::new(
            "widths",
            "float[]",
            Value::FloatVec(groom.thickness().to_vec()),
        )
        .interpolated("vertex"),
    ];
    attributes.extend(absorption_primvars(groom));
    let hair = data.create_spec(path(PRIM), SpecType::Prim);
    hair.add(FieldKey::Specifier, Value::Specifier(Specifier::Def));
    hair.add(FieldKey::TypeName, Value::Token("BasisCurves".into()));
    hair.add(
        ChildrenKey::PropertyChildren,
        Value::TokenVec(attributes.iter().map(|a| a.name.as_str().into()).collect()),
    );
    for a in attributes {
        let at = path(PRIM)
            .append_property(&a.name)
            .map_err(|e| UsdError::Write(super::stage::one_line(&e)))?;
        let spec = data.create_spec(at, SpecType::Attribute);
        spec.add(FieldKey::TypeName, Value::Token(a.type_name.into()));
        spec.add(FieldKey::Custom, Value::Bool(false));
        if a.uniform {
            spec.add(
                FieldKey::Variability,
                Value::Variability(Variability::Uniform),
            );
        }
        if let Some(i) = a.interpolation {
            spec.add("interpolation", Value::Token(i.into()));
        }
        spec.add(FieldKey::Default, a.value);
    }
    Ok(data)
}

/// One attribute to write.
struct Attr {
    name: String,
    type_name: &'static str,
    value: Value,
    uniform: bool,
    interpolation: Option<&'static str>,
}

impl Attr {
    fn new(name: &str, type_name: &'static str, value: Value) -> Self {
        Self {
            name: name.into(),
            type_name,
            value,
            uniform: false,
            interpolation: None,
        }
    }

    fn uniform(name: &str, type_name: &'static str, value: Value) -> Self {
        Self {
            uniform: true,
            ..Self::new(name, type_name, value)
        }
    }

    fn interpolated(self, interpolation: &'static str) -> Self {
        Self {
            interpolation: Some(interpolation),
            ..self
        }
    }

    /// A per-curve primvar (`name` with its `primvars:` prefix).
    fn per_curve(name: &str, type_name: &'static str, value: Value) -> Self {
        Self::new(name, type_name, value).interpolated("uniform")
    }
}

fn counts(groom: &Groom) -> Vec<i32> {
    groom.strands().map(|s| s.point_count() as i32).collect()
}

fn vec3s(values: impl Iterator<Item = [f32; 3]>) -> Value {
    Value::Vec3fVec(values.map(gf::Vec3f::from).collect())
}

/// The absorption primvars, or none when no strand has its own.
fn absorption_primvars(groom: &Groom) -> Vec<Attr> {
    let absorption: Vec<Option<Absorption>> =
        groom.appearance().iter().map(|a| a.absorption).collect();
    if absorption.iter().all(Option::is_none) {
        return Vec::new();
    }
    let source = absorption.iter().map(|a| match a {
        None => SOURCE_NONE,
        Some(Absorption::MuA(_)) => SOURCE_SIGMA_A,
        Some(Absorption::Melanin { .. }) => SOURCE_MELANIN,
    });
    let sigma = absorption.iter().map(|a| match *a {
        None => [0.0; 3],
        Some(Absorption::MuA(s)) => s,
        Some(Absorption::Melanin {
            eumelanin,
            pheomelanin,
        }) => mu_a_from_melanin(eumelanin.into(), pheomelanin.into())
            .as_vec3()
            .to_array(),
    });
    let mut out = vec![
        Attr::per_curve(SOURCE, "int[]", Value::IntVec(source.collect())),
        Attr::per_curve(SIGMA_A, "float3[]", vec3s(sigma)),
    ];
    let pigments: Vec<[f32; 2]> = absorption
        .iter()
        .map(|a| match *a {
            Some(Absorption::Melanin {
                eumelanin,
                pheomelanin,
            }) => [eumelanin, pheomelanin],
            _ => [0.0; 2],
        })
        .collect();
    if absorption
        .iter()
        .any(|a| matches!(a, Some(Absorption::Melanin { .. })))
    {
        let column = |k: usize| Value::FloatVec(pigments.iter().map(|p| p[k]).collect());
        let blender: Vec<[f32; 2]> = pigments.iter().map(|p| blender_amounts(*p)).collect();
        let blender_column = |k: usize| Value::FloatVec(blender.iter().map(|p| p[k]).collect());
        out.extend([
            Attr::per_curve(EUMELANIN, "float[]", column(0)),
            Attr::per_curve(PHEOMELANIN, "float[]", column(1)),
            Attr::per_curve(MELANIN, "float[]", blender_column(0)),
            Attr::per_curve(MELANIN_REDNESS, "float[]", blender_column(1)),
        ]);
    }
    out
}

/// Blender's melanin amount and redness for concentrations (eumelanin, pheomelanin): the
/// inverse of the reader's Cycles mapping, amount = 1 − e^(−(eu + pheo)), redness =
/// pheo / (eu + pheo).
fn blender_amounts([eu, pheo]: [f32; 2]) -> [f32; 2] {
    let total = f64::from(eu) + f64::from(pheo);
    let amount = 1.0 - (-total).exp();
    let redness = if total > 0.0 {
        f64::from(pheo) / total
    } else {
        0.0
    };
    [amount as f32, redness as f32]
}
