//! Multiple scattering by dual scattering under SRBF lights (Xu et al. 2011 §4.3, Zinke et al.
//! 2008).
//!
//! Each light j of energy E_j = L_j ∫G_j dω reaches a point two ways: unscattered with share T̃
//! (single scattering's, [`crate::srbf::single_scattering`]) and forward-scattered with share
//! d_f (T_f − T̃)⁺ ([`crate::srbf::forward_scattering`]), spread by ψ_f = s̃_f g^u(θ_i; θ_j,
//! σ_f)/cos θ_j (eq. 5), s̃_f = 1/π over the half circle around φ_j and σ_f² = λ_j²/2 + σ̄_f² (the
//! SRBF's longitudinal variance plus the spread). In the crate's units (lib.rs) they add
//! - the global term (eqs. 27–28): ℳ^G_t = (1/cos θ_j) ∫ g^u(θ_i; θ_j, σ_f) ½M_t(θ_h)
//!   (cos²θ_i/cos²θ_d) 𝒩^G_t(φ_o − φ_j, θ_d) dθ_i, with 𝒩^G_t closed form from the circular
//!   Gaussians and the half-circle tables ([`crate::tables::half_circle`]);
//! - the local term (eqs. 29–31), d_b times ℳ^L = (2/cos θ_j) ∫ g^u(θ_i; θ_j, σ) ½M_b(θ_h)
//!   (cos²θ_i/cos²θ_d) Ā_b 𝒩^L dθ_i, where ½M_b is the unit normal density in θ_i of mean
//!   2Δ̄_b − θ_o and deviation 2σ̄_b (as ½M_p is for α_p, β_p: Xu et al. 2011 eq. 7), the 2
//!   eq. 29's and Zinke et al. 2008's f_back = 2Ā_b g(θ_h − Δ̄_b, σ̄_b²)/(π cos²θ_d)
//!   ([`BACK_SCALE`]), and 𝒩^L the
//!   overlap of the light's azimuthal spread with s_b = 1/π on the backward half circle around
//!   φ_o: (π − |δ|)/π² for the scattered light, P(λ′, δ)/π for the direct light (which Zinke's
//!   F_direct also back-scatters, with σ = λ_j/√2).
//!
//! Where the paper divides by cos θ_j (the narrow limit of the spread's normalisation) we divide
//! by the exact Z(θ_j, σ) of [`crate::tables::spread`]: cos θ_j overstated a wide sky above hanging
//! hair twice over against the brute force.
//!
//! A frame shades the merged lights of [`crate::srbf::light_clusters`]
//! ([`Dual::shade_clustered`]): a group's direct energies and its forward-scattered ones
//! each become one light at each point; [`Dual::shade`] shades every light apart (the
//! reference, and a frame's with `merge_bandwidth` 0).
//!
//! Ā_b, Δ̄_b, σ̄_b are taken at the θ_d of the light's centre, (θ_o − θ_j)/2 (eqs. 29–31 as
//! printed, Ā_b at each quadrature node and Δ̃_b, σ̃_b averaged over θ_j ± σ, were tried: the
//! agreement with the brute force in tests/multiple.rs moved by under 2 % and shading took 24 %
//! longer); all outer integrals use the linear quadrature of §4.2.2. Eccentricity is ignored
//! here (Zinke's model is for circular fibers). Channels share one σ_f, the mean of theirs
//! weighted by their scattered shares.

