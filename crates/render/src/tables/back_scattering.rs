//! The averaged scattering functions of dual scattering (Zinke et al. 2008 §4; Xu et al. 2011
//! §4.3), tabulated over θ_d × absorption and rebuilt whenever a hair parameter changes (Xu et al.
//! 2011 §5: "the 1D textures are computed and updated on the fly").
//!
//! For one absorption channel, the forward and backward attenuations of mode p are the shares
//! of its energy leaving into the forward (|φ| > π/2) and backward (|φ| < π/2) half circle,
//! a_{f,p}(θ_d) = ∫_{|φ|>π/2} N_p dφ and a_{b,p}(θ_d) = ∫_{|φ|<π/2} N_p dφ, computed exactly in
//! the variable h (∫ N_p dφ = ½ ∫ A_p(h) dh over the h whose deflection Φ(p, h) lands in the
//! half), with ā_f = Σ_p a_{f,p}, ā_b = Σ_p a_{b,p}. The lobe shifts and widths are the
//! attenuation-weighted means α_f = Σ a_{f,p} α_p / ā_f, β_f² = Σ a_{f,p} β_p² / ā_f (likewise b).
//!
//! What comes back to the shading point from its neighbourhood is formed for a Poisson medium
//! of fibers (Zinke et al. 2008 §4's statistical hair, and the medium `tests/slab.rs` traces):
//! along any direction fibers are met at a constant rate ρ, independently on the way out and
//! on the way back. A path leaves through the shading fiber (ā_f), is back-scattered at depth
//! z (ρ dz ā_b) and returns, crossing N_out and N_back ~ Poisson(ρz) fibers forward, each
//! passing ā_f, so E[ā_f^N] = e^{−ρz(1−ā_f)} each way:
//! - A₁ = ā_f ā_b ∫₀^∞ ρ e^{−2ρz(1−ā_f)} dz = ā_f ā_b / (2(1 − ā_f)),
//! - A₃ = ā_f ā_b³ / (8(1 − ā_f)³), for three back-scattering events at depths z₁, z₂, z₃
//!   with z₂ < min(z₁, z₃) (the path's length 2(z₁ − z₂) + 2(z₃ − z₂) + 2z₂, three
//!   independent exponentials of rate 2ρ(1 − ā_f)),
//! - Ā_b = A₁ + A₃.
//!
//! Both tend to Zinke et al. 2008's A₁ = ā_b ā_f² / (1 − ā_f²) and A₃ = ā_b³ ā_f² / (1 − ā_f²)³
//! as ā_f → 1, but are larger for dark hair (A₁ by (1 + ā_f) / (2ā_f)): Zinke's lattice sends
//! a path back through exactly the fibers it came through, a random medium does not. Under the
//! same weights a path of k back-scattering events crosses n̄₁ = 1/(1 − ā_f) and
//! n̄₃ = 1 + 3ā_f/(1 − ā_f) fibers forward on average, so its lobe is shifted by
//! k α_b + n̄_k α_f and widened to a variance k β_b² + n̄_k β_f² (independent lobes add; the
//! spread of the count, α_f² Var n, is neglected beside β_f² n̄):
//! - Δ̄_b = Σ_k A_k (k α_b + n̄_k α_f) / Ā_b,
//! - σ̄_b² = Σ_k A_k (k β_b² + n̄_k β_f²) / Ā_b.
//!
//! This replaces Zinke's printed σ̄_b with its density factor (1 + d_b ā_f²): d_b is left to
//! weigh the local term (Xu et al. 2011 eq. 4) and enters no table.
//!
//! The table axes are θ_d ∈ [0, 1.5] (64 nodes) and x = ln(1 + μ_a/0.02) for μ_a ∈ [0, 1000]
//! (64 nodes), so that per-strand absorption needs no rebuild; entries are the smooth moments [ā_f,
//! ā_b, α_f, α_b, β_f², β_b²], and the combinations above are formed after interpolation.

use crate::angles::{HALF_PI, deflection, eta_prime, wrap_pi};
use crate::brute::exact_azimuthal::attenuation;
use crate::tables::absorption_axis;
use crate::tables::grid::Grid2;
use cuticle_fiber::models::marschner2003::MarschnerParams;

