//! The tabulated fast path for the azimuthal terms of d'Eon 2011 (d'Eon et al. 2014 eq. 4): N_p
//! built once per parameter set over (θ_i, |θ_d|, |φ|), read back by trilinear interpolation, as
//! production renderers do instead of integrating over h at every evaluation.
//!
//! The table holds TT, TRT and TRRT (RGB, plus the lobe-selection density importance sampling
//! uses), and the p ≥ 4 remainder over θ_i alone; R has a closed form and needs no table.
//! N_p is even in φ (A is even in h, Φ odd about pπ) and depends on θ_d only through
//! η′, so φ is folded to [0, π] and θ_d is tabulated along 1/η′ ∈ [0, 1/η]. The φ spacing follows
//! the narrowest azimuthal lobe (a third of its standard deviation, 64 to 1024 columns); below
//! β ≈ 0.02 the cap binds and the table blurs the narrowest lobes. Each row holds its lobes'
//! shapes, normalised; their energies over θ_i come from a finer axis (`table/energy.rs`),
//! since a lobe's energy can fall by an order of magnitude between two rows. Its error
//! against direct quadrature is measured in the tests below and in BENCHMARKS.md.

mod energy;

use crate::geometry::bravais::{azimuthal_deflection, eta_prime};
use crate::geometry::frame::wrap_pi;
use crate::lobe::LobeValues;
use crate::math::grid::{fill_rows, locate};
use crate::math::{GaussLegendre, normal_pdf};
use crate::models::deon2011::azimuthal::{
    AzimuthalScattering, PANEL_NODES, Weighting, rest_integral, selection_from,
};
use energy::{ENERGY_NODES, LobeEnergies, normalise_rows};
use glam::{DVec3, DVec4, Vec4};
use std::f64::consts::PI;

const THETA_I_NODES: usize = 64;
const THETA_D_NODES: usize = 32;
const MIN_PHI_NODES: usize = 64;
const MAX_PHI_NODES: usize = 1024;
/// Lobes tabulated over (θ_i, θ_d, φ): TT, TRT, TRRT.
const BLURRED: [usize; 3] = [1, 2, 3];

/// The lobe-selection probabilities at (θ_i, h) a sampler chooses with
/// ([`AzimuthalTable::build_with_selection`]).
pub type Selection<'a> = &'a (dyn Fn(f64, f64) -> [f64; 5] + Sync);

/// N_p on a grid; see the module documentation.
#[derive(Clone, Debug)]
pub struct AzimuthalTable {
    az: AzimuthalScattering,
    phi_nodes: usize,
    /// [θ_i][θ_d][φ] → TT, TRT and TRRT, each (r, g, b, selection), divided by its energy
    /// (the slab's integral over φ is 1): one texel holds every lobe, so a trilinear tap
    /// reads eight neighbouring cells once.
    blurred: Vec<[Vec4; 3]>,
    /// The same texels' selection channels alone, (TT, TRT, TRRT, 0): what a sampling density
    /// reads ([`AzimuthalTable::selection_taps`]), a quarter of the data.
    selection: Vec<Vec4>,
    /// Over a finer θ_i axis: the energies the shapes are multiplied by, and the p ≥ 4
    /// remainder.
    energy: LobeEnergies,
}

/// The cells of θ_i in a lookup: the lower node and the fraction toward the next on the
/// rows' axis and on the energies' finer one (`table/energy.rs`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ThetaICell {
    i0: usize,
    fi: f32,
    e0: usize,
    fe: f32,
}

/// Where a lookup falls in the table: the lower node and the fraction toward the next along
/// θ_i (both of its axes), θ_d (its η/η′) and |φ|. Found once per (ω_i, ω_o) and read by
/// every lobe.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TablePoint {
    i0: usize,
    fi: f32,
    e0: usize,
    fe: f32,
    d0: usize,
    fd: f32,
    f0: usize,
    ff: f32,
}

impl AzimuthalTable {
    /// Fills the table by quadrature over h, on every available core.
    pub fn build(az: &AzimuthalScattering) -> Self {
        Self::build_with_selection(az, None)
    }

