//! Running a sweep: each configuration in its own folder under the sweep root, complete exactly
//! when its `sim.json` exists. Images are written first and `sim.json` last, each atomically, so
//! a killed run loses only the configuration in flight, and a resumed run skips complete ones
//! and redoes (from an emptied folder) any that was cut short.

use crate::atomic::write_atomic;
use crate::grid::SweepConfig;
use crate::params::SimError;
use crate::record::sim_json;
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
    #[error("writing images into {path}: {message}")]
    Images { path: PathBuf, message: String },
    #[error("two configurations share the folder name {0}")]
    Duplicate(String),
}

fn io_err(path: &Path) -> impl FnOnce(std::io::Error) -> SweepError + '_ {
    move |source| SweepError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// Writes a result's images into a configuration folder (the CLI's EXR/PNG writer, or a test's).
pub type ImageWriter<'a> = &'a (dyn Fn(&Path, &SimResult) -> Result<(), String> + Sync);

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
        write_images: ImageWriter,
        stop: &dyn Fn() -> bool,
        on_done: &mut dyn FnMut(&SweepConfig, &SimResult),
    ) -> Result<SweepSummary, SweepError> {
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
            let result = self.run_one(config, write_images)?;
            summary.ran += 1;
            summary.remaining -= 1;
            summary.rays += result.rays;
            on_done(config, &result);
        }
        summary.seconds = start.elapsed().as_secs_f64();
        Ok(summary)
    }

    /// Simulates one configuration into an emptied folder: images first, `sim.json` last.
    pub fn run_one(
        &self,
        config: &SweepConfig,
        write_images: ImageWriter,
    ) -> Result<SimResult, SweepError> {
        let dir = self.dir(config);
        if dir.exists() {
            fs::remove_dir_all(&dir).map_err(io_err(&dir))?;
        }
        fs::create_dir_all(&dir).map_err(io_err(&dir))?;
        let result = simulate(&config.params(self.rays, self.seed, self.grid), &|_, _| {})?;
        write_images(&dir, &result).map_err(|message| SweepError::Images {
            path: dir.clone(),
            message,
        })?;
        let record = dir.join(RECORD);
        let mut text = serde_json::to_string_pretty(&sim_json(&result)).expect("JSON of numbers");
        text.push('\n');
        write_atomic(&record, text.as_bytes()).map_err(io_err(&record))?;
        Ok(result)
    }
}

/// Every complete configuration under `root`, read back from the `"params"` of its `sim.json`
/// (for tools that consume a sweep, such as validation), sorted by folder name.
pub fn list_complete(root: &Path) -> Result<Vec<(SweepConfig, PathBuf)>, SweepError> {
    let mut out = Vec::new();
    for entry in fs::read_dir(root).map_err(io_err(root))? {
        let dir = entry.map_err(io_err(root))?.path();
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
