//! The tilted model's cuticle, as d'Eon 2011's N_p sees it ([`Cuticle`]): A(p, h) traced
//! through scales tilted by α ([`scales::attenuation`]) with the rough surface's Fresnel
//! factors ([`RoughInterface`]), R's exact mirror off the tilted scale ([`scales::mirror`]),
//! the tilt's shift of TT's and TRT's Φ(p, h) ([`scales::deflection`]), and TT's exit azimuth
//! and spread per offset through the rough surface ([`RoughTtTable`]).
//!
//! [`scales::attenuation`]: super::scales::attenuation
//! [`scales::mirror`]: super::scales::mirror
//! [`scales::deflection`]: super::scales::deflection

use super::rough::deflection::RoughTtTable;
use super::scales::attenuation::{Surface, tilted_attenuation, tilted_reflectance};
use super::scales::deflection::{ReadAt, deflection_shift};
use super::scales::mirror::{MirrorOffset, tilted_mirror_offsets};
use crate::lobe::LobeValues;
use crate::models::deon2011::azimuthal::{AzimuthalScattering, Cuticle, ROffset};
use crate::optics::fresnel::fresnel_dielectric;
use crate::optics::rough_interface::RoughInterface;
use glam::DVec3;
use std::sync::Arc;

/// Tilted, possibly rough cuticle scales of a fiber of index η.
#[derive(Clone, Debug)]
pub struct TiltedCuticle {
    pub eta: f64,
    /// The scale tilt α (radians).
    pub alpha: f64,
    /// The micro-normal means of the Fresnel factors A(p, h) is taken with, where the surface
    /// counts as rough; `None` for the smooth Fresnel factor.
    pub rough: Option<Arc<RoughInterface>>,
    /// TT's azimuth offset by offset through the rough surface; `None` for Bravais' smooth
    /// Φ(1, h) and d'Eon et al. 2011's single variance.
    pub rough_tt: Option<Arc<RoughTtTable>>,
}

impl TiltedCuticle {
    /// Smooth scales of a fiber of index `eta`, untilted.
    pub fn smooth(eta: f64) -> Self {
        Self {
            eta,
            alpha: 0.0,
            rough: None,
            rough_tt: None,
        }
    }

    /// The tilted model's: scales tilted by `alpha` (radians) with a rough surface of Beckmann
    /// roughness `beta` for A(p, h) and TT's exit, each shared per (β, η) and (η, α, β).
    pub fn rough(eta: f64, alpha: f64, beta: f64) -> Self {
        Self {
            eta,
            alpha,
            rough: Some(RoughInterface::shared(beta, eta)),
            rough_tt: Some(RoughTtTable::shared(eta, alpha, beta)),
        }
    }

    /// The cuticle `az` is taken through, or smooth untilted scales.
    pub fn of(az: &AzimuthalScattering) -> Self {
        Self::read(az)
            .cloned()
            .unwrap_or_else(|| Self::smooth(az.eta))
    }

    /// The tilted cuticle `az` is taken through, if it is one.
    pub fn read(az: &AzimuthalScattering) -> Option<&Self> {
        az.cuticle()?.as_any().downcast_ref::<Self>()
    }

    /// The surface A(p, h) meets.
    pub fn surface(&self) -> Surface<'_> {
        match &self.rough {
            Some(rough) => Surface::rough(rough, self.alpha),
            None => Surface::smooth(self.eta, self.alpha),
        }
    }
}

/// The surface `az`'s A(p, h) meets: its tilted cuticle's, or the smooth untilted fiber's.
pub fn surface_of(az: &AzimuthalScattering) -> Surface<'_> {
    match TiltedCuticle::read(az) {
        Some(c) => c.surface(),
        None => Surface::smooth(az.eta, 0.0),
    }
}

