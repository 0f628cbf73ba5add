//! The output folder as a unit: a run writes into a fresh hidden sibling folder and renames it
//! into place at the end (an atomic exchange with the previous folder where Linux allows), so
//! `--out` holds either the previous complete result or the new one, never a mix; on an error
//! the temporary folder is removed ([`Drop`]), on a host's interrupt by the folder's own
//! [`Cleanup`] handle (the binary keeps one per folder and calls them on SIGINT/SIGTERM),
//! after a SIGKILL by the next run on that folder ([`remove_orphans`]). An existing folder is
//! replaced only when tribofe wrote it (its `run.toml`) or the caller forces it ([`check`]).
//!
//! No switch acts on the whole process: each folder has its own gate, closed by its own
//! [`Cleanup`]; writes into other folders (another run of the same host) go on.

use crate::{Error, Result};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Condvar, Mutex};

/// Where a folder under way stands.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Stage {
    Writing,
    Committed,
    Removed,
}

/// One folder's gate: its stage and the writes into it in progress.
#[derive(Debug)]
struct Gate {
    root: PathBuf,
    state: Mutex<(Stage, usize)>,
    idle: Condvar,
}

impl Gate {
    /// Waits for the writes in progress to end, then runs `f` on the stage, the gate held.
    fn exclusive<R>(&self, f: impl FnOnce(&mut Stage) -> R) -> R {
        let mut st = self.state.lock().unwrap_or_else(|e| e.into_inner());
        while st.1 > 0 {
            st = self.idle.wait(st).unwrap_or_else(|e| e.into_inner());
        }
        f(&mut st.0)
    }
}

/// The temporary folders being written in this process, so that a write finds its folder's
/// gate. Private: only an [`OutDir`] adds to it, only its drop removes from it.
static GATES: Mutex<Vec<Arc<Gate>>> = Mutex::new(Vec::new());

/// Held by every write of an output file while it writes: a write into a folder whose
/// [`Cleanup`] ran is refused ([`Error::Interrupted`]) instead of recreating the folder.
#[derive(Debug)]
pub struct WriteGuard(Option<Arc<Gate>>);

impl Drop for WriteGuard {
    fn drop(&mut self) {
        if let Some(g) = &self.0 {
            g.state.lock().unwrap_or_else(|e| e.into_inner()).1 -= 1;
            g.idle.notify_all();
        }
    }
}

/// The guard a writer of `path` holds while it writes (none needed outside the folders under
/// way; refused once the folder holding `path` was removed by its [`Cleanup`]).
pub fn write_guard(path: &Path) -> Result<WriteGuard> {
    let gate =
        GATES.lock().unwrap_or_else(|e| e.into_inner()).iter().find(|g| path.starts_with(&g.root)).cloned();
    let Some(gate) = gate else { return Ok(WriteGuard(None)) };
    let mut st = gate.state.lock().unwrap_or_else(|e| e.into_inner());
    if st.0 == Stage::Removed {
        return Err(Error::Interrupted);
    }
    st.1 += 1;
    drop(st);
    Ok(WriteGuard(Some(gate)))
}

/// An output folder being written: files go to [`OutDir::path`], [`OutDir::commit`] puts
/// them in place.
#[derive(Debug)]
pub struct OutDir {
    out: PathBuf,
    tmp: PathBuf,
    gate: Arc<Gate>,
}

/// Removes one output folder under way from any thread (a host's interrupt handler): waits for
/// the writes in progress into it, removes its temporary folder and refuses every later write
/// into it and its commit ([`Error::Interrupted`]). Does nothing once the folder was
/// committed or dropped. Cheap to clone; `Send + Sync`.
#[derive(Debug, Clone)]
pub struct Cleanup(Arc<Gate>);

impl Cleanup {
    /// Removes the temporary folder unless committed; returns whether it removed it.
    pub fn remove(&self) -> bool {
        self.0.exclusive(|stage| {
            let was = *stage == Stage::Writing;
            if was {
                let _ = std::fs::remove_dir_all(&self.0.root);
            }
            if *stage != Stage::Committed {
                *stage = Stage::Removed;
            }
            was
        })
    }

    /// Whether the folder is still being written (neither committed nor removed).
    pub fn is_open(&self) -> bool {
        self.0.state.lock().unwrap_or_else(|e| e.into_inner()).0 == Stage::Writing
    }
}

/// The run file every output folder holds (`run.toml`); a folder is tribofe's when it holds one
/// that starts with [`RUN_FILE_MARKER`].
pub const RUN_FILE: &str = "run.toml";
/// The first line of every run file starts with this.
pub const RUN_FILE_MARKER: &str = "# written by tribofe";

