//! The TT and TRT circular Gaussians of one fiber, fitted on the spot ([`FittedLobes`], the
//! reference) or read from a table over θ_d ([`LobeTable`]) that is rebuilt whenever a hair
//! parameter changes — Xu et al. 2011 §5 likewise updates its 1D textures "on the fly" — so that
//! shading interpolates the fits of [`crate::srbf::cg_lobes`] instead of redoing them at every
//! quadrature sample. Eccentric fibers add an η̄* axis to the TRT table (Xu et al. 2011 eq. 26).

use crate::scene::hair::caustic_bandwidth;
use crate::srbf::cg_lobes::{CausticMoments, Geometry, Lobe, TrtShape, trt_fit, tt_fit};
use crate::tables::absorption_axis;
use crate::tables::cg_integrals::Tables;
use crate::tables::grid::{Cell, Grid2};
use cuticle_fiber::models::marschner2003::MarschnerParams;
use glam::DVec3;
use std::f64::consts::PI;

/// N_TT of the three colour channels: a pair of circular Gaussians each, of one weight and
/// bandwidth, centred at π ± `offset` ([`tt_fit`]; Xu et al. 2011 eq. 16 is the pair at offset 0).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TtLobes {
    pub weight: [f64; 3],
    pub bandwidth: [f64; 3],
    pub offset: [f64; 3],
}

impl TtLobes {
    /// The pair of `channel`: centres π + δ and π − δ.
    pub fn lobes(&self, channel: usize) -> [Lobe; 2] {
        [1.0, -1.0].map(|side| Lobe {
            weight: self.weight[channel],
            centre: PI + side * self.offset[channel],
            bandwidth: self.bandwidth[channel],
        })
    }
}

/// N_TRT of the three colour channels in the slots of [`trt_fit`] (glint at +φ*, glint at −φ*,
/// centre), whose centres the channels share (Xu et al. 2011 eqs. 20–22).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TrtLobes {
    /// The slots' centres: φ*, −φ*, 0.
    pub centre: [f64; 3],
    /// `weight[channel][slot]`.
    pub weight: [[f64; 3]; 3],
    /// `bandwidth[channel][slot]`.
    pub bandwidth: [[f64; 3]; 3],
}

impl TrtLobes {
    pub fn lobe(&self, channel: usize, slot: usize) -> Lobe {
        Lobe {
            weight: self.weight[channel][slot],
            centre: self.centre[slot],
            bandwidth: self.bandwidth[channel][slot],
        }
    }

    /// Σ_slot weight × `unit(slot, bandwidth)` of each channel, `unit` being a slot's response
    /// per unit weight: computed once per slot and bandwidth, since the channels share the
    /// glints and the centre below η′ = 2 (only the weights differ there).
    pub fn weighted_sum(&self, mut unit: impl FnMut(usize, f64) -> f64) -> DVec3 {
        let mut cache: [Option<(f64, f64)>; 3] = [None; 3];
        DVec3::from_array(std::array::from_fn(|c| {
            (0..3)
                .map(|s| {
                    let (weight, bandwidth) = (self.weight[c][s], self.bandwidth[c][s]);
                    if weight == 0.0 {
                        return 0.0;
                    }
                    let value = match cache[s] {
                        Some((b, v)) if b == bandwidth => v,
                        _ => {
                            let v = unit(s, bandwidth);
                            cache[s] = Some((bandwidth, v));
                            v
                        }
                    };
                    weight * value
                })
                .sum()
        }))
    }

    fn from_fits(fits: [[Lobe; 3]; 3]) -> Self {
        Self {
            centre: fits[0].map(|l| l.centre),
            weight: fits.map(|f| f.map(|l| l.weight)),
            bandwidth: fits.map(|f| f.map(|l| l.bandwidth)),
        }
    }
}

