//! The brush: which strands lie under a dab and how much paint each takes.
//!
//! A dab at image position (x, y) of radius r pixels covers the subsamples of the frame's
//! visibility buffer within r; a subsample at distance d takes the weight
//! strength × f(d / r), f = 1 inside the hard core (1 − soft edge) and falling smoothly
//! (smoothstep) to 0 at the rim. A strand takes the largest weight of its subsamples and moves
//! its μ_a that fraction of the way to the brush's.

use crate::shading::StrandBuffer;
use cuticle_groom::Absorption;
use glam::DVec3;
use std::collections::BTreeMap;

/// The brush's settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Brush {
    /// Radius in pixels of the full-resolution image.
    pub radius_px: f64,
    /// Fraction of the way to the brush's absorption a dab moves a strand at its centre, (0, 1].
    pub strength: f64,
    /// Fraction of the radius, at the rim, over which the weight falls to 0, [0, 1].
    pub soft_edge: f64,
    /// What the brush paints.
    pub absorption: Absorption,
}

impl Default for Brush {
    fn default() -> Self {
        Self {
            radius_px: 24.0,
            strength: 0.8,
            soft_edge: 0.5,
            absorption: Absorption::Melanin {
                eumelanin: 0.3,
                pheomelanin: 2.5,
            },
        }
    }
}

impl Brush {
    /// Weight of a subsample at `d` pixels from the centre.
    pub fn weight(&self, d: f64) -> f64 {
        let r = self.radius_px.max(1e-6);
        let u = d / r;
        if u >= 1.0 {
            return 0.0;
        }
        let core = 1.0 - self.soft_edge.clamp(0.0, 1.0);
        let f = if u <= core {
            1.0
        } else {
            let t = ((1.0 - u) / (1.0 - core)).clamp(0.0, 1.0);
            t * t * (3.0 - 2.0 * t)
        };
        self.strength.clamp(0.0, 1.0) * f
    }

    /// Strands under a dab at (x, y), full-resolution image pixels of an image `full_width`
    /// wide, with their weights (0 < w ≤ strength), read from `buffer` at its own resolution.
    pub fn dab(
        &self,
        buffer: &StrandBuffer,
        full_width: usize,
        x: f64,
        y: f64,
    ) -> BTreeMap<u32, f64> {
        let mut out = BTreeMap::new();
        if buffer.width == 0 || full_width == 0 {
            return out;
        }
        // Subsamples per full-resolution pixel.
        let k = (buffer.width * buffer.ss) as f64 / full_width as f64;
        let (cx, cy, r) = (x * k, y * k, self.radius_px * k);
        let (sw, sh) = (buffer.width * buffer.ss, buffer.height * buffer.ss);
        let x0 = (cx - r).floor().max(0.0) as usize;
        let y0 = (cy - r).floor().max(0.0) as usize;
        let x1 = ((cx + r).ceil().max(0.0) as usize).min(sw);
        let y1 = ((cy + r).ceil().max(0.0) as usize).min(sh);
        for sy in y0..y1 {
            for sx in x0..x1 {
                let (dx, dy) = (sx as f64 + 0.5 - cx, sy as f64 + 0.5 - cy);
                let w = self.weight((dx * dx + dy * dy).sqrt() / k);
                if w <= 0.0 {
                    continue;
                }
                if let Some(s) = buffer.at(sx, sy) {
                    let e = out.entry(s).or_insert(0.0);
                    *e = f64::max(*e, w);
                }
            }
        }
        out
    }
}

/// μ_a moved the fraction `w` of the way from `from` to `to`.
pub fn blend(from: DVec3, to: DVec3, w: f64) -> DVec3 {
    from + (to - from) * w.clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shading::NO_STRAND;

    #[test]
    fn weight_is_full_in_the_core_and_falls_to_zero_at_the_rim() {
        let b = Brush {
            radius_px: 10.0,
            strength: 0.5,
            soft_edge: 0.4,
            ..Brush::default()
        };
        assert_eq!(b.weight(0.0), 0.5);
        assert_eq!(b.weight(6.0), 0.5);
        assert!(b.weight(8.0) > 0.0 && b.weight(8.0) < 0.5);
        assert!(b.weight(9.9) < b.weight(8.0));
        assert_eq!(b.weight(10.0), 0.0);
    }

    /// On a buffer of two strands side by side, a dab on the left one picks it alone, at
    /// the buffer's own resolution (half the image's, two subsamples per pixel).
    #[test]
    fn dab_picks_the_strands_under_it() {
        let (w, h, ss) = (8, 4, 2);
        let strand = (0..w * ss * h * ss)
            .map(|k| match k % (w * ss) {
                0..4 => 7,
                12..16 => 9,
                _ => NO_STRAND,
            })
            .collect();
        let buffer = StrandBuffer {
            width: w,
            height: h,
            ss,
            strand,
        };
        let b = Brush {
            radius_px: 2.0,
            ..Brush::default()
        };
        // The image is 16 px wide: a buffer subsample is one image pixel.
        let picked = b.dab(&buffer, 16, 2.0, 4.0);
        assert_eq!(picked.keys().copied().collect::<Vec<_>>(), vec![7]);
        let both = Brush {
            radius_px: 20.0,
            ..b
        }
        .dab(&buffer, 16, 8.0, 4.0);
        assert_eq!(both.keys().copied().collect::<Vec<_>>(), vec![7, 9]);
    }
}
