//! What stands between a hostile file and the USD library: every layer the stage opens passes
//! through [`GuardedResolver`], which refuses anything but a regular file of at most
//! [`MAX_LAYER_BYTES`], and checks a `.usdc` layer's structure ([`check_crate`]), and each
//! layer inside a `.usdz` package ([`check_layer`]), before the library reads it: the library allocates whatever counts a file declares, so a 1 KB file that
//! claims 2³¹ points would exhaust memory. Whatever the library still panics on is caught
//! ([`catch_quietly`]) and becomes one error line.
//!
//! Not checked: the lengths inside time samples and inside values nested in dictionaries or
//! references, which the library decodes itself; a crafted one may still make it allocate what
//! it declares (found so far by flipping every byte of the fixtures: nothing). A text layer's
//! memory is bounded by its size ([`MAX_LAYER_BYTES`]) times the parser's overhead.

use super::error::UsdError;
use openusd::ar::{self, Asset, DefaultResolver, ResolvedPath, Resolver};
use std::cell::Cell;
use std::io::{self, Cursor};
use std::sync::Once;

/// Largest layer read: ample for a groom of millions of points in text.
pub const MAX_LAYER_BYTES: u64 = 1 << 30;
/// Largest count a `.usdc` structural section (tokens, fields, paths, specs) may declare.
const MAX_STRUCTURE: u64 = 1 << 22;
/// Largest number of elements a compressed `.usdc` array may declare: 2²⁸, the most points a
/// `.hair` file holds.
const MAX_COMPRESSED_ELEMENTS: u64 = 1 << 28;
/// Most elements all arrays of one `.usdc` layer may declare together.
const MAX_TOTAL_ELEMENTS: u64 = 1 << 29;

/// The filesystem resolver, with every opened layer checked first.
pub struct GuardedResolver(DefaultResolver);

impl Default for GuardedResolver {
    fn default() -> Self {
        Self(DefaultResolver::new())
    }
}

impl Resolver for GuardedResolver {
    fn create_identifier(&self, asset_path: &str, anchor: Option<&ResolvedPath>) -> String {
        self.0.create_identifier(asset_path, anchor)
    }

    fn resolve(&self, asset_path: &str) -> Option<ResolvedPath> {
        self.0.resolve(asset_path)
    }

    fn resolve_for_new_asset(&self, asset_path: &str) -> Option<ResolvedPath> {
        self.0.resolve_for_new_asset(asset_path)
    }

    fn open_asset(&self, resolved_path: &ResolvedPath) -> io::Result<Box<dyn Asset>> {
        let path = std::path::Path::new(resolved_path.as_os_str());
        if !ar::is_package_relative_path(&resolved_path.to_string_lossy()) {
            let len = crate::hair_file::read::regular_file_len(path)?;
            if len > MAX_LAYER_BYTES {
                return Err(io::Error::other(format!(
                    "{} is {len} bytes, more than the {MAX_LAYER_BYTES} a groom's layer may be",
                    path.display()
                )));
            }
        }
        let mut asset = self.0.open_asset(resolved_path)?;
        let size = asset.size()?;
        if size > MAX_LAYER_BYTES {
            return Err(io::Error::other(format!(
                "a layer of {size} bytes is more than the {MAX_LAYER_BYTES} a groom's layer may be"
            )));
        }
        let bytes = asset.read_all()?;
        check_layer(&bytes).map_err(io::Error::other)?;
        Ok(Box::new(Cursor::new(bytes)))
    }

    fn identity(&self) -> String {
        "cuticle-guarded".into()
    }
}

/// A layer's bytes checked before the library reads them: a `.usdc` by [`check_crate`], a
/// `.usdz` package entry by entry (the library reads its first layer from the zip without the
/// resolver), text as it is (its arrays are as long as its text).
pub fn check_layer(bytes: &[u8]) -> Result<(), String> {
    if bytes.starts_with(openusd::usdc::MAGIC) {
        return check_crate(bytes).map_err(|e| format!("a broken .usdc: {e}"));
    }
    if bytes.starts_with(b"PK\x03\x04") {
        return check_package(bytes).map_err(|e| format!("a broken .usdz: {e}"));
    }
    Ok(())
}

/// Each entry of a `.usdz` (zip) package: no larger than a layer may be, and checked itself.
fn check_package(bytes: &[u8]) -> Result<(), String> {
    use std::io::Read;
    let mut zip = zip::ZipArchive::new(Cursor::new(bytes)).map_err(|e| e.to_string())?;
    for i in 0..zip.len() {
        let entry = zip.by_index(i).map_err(|e| e.to_string())?;
        let name = entry.name().to_string();
        if entry.size() > MAX_LAYER_BYTES {
            return Err(format!("{name} is {} bytes unpacked", entry.size()));
        }
        let mut inner = Vec::new();
        entry
            .take(MAX_LAYER_BYTES + 1)
            .read_to_end(&mut inner)
            .map_err(|e| format!("{name}: {e}"))?;
        if inner.len() as u64 > MAX_LAYER_BYTES {
            return Err(format!(
                "{name} unpacks to more than {MAX_LAYER_BYTES} bytes"
            ));
        }
        check_layer(&inner).map_err(|e| format!("{name}: {e}"))?;
    }
    Ok(())
}