use crate::angles::Outgoing;
use crate::angles::wrap_pi;
use crate::frame::shadows::ShadowOptions;
use crate::srbf::cg_lobes::r_coefficients_in;
use crate::srbf::circular_gaussian as cg;
use crate::srbf::forward_scattering::{Forward, forward};
use crate::srbf::light_clusters::LightClusters;
use crate::srbf::quadrature::Window;
use crate::srbf::single_scattering::{LocalLight, ShadingFiber};
use crate::tables::absorption_axis;
use crate::tables::back_scattering::{Averages, BackScatteringTables};
use crate::tables::cg_integrals::{FresnelRow, Tables};
use crate::tables::half_circle::HalfCircle;
use crate::tables::lobe_table::AzimuthalLobes;
use crate::tables::spread::SpreadNormalisation;
use cuticle_fiber::Lobe;
use cuticle_fiber::math::sin_cos_quadrant;
use cuticle_fiber::math::vmf::{concentration, mean_cosine};
use cuticle_fiber::models::marschner2003::MarschnerParams;
use glam::DVec3;
use std::f64::consts::{FRAC_1_SQRT_2, PI};

/// Scattered shares below this skip the global and scattered local terms.
const NEGLIGIBLE: f64 = 1e-5;

/// What [`forward`] gives a light that crosses no fiber (T̃ = 1).
const UNSCATTERED: Forward = Forward {
    scattered: 0.0,
    variance: 0.0,
};

/// Where a light's (or a merged group's) energy comes from, in the fiber frame.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Beam {
    theta: f64,
    phi: f64,
    bandwidth: f64,
}

/// How one light's energy arrives at a point (per channel where it differs).
#[derive(Clone, Copy, Debug)]
struct Arrival {
    /// Whether its transmittance passes the shadow cutoff (direct light, local term).
    direct: bool,
    /// d_f (T_f − T̃).
    scattered: DVec3,
    /// σ̄_f².
    variance: DVec3,
}

impl Arrival {
    fn forward_scattered(&self) -> bool {
        self.scattered.max_element() > NEGLIGIBLE
    }

    /// The channels' σ̄_f² weighted by their scattered shares (one σ_f for all three).
    fn spread(&self) -> f64 {
        (self.variance * self.scattered).element_sum() / self.scattered.element_sum()
    }
}

/// Energies and mean vector of lights being merged into one beam.
#[derive(Clone, Copy, Debug, Default)]
struct Merge {
    /// Σ energy, per channel.
    energy: DVec3,
    /// Σ |energy| A(κ_j) ω_j.
    moment: DVec3,
    /// Σ |energy|.
    weight: f64,
}

impl Merge {
    fn add(&mut self, energy: DVec3, mean: DVec3) {
        let w = energy.abs().element_sum();
        self.energy += energy;
        self.moment += w * mean;
        self.weight += w;
    }

    /// The SRBF of this mean vector: centre m/‖m‖, sharpness A⁻¹(‖m‖/Σw); none without
    /// energy.
    fn beam(&self) -> Option<Beam> {
        if self.weight <= 0.0 || self.moment == DVec3::ZERO {
            return None;
        }
        let m = self.moment / self.weight;
        let r = m.length();
        let d = m / r;
        let kappa = concentration(r);
        Some(Beam {
            theta: d.x.clamp(-1.0, 1.0).asin(),
            phi: d.z.atan2(d.y),
            bandwidth: cg::bandwidth(kappa).clamp(MIN_BEAM, MAX_BEAM),
        })
    }
}

/// The narrowest and widest beam a merge gives (the fitted lights' range).
const MIN_BEAM: f64 = cuticle_light::MIN_BANDWIDTH;
const MAX_BEAM: f64 = cuticle_light::MAX_BANDWIDTH;

/// The 2 of Zinke et al. 2008's f_back = 2Ā_b g(θ_h − Δ̄_b, σ̄_b²)/(π cos²θ_d) and of Xu et
/// al. 2011 eq. 29: with g a unit Gaussian in θ_h, f_back carries 2Ā_b of the power a fiber
/// intercepts, in the crate's units as in theirs (in which single scattering's ½M_p is the
/// unit density in θ_i, and so is ½M_b here). Dropping it, as this module once did, gave half
/// the local term of an exact path trace of a fiber slab (tests/slab.rs).
pub const BACK_SCALE: f64 = 2.0;

