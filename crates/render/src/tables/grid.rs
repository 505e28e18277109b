//! A regular 2D grid of small fixed-size vectors with bilinear lookup: the storage of the
//! precomputed tables (Xu et al. 2011 §5 stores them as 2D textures read with hardware filtering).

/// `nx × ny` nodes of `[f64; N]` over `[x0, x1] × [y0, y1]`, clamped at the edges.
#[derive(Clone, Debug)]
pub struct Grid2<const N: usize> {
    nx: usize,
    ny: usize,
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
    values: Vec<[f64; N]>,
}

impl<const N: usize> Grid2<N> {
    /// Fills node (i, j), at x_i = x0 + i (x1 − x0)/(nx − 1) and likewise y_j, with `f(x_i, y_j)`.
    pub fn build(
        (nx, x0, x1): (usize, f64, f64),
        (ny, y0, y1): (usize, f64, f64),
        f: impl Fn(f64, f64) -> [f64; N] + Sync,
    ) -> Self {
        use rayon::prelude::*;
        let values = (0..nx * ny)
            .into_par_iter()
            .map(|n| {
                let (i, j) = (n / ny, n % ny);
                f(node(x0, x1, nx, i), node(y0, y1, ny, j))
            })
            .collect();
        Self {
            nx,
            ny,
            x0,
            x1,
            y0,
            y1,
            values,
        }
    }

    /// Bilinear interpolation at (x, y), clamped to the grid.
    pub fn lookup(&self, x: f64, y: f64) -> [f64; N] {
        self.lookup_cells(self.cell_x(x), self.cell_y(y))
    }

    /// The cell of `x` along the first axis, for lookups that share it.
    pub fn cell_x(&self, x: f64) -> Cell {
        let (index, fraction) = cell(self.x0, self.x1, self.nx, x);
        Cell { index, fraction }
    }

    /// The cell of `y` along the second axis, for lookups that share it.
    pub fn cell_y(&self, y: f64) -> Cell {
        let (index, fraction) = cell(self.y0, self.y1, self.ny, y);
        Cell { index, fraction }
    }

    /// [`Self::lookup`] at cells found before.
    pub fn lookup_cells(&self, cx: Cell, cy: Cell) -> [f64; N] {
        let (i, fx, j, fy) = (cx.index, cx.fraction, cy.index, cy.fraction);
        let at = |i: usize, j: usize| &self.values[i * self.ny + j];
        let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i, j + 1), at(i + 1, j + 1));
        std::array::from_fn(|k| {
            let lo = a[k] + fx * (b[k] - a[k]);
            let hi = c[k] + fx * (d[k] - c[k]);
            lo + fy * (hi - lo)
        })
    }

    pub fn len(&self) -> usize {
        self.values.len()
    }

    /// The node layout, for a back end that uploads the grid (cuticle-gpu interpolates it as
    /// [`Self::lookup_cells`] does).
    pub fn layout(&self) -> GridLayout {
        GridLayout {
            nx: self.nx,
            ny: self.ny,
            x: (self.x0, self.x1),
            y: (self.y0, self.y1),
        }
    }

    /// The node values, node (i, j) at `i * ny + j`.
    pub fn values(&self) -> &[[f64; N]] {
        &self.values
    }

    pub fn is_empty(&self) -> bool {
        self.values.is_empty()
    }
}

/// Where a grid's nodes lie: `nx × ny` nodes over `x.0..=x.1` × `y.0..=y.1`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GridLayout {
    pub nx: usize,
    pub ny: usize,
    pub x: (f64, f64),
    pub y: (f64, f64),
}

/// A lower node index along one axis and the fraction of the way to the next.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cell {
    index: usize,
    fraction: f64,
}

fn node(a: f64, b: f64, n: usize, i: usize) -> f64 {
    a + (b - a) * i as f64 / (n - 1) as f64
}

/// The cell index and fraction of `x` on `n` nodes over [a, b], clamped; an axis with b = a
/// (a table constant along it) always reads its first cell.
fn cell(a: f64, b: f64, n: usize, x: f64) -> (usize, f64) {
    if b <= a {
        return (0, 0.0);
    }
    let t = ((x - a) / (b - a)).clamp(0.0, 1.0) * (n - 1) as f64;
    let i = (t as usize).min(n - 2);
    (i, t - i as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Bilinear lookup reproduces a bilinear function exactly and clamps outside.
    #[test]
    fn bilinear_is_exact_on_bilinear_functions() {
        let g = Grid2::build((5, 0.0, 1.0), (7, -1.0, 2.0), |x, y| [x + 2.0 * y + x * y]);
        for &(x, y) in &[(0.3, 0.1), (0.99, 1.7), (0.5, -0.5)] {
            assert!((g.lookup(x, y)[0] - (x + 2.0 * y + x * y)).abs() < 1e-12);
        }
        assert!((g.lookup(5.0, 9.0)[0] - (1.0 + 4.0 + 2.0)).abs() < 1e-12);
    }
}
