//! What a render needs in memory, estimated from the scene before anything large is allocated,
//! so that a request beyond the machine is refused with one sentence instead of failing, or
//! being killed, half way through.
//!
//! The estimate is an upper bound on the peak of the process (tested against a counting
//! allocator in `tests/memory.rs`): how many points are visible is known only after drawing, so
//! the visible-point buffers count the least of the groom's points and two per subsample.

use crate::frame::sub_lights::{max_sub_lights, split_wide};
use crate::scene::{Method, Scene, SceneSpec};
use cuticle_fiber::models::marschner2003::MarschnerParams;
use cuticle_groom::procedural::Preset;
use std::fmt;

/// Bytes per point of a groom while it is generated: the grown strands, then the assembled
/// positions, thickness and tangents.
const GROOM_PER_POINT: u64 = 48;
/// Bytes per strand of a groom: offsets, lengths, appearance, clumps.
const GROOM_PER_STRAND: u64 = 160;
/// Bytes per point of a frame besides shadows: visibility flags, the visible list, the strand
/// of each point, colours by point and by visible point.
const FRAME_PER_POINT: u64 = 64;
/// Bytes per subsample of the visibility buffer: segment, position along it and depth.
const PER_SUBSAMPLE: u64 = 12;
/// Bytes per pixel: background, the linear image, and the PNG and EXR encodings.
const PER_PIXEL: u64 = 120;
/// Bytes per point of one light's transmittance (the compact buffer, the per-light columns
/// and the frame's buffer, f32 each).
const SHADOW_PER_POINT_AND_LIGHT: u64 = 12;
/// Bytes per texel of an opacity map: first depth (and its copy while building), six layers
/// summed in place into their summed-area tables.
const PER_TEXEL: u64 = 56;
/// Bytes per point of one opacity map: the groom's points in the map's frame, and the depth
/// samples kept between its two passes (at most
/// [`crate::frame::shadows::KEPT_SAMPLES_PER_POINT`] of 16 bytes a point, else none).
const MAP_PER_POINT: u64 = 24 + 16 * crate::frame::shadows::KEPT_SAMPLES_PER_POINT as u64;
/// The renderer's tables, the default environment and its fit, and everything else of fixed
/// size (tests/memory.rs measures the peak against the whole estimate).
const FIXED: u64 = 40 << 20;
/// Bytes per pixel of an environment map read from a file, with the copies the fit makes.
const ENV_PER_PIXEL: u64 = 32;

/// The bytes a render needs, by part.
#[derive(Clone, Debug, PartialEq)]
pub struct MemoryNeed {
    pub parts: Vec<(&'static str, u64)>,
}

/// A render that needs more memory than the machine has.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error(
    "this {what} needs about {need} of memory, {largest} the most, and {available} is \
     available: {advice}",
    need = Bytes(self.need.total()),
    largest = self.need.largest(),
    available = Bytes(*available),
    what = self.advice.what,
    advice = self.advice.lower
)]
pub struct MemoryError {
    pub need: MemoryNeed,
    pub available: u64,
    pub advice: Advice,
}

/// What a refusal calls the work, and which of the command's own flags make it smaller
/// (issue 57 #14: `groom make` was told to lower a --width it does not have).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Advice {
    pub what: &'static str,
    pub lower: &'static str,
}

impl Advice {
    /// `render --method srbf|brute`, `bench render` and the window.
    pub const RENDER: Advice = Advice {
        what: "render",
        lower: "lower --width/--height/--supersampling, --strands or the number of lights",
    };
    /// `render --method path`: no lights, no supersampling.
    pub const PATH: Advice = Advice {
        what: "render",
        lower: "lower --width/--height or --strands",
    };
}

/// Bytes in the unit a person reads (`6.4 GB`).
pub struct Bytes(pub u64);

impl fmt::Display for Bytes {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let b = self.0 as f64;
        match b {
            b if b >= 1e9 => write!(f, "{:.1} GB", b / 1e9),
            b if b >= 1e6 => write!(f, "{:.0} MB", b / 1e6),
            b => write!(f, "{:.0} kB", b / 1e3),
        }
    }
}

impl MemoryNeed {
    pub fn total(&self) -> u64 {
        self.parts
            .iter()
            .fold(0u64, |sum, (_, b)| sum.saturating_add(*b))
    }

    /// "the shadows (4.8 GB)": the largest part and its size.
    pub fn largest(&self) -> String {
        self.parts
            .iter()
            .max_by_key(|(_, b)| *b)
            .map_or(String::new(), |(name, b)| format!("{name} ({})", Bytes(*b)))
    }

    /// Refuses the render when it needs more than `available` bytes.
    pub fn check(self, available: u64) -> Result<(), MemoryError> {
        self.check_for(available, Advice::RENDER)
    }

    /// Refuses the work when it needs more than `available` bytes, with `advice`.
    pub fn check_for(self, available: u64, advice: Advice) -> Result<(), MemoryError> {
        if self.total() <= available {
            Ok(())
        } else {
            Err(MemoryError {
                need: self,
                available,
                advice,
            })
        }
    }
}

