//! How much memory this process may still take: the least of what the kernel reports
//! available, the cgroup's limit less its use (v2, else v1), and the process's own address-space
//! limit (`RLIMIT_AS`, as `ulimit -v` or `prlimit --as` set it) less the address space it
//! already maps (issue 57 #14: under `prlimit --as=4294967296` a groom of 10 GB aborted in the
//! allocator). Commands (and the Python bindings) compare it with what their work needs
//! ([`crate::scene::memory`]) before allocating, and refuse with a sentence rather than be killed half way.
//! `CUTICLE_MEMORY_LIMIT` (bytes) caps it further.

use crate::scene::memory::Advice;
use crate::scene::{Method, Scene, SceneError, SceneSpec};
use cuticle_light::SrbfLight;
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
    mem.min(cgroup_headroom().unwrap_or(u64::MAX))
        .min(address_space_headroom().unwrap_or(u64::MAX))
        .min(limit)
}

/// `RLIMIT_AS` less the process's mapped address space (`VmSize` of /proc/self/status).
#[cfg(target_os = "linux")]
fn address_space_headroom() -> Option<u64> {
    // SAFETY: getrlimit only writes the struct it is given.
    let mut limit: libc::rlimit = unsafe { std::mem::zeroed() };
    if unsafe { libc::getrlimit(libc::RLIMIT_AS, &mut limit) } != 0
        || limit.rlim_cur == libc::RLIM_INFINITY
    {
        return None;
    }
    let status = fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmSize:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some((limit.rlim_cur as u64).saturating_sub(kb.saturating_mul(1024)))
}

#[cfg(not(target_os = "linux"))]
fn address_space_headroom() -> Option<u64> {
    None
}

/// The scene, loaded once what it needs in memory is known to fit in [`available`] (checked
/// before the groom is made, and again before drawing, with the groom's real size).
/// The path tracer's scene has no SRBF lights (it samples the map itself).
pub fn load_within_memory(
    spec: SceneSpec,
    lights: Option<Vec<SrbfLight>>,
) -> Result<Scene, SceneError> {
    let threads = rayon::current_num_threads();
    spec.validate()?;
    let available = available();
    let path = spec.method == Method::Path;
    let light_count = if path {
        Some(0)
    } else {
        lights.as_ref().map(Vec::len)
    };
    let advice = if path { Advice::PATH } else { Advice::RENDER };
    spec.memory_need(light_count, threads)
        .check_for(available, advice)?;
    let scene = if path {
        Scene::load_without_lights(spec)?
    } else {
        Scene::load(spec, lights)?
    };
    scene.memory_need(threads).check_for(available, advice)?;
    Ok(scene)
}

/// `MemAvailable` of /proc/meminfo.
fn meminfo_available() -> Option<u64> {
    let text = fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb.saturating_mul(1024))
}

/// A cgroup's limit less what the cgroup already uses: v2 (`memory.max`, "max" where there
/// is none), else v1 (`memory/memory.limit_in_bytes`).
fn cgroup_headroom() -> Option<u64> {
    let read = |f: &str| {
        fs::read_to_string(format!("/sys/fs/cgroup/{f}"))
            .ok()
            .and_then(|t| t.trim().parse::<u64>().ok())
    };
    let (max, current) = match (read("memory.max"), read("memory.current")) {
        (Some(max), Some(current)) => (max, current),
        _ => (
            read("memory/memory.limit_in_bytes")?,
            read("memory/memory.usage_in_bytes")?,
        ),
    };
    Some(max.saturating_sub(current))
}