/// Where shading takes a fiber's TT and TRT lobes from.
pub trait AzimuthalLobes {
    /// N_TT at θ_d.
    fn tt(&self, theta_d: f64) -> TtLobes;
    /// N_TRT at θ_d for index `eta` (η̄* of an eccentric fiber, η otherwise).
    fn trt(&self, eta: f64, theta_d: f64) -> TrtLobes;
}

/// The fits made at each call: exact to [`crate::srbf::cg_lobes`], and slow.
#[derive(Clone, Copy, Debug)]
pub struct FittedLobes<'a> {
    pub tables: &'a Tables,
    pub fiber: &'a MarschnerParams,
}

impl AzimuthalLobes for FittedLobes<'_> {
    fn tt(&self, theta_d: f64) -> TtLobes {
        let g = Geometry::new(self.tables, self.fiber.eta, theta_d);
        let lobes: [Lobe; 3] = std::array::from_fn(|c| tt_fit(&g, self.fiber.mu_a[c]));
        TtLobes {
            weight: lobes.map(|l| l.weight),
            bandwidth: lobes.map(|l| l.bandwidth),
            offset: lobes.map(|l| l.centre - PI),
        }
    }

    fn trt(&self, eta: f64, theta_d: f64) -> TrtLobes {
        let g = Geometry::new(self.tables, eta, theta_d);
        let shape = trt_shape(self.fiber);
        let caustics = CausticMoments::new(&g, shape);
        TrtLobes::from_fits(std::array::from_fn(|c| {
            trt_fit(&g, &caustics, self.fiber.mu_a[c], shape)
        }))
    }
}

/// Nodes over |θ_d| ∈ [0, THETA_D_MAX] (every lobe is even in θ_d): 0.003 rad apart.
const THETA_D_NODES: usize = 512;
/// Largest |θ_d| tabulated; cos θ_d is then 0.01 and the integrand's cos²θ_i nearly zero.
const THETA_D_MAX: f64 = 1.56;
/// Nodes over the [`absorption_axis`].
const MU_A_NODES: usize = 256;

/// The lobes of one colour channel, fitted at every node of (|θ_d|, ln(1 + μ_a/0.02)) for a
/// fiber's η and TRT shape: per-strand absorption (every strand of a preset groom differs) and
/// absorption edits read the same table, and only η or the caustic parameters rebuild it.
/// Between nodes the weights are interpolated linearly: where the interpolation errs most, at
/// strong absorption, the weights are e^{−2σ′} small (measured in the tests below).
#[derive(Clone, Debug)]
pub struct LobeTable {
    eta: f64,
    shape: TrtShape,
    /// [weight, bandwidth, offset] of TT over (|θ_d|, x).
    tt: Grid2<3>,
    /// [φ*, glint weight, glint bandwidth, centre weight, centre bandwidth] of TRT over
    /// (|θ_d|, x).
    trt: Grid2<5>,
}

impl LobeTable {
    /// Fits the lobes of a fiber with `fiber`'s η and caustics at every node (≈ 20 ms on two
    /// cores).
    pub fn build(tables: &Tables, fiber: &MarschnerParams) -> Self {
        let shape = trt_shape(fiber);
        let eta = fiber.eta;
        let axes = (
            (THETA_D_NODES, 0.0, THETA_D_MAX),
            (MU_A_NODES, 0.0, absorption_axis::max_coordinate()),
        );
        let fit = |td: f64, x: f64| (Geometry::new(tables, eta, td), absorption_axis::mu_a(x));
        let tt = Grid2::build(axes.0, axes.1, |td, x| {
            let (g, mu_a) = fit(td, x);
            let tt = tt_fit(&g, mu_a);
            [tt.weight, tt.bandwidth, tt.centre - PI]
        });
        // The caustic moments depend on θ_d alone: once per θ_d node.
        let caustics: Vec<CausticMoments> = (0..THETA_D_NODES)
            .map(|i| {
                let td = THETA_D_MAX * i as f64 / (THETA_D_NODES - 1) as f64;
                CausticMoments::new(&Geometry::new(tables, eta, td), shape)
            })
            .collect();
        let trt = Grid2::build(axes.0, axes.1, |td, x| {
            let (g, mu_a) = fit(td, x);
            let node = (td / THETA_D_MAX * (THETA_D_NODES - 1) as f64).round() as usize;
            let [glint, _, centre] = trt_fit(&g, &caustics[node], mu_a, shape);
            [
                glint.centre,
                glint.weight,
                glint.bandwidth,
                centre.weight,
                centre.bandwidth,
            ]
        });
        Self {
            eta,
            shape,
            tt,
            trt,
        }
    }

