//! The tabulated fast path for the azimuthal terms of d'Eon 2011 (d'Eon et al. 2014 eq. 4): N_p built
//! once per parameter set over (θ_i, |θ_d|, |φ|), read back by trilinear interpolation, as
//! production renderers do instead of integrating over h at every evaluation.
//!
//! The table holds TT, TRT and TRRT (RGB, plus the lobe-selection density importance sampling
//! uses), and the p ≥ 4 remainder over θ_i alone; R has a closed form and needs no table.
//! N_p is even in φ (A is even in h, Φ odd about pπ) and depends on θ_d only through
//! η′, so φ is folded to [0, π] and θ_d is tabulated along 1/η′ ∈ [0, 1/η]. The φ spacing follows the
//! narrowest azimuthal lobe (a third of its standard deviation, 64 to 1024 columns); below
//! β ≈ 0.02 the cap binds and the table blurs the narrowest lobes. Each row holds its lobes'
//! shapes, normalised; their energies over θ_i come from a finer axis (`table/energy.rs`),
//! since a lobe's energy can fall by an order of magnitude between two rows. Its error
//! against direct quadrature is measured in the tests below and in BENCHMARKS.md.

mod energy;

use crate::azimuthal::{
    AzimuthalScattering, PANEL_NODES, Weighting, rest_integral, selection_from,
};
use crate::bravais::{azimuthal_deflection, eta_prime};
use crate::frame::wrap_pi;
use crate::lobe::LobeValues;
use crate::special::{GaussLegendre, normal_pdf};
use energy::{ENERGY_NODES, LobeEnergies, normalise_rows};
use glam::{DVec3, DVec4, Vec4};
use std::f64::consts::{FRAC_PI_2, PI};

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

    /// N_p(φ) for TT, TRT, TRRT and the remainder, the lobes the table holds: [`AzimuthalTable::eval_all`]
    /// without R, for a caller that has R's offsets already.
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
    if az.surface().is_flat_and_smooth() || panels * PANEL_NODES <= TRACED_OFFSETS {
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
        let splats: Vec<Splat> = match az.rough_tt {
            Some(_) if p == 1 => nodes
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

/// How far inside ±π/2 the end nodes of an evenly spaced θ_i axis are evaluated: at the poles
/// the fiber's frame degenerates.
pub(crate) const GRAZING: f64 = 1e-4;

/// Node i of `nodes` evenly spaced over θ_i ∈ [−π/2, π/2], the ends [`GRAZING`] inside.
pub(crate) fn theta_i_node(i: usize, nodes: usize) -> f64 {
    (-FRAC_PI_2 + PI * i as f64 / (nodes - 1) as f64)
        .clamp(-FRAC_PI_2 + GRAZING, FRAC_PI_2 - GRAZING)
}

/// The lower node and the fraction toward the next for a coordinate t ∈ [0, 1] on n nodes.
#[inline]
pub(crate) fn locate(t: f64, n: usize) -> (usize, f32) {
    // t ≥ 0 (every coordinate is), so truncation is the floor. The clamp to the last cell
    // happens in f64 before the cast (NaN goes to the last cell, f64::min keeping the
    // number), and the cast's saturation sends any negative to node 0.
    let x = t * (n - 1) as f64;
    let i = x.min((n - 2) as f64) as u32 as usize;
    (i, (x - i as f64) as f32)
}

/// A per-process cache of tables keyed by the parameters they were built for.
pub(crate) type SharedTables<K, T> =
    std::sync::OnceLock<std::sync::Mutex<std::collections::HashMap<K, std::sync::Arc<T>>>>;

/// The table for `key` from `cache`, built by `build` the first time it is asked for. It is
/// built outside the lock, so that other keys need not wait for this one; two threads that
/// race for one key both build it and keep the first.
pub(crate) fn shared_table<K: std::hash::Hash + Eq, T>(
    cache: &SharedTables<K, T>,
    key: K,
    build: impl FnOnce() -> T,
) -> std::sync::Arc<T> {
    let cache = cache.get_or_init(Default::default);
    if let Some(found) = cache.lock().unwrap_or_else(|e| e.into_inner()).get(&key) {
        return found.clone();
    }
    let built = std::sync::Arc::new(build());
    let mut map = cache.lock().unwrap_or_else(|e| e.into_inner());
    map.entry(key).or_insert(built).clone()
}

/// Fills a row-major grid, `fill(row index, row)` for each row of `row_len` cells, the rows
/// shared out over every available core.
pub(crate) fn fill_rows<T: Send>(
    cells: &mut [T],
    row_len: usize,
    fill: impl Fn(usize, &mut [T]) + Sync,
) {
    let rows = cells.len() / row_len;
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let rows_per_thread = rows.div_ceil(threads).max(1);
    let fill = &fill;
    std::thread::scope(|s| {
        for (t, chunk) in cells.chunks_mut(rows_per_thread * row_len).enumerate() {
            s.spawn(move || {
                for (r, row) in chunk.chunks_mut(row_len).enumerate() {
                    fill(t * rows_per_thread + r, row);
                }
            });
        }
    });
}

/// The bilinear blend of a row-major grid of texels: cell `at` and its neighbours along the
/// row (`at + 1`) and the next row (`at + stride`), at fractions `f_row` across rows and
/// `f_col` along them.
#[inline]
pub(crate) fn bilinear<const N: usize>(
    texels: &[[f32; N]],
    at: usize,
    stride: usize,
    f_row: f32,
    f_col: f32,
) -> [f32; N] {
    let weights = [
        (1.0 - f_row) * (1.0 - f_col),
        (1.0 - f_row) * f_col,
        f_row * (1.0 - f_col),
        f_row * f_col,
    ];
    let taps = [at, at + 1, at + stride, at + stride + 1];
    let mut out = [0.0f32; N];
    for (tap, w) in taps.into_iter().zip(weights) {
        for (o, t) in out.iter_mut().zip(&texels[tap]) {
            *o += w * t;
        }
    }
    out
}

#[cfg(test)]
fn lerp4(a: Vec4, b: Vec4, t: f32) -> Vec4 {
    a + (b - a) * t
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Per lobe (TT, TRT, TRRT, rest) and for their sum: Σ|table − direct| / Σ direct over a
    /// grid of (θ_i, θ_o, φ) that falls between the table's nodes.
    fn relative_l1(beta: f64) -> [f64; 5] {
        let az = AzimuthalScattering::new(1.55, beta, DVec3::new(0.1, 0.4, 1.2));
        let table = AzimuthalTable::build(&az);
        let (mut err, mut mass) = ([0.0; 5], [0.0; 5]);
        for k in 0..17 {
            let theta_i = -1.45 + 2.9 * (k as f64 + 0.37) / 17.0;
            for theta_o in [-1.31, -0.52, 0.07, 0.66, 1.38] {
                let theta_d = 0.5 * (theta_o - theta_i);
                for f in 0..97 {
                    let phi = -PI + 2.0 * PI * (f as f64 + 0.29) / 97.0;
                    let (mut sum_direct, mut sum_fast) = (0.0, 0.0);
                    for p in 1..5 {
                        let direct = az.eval(p, theta_i, theta_d, phi, Weighting::Attenuation).x;
                        let fast = table
                            .eval(p, theta_i, theta_d, phi, Weighting::Attenuation)
                            .x;
                        err[p - 1] += (direct - fast).abs();
                        mass[p - 1] += direct;
                        sum_direct += direct;
                        sum_fast += fast;
                    }
                    err[4] += (sum_direct - sum_fast).abs();
                    mass[4] += sum_direct;
                }
            }
        }
        std::array::from_fn(|k| err[k] / mass[k])
    }

    /// Measured (quoted in BENCHMARKS.md): the sum of the tabulated lobes is within 0.5 % in L1
    /// and TT within 0.1 %; TRT (2 %) and TRRT (7 % at β = 0.04) are coarser, because their
    /// caustics move with η′(θ_d) faster than 32 nodes in 1/η′ follow.
    #[test]
    fn table_follows_direct_quadrature() {
        for beta in [0.04, 0.15, 0.3] {
            let e = relative_l1(beta);
            println!(
                "β {beta}: relative L1 TT {:.5} TRT {:.5} TRRT {:.5} rest {:.5} sum {:.5}",
                e[0], e[1], e[2], e[3], e[4]
            );
            assert!(e[0] < 0.002 && e[4] < 0.005, "β {beta}: {e:?}");
            assert!(e[1] < 0.03 && e[2] < 0.1 && e[3] < 0.01, "β {beta}: {e:?}");
        }
    }

    /// The square-root inverse against the axis it inverts, over every node and a dense grid
    /// between them. In θ_i the round trip is within 1e-15; in the coordinate, within 4e-15
    /// away from the ends and 1e-12 at them (the axis is flat at grazing, dθ_i/dx → 0, so a
    /// rounding of θ_i moves x by more, as it would through an arcsine): far below the 6e-8
    /// resolution of the table's f32 fractions.
    #[test]
    fn theta_i_coordinate_inverts_the_node_placement() {
        let (mut in_theta, mut inner, mut ends): (f64, f64, f64) = (0.0, 0.0, 0.0);
        let nodes = (0..THETA_I_NODES).map(|i| i as f64 / (THETA_I_NODES - 1) as f64);
        for c in (0..=100_000).map(|k| k as f64 / 100_000.0).chain(nodes) {
            let theta = theta_i_of_coord(c);
            let back = theta_i_coord(theta);
            in_theta = in_theta.max((theta_i_of_coord(back) - theta).abs());
            let e = (back - c).abs();
            if (c - 0.5).abs() < 0.49 {
                inner = inner.max(e);
            } else {
                ends = ends.max(e);
            }
        }
        eprintln!(
            "θ_i coordinate round trip: θ_i {in_theta:.2e}, coordinate {inner:.2e} inside, {ends:.2e} at the ends"
        );
        assert!(
            in_theta < 1e-15 && inner < 4e-15 && ends < 1e-12,
            "{in_theta:e} {inner:e} {ends:e}"
        );
        assert_eq!(theta_i_coord(2.0), 1.0);
        assert_eq!(theta_i_coord(-2.0), 0.0);
        assert_eq!(theta_i_coord(0.0), 0.5);
        // Denser toward grazing: the last cell is the narrowest, the middle one the widest.
        let cell = |i: usize| theta_i_at(i + 1) - theta_i_at(i);
        assert!(cell(THETA_I_NODES - 2) < cell(THETA_I_NODES / 2 - 1));
    }

    /// The corner-weight taps against the nested lerps, at points between the nodes, on the
    /// nodes and at the table's far corners: within 1e-6 of the largest texel involved (f32
    /// arithmetic in another order).
    #[test]
    fn selection_taps_are_the_taps_selection() {
        let az = AzimuthalScattering::new(1.55, 0.1, DVec3::new(0.2, 0.5, 1.1));
        let table = AzimuthalTable::build(&az);
        let mut compared = 0;
        for k in 0..23 {
            let theta_i = (k as f64 / 22.0 - 0.5) * 0.9999 * PI;
            for eta_ratio in [0.0, 0.13, 0.5, 0.77, 1.0] {
                for f in 0..41 {
                    let phi = -PI + 2.0 * PI * f as f64 / 40.0;
                    let at = table.point(theta_i, eta_ratio, phi);
                    let full = table.taps(at).map(|t| t.w);
                    assert_eq!(table.selection_taps(at), full, "θ_i {theta_i} φ {phi}");
                    compared += 1;
                }
            }
        }
        assert_eq!(compared, 23 * 5 * 41);
    }

    #[test]
    fn corner_weights_match_the_nested_lerps() {
        let az = AzimuthalScattering::new(1.55, 0.1, DVec3::new(0.2, 0.5, 1.1));
        let table = AzimuthalTable::build(&az);
        let mut worst: f32 = 0.0;
        for k in 0..23 {
            let theta_i = (k as f64 / 22.0 - 0.5) * 0.9999 * PI;
            for (d, eta_ratio) in [0.0, 0.13, 0.5, 0.77, 1.0].into_iter().enumerate() {
                for f in 0..41 {
                    let phi = -PI + 2.0 * PI * (f as f64 + 0.1 * d as f64) / 40.0;
                    let at = table.point(theta_i, eta_ratio, phi);
                    let (fast, nested) = (table.taps(at), table.taps_nested(at));
                    for (a, b) in fast.iter().zip(&nested) {
                        let scale = a.abs().max(b.abs()).max_element().max(1e-3);
                        worst = worst.max((*a - *b).abs().max_element() / scale);
                    }
                }
            }
        }
        eprintln!("corner-weight taps vs nested lerps: ≤ {worst:.2e} of the texel");
        assert!(worst < 1e-6, "{worst:e}");
    }

    /// The locate of the simplified clamp against its twin by floor and min: the same cell
    /// and the same fraction (bit for bit) on every coordinate in [0, 1]; NaN stays in the
    /// table (the last cell, f64::min keeping the number).
    #[test]
    fn locate_matches_floor_and_min() {
        for n in [THETA_D_NODES, THETA_I_NODES, 1024] {
            for k in 0..=20_011 {
                let t = k as f64 / 20_011.0;
                let x = t * (n - 1) as f64;
                let i = (x.floor() as usize).min(n - 2);
                assert_eq!(locate(t, n), (i, (x - i as f64) as f32), "n {n} t {t}");
            }
            assert_eq!(locate(1.0, n), (n - 2, 1.0));
            assert_eq!(locate(f64::NAN, n).0, n - 2);
        }
    }

    /// The Gaussian stepped along the columns by its ratio recurrence against the Gaussian at
    /// every column, for widths of one to forty columns (the table's lobes are one to six wide)
    /// and centres whose images wrap past 0 and π: within 1e-12 of the peak up to six columns,
    /// 1e-10 at forty (the rounding of e^(−s²/σ²) compounds over the 16σ/s steps), far below
    /// the table's f32 texels.
    #[test]
    fn splat_recurrence_matches_the_gaussian_at_every_column() {
        let columns = 1024;
        let step = PI / (columns - 1) as f64;
        for (sigma, bound) in [
            (step, 1e-12),
            (2.7 * step, 1e-12),
            (6.0 * step, 1e-12),
            (40.0 * step, 1e-10),
        ] {
            let splat = Splat::new(sigma, columns);
            assert!(splat.ratio_step.is_some());
            for center in [1e-3 - PI, -0.01, 0.0, 0.37, 1.5 + 0.3 * step, PI, PI - 1e-3] {
                let value = [1.0, 0.5, -2.0, 3.0];
                let (mut fast, mut direct) = (vec![[0.0; 4]; columns], vec![[0.0; 4]; columns]);
                splat.add(center, value, &mut fast);
                splat.add_direct(center, value, &mut direct);
                let peak = 3.0 / (sigma * (2.0 * PI).sqrt());
                let worst = fast
                    .iter()
                    .flatten()
                    .zip(direct.iter().flatten())
                    .map(|(a, b)| (a - b).abs())
                    .fold(0.0, f64::max);
                assert!(
                    worst < bound * peak,
                    "σ {sigma} centre {center}: {:e}",
                    worst / peak
                );
                assert!(direct.iter().flatten().any(|v| v.abs() > 1e-3 * peak));
            }
        }
        assert!(Splat::new(0.5 * step, columns).ratio_step.is_none());
    }

    /// Rows of a fiber with tilted, rough scales at β = 0.005, whose narrow lobes need more
    /// quadrature nodes than [`TRACED_OFFSETS`], built with A(p, h) interpolated between the
    /// traced offsets against the same rows with A traced at every node.
    #[test]
    fn interpolated_attenuation_follows_the_traced_one() {
        let beta = 0.005;
        let az = AzimuthalScattering::new(1.55, beta, DVec3::new(0.1, 0.4, 1.2))
            .with_scale_tilt((-4.0f64).to_radians())
            .with_rough_surface(beta);
        let panels = BLURRED
            .iter()
            .map(|&p| az.panel_count(p, az.eta))
            .max()
            .unwrap();
        assert!(
            panels * PANEL_NODES > TRACED_OFFSETS,
            "the rows must interpolate"
        );
        let phi_nodes = MAX_PHI_NODES;
        let slab = THETA_D_NODES * phi_nodes;
        let (mut err, mut mass, mut worst, mut peak) =
            ([0.0f64; 3], [0.0f64; 3], [0.0f64; 3], [0.0f64; 3]);
        for i in [4, 20, 33, 47, 58, 62] {
            let theta_i = theta_i_at(i);
            let (mut fast, mut traced) = (vec![[Vec4::ZERO; 3]; slab], vec![[Vec4::ZERO; 3]; slab]);
            fill_row(&az, None, theta_i, phi_nodes, &mut fast);
            let nodes = row_nodes_on(&az, None, theta_i, panels, |_, h| {
                az.attenuation(theta_i, h)
            });
            splat_row(&az, theta_i, &nodes, phi_nodes, &mut traced);
            for (f, t) in fast.iter().zip(&traced) {
                for l in 0..3 {
                    let (a, b) = (f[l].x as f64, t[l].x as f64);
                    err[l] += (a - b).abs();
                    mass[l] += b;
                    worst[l] = worst[l].max((a - b).abs());
                    peak[l] = peak[l].max(b);
                }
            }
        }
        let l1: [f64; 3] = std::array::from_fn(|l| err[l] / mass[l]);
        let max: [f64; 3] = std::array::from_fn(|l| worst[l] / peak[l]);
        eprintln!(
            "interpolated A: relative L1 {l1:?}, largest error {max:?} of the peak (TT, TRT, TRRT)"
        );
        assert!(
            l1.iter().all(|e| *e < 1e-4) && max.iter().all(|e| *e < 5e-4),
            "{l1:?} {max:?}"
        );
    }

    /// Between two θ_i rows where TT's energy falls by a factor of 10 (its exit through
    /// scales tilted by 4° passes the critical angle, β = 0.02), the table's N_TT integrated
    /// over φ, at three θ_d, against ½ ∫ A(1, h) dh traced at that θ_i itself: within 2 %
    /// (measured 1.0 %), where a linear blend of the rows' energies is a quarter too bright
    /// and more ([`energy`]).
    #[test]
    fn energy_follows_the_lobe_between_the_nodes() {
        let beta = 0.02;
        let az = AzimuthalScattering::new(1.55, beta, DVec3::ZERO)
            .with_scale_tilt(4f64.to_radians())
            .with_rough_surface(beta);
        let table = AzimuthalTable::build(&az);
        let (lo, hi) = (theta_i_at(45), theta_i_at(46));
        let energy = |theta_i: f64| {
            crate::tilted_attenuation::energy_budget(theta_i, az.surface(), DVec3::ZERO)
                .lobes
                .0[1]
                .x
        };
        assert!(energy(lo) > 10.0 * energy(hi), "the rows must differ");
        let columns = 8192;
        let mut worst = 0.0f64;
        for theta_i in [1.07, 1.085, 1.1] {
            let exact = energy(theta_i);
            let t = (theta_i_coord(theta_i) * (THETA_I_NODES - 1) as f64).fract();
            let blend = energy(lo) + t * (energy(hi) - energy(lo));
            assert!(blend > 1.25 * exact, "θ_i {theta_i}: {blend} {exact}");
            for theta_d in [-theta_i, -0.3, 0.2] {
                let integral: f64 = (0..columns)
                    .map(|f| {
                        let phi = -PI + 2.0 * PI * (f as f64 + 0.5) / columns as f64;
                        table
                            .eval(1, theta_i, theta_d, phi, Weighting::Attenuation)
                            .x
                    })
                    .sum::<f64>()
                    * 2.0
                    * PI
                    / columns as f64;
                worst = worst.max((integral / exact - 1.0).abs());
            }
        }
        eprintln!("TT's energy between the rows: within {worst:.2e}");
        assert!(worst < 0.02, "{worst:e}");
    }

    #[test]
    fn selection_and_attenuation_tables_agree_for_a_grey_lossless_fiber() {
        let az = AzimuthalScattering::new(1.55, 0.1, DVec3::ZERO);
        let table = AzimuthalTable::build(&az);
        for phi in [-2.9, -0.4, 0.0, 1.3, 3.1] {
            let a = table.eval(1, 0.4, -0.3, phi, Weighting::Attenuation).x;
            let s = table.eval(1, 0.4, -0.3, phi, Weighting::Selection).x;
            assert!((a - s).abs() < 1e-5 * a.max(1e-3), "{a} {s}");
        }
    }
}