/// A `.usdc` file's structure checked against its size before the library reads it: the
/// version, the table of contents, each section's counts, and then every array value's
/// declared length (Pixar's crate format: an 88-byte bootstrap, a table of sections, and
/// values addressed by 64-bit `ValueRep`s whose top bits say array / inlined / compressed).
pub fn check_crate(bytes: &[u8]) -> Result<(), String> {
    let len = bytes.len() as u64;
    let version = (at(bytes, 8, 1)?, at(bytes, 9, 1)?, at(bytes, 10, 1)?);
    if !((0, 4, 0)..=(0, 12, 0)).contains(&version) {
        return Err(format!(
            "its version is {}.{}.{}; versions 0.4.0 to 0.12.0 are read",
            version.0, version.1, version.2
        ));
    }
    let toc = at(bytes, 16, 8)?;
    let sections = at(bytes, toc, 8)?;
    if sections == 0 || sections > 64 {
        return Err(format!("its table of contents lists {sections} sections"));
    }
    for i in 0..sections {
        let entry = toc + 8 + i * 32;
        let (start, size) = (at(bytes, entry + 16, 8)?, at(bytes, entry + 24, 8)?);
        if start.checked_add(size).is_none_or(|end| end > len) || size < 8 {
            return Err(format!("section {i} lies outside the file"));
        }
        let name = &bytes[entry as usize..entry as usize + 16];
        check_section_counts(bytes, name, start, size)?;
    }
    let file = catch_quietly(|| {
        openusd::usdc::CrateFile::open(Cursor::new(bytes)).map_err(|e| format!("{e:#}"))
    })
    .map_err(|e| e.to_string())??;
    file.validate().map_err(|e| format!("{e:#}"))?;
    let mut total = 0u64;
    for field in &file.fields {
        total = total.saturating_add(check_value(bytes, field.value_rep.0, version)?);
    }
    if total > MAX_TOTAL_ELEMENTS {
        return Err(format!(
            "its arrays declare {total} entries together, more than {MAX_TOTAL_ELEMENTS}"
        ));
    }
    Ok(())
}

/// One value's declared lengths against the bytes after it; returns the elements it declares.
/// Arrays, the vector types (tokens, paths, strings, doubles, layer offsets), list ops and
/// dictionaries are checked; time samples and nested values are left to the library.
fn check_value(bytes: &[u8], rep: u64, version: (u64, u64, u64)) -> Result<u64, String> {
    // Before 0.5.0 an array starts with a u32 shape; before 0.7.0 its count is a u32.
    let shape = if version < (0, 5, 0) { 4 } else { 0 };
    let count_bytes = if version >= (0, 7, 0) { 8 } else { 4 };
    let (array, inlined, compressed) = (rep >> 63 == 1, rep >> 62 & 1 == 1, rep >> 61 & 1 == 1);
    if inlined {
        return Ok(0);
    }
    let offset = rep & ((1 << 48) - 1);
    let ty = ((rep >> 48) & 0xff) as u8;
    if array {
        let count = at(bytes, offset + shape, count_bytes)?;
        let room = room(bytes, offset + shape + count_bytes, element_bytes(ty));
        if (compressed && count > MAX_COMPRESSED_ELEMENTS) || (!compressed && count > room) {
            return Err(declares(offset, count));
        }
        return Ok(count);
    }
    let item = match ty {
        40 | 41 | 50 => 4, // path, token, string vectors: u32 indices
        48 | 31 | 45 => 8, // doubles; dictionary, variant map entries
        49 => 16,          // layer offsets
        32..=39 | 55 => return check_list_op(bytes, offset, ty),
        _ => return Ok(0),
    };
    let count = at(bytes, offset, 8)?;
    if count > room(bytes, offset + 8, item) {
        return Err(declares(offset, count));
    }
    Ok(count)
}

