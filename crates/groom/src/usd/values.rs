//! Attribute values of a prim as plain numbers, with primvar interpolation and indices
//! resolved, each checked finite.

use super::error::PrimFault;
use super::stage::READ_TIME;
use glam::DVec3;
use openusd::sdf::Value;
use openusd::tf::Token;
use openusd::usd::Prim;

/// How a primvar's values map onto curves (USD `interpolation` metadata).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Interpolation {
    /// One value for the prim.
    Constant,
    /// One value per curve.
    Uniform,
    /// One value per segment end of each curve.
    Varying,
    /// One value per control point.
    Vertex,
}

impl Interpolation {
    fn parse(token: &str) -> Option<Self> {
        match token {
            "constant" => Some(Self::Constant),
            "uniform" => Some(Self::Uniform),
            "varying" => Some(Self::Varying),
            "vertex" | "faceVarying" => Some(Self::Vertex),
            _ => None,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Self::Constant => "constant",
            Self::Uniform => "uniform",
            Self::Varying => "varying",
            Self::Vertex => "vertex",
        }
    }
}

/// A primvar read from a prim: its values (indices applied) and interpolation.
pub struct Primvar<T> {
    pub name: String,
    pub values: Vec<T>,
    pub interpolation: Interpolation,
}

/// The raw value of attribute `name`, if authored.
pub fn raw(prim: &Prim, name: &str) -> Result<Option<Value>, PrimFault> {
    prim.attribute(name)
        .get_at::<Value>(READ_TIME)
        .map_err(|e| PrimFault::WrongType {
            attribute: name.into(),
            found: super::stage::one_line(&e),
            wants: "a readable value",
        })
}

/// The token value of attribute `name`, if authored.
pub fn token(prim: &Prim, name: &'static str) -> Result<Option<String>, PrimFault> {
    match raw(prim, name)? {
        None => Ok(None),
        Some(Value::Token(t)) => Ok(Some(t.as_str().to_string())),
        Some(Value::String(s)) => Ok(Some(s)),
        Some(other) => Err(wrong(name, &other, "a token")),
    }
}

fn wrong(name: &str, value: &Value, wants: &'static str) -> PrimFault {
    let found = format!("{value:?}");
    let found = found
        .split(['(', '['])
        .next()
        .unwrap_or_default()
        .to_string();
    PrimFault::WrongType {
        attribute: name.into(),
        found,
        wants,
    }
}

/// Integers (`int[]` and the like).
pub fn ints(name: &str, value: Value) -> Result<Vec<i64>, PrimFault> {
    Ok(match value {
        Value::IntVec(v) => v.into_iter().map(i64::from).collect(),
        Value::UintVec(v) => v.into_iter().map(i64::from).collect(),
        Value::Int64Vec(v) => v,
        Value::Int(v) => vec![v.into()],
        other => return Err(wrong(name, &other, "integers")),
    })
}

/// Scalars (`float[]`, `double[]`, `half[]`, or one of them), each finite.
pub fn scalars(name: &str, value: Value) -> Result<Vec<f64>, PrimFault> {
    let v: Vec<f64> = match value {
        Value::FloatVec(v) => v.into_iter().map(f64::from).collect(),
        Value::DoubleVec(v) => v,
        Value::HalfVec(v) => v.into_iter().map(|h| h.to_f64()).collect(),
        Value::Float(v) => vec![v.into()],
        Value::Double(v) => vec![v],
        Value::Half(h) => vec![h.to_f64()],
        other => return Err(wrong(name, &other, "numbers")),
    };
    check_finite(name, v.iter().copied(), 1)?;
    Ok(v)
}

/// 3-vectors (`point3f[]`, `color3f[]`, `double3[]`, `half3[]`, or one of them), each finite.
pub fn vec3s(name: &str, value: Value) -> Result<Vec<DVec3>, PrimFault> {
    let f = |x: f32, y: f32, z: f32| DVec3::new(x.into(), y.into(), z.into());
    let v: Vec<DVec3> = match value {
        Value::Vec3fVec(v) => v.into_iter().map(|p| f(p.x, p.y, p.z)).collect(),
        Value::Vec3dVec(v) => v.into_iter().map(|p| DVec3::new(p.x, p.y, p.z)).collect(),
        Value::Vec3hVec(v) => v
            .into_iter()
            .map(|p| DVec3::new(p.x.to_f64(), p.y.to_f64(), p.z.to_f64()))
            .collect(),
        Value::Vec3f(p) => vec![f(p.x, p.y, p.z)],
        Value::Vec3d(p) => vec![DVec3::new(p.x, p.y, p.z)],
        other => return Err(wrong(name, &other, "3-vectors")),
    };
    check_finite(name, v.iter().flat_map(|p| p.to_array()), 3)?;
    Ok(v)
}

/// Every value finite; the first that is not is named by its entry (`width` numbers each).
fn check_finite(
    name: &str,
    values: impl Iterator<Item = f64>,
    width: usize,
) -> Result<(), PrimFault> {
    let mut values = values.enumerate();
    match values.find(|(_, x)| !x.is_finite()) {
        Some((i, value)) => Err(PrimFault::NonFinite {
            attribute: name.into(),
            index: i / width,
            value,
        }),
        None => Ok(()),
    }
}

/// Primvar `name` (a full attribute name, e.g. `widths` or `primvars:melanin`) decoded by
/// `decode`, with its interpolation (`fallback` when unauthored) and `:indices` applied.
pub fn primvar<T: Copy>(
    prim: &Prim,
    name: &str,
    fallback: Interpolation,
    decode: impl Fn(&str, Value) -> Result<Vec<T>, PrimFault>,
) -> Result<Option<Primvar<T>>, PrimFault> {
    let Some(value) = raw(prim, name)? else {
        return Ok(None);
    };
    let values = decode(name, value)?;
    let interpolation = match prim
        .attribute(name)
        .get_metadata::<Token>("interpolation")
        .ok()
        .flatten()
    {
        None => fallback,
        Some(t) => Interpolation::parse(t.as_str()).ok_or(PrimFault::Unsupported {
            attribute: "interpolation",
            value: t.as_str().to_string(),
            takes: "constant, uniform, varying or vertex",
        })?,
    };
    let values = match raw(prim, &format!("{name}:indices"))? {
        None => values,
        Some(indices) => apply_indices(name, &values, &ints(name, indices)?)?,
    };
    Ok(Some(Primvar {
        name: name.into(),
        values,
        interpolation,
    }))
}

fn apply_indices<T: Copy>(name: &str, values: &[T], indices: &[i64]) -> Result<Vec<T>, PrimFault> {
    indices
        .iter()
        .map(|&i| {
            usize::try_from(i)
                .ok()
                .and_then(|i| values.get(i).copied())
                .ok_or(PrimFault::Index {
                    attribute: format!("{name}:indices"),
                    index: i,
                    values: values.len(),
                })
        })
        .collect()
}
