//! Monte Carlo ground truth for fiber scattering (seed 000 §2.1): light paths through a
//! unit-radius rough dielectric cylinder along u = +x (the canonical frame of
//! `cuticle_fiber::FiberFrame`), with a Beckmann micro-surface and Smith shadowing
//! (Walter et al. 2007), tilted cuticle scales as a shading normal, and Beer–Lambert absorption
//! inside; exits are binned by lobe into lat-long images of S (DESIGN.md §3–4).
//!
//! ```no_run
//! use cuticle_sim::{SimParams, simulate};
//! let r = simulate(&SimParams { rays: 1_000_000, ..Default::default() }, &|_, _| {}).unwrap();
//! println!("R energy {}", r.energy[0].x);
//! ```
//!
//! [`sweep`] runs many configurations into folders, resumably; [`grid`] defines them.

mod absorption;
mod accumulate;
mod atomic;
pub mod beckmann;
mod bin;
pub mod cylinder;
pub mod dielectric;
mod erf;
pub mod grid;
mod interface;
mod ln;
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
