//! Drawing strands as thick lines into a supersampled depth buffer.
//!
//! Choice: each pixel holds `ss × ss` subsamples, each keeping the nearest strand segment that
//! covers it (its index and the position t along it). A segment is a capsule of its projected
//! thickness, at least one subsample wide, so hair thinner than a subsample is drawn a little
//! too wide, never dropped. Opaque and depth-tested, the result is order independent and
//! deterministic, and anti-aliased by the ss² subsamples a pixel averages; only the segments
//! left visible are shaded (per vertex, interpolated along t), so shading cost follows the
//! image, not the groom. Rows are split into bands rasterised in parallel.

use crate::scene::camera::{Projected, View};
use cuticle_groom::Groom;
use rayon::prelude::*;

/// No segment covers the subsample.
pub const EMPTY: u32 = u32::MAX;

/// The supersampled visibility of a groom.
#[derive(Clone, Debug)]
pub struct Coverage {
    pub width: usize,
    pub height: usize,
    /// Subsamples per pixel along each axis.
    pub ss: usize,
    /// Per subsample: the first point of the nearest segment, or [`EMPTY`].
    pub segment: Vec<u32>,
    /// Per subsample: position along that segment, 0 at its first point.
    pub t: Vec<f32>,
    depth: Vec<f32>,
}

/// Rows of subsamples per parallel band.
const BAND_ROWS: usize = 16;

impl Coverage {
    /// A visibility buffer drawn elsewhere (the GPU's): `segment` and `t` per subsample,
    /// row-major over `width·ss × height·ss`.
    pub fn from_parts(
        width: usize,
        height: usize,
        ss: usize,
        segment: Vec<u32>,
        t: Vec<f32>,
    ) -> Self {
        assert_eq!(
            segment.len(),
            width * ss * height * ss,
            "one segment per subsample"
        );
        assert_eq!(t.len(), segment.len(), "one t per subsample");
        Self {
            width,
            height,
            ss,
            segment,
            t,
            depth: Vec::new(),
        }
    }

    fn sub_width(&self) -> usize {
        self.width * self.ss
    }

    /// The subsamples of pixel (x, y), as indices into `segment` and `t`.
    pub fn pixel_samples(&self, x: usize, y: usize) -> impl Iterator<Item = usize> + '_ {
        let (ss, sw) = (self.ss, self.sub_width());
        (0..ss * ss).map(move |k| (y * ss + k / ss) * sw + x * ss + k % ss)
    }

    /// Every point index a visible segment starts or ends at, ascending.
    pub fn visible_points(&self, point_count: usize) -> Vec<u32> {
        let mut seen = vec![false; point_count];
        for &s in &self.segment {
            if s != EMPTY {
                seen[s as usize] = true;
                seen[s as usize + 1] = true;
            }
        }
        (0..point_count as u32)
            .filter(|&i| seen[i as usize])
            .collect()
    }

    /// Fraction of pixel (x, y)'s subsamples covered by hair.
    pub fn pixel_fraction(&self, x: usize, y: usize) -> f64 {
        let covered = self
            .pixel_samples(x, y)
            .filter(|&s| self.segment[s] != EMPTY)
            .count();
        covered as f64 / (self.ss * self.ss).max(1) as f64
    }

    /// Fraction of subsamples covered by hair.
    pub fn covered_fraction(&self) -> f64 {
        let n = self.segment.iter().filter(|&&s| s != EMPTY).count();
        n as f64 / self.segment.len().max(1) as f64
    }
}

/// A segment ready to draw: its ends in subsample coordinates and half widths.
#[derive(Clone, Copy, Debug)]
struct Capsule {
    first: u32,
    a: Projected,
    b: Projected,
    half_a: f32,
    half_b: f32,
}

/// Rasterises every segment of `groom` seen through `view` into `width × height` pixels of
/// `ss × ss` subsamples.
pub fn rasterize(groom: &Groom, view: &View, width: usize, height: usize, ss: usize) -> Coverage {
    let ss = ss.max(1);
    let capsules = capsules(groom, view, ss as f32);
    let (sw, sh) = (width * ss, height * ss);
    let bands = sh.div_ceil(BAND_ROWS);
    let mut binned: Vec<Vec<u32>> = vec![Vec::new(); bands];
    for (k, c) in capsules.iter().enumerate() {
        let r = c.half_a.max(c.half_b);
        let lo = (c.a.y.min(c.b.y) - r).floor().max(0.0) as usize / BAND_ROWS;
        let hi = ((c.a.y.max(c.b.y) + r).ceil().max(0.0) as usize / BAND_ROWS)
            .min(bands.saturating_sub(1));
        if c.a.y.min(c.b.y) - r > sh as f32 {
            continue;
        }
        for band in binned.iter_mut().take(hi + 1).skip(lo) {
            band.push(k as u32);
        }
    }
    let mut cov = Coverage {
        width,
        height,
        ss,
        segment: vec![EMPTY; sw * sh],
        t: vec![0.0; sw * sh],
        depth: vec![f32::INFINITY; sw * sh],
    };
    let rows = BAND_ROWS * sw;
    cov.segment
        .par_chunks_mut(rows)
        .zip(cov.t.par_chunks_mut(rows))
        .zip(cov.depth.par_chunks_mut(rows))
        .enumerate()
        .for_each(|(band, ((seg, t), depth))| {
            let mut tile = Tile {
                y0: band * BAND_ROWS,
                rows: seg.len() / sw.max(1),
                width: sw,
                segment: seg,
                t,
                depth,
            };
            for &k in &binned[band] {
                tile.draw(&capsules[k as usize]);
            }
        });
    cov
}

