//! Lobes (scattering modes) and per-lobe values.

use glam::DVec3;
use serde::Serialize;

/// A scattering mode, by its number p of internal path segments (docs/conventions.md §2).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
pub enum Lobe {
    R,
    TT,
    TRT,
    TRRT,
    /// Every mode with p ≥ 4.
    Rest,
}

impl Lobe {
    pub const ALL: [Lobe; 5] = [Lobe::R, Lobe::TT, Lobe::TRT, Lobe::TRRT, Lobe::Rest];

    /// p, with `Rest` reported as 4.
    pub const fn index(self) -> usize {
        self as usize
    }

    pub const fn from_index(p: usize) -> Lobe {
        match p {
            0 => Lobe::R,
            1 => Lobe::TT,
            2 => Lobe::TRT,
            3 => Lobe::TRRT,
            _ => Lobe::Rest,
        }
    }

    /// The file and JSON name (docs/conventions.md §5).
    pub const fn name(self) -> &'static str {
        match self {
            Lobe::R => "R",
            Lobe::TT => "TT",
            Lobe::TRT => "TRT",
            Lobe::TRRT => "TRRT",
            Lobe::Rest => "rest",
        }
    }
}

/// An RGB value for each lobe, indexed by [`Lobe::index`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LobeValues(pub [DVec3; 5]);

impl LobeValues {
    /// M_p N_p per lobe from the longitudinal lobes of R, TT, TRT, TRRT and the five azimuthal
    /// ones (the p ≥ 4 remainder shares TRRT's longitudinal lobe).
    pub fn separable(m: [f64; 4], n: [DVec3; 5]) -> Self {
        Self([
            m[0] * n[0],
            m[1] * n[1],
            m[2] * n[2],
            m[3] * n[3],
            m[3] * n[4],
        ])
    }

    pub fn get(&self, lobe: Lobe) -> DVec3 {
        self.0[lobe.index()]
    }

    #[inline]
    pub fn total(&self) -> DVec3 {
        let [r, tt, trt, trrt, rest] = self.0;
        r + tt + trt + trrt + rest
    }
}

impl std::ops::Index<Lobe> for LobeValues {
    type Output = DVec3;
    fn index(&self, lobe: Lobe) -> &DVec3 {
        &self.0[lobe.index()]
    }
}

impl std::ops::IndexMut<Lobe> for LobeValues {
    fn index_mut(&mut self, lobe: Lobe) -> &mut DVec3 {
        &mut self.0[lobe.index()]
    }
}

/// The channel mean of an RGB value: what CSV and JSON outputs report, and what lobe selection
/// in importance sampling is proportional to.
pub fn channel_mean(v: DVec3) -> f64 {
    (v.x + v.y + v.z) / 3.0
}