    /// The grids as stored over (|θ_d|, absorption coordinate): TT [weight, bandwidth, offset] and
    /// TRT [φ*, glint weight, glint bandwidth, centre weight, centre bandwidth].
    pub fn grids(&self) -> (&Grid2<3>, &Grid2<5>) {
        (&self.tt, &self.trt)
    }

    /// Whether this table holds the lobes of `fiber` (its η and caustics; absorption is an axis).
    pub fn matches(&self, fiber: &MarschnerParams) -> bool {
        self.eta == fiber.eta && self.shape == trt_shape(fiber)
    }

    /// The table's lobes for one fiber, whose TRT is fitted on the spot if it is eccentric
    /// (its η̄* varies with the light; the table holds one η).
    pub fn for_fiber<'a>(
        &'a self,
        tables: &'a Tables,
        fiber: &'a MarschnerParams,
    ) -> TabulatedLobes<'a> {
        debug_assert!(self.matches(fiber));
        TabulatedLobes {
            table: self,
            fitted: FittedLobes { tables, fiber },
            x: fiber
                .mu_a
                .to_array()
                .map(|mu| self.tt.cell_y(absorption_axis::coordinate(mu))),
            eccentric: fiber.eccentricity != 1.0,
        }
    }
}

/// A [`LobeTable`] read for one fiber's three absorptions.
#[derive(Clone, Copy, Debug)]
pub struct TabulatedLobes<'a> {
    table: &'a LobeTable,
    fitted: FittedLobes<'a>,
    /// Each channel's cell on the absorption axis (both grids share their axes).
    x: [Cell; 3],
    eccentric: bool,
}

impl AzimuthalLobes for TabulatedLobes<'_> {
    fn tt(&self, theta_d: f64) -> TtLobes {
        let cell = self.table.tt.cell_x(theta_d.abs());
        let v = self.x.map(|x| self.table.tt.lookup_cells(cell, x));
        TtLobes {
            weight: v.map(|v| v[0]),
            bandwidth: v.map(|v| v[1]),
            offset: v.map(|v| v[2]),
        }
    }

    fn trt(&self, eta: f64, theta_d: f64) -> TrtLobes {
        if self.eccentric {
            return self.fitted.trt(eta, theta_d);
        }
        let cell = self.table.trt.cell_x(theta_d.abs());
        let v = self.x.map(|x| self.table.trt.lookup_cells(cell, x));
        TrtLobes {
            centre: [v[0][0], -v[0][0], 0.0],
            weight: v.map(|v| [v[1], v[1], v[3]]),
            bandwidth: v.map(|v| [v[2], v[2], v[4]]),
        }
    }
}

