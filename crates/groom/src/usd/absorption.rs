//! Per-strand absorption from a prim's primvars, and the primvars that write it back.
//!
//! Read, first match wins for the whole prim:
//! 1. `cuticle:absorption_source` (int per curve, written by cuticle: 0 none, 1 `sigma_a`,
//!    2 `eumelanin`/`pheomelanin`) picks each strand's own, so a written groom reads back
//!    exactly;
//! 2. `eumelanin` and/or `pheomelanin`: concentrations as cuticle's melanin model takes them;
//! 3. `melanin` (and `melanin_redness`, default 0), Blender's principled-hair amounts in
//!    [0, 1], turned into concentrations as Cycles does: c = −ln(max(1 − melanin, 10⁻⁴)),
//!    eumelanin = c·(1 − redness), pheomelanin = c·redness (the concentrations then go through
//!    cuticle's melanin model, d'Eon et al. 2011's absorption, not Cycles' own constants);
//! 4. `sigma_a`: μ_a per unit radius, RGB;
//! 5. `displayColor`, then `color`: a colour, turned into μ_a by
//!    [`cuticle_fiber::optics::absorption::mu_a_from_color`] at
//!    [`cuticle_fiber::optics::absorption::COLOUR_BETA_N`], the window's colour mapping.
//!
//! Each may be constant, uniform (per curve), varying or vertex; a curve with several values
//! takes their mean.

use super::curves::Layout;
use super::error::PrimFault;
use super::values::{self, Interpolation, Primvar};
use crate::appearance::Absorption;
use cuticle_fiber::optics::absorption::{COLOUR_BETA_N, mu_a_from_color};
use glam::DVec3;
use openusd::usd::Prim;

/// Primvar names, as attributes.
pub const SOURCE: &str = "primvars:cuticle:absorption_source";
pub const SIGMA_A: &str = "primvars:sigma_a";
pub const EUMELANIN: &str = "primvars:eumelanin";
pub const PHEOMELANIN: &str = "primvars:pheomelanin";
pub const MELANIN: &str = "primvars:melanin";
pub const MELANIN_REDNESS: &str = "primvars:melanin_redness";

/// `cuticle:absorption_source` values.
pub const SOURCE_NONE: i32 = 0;
pub const SOURCE_SIGMA_A: i32 = 1;
pub const SOURCE_MELANIN: i32 = 2;

/// Each curve's absorption from `prim`'s primvars (`None` everywhere when it has none).
pub fn read(prim: &Prim, layout: &Layout) -> Result<Vec<Option<Absorption>>, PrimFault> {
    let curves = layout.curves.len();
    let scalar = |name| per_curve(prim, layout, name, values::scalars);
    let vector = |name| per_curve(prim, layout, name, values::vec3s);
    let source = per_curve(prim, layout, SOURCE, |n, v| {
        Ok(values::ints(n, v)?.into_iter().map(|i| i as f64).collect())
    })?;
    let (eu, pheo) = (scalar(EUMELANIN)?, scalar(PHEOMELANIN)?);
    let sigma = vector(SIGMA_A)?;
    non_negative(EUMELANIN, eu.as_deref())?;
    non_negative(PHEOMELANIN, pheo.as_deref())?;
    if let Some(s) = &sigma {
        let flat: Vec<f64> = s.iter().flat_map(|v| v.to_array()).collect();
        non_negative(SIGMA_A, Some(&flat))?;
    }
    let melanin_of = |c: usize| Absorption::Melanin {
        eumelanin: eu.as_ref().map_or(0.0, |v| v[c]) as f32,
        pheomelanin: pheo.as_ref().map_or(0.0, |v| v[c]) as f32,
    };
    let sigma_of = |c: usize, s: &Vec<DVec3>| Absorption::MuA(s[c].as_vec3().to_array());
    if let Some(source) = source {
        return (0..curves)
            .map(|c| match source[c] as i32 {
                SOURCE_MELANIN if eu.is_some() || pheo.is_some() => Ok(Some(melanin_of(c))),
                SOURCE_SIGMA_A if sigma.is_some() => Ok(Some(sigma_of(c, sigma.as_ref().unwrap()))),
                SOURCE_NONE => Ok(None),
                other => Err(PrimFault::Unsupported {
                    attribute: "primvars:cuticle:absorption_source",
                    value: other.to_string(),
                    takes: "0 (none), 1 (with sigma_a) or 2 (with eumelanin/pheomelanin)",
                }),
            })
            .collect();
    }
    if eu.is_some() || pheo.is_some() {
        return Ok((0..curves).map(|c| Some(melanin_of(c))).collect());
    }
    if let Some(m) = scalar(MELANIN)? {
        return blender_melanin(&m, scalar(MELANIN_REDNESS)?.as_deref());
    }
    if let Some(s) = &sigma {
        return Ok((0..curves).map(|c| Some(sigma_of(c, s))).collect());
    }
    for name in ["primvars:displayColor", "primvars:color"] {
        if let Some(colours) = vector(name)? {
            return Ok(colours
                .iter()
                .map(|c| {
                    let m = mu_a_from_color(*c, COLOUR_BETA_N);
                    Some(Absorption::MuA(m.as_vec3().to_array()))
                })
                .collect());
        }
    }
    Ok(vec![None; curves])
}

/// Blender's melanin amount and redness (each in [0, 1]) as concentrations, per curve.
fn blender_melanin(
    melanin: &[f64],
    redness: Option<&[f64]>,
) -> Result<Vec<Option<Absorption>>, PrimFault> {
    fraction(MELANIN, melanin)?;
    if let Some(r) = redness {
        fraction(MELANIN_REDNESS, r)?;
    }
    Ok(melanin
        .iter()
        .enumerate()
        .map(|(c, &m)| {
            let r = redness.map_or(0.0, |r| r[c]);
            let amount = -(1.0 - m).max(1e-4).ln();
            Some(Absorption::Melanin {
                eumelanin: (amount * (1.0 - r)) as f32,
                pheomelanin: (amount * r) as f32,
            })
        })
        .collect())
}

/// Primvar `name` as one value per curve (the mean of a curve's values), checked.
fn per_curve<T: Copy + std::iter::Sum + std::ops::Div<f64, Output = T>>(
    prim: &Prim,
    layout: &Layout,
    name: &str,
    decode: impl Fn(&str, openusd::sdf::Value) -> Result<Vec<T>, PrimFault>,
) -> Result<Option<Vec<T>>, PrimFault> {
    let Some(p): Option<Primvar<T>> = values::primvar(prim, name, Interpolation::Constant, decode)?
    else {
        return Ok(None);
    };
    layout.check(&p)?;
    let per = (0..layout.curves.len())
        .map(|c| {
            let v = layout.values_of(&p, c);
            v.iter().copied().sum::<T>() / v.len() as f64
        })
        .collect();
    Ok(Some(per))
}

fn non_negative(name: &str, values: Option<&[f64]>) -> Result<(), PrimFault> {
    match values.and_then(|v| v.iter().position(|&x| x < 0.0).map(|i| (i, v[i]))) {
        Some((index, value)) => Err(PrimFault::Negative {
            attribute: name.into(),
            index,
            value,
        }),
        None => Ok(()),
    }
}

fn fraction(name: &str, values: &[f64]) -> Result<(), PrimFault> {
    match values.iter().position(|&x| !(0.0..=1.0).contains(&x)) {
        Some(index) => Err(PrimFault::NotAFraction {
            attribute: name.into(),
            index,
            value: values[index],
        }),
        None => Ok(()),
    }
}