/// A list op: a header byte, then each present list as a count and its items (token, string,
/// path, int and uint lists: 4 bytes an item; 64-bit ones: 8; references and payloads: at
/// least 8, and only their first list is checked, as their items vary in size).
fn check_list_op(bytes: &[u8], offset: u64, ty: u8) -> Result<u64, String> {
    let header = at(bytes, offset, 1)?;
    let (item, sized) = match ty {
        37 | 39 => (8, true),
        35 | 55 => (8, false),
        _ => (4, true),
    };
    let mut at_byte = offset + 1;
    let mut total = 0u64;
    // openusd's order: explicit, added, prepended, appended, deleted, ordered.
    for bit in [1, 2, 5, 6, 3, 4] {
        if header & (1 << bit) == 0 {
            continue;
        }
        let count = at(bytes, at_byte, 8)?;
        if count > room(bytes, at_byte + 8, item) {
            return Err(declares(at_byte, count));
        }
        total += count;
        if !sized {
            break;
        }
        at_byte += 8 + count * item;
    }
    Ok(total)
}

/// Elements of `size` bytes that fit between `from` and the end of the file.
fn room(bytes: &[u8], from: u64, size: u64) -> u64 {
    (bytes.len() as u64).saturating_sub(from) / size
}

fn declares(offset: u64, count: u64) -> String {
    format!("a value at byte {offset} declares {count} entries, more than the file holds")
}

/// A structural section's counts, each bounded, and its compressed blocks (each a u64 size
/// and that many bytes), each inside the section: TOKENS is a count, its text's size and one
/// block; FIELDS a count and two blocks; FIELDSETS a count and one; PATHS two counts and three;
/// SPECS a count and three.
fn check_section_counts(bytes: &[u8], name: &[u8], start: u64, size: u64) -> Result<(), String> {
    let name = String::from_utf8_lossy(name.split(|b| *b == 0).next().unwrap_or_default());
    let (counts, blocks) = match name.as_ref() {
        "TOKENS" => (2, 1),
        "FIELDS" => (1, 2),
        "FIELDSETS" => (1, 1),
        "PATHS" => (2, 3),
        "SPECS" => (1, 3),
        "STRINGS" => (1, 0),
        _ => (0, 0),
    };
    let end = start + size;
    for k in 0..counts {
        let count = at(bytes, start + 8 * k, 8)?;
        if count > MAX_STRUCTURE {
            return Err(format!(
                "its {name} section declares {count} entries, more than {MAX_STRUCTURE}"
            ));
        }
    }
    let mut block = start + 8 * counts;
    for _ in 0..blocks {
        let len = at(bytes, block, 8)?;
        match block.checked_add(8).and_then(|b| b.checked_add(len)) {
            Some(next) if next <= end => block = next,
            _ => return Err(format!("its {name} section's data runs past its end")),
        }
    }
    Ok(())
}

/// Bytes of one element of a crate value type (`Usd_CrateFile` type enum), at least 1: a
/// lower bound, so that an array's declared length is compared with the room it needs.
fn element_bytes(ty: u8) -> u64 {
    match ty {
        3 | 4 | 8 | 10 | 11 | 12 => 4, // int, uint, float, string, token, asset path
        5 | 6 | 9 => 8,                // int64, uint64, double
        7 => 2,                        // half
        13 => 32,                      // matrix2d
        14 => 72,                      // matrix3d
        15 => 128,                     // matrix4d
        16 => 32,                      // quatd
        17 => 16,                      // quatf
        18 => 8,                       // quath
        19 => 16,                      // vec2d
        20 | 22 => 8,                  // vec2f, vec2i
        21 => 4,                       // vec2h
        23 => 24,                      // vec3d
        24 | 26 => 12,                 // vec3f, vec3i
        25 => 6,                       // vec3h
        27 => 32,                      // vec4d
        28 | 30 => 16,                 // vec4f, vec4i
        29 => 8,                       // vec4h
        _ => 1,
    }
}

/// The little-endian unsigned integer of `n` bytes at `offset`.
fn at(bytes: &[u8], offset: u64, n: u64) -> Result<u64, String> {
    let range = usize::try_from(offset)
        .ok()
        .and_then(|o| Some(o..o.checked_add(n as usize)?))
        .filter(|r| r.end <= bytes.len())
        .ok_or_else(|| format!("it ends before byte {}", offset.saturating_add(n)))?;
    Ok(bytes[range]
        .iter()
        .rev()
        .fold(0u64, |v, b| (v << 8) | u64::from(*b)))
}

thread_local! {
    static QUIET: Cell<bool> = const { Cell::new(false) };
}

/// Runs `f`, turning a panic into [`UsdError::Panicked`] without printing it: the panic hook
/// stays silent for this thread while `f` runs and forwards every other panic as before.
pub fn catch_quietly<T>(f: impl FnOnce() -> T) -> Result<T, UsdError> {
    static HOOK: Once = Once::new();
    HOOK.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if !QUIET.with(Cell::get) {
                previous(info);
            }
        }));
    });
    let was = QUIET.with(|q| q.replace(true));
    let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(f));
    QUIET.with(|q| q.set(was));
    result.map_err(|payload| {
        let message = payload
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "a panic".into());
        UsdError::Panicked(message.lines().next().unwrap_or_default().to_string())
    })
}