    /// [`AzimuthalTable::build`] with the selection densities taken from `selection`, the
    /// probabilities of each lobe at (θ_i, h) a sampler chooses with, instead of A(p, h)'s
    /// own: so the densities the table reports are the ones that sampler realises.
    pub fn build_with_selection(az: &AzimuthalScattering, selection: Option<Selection>) -> Self {
        let sigma_min = az.v_n[1..]
            .iter()
            .fold(f64::INFINITY, |m, v| m.min(v.sqrt()));
        let phi_nodes =
            ((PI / (sigma_min / 3.0)).ceil() as usize).clamp(MIN_PHI_NODES, MAX_PHI_NODES);
        let slab = THETA_D_NODES * phi_nodes;
        let mut blurred = vec![[Vec4::ZERO; 3]; THETA_I_NODES * slab];
        fill_rows(&mut blurred, slab, |i, row| {
            fill_row(az, selection, theta_i_at(i), phi_nodes, row)
        });
        let energies = normalise_rows(&mut blurred, THETA_I_NODES, THETA_D_NODES, phi_nodes);
        let rows: Vec<[DVec4; 4]> = energies
            .iter()
            .enumerate()
            .map(|(i, [tt, trt, trrt])| {
                let theta_i = theta_i_at(i);
                let a = az.eval(4, theta_i, -theta_i, 0.0, Weighting::Attenuation);
                let sel = match selection {
                    Some(f) => rest_integral(|h| DVec3::splat(f(theta_i, h)[4])).x,
                    None => az.eval(4, theta_i, -theta_i, 0.0, Weighting::Selection).x,
                };
                [*tt, *trt, *trrt, a.extend(sel)]
            })
            .collect();
        let selection = blurred
            .iter()
            .map(|[tt, trt, trrt]| Vec4::new(tt.w, trt.w, trrt.w, 0.0))
            .collect();
        Self {
            az: az.clone(),
            phi_nodes,
            blurred,
            selection,
            energy: LobeEnergies::from_rows(&rows),
        }
    }

    /// N_p(φ) as [`AzimuthalScattering::eval`] gives it, from the table (R directly).
    pub fn eval(
        &self,
        p: usize,
        theta_i: f64,
        theta_d: f64,
        phi: f64,
        weighting: Weighting,
    ) -> DVec3 {
        self.eval_all(theta_i, theta_d, phi, weighting)[p]
    }

    /// N_p(φ) weighted by attenuation and by selection together, from the same texels: what
    /// [`AzimuthalTable::eval_all`] gives for each weighting (the selection as its first channel).
    pub fn eval_all_both(&self, theta_i: f64, theta_d: f64, phi: f64) -> ([DVec3; 5], [DVec3; 5]) {
        let texels = self.taps(self.point(theta_i, self.eta_ratio(theta_d), phi));
        let rgb = |v: Vec4| v.truncate().as_dvec3();
        let sel = |v: Vec4| DVec3::splat(v.w as f64);
        (
            [
                self.az
                    .eval(0, theta_i, theta_d, phi, Weighting::Attenuation),
                rgb(texels[0]),
                rgb(texels[1]),
                rgb(texels[2]),
                rgb(texels[3]),
            ],
            [
                self.az.eval(0, theta_i, theta_d, phi, Weighting::Selection),
                sel(texels[0]),
                sel(texels[1]),
                sel(texels[2]),
                sel(texels[3]),
            ],
        )
    }

    /// N_p(φ) for every lobe at once: the table coordinates are found once.
    pub fn eval_all(
        &self,
        theta_i: f64,
        theta_d: f64,
        phi: f64,
        weighting: Weighting,
    ) -> [DVec3; 5] {
        let [t1, t2, t3, rest] = self.eval_beyond_r(theta_i, theta_d, phi, weighting);
        [
            self.az.eval(0, theta_i, theta_d, phi, weighting),
            t1,
            t2,
            t3,
            rest,
        ]
    }

