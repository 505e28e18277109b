//! A groom rebuilt at chosen places along its strands: the one way every step of
//! [`super`] adds points.

use cuticle_groom::{Groom, GroomParts};

/// Where each strand is sampled: per strand, ascending fractional point indices counted from
/// the strand's first point (`0.0` its first, `n − 1` its last; `2.5` halfway along its third
/// segment). Each list starts at 0 and ends at the strand's last point.
pub struct Knots(pub Vec<Vec<f64>>);

impl Knots {
    /// Whether every knot is one of the groom's own points.
    pub fn adds_nothing(&self, groom: &Groom) -> bool {
        self.0.iter().map(Vec::len).sum::<usize>() == groom.point_count()
    }
}

/// Where fractional index `u` lies in a strand of `n` points: the segment's first point and
/// the fraction along it.
pub fn segment_at(u: f64, n: usize) -> (usize, f32) {
    let i = (u.floor().max(0.0) as usize).min(n.saturating_sub(2));
    (i, (u - i as f64).clamp(0.0, 1.0) as f32)
}

/// `groom` with each strand's points at `knots` (points, thickness, colour and transparency
/// interpolated linearly along the segment a knot lies on; strand appearance kept). The groom
/// itself when the knots are its own points.
pub fn rebuild(groom: Groom, knots: &Knots) -> Groom {
    if knots.adds_nothing(&groom) {
        return groom;
    }
    let parts = groom.parts();
    let mut out = GroomParts {
        positions: Vec::new(),
        thickness: Vec::new(),
        colors: parts.colors.as_ref().map(|_| Vec::new()),
        transparency: parts.transparency.as_ref().map(|_| Vec::new()),
        strand_offsets: vec![0],
    };
    for (s, strand) in knots.0.iter().enumerate() {
        let r = groom.strand_range(s);
        for &u in strand {
            let (i, t) = segment_at(u, r.len());
            let (a, b) = (r.start + i, (r.start + i + 1).min(r.end - 1));
            out.positions
                .push(parts.positions[a].lerp(parts.positions[b], t));
            out.thickness
                .push(parts.thickness[a] + t * (parts.thickness[b] - parts.thickness[a]));
            if let (Some(c), Some(src)) = (out.colors.as_mut(), parts.colors.as_ref()) {
                c.push(src[a].lerp(src[b], t));
            }
            if let (Some(c), Some(src)) = (out.transparency.as_mut(), parts.transparency.as_ref()) {
                c.push(src[a] + t * (src[b] - src[a]));
            }
        }
        out.strand_offsets.push(out.positions.len() as u32);
    }
    let appearance = groom.appearance().to_vec();
    Groom::from_parts(out)
        .and_then(|g| g.with_appearance(appearance))
        .expect("knots along a valid groom's strands make a valid groom")
}
