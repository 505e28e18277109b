//! Reading a sweep's folder layout (`cuticle_sim::sweep`): one subfolder per configuration,
//! complete when its `sim.json` exists, whose `"params"` give θ_i (radians), α (degrees, the
//! simulator's sign), β, η, μ_a, the ray count and the grid, and whose `"energy"` gives each
//! lobe's. The images beside it (`R.exr`, …, `total.exr`) and `azimuthal.csv` are read by the
//! caller, which owns the EXR codec, and checked here against the record
//! ([`SimConfig::check_set`]): validation relies on a configuration only once everything in
//! its folder agrees.

use crate::error::ValidateError;
use cuticle_fiber::lobe::channel_mean;
use cuticle_fiber::ranges::{ALPHA_DEG, BETA, ETA, MU_A, Range, THETA_I};
use cuticle_fiber::{FiberParams, LatLongImage};
use glam::DVec3;
use serde::Serialize;
use serde_json::Value;
use std::fs;
use std::path::{Path, PathBuf};

/// The record a finished configuration leaves.
pub const RECORD: &str = "sim.json";
/// The largest `sim.json` read (a real one is under 2 kB). `path.is_file()` already keeps out
/// pipes and devices.
const MAX_RECORD_BYTES: u64 = 1 << 20;

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
    /// The lat-long grid of the images, [width, height].
    pub grid: [usize; 2],
    /// ∫ S dω of R, TT, TRT, TRRT, rest and their total (channel means), as recorded.
    pub energy: [f64; 6],
    /// The simulation's random seed, where its record gives one.
    pub seed: Option<u64>,
}

/// The lobe files of a configuration, in lobe order, then their sum.
pub const FILES: [&str; 6] = ["R", "TT", "TRT", "TRRT", "rest", "total"];

/// How far a recorded figure may sit from the same figure of the f32 images.
const F32_TOLERANCE: f64 = 1e-5;