    /// N_p(φ) for TT, TRT, TRRT and the remainder, the lobes the table holds:
    /// [`AzimuthalTable::eval_all`] without R, for a caller that has R's offsets already.
    pub fn eval_beyond_r(
        &self,
        theta_i: f64,
        theta_d: f64,
        phi: f64,
        weighting: Weighting,
    ) -> [DVec3; 4] {
        match weighting {
            Weighting::Attenuation => self
                .beyond_r_taps(theta_i, theta_d, phi)
                .map(|v| v.truncate().as_dvec3()),
            Weighting::Selection => self
                .selection_beyond_r(theta_i, theta_d, phi)
                .map(DVec3::splat),
        }
    }

    /// [`AzimuthalTable::eval_beyond_r`]'s selection densities, one number per lobe.
    #[inline]
    pub fn selection_beyond_r(&self, theta_i: f64, theta_d: f64, phi: f64) -> [f64; 4] {
        self.selection_taps(self.point(theta_i, self.eta_ratio(theta_d), phi))
            .map(f64::from)
    }

    /// [`AzimuthalTable::eval_beyond_r`] under both weightings from one read of the texels:
    /// (attenuation, selection).
    pub fn eval_beyond_r_both(
        &self,
        theta_i: f64,
        theta_d: f64,
        phi: f64,
    ) -> ([DVec3; 4], [DVec3; 4]) {
        let taps = self.beyond_r_taps(theta_i, theta_d, phi);
        (
            taps.map(|v| v.truncate().as_dvec3()),
            taps.map(|v| DVec3::splat(v.w as f64)),
        )
    }

    /// The taps of TT, TRT, TRRT and the remainder at (θ_i, θ_d, φ).
    #[inline]
    fn beyond_r_taps(&self, theta_i: f64, theta_d: f64, phi: f64) -> [Vec4; 4] {
        self.taps(self.point(theta_i, self.eta_ratio(theta_d), phi))
    }

    /// η/η′(θ_d), the table's θ_d coordinate, from θ_d.
    fn eta_ratio(&self, theta_d: f64) -> f64 {
        self.az.eta / eta_prime(self.az.eta, theta_d)
    }

    /// η/η′(θ_d) = η cos θ_d / √(η² − sin²θ_d) from cos(θ_o − θ_i) = cos 2θ_d alone, by the
    /// half-angle identities (θ_d ∈ [−π/2, π/2], so cos θ_d ≥ 0): no trigonometry.
    #[inline]
    pub fn eta_ratio_from_cos_2d(&self, cos_2d: f64) -> f64 {
        let eta = self.az.eta;
        let cos2_d = (0.5 * (1.0 + cos_2d)).clamp(0.0, 1.0);
        let sin2_d = 1.0 - cos2_d;
        eta * (cos2_d / (eta * eta - sin2_d).max(1e-300)).sqrt()
    }

    /// The table coordinates of (θ_i, θ_d, φ), θ_d given by its η/η′ (see
    /// [`AzimuthalTable::eta_ratio_from_cos_2d`]).
    #[inline]
    pub fn point(&self, theta_i: f64, eta_ratio: f64, phi: f64) -> TablePoint {
        self.point_in_row(Self::theta_i_cell(theta_i), eta_ratio, phi)
    }

    /// The θ_i cells of a lookup: what every lookup for one incident direction shares.
    #[inline]
    pub fn theta_i_cell(theta_i: f64) -> ThetaICell {
        let c = theta_i_coord(theta_i);
        let (i0, fi) = locate(c, THETA_I_NODES);
        let (e0, fe) = locate(c, ENERGY_NODES);
        ThetaICell { i0, fi, e0, fe }
    }

    /// [`AzimuthalTable::point`] with the θ_i cells already found
    /// ([`AzimuthalTable::theta_i_cell`]).
    #[inline]
    pub fn point_in_row(&self, cell: ThetaICell, eta_ratio: f64, phi: f64) -> TablePoint {
        let (d0, fd) = locate(eta_ratio, THETA_D_NODES);
        let (f0, ff) = locate(wrap_pi(phi).abs() / PI, self.phi_nodes);
        let ThetaICell { i0, fi, e0, fe } = cell;
        TablePoint {
            i0,
            fi,
            e0,
            fe,
            d0,
            fd,
            f0,
            ff,
        }
    }

