//! Which lat-long pixel (docs/conventions.md §4) an exit direction falls in, without asin or atan2:
//! a table gives a first guess, and comparisons with the exact pixel edges settle it. Row k holds
//! sin θ_top(k+1) < ω·u ≤ sin θ_top(k); column j holds the azimuths from edge j (inclusive) to
//! edge j+1, tested by the sign of 2D cross products with the edge directions. This agrees with
//! `LatLongGrid::index_of` except for directions within rounding of an edge.

use cuticle_fiber::LatLongGrid;
use glam::{DVec2, DVec3};

/// Table entries per column (and per row) of the first-guess tables.
const OVERSAMPLE: usize = 4;

#[derive(Clone, Debug)]
pub struct Binner {
    grid: LatLongGrid,
    /// sin θ at the top edge of rows 0..=height.
    sin_top: Vec<f64>,
    /// (cos φ_j, sin φ_j) of column edges φ_j = −π + jΔφ, j = 0..=width (edge `width` = edge 0).
    edges: Vec<DVec2>,
    /// First guess of the row, by ω·u on a uniform table over [−1, 1].
    row_guess: Vec<u32>,
    /// First guess of the column, by pseudo-angle on a uniform table over [0, 4).
    col_guess: Vec<u32>,
}

/// A monotone stand-in for the azimuth φ ∈ (−π, π]: the "diamond angle" in [0, 4), starting at
/// φ = −π, computed with one division.
fn pseudo_angle(v: DVec2) -> f64 {
    let (y, z) = (v.x, v.y);
    let q = y.abs() + z.abs();
    if z < 0.0 {
        if y < 0.0 { -z / q } else { 1.0 + y / q }
    } else if y >= 0.0 {
        2.0 + z / q
    } else {
        3.0 - y / q
    }
}

impl Binner {
    pub fn new(grid: LatLongGrid) -> Self {
        let (w, h) = (grid.width, grid.height);
        let sin_top: Vec<f64> = (0..=h).map(|k| grid.theta_top(k).sin()).collect();
        // Edges 0 and `width` are both φ = ±π, exactly (−1, 0), so that φ = π falls in column 0
        // as it does for `LatLongGrid::pixel_of`.
        let edges: Vec<DVec2> = (0..=w)
            .map(|j| match j {
                0 => DVec2::new(-1.0, 0.0),
                j if j == w => DVec2::new(-1.0, 0.0),
                j => {
                    let phi = -std::f64::consts::PI + grid.d_phi() * j as f64;
                    DVec2::new(phi.cos(), phi.sin())
                }
            })
            .collect();
        let rows = OVERSAMPLE * h;
        let row_guess = (0..rows)
            .map(|i| {
                let x = -1.0 + 2.0 * (i as f64 + 0.5) / rows as f64;
                grid.pixel_of(x.asin(), 0.0).1 as u32
            })
            .collect();
        let cols = OVERSAMPLE * w;
        let col_guess = (0..cols)
            .map(|i| {
                let p = 4.0 * (i as f64 + 0.5) / cols as f64;
                let phi = Self::angle_of_pseudo(p);
                grid.pixel_of(0.0, phi).0 as u32
            })
            .collect();
        Self {
            grid,
            sin_top,
            edges,
            row_guess,
            col_guess,
        }
    }

    /// The azimuth whose pseudo-angle is p (the inverse of [`pseudo_angle`]).
    fn angle_of_pseudo(p: f64) -> f64 {
        let quadrant = p.floor().min(3.0);
        let t = p - quadrant;
        let (y, z) = match quadrant as u8 {
            0 => (-(1.0 - t), -t),
            1 => (t, -(1.0 - t)),
            2 => (1.0 - t, t),
            _ => (-t, 1.0 - t),
        };
        z.atan2(y)
    }

    /// The flat pixel index (row-major from the top row) of unit direction d.
    #[inline(always)]
    pub fn index(&self, d: DVec3) -> usize {
        self.row(d.x) * self.grid.width + self.column(DVec2::new(d.y, d.z))
    }

    #[inline(always)]
    fn row(&self, x: f64) -> usize {
        let n = self.row_guess.len();
        let i = (((x + 1.0) * 0.5 * n as f64) as usize).min(n - 1);
        let mut k = self.row_guess[i] as usize;
        while k > 0 && x > self.sin_top[k] {
            k -= 1;
        }
        while k + 1 < self.grid.height && x <= self.sin_top[k + 1] {
            k += 1;
        }
        k
    }

    #[inline(always)]
    fn column(&self, v: DVec2) -> usize {
        if v == DVec2::ZERO {
            return self.grid.pixel_of(0.0, 0.0).0;
        }
        let w = self.grid.width;
        let n = self.col_guess.len();
        let i = ((pseudo_angle(v) * 0.25 * n as f64) as usize).min(n - 1);
        let mut j = self.col_guess[i] as usize;
        for _ in 0..w {
            if self.edges[j].perp_dot(v) < 0.0 {
                j = if j == 0 { w - 1 } else { j - 1 };
            } else if self.edges[j + 1].perp_dot(v) >= 0.0 {
                j = if j + 1 == w { 0 } else { j + 1 };
            } else {
                break;
            }
        }
        j
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Sampler;
    use cuticle_fiber::FiberAngles;

    #[test]
    fn agrees_with_the_grid_away_from_edges() {
        for grid in [
            LatLongGrid::default(),
            LatLongGrid::new(37, 11),
            LatLongGrid::new(720, 360),
        ] {
            let b = Binner::new(grid);
            let mut rng = Sampler::for_chunk(3, 0);
            for _ in 0..200_000 {
                let z = 2.0 * rng.uniform() - 1.0;
                let phi = std::f64::consts::TAU * rng.uniform();
                let r = (1.0 - z * z).sqrt();
                let d = DVec3::new(z, r * phi.cos(), r * phi.sin());
                let a = FiberAngles::from_dir(d);
                let want = grid.index_of(a.theta, a.phi);
                let got = b.index(d);
                if got != want {
                    let pi = std::f64::consts::PI;
                    let row = ((pi / 2.0 - a.theta) / pi * grid.height as f64).fract();
                    let col = ((a.phi + pi) / grid.d_phi()).fract();
                    let near = |f: f64| !(1e-9..=1.0 - 1e-9).contains(&f);
                    assert!(near(row) || near(col), "{d:?} far from any pixel edge");
                }
            }
        }
    }
}