/// Whether `dir` holds a run file written by tribofe: `run.toml`, or the `run_<I>of<N>.toml`
/// of a sharded sweep (see [`RUN_FILE`]).
pub fn is_tribofe_folder(dir: &Path) -> bool {
    if is_run_file(&dir.join(RUN_FILE)) {
        return true;
    }
    let Ok(entries) = std::fs::read_dir(dir) else { return false };
    entries.flatten().take(10_000).any(|e| {
        let name = e.file_name().to_string_lossy().into_owned();
        name.starts_with("run_") && name.ends_with(".toml") && name.contains("of") && is_run_file(&e.path())
    })
}

/// Whether `path` is a run file: the marker line first.
fn is_run_file(path: &Path) -> bool {
    use std::io::Read;
    let mut head = String::new();
    // The marker and the table come first: a bounded read, whatever the file's size.
    let read = std::fs::File::open(path).and_then(|f| f.take(64 * 1024).read_to_string(&mut head));
    // The marker alone also recognises the run files of tribofe versions before the
    // [tribofe] table (slide and edges wrote one).
    read.is_ok() && head.starts_with(RUN_FILE_MARKER)
}

/// Refuses an output path that cannot become a folder (an existing file, a dangling
/// symbolic link, no final name) and, unless `force`, an existing folder that holds anything
/// and was not written by tribofe ([`is_tribofe_folder`]), before any work. Removes the
/// orphaned temporaries of killed runs on that folder ([`remove_orphans`]).
pub fn check(out: &Path, force: bool) -> Result<()> {
    let bad = |why: String| Err(Error::Output { path: out.to_path_buf(), why });
    if out.file_name().is_none() {
        return bad("has no final name (use e.g. out/check)".into());
    }
    remove_orphans(out);
    match std::fs::symlink_metadata(out) {
        Ok(m) if m.is_dir() => {
            if force || is_tribofe_folder(out) {
                return Ok(());
            }
            let mut entries = std::fs::read_dir(out).map_err(|e| Error::io(out, e))?;
            match entries.next() {
                None => Ok(()),
                Some(e) => {
                    let first = e.map(|e| e.file_name().to_string_lossy().into_owned()).unwrap_or_default();
                    bad(format!(
                        "exists and holds files tribofe did not write (e.g. '{}'; no run.toml of a \
                         previous tribofe run): give --force to replace the whole folder, or choose \
                         another --out",
                        crate::error::quote(&first)
                    ))
                }
            }
        }
        Ok(m) if m.file_type().is_symlink() => {
            if out.is_dir() {
                bad("is a symbolic link; give the folder it points to".into())
            } else {
                bad("is a symbolic link to nothing or to a file; remove it or choose another --out".into())
            }
        }
        Ok(_) => bad("is an existing file, not a folder; remove it or choose another --out".into()),
        Err(_) => Ok(()),
    }
}

/// Removes the hidden temporaries `.<name>.tmp-<pid>` (and `.<name>.tmp-<pid>.old`) next to
/// `out` whose process is gone: what a SIGKILL (or a power cut) left behind. A live pid keeps
/// its folder (another run under way); a reused pid keeps it until that process ends.
pub fn remove_orphans(out: &Path) {
    let Some(name) = out.file_name() else { return };
    let prefix = format!(".{}.tmp-", name.to_string_lossy());
    let parent = out.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    let Ok(entries) = std::fs::read_dir(parent) else { return };
    for e in entries.flatten() {
        let file = e.file_name().to_string_lossy().into_owned();
        let Some(rest) = file.strip_prefix(&prefix) else { continue };
        let pid = rest.strip_suffix(".old").unwrap_or(rest);
        let Ok(pid) = pid.parse::<i32>() else { continue };
        if pid > 0 && pid != std::process::id() as i32 && !alive(pid) {
            let _ = std::fs::remove_dir_all(e.path());
        }
    }
    // Inside a tribofe folder written in place (sweep shards): the files `.<file>.<pid>.tmp`
    // of a killed writer ([`crate::report::write_atomic`]).
    if !is_tribofe_folder(out) {
        return;
    }
    let Ok(entries) = std::fs::read_dir(out) else { return };
    for e in entries.flatten() {
        let file = e.file_name().to_string_lossy().into_owned();
        let Some(pid) = file
            .strip_prefix('.')
            .and_then(|f| f.strip_suffix(".tmp"))
            .and_then(|f| f.rsplit_once('.'))
            .and_then(|(_, pid)| pid.parse::<i32>().ok())
        else {
            continue;
        };
        if pid > 0 && pid != std::process::id() as i32 && !alive(pid) && e.path().is_file() {
            let _ = std::fs::remove_file(e.path());
        }
    }
}