    /// The trilinear taps of the blurred lobes p = 1, 2, 3 (over θ_i, θ_d's η/η′, |φ|) and the
    /// remainder's tap over θ_i, each (attenuation RGB, selection): each lobe the sum of its
    /// eight corner texels times their trilinear weights, found once for all three lobes,
    /// times its energy at θ_i (`table/energy.rs`). The same interpolant as the nested lerps
    /// of [`AzimuthalTable::taps_nested`] (within f32 rounding,
    /// `corner_weights_match_the_nested_lerps`) in fewer operations and registers, and one
    /// bounds check per pair of neighbouring φ columns.
    #[inline(always)]
    pub fn taps(&self, at: TablePoint) -> [Vec4; 4] {
        let (base, corners, gf, ff) = self.corners(at);
        let mut acc = [Vec4::ZERO; 3];
        for (offset, w) in corners {
            let [lo, hi]: &[[Vec4; 3]; 2] = self.blurred[base + offset..base + offset + 2]
                .try_into()
                .expect("a pair of columns");
            let (wl, wh) = (Vec4::splat(w * gf), Vec4::splat(w * ff));
            for l in 0..3 {
                acc[l] += lo[l] * wl + hi[l] * wh;
            }
        }
        let [tt, trt, trrt, rest] = self.energy.at(at.e0, at.fe);
        [acc[0] * tt, acc[1] * trt, acc[2] * trrt, rest]
    }

    /// A tap's first texel, its four (θ_i, θ_d) corners as offsets from it with their
    /// bilinear weights, and the weights of the lower and upper φ column.
    #[inline(always)]
    fn corners(&self, at: TablePoint) -> (usize, [(usize, f32); 4], f32, f32) {
        let p = self.phi_nodes;
        let slab = THETA_D_NODES * p;
        let (fi, fd) = (at.fi, at.fd);
        let (gi, gd) = (1.0 - fi, 1.0 - fd);
        let corners = [
            (0, gi * gd),
            (p, gi * fd),
            (slab, fi * gd),
            (slab + p, fi * fd),
        ];
        let base = at.i0 * slab + at.d0 * p + at.f0;
        (base, corners, 1.0 - at.ff, at.ff)
    }

    /// The selection channels of [`AzimuthalTable::taps`], (TT, TRT, TRRT, the remainder),
    /// from the selection texels alone: the same products and sums in the same order, lane by
    /// lane, so the same bits (`selection_taps_are_the_taps_selection`).
    #[inline(always)]
    pub fn selection_taps(&self, at: TablePoint) -> [f32; 4] {
        let (base, corners, gf, ff) = self.corners(at);
        let mut acc = Vec4::ZERO;
        for (offset, w) in corners {
            let [lo, hi]: &[Vec4; 2] = self.selection[base + offset..base + offset + 2]
                .try_into()
                .expect("a pair of columns");
            acc += *lo * Vec4::splat(w * gf) + *hi * Vec4::splat(w * ff);
        }
        let energy = self.energy.selection_at(at.e0, at.fe);
        let acc = acc * energy;
        [acc.x, acc.y, acc.z, energy.w]
    }

    /// [`AzimuthalTable::taps`] by nested lerps (φ, then θ_d, then θ_i): its reference twin.
    #[cfg(test)]
    fn taps_nested(&self, at: TablePoint) -> [Vec4; 4] {
        let slab = THETA_D_NODES * self.phi_nodes;
        let row = |i: usize, d: usize| i * slab + d * self.phi_nodes + at.f0;
        let lerp3 = |a: &[Vec4; 3], b: &[Vec4; 3], t: f32| {
            [
                lerp4(a[0], b[0], t),
                lerp4(a[1], b[1], t),
                lerp4(a[2], b[2], t),
            ]
        };
        let plane = |i: usize| {
            let (lo, hi) = (row(i, at.d0), row(i, at.d0 + 1));
            let lo = lerp3(&self.blurred[lo], &self.blurred[lo + 1], at.ff);
            let hi = lerp3(&self.blurred[hi], &self.blurred[hi + 1], at.ff);
            lerp3(&lo, &hi, at.fd)
        };
        let [tt, trt, trrt] = lerp3(&plane(at.i0), &plane(at.i0 + 1), at.fi);
        let [e_tt, e_trt, e_trrt, rest] = self.energy.at(at.e0, at.fe);
        [tt * e_tt, trt * e_trt, trrt * e_trrt, rest]
    }
}

