//! The non-separable model's longitudinal lobes M_p, per lobe and per (θ_i, φ): R's cone off
//! the (tilted, rough) mirror, TT's skewed sine lobe through the rough exit, TRT's cut lobe,
//! each from the model's tables where it was tabulated and from the exact construction
//! otherwise ([`NonSeparable::longitudinal_exact`]).

use super::cones::{
    self, CutLobe, cone_r, cone_trt, cone_tt, first_order_tt, tt_lobe_rough, variance_r,
    variance_trt, variance_tt,
};
use super::rough::trt::RoughTrtTable;
use super::scales::attenuation::incident;
use super::scales::deflection::tilted_tt_offset;
use super::scales::mirror::{MirrorOffset, tilted_mirror_offsets};
use super::tables::mirrors::{MirrorCone, TabulatedMirror};
use super::tables::sine_lobes;
use super::tt_offsets::TtOffsets;
use super::{NO_MIRRORS, NonSeparable, Scales};
use crate::geometry::bravais::eta_prime;
use crate::geometry::nusselt;
use crate::lobes::longitudinal::{ConeLobe, LongitudinalLobe};
use crate::lobes::sine_lobe::{FULL_REACH, SineMoments, SkewSplit, SkewedSine, SkewedSineLobe};
use crate::math::{asin_fast, cos_quadrant, sin_cos_quadrant};
use crate::params::FiberParams;

impl NonSeparable {
    /// The longitudinal lobe of mode p for light at θ_i leaving at azimuth φ.
    ///
    /// Widths, and the offset h that TT's cone depends on, are evaluated at the specular cone's
    /// difference angle θ_d* = −θ_i rather than at the θ_d of the outgoing direction (d'Eon et al.
    /// 2014 writes θ_d): then M is a normalised density in θ_o for every φ and the model conserves
    /// energy, where the per-direction θ_d loses up to 17 % at grazing incidence (albedo 0.83
    /// at β = 0.3, θ_i = 1.0; 0.87 at β = 0.04, θ_i = 1.4, measured with `furnace::albedo`).
    ///
    /// The tilted model's TT lobe lies in sin θ_o ([`SkewedSineLobe`]); here it is described by
    /// the cone at its mean sine and the width in θ of its spread ([`cone_of_sine_lobe`]).
    pub fn longitudinal(&self, p: usize, theta_i: f64, phi: f64) -> LongitudinalLobe {
        self.longitudinal_at(p, theta_i, phi, &self.cone_mirrors(p, theta_i, phi))
    }

    /// R's offsets as lobe p's cone alone needs them: solved for R where the mirror table
    /// does not give its cone, none otherwise.
    pub(super) fn cone_mirrors(
        &self,
        p: usize,
        theta_i: f64,
        phi: f64,
    ) -> [Option<MirrorOffset>; 3] {
        match p {
            0 if self.mirror_cones.is_none() && self.rough_mirror().is_none() => {
                self.mirrors(theta_i, phi)
            }
            _ => NO_MIRRORS,
        }
    }

    /// The lobe of mode p ≤ 2 as sampling draws from it, but for the tilted model's TT
    /// ([`Self::sample_lobe_sin`]): [`Self::cone_lobe`], the lobe the evaluation reads, with R's
    /// offsets solved where the mirror table does not give its cone.
    #[inline]
    pub(super) fn sampling_lobe(&self, p: usize, theta_i: f64, phi: f64) -> ConeLobe {
        self.cone_lobe(p, theta_i, phi, &self.cone_mirrors(p, theta_i, phi))
    }

    /// Whether an evaluation solves R's offsets: where the rough mirror does not give N_R and
    /// R's lobe (the mirror table then gives the cone where there is one).
    pub(super) fn needs_mirrors(&self) -> bool {
        self.scales == Scales::Tilted && self.rough_mirror().is_none()
    }

