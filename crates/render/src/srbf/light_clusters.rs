//! The frame's lights grouped by direction, for multiple scattering
//! ([`crate::srbf::dual_scattering::Dual::shade_clustered`]). Dual scattering spreads each
//! light's energy over a wide cone (the forward spread σ_f, the back-scattering lobes), so the
//! narrow sub-lights that single scattering's shadows need ([`crate::frame::sub_lights`]) can
//! reach it merged, a group per cell of a coarser set of directions.
//!
//! Each light between half the cells' bandwidth and that bandwidth belongs to the cell of a
//! spherical Fibonacci set (spaced ≈ that bandwidth apart) nearest its centre; a wider light,
//! and a narrower one (a sun: merging would move it by more than its width), is alone. The frame's
//! lights are ordered by cell ([`sort_by_cell`]), so that a group is a run of consecutive
//! lights (the GPU's shading pass reads it so). The grouping depends on the lights only, so
//! it is made once per frame; what a group merges into depends on each point's
//! transmittances and is made there.

use crate::frame::renderer::WorldLight;
use crate::frame::sub_lights::{fibonacci_sphere, max_sub_lights};
use glam::DVec3;
use std::ops::Range;

/// The default bandwidth of the cells: about three sub-lights
/// ([`crate::frame::sub_lights::SPLIT_BANDWIDTH`]) to a group. Wider cells merge more and
/// shade faster, and move multiple scattering further from every light shaded apart
/// (docs/multiple-scattering.md, "Merged lights").
pub const MERGE_BANDWIDTH: f64 = 0.5;

/// The most cells: a bandwidth below ≈ 0.055 groups only the lights narrower than it, in cells
/// that fine.
const MAX_CELLS: usize = 4096;

/// Lights within this relative difference of half a cell's bandwidth count as that wide (the
/// sub-lights' f32 bandwidth).
const WIDTH_TOLERANCE: f64 = 1e-6;

/// Each light's cell: the index of its cell, or a number past every cell (its own) for a light
/// that is alone.
fn cells_of(lights: &[WorldLight], bandwidth: f64) -> Vec<usize> {
    let grouped = |l: &WorldLight| {
        l.bandwidth > 0.0
            && l.bandwidth <= bandwidth
            && 2.0 * l.bandwidth >= bandwidth * (1.0 - WIDTH_TOLERANCE)
    };
    let cells = if lights.iter().any(grouped) {
        fibonacci_sphere(max_sub_lights(bandwidth).min(MAX_CELLS))
    } else {
        Vec::new()
    };
    lights
        .iter()
        .enumerate()
        .map(|(j, l)| match grouped(l) {
            true => nearest(&cells, l.direction),
            false => cells.len() + j,
        })
        .collect()
}

/// The index of the direction of `cells` nearest `d`.
fn nearest(cells: &[DVec3], d: DVec3) -> usize {
    (0..cells.len())
        .max_by(|&a, &b| cells[a].dot(d).total_cmp(&cells[b].dot(d)))
        .unwrap_or(0)
}

/// Orders `lights` by cell (a stable sort: the lights of a cell keep their order), so that
/// [`LightClusters::of`] finds each cell's lights as one group.
pub fn sort_by_cell(lights: &mut Vec<WorldLight>, bandwidth: f64) {
    let cells = cells_of(lights, bandwidth);
    let mut keyed: Vec<(usize, WorldLight)> = cells.into_iter().zip(lights.drain(..)).collect();
    keyed.sort_by_key(|&(cell, _)| cell);
    lights.extend(keyed.into_iter().map(|(_, l)| l));
}

/// A frame's lights in groups: runs of consecutive lights in one cell.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LightClusters {
    /// Where each group starts, and the number of lights last.
    starts: Vec<usize>,
}

impl LightClusters {
    /// The runs of consecutive `lights` that share a cell of `bandwidth` (0: each light
    /// alone). Lights ordered by [`sort_by_cell`] give one group per cell.
    pub fn of(lights: &[WorldLight], bandwidth: f64) -> Self {
        let cells = cells_of(lights, bandwidth);
        let mut starts: Vec<usize> = (0..cells.len())
            .filter(|&j| j == 0 || cells[j] != cells[j - 1])
            .collect();
        starts.push(cells.len());
        Self { starts }
    }

