//! One `BasisCurves` prim → polylines: counts checked against the basis, points subdivided
//! ([`super::basis`]), widths expanded from their interpolation, everything moved into
//! cuticle's frame.

use super::basis::{Basis, STEPS, Segments};
use super::error::PrimFault;
use super::values::{self, Interpolation, Primvar};
use glam::{DMat4, DVec3};
use openusd::usd::Prim;

/// Diameter of a strand whose prim has no widths: 70 µm, a human hair, in centimetres.
pub const DEFAULT_WIDTH_CM: f64 = 0.007;

/// How a prim's curves are drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    Linear,
    Cubic(Segments),
}

impl Kind {
    /// The prim's `type`, `basis` and `wrap` (USD's fallbacks: cubic, bezier, nonperiodic).
    pub fn of(prim: &Prim) -> Result<Self, PrimFault> {
        let ty = values::token(prim, "type")?.unwrap_or_else(|| "cubic".into());
        let wrap = values::token(prim, "wrap")?.unwrap_or_else(|| "nonperiodic".into());
        let pinned = match wrap.as_str() {
            "nonperiodic" => false,
            "pinned" => true,
            _ => return Err(unsupported("wrap", wrap, "nonperiodic or pinned")),
        };
        match ty.as_str() {
            "linear" => Ok(Self::Linear),
            "cubic" => {
                let name = values::token(prim, "basis")?.unwrap_or_else(|| "bezier".into());
                let basis = Basis::from_token(&name)
                    .ok_or_else(|| unsupported("basis", name, "bezier, bspline or catmullRom"))?;
                Ok(Self::Cubic(Segments { basis, pinned }))
            }
            _ => Err(unsupported("type", ty, "linear or cubic")),
        }
    }

    fn describe(self) -> String {
        match self {
            Self::Linear => "linear".into(),
            Self::Cubic(s) if s.pinned => format!("pinned {}", s.basis.name()),
            Self::Cubic(s) => s.basis.name().into(),
        }
    }

    fn needs(self) -> &'static str {
        match self {
            Self::Linear => "at least 2",
            Self::Cubic(s) if s.basis == Basis::Bezier => "4, 7, 10, … (3 per segment + 1)",
            Self::Cubic(s) if s.pinned => "at least 2",
            Self::Cubic(_) => "at least 4",
        }
    }

    /// Segments of a curve of `n` points (linear: n − 1), or `None` if `n` makes no curve.
    fn segments(self, n: usize) -> Option<usize> {
        match self {
            Self::Linear => (n >= 2).then(|| n - 1),
            Self::Cubic(s) => s.count(n),
        }
    }

    /// Values per curve of a `varying` primvar.
    fn varying(self, n: usize, segments: usize) -> usize {
        match self {
            Self::Linear => n,
            Self::Cubic(_) => segments + 1,
        }
    }

    /// Polyline points of a curve of `segments`.
    fn out_points(self, n: usize, segments: usize) -> usize {
        match self {
            Self::Linear => n,
            Self::Cubic(_) => segments * STEPS + 1,
        }
    }
}

fn unsupported(attribute: &'static str, value: String, takes: &'static str) -> PrimFault {
    PrimFault::Unsupported {
        attribute,
        value,
        takes,
    }
}

/// One curve's place in the prim's arrays.
#[derive(Clone, Copy, Debug)]
pub struct Curve {
    /// Its first control point, and how many it has.
    pub first: usize,
    pub points: usize,
    /// Its first `varying` value, and its segments.
    pub first_varying: usize,
    pub segments: usize,
}

/// A prim's curves, counted and checked, before anything is evaluated.
pub struct Layout {
    pub kind: Kind,
    pub curves: Vec<Curve>,
    pub points: usize,
    pub varying: usize,
    /// Polyline points all curves will make.
    pub out_points: u64,
}

impl Layout {
    /// The layout of `counts` (`curveVertexCounts`) over `points` control points.
    pub fn new(kind: Kind, counts: &[i64], points: usize) -> Result<Self, PrimFault> {
        let mut curves = Vec::with_capacity(counts.len());
        let (mut first, mut first_varying, mut out_points) = (0usize, 0usize, 0u64);
        for (curve, &count) in counts.iter().enumerate() {
            let segments = usize::try_from(count)
                .ok()
                .and_then(|n| kind.segments(n))
                .ok_or_else(|| PrimFault::TooFewPoints {
                    curve,
                    count,
                    kind: kind.describe(),
                    needs: kind.needs(),
                })?;
            let n = count as usize;
            curves.push(Curve {
                first,
                points: n,
                first_varying,
                segments,
            });
            first = first.saturating_add(n);
            first_varying += kind.varying(n, segments);
            out_points += kind.out_points(n, segments) as u64;
        }
        if first != points {
            let sum = counts.iter().map(|&c| c.max(0) as u64).sum();
            return Err(PrimFault::CountMismatch { sum, points });
        }
        Ok(Self {
            kind,
            curves,
            points,
            varying: first_varying,
            out_points,
        })
    }

