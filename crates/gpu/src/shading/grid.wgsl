// tables/grid.rs in f32: a regular 2D grid of small vectors, bilinear between nodes, clamped
// at the edges. One reader per buffer (WGSL passes no storage pointers).

// A lower node index along one axis and the fraction of the way to the next.
struct Cell {
    index: u32,
    fraction: f32,
}

// The cell of x on n nodes over [a, b], clamped; an axis with b = a reads its first cell.
fn cell(a: f32, b: f32, n: u32, x: f32) -> Cell {
    if (b <= a) {
        return Cell(0u, 0.0);
    }
    let t = clamp((x - a) / (b - a), 0.0, 1.0) * f32(n - 1u);
    let i = min(u32(t), n - 2u);
    return Cell(i, t - f32(i));
}

fn cell_x(g: Grid, x: f32) -> Cell {
    return cell(g.x0, g.x1, g.nx, x);
}

fn cell_y(g: Grid, y: f32) -> Cell {
    return cell(g.y0, g.y1, g.ny, y);
}

// The four node indices (of value k) around cells (cx, cy).
struct Corners {
    a: u32,
    b: u32,
    c: u32,
    d: u32,
}

fn corners(g: Grid, cx: Cell, cy: Cell, k: u32) -> Corners {
    let at = g.offset + (cx.index * g.ny + cy.index) * g.n + k;
    let step_x = g.ny * g.n;
    return Corners(at, at + step_x, at + g.n, at + step_x + g.n);
}

fn bilinear(a: f32, b: f32, c: f32, d: f32, cx: Cell, cy: Cell) -> f32 {
    let lo = a + cx.fraction * (b - a);
    let hi = c + cx.fraction * (d - c);
    return lo + cy.fraction * (hi - lo);
}

fn static_at(slot: u32, cx: Cell, cy: Cell, k: u32) -> f32 {
    let q = corners(params.grids[slot], cx, cy, k);
    return bilinear(static_tables[q.a], static_tables[q.b], static_tables[q.c], static_tables[q.d], cx, cy);
}

fn lobe_at(slot: u32, cx: Cell, cy: Cell, k: u32) -> f32 {
    let q = corners(params.grids[slot], cx, cy, k);
    return bilinear(lobe_tables[q.a], lobe_tables[q.b], lobe_tables[q.c], lobe_tables[q.d], cx, cy);
}

fn back_at(slot: u32, cx: Cell, cy: Cell, k: u32) -> f32 {
    let q = corners(params.grids[slot], cx, cy, k);
    return bilinear(back_tables[q.a], back_tables[q.b], back_tables[q.c], back_tables[q.d], cx, cy);
}

// Value k of a static table at (x, y).
fn static_lookup(slot: u32, x: f32, y: f32, k: u32) -> f32 {
    let g = params.grids[slot];
    return static_at(slot, cell_x(g, x), cell_y(g, y), k);
}
