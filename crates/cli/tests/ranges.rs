//! Every range a command checks, taken from the constant that states it (each lives once,
//! beside what it bounds): the command refuses the value just outside each finite end, in one
//! line that names the range, and accepts the flag's default. A range restated anywhere (a
//! second constant, a literal in a parser) drifts from these and fails here.

mod common;

use common::assert_refused;
use cuticle_fiber::ranges::{self, CountRange, End, Range};
use cuticle_render::scene;

/// A command line up to the flag under test; every one fails fast on a bad value.
type Command = &'static [&'static str];

const LOBES: Command = &["lobes"];
const RENDER: Command = &["render"];
const PATH: Command = &["render", "--method", "path"];
const SIM: Command = &["sim"];

/// The real ranges: (command, flag, range).
fn real_ranges() -> Vec<(Command, &'static str, Range)> {
    vec![
        (LOBES, "--beta", ranges::BETA),
        (LOBES, "--eta", ranges::ETA),
        (LOBES, "--alpha-deg", ranges::ALPHA_DEG),
        (LOBES, "--theta-i", ranges::THETA_I),
        (LOBES, "--mu-a", ranges::MU_A),
        (LOBES, "--eumelanin", ranges::MELANIN),
        (RENDER, "--eta", ranges::ETA),
        (RENDER, "--alpha-r-deg", ranges::ALPHA_R_DEG),
        (RENDER, "--beta-r-deg", ranges::BETA_R_DEG),
        (RENDER, "--mu-a", ranges::MU_A),
        (RENDER, "--eccentricity", ranges::ECCENTRICITY),
        (RENDER, "--caustic-width-deg", ranges::CAUSTIC_WIDTH_DEG),
    ]
}

/// Count flags whose 0 means "off" (`lobes --samples 0`: no histogram), below their range.
const ZERO_IS_OFF: [&str; 1] = ["--samples"];

/// The count ranges: (command, flag, range).
fn count_ranges() -> Vec<(Command, &'static str, CountRange)> {
    vec![
        (LOBES, "--iterations", ranges::ITERATIONS),
        (LOBES, "--samples", ranges::SAMPLES),
        (SIM, "--rays", cuticle_sim::params::RAYS),
        (RENDER, "--width", scene::SIZE),
        (RENDER, "--height", scene::SIZE),
        (RENDER, "--supersampling", scene::SUPERSAMPLING),
        (RENDER, "--quadrature", scene::QUADRATURE),
        (RENDER, "--brute-grid", scene::BRUTE_GRID),
        (RENDER, "--strands", scene::STRANDS),
        (RENDER, "--lights", scene::LIGHTS),
        (PATH, "--spp", cuticle_trace::SPP),
        (PATH, "--max-depth", cuticle_trace::MAX_DEPTH),
    ]
}

/// The values just outside a range's finite ends: an open end itself, a closed one moved
/// outward by a relative 1e-6 (and 1e-6 at zero).
fn just_outside(r: &Range) -> Vec<f64> {
    let out = |v: f64, sign: f64| v + sign * 1e-6 * v.abs().max(1.0);
    [(r.min, -1.0), (r.max, 1.0)]
        .into_iter()
        .filter_map(|(end, sign)| match end {
            End::Open(v) if v.is_finite() => Some(v),
            End::Closed(v) if v.is_finite() => Some(out(v, sign)),
            _ => None,
        })
        .collect()
}

#[test]
fn every_real_range_refuses_the_value_just_outside() {
    for (command, flag, range) in real_ranges() {
        for value in just_outside(&range) {
            assert!(!range.contains(value), "{flag}: {value} is inside {range}");
            let value = format!("{value}");
            let mut args: Vec<&str> = command.to_vec();
            args.extend([flag, value.as_str(), "--out", "/nonexistent/ranges"]);
            // The message states the range as the constant prints it.
            assert_refused(&args, &range.to_string());
        }
    }
}

#[test]
fn every_count_range_refuses_the_count_just_outside() {
    for (command, flag, range) in count_ranges() {
        let mut outside = vec![range.max + 1];
        if range.min > 0 && !(range.min == 1 && ZERO_IS_OFF.contains(&flag)) {
            outside.push(range.min - 1);
        }
        for value in outside {
            let value = value.to_string();
            let mut args: Vec<&str> = command.to_vec();
            args.extend([flag, value.as_str(), "--out", "/nonexistent/ranges"]);
            assert_refused(&args, &range.to_string());
        }
    }
}