/// Projects every segment with both ends in front of the camera.
fn capsules(groom: &Groom, view: &View, ss: f32) -> Vec<Capsule> {
    let pos = groom.positions();
    let thick = groom.thickness();
    let projected: Vec<Option<Projected>> = pos
        .par_iter()
        .map(|p| {
            view.project(p.as_dvec3()).map(|q| Projected {
                x: q.x * ss,
                y: q.y * ss,
                depth: q.depth,
            })
        })
        .collect();
    let half = |i: usize, q: &Projected| {
        (0.5 * thick[i] as f64 * view.pixels_per_unit(q.depth as f64) * ss as f64).max(0.5) as f32
    };
    let mut out = Vec::with_capacity(groom.segment_count());
    for s in 0..groom.strand_count() {
        let range = groom.strand_range(s);
        for i in range.start..range.end.saturating_sub(1) {
            if let (Some(a), Some(b)) = (projected[i], projected[i + 1]) {
                out.push(Capsule {
                    first: i as u32,
                    a,
                    b,
                    half_a: half(i, &a),
                    half_b: half(i + 1, &b),
                });
            }
        }
    }
    out
}

/// One band of rows of the buffers.
struct Tile<'a> {
    y0: usize,
    rows: usize,
    width: usize,
    segment: &'a mut [u32],
    t: &'a mut [f32],
    depth: &'a mut [f32],
}

impl Tile<'_> {
    /// Covers every subsample centre within the capsule, keeping the nearest.
    fn draw(&mut self, c: &Capsule) {
        let r = c.half_a.max(c.half_b);
        let x_lo = (c.a.x.min(c.b.x) - r).floor().max(0.0) as usize;
        let x_hi = ((c.a.x.max(c.b.x) + r).ceil().max(0.0) as usize).min(self.width);
        let y_lo = ((c.a.y.min(c.b.y) - r).floor().max(self.y0 as f32) as usize).max(self.y0);
        let y_hi = ((c.a.y.max(c.b.y) + r).ceil().max(0.0) as usize).min(self.y0 + self.rows);
        let (dx, dy) = (c.b.x - c.a.x, c.b.y - c.a.y);
        let len2 = dx * dx + dy * dy;
        let steep = dy.abs() > dx.abs();
        let (u_lo, u_hi, v_lo, v_hi) = if steep {
            (y_lo, y_hi, x_lo, x_hi)
        } else {
            (x_lo, x_hi, y_lo, y_hi)
        };
        for u in u_lo..u_hi {
            let (v0, v1) = minor_range(c, steep, u as f32 + 0.5, r);
            let v_start = (v0.floor().max(v_lo as f32) as usize).max(v_lo);
            let v_end = (v1.ceil().max(0.0) as usize).min(v_hi);
            for v in v_start..v_end {
                let (x, y) = if steep { (v, u) } else { (u, v) };
                let (px, py) = (x as f32 + 0.5 - c.a.x, y as f32 + 0.5 - c.a.y);
                let t = if len2 > 0.0 {
                    ((px * dx + py * dy) / len2).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                let (ex, ey) = (px - t * dx, py - t * dy);
                let half = c.half_a + t * (c.half_b - c.half_a);
                if ex * ex + ey * ey > half * half {
                    continue;
                }
                let z = c.a.depth + t * (c.b.depth - c.a.depth);
                let k = (y - self.y0) * self.width + x;
                if z < self.depth[k] {
                    self.depth[k] = z;
                    self.segment[k] = c.first;
                    self.t[k] = t;
                }
            }
        }
    }
}

/// The span of the minor coordinate the capsule can cover at major coordinate `u`.
fn minor_range(c: &Capsule, steep: bool, u: f32, r: f32) -> (f32, f32) {
    let (au, av, bu, bv) = if steep {
        (c.a.y, c.a.x, c.b.y, c.b.x)
    } else {
        (c.a.x, c.a.y, c.b.x, c.b.y)
    };
    let (lo_v, hi_v) = (av.min(bv) - r, av.max(bv) + r);
    let du = bu - au;
    if du.abs() < 1e-6 {
        return (lo_v, hi_v);
    }
    let slope = (bv - av) / du;
    let centre = av + (u.clamp(au.min(bu), au.max(bu)) - au) * slope;
    let reach = r * (1.0 + slope * slope).sqrt() + 1.0;
    ((centre - reach).max(lo_v), (centre + reach).min(hi_v))
}
