//! Reading a sweep's folder layout (`cuticle_sim::sweep`): one subfolder per configuration,
//! complete when its `sim.json` exists, whose `"params"` give θ_i (radians), α (degrees, the
//! simulator's sign), β, η, μ_a and the ray count. The lobe images beside it (`R.exr`, …) are
//! read by the caller, which owns the EXR codec.

use crate::error::ValidateError;
use cuticle_fiber::FiberParams;
use glam::DVec3;
use serde::Serialize;
use serde_json::Value;
use std::fs;
use std::path::{Path, PathBuf};

/// The record a finished configuration leaves.
pub const RECORD: &str = "sim.json";

/// One simulated configuration.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SimConfig {
    pub dir: PathBuf,
    /// The folder's name, e.g. `ti0.75_a-2_b0.04_mu0_eta1.55`.
    pub name: String,
    pub theta_i: f64,
    pub alpha_deg: f64,
    pub beta: f64,
    pub eta: f64,
    pub mu_a: [f64; 3],
    pub rays: u64,
    /// The simulation's random seed, where its record gives one.
    pub seed: Option<u64>,
}

impl SimConfig {
    /// Reads `dir/sim.json`.
    pub fn read(dir: &Path) -> Result<Self, ValidateError> {
        let path = dir.join(RECORD);
        if !path.is_file() {
            return Err(ValidateError::NoRecord(dir.to_path_buf()));
        }
        let text = fs::read_to_string(&path).map_err(|source| ValidateError::Io {
            path: path.clone(),
            source,
        })?;
        let bad = |message: String| ValidateError::BadRecord {
            path: path.clone(),
            message,
        };
        let record: Value = serde_json::from_str(&text).map_err(|e| bad(e.to_string()))?;
        let params = &record["params"];
        let number = |key: &str| {
            params[key]
                .as_f64()
                .ok_or_else(|| bad(format!("\"params\" has no number \"{key}\"")))
        };
        let mu: Vec<f64> = params["mu_a"]
            .as_array()
            .map(|a| a.iter().filter_map(Value::as_f64).collect())
            .unwrap_or_default();
        let mu_a: [f64; 3] = mu
            .try_into()
            .map_err(|_| bad("\"params\".\"mu_a\" is not [r, g, b]".into()))?;
        Ok(Self {
            dir: dir.to_path_buf(),
            name: dir
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default(),
            theta_i: number("theta_i")?,
            alpha_deg: number("alpha_deg")?,
            beta: number("beta")?,
            eta: number("eta")?,
            mu_a,
            rays: record["rays"].as_u64().unwrap_or(0),
            seed: params["seed"].as_u64(),
        })
    }

    /// Whether `other` simulates the same fiber and light with as many paths: what a second
    /// run for the noise floor must do ([`crate::noise`]); its seed must differ.
    pub fn same_setup(&self, other: &SimConfig) -> bool {
        (
            self.theta_i,
            self.alpha_deg,
            self.beta,
            self.eta,
            self.mu_a,
            self.rays,
        ) == (
            other.theta_i,
            other.alpha_deg,
            other.beta,
            other.eta,
            other.mu_a,
            other.rays,
        )
    }

    /// The fiber the models are built for: α converted to radians with the simulator's sign.
    pub fn fiber_params(&self) -> FiberParams {
        FiberParams {
            eta: self.eta,
            beta: self.beta,
            alpha: self.alpha_deg.to_radians(),
            mu_a: DVec3::from_array(self.mu_a),
        }
    }

    /// μ_a's channel mean, for tables.
    pub fn mu_a_mean(&self) -> f64 {
        self.mu_a.iter().sum::<f64>() / 3.0
    }
}

/// The configurations under `root`, sorted by folder name: `root` itself when it holds a
/// `sim.json`, else every subfolder, each of which must hold one.
pub fn list_configs(root: &Path) -> Result<Vec<SimConfig>, ValidateError> {
    if !root.is_dir() {
        return Err(ValidateError::MissingFolder(root.to_path_buf()));
    }
    if root.join(RECORD).is_file() {
        return Ok(vec![SimConfig::read(root)?]);
    }
    let io = |source| ValidateError::Io {
        path: root.to_path_buf(),
        source,
    };
    let mut dirs: Vec<PathBuf> = fs::read_dir(root)
        .map_err(io)?
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| p.is_dir())
        .collect();
    dirs.sort();
    if dirs.is_empty() {
        return Err(ValidateError::Empty(root.to_path_buf()));
    }
    dirs.iter().map(|d| SimConfig::read(d)).collect()
}