impl SimConfig {
    /// Reads `dir/sim.json`.
    pub fn read(dir: &Path) -> Result<Self, ValidateError> {
        let path = dir.join(RECORD);
        if !path.is_file() {
            return Err(ValidateError::NoRecord(dir.to_path_buf()));
        }
        let len = fs::metadata(&path).map(|m| m.len()).unwrap_or(0);
        if len > MAX_RECORD_BYTES {
            return Err(ValidateError::BadRecord {
                path,
                message: format!("is {len} bytes; a record is at most {MAX_RECORD_BYTES}"),
            });
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
        // The ranges `sim` checks its parameters with (issue 57 #10: θ_i = 10 validated to
        // energies of 0, θ_i = 1e308 to a report of NaN).
        let number = |key: &str, range: Range| {
            let v = params[key]
                .as_f64()
                .filter(|v| v.is_finite())
                .ok_or_else(|| bad(format!("\"params\" has no finite number \"{key}\"")))?;
            range.check(v).map_err(|e| bad(format!("\"params\": {e}")))
        };
        let triple = |v: &Value, key: &str| -> Result<Vec<f64>, ValidateError> {
            let a = v
                .as_array()
                .ok_or_else(|| bad(format!("{key} is not a list")))?;
            a.iter()
                .map(|x| {
                    x.as_f64()
                        .filter(|v| v.is_finite())
                        .ok_or_else(|| bad(format!("{key} holds {x}, not a finite number")))
                })
                .collect()
        };
        let mu_a: [f64; 3] = triple(&params["mu_a"], "\"params\".\"mu_a\"")?
            .try_into()
            .map_err(|_| bad("\"params\".\"mu_a\" is not [r, g, b]".into()))?;
        MU_A.check_all(&mu_a)
            .map_err(|e| bad(format!("\"params\": {e}")))?;
        let grid: Vec<usize> = triple(&params["grid"], "\"params\".\"grid\"")?
            .into_iter()
            .filter(|v| v.fract() == 0.0 && *v >= 1.0 && *v <= 1e5)
            .map(|v| v as usize)
            .collect();
        let grid: [usize; 2] = grid
            .try_into()
            .map_err(|_| bad("\"params\".\"grid\" is not [width, height]".into()))?;
        let rays = record["rays"]
            .as_u64()
            .ok_or_else(|| bad("\"rays\" is not a whole number".into()))?;
        cuticle_sim::params::RAYS
            .check(rays)
            .map_err(|e| bad(e.to_string()))?;
        let mut energy = [0.0; 6];
        for (e, name) in energy.iter_mut().zip(FILES) {
            *e = record["energy"][name]
                .as_f64()
                .filter(|v| v.is_finite())
                .ok_or_else(|| {
                    bad(format!(
                        "\"energy\".\"{name}\" is {}, not a finite number",
                        record["energy"][name]
                    ))
                })?;
        }
        Ok(Self {
            dir: dir.to_path_buf(),
            name: dir
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default(),
            theta_i: number("theta_i", THETA_I)?,
            alpha_deg: number("alpha_deg", ALPHA_DEG)?,
            beta: number("beta", BETA)?,
            eta: number("eta", ETA)?,
            mu_a,
            rays,
            grid,
            energy,
            seed: params["seed"].as_u64(),
        })
    }

    /// Whether `other` simulates the same fiber and light with as many paths, onto the same
    /// grid: what a second run for the noise floor must do ([`crate::noise`]); its seed must
    /// differ.
    pub fn same_setup(&self, other: &SimConfig) -> bool {
        self.grid == other.grid && self.same_fiber_and_paths(other)
    }

    fn same_fiber_and_paths(&self, other: &SimConfig) -> bool {
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

    /// Checks the configuration's images and `azimuthal.csv` against each other and against
    /// `sim.json`: each on the recorded grid, finite and non-negative; `total` the sum of the
    /// lobes; each image's energy the recorded one; the CSV's columns the images' densities in
    /// φ, row by row. `images` are R, TT, TRT, TRRT, rest, total.
    pub fn check_set(&self, images: &[LatLongImage; 6], csv: &str) -> Result<(), ValidateError> {
        let bad = |file: &str, message: String| ValidateError::BadRecord {
            path: self.dir.join(file),
            message,
        };
        for (img, name) in images.iter().zip(FILES) {
            let file = format!("{name}.exr");
            if [img.grid.width, img.grid.height] != self.grid {
                return Err(bad(
                    &file,
                    format!(
                        "is {}x{}, but sim.json records a {}x{} grid",
                        img.grid.width, img.grid.height, self.grid[0], self.grid[1]
                    ),
                ));
            }
            if let Some((k, p)) = img
                .pixels
                .iter()
                .enumerate()
                .find(|(_, p)| !p.is_finite() || p.min_element() < 0.0)
            {
                let (x, y) = (k % img.grid.width, k / img.grid.width);
                return Err(bad(
                    &file,
                    format!("pixel ({x}, {y}) is {p}, not a finite non-negative value"),
                ));
            }
            let e = channel_mean(img.energy());
            let want = self.energy[FILES.iter().position(|f| *f == name).unwrap_or(0)];
            if !close(e, want) {
                return Err(bad(
                    &file,
                    format!("holds energy {e}, but sim.json records {want}"),
                ));
            }
        }
        let mut sum = LatLongImage::zeros(images[0].grid);
        images[..5].iter().for_each(|i| sum.add(i));
        if let Some(k) = (0..sum.pixels.len()).find(|&k| {
            let (a, b) = (sum.pixels[k], images[5].pixels[k]);
            !(0..3).all(|c| close(a[c], b[c]))
        }) {
            return Err(bad(
                "total.exr",
                format!("pixel {k} is not the sum of the lobes' pixels"),
            ));
        }
        check_csv(images, csv).map_err(|m| bad("azimuthal.csv", m))
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

/// Equal to the precision the images are stored in.
fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= F32_TOLERANCE * a.abs().max(b.abs()) + 1e-12
}

/// `azimuthal.csv` against the images: the header, one row per column of the grid at its φ,
/// and each lobe's density in φ.
fn check_csv(images: &[LatLongImage; 6], csv: &str) -> Result<(), String> {
    let mut lines = csv.lines();
    let header = format!("phi,{}", FILES.join(","));
    if lines.next() != Some(header.as_str()) {
        return Err(format!("does not start with the header {header}"));
    }
    let grid = images[0].grid;
    let densities: Vec<Vec<f64>> = images
        .iter()
        .map(|i| i.azimuthal().into_iter().map(channel_mean).collect())
        .collect();
    let mut rows = 0;
    for (j, line) in lines.enumerate() {
        let values: Vec<f64> = line
            .split(',')
            .map(|v| v.trim().parse::<f64>())
            .collect::<Result<_, _>>()
            .map_err(|_| format!("row {} is not numbers: {line:?}", j + 2))?;
        if j >= grid.width || values.len() != 7 {
            return Err(format!(
                "row {} does not fit the {}-column grid",
                j + 2,
                grid.width
            ));
        }
        let want = std::iter::once(grid.phi_center(j)).chain(densities.iter().map(|d| d[j]));
        if !values.iter().zip(want).all(|(v, w)| close(*v, w)) {
            return Err(format!("row {} disagrees with the images", j + 2));
        }
        rows += 1;
    }
    if rows != grid.width {
        return Err(format!(
            "has {rows} rows for a grid of {} columns",
            grid.width
        ));
    }
    Ok(())
}

/// The order to visit `configs` in: grouped by fiber (η, β, α, μ_a: every parameter but θ_i),
/// in the order each fiber first appears, each group in its own order, so that a fiber's models
/// are built once for all its inclinations ([`crate::models::FiberModels`]).
pub fn fiber_order(configs: &[SimConfig]) -> Vec<usize> {
    let fiber = |c: &SimConfig| {
        let p = c.fiber_params();
        [p.eta, p.beta, p.alpha, p.mu_a.x, p.mu_a.y, p.mu_a.z].map(f64::to_bits)
    };
    let mut first_seen: Vec<[u64; 6]> = Vec::new();
    let mut group = |c: &SimConfig| {
        let key = fiber(c);
        first_seen
            .iter()
            .position(|k| *k == key)
            .unwrap_or_else(|| {
                first_seen.push(key);
                first_seen.len() - 1
            })
    };
    let groups: Vec<usize> = configs.iter().map(&mut group).collect();
    let mut order: Vec<usize> = (0..configs.len()).collect();
    order.sort_by_key(|&i| groups[i]);
    order
}

/// The configurations under `root`, sorted by folder name: `root` itself when it holds a
/// `sim.json`, else every subfolder (but the hidden stages of configurations being written),
/// each of which must hold one.
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
        .filter(|p| p.is_dir() && !cuticle_sim::sweep::is_hidden(p))
        .collect();
    dirs.sort();
    if dirs.is_empty() {
        return Err(ValidateError::Empty(root.to_path_buf()));
    }
    dirs.iter().map(|d| SimConfig::read(d)).collect()
}

#[cfg(test)]
mod order_tests {
    use super::*;

    fn config(name: &str, theta_i: f64, beta: f64, mu_a: f64) -> SimConfig {
        SimConfig {
            dir: PathBuf::from(name),
            name: name.to_string(),
            theta_i,
            alpha_deg: -2.0,
            beta,
            eta: 1.55,
            mu_a: [mu_a; 3],
            rays: 1000,
            grid: [8, 4],
            energy: [0.0; 6],
            seed: Some(1),
        }
    }

    /// Folders sort by θ_i first, so one fiber's configurations lie apart; the order groups
    /// them, fibers in order of first appearance and each group in folder order.
    #[test]
    fn fiber_order_groups_the_inclinations_of_each_fiber() {
        let configs = [
            config("ti0.25_b0.04_mu0", 0.25, 0.04, 0.0),
            config("ti0.25_b0.08_mu0", 0.25, 0.08, 0.0),
            config("ti0.25_b0.04_mu0.5", 0.25, 0.04, 0.5),
            config("ti0.75_b0.04_mu0", 0.75, 0.04, 0.0),
            config("ti0.75_b0.08_mu0", 0.75, 0.08, 0.0),
            config("ti1.1_b0.04_mu0", 1.1, 0.04, 0.0),
        ];
        assert_eq!(fiber_order(&configs), [0, 3, 5, 1, 4, 2]);
        assert_eq!(fiber_order(&[]), Vec::<usize>::new());
    }
}
