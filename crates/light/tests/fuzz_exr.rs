//! A short deterministic fuzz run of the OpenEXR reader (issue 57 #1): thousands of mutated
//! files of every compression the `exr` crate writes (bit flips, truncations, 64-bit counters set
//! to huge values, garbage tails). None may panic, abort or allocate more than the bound the
//! reader promises; a crafted DWAA chunk once made it ask for 64 TiB. The long run is
//! `cargo fuzz run exr_reader` (fuzz/fuzz_targets/exr_reader.rs).

use cuticle_light::image_file::{MAX_DECODE_BYTES, rgb_exr_from_bytes};
use exr::prelude::*;
use std::alloc::{GlobalAlloc, Layout, System};
use std::path::Path;
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

/// The system allocator, noting the largest single request of any thread (the reader decodes
/// chunks on rayon's threads). The tests take [`ONE_AT_A_TIME`] so that the figure is theirs.
struct Tracking;

static LARGEST: AtomicUsize = AtomicUsize::new(0);
static ONE_AT_A_TIME: Mutex<()> = Mutex::new(());

unsafe impl GlobalAlloc for Tracking {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        LARGEST.fetch_max(layout.size(), Ordering::Relaxed);
        unsafe { System.alloc(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        LARGEST.fetch_max(new_size, Ordering::Relaxed);
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static ALLOCATOR: Tracking = Tracking;

/// Mutants per (compression, sample type): 8000 files in all, a few seconds.
const MUTANTS: usize = 400;

/// A deterministic generator (SplitMix64).
struct TestRng(u64);

impl TestRng {
    fn below(&mut self, n: u64) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        (z ^ (z >> 31)) % n.max(1)
    }
}

/// Every compression the crate writes.
fn compressions() -> Vec<Compression> {
    vec![
        Compression::Uncompressed,
        Compression::RLE,
        Compression::ZIP1,
        Compression::ZIP16,
        Compression::PIZ,
        Compression::PXR24,
        Compression::B44,
        Compression::B44A,
        Compression::DWAA(None),
        Compression::DWAB(None),
    ]
}

/// A small RGB image with smooth and noisy parts, `compression`-encoded, half or float.
fn encoded(compression: Compression, half: bool, seed: u64) -> Vec<u8> {
    let (w, h) = (40, 20);
    let value = |x: usize, y: usize, c: usize| {
        let noise = ((x * 31 + y * 17 + c * 7 + seed as usize) % 13) as f32 / 13.0;
        0.1 + x as f32 / w as f32 + 0.3 * noise + y as f32 * 0.01
    };
    let encoding = Encoding {
        compression,
        ..Encoding::FAST_LOSSLESS
    };
    let mut bytes = std::io::Cursor::new(Vec::new());
    if half {
        let channels = SpecificChannels::rgb(|Vec2(x, y): Vec2<usize>| {
            (
                f16::from_f32(value(x, y, 0)),
                f16::from_f32(value(x, y, 1)),
                f16::from_f32(value(x, y, 2)),
            )
        });
        Image::from_encoded_channels((w, h), encoding, channels)
            .write()
            .to_buffered(&mut bytes)
            .unwrap();
    } else {
        let channels = SpecificChannels::rgb(|Vec2(x, y): Vec2<usize>| {
            (value(x, y, 0), value(x, y, 1), value(x, y, 2))
        });
        Image::from_encoded_channels((w, h), encoding, channels)
            .write()
            .to_buffered(&mut bytes)
            .unwrap();
    }
    bytes.into_inner()
}

/// A 64-bit count a hostile chunk might claim.
fn inflated(rng: &mut TestRng) -> u64 {
    let choices = [
        1 << 45,
        1 << 40,
        1 << 32,
        u32::MAX as u64,
        1 << 28,
        1 << 20,
        65_536,
        (i64::MAX) as u64,
    ];
    match rng.below(3) {
        0 => choices[rng.below(choices.len() as u64) as usize],
        1 => rng.below(u64::MAX),
        _ => rng.below(1 << 16),
    }
}

/// One mutation of a valid file, chosen by `rng`; most land after the header, in the chunks.
fn mutate(bytes: &[u8], rng: &mut TestRng) -> Vec<u8> {
    let mut out = bytes.to_vec();
    let len = out.len() as u64;
    match rng.below(6) {
        0 => {
            for _ in 0..1 + rng.below(8) {
                let at = rng.below(len) as usize;
                out[at] ^= 1 << rng.below(8);
            }
        }
        1 => out.truncate(rng.below(len + 1) as usize),
        2 | 3 => {
            // A counter of a chunk leader (DWA's eleven u64, PIZ's and B44's sizes).
            let at = rng.below(len.saturating_sub(8)) as usize;
            let word = if rng.below(2) == 0 {
                inflated(rng).to_le_bytes()
            } else {
                let mut w = [0; 8];
                w[..4].copy_from_slice(&(inflated(rng) as u32).to_le_bytes());
                w
            };
            let n = if rng.below(2) == 0 { 8 } else { 4 };
            let end = (at + n).min(out.len());
            out[at..end].copy_from_slice(&word[..end - at]);
        }
        4 => out.extend((0..1 + rng.below(64)).map(|_| rng.below(256) as u8)),
        _ => {
            let at = rng.below(len) as usize;
            for b in out.iter_mut().skip(at).take(1 + rng.below(16) as usize) {
                *b = rng.below(256) as u8;
            }
        }
    }
    out
}

/// Reads `bytes`, checking the reader's promise: a result, and no allocation beyond its bound.
fn check(bytes: &[u8]) -> bool {
    LARGEST.store(0, Ordering::Relaxed);
    let accepted = rgb_exr_from_bytes(Path::new("fuzz.exr"), bytes).is_ok();
    let largest = LARGEST.load(Ordering::Relaxed);
    assert!(
        largest <= MAX_DECODE_BYTES,
        "{largest} bytes allocated for a {}-byte file",
        bytes.len()
    );
    accepted
}

#[test]
fn mutated_files_of_every_compression_never_panic_or_overallocate() {
    let _alone = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    let mut accepted = 0;
    let mut total = 0;
    for (k, compression) in compressions().into_iter().enumerate() {
        for half in [false, true] {
            let original = encoded(compression, half, k as u64);
            let rng = &mut TestRng(1000 + 2 * k as u64 + half as u64);
            for _ in 0..MUTANTS {
                total += 1;
                accepted += check(&mutate(&original, rng)) as usize;
            }
        }
    }
    assert_eq!(total, 10 * 2 * MUTANTS);
    assert!(accepted > 0, "some mutations leave a readable file");
}

#[test]
fn the_crafted_dwaa_file_is_refused_with_one_line() {
    let path = Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../../shared/data/hostile/dwaa_dc_count_2e45.exr"
    ));
    let Ok(bytes) = std::fs::read(path) else {
        eprintln!("skipped: {} is not here", path.display());
        return;
    };
    let _alone = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    LARGEST.store(0, Ordering::Relaxed);
    let err = rgb_exr_from_bytes(path, &bytes).unwrap_err().to_string();
    assert!(LARGEST.load(Ordering::Relaxed) <= MAX_DECODE_BYTES);
    assert!(err.contains("DWAA") && !err.contains('\n'), "{err}");
}

#[test]
fn every_lossless_compression_still_reads() {
    let _alone = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    for compression in [
        Compression::Uncompressed,
        Compression::RLE,
        Compression::ZIP1,
        Compression::ZIP16,
        Compression::PIZ,
    ] {
        let image = rgb_exr_from_bytes(Path::new("x.exr"), &encoded(compression, false, 3))
            .unwrap_or_else(|e| panic!("{compression:?}: {e}"));
        assert_eq!((image.width, image.height), (40, 20));
    }
}
