//! Reading an input file whole, bounded: only a regular file (a FIFO given as `--scene` once
//! blocked forever, `/dev/zero` or a 20 GB sparse file failed only at the address-space
//! limit: issue 57), and no larger than its kind may be. Every reader of a scene, map, image,
//! lights or grid file, and a sweep's CSV, goes through [`read_regular`].

use std::io::{Error, ErrorKind, Read};
use std::path::Path;

/// The largest map or image read: a 16k × 8k RGBA float OpenEXR, uncompressed, with room.
pub const MAX_IMAGE_FILE: u64 = 4 << 30;
/// The largest text file read whole (scene TOML, a sweep's CSV, a grid of configurations).
pub const MAX_TEXT_FILE: u64 = 64 << 20;

/// The bytes of `path` when it is a regular file of at most `max_bytes` bytes; otherwise an
/// error saying which rule it breaks (the caller names the file).
pub fn read_regular(path: &Path, max_bytes: u64) -> std::io::Result<Vec<u8>> {
    // `metadata` follows links and never opens the file, so a FIFO does not block here.
    let meta = std::fs::metadata(path)?;
    if !meta.is_file() {
        return Err(Error::new(
            ErrorKind::InvalidInput,
            "not a regular file (a folder, pipe or device)",
        ));
    }
    if meta.len() > max_bytes {
        return Err(too_large(meta.len(), max_bytes));
    }
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    // A file that grows while it is read is held to the same bound.
    std::fs::File::open(path)?
        .take(max_bytes + 1)
        .read_to_end(&mut bytes)?;
    if bytes.len() as u64 > max_bytes {
        return Err(too_large(bytes.len() as u64, max_bytes));
    }
    Ok(bytes)
}

/// [`read_regular`] as UTF-8 text.
pub fn read_regular_text(path: &Path, max_bytes: u64) -> std::io::Result<String> {
    String::from_utf8(read_regular(path, max_bytes)?)
        .map_err(|_| Error::new(ErrorKind::InvalidData, "not UTF-8 text"))
}

fn too_large(len: u64, max: u64) -> Error {
    Error::new(
        ErrorKind::InvalidInput,
        format!("{len} bytes, more than the {max} such a file may hold"),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_regular_files_within_the_bound_are_read() {
        let dir = std::env::temp_dir().join(format!("cuticle-read-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir.join("a.txt");
        std::fs::write(&file, "12345").unwrap();
        assert_eq!(read_regular(&file, 5).unwrap(), b"12345");
        let err = read_regular(&file, 4).unwrap_err().to_string();
        assert!(err.contains("5 bytes, more than the 4"), "{err}");
        let err = read_regular(&dir, 100).unwrap_err().to_string();
        assert!(err.contains("not a regular file"), "{err}");
        assert!(read_regular(Path::new("/dev/zero"), 100).is_err());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