    /// Values a primvar of `interpolation` must hold over these curves.
    pub fn expected(&self, interpolation: Interpolation) -> usize {
        match interpolation {
            Interpolation::Constant => 1,
            Interpolation::Uniform => self.curves.len(),
            Interpolation::Varying => self.varying,
            Interpolation::Vertex => self.points,
        }
    }

    /// Checks a primvar's length against its interpolation.
    pub fn check<T>(&self, p: &Primvar<T>) -> Result<(), PrimFault> {
        let expected = self.expected(p.interpolation);
        if p.values.len() != expected {
            return Err(PrimFault::Length {
                attribute: p.name.clone(),
                interpolation: p.interpolation.name().into(),
                expected,
                actual: p.values.len(),
            });
        }
        Ok(())
    }

    /// The values of curve `c` of a checked primvar (one for constant and uniform).
    pub fn values_of<'a, T>(&self, p: &'a Primvar<T>, c: usize) -> &'a [T] {
        let curve = self.curves[c];
        match p.interpolation {
            Interpolation::Constant => &p.values[..1],
            Interpolation::Uniform => &p.values[c..c + 1],
            Interpolation::Varying => {
                let n = self.kind.varying(curve.points, curve.segments);
                &p.values[curve.first_varying..curve.first_varying + n]
            }
            Interpolation::Vertex => &p.values[curve.first..curve.first + curve.points],
        }
    }
}

/// A prim's strands as polylines in cuticle's frame.
pub struct Polylines {
    pub positions: Vec<DVec3>,
    pub widths: Vec<f64>,
    /// Points per strand.
    pub counts: Vec<usize>,
}

/// The strands of `prim`, whose `layout` is checked, with `to_world` its transform into
/// cuticle's frame and `width_scale` what that does to lengths.
pub fn polylines(
    prim: &Prim,
    layout: &Layout,
    control: &[DVec3],
    to_world: DMat4,
    width_scale: f64,
) -> Result<Polylines, PrimFault> {
    let widths = read_widths(prim, layout)?;
    let mut out = Polylines {
        positions: Vec::with_capacity(layout.out_points as usize),
        widths: Vec::with_capacity(layout.out_points as usize),
        counts: Vec::with_capacity(layout.curves.len()),
    };
    for (c, curve) in layout.curves.iter().enumerate() {
        let before = out.positions.len();
        let p = &control[curve.first..curve.first + curve.points];
        match layout.kind {
            Kind::Linear => out.positions.extend_from_slice(p),
            Kind::Cubic(s) => s.evaluate(p, &mut out.positions),
        }
        let made = out.positions.len() - before;
        match &widths {
            None => out
                .widths
                .extend(std::iter::repeat_n(DEFAULT_WIDTH_CM, made)),
            Some(w) => expand_widths(layout, w, c, &mut out.widths),
        }
        out.counts.push(made);
    }
    for p in &mut out.positions {
        *p = to_world.transform_point3(*p);
    }
    for w in &mut out.widths {
        *w = w.max(0.0) * width_scale;
    }
    Ok(out)
}

/// `widths` (or `primvars:widths`), checked: its length, and every width ≥ 0.
fn read_widths(prim: &Prim, layout: &Layout) -> Result<Option<Primvar<f64>>, PrimFault> {
    let mut w = values::primvar(prim, "widths", Interpolation::Vertex, values::scalars)?;
    if w.is_none() {
        w = values::primvar(
            prim,
            "primvars:widths",
            Interpolation::Vertex,
            values::scalars,
        )?;
    }
    let Some(w) = w else { return Ok(None) };
    layout.check(&w)?;
    if let Some(index) = w.values.iter().position(|&x| x < 0.0) {
        return Err(PrimFault::Negative {
            attribute: w.name.clone(),
            index,
            value: w.values[index],
        });
    }
    Ok(Some(w))
}

/// Curve `c`'s widths at its polyline points: constant and uniform repeat, varying interpolates
/// linearly along each segment, vertex follows the basis like the points.
fn expand_widths(layout: &Layout, w: &Primvar<f64>, c: usize, out: &mut Vec<f64>) {
    let curve = layout.curves[c];
    let v = layout.values_of(w, c);
    let made = layout.kind.out_points(curve.points, curve.segments);
    match (w.interpolation, layout.kind) {
        (Interpolation::Constant | Interpolation::Uniform, _) => {
            out.extend(std::iter::repeat_n(v[0], made))
        }
        (_, Kind::Linear) => out.extend_from_slice(v),
        (Interpolation::Vertex, Kind::Cubic(s)) => s.evaluate(v, out),
        (Interpolation::Varying, Kind::Cubic(_)) => {
            out.push(v[0]);
            for pair in v.windows(2) {
                for k in 1..=STEPS {
                    let u = k as f64 / STEPS as f64;
                    out.push(pair[0] + (pair[1] - pair[0]) * u);
                }
            }
        }
    }
}
