//! Any bytes given to the `.hair` reader: it must return, not panic; what it accepts must be
//! canonical (written back, the same bytes) and convert to a groom and a summary without panic.

#![no_main]

use cuticle_groom::HairFile;
use cuticle_groom::summary::HairFileSummary;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(file) = HairFile::from_bytes(data) else { return };
    let written = file.to_bytes().expect("an accepted file can be written back");
    assert_eq!(written, data, "an accepted file must be canonical");
    let _ = HairFileSummary::of(&file);
    let _ = file.into_groom();
});
