//! The CPU renderer's tables as the shaders read them: every [`Grid2`] flattened to f32 in its
//! own node order, with a [`GridDesc`] that tells `shading/grid.wgsl` where it lies and how to
//! interpolate it (bilinear in f32, as `Grid2::lookup_cells` does in f64; storage buffers, not
//! filtered textures, whose 8-bit interpolation weights would cost the parity).
//!
//! - Built once with [`GpuRenderer::new`](crate::GpuRenderer::new), independent of every hair
//!   parameter ([`StaticTables`]): 𝒞_k/Z with ln Z, ℋ^TRT (for eccentric fibers, whose TRT is
//!   fitted at each sample), N_R's Fresnel quintic, the half-circle integrals W_k and P, the spread
//!   normalisation Z, and the circular-Gaussian width correction.
//! - Rebuilt by the CPU renderer when η, the caustics or (for dual scattering) any parameter but
//!   absorption changes, and uploaded then: the lobe table (TT, TRT) and the back-scattering
//!   moments ([`lobe_grids`], [`back_grid`]).

use bytemuck::{Pod, Zeroable};
use cuticle_render::srbf::circular_gaussian::width_table;
use cuticle_render::tables::back_scattering::BackScatteringTables;
use cuticle_render::tables::cg_integrals::Tables;
use cuticle_render::tables::grid::Grid2;
use cuticle_render::tables::half_circle::HalfCircle;
use cuticle_render::tables::lobe_table::LobeTable;
use cuticle_render::tables::spread::SpreadNormalisation;

/// Where one grid lies in its buffer: `nx × ny` nodes of `n` values from `offset` (in f32s),
/// node (i, j) at `offset + (i ny + j) n`, over [x0, x1] × [y0, y1].
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GridDesc {
    pub nx: u32,
    pub ny: u32,
    pub n: u32,
    pub offset: u32,
    pub x0: f32,
    pub x1: f32,
    pub y0: f32,
    pub y1: f32,
}

/// Slots of [`GridDesc`]s in the shaders' uniform (the `GRID_*` constants of grid.wgsl).
pub mod slot {
    pub const COSINE: usize = 0;
    pub const H_TRT: usize = 1;
    pub const HALF_COSINES: usize = 2;
    pub const HALF_SHARE: usize = 3;
    pub const SPREAD: usize = 4;
    pub const WIDTH: usize = 5;
    pub const LOBE_TT: usize = 6;
    pub const LOBE_TRT: usize = 7;
    pub const BACK: usize = 8;
    pub const R_FRESNEL: usize = 9;
    /// Slots in all.
    pub const COUNT: usize = 10;
}

/// Grids flattened into one f32 buffer.
#[derive(Clone, Debug, Default)]
pub struct Packed {
    pub data: Vec<f32>,
    /// (slot, where) of each grid packed.
    pub grids: Vec<(usize, GridDesc)>,
}

impl Packed {
    /// Appends `grid` for `slot`.
    pub fn push<const N: usize>(&mut self, slot: usize, grid: &Grid2<N>) {
        let layout = grid.layout();
        let offset = self.data.len() as u32;
        self.data.extend(
            grid.values()
                .iter()
                .flat_map(|v| v.iter().map(|&x| x as f32)),
        );
        self.grids.push((
            slot,
            GridDesc {
                nx: layout.nx as u32,
                ny: layout.ny as u32,
                n: N as u32,
                offset,
                x0: layout.x.0 as f32,
                x1: layout.x.1 as f32,
                y0: layout.y.0 as f32,
                y1: layout.y.1 as f32,
            },
        ));
    }

    /// Writes each packed grid's descriptor into `descs`.
    pub fn describe(&self, descs: &mut [GridDesc; slot::COUNT]) {
        for &(s, d) in &self.grids {
            descs[s] = d;
        }
    }
}

/// The parameter-independent tables.
pub fn static_grids(tables: &Tables, half: &HalfCircle, spread: &SpreadNormalisation) -> Packed {
    let mut packed = Packed::default();
    let grids = tables.grids();
    packed.push(slot::COSINE, grids.cosine);
    packed.push(slot::H_TRT, grids.h_trt);
    packed.push(slot::R_FRESNEL, grids.r_fresnel);
    let (cosines, share) = half.grids();
    packed.push(slot::HALF_COSINES, cosines);
    packed.push(slot::HALF_SHARE, share);
    packed.push(slot::SPREAD, spread.grid());
    packed.push(slot::WIDTH, &width_grid());
    packed
}

/// The width correction of `bandwidth_for_integral` over ln(area/√π) as a grid constant in its
/// second axis (grid.wgsl's lookup needs two nodes there).
fn width_grid() -> Grid2<1> {
    let table = width_table();
    let n = table.correction.len();
    let (l0, l1) = (table.range.0.ln(), table.range.1.ln());
    Grid2::build((n, l0, l1), (2, 0.0, 0.0), |x, _| {
        let k = ((x - l0) / (l1 - l0) * (n - 1) as f64).round() as usize;
        [table.correction[k.min(n - 1)]]
    })
}

/// The lobe table's TT and TRT grids.
pub fn lobe_grids(lobes: &LobeTable) -> Packed {
    let mut packed = Packed::default();
    let (tt, trt) = lobes.grids();
    packed.push(slot::LOBE_TT, tt);
    packed.push(slot::LOBE_TRT, trt);
    packed
}

/// The back-scattering moments.
pub fn back_grid(back: &BackScatteringTables) -> Packed {
    let mut packed = Packed::default();
    packed.push(slot::BACK, back.grid());
    packed
}
