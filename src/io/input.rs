//! Reading an input file (a mesh, a scene, a run file): the one way the crate reads one. A
//! regular file only, bounded by size: a FIFO given as a mesh blocked the run forever at its
//! open, `/dev/zero` was read until the memory ran out.

use crate::error::{quote, Error, Result};
use std::io::Read;
use std::path::Path;

/// Largest mesh file read: 1 GiB, about 2e7 nodes in ASCII MSH, far above the default size
/// limit (1.5e6 unknowns; `--max-dofs`).
pub const MESH_MAX_BYTES: u64 = 1 << 30;
/// Largest table read (a sweep shard's, ~1 kB a point; `sweep --merge`): 1 GiB.
pub const TABLE_MAX_BYTES: u64 = 1 << 30;
/// Largest TOML file read (a scene, a run file): 16 MiB; tribofe's are a few kB, a run file
/// with its manifest at most a few MB.
pub const TOML_MAX_BYTES: u64 = 16 << 20;

/// What a path that is not a regular file is, for a refusal.
fn kind(t: std::fs::FileType) -> &'static str {
    use std::os::unix::fs::FileTypeExt;
    if t.is_dir() {
        "a folder"
    } else if t.is_fifo() {
        "a FIFO"
    } else if t.is_char_device() {
        "a character device"
    } else if t.is_block_device() {
        "a block device"
    } else if t.is_socket() {
        "a socket"
    } else {
        "not a regular file"
    }
}

/// The bytes of the regular file `path`, at most `max`; `what` names it in a refusal as the
/// user gave it (`--mesh`, `--scene`). Anything else is refused before reading: a FIFO,
/// device, socket or folder (opened without blocking, then checked), a file above `max`.
pub fn read_bounded(path: &Path, what: &str, max: u64) -> Result<Vec<u8>> {
    use std::os::unix::fs::OpenOptionsExt;
    let shown = || quote(&path.display().to_string());
    // O_NONBLOCK: opening a FIFO with no writer would block; on a regular file it does nothing.
    let f = std::fs::OpenOptions::new()
        .read(true)
        .custom_flags(libc::O_NONBLOCK)
        .open(path)
        .map_err(|e| Error::read(path, e))?;
    let meta = f.metadata().map_err(|e| Error::read(path, e))?;
    if !meta.is_file() {
        return Err(Error::input(
            what,
            format!("'{}' is {}; give a regular file", shown(), kind(meta.file_type())),
        ));
    }
    let too_big = |size: String| {
        Error::input(what, format!("'{}' holds {size} bytes, above the {max} this input may have", shown()))
    };
    if meta.len() > max {
        return Err(too_big(meta.len().to_string()));
    }
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    f.take(max + 1).read_to_end(&mut bytes).map_err(|e| Error::read(path, e))?;
    if bytes.len() as u64 > max {
        return Err(too_big(format!("more than {max}")));
    }
    Ok(bytes)
}

/// [`read_bounded`] as UTF-8 text.
pub fn read_text(path: &Path, what: &str, max: u64) -> Result<String> {
    String::from_utf8(read_bounded(path, what, max)?)
        .map_err(|e| Error::read(path, std::io::Error::new(std::io::ErrorKind::InvalidData, e.utf8_error())))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn special_files_and_large_files_are_refused_without_blocking() {
        let d = tempfile::tempdir().unwrap();
        let fifo = d.path().join("f");
        let c = std::ffi::CString::new(fifo.to_str().unwrap()).unwrap();
        // SAFETY: a valid NUL-terminated path.
        assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
        let e = read_bounded(&fifo, "--mesh", 10).unwrap_err().to_string();
        assert!(e.contains("--mesh") && e.contains("is a FIFO; give a regular file"), "{e}");
        let e = read_bounded(Path::new("/dev/zero"), "--scene", 10).unwrap_err().to_string();
        assert!(e.contains("a character device"), "{e}");
        let e = read_bounded(d.path(), "--scene", 10).unwrap_err().to_string();
        assert!(e.contains("a folder"), "{e}");
        let big = d.path().join("big");
        std::fs::write(&big, [b'x'; 11]).unwrap();
        let e = read_bounded(&big, "--scene", 10).unwrap_err().to_string();
        assert!(e.contains("holds 11 bytes, above the 10"), "{e}");
        assert_eq!(read_text(&big, "--scene", 11).unwrap(), "x".repeat(11));
    }
}