/// Everything multiple scattering reads besides the point and its lights.
#[derive(Clone, Copy, Debug)]
pub struct Dual<'a> {
    /// Xu et al. 2011 §5's tables (N_R's Fresnel quintic).
    pub tables: &'a Tables,
    pub half: &'a HalfCircle,
    /// Z(θ_j, σ) of each spread (the narrow limit cos θ_j overstates wide lights at the axis).
    pub spread: &'a SpreadNormalisation,
    /// Decides whether the direct light's local term is worth computing.
    pub shadows: ShadowOptions,
    pub back: &'a BackScatteringTables,
    pub d_b: f64,
    /// Segments m of the linear quadrature.
    pub m: usize,
}

/// What every light of one point shares: its view and its channels' absorption coordinates
/// in the back-scattering tables.
struct PointView {
    outgoing: Outgoing,
    phi_o: f64,
    absorption: [f64; 3],
}

/// ∫ G_j dω of an SRBF exp(κ(ω·ω_j − 1)), κ = 2/λ².
pub fn srbf_integral(lambda: f64) -> f64 {
    let kappa = 2.0 / (lambda * lambda).max(1e-12);
    2.0 * PI * (1.0 - (-2.0 * kappa).exp()) / kappa
}

impl Dual<'_> {
    /// Multiple-scattering radiance toward (θ_o, φ_o) from every light; `lights` carry the
    /// unshadowed coefficients L_j, `transmittance` their T̃_j.
    pub fn shade<L: AzimuthalLobes>(
        &self,
        fiber: ShadingFiber<L>,
        theta_o: f64,
        phi_o: f64,
        lights: &[LocalLight],
        transmittance: &[f32],
    ) -> DVec3 {
        let view = self.view(fiber, theta_o, phi_o);
        lights
            .iter()
            .zip(transmittance)
            .map(|(light, &t)| self.light(fiber, &view, light, t as f64))
            .sum()
    }

    /// [`Self::shade`] with each group of `clusters` merged at this point: its lights' direct
    /// energies (T̃_j E_j) into one beam, their forward-scattered energies into another, each
    /// beam the SRBF whose mean vector is theirs (von Mises–Fisher moment matching, Banerjee et
    /// al. 2005 §4, as [`crate::preview::merged_lights`] does for whole lights). `directions`
    /// are the lights' unit vectors in the fiber frame (u, v, w), as `lights`' angles.
    #[allow(clippy::too_many_arguments)]
    pub fn shade_clustered<L: AzimuthalLobes>(
        &self,
        fiber: ShadingFiber<L>,
        theta_o: f64,
        phi_o: f64,
        lights: &[LocalLight],
        directions: &[DVec3],
        transmittance: &[f32],
        clusters: &LightClusters,
    ) -> DVec3 {
        let view = self.view(fiber, theta_o, phi_o);
        clusters
            .groups()
            .map(|g| match g.len() {
                1 => self.light(
                    fiber,
                    &view,
                    &lights[g.start],
                    transmittance[g.start] as f64,
                ),
                _ => self.group(
                    fiber,
                    &view,
                    &lights[g.clone()],
                    &directions[g.clone()],
                    &transmittance[g],
                ),
            })
            .sum()
    }

    /// A group's lights merged into a direct beam and a forward-scattered one, each shaded
    /// once ([`Self::shade_clustered`]).
    fn group<L: AzimuthalLobes>(
        &self,
        fiber: ShadingFiber<L>,
        view: &PointView,
        lights: &[LocalLight],
        directions: &[DVec3],
        transmittance: &[f32],
    ) -> DVec3 {
        let mut direct = Merge::default();
        let mut scattered = Merge::default();
        // Σ_j |E_j| Σ_c (σ̄_f² d_f (T_f − T̃)) and Σ_j |E_j| Σ_c d_f (T_f − T̃): each light's
        // spread as Arrival::spread has it, weighted by its energy.
        let (mut spread, mut spread_weight) = (0.0, 0.0);
        for ((light, &d), &t) in lights.iter().zip(directions).zip(transmittance) {
            let t = t as f64;
            let energy = light.radiance * srbf_integral(light.bandwidth);
            if energy.max_element() <= 0.0 {
                continue;
            }
            let arrival = self.arrival(view, light.theta, t);
            let mean = mean_cosine(cg::sharpness(light.bandwidth)) * d;
            if arrival.direct {
                direct.add(t * energy, mean);
            }
            if arrival.forward_scattered() {
                scattered.add(energy * arrival.scattered, mean);
                let w = energy.abs().element_sum();
                spread += w * (arrival.variance * arrival.scattered).element_sum();
                spread_weight += w * arrival.scattered.element_sum();
            }
        }
        let mut out = DVec3::ZERO;
        if let Some(at) = direct.beam() {
            out += direct.energy * self.direct(view, &at, 1.0);
        }
        if let Some(at) = scattered.beam() {
            out += self.scattered(fiber, view, &at, scattered.energy, spread / spread_weight);
        }
        out
    }

    fn view<L>(&self, fiber: ShadingFiber<L>, theta_o: f64, phi_o: f64) -> PointView {
        PointView {
            outgoing: Outgoing::new(theta_o),
            phi_o,
            absorption: fiber
                .params
                .mu_a
                .to_array()
                .map(absorption_axis::coordinate),
        }
    }

    /// One light's global and local terms.
    fn light<L: AzimuthalLobes>(
        &self,
        fiber: ShadingFiber<L>,
        view: &PointView,
        light: &LocalLight,
        t: f64,
    ) -> DVec3 {
        let energy = light.radiance * srbf_integral(light.bandwidth);
        if energy.max_element() <= 0.0 {
            return DVec3::ZERO;
        }
        let arrival = self.arrival(view, light.theta, t);
        if !arrival.direct && !arrival.forward_scattered() {
            return DVec3::ZERO;
        }
        let at = Beam {
            theta: light.theta,
            phi: light.phi,
            bandwidth: light.bandwidth,
        };
        let mut out = if arrival.direct {
            self.direct(view, &at, t)
        } else {
            DVec3::ZERO
        };
        if arrival.forward_scattered() {
            out += self.scattered(fiber, view, &at, arrival.scattered, arrival.spread());
        }
        energy * out
    }

    /// How light of transmittance `t` from elevation `theta_j` arrives: whether directly
    /// (above the cutoff) and the forward-scattered share of each channel.
    fn arrival(&self, view: &PointView, theta_j: f64, t: f64) -> Arrival {
        // An unshadowed light (T̃ = 1: no optical depth) scatters nothing forward, exactly.
        let fw = if t < 1.0 {
            view.absorption
                .map(|x| forward(t, &self.back.at_coordinate(theta_j, x)))
        } else {
            [UNSCATTERED; 3]
        };
        Arrival {
            direct: self.shadows.passes(t),
            scattered: DVec3::from_array(fw.map(|f| f.scattered)),
            variance: DVec3::from_array(fw.map(|f| f.variance)),
        }
    }

    /// share · d_b ℳ^L / Z of the direct light from a beam of unit energy (eq. 29), `share` the
    /// part of it that arrives unscattered.
    fn direct(&self, view: &PointView, at: &Beam, share: f64) -> DVec3 {
        let delta = wrap_pi(view.phi_o - at.phi);
        let back = self.back_at(view, at.theta);
        let cos_j = sin_cos_quadrant(at.theta).1.max(1e-4);
        let direct_azimuth = self.half.share(at.bandwidth / cos_j, delta) / PI;
        let sigma_light = srbf_deviation(at.bandwidth);
        share * self.d_b * self.local(&back, view.outgoing, at.theta, sigma_light, direct_azimuth)
            / self.spread.at(at.theta, sigma_light)
    }

    /// share · (ℳ^G + d_b ℳ^L) / Z of forward-scattered light from a beam of unit energy,
    /// `share` the scattered part of each channel, whose crossings add the longitudinal
    /// variance `spread` (eqs. 27–29).
    fn scattered<L: AzimuthalLobes>(
        &self,
        fiber: ShadingFiber<L>,
        view: &PointView,
        at: &Beam,
        share: DVec3,
        spread: f64,
    ) -> DVec3 {
        let theta_o = view.outgoing.theta;
        let delta = wrap_pi(view.phi_o - at.phi);
        let back = self.back_at(view, at.theta);
        let sigma_f = (srbf_deviation(at.bandwidth).powi(2) + spread).sqrt();
        let scattered_azimuth = (PI - delta.abs()) / (PI * PI);
        share
            * (self.global(fiber, theta_o, at.theta, sigma_f, delta)
                + self.d_b * self.local(&back, view.outgoing, at.theta, sigma_f, scattered_azimuth))
            / self.spread.at(at.theta, sigma_f)
    }

    /// Each channel's back-scattering averages at the θ_d of a light at `theta_j`.
    fn back_at(&self, view: &PointView, theta_j: f64) -> [Averages; 3] {
        let theta_d = 0.5 * (view.outgoing.theta - theta_j);
        view.absorption.map(|x| self.back.at_coordinate(theta_d, x))
    }

    /// Σ_t ∫ g^u(θ_i; θ_j, σ_f) ½M_t (cos²θ_i/cos²θ_d) 𝒩^G_t dθ_i (eq. 27 without 1/Z).
    fn global<L: AzimuthalLobes>(
        &self,
        fiber: ShadingFiber<L>,
        theta_o: f64,
        theta_j: f64,
        sigma_f: f64,
        delta: f64,
    ) -> DVec3 {
        let w = self.half.cosines(delta);
        let eta = fiber.params.eta;
        let fresnel = self.tables.fresnel_row(eta);
        let lobes = fiber.params.longitudinal();
        let outgoing = Outgoing::new(theta_o);
        MarschnerParams::LOBES
            .into_iter()
            .map(|lobe| {
                let (alpha, beta) = lobes[lobe.index()];
                let window =
                    Window::normal_product(theta_j, sigma_f, 2.0 * alpha - theta_o, 2.0 * beta);
                window.integrate_incident(self.m, &outgoing, |sample| {
                    let theta_d = sample.theta_d;
                    match lobe {
                        Lobe::R => DVec3::splat(r_half(self.tables, fresnel, theta_d, &w)),
                        Lobe::TT => {
                            let tt = fiber.lobes.tt(theta_d);
                            DVec3::from_array(std::array::from_fn(|c| {
                                if tt.weight[c] == 0.0 {
                                    return 0.0;
                                }
                                let bandwidth = tt.bandwidth[c];
                                let [near, far] = self.half.shares(
                                    bandwidth,
                                    [delta - PI - tt.offset[c], delta - PI + tt.offset[c]],
                                );
                                tt.weight[c] * cg::integral(bandwidth) / PI * (near + far)
                            }))
                        }
                        // TRT; Marschner 2003 has no further lobe.
                        _ => {
                            let trt = fiber.lobes.trt(eta, theta_d);
                            trt.weighted_sum(|s, bandwidth| {
                                self.unit_half(bandwidth, delta - trt.centre[s])
                            })
                        }
                    }
                })
            })
            .sum()
    }

    /// (1/π) ∫ over the half circle around `offset` = δ − μ of g^c(φ; μ, λ).
    fn unit_half(&self, bandwidth: f64, offset: f64) -> f64 {
        cg::integral(bandwidth) * self.half.share(bandwidth, offset) / PI
    }

    /// Per channel 2Ā_b 𝒩^L ∫ g^u(θ_i; θ_j, σ) ½M_b (cos²θ_i/cos²θ_d) dθ_i (eq. 29 without
    /// 1/Z), `azimuth` being 𝒩^L and `back` each channel's averages at θ_d of the light.
    fn local(
        &self,
        back: &[Averages; 3],
        outgoing: Outgoing,
        theta_j: f64,
        sigma: f64,
        azimuth: f64,
    ) -> DVec3 {
        if azimuth <= 0.0 {
            return DVec3::ZERO;
        }
        DVec3::from_array(std::array::from_fn(|c| {
            let a = &back[c];
            if a.back <= 0.0 {
                return 0.0;
            }
            let window = Window::normal_product(
                theta_j,
                sigma,
                2.0 * a.back_shift - outgoing.theta,
                2.0 * a.back_width,
            );
            let integral = window.integrate_incident(self.m, &outgoing, |_| DVec3::ONE);
            BACK_SCALE * a.back * azimuth * integral.x
        }))
    }
}

