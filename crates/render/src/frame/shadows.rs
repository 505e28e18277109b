//! Self-shadowing: the effective transmittance T̃(ω_j, λ_j) of each SRBF light (Xu et al. 2011 eq.
//! 2).
//!
//! Choice: a deep opacity map (Yuksel & Keyser 2008) per light, orthographic along the light,
//! whose layers are box-filtered with a summed-area table to the light's bandwidth — the idea of
//! Ren et al. 2010's convolution optical depth map (an SRBF of width λ seen from a point at depth
//! z behind the first hair averages the optical depth over a disc of radius ≈ zλ), on the layered
//! map rather than their one optical-depth map. Why: deep opacity layers start at each texel's
//! first hair, so a point's own strand does not shadow it and the depth resolution sits where
//! hair is, with no bias to tune; the summed-area table makes the filter cost independent of λ,
//! so wide sky lights cost what a sun costs. Optical depth counts projected fiber area per texel
//! area (a fiber blocks what it covers), T̃ = exp(−depth).

use crate::frame::sub_lights::SPLIT_BANDWIDTH;
use crate::scene::camera::NEAR;
use crate::srbf::light_clusters::MERGE_BANDWIDTH;
use cuticle_groom::Groom;
use glam::DVec3;
use rayon::prelude::*;

/// Settings of the opacity maps.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ShadowOptions {
    /// Texels along each side of a map.
    pub resolution: usize,
    /// Multiplies the optical depth (1: physical; 0: no shadows).
    pub density: f64,
    /// Transmittance T̃ below which a light's direct contribution (single scattering, and dual
    /// scattering's local term of the direct light) is skipped: each skipped light gives less
    /// than this fraction of what it gives an unshadowed point. 0 skips nothing. A quarter of
    /// the default scene's (point, light) pairs lie deep enough to fall below 1e-4.
    pub cutoff: f64,
    /// Bandwidth λ_s of the sub-lights that replace every light wider than √2 λ_s, each with its
    /// own map ([`crate::frame::sub_lights`]); from 20 up nothing is split (one map per light).
    pub split_bandwidth: f64,
    /// Bandwidth of the cells in which the lights between half as wide and as wide as it are
    /// merged, point by point, for multiple scattering ([`crate::srbf::light_clusters`]); 0
    /// merges none (the reference).
    pub merge_bandwidth: f64,
}

impl Default for ShadowOptions {
    fn default() -> Self {
        Self {
            resolution: 256,
            density: 1.0,
            cutoff: 1e-4,
            split_bandwidth: SPLIT_BANDWIDTH,
            merge_bandwidth: MERGE_BANDWIDTH,
        }
    }
}

impl ShadowOptions {
    /// Whether a light of transmittance `t` adds direct light.
    pub fn passes(&self, t: f64) -> bool {
        t > 0.0 && t >= self.cutoff
    }
}

/// Layer boundaries behind the first hair, as fractions of the groom's bounding radius (pub,
/// with [`MapFrame`]: the GPU's twin builds the same maps).
pub const LAYERS: [f64; 7] = [0.0, 0.005, 0.015, 0.035, 0.075, 0.155, 0.4];
/// Layers of a map.
pub const NL: usize = LAYERS.len() - 1;

/// Where one light's map lies: orthographic along the light's travel over the groom's
/// bounding sphere, `n` texels a side.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MapFrame {
    pub n: usize,
    pub centre: DVec3,
    /// u, v across the map and the light's travel (depth grows along it).
    pub axes: [DVec3; 3],
    pub radius: f64,
    pub texel: f64,
}

impl MapFrame {
    /// The frame of light arriving from `toward_light` (a unit vector pointing at the light).
    pub fn new(groom: &Groom, toward_light: DVec3, n: usize) -> Self {
        let b = groom.bounds();
        let (lo, hi) = (b.min.as_dvec3(), b.max.as_dvec3());
        let centre = 0.5 * (lo + hi);
        let radius = (0.5 * (hi - lo).length()).max(NEAR);
        let travel = -toward_light.normalize();
        let u = travel.any_orthonormal_vector();
        let v = travel.cross(u);
        Self {
            n,
            centre,
            axes: [u, v, travel],
            radius,
            texel: 2.0 * radius / n as f64,
        }
    }
}