/// The absorption-independent shape of a fiber's TRT fit.
pub fn trt_shape(fiber: &MarschnerParams) -> TrtShape {
    TrtShape {
        caustic_bandwidth: caustic_bandwidth(fiber),
        caustic_fade: fiber.caustic_fade,
        glint_scale: fiber.glint_scale,
        caustic_limit: fiber.caustic_limit,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::OnceLock;

    fn tables() -> &'static Tables {
        static T: OnceLock<Tables> = OnceLock::new();
        T.get_or_init(Tables::build)
    }

    /// Σ over lobes of the lobe convolved with a light of bandwidth λ′ at offset δ: what
    /// shading reads.
    fn response(lobes: impl Iterator<Item = Lobe>, lambda: f64, delta: f64) -> f64 {
        lobes.map(|l| l.convolve(lambda, delta)).sum()
    }

    /// TT and TRT responses of channel `c` from two sources of lobes.
    fn pairs(
        a: &impl AzimuthalLobes,
        b: &impl AzimuthalLobes,
        eta: f64,
        td: f64,
        c: usize,
        (lambda, delta): (f64, f64),
    ) -> [(f64, f64); 2] {
        let tt = |l: &dyn Fn() -> TtLobes| response(l().lobes(c).into_iter(), lambda, delta);
        let trt =
            |l: &dyn Fn() -> TrtLobes| response((0..3).map(|s| l().lobe(c, s)), lambda, delta);
        [
            (tt(&|| a.tt(td)), tt(&|| b.tt(td))),
            (trt(&|| a.trt(eta, td)), trt(&|| b.trt(eta, td))),
        ]
    }

    /// The table against the fits it interpolates, as shading sees them (convolved with a
    /// light), over θ_d in steps that fall between nodes, absorptions between nodes from
    /// blond to black, lights narrow and wide, and through the merge of the TRT glints at
    /// η′ = 2 (θ_d ≈ 0.9 at η = 1.55), relative to the largest response of each sweep (all
    /// three channels): within 0.2 % for a blond-to-brown fiber (measured 0.09 %), 5 % for a
    /// black one (measured 4.1 % with the TT pair, 0.72 % with eq. 16's single Gaussian: between
    /// absorption nodes e^{−2σ′} is far from linear and the pair's offset δ is interpolated
    /// too; its responses are 1e-4 of the blond ones).
    #[test]
    fn table_matches_the_fits_it_interpolates() {
        let fiber = MarschnerParams::default();
        let table = LobeTable::build(tables(), &fiber);
        for (mu_a, bound) in [
            (DVec3::new(0.033, 0.41, 1.57), 2e-3),
            (DVec3::new(2.9, 4.3, 7.7), 5e-2),
        ] {
            let fiber = MarschnerParams { mu_a, ..fiber };
            assert!(table.matches(&fiber));
            let tabulated = table.for_fiber(tables(), &fiber);
            let fitted = FittedLobes {
                tables: tables(),
                fiber: &fiber,
            };
            for light in [(0.05, 0.1), (0.4, 2.9), (1.5, 1.0)] {
                let (mut worst, mut largest) = (0.0f64, 0.0f64);
                for i in 0..700 {
                    let td = -1.45 + 2.9 * (i as f64 + 0.37) / 700.0;
                    for c in 0..3 {
                        for (got, want) in pairs(&tabulated, &fitted, fiber.eta, td, c, light) {
                            worst = worst.max((got - want).abs());
                            largest = largest.max(want.abs());
                        }
                    }
                }
                assert!(
                    worst <= bound * largest,
                    "μ_a {mu_a}, light {light:?}: {worst} of {largest}"
                );
            }
        }
    }

    /// A table serves every absorption but only its η and caustics; an eccentric fiber's TRT,
    /// whose η̄* the table does not cover, is the fit itself.
    #[test]
    fn table_covers_absorption_and_fits_eccentric_trt() {
        let fiber = MarschnerParams::default();
        let table = LobeTable::build(tables(), &fiber);
        assert!(table.matches(&MarschnerParams {
            mu_a: DVec3::splat(9.0),
            ..fiber
        }));
        assert!(!table.matches(&MarschnerParams { eta: 1.6, ..fiber }));
        assert!(!table.matches(&MarschnerParams {
            caustic_width: 0.2,
            ..fiber
        }));
        let eccentric = MarschnerParams {
            eccentricity: 0.85,
            ..fiber
        };
        let fitted = FittedLobes {
            tables: tables(),
            fiber: &eccentric,
        };
        let tabulated = table.for_fiber(tables(), &eccentric);
        assert_eq!(tabulated.trt(1.7, 0.3), fitted.trt(1.7, 0.3));
    }
}
