//! A short deterministic fuzz run of the reader: thousands of mutated files (bit flips,
//! truncations, inflated counts, random headers). None may panic; none may allocate more than
//! a small multiple of its size; any file accepted must be canonical (written back, it gives
//! the same bytes). The long run is `cargo fuzz` (see README, "Developing").

mod common;

use common::{TestRng, random_hair_file};
use cuticle_groom::summary::HairFileSummary;
use cuticle_groom::{ArrayFlags, HairFile, HairFileError};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::collections::HashSet;

/// The system allocator, noting the largest single request of the current thread.
struct Tracking;

thread_local! {
    static LARGEST: Cell<usize> = const { Cell::new(0) };
}

unsafe impl GlobalAlloc for Tracking {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        LARGEST.with(|l| l.set(l.get().max(layout.size())));
        unsafe { System.alloc(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        LARGEST.with(|l| l.set(l.get().max(new_size)));
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static ALLOCATOR: Tracking = Tracking;

const MUTANTS_PER_SEED: usize = 200;

/// One mutation of a valid file, chosen by `rng`.
fn mutate(bytes: &[u8], rng: &mut TestRng) -> Vec<u8> {
    let mut out = bytes.to_vec();
    match rng.below(8) {
        0 => flip_bits(&mut out, rng),
        1 => out.truncate(rng.below(out.len() as u64 + 1) as usize),
        2 => set_word(&mut out, 4 * (1 + rng.below(4) as usize), inflated(rng)),
        3 => out.extend((0..1 + rng.below(40)).map(|_| rng.below(256) as u8)),
        4 => random_header(&mut out, rng),
        5 => {
            flip_bits(&mut out, rng);
            out.truncate(out.len().saturating_sub(rng.below(30) as usize));
        }
        6 => set_word(
            &mut out,
            4 + 4 * rng.below(9) as usize,
            rng.below(1 << 32) as u32,
        ),
        _ => consistent_counts(&mut out, rng),
    }
    out
}

fn flip_bits(bytes: &mut [u8], rng: &mut TestRng) {
    for _ in 0..1 + rng.below(8) {
        let in_header = rng.below(2) == 0;
        let span = if in_header {
            bytes.len().min(128)
        } else {
            bytes.len()
        };
        let at = rng.below(span as u64) as usize;
        bytes[at] ^= 1 << rng.below(8);
    }
}

/// A count a corrupt or hostile header might claim.
fn inflated(rng: &mut TestRng) -> u32 {
    let choices = [
        u32::MAX,
        1 << 31,
        1 << 28,
        (1 << 28) + 1,
        1 << 26,
        65_536,
        1,
        0,
    ];
    match rng.below(3) {
        0 => choices[rng.below(choices.len() as u64) as usize],
        1 => rng.below(1 << 32) as u32,
        _ => rng.below(64) as u32,
    }
}

/// Inflates the strand count and sets the point count to agree with it, as a hostile file
/// would to pass the first checks.
fn consistent_counts(bytes: &mut [u8], rng: &mut TestRng) {
    let strands = inflated(rng);
    let per_strand = u32::from_le_bytes(bytes[16..20].try_into().unwrap()).wrapping_add(1);
    set_word(bytes, 4, strands);
    set_word(bytes, 8, strands.wrapping_mul(per_strand));
}

fn random_header(bytes: &mut [u8], rng: &mut TestRng) {
    for at in (4..bytes.len().min(40)).step_by(4) {
        set_word(
            bytes,
            at,
            if rng.below(2) == 0 {
                inflated(rng)
            } else {
                rng.below(32) as u32
            },
        );
    }
}

fn set_word(bytes: &mut [u8], at: usize, value: u32) {
    if at + 4 <= bytes.len() {
        bytes[at..at + 4].copy_from_slice(&value.to_le_bytes());
    }
}

/// Reads `input` with every consumer of a file, checking the promises the reader makes.
fn check(input: &[u8]) -> Result<(), HairFileError> {
    LARGEST.with(|l| l.set(0));
    let result = HairFile::from_bytes(input).map(|file| {
        let written = file.to_bytes().expect("an accepted file can be written");
        assert_eq!(written, input, "an accepted file must be canonical");
        let _ = HairFileSummary::of(&file);
        let _ = file.into_groom();
    });
    let largest = LARGEST.with(Cell::get);
    let allowed = 4 * input.len() + 4096;
    assert!(
        largest <= allowed,
        "{} bytes allocated for a {}-byte file",
        largest,
        input.len()
    );
    result
}

#[test]
fn thousands_of_mutated_files_never_panic_or_overallocate() {
    let mut kinds = HashSet::new();
    let mut accepted = 0;
    let mut total = 0;
    for seed in 0..32u64 {
        let flags = ArrayFlags::from_bits((seed % 32) as u32).unwrap();
        let original = random_hair_file(flags, seed).to_bytes().unwrap();
        let rng = &mut TestRng::new(1000 + seed);
        for _ in 0..MUTANTS_PER_SEED {
            let mutant = mutate(&original, rng);
            total += 1;
            match check(&mutant) {
                Ok(()) => accepted += 1,
                Err(err) => {
                    kinds.insert(std::mem::discriminant(&err));
                }
            }
        }
    }
    assert_eq!(total, 32 * MUTANTS_PER_SEED);
    assert!(
        accepted > 0,
        "some mutations (flipped mantissa bits) leave a valid file"
    );
    assert!(
        kinds.len() >= 8,
        "the run should reach most kinds of fault, reached {}",
        kinds.len()
    );
}

#[test]
fn random_garbage_after_a_valid_magic_is_refused_cleanly() {
    let rng = &mut TestRng::new(77);
    for _ in 0..2000 {
        let len = rng.below(400) as usize;
        let mut bytes: Vec<u8> = (0..len).map(|_| rng.below(256) as u8).collect();
        if len >= 4 {
            bytes[..4].copy_from_slice(b"HAIR");
        }
        let _ = check(&bytes);
    }
}