/// Largest θ_d tabulated.
const THETA_MAX: f64 = 1.5;
/// Nodes along each axis.
const NODES: usize = 64;
/// Midpoint samples in h per mode.
const H_SAMPLES: usize = 128;
/// Keeps 1 − ā_f away from zero (ā_f → 1 only for a lossless, purely forward fiber).
const MAX_FORWARD: f64 = 0.995;

/// The averaged functions of one parameter set, looked up per channel.
#[derive(Clone, Debug)]
pub struct BackScatteringTables {
    grid: Grid2<6>,
}

/// One lookup: [`BackScatteringTables::at`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Averages {
    /// ā_f: the energy a hair passes on forward, per crossing.
    pub forward: f64,
    /// β̄_f²: the longitudinal variance one forward crossing adds.
    pub forward_variance: f64,
    /// Ā_b: the energy coming back from the neighbourhood.
    pub back: f64,
    /// Δ̄_b: the longitudinal shift of the back-scattered lobe (in θ_h).
    pub back_shift: f64,
    /// σ̄_b: its longitudinal deviation (in θ_h).
    pub back_width: f64,
}

/// (a_f, a_b) of mode p for one channel, by the change of variable φ = Φ(p, h).
pub fn mode_attenuations(p: u32, eta: f64, theta_d: f64, mu_a: f64) -> (f64, f64) {
    let ep = eta_prime(eta, theta_d);
    let dh = 2.0 / H_SAMPLES as f64;
    let (mut forward, mut back) = (0.0, 0.0);
    for i in 0..H_SAMPLES {
        let h = -1.0 + (i as f64 + 0.5) * dh;
        let share = 0.5 * attenuation(p, eta, theta_d, mu_a, h) * dh;
        if wrap_pi(deflection(p, h, ep)).abs() > HALF_PI {
            forward += share;
        } else {
            back += share;
        }
    }
    (forward, back)
}

/// The paths that come back to the shading point after `events` back-scattering events.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BackPaths {
    /// How many times the path was back-scattered (1 or 3).
    pub events: f64,
    /// A_k: the energy they bring back.
    pub weight: f64,
    /// n̄_k: the fibers they cross forward, on average under their weight.
    pub forward_crossings: f64,
}

impl BackPaths {
    /// What these paths add up of a quantity that each forward crossing adds `forward` to and
    /// each back-scattering event `back`: n̄_k forward + k back (the shift from α_f, α_b, the
    /// variance from β_f², β_b²).
    pub fn summed(&self, forward: f64, back: f64) -> f64 {
        self.forward_crossings * forward + self.events * back
    }
}

/// A₁ and A₃ of a Poisson medium, with their mean forward crossings (module doc).
pub fn back_paths(af: f64, ab: f64) -> [BackPaths; 2] {
    let open = 1.0 - af;
    [
        BackPaths {
            events: 1.0,
            weight: af * ab / (2.0 * open),
            forward_crossings: 1.0 / open,
        },
        BackPaths {
            events: 3.0,
            weight: af * ab.powi(3) / (8.0 * open.powi(3)),
            forward_crossings: 1.0 + 3.0 * af / open,
        },
    ]
}

/// [ā_f, β̄_f², Ā_b, Δ̄_b, σ̄_b] from [`moments`] (module doc).
pub fn averages_from_moments(moments: [f64; 6]) -> [f64; 5] {
    let [af, ab, alpha_f, alpha_b, beta_f2, beta_b2] = moments;
    let (af, ab) = (af.clamp(0.0, MAX_FORWARD), ab.max(0.0));
    let (beta_f2, beta_b2) = (beta_f2.max(0.0), beta_b2.max(0.0));
    let [one, three] = back_paths(af, ab);
    let big_ab = one.weight + three.weight;
    let (shift, variance) = if big_ab > 1e-300 {
        let mean = |forward: f64, back: f64| {
            (one.weight * one.summed(forward, back) + three.weight * three.summed(forward, back))
                / big_ab
        };
        (mean(alpha_f, alpha_b), mean(beta_f2, beta_b2))
    } else {
        (one.summed(alpha_f, alpha_b), one.summed(beta_f2, beta_b2))
    };
    [af, beta_f2, big_ab, shift, variance.sqrt().max(1e-4)]
}