/// The most samples a point's segment may make for a map to keep them between its two passes:
/// above what the default scene and straight.hair make (BENCHMARKS.md), so that they keep
/// theirs, and a bound on what a map of long segments may hold.
pub const KEPT_SAMPLES_PER_POINT: usize = 6;

/// A point along a segment, as a map's two passes read it: its texel, depth along the light's
/// travel and optical depth.
#[derive(Clone, Copy)]
struct Sample {
    texel: u32,
    depth: f32,
    area: f64,
}

/// One light's deep opacity map.
struct OpacityMap {
    n: usize,
    centre: DVec3,
    axes: [DVec3; 3],
    radius: f64,
    texel: f64,
    /// Depth (along the light's travel) of the first hair per texel.
    first: Vec<f32>,
    /// Summed-area tables of each layer's optical depth, the layers of a texel side by side
    /// (one cache line holds what a corner of a box reads for every layer).
    sat: Vec<[f64; NL]>,
}

/// T̃ of each light at each of `points`: `out[p * lights + j]`. `bandwidths` are the lights' λ_j
/// (0 for a directional light). Parallel over lights.
pub fn transmittance(
    groom: &Groom,
    points: &[u32],
    directions: &[DVec3],
    bandwidths: &[f64],
    options: &ShadowOptions,
) -> Vec<f32> {
    let nl = directions.len();
    let mut out = vec![1.0f32; points.len() * nl];
    if options.density <= 0.0 || groom.point_count() == 0 || points.is_empty() {
        return out;
    }
    let columns: Vec<Vec<f32>> = directions
        .par_iter()
        .zip(bandwidths.par_iter())
        .map(|(&dir, &lambda)| {
            let map = OpacityMap::build(groom, dir, options.resolution);
            points
                .iter()
                .map(|&p| {
                    let x = groom.positions()[p as usize].as_dvec3();
                    (-options.density * map.depth(x, lambda)).exp() as f32
                })
                .collect()
        })
        .collect();
    for (j, col) in columns.iter().enumerate() {
        for (p, &v) in col.iter().enumerate() {
            out[p * nl + j] = v;
        }
    }
    out
}

/// Deep opacity maps of directional lights (λ = 0), kept to read T̃ at any world point
/// (where the groom may later be sampled, not only at its points).
pub struct DirectionalShadows {
    maps: Vec<OpacityMap>,
    density: f64,
}

impl DirectionalShadows {
    /// One map per direction (unit vectors toward the lights), parallel over them.
    pub fn build(groom: &Groom, directions: &[DVec3], options: &ShadowOptions) -> Self {
        let maps = if options.density <= 0.0 || groom.point_count() == 0 {
            Vec::new()
        } else {
            directions
                .par_iter()
                .map(|&d| OpacityMap::build(groom, d, options.resolution))
                .collect()
        };
        Self {
            maps,
            density: options.density,
        }
    }

    /// Each light's T̃ at world point `x`, in the order of the directions (none with no maps).
    pub fn transmittances(&self, x: DVec3) -> Vec<f64> {
        self.maps
            .iter()
            .map(|m| (-self.density * m.depth(x, 0.0)).exp())
            .collect()
    }
}

impl OpacityMap {
    /// The map of light arriving from `toward_light` (a unit vector pointing at the light).
    fn build(groom: &Groom, toward_light: DVec3, n: usize) -> Self {
        Self::build_keeping(groom, toward_light, n, KEPT_SAMPLES_PER_POINT)
    }

