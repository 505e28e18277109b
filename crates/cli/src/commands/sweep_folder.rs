//! The folder a sweep writes to (issue 57 #7, #8): only a sweep's own, and one run at a time
//! per configuration.
//!
//! 1. [`check_is_sweep`]: the folder may hold only what sweeps write — configuration folders
//!    (`ti…_a…_b…_mu…_eta…`), the records `sweep.json` and `sweep-K-of-N.json`, and hidden
//!    entries (stages, the lock). A render's output or a folder of notes is refused, as
//!    `render` refuses a folder that is not a render's.
//! 2. [`ConfigLocks::take`]: the run locks one byte of the hidden file `.sweep.lock` for each
//!    configuration it owns (the byte at a hash of the configuration's folder name; POSIX
//!    record locks, `fcntl(F_SETLK)`), all before it simulates anything. Two runs that share a
//!    configuration (the same sweep twice, a sweep and one of its shards, two grids that
//!    overlap) cannot both hold it, so the second is refused with one line; the shards of one
//!    sweep own disjoint configurations and run side by side as before. The kernel drops the
//!    locks when the process ends, however it ends, so a killed run never leaves the folder
//!    locked.

use anyhow::{Context, Result, bail};
use cuticle_sim::SweepConfig;
use std::fs::File;
use std::path::Path;

/// The lock file in a sweep's folder.
const LOCK_FILE: &str = ".sweep.lock";

/// Refuses `root` unless everything in it is a sweep's (see the module documentation).
pub fn check_is_sweep(root: &Path) -> Result<()> {
    let entries = std::fs::read_dir(root)
        .with_context(|| format!("cannot read output folder {}", root.display()))?;
    for entry in entries {
        let entry = entry.with_context(|| format!("cannot read {}", root.display()))?;
        let name = entry.file_name().to_string_lossy().into_owned();
        let is_dir = entry.file_type().is_ok_and(|t| t.is_dir());
        let ours = name.starts_with('.')
            || (is_dir && is_config_name(&name))
            || (!is_dir && is_record_name(&name));
        if !ours {
            bail!(
                "{} is not a sweep's folder (it holds {name}); sweep writes to a new or empty \
                 folder, or to a sweep's own",
                root.display()
            );
        }
    }
    Ok(())
}

/// `ti0.75_a-2_b0.04_mu0.25_eta1.55` ([`SweepConfig::dir_name`]).
fn is_config_name(name: &str) -> bool {
    let mut rest = name;
    ["ti", "_a", "_b", "_mu", "_eta"]
        .iter()
        .all(|key| match rest.strip_prefix(key) {
            Some(after) => {
                let end = after.find('_').unwrap_or(after.len());
                rest = &after[end..];
                end > 0
            }
            None => false,
        })
        && rest.is_empty()
}

/// `sweep.json`, `sweep-K-of-N.json`.
fn is_record_name(name: &str) -> bool {
    if name == "sweep.json" {
        return true;
    }
    let Some(middle) = name
        .strip_prefix("sweep-")
        .and_then(|n| n.strip_suffix(".json"))
    else {
        return false;
    };
    let mut parts = middle.split("-of-");
    let number =
        |p: Option<&str>| p.is_some_and(|p| !p.is_empty() && p.bytes().all(|b| b.is_ascii_digit()));
    number(parts.next()) && number(parts.next()) && parts.next().is_none()
}

/// The configurations one run holds; dropping it (or the process ending) releases them.
pub struct ConfigLocks {
    _file: File,
}

impl ConfigLocks {
    /// Locks each of `configs` in `root`, or names the first one another run holds.
    pub fn take<'a>(
        root: &Path,
        configs: impl IntoIterator<Item = &'a SweepConfig>,
    ) -> Result<Self> {
        let path = root.join(LOCK_FILE);
        let file = File::options()
            .create(true)
            .truncate(false)
            .write(true)
            .open(&path)
            .with_context(|| format!("cannot open the sweep's lock {}", path.display()))?;
        for config in configs {
            let name = config.dir_name();
            if !lock_byte(&file, slot(&name))
                .with_context(|| format!("cannot lock {}", path.display()))?
            {
                bail!(
                    "another sweep is running in {} (it holds configuration {name}); wait for \
                     it to end, or write to another folder",
                    root.display()
                );
            }
        }
        Ok(Self { _file: file })
    }
}

/// The byte of the lock file that stands for configuration `name` (FNV-1a, within the
/// offsets every file system takes).
fn slot(name: &str) -> u64 {
    let hash = name.bytes().fold(0xcbf2_9ce4_8422_2325u64, |h, b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    });
    hash % (1 << 40)
}

/// Takes a write lock on byte `at` of `file` without waiting: `Ok(false)` when another process
/// holds it.
#[cfg(target_os = "linux")]
fn lock_byte(file: &File, at: u64) -> std::io::Result<bool> {
    use std::os::fd::AsRawFd;
    // SAFETY: a plain-old-data struct, zeroed, then the fields F_SETLK reads are set.
    let mut lock: libc::flock = unsafe { std::mem::zeroed() };
    lock.l_type = libc::F_WRLCK as libc::c_short;
    lock.l_whence = libc::SEEK_SET as libc::c_short;
    lock.l_start = at as libc::off_t;
    lock.l_len = 1;
    // SAFETY: the descriptor is open for the call's duration and `lock` is a valid flock.
    if unsafe { libc::fcntl(file.as_raw_fd(), libc::F_SETLK, &lock) } == 0 {
        return Ok(true);
    }
    let err = std::io::Error::last_os_error();
    match err.raw_os_error() {
        Some(libc::EACCES) | Some(libc::EAGAIN) => Ok(false),
        _ => Err(err),
    }
}

/// Elsewhere there is no lock: concurrent sweeps into one folder are the user's to avoid.
#[cfg(not(target_os = "linux"))]
fn lock_byte(_: &File, _: u64) -> std::io::Result<bool> {
    Ok(true)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_of_sweeps_are_recognised() {
        for name in [
            "ti0.75_a-2_b0.04_mu0.25_eta1.55",
            "ti-1.2_a0_b1e-4_mu0.1-0.2-0.3_eta1.55",
        ] {
            assert!(is_config_name(name), "{name}");
        }
        for name in [
            "notes",
            "ti_a_b_mu_eta",
            "ti1_a2_b3_mu4",
            "ti1_a2_b3_mu4_eta5_x",
        ] {
            assert!(!is_config_name(name), "{name}");
        }
        assert!(is_record_name("sweep.json") && is_record_name("sweep-2-of-8.json"));
        for name in [
            "render.json",
            "sweep-x-of-2.json",
            "sweep-1-of-.json",
            "sweep-1-of-2-of-3.json",
        ] {
            assert!(!is_record_name(name), "{name}");
        }
    }
}
