//! Any bytes given to the USD groom reader, as a `.usdc` file (the binary format, whose
//! declared counts the guard checks) and as a `.usda` file: it must return, not panic, abort
//! or allocate what the bytes merely declare; what it accepts must be a valid groom.

#![no_main]

use cuticle_groom::Groom;
use cuticle_groom::usd::guard::check_crate;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = check_crate(data);
    let dir = std::env::temp_dir().join(format!("cuticle-fuzz-usd-{}", std::process::id()));
    let _ = std::fs::create_dir_all(&dir);
    for name in ["fuzz.usdc", "fuzz.usda"] {
        let path = dir.join(name);
        if std::fs::write(&path, data).is_err() {
            return;
        }
        if let Ok(groom) = Groom::read(&path) {
            assert!(groom.positions().iter().all(|p| p.is_finite()));
            assert!(groom.thickness().iter().all(|t| t.is_finite() && *t >= 0.0));
        }
    }
});
