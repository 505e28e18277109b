//! Procedural grooms, deterministic from a seed.
//!
//! Strands grow from the scalp of an ellipsoidal head ([`Head`]) centred at the origin, **+z
//! up, the face toward +y** (as in the cyHair models), in centimetres. Each strand starts along
//! the comb direction (back and away from a centre parting), bends under gravity, stays outside
//! the head, is pulled toward its clump's guide strand, and gets its clump's waves and curls.
//! Every clump and strand draws from its own generator, so the groom is the same for a seed
//! whatever the number of threads.
//!
//! [`default_groom`] is the project's built-in scene groom: [`Preset::Straight`], 10,000
//! strands of 20–30 points. Thickness is about 4× that of real hair (300 µm at the root), as in
//! the cyHair models, so that 10,000 strands cover a head.

mod growth;
mod head;
mod params;
mod preset;
mod random;
mod styling;

pub use head::Head;
pub use params::{
    CLUMP_SIZE, CLUMPING, GroomParams, MAX_POINTS_PER_STRAND, MAX_STRANDS, MIN_POINTS,
    NON_NEGATIVE, POSITIVE, STRANDS,
};
pub use preset::Preset;

use crate::appearance::Appearance;
use crate::error::ParamsError;
use crate::groom::{Groom, GroomParts};
use glam::Vec3;
use growth::Growth;
use random::{Random, Stream};
use rayon::prelude::*;
use styling::{Curl, Wave};

/// The project's built-in scene groom: the default preset with its default seed.
pub fn default_groom() -> Groom {
    generate(&Preset::default().params()).expect("the default preset's parameters are valid")
}

/// The groom `params` describe.
pub fn generate(params: &GroomParams) -> Result<Groom, ParamsError> {
    params.validate()?;
    let clump_count = params.strands.div_ceil(params.clump_size);
    let clumps: Vec<Clump> = (0..clump_count)
        .into_par_iter()
        .map(|c| Clump::new(params, c))
        .collect();
    let strands: Vec<GrownStrand> = (0..params.strands)
        .into_par_iter()
        .map(|i| grow_strand(params, &clumps, i))
        .collect();
    assemble(params, strands)
}

/// What the strands of one clump share: a guide to gather around, and their style.
struct Clump {
    root_dir: Vec3,
    guide: Vec<Vec3>,
    side: Vec3,
    wave: Wave,
    curl: Curl,
    absorption_scale: f32,
}

impl Clump {
    fn new(params: &GroomParams, index: usize) -> Self {
        let rng = &mut Random::for_object(params.seed, Stream::Clump, index);
        let root_dir = params.head.sample_scalp_direction(rng);
        let guide = growth_from(params, root_dir, params.max_points, rng).centreline(&params.head);
        let normal = params.head.normal_at(guide[0]);
        Self {
            root_dir,
            guide,
            side: head::side_direction(normal),
            wave: Wave {
                amplitude: params.wave_amplitude * rng.range(0.7, 1.3),
                wavelength: params.wavelength * rng.range(0.85, 1.15),
                phase: rng.angle(),
            },
            curl: Curl {
                radius: params.curl_radius * rng.range(0.8, 1.2),
                pitch: params.curl_pitch * rng.range(0.85, 1.15),
                phase: rng.angle(),
            },
            absorption_scale: (params.absorption_variation * rng.normal()).exp(),
        }
    }
}

/// How a strand rooted at `root_dir` grows: its length, volume and comb direction drawn here.
fn growth_from(params: &GroomParams, root_dir: Vec3, points: usize, rng: &mut Random) -> Growth {
    let head = &params.head;
    let root = head.surface_point(root_dir);
    let normal = head.normal_at(root);
    Growth {
        root,
        direction: head::comb_direction(root_dir, normal, params.lift),
        length: params.length * (1.0 + params.length_variation * rng.normal()).max(0.3),
        points,
        gravity: params.gravity,
        margin: params.volume * rng.range(0.15, 1.0),
    }
}

/// One finished strand.
struct GrownStrand {
    points: Vec<Vec3>,
    appearance: Appearance,
}

fn grow_strand(params: &GroomParams, clumps: &[Clump], index: usize) -> GrownStrand {
    let rng = &mut Random::for_object(params.seed, Stream::Strand, index);
    let clump = &clumps[index % clumps.len()];
    let root_dir = scatter_root(params, clump.root_dir, rng);
    let points_count = rng.int_inclusive(params.min_points, params.max_points);
    let mut points = growth_from(params, root_dir, points_count, rng).centreline(&params.head);
    styling::clump_toward(&mut points, &clump.guide, params.clumping);
    let wave = Wave {
        phase: clump.wave.phase + 0.2 * rng.normal(),
        ..clump.wave
    };
    let curl = Curl {
        phase: clump.curl.phase + 0.2 * rng.normal(),
        ..clump.curl
    };
    styling::add_wave_and_curl(&mut points, clump.side, wave, curl);
    for p in points.iter_mut().skip(1) {
        *p = params.head.push_out(*p, 0.02).unwrap_or(*p);
    }
    let scale = clump.absorption_scale * (0.5 * params.absorption_variation * rng.normal()).exp();
    GrownStrand {
        points,
        appearance: params.appearance.with_absorption_scaled(scale),
    }
}

/// A root near the clump's, spread over the clump's footprint.
fn scatter_root(params: &GroomParams, clump_dir: Vec3, rng: &mut Random) -> Vec3 {
    let mean_radius = params.head.radii.iter().sum::<f32>() / 3.0;
    let spread = params.clump_radius / mean_radius;
    let (a, b) = clump_dir.any_orthonormal_pair();
    (clump_dir + (a * rng.normal() + b * rng.normal()) * spread).normalize()
}

/// Flattens the strands into a groom's arrays, with tapered thickness.
fn assemble(params: &GroomParams, strands: Vec<GrownStrand>) -> Result<Groom, ParamsError> {
    let total: usize = strands.iter().map(|s| s.points.len()).sum();
    let mut parts = GroomParts {
        positions: Vec::with_capacity(total),
        thickness: Vec::with_capacity(total),
        strand_offsets: Vec::with_capacity(strands.len() + 1),
        ..GroomParts::default()
    };
    parts.strand_offsets.push(0);
    let mut appearance = Vec::with_capacity(strands.len());
    for strand in strands {
        let n = strand.points.len();
        parts
            .thickness
            .extend((0..n).map(|k| taper(params, k as f32 / (n - 1) as f32)));
        parts.positions.extend(strand.points);
        parts.strand_offsets.push(parts.positions.len() as u32);
        appearance.push(strand.appearance);
    }
    Ok(Groom::from_parts(parts)?.with_appearance(appearance)?)
}

/// Thickness a fraction `t` of the way from root to tip: constant, then tapering over the
/// last fifth.
fn taper(params: &GroomParams, t: f32) -> f32 {
    let s = ((t - 0.8) / 0.2).clamp(0.0, 1.0);
    params.root_thickness + (params.tip_thickness - params.root_thickness) * s
}
