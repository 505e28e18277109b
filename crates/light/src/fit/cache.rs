//! Fits kept on disk. A fit is a function of the map's pixels, its rotation and the
//! [`FitOptions`] alone, and costs seconds, while reading it back costs a millisecond: a render
//! of a map fitted before (the default sky every time) reads its lights from the cache folder.
//!
//! - Where: `$CUTICLE_CACHE_DIR`, else `$XDG_CACHE_HOME/cuticle`, else `$HOME/.cache/cuticle`;
//!   `CUTICLE_CACHE_DIR=off` (or an empty value) turns the cache off. Entries live in `fits/`,
//!   one JSON file per key.
//! - Key: a 128-bit digest of a format version, the map's size, rotation and pixel bits, and the
//!   options' every field ([`key`]). A map edited in place gets a new key; nothing goes stale.
//! - A cache never fails a command: an entry that cannot be read, parsed or that holds lights
//!   [`validate_lights`](crate::validate_lights) refuses is fitted anew and rewritten; an entry
//!   that cannot be written (read-only or full disk) is skipped. Writes are atomic (temp file,
//!   then rename), so concurrent renders of one map each read a whole entry or none.

use super::{FitOptions, FitReport, fit_srbf_with_progress};
use crate::{EnvMap, FitProgress, LightError, validate_lights};
use serde::{Deserialize, Serialize};
use std::hash::{Hash, Hasher};
use std::path::{Path, PathBuf};

/// Bumped whenever the fit's algorithm or the report's fields change, so old entries miss.
const FORMAT: u32 = 1;

/// Entries larger than this are not read (a fit of [`crate::MAX_LIGHTS`] lights is a few
/// hundred kilobytes at most).
const MAX_ENTRY_BYTES: u64 = 16 << 20;

/// Where a fit came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum FitSource {
    /// Fitted now (and stored, where the cache is on and writable).
    Fitted,
    /// Read back from the cache folder.
    Cached,
}

/// The cache folder of fits.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FitCache {
    dir: PathBuf,
}

/// One stored fit, with its key, so that a renamed or copied entry is not taken for another.
#[derive(Serialize, Deserialize)]
struct Entry {
    format: u32,
    key: String,
    report: FitReport,
}

impl FitCache {
    /// A cache in `dir` (its `fits/` subfolder is made on the first write).
    pub fn at(dir: impl Into<PathBuf>) -> Self {
        Self { dir: dir.into() }
    }

    /// The cache the environment names (module documentation), or `None` when it is off or no
    /// folder can be named.
    pub fn from_env() -> Option<Self> {
        let var = |name: &str| std::env::var_os(name).filter(|v| !v.is_empty());
        match std::env::var_os("CUTICLE_CACHE_DIR") {
            Some(v) if v.is_empty() || v == "off" => None,
            Some(v) => Some(Self::at(v)),
            None => var("XDG_CACHE_HOME")
                .map(|d| Path::new(&d).join("cuticle"))
                .or_else(|| var("HOME").map(|h| Path::new(&h).join(".cache").join("cuticle")))
                .map(Self::at),
        }
    }

    fn path(&self, key: &str) -> PathBuf {
        self.dir.join("fits").join(format!("{key}.json"))
    }

    /// The stored fit of `key`, if a whole, valid one is there.
    pub fn get(&self, key: &str) -> Option<FitReport> {
        let path = self.path(key);
        let meta = std::fs::metadata(&path).ok()?;
        if !meta.is_file() || meta.len() > MAX_ENTRY_BYTES {
            return None;
        }
        let entry: Entry = serde_json::from_slice(&std::fs::read(&path).ok()?).ok()?;
        let valid = entry.format == FORMAT
            && entry.key == key
            && validate_lights(&entry.report.lights).is_ok()
            && entry.report.relative_l2.is_finite();
        valid.then_some(entry.report)
    }

    /// Stores `report` under `key`; a failure (read-only folder, full disk) only skips it.
    pub fn put(&self, key: &str, report: &FitReport) {
        let _ = self.try_put(key, report);
    }

    fn try_put(&self, key: &str, report: &FitReport) -> std::io::Result<()> {
        let path = self.path(key);
        let dir = path.parent().expect("an entry lies in fits/");
        std::fs::create_dir_all(dir)?;
        let entry = Entry {
            format: FORMAT,
            key: key.to_owned(),
            report: report.clone(),
        };
        let bytes = serde_json::to_vec(&entry).map_err(std::io::Error::other)?;
        // Unique per process and per write, so that two threads storing one key never share
        // a temporary file.
        static WRITES: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
        let n = WRITES.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let temp = dir.join(format!(".{key}.{}.{n}.tmp", std::process::id()));
        let written = std::fs::write(&temp, bytes).and_then(|()| std::fs::rename(&temp, &path));
        if written.is_err() {
            let _ = std::fs::remove_file(&temp);
        }
        written
    }
}

/// The cache key of fitting `map` with `options`: two 64-bit SipHash digests (fixed keys, two
/// seeds) of everything the fit reads, in hexadecimal.
pub fn key(map: &EnvMap, options: &FitOptions) -> String {
    let digest = |seed: u64| {
        #[allow(deprecated)] // SipHasher: std's stable-keyed SipHash-2-4, exactly what a key needs.
        let mut h = std::hash::SipHasher::new_with_keys(seed, !seed);
        FORMAT.hash(&mut h);
        (map.width(), map.height()).hash(&mut h);
        map.rotation().to_bits().hash(&mut h);
        for p in map.pixels() {
            p.to_array().map(f32::to_bits).hash(&mut h);
        }
        serde_json::to_string(options)
            .expect("options serialise")
            .hash(&mut h);
        h.finish()
    };
    format!(
        "{:016x}{:016x}",
        digest(0x6375_7469_636c_6531),
        digest(0x7372_6266_2d66_6974)
    )
}

/// [`fit_srbf_with_progress`] through `cache`: the stored fit when there is one, else a new fit,
/// stored. With no cache, always a new fit.
pub fn fit_srbf_cached(
    map: &EnvMap,
    options: &FitOptions,
    cache: Option<&FitCache>,
    progress: &mut dyn FnMut(FitProgress),
) -> Result<(FitReport, FitSource), LightError> {
    let Some(cache) = cache else {
        return Ok((
            fit_srbf_with_progress(map, options, progress)?,
            FitSource::Fitted,
        ));
    };
    let key = key(map, options);
    if let Some(report) = cache.get(&key) {
        return Ok((report, FitSource::Cached));
    }
    let report = fit_srbf_with_progress(map, options, progress)?;
    cache.put(&key, &report);
    Ok((report, FitSource::Fitted))
}