    /// R's mirror at (θ_i, φ): the mirror table's where it answers, else the first of the
    /// solved `mirrors` (which the caller solved where there is no table); `None` where no
    /// offset mirrors to φ, and in the paper's form.
    pub(super) fn r_cone(
        &self,
        theta_i: f64,
        phi: f64,
        mirrors: &[Option<MirrorOffset>; 3],
    ) -> Option<MirrorCone> {
        let first = |m: &[Option<MirrorOffset>; 3]| m.iter().flatten().next().map(MirrorCone::from);
        let Some(table) = &self.mirror_cones else {
            return first(mirrors);
        };
        match table.at(theta_i, phi) {
            TabulatedMirror::Mirror(cone) => Some(cone),
            TabulatedMirror::Beyond => None,
            TabulatedMirror::Unknown => first(&self.mirrors(theta_i, phi)),
        }
    }

    /// R's lobe where no tilted mirror places it: d'Eon et al. 2014 §2.3's cone and eq. 6's
    /// variance.
    pub(super) fn r_lobe_paper(&self, theta_i: f64, phi: f64) -> LongitudinalLobe {
        LongitudinalLobe::new(
            variance_r(self.params.beta, phi),
            cone_r(theta_i, self.params.alpha, phi),
        )
    }

    /// R's offsets at (θ_i, φ) in the tilted model ([`tilted_mirror_offsets`]): N_R and R's
    /// cone both need them, so an evaluation solves them once. None in the paper's form.
    pub(super) fn mirrors(&self, theta_i: f64, phi: f64) -> [Option<MirrorOffset>; 3] {
        match self.scales {
            Scales::Tilted => tilted_mirror_offsets(theta_i, self.params.alpha, phi),
            Scales::Paper => NO_MIRRORS,
        }
    }

    /// [`NonSeparable::longitudinal`] with R's offsets already solved.
    pub(super) fn longitudinal_at(
        &self,
        p: usize,
        theta_i: f64,
        phi: f64,
        mirrors: &[Option<MirrorOffset>; 3],
    ) -> LongitudinalLobe {
        match (&self.lobes, p) {
            (_, 1) if self.scales == Scales::Tilted => {
                cone_of_sine_lobe(self.tt_sine_lobe(theta_i, phi))
            }
            (Some(table), 1) => self.lobe_from_shape(theta_i, table.tt(theta_i, phi).shape),
            (Some(table), 2) => self.lobe_from_shape(theta_i, table.trt(theta_i)),
            _ => self.longitudinal_exact(p, theta_i, phi, mirrors),
        }
    }

    /// [`Self::longitudinal_at`] with the cone as its sine and cosine, for evaluation: where
    /// the sine is what the model finds (the lobe table's exit for tilted scales, R's mirror),
    /// no arcsine and no sine is taken.
    #[inline]
    pub(super) fn cone_lobe(
        &self,
        p: usize,
        theta_i: f64,
        phi: f64,
        mirrors: &[Option<MirrorOffset>; 3],
    ) -> ConeLobe {
        let tilted = self.scales == Scales::Tilted;
        let exit = |[x, w]: sine_lobes::Shape| ConeLobe::from_sin(shape_variance(theta_i, w), x);
        match (&self.lobes, p) {
            (Some(table), 2) if tilted => exit(table.trt(theta_i)),
            (_, 0) => {
                if let Some(rough) = self.rough_mirror() {
                    return rough.lobe(theta_i, sin_cos_quadrant(theta_i).0, phi);
                }
                match self.r_cone(theta_i, phi, mirrors) {
                    Some(m) => {
                        ConeLobe::from_sin(mirror_variance(self.params.beta, &m), m.sin_theta)
                    }
                    None => self.r_lobe_paper(theta_i, phi).into(),
                }
            }
            _ => self.longitudinal_at(p, theta_i, phi, mirrors).into(),
        }
    }

