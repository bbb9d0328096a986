//! Reading the files a scene names, safely: only regular files (a FIFO would block forever,
//! `/dev/zero` would never end), and never more than a stated number of bytes.

use std::fs::File;
use std::io::{self, Read};
use std::path::{Path, PathBuf};

/// Largest scene file read, in bytes (256 MiB).
pub const MAX_SCENE_BYTES: u64 = 1 << 28;

/// Largest OBJ file read, in bytes (4 GiB).
pub const MAX_OBJ_BYTES: u64 = 1 << 32;

/// Opens `path` for reading if it is a regular file (after following symbolic links).
/// The type is checked before opening, since opening a FIFO blocks until a writer comes.
pub(crate) fn open_regular(path: &Path) -> io::Result<File> {
    let not_regular = |m: std::fs::Metadata| {
        let t = m.file_type();
        let what = if t.is_dir() {
            "a directory"
        } else if t.is_symlink() {
            "a symbolic link"
        } else {
            "a device, FIFO or socket"
        };
        io::Error::other(format!("not a regular file (it is {what})"))
    };
    let m = std::fs::metadata(path)?;
    if !m.is_file() {
        return Err(not_regular(m));
    }
    let f = File::open(path)?;
    let m = f.metadata()?;
    if !m.is_file() {
        return Err(not_regular(m));
    }
    Ok(f)
}

/// The contents of the regular file `path`, refused if longer than `cap` bytes.
pub(crate) fn read_capped(path: &Path, cap: u64) -> io::Result<Vec<u8>> {
    let f = open_regular(path)?;
    let mut bytes = Vec::new();
    f.take(cap.saturating_add(1)).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > cap {
        return Err(io::Error::other(format!("longer than {cap} bytes")));
    }
    Ok(bytes)
}

/// A path made absolute and free of `..` where the file system allows, for cycle checks (a scene that includes itself).
pub(crate) fn canonical(p: &Path) -> PathBuf {
    std::fs::canonicalize(p).unwrap_or_else(|_| p.to_path_buf())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn special_files_are_refused() {
        let e = read_capped(Path::new("/dev/zero"), 1 << 20).unwrap_err();
        assert!(e.to_string().contains("not a regular file"), "{e}");
        let e = read_capped(Path::new("src"), 1 << 20).unwrap_err();
        assert!(e.to_string().contains("directory"), "{e}");
        let ok = read_capped(Path::new("Cargo.toml"), 1 << 20).expect("Cargo.toml");
        assert!(!ok.is_empty());
        let e = read_capped(Path::new("Cargo.toml"), 10).unwrap_err();
        assert!(e.to_string().contains("longer than 10 bytes"), "{e}");
    }
}