/// One quadrature node of a θ_i row, shared by the blurred lobes: its offset h, and per lobe
/// the shift of Φ by the tilt ([`AzimuthalScattering::deflection_shift`]), the azimuthal
/// standard deviation ([`AzimuthalScattering::azimuthal_sigma`]), A(p, h) and the selection
/// probability, each of the last two times the node's weight.
#[derive(Clone, Copy, Debug)]
struct RowNode {
    h: f64,
    shift: [f64; 3],
    sigma: [f64; 3],
    a: [DVec3; 3],
    sel: [f64; 3],
}

/// Evenly spaced offsets γ at which a row traces A(p, h) through tilted or rough scales where
/// its quadrature has more nodes than this; the nodes then interpolate A linearly between them
/// ([`TracedRow`]). Its error against A traced at every node is measured in
/// `interpolated_attenuation_follows_the_traced_one`.
const TRACED_OFFSETS: usize = 1024;

/// The quadrature nodes of θ_i's row, on the panels the most demanding blurred lobe needs, so
/// that A(p, h) and the selection probabilities are found once per node for all three lobes.
/// Where A is a trace through tilted or rough scales (most of the build's time at low
/// roughness, whose narrow lobes need many nodes), it is traced at no more than
/// [`TRACED_OFFSETS`] offsets per row.
fn row_nodes(az: &AzimuthalScattering, selection: Option<Selection>, theta_i: f64) -> Vec<RowNode> {
    let panels = BLURRED
        .iter()
        .map(|&p| az.panel_count(p, az.eta))
        .max()
        .unwrap_or(2);
    if az.is_flat_and_smooth() || panels * PANEL_NODES <= TRACED_OFFSETS {
        return row_nodes_on(az, selection, theta_i, panels, |_, h| {
            az.attenuation(theta_i, h)
        });
    }
    let traced = TracedRow::new(az, theta_i);
    row_nodes_on(az, selection, theta_i, panels, |gamma, _| traced.at(gamma))
}

/// [`row_nodes`] on `panels` panels, with A(p, h) from `attenuation(γ, h)`.
fn row_nodes_on(
    az: &AzimuthalScattering,
    selection: Option<Selection>,
    theta_i: f64,
    panels: usize,
    attenuation: impl Fn(f64, f64) -> LobeValues,
) -> Vec<RowNode> {
    let rule = GaussLegendre::cached(PANEL_NODES);
    let width = PI / panels as f64;
    (0..panels)
        .flat_map(|k| {
            rule.nodes
                .iter()
                .zip(&rule.weights)
                .map(move |(x, w)| (k, *x, *w))
        })
        .map(|(k, x, w)| {
            let gamma = -0.5 * PI + (k as f64 + 0.5 + 0.5 * x) * width;
            let h = gamma.sin();
            let a = attenuation(gamma, h);
            let weight = 0.25 * width * w * gamma.cos();
            let sel = match selection {
                Some(f) => f(theta_i, h),
                None => selection_from(&a),
            };
            RowNode {
                h,
                shift: BLURRED.map(|p| az.deflection_shift(p, theta_i, h)),
                sigma: BLURRED.map(|p| az.azimuthal_sigma(p, theta_i, h)),
                a: BLURRED.map(|p| a.0[p] * weight),
                sel: BLURRED.map(|p| sel[p] * weight),
            }
        })
        .collect()
}

/// A(p, h) of one θ_i row traced at [`TRACED_OFFSETS`] offsets, the midpoints of equal steps
/// in γ = asin h, and read linearly in γ between them (held at the ends).
struct TracedRow {
    lobes: Vec<LobeValues>,
}

impl TracedRow {
    const STEP: f64 = PI / TRACED_OFFSETS as f64;