    /// TT's lobe at (θ_i, φ) as the lobe table holds it: for the tilted model, the mean and
    /// standard deviation of the exit sine and the split of its skewness
    /// ([`Self::tt_moments`]), else [`Self::lobe_shape`]'s, unsplit.
    pub(super) fn tt_shape(&self, theta_i: f64, phi: f64) -> sine_lobes::TtShape {
        match self.scales {
            Scales::Tilted => {
                let SkewedSine {
                    moments: SineMoments { mean, variance },
                    skewness,
                    reach,
                } = self.tt_moments(theta_i, phi);
                sine_lobes::TtShape {
                    shape: [mean, variance.sqrt()],
                    split: SkewSplit::new(skewness),
                    reach,
                }
            }
            Scales::Paper => sine_lobes::TtShape {
                shape: self.lobe_shape(1, theta_i, phi),
                split: SkewSplit::new(0.0),
                reach: FULL_REACH,
            },
        }
    }

    /// The tilted model's TT lobe at (θ_i, φ) without the lobe table, as the mean, variance
    /// and skewness of its exit sine over the light of every offset that reaches φ through the
    /// rough surface
    /// ([`crate::models::nonseparable::rough::deflection::RoughTtTable::column_sine`]), at every
    /// inclination: where the smooth path at h = 0 is blocked too, the light that leaves comes from
    /// the slopes' tails, which the widened lattice reaches (departure 25; before it, the lobe
    /// there was the one a rough exit cuts at the offset whose exit leaves at φ,
    /// [`tt_lobe_rough`]). The columns' mean and variance are set apart from the moments they
    /// give so that the sine lobe has those moments after its truncation to [−1, 1]
    /// ([`SkewedSineLobe::matched`]; departure 22). The tilted model always has the columns;
    /// without them (a model built otherwise) the lobe is the cut one.
    pub(super) fn tt_moments(&self, theta_i: f64, phi: f64) -> SkewedSine {
        let Some(table) = self.rough_tt() else {
            let FiberParams {
                eta, beta, alpha, ..
            } = self.params;
            return SkewedSine {
                moments: tt_lobe_rough(theta_i, alpha, eta, beta, self.tt_offset(theta_i, phi)),
                skewness: self.tt_skewness(theta_i),
                reach: FULL_REACH,
            };
        };
        let column = table.column_sine(theta_i, phi);
        SkewedSine {
            moments: SkewedSineLobe::matched(column),
            ..column
        }
    }

    /// TRT's (p = 2) or the paper's TT lobe shape as the lobe table holds it ([`lobe_table`]):
    /// the Nusselt exit's sine before any clamp, at TT's offset for φ or TRT's h = 0, and
    /// √v cos θ_d.
    pub(super) fn lobe_shape(&self, p: usize, theta_i: f64, phi: f64) -> sine_lobes::Shape {
        let cos_d = theta_i.cos().abs();
        match p {
            1 => {
                let h = self.tt_offset(theta_i, phi);
                let FiberParams {
                    eta, beta, alpha, ..
                } = self.params;
                let CutLobe { sin_cone, variance } = first_order_tt(theta_i, alpha, eta, beta, h);
                [sin_cone, variance.sqrt() * cos_d]
            }
            _ => {
                let CutLobe { sin_cone, variance } = self.trt_lobe(theta_i);
                [sin_cone, variance.sqrt() * cos_d]
            }
        }
    }

