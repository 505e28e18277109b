//! Running a sweep: each configuration in its own folder under the sweep root, complete exactly
//! when its `sim.json` exists. The writer puts a configuration's whole set in place at once
//! (the command line stages it beside the folder), so a killed run loses only the configuration
//! in flight; a resumed run skips complete ones, redoes (from an emptied folder) any that was
//! cut short, and refuses a folder whose complete configurations were made with other
//! settings (rays, seed, grid), rather than mixing two runs in one sweep.

use crate::grid::SweepConfig;
use crate::params::SimError;
use crate::shard::Shard;
use crate::simulate::{SimResult, simulate};
use cuticle_fiber::LatLongGrid;
use std::collections::HashSet;
use std::fs;
use std::path::{Path, PathBuf};
use std::time::Instant;
use thiserror::Error;

/// The file whose presence marks a configuration complete.
pub const RECORD: &str = "sim.json";

#[derive(Debug, Error)]
pub enum SweepError {
    #[error(transparent)]
    Sim(#[from] SimError),
    #[error("{path}: {source}")]
    Io {
        path: PathBuf,
        source: std::io::Error,
    },
    #[error("writing configuration {path}: {message}")]
    Images { path: PathBuf, message: String },
    #[error("two configurations share the folder name {0}")]
    Duplicate(String),
    #[error(
        "{path} was made with {what}; resume with the settings it was made with, or write to \
         another folder"
    )]
    OtherSettings { path: PathBuf, what: String },
    #[error("{path}: {message}")]
    BadRecord { path: PathBuf, message: String },
}

fn io_err(path: &Path) -> impl FnOnce(std::io::Error) -> SweepError + '_ {
    move |source| SweepError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// Writes a configuration's whole set into its folder: the images and, last, `sim.json`
/// ([`crate::sim_json`]), so that the folder holds `sim.json` only once everything else is there
/// (the CLI's staged EXR/PNG writer, or a test's).
pub type ConfigWriter<'a> = &'a (dyn Fn(&Path, &SimResult) -> Result<(), String> + Sync);

/// A sweep: the configurations this shard owns, where they go, and the settings they share.
pub struct Sweep {
    /// (index in the whole sweep, configuration), for this shard only.
    pub configs: Vec<(usize, SweepConfig)>,
    pub root: PathBuf,
    pub rays: u64,
    pub seed: u64,
    pub grid: LatLongGrid,
}

/// What a call to [`Sweep::run`] did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SweepSummary {
    /// Configurations of this shard.
    pub total: usize,
    /// Found complete on disk and skipped.
    pub skipped: usize,
    /// Simulated and written by this call.
    pub ran: usize,
    /// Left to do when the call stopped.
    pub remaining: usize,
    pub seconds: f64,
    /// Paths traced by this call.
    pub rays: u64,
}

impl Sweep {
    /// The part of `all` that `shard` owns; fails if two configurations would share a folder.
    pub fn new(
        all: &[SweepConfig],
        shard: Shard,
        root: &Path,
        rays: u64,
        seed: u64,
        grid: LatLongGrid,
    ) -> Result<Self, SweepError> {
        let mut seen = HashSet::new();
        for c in all {
            if !seen.insert(c.dir_name()) {
                return Err(SweepError::Duplicate(c.dir_name()));
            }
            c.params(rays, seed, grid).validate()?;
        }
        let configs = all
            .iter()
            .cloned()
            .enumerate()
            .filter(|(i, _)| shard.contains(*i))
            .collect();
        Ok(Self {
            configs,
            root: root.to_path_buf(),
            rays,
            seed,
            grid,
        })
    }

    pub fn dir(&self, config: &SweepConfig) -> PathBuf {
        self.root.join(config.dir_name())
    }

    pub fn is_complete(&self, config: &SweepConfig) -> bool {
        self.dir(config).join(RECORD).is_file()
    }

    /// Checks that every complete configuration of this shard was made with this sweep's rays,
    /// seed and grid, and is the configuration its folder name says: a resumed sweep never
    /// mixes configurations of two settings.
    pub fn check_settings(&self) -> Result<(), SweepError> {
        for (_, config) in &self.configs {
            if self.is_complete(config) {
                self.check_record(config)?;
            }
        }
        Ok(())
    }

    fn check_record(&self, config: &SweepConfig) -> Result<(), SweepError> {
        let path = self.dir(config).join(RECORD);
        let text = fs::read_to_string(&path).map_err(io_err(&path))?;
        let bad = |message: String| SweepError::BadRecord {
            path: path.clone(),
            message,
        };
        let value: serde_json::Value =
            serde_json::from_str(&text).map_err(|e| bad(format!("not JSON: {e}")))?;
        let made = config_of_record(&text).map_err(|e| bad(e.to_string()))?;
        let p = &value["params"];
        let grid = [self.grid.width, self.grid.height];
        let differences = [
            (p["rays"].as_u64() != Some(self.rays))
                .then(|| format!("rays {} (this run: {})", p["rays"], self.rays)),
            (p["seed"].as_u64() != Some(self.seed))
                .then(|| format!("seed {} (this run: {})", p["seed"], self.seed)),
            (p["grid"] != serde_json::json!(grid))
                .then(|| format!("grid {} (this run: {grid:?})", p["grid"])),
            (!same_config(&made, config))
                .then(|| format!("parameters {made:?} (this run: {config:?})")),
        ];
        match differences.into_iter().flatten().next() {
            Some(what) => Err(SweepError::OtherSettings { path, what }),
            None => Ok(()),
        }
    }