    /// [`Self::build`] keeping the samples between the passes where there are at most
    /// `kept_per_point` a point.
    fn build_keeping(groom: &Groom, toward_light: DVec3, n: usize, kept_per_point: usize) -> Self {
        let MapFrame {
            centre,
            axes,
            radius,
            texel,
            ..
        } = MapFrame::new(groom, toward_light, n);
        let mut map = Self {
            n,
            centre,
            axes,
            radius,
            texel,
            first: Vec::new(),
            sat: Vec::new(),
        };
        // Two passes over the same samples: the first hair of each texel, then each sample's
        // optical depth into its layer behind it. The samples are kept between the passes
        // (16 bytes each, freed with the build) where there are at most `kept_per_point` a
        // point, and generated twice beyond; the same samples in the same order either way.
        let locals: Vec<DVec3> = groom
            .positions()
            .iter()
            .map(|p| map.local(p.as_dvec3()))
            .collect();
        let mut first = vec![f32::INFINITY; n * n];
        let count = map.sample_count(groom, &locals);
        let keep = count <= kept_per_point.saturating_mul(locals.len());
        let mut samples = Vec::with_capacity(if keep { count } else { 0 });
        map.for_each_sample(groom, &locals, |k, z, area| {
            first[k] = first[k].min(z);
            if keep {
                samples.push(Sample {
                    texel: k as u32,
                    depth: z,
                    area,
                });
            }
        });
        let mut layers = vec![[0.0f64; NL]; n * n];
        let mut add = |k: usize, z: f32, area: f64| {
            let rel = (z - first[k]) as f64 / radius;
            let l = LAYERS[1..].iter().position(|&b| rel < b).unwrap_or(NL - 1);
            layers[k][l] += area;
        };
        if keep {
            drop(locals);
            for &Sample { texel, depth, area } in &samples {
                add(texel as usize, depth, area);
            }
        } else {
            map.for_each_sample(groom, &locals, add);
        }
        map.first = first;
        map.sat = summed_area(layers, n);
        map
    }

    /// How many samples [`Self::for_each_sample`] makes at most (those off the map are not
    /// passed on).
    fn sample_count(&self, groom: &Groom, locals: &[DVec3]) -> usize {
        (0..groom.strand_count())
            .flat_map(|s| {
                let r = groom.strand_range(s);
                r.start..r.end.saturating_sub(1)
            })
            .map(|i| self.steps(locals[i + 1] - locals[i]))
            .fold(0, usize::saturating_add)
    }

    /// Samples along a segment `d` (in the map's frame): spaced at most a texel across it.
    fn steps(&self, d: DVec3) -> usize {
        (d.truncate().length() / self.texel).ceil().max(1.0) as usize
    }

    /// Calls `f(texel, depth, optical depth)` for points spaced at most a texel along every
    /// segment, `locals` being the groom's points in the map's frame ([`Self::local`]).
    fn for_each_sample(&self, groom: &Groom, locals: &[DVec3], mut f: impl FnMut(usize, f32, f64)) {
        let thick = groom.thickness();
        for s in 0..groom.strand_count() {
            let r = groom.strand_range(s);
            for i in r.start..r.end.saturating_sub(1) {
                let (a, b) = (locals[i], locals[i + 1]);
                let d = b - a;
                let across = d.truncate().length();
                let area =
                    across * 0.5 * (thick[i] + thick[i + 1]) as f64 / (self.texel * self.texel);
                let steps = self.steps(d);
                for k in 0..steps {
                    let p = a + d * ((k as f64 + 0.5) / steps as f64);
                    if let Some(t) = self.texel_of(p) {
                        f(t, p.z as f32, area / steps as f64);
                    }
                }
            }
        }
    }

    fn local(&self, p: DVec3) -> DVec3 {
        let d = p - self.centre;
        DVec3::new(
            d.dot(self.axes[0]),
            d.dot(self.axes[1]),
            d.dot(self.axes[2]),
        )
    }

    /// The texel under `p` (in the map's frame), if inside. Truncation is the floor here, for
    /// the coordinates it is applied to are checked non-negative first (and it is inlined,
    /// where the baseline x86-64 build calls libm's `floor`).
    fn texel_of(&self, p: DVec3) -> Option<usize> {
        let x = (p.x + self.radius) / self.texel;
        let y = (p.y + self.radius) / self.texel;
        let n = self.n as f64;
        (x >= 0.0 && y >= 0.0 && x < n && y < n).then(|| y as usize * self.n + x as usize)
    }

    /// Optical depth in front of world point `x`, each layer averaged over a square of half
    /// side max(½ texel, λ × the layer's distance behind the first hair).
    fn depth(&self, x: DVec3, lambda: f64) -> f64 {
        let p = self.local(x);
        let Some(k) = self.texel_of(p) else {
            return 0.0;
        };
        let first = self.first[k];
        if !first.is_finite() {
            return 0.0;
        }
        let rel = (p.z as f32 - first) as f64 / self.radius;
        let mut total = 0.0;
        for l in 0..NL {
            let (b0, b1) = (LAYERS[l], LAYERS[l + 1]);
            let share = ((rel - b0) / (b1 - b0)).clamp(0.0, 1.0);
            if share == 0.0 {
                break;
            }
            let reach = lambda * 0.5 * (b0 + b1) * self.radius;
            total += share * self.box_mean(l, p, reach);
        }
        total
    }