/// The stored entry at (θ_d, μ_a): [ā_f, ā_b, α_f, α_b, β_f², β_b²], smooth enough to
/// interpolate; Zinke's strongly nonlinear combinations are formed after the lookup.
fn entry(fiber: &MarschnerParams, theta_d: f64, mu_a: f64) -> [f64; 6] {
    let mut forward = [0.0; 3];
    let mut back = [0.0; 3];
    for p in 0..3 {
        (forward[p], back[p]) = mode_attenuations(p as u32, fiber.eta, theta_d, mu_a);
    }
    moments(forward, back, fiber.longitudinal())
}

/// [ā_f, ā_b, α_f, α_b, β_f², β_b²] from the per-mode attenuations and lobes.
pub fn moments(forward: [f64; 3], back: [f64; 3], lobes: [(f64, f64); 3]) -> [f64; 6] {
    let mean = |w: [f64; 3], f: &dyn Fn((f64, f64)) -> f64| -> f64 {
        let total: f64 = w.iter().sum();
        (0..3).map(|p| w[p] * f(lobes[p])).sum::<f64>() / total.max(1e-300)
    };
    [
        forward.iter().sum(),
        back.iter().sum(),
        mean(forward, &|l| l.0),
        mean(back, &|l| l.0),
        mean(forward, &|l| l.1 * l.1),
        mean(back, &|l| l.1 * l.1),
    ]
}

impl BackScatteringTables {
    /// Builds the tables for the global parameters of `fiber` (its absorption is an axis).
    pub fn build(fiber: &MarschnerParams) -> Self {
        Self::build_at(fiber, NODES)
    }

    /// [`Self::build`] on `nodes` × `nodes` nodes (at least 2): a coarser grid costs less to
    /// rebuild (a preview's, [`crate::preview::PREVIEW_TABLE_NODES`]).
    pub fn build_at(fiber: &MarschnerParams, nodes: usize) -> Self {
        let nodes = nodes.max(2);
        let grid = Grid2::build(
            (nodes, 0.0, THETA_MAX),
            (nodes, 0.0, absorption_axis::max_coordinate()),
            |theta_d, x| entry(fiber, theta_d, absorption_axis::mu_a(x)),
        );
        Self { grid }
    }

    /// The averages at |θ_d| for one channel's μ_a.
    pub fn at(&self, theta_d: f64, mu_a: f64) -> Averages {
        self.at_coordinate(theta_d, absorption_axis::coordinate(mu_a))
    }

    /// [`Self::at`] from μ_a's [`absorption_axis::coordinate`], which shading computes once a
    /// point.
    pub fn at_coordinate(&self, theta_d: f64, x: f64) -> Averages {
        let moments = self.grid.lookup(theta_d.abs(), x);
        let [forward, forward_variance, back, back_shift, back_width] =
            averages_from_moments(moments);
        Averages {
            forward,
            forward_variance,
            back,
            back_shift,
            back_width,
        }
    }
}