    /// The groups, each a non-empty range of light indices.
    pub fn groups(&self) -> impl Iterator<Item = Range<usize>> + '_ {
        self.starts.windows(2).map(|w| w[0]..w[1])
    }

    /// How many groups.
    pub fn len(&self) -> usize {
        self.starts.len().saturating_sub(1)
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// For each light, the end of its group if it starts one, else 0 (the GPU's `group_end`).
    pub fn group_ends(&self) -> Vec<u32> {
        let mut ends = vec![0; self.starts.last().copied().unwrap_or(0)];
        for g in self.groups() {
            ends[g.start] = g.end as u32;
        }
        ends
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frame::sub_lights::fibonacci_sphere;

    fn light(direction: DVec3, bandwidth: f64) -> WorldLight {
        WorldLight {
            direction,
            bandwidth,
            radiance: DVec3::ONE,
        }
    }

    /// Sub-lights 0.3 apart, a wide light and a directional one: after sorting, every group is
    /// one cell's lights (no cell split in two runs, no two cells in one run), the groups
    /// cover every light once, and a light wider than the cells is alone.
    #[test]
    fn sorted_lights_group_by_cell() {
        let mut lights: Vec<WorldLight> = fibonacci_sphere(140)
            .into_iter()
            .map(|d| light(d, 0.3))
            .collect();
        lights.insert(7, light(DVec3::Z, 2.0));
        lights.push(light(DVec3::X, 0.0));
        // A sun beside sub-lights.
        lights.push(light(fibonacci_sphere(140)[3], 0.05));
        sort_by_cell(&mut lights, MERGE_BANDWIDTH);
        let cells = cells_of(&lights, MERGE_BANDWIDTH);
        let clusters = LightClusters::of(&lights, MERGE_BANDWIDTH);
        let groups: Vec<Range<usize>> = clusters.groups().collect();
        assert_eq!(groups.iter().map(|g| g.len()).sum::<usize>(), lights.len());
        assert!(groups.windows(2).all(|w| w[0].end == w[1].start));
        for g in &groups {
            assert!(cells[g.clone()].iter().all(|&c| c == cells[g.start]));
        }
        let firsts: Vec<usize> = groups.iter().map(|g| cells[g.start]).collect();
        let mut distinct = firsts.clone();
        distinct.dedup();
        assert_eq!(firsts, distinct, "a cell split into two runs");
        for (j, l) in lights.iter().enumerate() {
            if 2.0 * l.bandwidth < MERGE_BANDWIDTH || l.bandwidth > MERGE_BANDWIDTH {
                assert!(groups.contains(&(j..j + 1)), "light {j} not alone");
            }
        }
        // About three sub-lights a cell, as the default's doc says.
        let merged = groups.iter().filter(|g| g.len() > 1).count();
        assert!((30..=60).contains(&merged), "{merged} merged groups");
        let in_groups: usize = groups.iter().filter(|g| g.len() > 1).map(|g| g.len()).sum();
        assert!(in_groups >= 120, "{in_groups} of 140 sub-lights merged");
        let ends = clusters.group_ends();
        for g in &groups {
            assert_eq!(ends[g.start], g.end as u32);
            assert!(ends[g.start + 1..g.end].iter().all(|&e| e == 0));
        }
    }

    /// Bandwidth 0 leaves every light alone, and so do cells narrower than every light or
    /// more than twice as wide.
    #[test]
    fn no_merging_at_zero() {
        let lights: Vec<WorldLight> = fibonacci_sphere(50)
            .into_iter()
            .map(|d| light(d, 0.3))
            .collect();
        for bandwidth in [0.0, 0.2, 0.7] {
            let clusters = LightClusters::of(&lights, bandwidth);
            assert_eq!(clusters.len(), lights.len(), "bandwidth {bandwidth}");
            assert!(clusters.groups().all(|g| g.len() == 1));
        }
    }
}