    fn new(az: &AzimuthalScattering, theta_i: f64) -> Self {
        let lobes = (0..TRACED_OFFSETS)
            .map(|j| az.attenuation(theta_i, Self::gamma_at(j).sin()))
            .collect();
        Self { lobes }
    }

    fn gamma_at(j: usize) -> f64 {
        -0.5 * PI + (j as f64 + 0.5) * Self::STEP
    }

    fn at(&self, gamma: f64) -> LobeValues {
        let x = ((gamma + 0.5 * PI) / Self::STEP - 0.5).clamp(0.0, (TRACED_OFFSETS - 1) as f64);
        let j = (x as usize).min(TRACED_OFFSETS - 2);
        let t = x - j as f64;
        let (a, b) = (&self.lobes[j].0, &self.lobes[j + 1].0);
        LobeValues(std::array::from_fn(|p| a[p] + (b[p] - a[p]) * t))
    }
}

/// One θ_i row of the blurred lobes: the quadrature nodes once ([`row_nodes`]), then
/// [`splat_row`].
fn fill_row(
    az: &AzimuthalScattering,
    selection: Option<Selection>,
    theta_i: f64,
    phi_nodes: usize,
    row: &mut [[Vec4; 3]],
) {
    splat_row(
        az,
        theta_i,
        &row_nodes(az, selection, theta_i),
        phi_nodes,
        row,
    );
}

/// For each blurred lobe and θ_d, the nodes' wrapped Gaussians splatted onto the φ columns
/// they reach.
fn splat_row(
    az: &AzimuthalScattering,
    theta_i: f64,
    nodes: &[RowNode],
    phi_nodes: usize,
    row: &mut [[Vec4; 3]],
) {
    let mut acc = vec![[0.0f64; 4]; phi_nodes];
    for (l, &p) in BLURRED.iter().enumerate() {
        // One splat for the lobe, or one per node where its spread varies with the offset.
        let fixed = Splat::new(az.v_n[p].sqrt(), phi_nodes);
        let splats: Vec<Splat> = match az.cuticle() {
            Some(c) if c.owns_exit(p) => nodes
                .iter()
                .map(|n| Splat::new(n.sigma[l], phi_nodes))
                .collect(),
            _ => vec![],
        };
        for d in 0..THETA_D_NODES {
            let eta_p = eta_perp_at(az.eta, d);
            acc.fill([0.0; 4]);
            for (n, node) in nodes.iter().enumerate() {
                let eta_p = az.lobe_eta_prime(p, theta_i, eta_p);
                let center = wrap_pi(azimuthal_deflection(p as u32, node.h, eta_p) + node.shift[l]);
                let a = node.a[l];
                let splat = splats.get(n).unwrap_or(&fixed);
                splat.add(center, [a.x, a.y, a.z, node.sel[l]], &mut acc);
            }
            for (cell, a) in row[d * phi_nodes..(d + 1) * phi_nodes].iter_mut().zip(&acc) {
                cell[l] = Vec4::from_array(a.map(|x| x as f32));
            }
        }
    }
}

/// A wrapped Gaussian of standard deviation σ added onto the φ columns of [0, π] it reaches
/// (8σ either side), every image c + 2πk of its centre.
struct Splat {
    sigma: f64,
    reach: f64,
    images: i32,
    step: f64,
    columns: usize,
    /// e^(−step²/σ²), the ratio of successive ratios of the Gaussian at the columns, where
    /// [`Splat::add`] steps along them by the recurrence; `None` where the columns are wider
    /// than σ and the ratios would leave f64's range.
    ratio_step: Option<f64>,
}

impl Splat {
    fn new(sigma: f64, columns: usize) -> Self {
        let reach = 8.0 * sigma;
        let step = PI / (columns - 1) as f64;
        Self {
            sigma,
            reach,
            images: ((reach + PI) / (2.0 * PI)).ceil() as i32,
            step,
            columns,
            ratio_step: (step <= sigma).then(|| (-(step * step) / (sigma * sigma)).exp()),
        }
    }

