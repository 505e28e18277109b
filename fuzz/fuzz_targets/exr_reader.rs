//! Any bytes given to the OpenEXR reader (maps, and images `compare` reads): it must return,
//! not panic or abort, and allocate within its bound whatever a header or chunk claims; what it
//! accepts holds finite pixels of the size it states.

#![no_main]

use cuticle_light::image_file::rgb_exr_from_bytes;
use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let Ok(image) = rgb_exr_from_bytes(Path::new("fuzz.exr"), data) else { return };
    assert_eq!(image.pixels.len(), image.width * image.height);
    assert!(image.pixels.iter().all(|p| p.is_finite()));
});