/// 𝒩^G_R = (1/π) Σ_k C_k W_k(δ) (eqs. 13, 28).
fn r_half(tables: &Tables, fresnel: FresnelRow, theta_d: f64, w: &[f64; 7]) -> f64 {
    let c = r_coefficients_in(tables, fresnel, theta_d);
    (1..7).map(|k| c[k] * w[k]).sum::<f64>() / PI
}

/// λ_j/√2: the longitudinal deviation of an SRBF of bandwidth λ_j.
pub fn srbf_deviation(lambda: f64) -> f64 {
    FRAC_1_SQRT_2 * lambda
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frame::renderer::Renderer;
    use crate::scene::hair::HairParams;
    use cuticle_fiber::FiberAngles;

    fn local(d: DVec3, bandwidth: f64, radiance: DVec3) -> (LocalLight, DVec3) {
        let d = d.normalize();
        let a = FiberAngles::from_dir(d);
        let light = LocalLight {
            theta: a.theta,
            phi: a.phi,
            bandwidth,
            radiance,
        };
        (light, d)
    }

    /// A group of one light merges into that light (the moment matching inverts A(κ)), and two
    /// lights of different colours at one direction into the sum of the two shaded apart, at
    /// every kind of transmittance (unshadowed, shadowed, below the cutoff). How far merging
    /// lights at different directions moves an image is tests/dual_merge.rs's.
    #[test]
    fn merging_keeps_a_light_and_its_energy() {
        let renderer = Renderer::new();
        let params = HairParams::default().fiber(None);
        let table = renderer.lobe_table(&params);
        let lobes = table.for_fiber(&renderer.tables, &params);
        let fiber = ShadingFiber {
            params: &params,
            lobes: &lobes,
        };
        let back = renderer.back_scattering(&params);
        let dual = Dual {
            tables: &renderer.tables,
            half: &renderer.half,
            spread: &renderer.spread,
            shadows: ShadowOptions::default(),
            back: &back,
            d_b: HairParams::default().d_b,
            m: 4,
        };
        let (theta_o, phi_o) = (0.2, 0.4);
        let view = dual.view(fiber, theta_o, phi_o);
        let (a, da) = local(DVec3::new(0.3, -0.8, 0.4), 0.3, DVec3::new(2.0, 1.5, 1.0));
        let (b, _) = local(DVec3::new(0.1, -0.6, 0.7), 0.3, DVec3::new(1.0, 1.2, 1.4));
        for t in [1.0f32, 0.4, 0.01] {
            let alone = dual.light(fiber, &view, &a, t as f64);
            let merged = dual.group(fiber, &view, &[a], &[da], &[t]);
            assert!(alone.max_element() > 0.0, "t {t}: {alone}");
            let err = (merged - alone).abs().max_element() / alone.max_element();
            assert!(err < 1e-9, "t {t}: group of one {merged} against {alone}");
            let b = LocalLight {
                radiance: b.radiance,
                ..a
            };
            let sum = alone + dual.light(fiber, &view, &b, t as f64);
            let pair = dual.group(fiber, &view, &[a, b], &[da, da], &[t, t]);
            let err = (pair - sum).abs().max_element() / sum.max_element();
            assert!(
                err < 1e-9,
                "t {t}: two lights at one direction {pair} against {sum}"
            );
        }
    }
}