/// The stored form, for a back end that uploads it (cuticle-gpu forms the averages after its
/// own lookup, as [`BackScatteringTables::at_coordinate`] does).
impl BackScatteringTables {
    /// [ā_f, ā_b, α_f, α_b, β_f², β_b²] over (|θ_d|, absorption coordinate).
    pub fn grid(&self) -> &Grid2<6> {
        &self.grid
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::brute::exact_azimuthal::azimuthal;
    use crate::scene::hair::HairParams;
    use std::f64::consts::PI;

    /// ∫ N_p over the forward and backward half circles, integrating the exact N_p in φ
    /// (root finding at each φ: independent of the change of variable the tables use).
    fn direct(p: u32, eta: f64, theta_d: f64, mu_a: f64) -> (f64, f64) {
        let n = 1440;
        let dphi = 2.0 * PI / n as f64;
        let (mut f, mut b) = (0.0, 0.0);
        for i in 0..n {
            let phi = -PI + (i as f64 + 0.5) * dphi;
            let v = azimuthal(p, eta, theta_d, mu_a, phi) * dphi;
            if phi.abs() > HALF_PI { f += v } else { b += v }
        }
        (f, b)
    }

    #[test]
    fn tables_match_direct_integration_of_the_exact_lobes() {
        let hair = HairParams::default();
        let fiber = hair.fiber(None);
        let tables = BackScatteringTables::build(&fiber);
        // Off-node queries: interpolation error is part of what is measured.
        for &(theta_d, mu_a) in &[(0.1, 0.2), (0.45, 0.05), (0.8, 0.7), (1.05, 2.0)] {
            let mut forward = [0.0; 3];
            let mut back = [0.0; 3];
            for p in 0..3 {
                (forward[p], back[p]) = direct(p as u32, fiber.eta, theta_d, mu_a);
            }
            let want = averages_from_moments(moments(forward, back, fiber.longitudinal()));
            let got = tables.at(theta_d, mu_a);
            let got = [
                got.forward,
                got.forward_variance,
                got.back,
                got.back_shift,
                got.back_width,
            ];
            // ā_f, Ā_b within 0.02 absolute (caustic singularities limit the φ-rule); the
            // lobe moments within 8% of their own scale (Δ̄_b divides by (1 − ā_f²)³).
            let tol = [
                0.02,
                0.08 * want[1],
                0.02,
                0.08 * want[3].abs() + 1e-3,
                0.08 * want[4],
            ];
            for k in 0..5 {
                assert!(
                    (got[k] - want[k]).abs() <= tol[k],
                    "entry {k} at θ_d {theta_d}, μ_a {mu_a}: table {} direct {}",
                    got[k],
                    want[k]
                );
            }
        }
    }

    #[test]
    fn halves_add_up_to_the_mode_energy() {
        for p in 0..3 {
            let (f, b) = mode_attenuations(p, 1.55, 0.3, 0.4);
            let e = crate::brute::exact_azimuthal::energy(p, 1.55, 0.3, 0.4);
            assert!(
                (f + b - e).abs() < 0.015 * e.max(1e-3),
                "mode {p}: {f} + {b} vs {e}"
            );
        }
    }

    #[test]
    fn back_scattering_grows_as_absorption_falls() {
        let hair = HairParams::default();
        let tables = BackScatteringTables::build(&hair.fiber(None));
        let light = tables.at(0.2, 0.05);
        let dark = tables.at(0.2, 2.0);
        assert!(light.forward > 2.0 * dark.forward, "{light:?} {dark:?}");
        assert!(light.back > 2.0 * dark.back, "{light:?} {dark:?}");
        assert!(light.forward < 1.0 && light.back < 1.0);
    }

    /// A walker in a one-dimensional Poisson medium: exponential free paths of rate 1 (fresh
    /// after every turn, as in a medium whose way back meets other fibers than the way out),
    /// at each fiber passing on with probability ā_f, turning back with ā_b, absorbed
    /// otherwise. The shares that come back above the start after one and after three turns,
    /// and their mean forward crossings, are `back_paths`'s A₁, A₃, n̄₁ and n̄₃.
    #[test]
    fn back_paths_match_a_walk_through_a_poisson_medium() {
        use rand_core::{Rng, SeedableRng};
        let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(0xba5e);
        let mut uniform = || (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        let (af, ab) = (0.6, 0.2);
        let walks = 400_000;
        let mut back = [(0.0, 0.0); 2];
        for _ in 0..walks {
            // Through the shading fiber first.
            if uniform() >= af {
                continue;
            }
            let (mut depth, mut down, mut turns, mut crossed) = (0.0, true, 0, 1.0);
            loop {
                let flight = -(1.0 - uniform()).ln();
                depth += if down { flight } else { -flight };
                if depth < 0.0 {
                    match turns {
                        1 => back[0] = (back[0].0 + 1.0, back[0].1 + crossed),
                        3 => back[1] = (back[1].0 + 1.0, back[1].1 + crossed),
                        _ => {}
                    }
                    break;
                }
                let u = uniform();
                if u < af {
                    crossed += 1.0;
                } else if u < af + ab {
                    down = !down;
                    turns += 1;
                } else {
                    break;
                }
            }
        }
        let paths = back_paths(af, ab);
        for (k, (&(count, crossed), path)) in back.iter().zip(&paths).enumerate() {
            let weight = count / walks as f64;
            let crossings = crossed / count;
            // Binomial errors: 0.3 % of A₁ and 1.7 % of A₃ (one standard deviation).
            let tol = [0.015, 0.07][k];
            assert!(
                (weight / path.weight - 1.0).abs() < tol,
                "A at {} events: walk {weight}, formula {}",
                path.events,
                path.weight
            );
            assert!(
                (crossings / path.forward_crossings - 1.0).abs() < tol,
                "n̄ at {} events: walk {crossings}, formula {}",
                path.events,
                path.forward_crossings
            );
        }
    }
}