    /// TRT's lobe: the exit's sine at h = 0 before any clamp and the paper's variance
    /// ([`variance_trt`]), or, through tilted scales, the von Mises–Fisher lobe whose light has
    /// the mean and variance of the exit sine that TRT's micro-normal triples let out over
    /// every offset ([`RoughTrtTable`], [`ConeLobe::from_sine_moments`]; departure 29), and
    /// where none leaves, the spread of the smooth exit over the offsets
    /// ([`cones::trt_lobe_tilted`]).
    pub(super) fn trt_lobe(&self, theta_i: f64) -> CutLobe {
        let FiberParams {
            eta, beta, alpha, ..
        } = self.params;
        match self.scales {
            Scales::Paper => CutLobe {
                sin_cone: nusselt::exit_trt([alpha; 3], eta, incident(theta_i, 0.0)),
                variance: variance_trt(beta, eta, -theta_i),
            },
            Scales::Tilted => match RoughTrtTable::shared(eta, alpha, beta).at(theta_i) {
                Some(SineMoments { mean, variance }) => {
                    let lobe = ConeLobe::from_sine_moments(mean, variance);
                    CutLobe {
                        sin_cone: lobe.sin_cone,
                        variance: lobe.v,
                    }
                }
                None => cones::trt_lobe_tilted(theta_i, alpha, eta, beta, |h| {
                    let a = self.azimuthal().attenuation(theta_i, h).0[2];
                    (a.x + a.y + a.z) / 3.0
                }),
            },
        }
    }

    /// The tilted model's TT lobe at (θ_i, φ), in its exit sine ([`SkewedSineLobe`]): the
    /// lobe table's where there is one, else [`Self::tt_moments`].
    #[inline]
    pub(super) fn tt_sine_lobe(&self, theta_i: f64, phi: f64) -> SkewedSineLobe {
        match &self.lobes {
            Some(table) => {
                let sine_lobes::TtShape {
                    shape: [mean, sd],
                    split,
                    reach,
                } = table.tt(theta_i, phi);
                SkewedSineLobe::split(mean, sd, split, reach)
            }
            None => self.tt_sine_lobe_exact(theta_i, phi),
        }
    }

    /// [`Self::tt_sine_lobe`] without the table: [`Self::tt_moments`] found anew, the
    /// reference the table is measured against.
    pub(super) fn tt_sine_lobe_exact(&self, theta_i: f64, phi: f64) -> SkewedSineLobe {
        SkewedSineLobe::new(self.tt_moments(theta_i, phi))
    }

    /// The skewness of the tilted model's TT exit sine at θ_i where the rough exit cuts the
    /// lobe ([`cones::tt_skewness`]); 0 in the paper's form.
    pub(super) fn tt_skewness(&self, theta_i: f64) -> f64 {
        let FiberParams {
            eta, beta, alpha, ..
        } = self.params;
        match self.scales {
            Scales::Tilted => cones::tt_skewness(theta_i, alpha, eta, beta),
            Scales::Paper => 0.0,
        }
    }

    /// sin θ_o drawn from lobe p ≤ 2 at (θ_i, φ) with two uniform numbers: from the lobe
    /// sampling reads ([`Self::sampling_lobe`]), or the tilted model's TT lobe, which takes one.
    #[inline]
    pub(super) fn sample_lobe_sin(&self, p: usize, theta_i: f64, phi: f64, u: [f64; 2]) -> f64 {
        match (p, self.scales) {
            (1, Scales::Tilted) => self.tt_sine_lobe(theta_i, phi).sample_sin(u[0]),
            _ => self.sampling_lobe(p, theta_i, phi).sample_sin(u[0], u[1]),
        }
    }

    /// The lobe of an interpolated shape: the cone from its x as [`cone_tt_tilted`] and
    /// [`cone_tt`] take it from theirs, v from √v cos θ_d.
    pub(super) fn lobe_from_shape(
        &self,
        theta_i: f64,
        [x, w]: sine_lobes::Shape,
    ) -> LongitudinalLobe {
        let cone = match self.scales {
            Scales::Tilted => asin_fast(x.clamp(-1.0, 1.0)),
            Scales::Paper => cones::pole_where_beyond(theta_i, x),
        };
        LongitudinalLobe::new(shape_variance(theta_i, w), cone)
    }

