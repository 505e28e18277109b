//! The strands as the renderers get them: each strand the polyline the path tracer draws, with
//! its diameter per point, and the strands grouped by absorption (one material per group).
//!
//! A point closer to the previous kept point than a thousandth of that point's radius is a
//! repeat and is dropped, as `cuticle_trace::tubes` drops it (a zero-length segment has no
//! direction; pbrt-v4's Bézier and Mitsuba's linear curve would meet a degenerate segment). A
//! strand left with fewer than two points is not written, and counted.

use crate::{Absorption, ExportError};
use cuticle_groom::Groom;
use glam::{DVec3, Vec3};

/// Distances below this fraction of the radius are repeated points (the trace crate's rule).
const MIN_LENGTH_OVER_RADIUS: f32 = 1e-3;

/// One strand as written: its points and each point's diameter (the groom's thickness).
#[derive(Clone, Debug, PartialEq)]
pub struct Polyline {
    /// The strand's index in the groom.
    pub strand: usize,
    pub points: Vec<Vec3>,
    pub diameters: Vec<f32>,
}

/// The strands that share one absorption.
#[derive(Clone, Debug, PartialEq)]
pub struct Group {
    /// σ_a per unit radius.
    pub sigma_a: DVec3,
    pub strands: Vec<Polyline>,
}

/// The groom's strands by absorption, in order of each absorption's first strand.
#[derive(Clone, Debug, PartialEq)]
pub struct Grouped {
    pub groups: Vec<Group>,
    /// Strands of fewer than two distinct points, not written.
    pub skipped: usize,
}

impl Grouped {
    pub fn strand_count(&self) -> usize {
        self.groups.iter().map(|g| g.strands.len()).sum()
    }

    pub fn point_count(&self) -> usize {
        self.groups
            .iter()
            .flat_map(|g| &g.strands)
            .map(|s| s.points.len())
            .sum()
    }
}

/// Strand `s` of `groom` without repeated points.
pub fn polyline(groom: &Groom, s: usize) -> Polyline {
    let (positions, thickness) = (groom.positions(), groom.thickness());
    let mut line = Polyline {
        strand: s,
        points: Vec::new(),
        diameters: Vec::new(),
    };
    for i in groom.strand_range(s) {
        let keep = match (line.points.last(), line.diameters.last()) {
            (Some(&p), Some(&d)) => {
                (positions[i] - p).length() > MIN_LENGTH_OVER_RADIUS * 0.5 * d.abs().max(1e-12)
            }
            _ => true,
        };
        if keep {
            line.points.push(positions[i]);
            line.diameters.push(thickness[i].abs());
        }
    }
    line
}

/// Every strand of two or more distinct points, grouped by its absorption.
pub fn grouped(groom: &Groom, sigma_a: &Absorption) -> Result<Grouped, ExportError> {
    let mut out = Grouped {
        groups: Vec::new(),
        skipped: 0,
    };
    for s in 0..groom.strand_count() {
        let line = polyline(groom, s);
        if line.points.len() < 2 {
            out.skipped += 1;
            continue;
        }
        let value = match sigma_a {
            Absorption::Uniform(v) => *v,
            Absorption::PerStrand(v) => v[s],
        };
        match out.groups.iter_mut().find(|g| g.sigma_a == value) {
            Some(g) => g.strands.push(line),
            None => out.groups.push(Group {
                sigma_a: value,
                strands: vec![line],
            }),
        }
    }
    if out.groups.is_empty() {
        return Err(ExportError::NoStrands);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use cuticle_groom::GroomParts;

    fn groom() -> Groom {
        let p = |x: f32, z: f32| Vec3::new(x, 0.0, z);
        Groom::from_parts(GroomParts {
            positions: vec![
                p(0.0, 0.0),
                p(0.0, 1.0),
                p(0.0, 1.0),
                p(0.0, 2.0),
                p(1.0, 0.0),
                p(1.0, 1.0),
                p(2.0, 0.0),
                p(2.0, 0.0),
            ],
            thickness: vec![0.1, 0.08, 0.08, 0.06, 0.1, 0.1, 0.1, 0.1],
            strand_offsets: vec![0, 4, 6, 8],
            ..GroomParts::default()
        })
        .unwrap()
    }

    /// Repeats are dropped with their diameter, a strand of one distinct point is skipped, and
    /// strands of the same absorption share a group, in first-seen order.
    #[test]
    fn strands_lose_repeats_and_group_by_absorption() {
        let g = groom();
        let line = polyline(&g, 0);
        assert_eq!(line.points.len(), 3);
        assert_eq!(line.diameters, vec![0.1, 0.08, 0.06]);
        let (a, b) = (DVec3::new(1.0, 2.0, 3.0), DVec3::new(0.5, 0.5, 0.5));
        let grouped = grouped(&g, &Absorption::PerStrand(vec![a, b, a])).unwrap();
        assert_eq!(grouped.skipped, 1);
        assert_eq!(grouped.groups.len(), 2);
        assert_eq!(grouped.groups[0].sigma_a, a);
        assert_eq!(grouped.groups[1].strands[0].strand, 1);
        assert_eq!(grouped.strand_count(), 2);
        assert_eq!(grouped.point_count(), 5);
        let one = super::grouped(&g, &Absorption::Uniform(a)).unwrap();
        assert_eq!(one.groups.len(), 1);
    }
}