    /// Mean of layer `l` over the texels within `reach` of p (at least p's own texel).
    fn box_mean(&self, l: usize, p: DVec3, reach: f64) -> f64 {
        let n = self.n as i64;
        // p lies in the map (its texel was found) and reach ≥ 0: truncation is the floor.
        let cx = ((p.x + self.radius) / self.texel) as i64;
        let cy = ((p.y + self.radius) / self.texel) as i64;
        let r = (reach / self.texel).max(0.0).min(n as f64) as i64;
        let (x0, x1) = ((cx - r).max(0), (cx + r).min(n - 1));
        let (y0, y1) = ((cy - r).max(0), (cy + r).min(n - 1));
        let at = |x: i64, y: i64| -> f64 {
            if x < 0 || y < 0 {
                0.0
            } else {
                self.sat[(y * n + x) as usize][l]
            }
        };
        let sum = at(x1, y1) - at(x0 - 1, y1) - at(x1, y0 - 1) + at(x0 - 1, y0 - 1);
        sum / ((x1 - x0 + 1) * (y1 - y0 + 1)) as f64
    }
}

/// Inclusive 2D prefix sums of an n × n grid, each layer on its own.
fn summed_area(mut s: Vec<[f64; NL]>, n: usize) -> Vec<[f64; NL]> {
    for y in 0..n {
        for x in 1..n {
            let left = s[y * n + x - 1];
            for (v, l) in s[y * n + x].iter_mut().zip(left) {
                *v += l;
            }
        }
    }
    for y in 1..n {
        for x in 0..n {
            let below = s[(y - 1) * n + x];
            for (v, b) in s[y * n + x].iter_mut().zip(below) {
                *v += b;
            }
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use cuticle_groom::procedural::{GroomParams, Preset, generate};

    /// A map built from kept samples is the one built from samples generated twice, bit for
    /// bit, for a groom whose segments make a few samples a point and for one of long
    /// segments that make dozens (the case the kept path leaves to the other).
    #[test]
    fn kept_samples_make_the_same_map() {
        let fine = generate(&GroomParams {
            strands: 60,
            ..Preset::Wavy.params()
        })
        .unwrap();
        let coarse = cuticle_groom::Groom::from_parts(cuticle_groom::GroomParts {
            positions: vec![
                glam::Vec3::new(-5.0, 0.0, 0.0),
                glam::Vec3::new(5.0, 0.0, 0.0),
                glam::Vec3::new(0.0, -5.0, 1.0),
                glam::Vec3::new(0.0, 5.0, 1.0),
            ],
            thickness: vec![0.05; 4],
            strand_offsets: vec![0, 2, 4],
            ..cuticle_groom::GroomParts::default()
        })
        .unwrap();
        for (name, groom) in [("fine", &fine), ("coarse", &coarse)] {
            let light = DVec3::new(0.3, 0.4, 0.87).normalize();
            let kept = OpacityMap::build_keeping(groom, light, 64, usize::MAX);
            let locals: Vec<DVec3> = groom
                .positions()
                .iter()
                .map(|p| kept.local(p.as_dvec3()))
                .collect();
            let per_point = kept.sample_count(groom, &locals) as f64 / locals.len() as f64;
            println!("{name}: {per_point:.1} samples a point");
            // The coarse groom is one the default build regenerates instead of keeping.
            assert_eq!(
                name == "coarse",
                per_point > KEPT_SAMPLES_PER_POINT as f64,
                "{name}"
            );
            let again = OpacityMap::build_keeping(groom, light, 64, 0);
            assert!(
                kept.sat.iter().any(|t| t.iter().any(|&v| v > 0.0)),
                "{name}: empty"
            );
            assert_eq!(kept.first, again.first, "{name}");
            assert_eq!(kept.sat, again.sat, "{name}");
        }
    }
}
