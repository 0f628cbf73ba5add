//! The output folder as a unit: a run writes into a fresh hidden sibling folder and renames it
//! into place at the end (an atomic exchange with the previous folder where Linux allows), so
//! `--out` holds either the previous complete result or the new one, never a mix; on an error
//! the temporary folder is removed ([`Drop`]), on SIGINT/SIGTERM by [`remove_temporaries`].

use crate::{Error, Result};
use std::path::{Path, PathBuf};
use std::sync::{Mutex, RwLock, RwLockReadGuard};

/// Temporary folders of the runs under way, for [`remove_temporaries`].
static ACTIVE: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// Held (shared) by every write of an output file; taken for good by [`remove_temporaries`],
/// so nothing is written (nor a removed folder recreated) once an interrupt cleans up.
static WRITES: RwLock<()> = RwLock::new(());

/// The guard every output write holds while it writes.
pub fn write_guard() -> RwLockReadGuard<'static, ()> {
    WRITES.read().unwrap_or_else(|e| e.into_inner())
}

/// An output folder being written: files go to [`OutDir::path`], [`OutDir::commit`] puts
/// them in place.
#[derive(Debug)]
pub struct OutDir {
    out: PathBuf,
    tmp: PathBuf,
    committed: bool,
}

/// Refuses an output path that cannot become a folder (an existing file, a dangling
/// symbolic link, no final name), before any work.
pub fn check(out: &Path) -> Result<()> {
    let bad = |why: &str| Err(Error::Output { path: out.to_path_buf(), why: why.into() });
    if out.file_name().is_none() {
        return bad("has no final name (use e.g. out/check)");
    }
    match std::fs::symlink_metadata(out) {
        Ok(m) if m.is_dir() => Ok(()),
        Ok(m) if m.file_type().is_symlink() => {
            if out.is_dir() {
                bad("is a symbolic link; give the folder it points to")
            } else {
                bad("is a symbolic link to nothing or to a file; remove it or choose another --out")
            }
        }
        Ok(_) => bad("is an existing file, not a folder; remove it or choose another --out"),
        Err(_) => Ok(()),
    }
}

impl OutDir {
    /// Checks `out` ([`check`]) and creates the temporary sibling folder
    /// `.<name>.tmp-<pid>` (and the parent folders).
    pub fn begin(out: &Path) -> Result<OutDir> {
        check(out)?;
        let _writing = write_guard();
        let name = out.file_name().unwrap_or_default().to_string_lossy();
        let parent = out.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
        std::fs::create_dir_all(parent).map_err(|e| Error::io(parent, e))?;
        let tmp = parent.join(format!(".{name}.tmp-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&tmp); // a leftover of a killed run with this pid
        std::fs::create_dir(&tmp).map_err(|e| Error::io(&tmp, e))?;
        ACTIVE.lock().unwrap_or_else(|e| e.into_inner()).push(tmp.clone());
        Ok(OutDir { out: out.to_path_buf(), tmp, committed: false })
    }

    /// Where the files go until [`OutDir::commit`].
    pub fn path(&self) -> &Path {
        &self.tmp
    }

    /// Puts the new folder in place of `out`; the previous folder, if any, is removed.
    pub fn commit(mut self) -> Result<()> {
        let _writing = write_guard();
        let err = |e| Error::io(&self.out, e);
        if self.out.is_dir() {
            if exchange(&self.tmp, &self.out).is_err() {
                // No atomic exchange here: move the old folder aside, then the new one in.
                let old = self.tmp.with_extension("old");
                std::fs::rename(&self.out, &old).map_err(err)?;
                std::fs::rename(&self.tmp, &self.out).map_err(err)?;
                std::fs::rename(&old, &self.tmp).map_err(err)?;
            }
            // tmp now holds the previous folder: removed by drop.
        } else {
            std::fs::rename(&self.tmp, &self.out).map_err(err)?;
        }
        self.committed = true;
        let _ = std::fs::remove_dir_all(&self.tmp);
        forget(&self.tmp);
        Ok(())
    }
}

impl Drop for OutDir {
    fn drop(&mut self) {
        if !self.committed {
            let _ = std::fs::remove_dir_all(&self.tmp);
            forget(&self.tmp);
        }
    }
}

fn forget(tmp: &Path) {
    ACTIVE.lock().unwrap_or_else(|e| e.into_inner()).retain(|p| p != tmp);
}

/// Removes the temporary folders of the runs under way, after the writes in progress end, and
/// blocks every later write: call it only just before exiting (on SIGINT/SIGTERM).
pub fn remove_temporaries() {
    std::mem::forget(WRITES.write().unwrap_or_else(|e| e.into_inner()));
    let active = std::mem::take(&mut *ACTIVE.lock().unwrap_or_else(|e| e.into_inner()));
    for p in active {
        let _ = std::fs::remove_dir_all(p);
    }
}

/// Swaps two folders atomically (Linux renameat2 RENAME_EXCHANGE).
#[cfg(target_os = "linux")]
fn exchange(a: &Path, b: &Path) -> std::io::Result<()> {
    use std::os::unix::ffi::OsStrExt;
    let c = |p: &Path| std::ffi::CString::new(p.as_os_str().as_bytes()).map_err(std::io::Error::other);
    let (ca, cb) = (c(a)?, c(b)?);
    // SAFETY: both are valid NUL-terminated paths; the call only renames.
    let r = unsafe {
        libc::renameat2(libc::AT_FDCWD, ca.as_ptr(), libc::AT_FDCWD, cb.as_ptr(), libc::RENAME_EXCHANGE)
    };
    if r == 0 {
        Ok(())
    } else {
        Err(std::io::Error::last_os_error())
    }
}

#[cfg(not(target_os = "linux"))]
fn exchange(_: &Path, _: &Path) -> std::io::Result<()> {
    Err(std::io::Error::other("no atomic exchange"))
}
