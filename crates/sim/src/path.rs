//! One light path through the fiber, from its entry offset h until it leaves, is lost, or is
//! cut off, recorded into a [`Tally`].

use crate::absorption::Absorption;
use crate::accumulate::{Loss, LossSums, Tally};
use crate::bin::Binner;
use crate::cylinder::{advance, chord, entry_point, incident_ray, macro_normal};
use crate::interface::{Event, Surface};
use crate::params::SimParams;
use crate::rng::Sampler;
use crate::scale::Tilt;
use glam::{DVec2, DVec3};

/// Surface events after which a path is cut off and its weight counted as `Loss::Cutoff`.
pub const MAX_EVENTS: usize = 100;

/// The fiber and light of one simulation, with what every path reuses precomputed.
#[derive(Clone, Debug)]
pub struct Fiber {
    ray: DVec3,
    tilt: Tilt,
    outside: Surface,
    inside: Surface,
    absorption: Absorption,
    bins: Binner,
}

/// A path in flight: where it is, where it goes, and what it carries.
struct Path {
    /// Surface point (y, z) on the unit circle.
    p: DVec2,
    /// Travel direction.
    d: DVec3,
    inside: bool,
    /// Scalar surface-sampling weight w.
    w: f64,
    /// Beer–Lambert transmittance exp(−μ_a L) of the internal length L so far, RGB.
    atten: DVec3,
    /// Internal segments so far: the lobe index p on exit.
    segments: usize,
    /// Shadowing loss accumulated along the path, RGB (summed per path, recorded once).
    shadowed: DVec3,
}

impl Fiber {
    pub fn new(p: &SimParams) -> Self {
        Self {
            ray: incident_ray(p.theta_i),
            tilt: Tilt::new(p.alpha),
            outside: Surface::new(p.beta, p.eta),
            inside: Surface::new(p.beta, 1.0 / p.eta),
            absorption: Absorption::new(p.mu_a),
            bins: Binner::new(p.grid),
        }
    }

    /// Traces the path entering at offset h. The path's RGB weight is w · exp(−μ_a L): the
    /// surface sampling weights times Beer–Lambert over the internal length L. Every change of
    /// weight is recorded (exits in `tally`, losses in `lost`), so exits + losses + absorption
    /// = 1 per path.
    pub fn trace(&self, h: f64, rng: &mut Sampler, tally: &mut Tally, lost: &mut LossSums) {
        let mut path = Path {
            p: entry_point(h),
            d: self.ray,
            inside: false,
            w: 1.0,
            atten: DVec3::ONE,
            segments: 0,
            shadowed: DVec3::ZERO,
        };
        let end = self.run(&mut path, rng);
        lost.add(Loss::Shadowing, path.shadowed);
        match end {
            End::Exit(dir) => tally.exit(path.segments, self.bins.index(dir), path.w * path.atten),
            End::Lost(why) => lost.add(why, path.w * path.atten),
        }
    }

    /// Follows the path from surface event to surface event until it ends.
    fn run(&self, path: &mut Path, rng: &mut Sampler) -> End {
        for _ in 0..MAX_EVENTS {
            let n = macro_normal(path.p);
            let frame = self.tilt.frame_at(path.p);
            let (ng, frame, surface) = if path.inside {
                (-n, frame.flipped(), &self.inside)
            } else {
                (n, frame, &self.outside)
            };
            let (dir, factor, refracted) = match surface.scatter(-path.d, ng, &frame, rng) {
                Event::Scattered {
                    dir,
                    factor,
                    refracted,
                } => (dir, factor, refracted),
                Event::BackFacing => return End::Lost(Loss::BackFacing),
                Event::Shadowed => return End::Lost(Loss::Shadowing),
            };
            path.shadowed += (path.w - path.w * factor) * path.atten;
            path.w *= factor;
            if refracted == path.inside {
                return End::Exit(dir);
            }
            self.travel(path, dir);
        }
        End::Lost(Loss::Cutoff)
    }

    /// Crosses the fiber along `dir` to the next surface point.
    fn travel(&self, path: &mut Path, dir: DVec3) {
        let length = chord(path.p, dir);
        path.p = advance(path.p, dir, length);
        if self.absorption.absorbs() {
            path.atten *= self.absorption.over(length);
        }
        path.inside = true;
        path.segments += 1;
        path.d = dir;
    }
}

/// How a path ended.
enum End {
    Exit(DVec3),
    Lost(Loss),
}
