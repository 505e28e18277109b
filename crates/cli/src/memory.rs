//! How much memory this process may still take: what the kernel reports available, within the
//! cgroup's limit when there is one. Commands compare it with what their work needs
//! (`cuticle_render::scene::memory`) before allocating, and refuse with a sentence rather than
//! be killed half way. `CUTICLE_MEMORY_LIMIT` (bytes) caps it further.

use std::fs;

/// Caps what [`available`] reports, in bytes: to share a machine, and for tests that must
/// not depend on the machine's size.
pub const LIMIT_VAR: &str = "CUTICLE_MEMORY_LIMIT";

/// Bytes available to this process; `u64::MAX` where the system does not say.
pub fn available() -> u64 {
    let mem = meminfo_available().unwrap_or(u64::MAX);
    let limit = std::env::var(LIMIT_VAR)
        .ok()
        .and_then(|v| v.trim().parse::<u64>().ok())
        .unwrap_or(u64::MAX);
    mem.min(cgroup_headroom().unwrap_or(u64::MAX)).min(limit)
}

/// `MemAvailable` of /proc/meminfo.
fn meminfo_available() -> Option<u64> {
    let text = fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb.saturating_mul(1024))
}

/// A cgroup v2 limit less what the cgroup already uses.
fn cgroup_headroom() -> Option<u64> {
    let read = |f: &str| fs::read_to_string(format!("/sys/fs/cgroup/{f}")).ok();
    let max: u64 = read("memory.max")?.trim().parse().ok()?;
    let current: u64 = read("memory.current")?.trim().parse().ok()?;
    Some(max.saturating_sub(current))
}