/// What one frame of `spec` needs for a groom of `points` points in `strands` strands lit by
/// `lights` lights, with `threads` opacity maps built at once.
pub fn frame_need(
    spec: &SceneSpec,
    points: u64,
    strands: u64,
    lights: u64,
    threads: u64,
    env_pixels: u64,
) -> MemoryNeed {
    let m = |a: u64, b: u64| a.saturating_mul(b);
    let pixels = m(spec.width as u64, spec.height as u64);
    let ss = spec.supersampling as u64;
    let subsamples = m(pixels, ss * ss);
    let texels = m(
        spec.shadows.resolution as u64,
        spec.shadows.resolution as u64,
    );
    // Each covered subsample makes the two ends of one segment visible.
    let visible = points.min(m(subsamples, 2));
    let maps_at_once = threads.clamp(1, lights.max(1));
    let per_map = m(texels, PER_TEXEL).saturating_add(m(points, MAP_PER_POINT));
    let fibers = std::mem::size_of::<MarschnerParams>() as u64;
    MemoryNeed {
        parts: vec![
            ("the tables", FIXED),
            ("the environment map", m(env_pixels, ENV_PER_PIXEL)),
            (
                "the groom",
                m(points, GROOM_PER_POINT).saturating_add(m(strands, GROOM_PER_STRAND)),
            ),
            (
                "the visibility buffer (width x height x supersampling^2)",
                m(subsamples, PER_SUBSAMPLE),
            ),
            ("the images", m(pixels, PER_PIXEL)),
            (
                "the points' shading buffers",
                m(points, FRAME_PER_POINT).saturating_add(m(strands, fibers)),
            ),
            (
                "the shadows (visible points x lights)",
                m(m(visible, lights), SHADOW_PER_POINT_AND_LIGHT),
            ),
            ("the opacity maps", m(maps_at_once, per_map)),
        ],
    }
}

/// The most lights a frame shades for `fitted` SRBF lights before they are split: each wide
/// light may become sub-lights of the shared set of `max_sub_lights` (frame/sub_lights.rs), so
/// the split adds at most that many.
pub fn split_bound(spec: &SceneSpec, fitted: usize) -> usize {
    fitted + max_sub_lights(spec.shadows.split_bandwidth)
}

/// The lights a frame of `spec` shades: the brute force's 6 n² directions, or the SRBF lights.
pub fn light_count(spec: &SceneSpec, srbf_lights: usize) -> u64 {
    match spec.method {
        Method::Brute => 6 * (spec.brute_grid as u64).pow(2),
        Method::Srbf | Method::Path => srbf_lights as u64,
    }
}

impl SceneSpec {
    /// What a frame of this scene needs, known before the groom is made: a preset's points at
    /// its most points per strand (a `.hair` groom counts as none until it is read), and
    /// `lights` SRBF lights (read from a file) or the number to fit, with the most sub-lights
    /// their split can add.
    pub fn memory_need(&self, lights: Option<usize>, threads: usize) -> MemoryNeed {
        let (points, strands) = match self.groom.parse::<Preset>() {
            Ok(preset) => {
                let strands = self.strands as u64;
                (
                    strands.saturating_mul(preset.params().max_points as u64),
                    strands,
                )
            }
            Err(_) => (0, 0),
        };
        let lights = light_count(self, split_bound(self, lights.unwrap_or(self.lights)));
        frame_need(self, points, strands, lights, threads as u64, 0)
    }
}

impl Scene {
    /// The lights a frame of this scene shades: the brute force's directions, or the SRBF
    /// lights after the wide ones are split (what render.json reports as `shaded_lights`).
    pub fn shaded_lights(&self) -> u64 {
        light_count(
            &self.spec,
            split_wide(&self.lights, self.spec.shadows.split_bandwidth).len(),
        )
    }

    /// What a frame of this loaded scene needs.
    pub fn memory_need(&self, threads: usize) -> MemoryNeed {
        frame_need(
            &self.spec,
            self.groom.point_count() as u64,
            self.groom.strand_count() as u64,
            self.shaded_lights(),
            threads as u64,
            (self.env.width() * self.env.height()) as u64,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_issue_s_sizes_need_what_they_were_measured_to_need() {
        let spec = |f: fn(&mut SceneSpec)| {
            let mut s = SceneSpec::default();
            f(&mut s);
            s
        };
        // 16384 × 16384 at 3 × 3 subsamples: 29 GB of visibility buffer alone.
        let big = spec(|s| (s.width, s.height) = (16384, 16384)).memory_need(None, 2);
        assert!(big.total() > 29_000_000_000, "{}", Bytes(big.total()));
        let visibility = big
            .parts
            .iter()
            .find(|(n, _)| n.starts_with("the visibility"));
        assert!(
            visibility.is_some_and(|(_, b)| *b > 28_000_000_000),
            "{big:?}"
        );
        let err = big.check(8_000_000_000).unwrap_err().to_string();
        assert!(
            err.contains("needs about") && err.contains("8.0 GB is available"),
            "{err}"
        );
        // 2,000,000 strands: the issue saw 4.8 GB allocations fail after 6.4 GB resident.
        let many = spec(|s| s.strands = 2_000_000).memory_need(None, 2);
        assert!(many.total() > 11_000_000_000, "{}", Bytes(many.total()));
        // The default scene fits in well under a gigabyte.
        let default = SceneSpec::default().memory_need(None, 2);
        assert!(
            default.total() < 1_000_000_000,
            "{}",
            Bytes(default.total())
        );
        assert!(default.check(1 << 30).is_ok());
    }

    /// Before the lights are fitted, the estimate counts the sub-lights the split may add: the
    /// shadows of a frame grow with them, and splitting off must lower it.
    #[test]
    fn the_estimate_before_the_fit_counts_the_sub_lights() {
        let mut split = SceneSpec::default();
        split.shadows.split_bandwidth = 0.5;
        let mut whole = split.clone();
        whole.shadows.split_bandwidth = 1000.0;
        assert_eq!(split_bound(&split, 40), 40 + 51);
        assert_eq!(split_bound(&whole, 40), 41);
        let (a, b) = (
            split.memory_need(Some(40), 2),
            whole.memory_need(Some(40), 2),
        );
        assert!(
            a.total() > b.total(),
            "{} vs {}",
            Bytes(a.total()),
            Bytes(b.total())
        );
    }
}
