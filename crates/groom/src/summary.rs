//! [`HairFileSummary`]: what `cuticle groom info` reports about a file.

use crate::geometry::{Aabb, polyline_length};
use crate::hair_file::{ArrayFlags, HairDefaults, HairFile};
use serde::Serialize;

/// Minimum, mean, median and maximum of a set of numbers.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Stats {
    pub min: f64,
    pub mean: f64,
    pub median: f64,
    pub max: f64,
}

impl Stats {
    /// Statistics of `values`, or `None` when there are none.
    pub fn of(values: impl IntoIterator<Item = f64>) -> Option<Self> {
        let mut sorted: Vec<f64> = values.into_iter().collect();
        if sorted.is_empty() {
            return None;
        }
        sorted.sort_by(f64::total_cmp);
        let n = sorted.len();
        let median = if n % 2 == 1 {
            sorted[n / 2]
        } else {
            0.5 * (sorted[n / 2 - 1] + sorted[n / 2])
        };
        Some(Self {
            min: sorted[0],
            mean: sorted.iter().sum::<f64>() / n as f64,
            median,
            max: sorted[n - 1],
        })
    }
}

/// A box as plain arrays, for reports.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct BoundsSummary {
    pub min: [f32; 3],
    pub max: [f32; 3],
    pub size: [f32; 3],
}

impl From<Aabb> for BoundsSummary {
    fn from(b: Aabb) -> Self {
        Self {
            min: b.min.to_array(),
            max: b.max.to_array(),
            size: b.size().to_array(),
        }
    }
}

/// Counts, present arrays, defaults, bounds and strand statistics of a `.hair` file.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct HairFileSummary {
    pub strands: u32,
    pub points: u32,
    /// The header's flag word.
    pub flags: u32,
    pub arrays: ArrayFlags,
    pub defaults: HairDefaults,
    pub info: String,
    pub points_per_strand: Option<Stats>,
    /// `None` when the file has no points array (or no points).
    pub bounds: Option<BoundsSummary>,
    /// Arc lengths of the strands; `None` without points.
    pub strand_length: Option<Stats>,
}

impl HairFileSummary {
    pub fn of(file: &HairFile) -> Self {
        let points = file.points.as_deref().filter(|p| !p.is_empty());
        Self {
            strands: file.strand_count,
            points: file.point_count,
            flags: file.flags().bits(),
            arrays: file.flags(),
            defaults: file.defaults,
            info: file.info.text(),
            points_per_strand: points_per_strand(file),
            bounds: points.map(|p| Aabb::of_points(p).into()),
            strand_length: points.and_then(|p| {
                Stats::of(
                    file.strand_ranges()
                        .map(|r| f64::from(polyline_length(&p[r]))),
                )
            }),
        }
    }
}

/// Without a segments array every strand has the default count: no need to visit them all.
fn points_per_strand(file: &HairFile) -> Option<Stats> {
    match &file.segments {
        Some(segments) => Stats::of(segments.iter().map(|&s| f64::from(s) + 1.0)),
        None => {
            Stats::of((file.strand_count > 0).then_some(f64::from(file.defaults.segments) + 1.0))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stats_of_odd_and_even_sets() {
        let s = Stats::of([3.0, 1.0, 2.0]).unwrap();
        assert_eq!((s.min, s.mean, s.median, s.max), (1.0, 2.0, 2.0, 3.0));
        assert_eq!(Stats::of([4.0, 1.0, 2.0, 10.0]).unwrap().median, 3.0);
        assert_eq!(Stats::of(std::iter::empty()), None);
    }
}
