//! Monte Carlo ground truth for fiber scattering (d'Eon et al. 2014 §2.1): light paths through a
//! unit-radius rough dielectric cylinder along u = +x (the canonical frame of
//! `cuticle_fiber::FiberFrame`), with a Beckmann micro-surface and Smith shadowing
//! (Walter et al. 2007), tilted cuticle scales as a shading normal, and Beer–Lambert absorption
//! inside; exits are binned by lobe into lat-long images of S (docs/conventions.md §3–4).
//!
//! ```no_run
//! use cuticle_sim::{SimParams, simulate};
//! let r = simulate(&SimParams { rays: 1_000_000, ..Default::default() }, &|_, _| {}).unwrap();
//! println!("R energy {}", r.energy[0].x);
//! ```
//!
//! [`sweep`] runs many configurations into folders, resumably; [`grid`] defines them.
//!
//! Conventions a model compared with this simulator must share:
//! - Light arrives from ω_i = (sin θ_i, cos θ_i, 0) (φ_i = 0); a ray at offset h first meets the
//!   surface at azimuth −asin h, so its mirror direction has φ = −2γ_i (Bravais' Φ(0, h)).
//! - Positive α tilts the outward scale normal toward +u. With it, the R cone is d'Eon et al. 2014
//!   §2.3's θ_cone_R (to its own 0.2° approximation), and TT and TRT shift the other way: d'Eon et
//!   al. 2014 §2.2's derivative list holds with −α (the seed's two sections disagree on the sign;
//!   see `tests/tilt.rs`).
//! - Images hold S in sr⁻¹ per unit intercepted power (docs/conventions.md §3); the lobe is the
//!   number of internal segments, p ≥ 4 in "rest". Losses are reported, not renormalised away:
//!   shadowing and masking (with rays sent below the macro surface), back-facing scales, and paths
//!   cut off after [`path::MAX_EVENTS`] surface events.

mod absorption;
mod accumulate;
pub mod beckmann;
mod bin;
pub mod cylinder;
pub mod dielectric;
pub mod grid;
mod interface;
pub mod params;
pub mod path;
pub mod record;
mod rng;
pub mod scale;
pub mod shard;
pub mod simulate;
pub mod sweep;

pub use accumulate::LOBES;
pub use grid::SweepConfig;
pub use params::{SimError, SimParams};
pub use record::sim_json;
pub use shard::Shard;
pub use simulate::{CHUNK, LOBE_NAMES, SimResult, simulate};
pub use sweep::{Sweep, SweepError, SweepSummary, list_complete};
