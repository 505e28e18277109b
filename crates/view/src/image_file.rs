//! Writing one file of the window (a screenshot, a frame's PNG and EXR) in place atomically.
//! The encoders are the renderer's ([`cuticle_render::Image::png_bytes`], `exr_bytes`) and the
//! light crate's ([`cuticle_light::image_file`]), which the command line uses too.

/// Writes `bytes` to `path` through a temporary file beside it and a rename.
pub fn write_atomic(path: &std::path::Path, bytes: &[u8]) -> Result<(), String> {
    let tmp = path.with_extension(format!(
        "{}.partial",
        path.extension().and_then(|e| e.to_str()).unwrap_or("")
    ));
    std::fs::write(&tmp, bytes)
        .and_then(|_| std::fs::rename(&tmp, path))
        .map_err(|e| {
            let _ = std::fs::remove_file(&tmp);
            format!("cannot write {}: {e}", path.display())
        })
}