/// Whether a process `pid` exists (signal 0 probes without sending anything).
fn alive(pid: i32) -> bool {
    // SAFETY: kill with signal 0 sends nothing; it only reports whether the pid exists.
    let r = unsafe { libc::kill(pid, 0) };
    r == 0 || std::io::Error::last_os_error().raw_os_error() != Some(libc::ESRCH)
}

impl OutDir {
    /// Checks `out` ([`check`], `force` as there) and creates the temporary sibling folder
    /// `.<name>.tmp-<pid>` (and the parent folders).
    pub fn begin(out: &Path, force: bool) -> Result<OutDir> {
        check(out, force)?;
        let name = out.file_name().unwrap_or_default().to_string_lossy();
        let parent = out.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
        std::fs::create_dir_all(parent).map_err(|e| Error::io(parent, e))?;
        let tmp = parent.join(format!(".{name}.tmp-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&tmp); // a leftover of a killed run with this pid
        std::fs::create_dir(&tmp).map_err(|e| Error::io(&tmp, e))?;
        let gate = Arc::new(Gate {
            root: tmp.clone(),
            state: Mutex::new((Stage::Writing, 0)),
            idle: Condvar::new(),
        });
        GATES.lock().unwrap_or_else(|e| e.into_inner()).push(gate.clone());
        Ok(OutDir { out: out.to_path_buf(), tmp, gate })
    }

    /// The handle that removes this folder from another thread ([`Cleanup`]).
    pub fn cleanup(&self) -> Cleanup {
        Cleanup(self.gate.clone())
    }

    /// Where the files go until [`OutDir::commit`].
    pub fn path(&self) -> &Path {
        &self.tmp
    }

    /// Puts the new folder in place of `out`; the previous folder, if any, is removed.
    pub fn commit(self) -> Result<()> {
        let gate = self.gate.clone();
        gate.exclusive(|stage| self.swap_in(stage))
    }

    fn swap_in(&self, stage: &mut Stage) -> Result<()> {
        if *stage != Stage::Writing {
            return Err(Error::Interrupted);
        }
        let err = |e| Error::io(&self.out, e);
        if self.out.is_dir() {
            if exchange(&self.tmp, &self.out).is_err() {
                // No atomic exchange here: move the old folder aside, then the new one in.
                let old = self.tmp.with_extension("old");
                std::fs::rename(&self.out, &old).map_err(err)?;
                std::fs::rename(&self.tmp, &self.out).map_err(err)?;
                std::fs::rename(&old, &self.tmp).map_err(err)?;
            }
        } else {
            std::fs::rename(&self.tmp, &self.out).map_err(err)?;
        }
        *stage = Stage::Committed;
        // tmp holds the previous folder, if any.
        let _ = std::fs::remove_dir_all(&self.tmp);
        Ok(())
    }
}

impl Drop for OutDir {
    fn drop(&mut self) {
        // Uncommitted (an error, a panic): the temporary goes, and a late write into it is
        // refused rather than recreating it.
        self.gate.exclusive(|stage| {
            if *stage == Stage::Writing {
                let _ = std::fs::remove_dir_all(&self.tmp);
                *stage = Stage::Removed;
            }
        });
        GATES.lock().unwrap_or_else(|e| e.into_inner()).retain(|g| !Arc::ptr_eq(g, &self.gate));
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cleanup_removes_its_folder_only_and_refuses_later_writes() {
        let d = tempfile::tempdir().unwrap();
        let (a, b) = (
            OutDir::begin(&d.path().join("a"), false).unwrap(),
            OutDir::begin(&d.path().join("b"), false).unwrap(),
        );
        let (fa, fb) = (a.path().join("x.csv"), b.path().join("x.csv"));
        std::fs::write(&fa, b"1\n").unwrap();
        let stop = a.cleanup();
        assert!(stop.remove() && !a.path().exists());
        // The removed folder's writes and commit are refused; the other folder goes on.
        assert!(matches!(write_guard(&fa), Err(Error::Interrupted)));
        assert!(!a.path().exists(), "a refused write recreated the folder");
        assert!(matches!(a.commit(), Err(Error::Interrupted)));
        let g = write_guard(&fb).unwrap();
        std::fs::write(&fb, b"3\n").unwrap();
        drop(g);
        let c = b.cleanup();
        b.commit().unwrap();
        assert!(!c.remove(), "a committed folder is kept");
        assert_eq!(std::fs::read_to_string(d.path().join("b/x.csv")).unwrap(), "3\n");
        assert!(!d.path().join("a").exists());
    }
}