/// d'Eon 2011's azimuthal terms taken through tilted, rough scales: each call sets one part of
/// the cuticle and keeps what the calls before it set.
pub trait WithScales {
    /// A(p, h), R's mirror and the shift of Φ through scales tilted by `alpha` (radians).
    fn with_scale_tilt(self, alpha: f64) -> Self;
    /// A(p, h) with the micro-normal means of the Fresnel factors of a surface of Beckmann
    /// roughness `beta` ([`RoughInterface`]), shared per (β, η).
    fn with_rough_surface(self, beta: f64) -> Self;
    /// TT's Φ(1, h) and azimuthal spread per offset through the rough surface of roughness
    /// `beta` and the scale tilt set so far ([`RoughTtTable`]): call after
    /// [`WithScales::with_scale_tilt`].
    fn with_rough_deflection(self, beta: f64) -> Self;
}

impl WithScales for AzimuthalScattering {
    fn with_scale_tilt(self, alpha: f64) -> Self {
        let cuticle = TiltedCuticle {
            alpha,
            ..TiltedCuticle::of(&self)
        };
        self.with_cuticle(Arc::new(cuticle))
    }

    fn with_rough_surface(self, beta: f64) -> Self {
        let cuticle = TiltedCuticle {
            rough: Some(RoughInterface::shared(beta, self.eta)),
            ..TiltedCuticle::of(&self)
        };
        self.with_cuticle(Arc::new(cuticle))
    }

    fn with_rough_deflection(self, beta: f64) -> Self {
        let cuticle = TiltedCuticle::of(&self);
        let cuticle = TiltedCuticle {
            rough_tt: Some(RoughTtTable::shared(self.eta, cuticle.alpha, beta)),
            ..cuticle
        };
        self.with_cuticle(Arc::new(cuticle))
    }
}

impl From<MirrorOffset> for ROffset {
    fn from(m: MirrorOffset) -> Self {
        ROffset {
            h: m.h,
            dh_dphi: m.dh_dphi,
        }
    }
}

impl Cuticle for TiltedCuticle {
    fn attenuation(&self, theta_i: f64, h: f64, mu_a: DVec3) -> LobeValues {
        tilted_attenuation(theta_i, h, self.surface(), mu_a).lobes
    }

    fn reflectance(&self, theta_i: f64, h: f64) -> f64 {
        if self.alpha == 0.0 && self.rough.is_none() {
            let cos_gamma = (1.0 - h * h).max(0.0).sqrt();
            fresnel_dielectric(theta_i.cos() * cos_gamma, self.eta)
        } else {
            tilted_reflectance(theta_i, h, self.surface())
        }
    }

    fn is_flat_and_smooth(&self) -> bool {
        self.surface().is_flat_and_smooth()
    }

    fn tilted(&self) -> bool {
        self.alpha != 0.0
    }

    fn r_offsets(&self, theta_i: f64, phi: f64) -> [Option<ROffset>; 3] {
        tilted_mirror_offsets(theta_i, self.alpha, phi).map(|m| m.map(ROffset::from))
    }

    /// TT's is the rough surface's where it is set, at any tilt; TT's and TRT's are otherwise
    /// the tilt's ([`deflection_shift`]), 0 untilted. R's tilted form solves its exact mirror
    /// instead. TRRT keeps Bravais' Φ: its two internal reflections off the rough surface turn
    /// it more than the tilt does (docs/departures/15-shift-reference.md).
    fn deflection_shift(&self, p: usize, theta_i: f64, h: f64) -> f64 {
        if let (Some(table), 1) = (&self.rough_tt, p) {
            return table.at(theta_i, h).shift;
        }
        match p {
            1 => deflection_shift(1, theta_i, self.alpha, self.eta, h, ReadAt::OwnExit),
            2 => deflection_shift(2, theta_i, self.alpha, self.eta, h, ReadAt::CentralExit),
            _ => 0.0,
        }
    }

    fn owns_exit(&self, p: usize) -> bool {
        p == 1 && self.rough_tt.is_some()
    }

    fn exit_sigma(&self, _p: usize, theta_i: f64, h: f64) -> f64 {
        self.rough_tt
            .as_ref()
            .map_or(f64::NAN, |table| table.at(theta_i, h).sigma)
    }

    fn exit_sigma_max(&self, _p: usize) -> f64 {
        self.rough_tt
            .as_ref()
            .map_or(f64::NAN, |table| table.sigma_max())
    }

    fn as_any(&self) -> &dyn std::any::Any {
        self
    }
}