    /// Configurations of this shard already complete on disk.
    pub fn complete_count(&self) -> usize {
        self.configs
            .iter()
            .filter(|(_, c)| self.is_complete(c))
            .count()
    }

    /// Simulates every incomplete configuration in order, asking `stop()` before each one (a
    /// cancel flag, a limit) and calling `on_done` after each is on disk.
    pub fn run(
        &self,
        write: ConfigWriter,
        stop: &dyn Fn() -> bool,
        on_done: &mut dyn FnMut(&SweepConfig, &SimResult),
    ) -> Result<SweepSummary, SweepError> {
        self.check_settings()?;
        let start = Instant::now();
        let todo: Vec<&SweepConfig> = self
            .configs
            .iter()
            .map(|(_, c)| c)
            .filter(|c| !self.is_complete(c))
            .collect();
        let mut summary = SweepSummary {
            total: self.configs.len(),
            skipped: self.configs.len() - todo.len(),
            remaining: todo.len(),
            ..Default::default()
        };
        for config in todo {
            if stop() {
                break;
            }
            let result = self.run_one(config, write)?;
            summary.ran += 1;
            summary.remaining -= 1;
            summary.rays += result.rays;
            on_done(config, &result);
        }
        summary.seconds = start.elapsed().as_secs_f64();
        Ok(summary)
    }

    /// Simulates one configuration and has `write` put its set in place of an incomplete
    /// folder (one a killed run left without `sim.json`, removed first).
    pub fn run_one(
        &self,
        config: &SweepConfig,
        write: ConfigWriter,
    ) -> Result<SimResult, SweepError> {
        let dir = self.dir(config);
        if dir.exists() && !self.is_complete(config) {
            fs::remove_dir_all(&dir).map_err(io_err(&dir))?;
        }
        let result = simulate(&config.params(self.rays, self.seed, self.grid), &|_, _| {})?;
        write(&dir, &result).map_err(|message| SweepError::Images {
            path: dir.clone(),
            message,
        })?;
        Ok(result)
    }
}

/// Every complete configuration under `root`, read back from the `"params"` of its `sim.json`
/// (for tools that consume a sweep, such as validation), sorted by folder name.
pub fn list_complete(root: &Path) -> Result<Vec<(SweepConfig, PathBuf)>, SweepError> {
    let mut out = Vec::new();
    for entry in fs::read_dir(root).map_err(io_err(root))? {
        let dir = entry.map_err(io_err(root))?.path();
        if is_hidden(&dir) {
            continue;
        }
        let record = dir.join(RECORD);
        if !record.is_file() {
            continue;
        }
        let text = fs::read_to_string(&record).map_err(io_err(&record))?;
        let config = config_of_record(&text)
            .map_err(|e| SimError::InvalidParam(format!("{}: {e}", record.display())))?;
        out.push((config, dir));
    }
    out.sort_by(|a, b| a.1.cmp(&b.1));
    Ok(out)
}

/// A hidden entry (`.NAME…`): a stage of a configuration being written, never one itself.
pub fn is_hidden(path: &Path) -> bool {
    path.file_name()
        .is_some_and(|n| n.to_string_lossy().starts_with('.'))
}

/// Equal up to the rounding of α's trip through radians in `sim.json`.
fn same_config(a: &SweepConfig, b: &SweepConfig) -> bool {
    let close = |x: f64, y: f64| (x - y).abs() <= 1e-12 * x.abs().max(y.abs()).max(1.0);
    close(a.theta_i, b.theta_i)
        && close(a.alpha_deg, b.alpha_deg)
        && close(a.beta, b.beta)
        && close(a.eta, b.eta)
        && a.mu_a.iter().zip(&b.mu_a).all(|(x, y)| close(*x, *y))
}

fn config_of_record(text: &str) -> Result<SweepConfig, serde_json::Error> {
    let v: serde_json::Value = serde_json::from_str(text)?;
    let p = &v["params"];
    let field = |k: &str| serde_json::from_value::<f64>(p[k].clone());
    Ok(SweepConfig {
        theta_i: field("theta_i")?,
        alpha_deg: field("alpha_deg")?,
        beta: field("beta")?,
        eta: field("eta")?,
        mu_a: serde_json::from_value(p["mu_a"].clone())?,
    })
}