    /// Adds `value` times the Gaussian centred at `center` to the columns. Successive columns
    /// by g(x + s) = g(x) r, r(x + s) = r(x) e^(−s²/σ²) with r(x) = e^(−(x s + s²/2)/σ²): two
    /// exponentials per image instead of one per column ([`Splat::add_direct`] is its twin).
    fn add(&self, center: f64, value: [f64; 4], acc: &mut [[f64; 4]]) {
        let Some(q) = self.ratio_step else {
            return self.add_direct(center, value, acc);
        };
        let (s, inv_var) = (self.step, 1.0 / (self.sigma * self.sigma));
        for k in -self.images..=self.images {
            let c = center + 2.0 * PI * k as f64;
            let Some((lo, hi)) = self.columns_reached(c) else {
                continue;
            };
            let x = lo as f64 * s - c;
            let mut g = normal_pdf(x / self.sigma) / self.sigma;
            let mut r = (-(x * s + 0.5 * s * s) * inv_var).exp();
            for cell in &mut acc[lo..=hi] {
                for (o, v) in cell.iter_mut().zip(value) {
                    *o += g * v;
                }
                g *= r;
                r *= q;
            }
        }
    }

    /// [`Splat::add`] with the Gaussian evaluated at every column.
    fn add_direct(&self, center: f64, value: [f64; 4], acc: &mut [[f64; 4]]) {
        for k in -self.images..=self.images {
            let c = center + 2.0 * PI * k as f64;
            let Some((lo, hi)) = self.columns_reached(c) else {
                continue;
            };
            for (f, cell) in acc.iter_mut().enumerate().take(hi + 1).skip(lo) {
                let g = normal_pdf((f as f64 * self.step - c) / self.sigma) / self.sigma;
                for (o, v) in cell.iter_mut().zip(value) {
                    *o += g * v;
                }
            }
        }
    }

    /// The first and last column within reach of an image centred at c, if any.
    fn columns_reached(&self, c: f64) -> Option<(usize, usize)> {
        if c + self.reach < 0.0 || c - self.reach > PI {
            return None;
        }
        let lo = ((c - self.reach) / self.step).floor().max(0.0) as usize;
        let hi = (((c + self.reach) / self.step).ceil().max(0.0) as usize).min(self.columns - 1);
        Some((lo, hi))
    }
}

/// η′ at θ_d node d: the nodes are uniform in 1/η′ ∈ [0, 1/η], along which the azimuthal
/// deflections (and the TRT caustics) move almost linearly, where they race in θ_d near grazing.
fn eta_perp_at(eta: f64, d: usize) -> f64 {
    let u = d as f64 / (THETA_D_NODES - 1) as f64 / eta;
    if u > 0.0 { 1.0 / u } else { 1e12 }
}

/// θ_i at node i: θ_i = (π/2) x (2 − |x|) for x uniform on [−1, 1], denser toward grazing
/// incidence where the Fresnel factor, and with it A(p, h), changes fastest (the node spacing
/// shrinks linearly to zero there, as it would for (π/2) sin(πx/2)). Quadratic in x, so its
/// inverse [`theta_i_coord`] is one square root, where a sine axis needs an arcsine.
fn theta_i_at(i: usize) -> f64 {
    theta_i_of_coord(i as f64 / (THETA_I_NODES - 1) as f64)
}

/// θ_i at table coordinate c ∈ [0, 1] (x = 2c − 1), between the nodes too.
fn theta_i_of_coord(c: f64) -> f64 {
    let x = 2.0 * c - 1.0;
    0.5 * PI * x * (2.0 - x.abs())
}

/// The table coordinate in [0, 1] of θ_i (inverse of [`theta_i_at`]): with t = 2|θ_i|/π,
/// |x| = 1 − √(1 − t) = t / (1 + √(1 − t)), the second form free of cancellation near t = 0.
#[inline]
fn theta_i_coord(theta_i: f64) -> f64 {
    let t = (theta_i.abs() * (2.0 / PI)).min(1.0);
    let x = t / (1.0 + (1.0 - t).sqrt());
    0.5 + 0.5 * x.copysign(theta_i)
}

#[cfg(test)]
fn lerp4(a: Vec4, b: Vec4, t: f32) -> Vec4 {
    a + (b - a) * t
}

#[cfg(test)]
mod tests;