    /// The offset h whose TT path leaves at azimuth φ for light at θ_i: through the tilted
    /// scales where they tilt and the path at h = 0 leaves ([`tilted_tt_offset`]), else by
    /// Bravais' Φ(1, h) ([`TtOffsets`]).
    pub(super) fn tt_offset(&self, theta_i: f64, phi: f64) -> f64 {
        let eta = self.params.eta;
        let alpha = self.params.alpha;
        if self.scales == Scales::Tilted
            && alpha != 0.0
            && let Some(h) = tilted_tt_offset(theta_i, alpha, eta, phi)
        {
            return h;
        }
        self.tt_offsets
            .get_or_init(|| TtOffsets::build(eta))
            .offset(phi, eta_prime(eta, -theta_i))
    }

    /// [`Self::longitudinal_at`] without the lobe table: TT's offset solved and the Nusselt
    /// rotations run.
    pub(super) fn longitudinal_exact(
        &self,
        p: usize,
        theta_i: f64,
        phi: f64,
        mirrors: &[Option<MirrorOffset>; 3],
    ) -> LongitudinalLobe {
        let FiberParams {
            eta, beta, alpha, ..
        } = self.params;
        let theta_d = -theta_i;
        let tilted = self.scales == Scales::Tilted;
        match p {
            // The exact mirror at the offset that reflects to φ (the first of φ, φ − 2π,
            // φ + 2π that one reaches; the mirror table's in the fast path), its variance at
            // fixed φ through the tilted scale.
            0 => {
                if let Some(rough) = self.rough_mirror() {
                    let lobe = rough.lobe(theta_i, sin_cos_quadrant(theta_i).0, phi);
                    return LongitudinalLobe::new(lobe.v, asin_fast(lobe.sin_cone));
                }
                match self.r_cone(theta_i, phi, mirrors) {
                    Some(m) => {
                        LongitudinalLobe::new(mirror_variance(beta, &m), asin_fast(m.sin_theta))
                    }
                    None => self.r_lobe_paper(theta_i, phi),
                }
            }
            1 => {
                if tilted {
                    return cone_of_sine_lobe(self.tt_sine_lobe_exact(theta_i, phi));
                }
                let h = self.tt_offset(theta_i, phi);
                let cone = cone_tt(theta_i, alpha, eta, h);
                LongitudinalLobe::new(variance_tt(beta, eta, theta_d, h), cone)
            }
            2 => {
                let lobe = self.trt_lobe(theta_i);
                let cone = if tilted {
                    asin_fast(lobe.sin_cone.clamp(-1.0, 1.0))
                } else {
                    cone_trt(theta_i, alpha, eta)
                };
                LongitudinalLobe::new(lobe.variance, cone)
            }
            _ => self.deon.longitudinal(p, theta_i),
        }
    }
}

/// The von Mises–Fisher lobe with a sine lobe's mean and variance of sin θ_o to first order,
/// those of its light as truncated (to the pole or its reach): where
/// [`NonSeparable::longitudinal`] describes the tilted model's TT lobe, whose shape is the
/// [`SkewedSineLobe`], by a cone and a width in θ.
pub(super) fn cone_of_sine_lobe(lobe: SkewedSineLobe) -> LongitudinalLobe {
    let SineMoments { mean, variance } = lobe.truncated_moments();
    LongitudinalLobe::new(
        cones::variance_from_sine_spread(mean, variance),
        asin_fast(mean.clamp(-1.0, 1.0)),
    )
}

/// v of a lobe table shape's √v cos θ_d, with θ_d = −θ_i.
#[inline]
pub(super) fn shape_variance(theta_i: f64, w: f64) -> f64 {
    let cos_d = cos_quadrant(theta_i).abs().max(1e-6);
    (w / cos_d).powi(2)
}

/// R's variance at the offset of its mirror: ½β² times the square of the mirror's spread at
/// fixed φ through the tilted scale ([`MirrorOffset::spread`]), which untilted is eq. 6's
/// v_R = 2β²(1 − h²).
#[inline]
pub(super) fn mirror_variance(beta: f64, m: &MirrorCone) -> f64 {
    0.5 * beta * beta * m.spread * m.spread
}
