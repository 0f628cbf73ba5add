//! The output folder, changed by record, never by guess. A run writes its files into a fresh
//! hidden sibling folder `.<name>.tmp-<pid>`; [`OutDir::commit`] then lists them in `run.toml`
//! (path, size and SHA-256 of each: the manifest, [`Manifest`]) and puts them in place.
//!
//! - `--out` absent: the whole temporary folder is renamed into place (never over anything:
//!   `renameat2(RENAME_NOREPLACE)`), so the folder appears complete or not at all.
//! - `--out` present: each new file is renamed into the existing folder over its own name, and
//!   the previous run's files that this run does not write (its manifest) are removed. Nothing
//!   else in the folder is touched: a user's notes, subfolders, finished shards and files
//!   written there while the run was under way stay. Renaming file by file rather than
//!   exchanging whole folders is what keeps them: a whole-folder exchange would have to move
//!   the user's entries across, and a file written into the old folder in between would go
//!   with it. Each listed file is at every instant either its previous complete version or its
//!   new one (rename(2) is atomic); `run.toml` is renamed last, so its manifest matches the
//!   folder again once the commit is done. The commit holds the folder's gate, so an
//!   interrupt (SIGINT/SIGTERM) lands before it (the folder as before) or after it (the new
//!   run complete), never inside; only a SIGKILL or a power cut in the commit's few renames
//!   can leave a mix, which the next run sees as a mismatch and refuses without `--force`
//!   (nothing is deleted).
//!
//! A folder is tribofe's only when its `run.toml` has a manifest and every listed file is
//! there, a regular file, with that size and hash ([`standing`]); a copied `run.toml`, one
//! without a manifest (an older tribofe), or one whose files were edited or removed does not
//! count. A folder holding only verified sweep shards (`run_<I>of<N>.toml` with their tables)
//! holds nothing of the user's and is accepted too. Anything else is refused before any work
//! unless `--force` ([`check`]); even with `--force` only files of the new run's names are
//! replaced, and never a folder, a symbolic link or a special file. A user's file whose name
//! is one this run writes is refused at the commit (the folder left as before), since a
//! command's file names depend on its options and are known only once it has run.
//!
//! On an error the temporary folder is removed ([`Drop`]), on a host's interrupt by the
//! folder's own [`Cleanup`] handle (the binary keeps one per folder and calls them on
//! SIGINT/SIGTERM), after a SIGKILL by the next run on that folder ([`remove_orphans`]).
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
    out: PathBuf,
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
    force: bool,
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

    /// Whether the folder was committed: `--out` holds the new run.
    pub fn is_committed(&self) -> bool {
        self.0.state.lock().unwrap_or_else(|e| e.into_inner()).0 == Stage::Committed
    }

    /// The `--out` folder this handle belongs to.
    pub fn out(&self) -> &Path {
        &self.0.out
    }
}

/// The run file every output folder holds (`run.toml`): the provenance of the run and the
/// manifest of the files it wrote ([`Manifest`]).
pub const RUN_FILE: &str = "run.toml";
/// The first line of every run file starts with this.
pub const RUN_FILE_MARKER: &str = "# written by tribofe";
/// The manifest's content hash, recorded in it as `algorithm`.
pub const HASH_ALGORITHM: &str = "sha256";

/// A run file is read whole to check its manifest; tribofe's are far smaller (a bounded read
/// of whatever a user put there).
const RUN_FILE_MAX_BYTES: u64 = 64 << 20;

/// One file tribofe wrote: its path in the folder (`/`-separated), size in bytes, SHA-256.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Listed {
    pub path: String,
    pub size: u64,
    pub sha256: String,
}

/// The `[manifest]` table of a run file: every file tribofe wrote into the folder (the run
/// file itself aside), what makes the folder tribofe's ([`standing`]).
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Manifest {
    pub algorithm: String,
    pub files: Vec<Listed>,
}

impl Manifest {
    /// The manifest of files given by name and content (written in place, [`write_in_place`]).
    pub fn of_bytes(files: &[(&str, &[u8])]) -> Manifest {
        let files = files
            .iter()
            .map(|(p, b)| Listed { path: p.to_string(), size: b.len() as u64, sha256: sha256_hex(b) })
            .collect();
        Manifest { algorithm: HASH_ALGORITHM.into(), files }
    }

    /// The `[manifest]` table as TOML text, to append to a run file.
    pub fn to_toml(&self) -> Result<String> {
        #[derive(serde::Serialize)]
        struct Wrap<'a> {
            manifest: &'a Manifest,
        }
        toml::to_string(&Wrap { manifest: self }).map_err(|e| Error::input("run.toml", e.to_string()))
    }

    /// The manifest of a run file's text: `None` unless the marker comes first and the table
    /// is whole (a known algorithm, plain relative paths, hex hashes).
    pub fn of_run_file(text: &str, own_name: &str) -> Option<Manifest> {
        if !text.starts_with(RUN_FILE_MARKER) {
            return None;
        }
        let t: toml::Table = text.parse().ok()?;
        let m: Manifest = t.get("manifest")?.clone().try_into().ok()?;
        let sane = |l: &Listed| {
            l.path != own_name
                && plain_relative(&l.path)
                && l.sha256.len() == 64
                && l.sha256.bytes().all(|b| b.is_ascii_hexdigit())
        };
        (m.algorithm == HASH_ALGORITHM && m.files.iter().all(sane)).then_some(m)
    }
}

/// Whether `p` names a path inside a folder: relative, only plain names (no `..`, no root).
fn plain_relative(p: &str) -> bool {
    !p.is_empty()
        && Path::new(p).components().all(|c| matches!(c, std::path::Component::Normal(_)))
        && !p.contains('\\')
}

/// SHA-256 of `bytes` in lower-case hex.
pub fn sha256_hex(bytes: &[u8]) -> String {
    use sha2::Digest;
    hex(&sha2::Sha256::digest(bytes))
}

fn hex(d: &[u8]) -> String {
    d.iter().map(|b| format!("{b:02x}")).collect()
}

/// What identifies a file's content without reading it: a changed file changes its ctime.
type Stamp = (u64, i64, i64, i64, i64, u64, u64);

fn stamp(m: &std::fs::Metadata) -> Stamp {
    use std::os::unix::fs::MetadataExt;
    (m.len(), m.mtime(), m.mtime_nsec(), m.ctime(), m.ctime_nsec(), m.ino(), m.dev())
}

/// Hashes already computed in this process, by file and stamp: a run checks its folder at the
/// start, again when it begins writing and at the commit, and reads each file once.
static HASHES: Mutex<Option<std::collections::HashMap<PathBuf, (Stamp, String)>>> = Mutex::new(None);

/// Size and SHA-256 of the regular file `path` (a symbolic link is not followed: refused).
fn hash_file(path: &Path) -> std::io::Result<(u64, String)> {
    use sha2::Digest;
    use std::io::Read;
    use std::os::unix::fs::OpenOptionsExt;
    let f = std::fs::OpenOptions::new()
        .read(true)
        .custom_flags(libc::O_NOFOLLOW | libc::O_NONBLOCK)
        .open(path)?;
    let meta = f.metadata()?;
    if !meta.is_file() {
        return Err(std::io::Error::other("not a regular file"));
    }
    let key = stamp(&meta);
    if let Some((s, h)) = HASHES.lock().unwrap_or_else(|e| e.into_inner()).as_ref().and_then(|m| m.get(path))
    {
        if *s == key {
            return Ok((meta.len(), h.clone()));
        }
    }
    let mut hasher = sha2::Sha256::new();
    let mut buf = vec![0u8; 1 << 16];
    let mut f = f;
    let mut size = 0u64;
    loop {
        let n = f.read(&mut buf)?;
        if n == 0 {
            break;
        }
        size += n as u64;
        hasher.update(&buf[..n]);
    }
    let h = hex(&hasher.finalize());
    if size == meta.len() {
        let mut cache = HASHES.lock().unwrap_or_else(|e| e.into_inner());
        cache.get_or_insert_with(Default::default).insert(path.to_path_buf(), (key, h.clone()));
    }
    Ok((size, h))
}

/// What stands at `dir/rel`, every folder on the way a real folder (not a link).
#[derive(Debug, PartialEq, Eq)]
enum Spot {
    Absent,
    Regular,
    /// A folder, a symbolic link or a special file at `rel` or on the way: the prefix and what.
    Blocked(String, &'static str),
}

fn kind(m: &std::fs::Metadata) -> &'static str {
    let t = m.file_type();
    if t.is_symlink() {
        "a symbolic link"
    } else if t.is_dir() {
        "a folder"
    } else {
        "a special file (FIFO, device or socket)"
    }
}

fn spot(dir: &Path, rel: &str) -> std::io::Result<Spot> {
    let parts: Vec<&str> = rel.split('/').collect();
    let mut at = dir.to_path_buf();
    for (i, part) in parts.iter().enumerate() {
        at.push(part);
        let last = i + 1 == parts.len();
        match std::fs::symlink_metadata(&at) {
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Spot::Absent),
            Err(e) => return Err(e),
            Ok(m) if last && m.is_file() => return Ok(Spot::Regular),
            Ok(m) if !last && m.is_dir() => {}
            Ok(m) => return Ok(Spot::Blocked(parts[..=i].join("/"), kind(&m))),
        }
    }
    Ok(Spot::Absent)
}

/// Whether the listed file is in `dir` as recorded; else why not, naming it.
fn verify(dir: &Path, l: &Listed, record: &str) -> std::result::Result<(), String> {
    let name = crate::error::quote(&l.path);
    match spot(dir, &l.path) {
        Ok(Spot::Regular) => {}
        Ok(Spot::Absent) => return Err(format!("'{name}', listed in its {record}, is missing")),
        Ok(Spot::Blocked(at, what)) => {
            return Err(format!(
                "'{}', on the way to '{name}' listed in its {record}, is {what}",
                crate::error::quote(&at)
            ))
        }
        Err(e) => return Err(format!("'{name}', listed in its {record}, cannot be read: {e}")),
    }
    match hash_file(&dir.join(&l.path)) {
        Ok((size, h)) if size == l.size && h == l.sha256 => Ok(()),
        Ok(_) => {
            Err(format!("'{name}' differs from the file tribofe wrote (its size or SHA-256 in {record})"))
        }
        Err(e) => Err(format!("'{name}', listed in its {record}, cannot be read: {e}")),
    }
}

/// The manifest of the run file `dir/name`, or why the folder has none.
fn read_record(dir: &Path, name: &str) -> std::result::Result<Manifest, String> {
    let path = dir.join(name);
    let m = match std::fs::symlink_metadata(&path) {
        Ok(m) => m,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Err(format!("has no {name}")),
        Err(e) => return Err(format!("its {name} cannot be read: {e}")),
    };
    if !m.is_file() {
        return Err(format!("its {name} is {}", kind(&m)));
    }
    let text = match crate::io::input::read_text(&path, name, RUN_FILE_MAX_BYTES) {
        Ok(t) => t,
        Err(e) => return Err(format!("its {name} cannot be read: {e}")),
    };
    if !text.starts_with(RUN_FILE_MARKER) {
        return Err(format!("its {name} was not written by tribofe"));
    }
    Manifest::of_run_file(&text, name).ok_or_else(|| {
        format!(
            "its {name} has no manifest of the files tribofe wrote (a copied run file, or one of a \
             tribofe before the manifest)"
        )
    })
}

/// Whether `name` is the run file of a sweep shard, `run_<I>of<N>.toml`.
fn is_shard_record(name: &str) -> bool {
    name.strip_prefix("run_")
        .and_then(|r| r.strip_suffix(".toml"))
        .and_then(|r| r.split_once("of"))
        .is_some_and(|(i, n)| {
            !i.is_empty() && !n.is_empty() && i.bytes().chain(n.bytes()).all(|b| b.is_ascii_digit())
        })
}

/// Whether `name` is a temporary of tribofe's file writer, `.<file>.<pid>.tmp`.
fn is_writer_temporary(name: &str) -> bool {
    name.strip_prefix('.')
        .and_then(|f| f.strip_suffix(".tmp"))
        .and_then(|f| f.rsplit_once('.'))
        .is_some_and(|(_, pid)| pid.parse::<i32>().is_ok())
}

/// Whose an existing folder is, by record ([`standing`]).
#[derive(Debug)]
pub enum Standing {
    /// Nothing of that name.
    Absent,
    /// A folder holding nothing.
    Empty,
    /// A folder whose `run.toml` has a manifest that every listed file matches.
    Tribofe(Manifest),
    /// A folder holding only sweep shards tribofe wrote (`run_<I>of<N>.toml` with a manifest,
    /// the files they list) and no `run.toml`.
    Shards,
    /// Anything else (or not a folder): why, naming an entry.
    Foreign(String),
}

/// Whose the folder `dir` is, by the manifests of its run files (never by a name alone).
pub fn standing(dir: &Path) -> Standing {
    match std::fs::symlink_metadata(dir) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Standing::Absent,
        Err(e) => return Standing::Foreign(format!("cannot be read: {e}")),
        Ok(m) if !m.is_dir() => return Standing::Foreign(format!("is {}", kind(&m))),
        Ok(_) => {}
    }
    let names: Vec<String> = match std::fs::read_dir(dir) {
        Ok(es) => es.flatten().map(|e| e.file_name().to_string_lossy().into_owned()).collect(),
        Err(e) => return Standing::Foreign(format!("cannot be read: {e}")),
    };
    if names.is_empty() {
        return Standing::Empty;
    }
    if names.iter().any(|n| n == RUN_FILE) {
        let m = match read_record(dir, RUN_FILE) {
            Ok(m) => m,
            Err(why) => return Standing::Foreign(why),
        };
        return match m.files.iter().try_for_each(|l| verify(dir, l, RUN_FILE)) {
            Ok(()) => Standing::Tribofe(m),
            Err(why) => Standing::Foreign(why),
        };
    }
    // No run.toml: shards only. A listed table not there yet is no user's file (shards write
    // their run file first, and run concurrently); a changed one is.
    let mut ours: std::collections::HashSet<String> = std::collections::HashSet::new();
    for n in names.iter().filter(|n| is_shard_record(n)) {
        let m = match read_record(dir, n) {
            Ok(m) => m,
            Err(why) => return Standing::Foreign(why),
        };
        for l in &m.files {
            match verify(dir, l, n) {
                Ok(()) => {}
                Err(_) if spot(dir, &l.path).is_ok_and(|s| s == Spot::Absent) => {}
                Err(why) => return Standing::Foreign(why),
            }
            ours.insert(l.path.split('/').next().unwrap_or_default().to_string());
        }
        ours.insert(n.clone());
    }
    match names.iter().find(|n| !ours.contains(*n) && !is_writer_temporary(n)) {
        None => Standing::Shards,
        Some(first) => Standing::Foreign(format!(
            "holds files tribofe did not write (e.g. '{}'; no run.toml of a previous tribofe run lists it)",
            crate::error::quote(first)
        )),
    }
}

/// Whether `dir` is a folder tribofe wrote, by record ([`standing`]): a `run.toml` whose
/// manifest matches, or only verified sweep shards.
pub fn is_tribofe_folder(dir: &Path) -> bool {
    matches!(standing(dir), Standing::Tribofe(_) | Standing::Shards)
}

/// Refuses an output path that cannot become a folder (an existing file, a symbolic link, no
/// final name) and, unless `force`, an existing folder that holds anything and is not
/// tribofe's by record ([`standing`]), before any work. Removes the orphaned temporaries of
/// killed runs on that folder ([`remove_orphans`]).
pub fn check(out: &Path, force: bool) -> Result<()> {
    let bad = |why: String| Err(Error::Output { path: out.to_path_buf(), why });
    if out.file_name().is_none() {
        return bad("has no final name (use e.g. out/check)".into());
    }
    remove_orphans(out);
    if let Some(why) = locked_on_the_way(out) {
        return bad(why);
    }
    match std::fs::symlink_metadata(out) {
        Ok(m) if m.is_dir() => {
            if force {
                return Ok(());
            }
            match standing(out) {
                Standing::Foreign(why) => bad(format!(
                    "is not a folder of tribofe's by its record: it {why}. Give --force to write into \
                     it anyway (only files of this run's names are replaced; nothing else is \
                     deleted), or choose another --out"
                )),
                _ => Ok(()),
            }
        }
        Ok(m) if m.file_type().is_symlink() => {
            if out.is_dir() {
                bad("is a symbolic link; give the folder it points to (tribofe does not write through a link)".into())
            } else {
                bad("is a symbolic link to nothing or to a file; remove it or choose another --out".into())
            }
        }
        Ok(_) => bad("is an existing file, not a folder; remove it or choose another --out".into()),
        Err(_) => Ok(()),
    }
}

/// Why the run could not clean up after itself or replace its files, if so: the folder that
/// holds `out`, `out` itself or a file its run.toml lists is immutable or append-only
/// (`chattr +i`/`+a`, which stop root too). In an append-only parent the temporary folder
/// could be made but never removed (nor renamed into place): it stayed as a hidden
/// `.<name>.tmp-<pid>` that no later run could remove either. In a locked `out` the commit
/// failed half-way, some files new and some old.
fn locked_on_the_way(out: &Path) -> Option<String> {
    let parent = out.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    let show = |p: &Path| crate::error::quote(&p.display().to_string());
    if let Some(what) = locked(parent) {
        return Some(format!(
            "cannot hold this run's temporary folder: the folder '{}' that holds it is {what}, so the hidden temporary '.<name>.tmp-<pid>' could be neither removed nor renamed into place; nothing was written (remove the attribute with chattr, or choose another --out)",
            show(parent)
        ));
    }
    if !std::fs::symlink_metadata(out).is_ok_and(|m| m.is_dir()) {
        return None;
    }
    if let Some(what) = locked(out) {
        return Some(format!(
            "is {what}: this run's files could not be put in place or the previous run's replaced; nothing was written (remove the attribute with chattr, or choose another --out)"
        ));
    }
    let listed = read_record(out, RUN_FILE).map(|m| m.files).unwrap_or_default();
    let names = listed.iter().map(|l| l.path.as_str()).chain([RUN_FILE]);
    for rel in names.filter(|rel| spot(out, rel).is_ok_and(|s| s == Spot::Regular)) {
        if let Some(what) = locked(&out.join(rel)) {
            return Some(format!(
                "holds '{}', a file of the previous run, which is {what}: it could not be replaced or removed; nothing was written (remove the attribute with chattr, or choose another --out)",
                crate::error::quote(rel)
            ));
        }
    }
    None
}

/// Whether `path` is immutable or append-only (the inode flags of `chattr`); None where the
/// file system has no such flags or they cannot be read.
#[cfg(target_os = "linux")]
fn locked(path: &Path) -> Option<&'static str> {
    use std::os::unix::fs::OpenOptionsExt;
    use std::os::unix::io::AsRawFd;
    // linux/fs.h: FS_IMMUTABLE_FL, FS_APPEND_FL.
    const IMMUTABLE: libc::c_long = 0x10;
    const APPEND: libc::c_long = 0x20;
    // Followed if a link: the callers pass a real folder or file, or the parent as given.
    let f = std::fs::OpenOptions::new().read(true).custom_flags(libc::O_NONBLOCK).open(path).ok()?;
    let mut flags: libc::c_long = 0;
    // SAFETY: FS_IOC_GETFLAGS writes the inode's flags (an int) into `flags`, a valid long.
    if unsafe { libc::ioctl(f.as_raw_fd(), libc::FS_IOC_GETFLAGS, &mut flags) } != 0 {
        return None;
    }
    if flags & IMMUTABLE != 0 {
        Some("immutable (chattr +i)")
    } else if flags & APPEND != 0 {
        Some("append-only (chattr +a)")
    } else {
        None
    }
}

#[cfg(not(target_os = "linux"))]
fn locked(_: &Path) -> Option<&'static str> {
    None
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
    // Inside a tribofe folder (sweep shards, files renamed in across file systems): the files
    // `.<file>.<pid>.tmp` of a killed writer.
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

/// The refusal of targets a run would write over: the user's files (or folders, links,
/// special files) at names this run writes.
fn clash_error(out: &Path, clashes: &[(String, &'static str)], force: bool) -> Error {
    let shown: Vec<String> =
        clashes.iter().take(5).map(|(p, what)| format!("'{}' ({what})", crate::error::quote(p))).collect();
    let more = if clashes.len() > 5 { format!(" and {} more", clashes.len() - 5) } else { String::new() };
    let how = if force {
        "move or rename it (--force replaces regular files only)"
    } else {
        "move or rename it, or give --force to replace a regular file"
    };
    Error::Output {
        path: out.to_path_buf(),
        why: format!(
            "holds {}{more}, which tribofe did not write (no run.toml lists it), where this run \
             writes a file of that name: {how}; nothing was written",
            shown.join(", ")
        ),
    }
}

/// The targets among `names` in `out` that a run may not write over: absent is free; a
/// regular file is free when `ours` says tribofe wrote it or `force`; a folder, link or
/// special file never is.
fn clashes(
    out: &Path,
    names: &[&str],
    force: bool,
    ours: impl Fn(&str) -> bool,
) -> Result<Vec<(String, &'static str)>> {
    let mut found = Vec::new();
    for &rel in names {
        match spot(out, rel).map_err(|e| Error::io(out.join(rel), e))? {
            Spot::Absent => {}
            Spot::Regular if force || ours(rel) => {}
            Spot::Regular => found.push((rel.to_string(), "a file")),
            Spot::Blocked(at, what) => found.push((at, what)),
        }
    }
    Ok(found)
}

/// Writes `files` (name in `out`, bytes) and their run file `record` (its `text` with the
/// manifest appended) straight into the folder `out`, each by its own temporary and rename,
/// the run file first: how the shards of one sweep share a folder, written concurrently.
/// Never writes over a file that is not this record's own (a rerun of the same shard) unless
/// `force`, and never over a folder, link or special file. `write` writes one file whole (a
/// temporary and a rename: `report::write_atomic`, which sits above this layer).
pub fn write_in_place(
    out: &Path,
    force: bool,
    record: &str,
    text: &str,
    files: &[(&str, &[u8])],
    write: impl Fn(&Path, &[u8]) -> Result<()>,
) -> Result<()> {
    check(out, force)?;
    std::fs::create_dir_all(out).map_err(|e| Error::io(out, e))?;
    let previous = read_record(out, record).ok();
    // A rerun of the same shard: its own run file, and its files still as recorded.
    let ours = |rel: &str| {
        previous.as_ref().is_some_and(|m| {
            rel == record || m.files.iter().any(|l| l.path == rel && verify(out, l, record).is_ok())
        })
    };
    let mut names: Vec<&str> = files.iter().map(|f| f.0).collect();
    names.push(record);
    let found = clashes(out, &names, force, ours)?;
    if !found.is_empty() {
        return Err(clash_error(out, &found, force));
    }
    let mut body = text.to_string();
    if !body.ends_with('\n') {
        body.push('\n');
    }
    body.push('\n');
    body.push_str(&Manifest::of_bytes(files).to_toml()?);
    write(&out.join(record), body.as_bytes())?;
    for (name, bytes) in files {
        write(&out.join(name), bytes)?;
    }
    Ok(())
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
            out: out.to_path_buf(),
            state: Mutex::new((Stage::Writing, 0)),
            idle: Condvar::new(),
        });
        GATES.lock().unwrap_or_else(|e| e.into_inner()).push(gate.clone());
        Ok(OutDir { out: out.to_path_buf(), tmp, gate, force })
    }

    /// The handle that removes this folder from another thread ([`Cleanup`]).
    pub fn cleanup(&self) -> Cleanup {
        Cleanup(self.gate.clone())
    }

    /// Where the files go until [`OutDir::commit`].
    pub fn path(&self) -> &Path {
        &self.tmp
    }

    /// Lists the new files in `run.toml` and puts them in place (see the module's doc): the
    /// previous run's files by record are replaced or removed, nothing else in the folder is.
    pub fn commit(self) -> Result<()> {
        let gate = self.gate.clone();
        gate.exclusive(|stage| self.swap_in(stage))
    }

    fn swap_in(&self, stage: &mut Stage) -> Result<()> {
        if *stage != Stage::Writing {
            return Err(Error::Interrupted);
        }
        let mut files = Vec::new();
        list_files(&self.tmp, "", &mut files).map_err(|e| Error::io(&self.tmp, e))?;
        files.retain(|f| f != RUN_FILE);
        files.sort();
        self.seal_run_file(&files)?;
        let err = |e| Error::io(&self.out, e);
        match std::fs::symlink_metadata(&self.out) {
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                match rename_noreplace(&self.tmp, &self.out) {
                    Ok(()) => {
                        *stage = Stage::Committed;
                        return Ok(());
                    }
                    // Made meanwhile by someone else: into it file by file, as into any folder.
                    Err(e) if matches!(e.raw_os_error(), Some(libc::EEXIST) | Some(libc::ENOTEMPTY)) => {}
                    Err(e) => return Err(err(e)),
                }
            }
            Err(e) => return Err(err(e)),
            Ok(_) => {}
        }
        // The previous run's files, by its record (none in an empty or shards-only folder).
        let old = match standing(&self.out) {
            Standing::Tribofe(m) => Some(m.files),
            Standing::Foreign(why) if !self.force => {
                return Err(Error::Output {
                    path: self.out.clone(),
                    why: format!(
                        "changed during the run: it {why}; nothing was written (give --force, or \
                         choose another --out)"
                    ),
                })
            }
            _ => None,
        };
        let listed: std::collections::HashSet<&str> = old.iter().flatten().map(|l| l.path.as_str()).collect();
        let mut names: Vec<&str> = files.iter().map(String::as_str).collect();
        names.push(RUN_FILE);
        let found = clashes(&self.out, &names, self.force, |rel| {
            listed.contains(rel) || (rel == RUN_FILE && old.is_some())
        })?;
        if !found.is_empty() {
            return Err(clash_error(&self.out, &found, self.force));
        }
        for rel in &files {
            move_file(&self.tmp.join(rel), &self.out.join(rel))?;
        }
        // The previous run's files this one does not write, if still as recorded.
        let new: std::collections::HashSet<&str> = files.iter().map(String::as_str).collect();
        for l in old.iter().flatten().filter(|l| !new.contains(l.path.as_str())) {
            if verify(&self.out, l, RUN_FILE).is_ok() && std::fs::remove_file(self.out.join(&l.path)).is_ok()
            {
                // Its folders too, when nothing else is left in them.
                let mut p = Path::new(&l.path).parent();
                while let Some(d) = p.filter(|d| !d.as_os_str().is_empty()) {
                    if std::fs::remove_dir(self.out.join(d)).is_err() {
                        break;
                    }
                    p = d.parent();
                }
            }
        }
        // Last: from here the manifest matches the folder again.
        move_file(&self.tmp.join(RUN_FILE), &self.out.join(RUN_FILE))?;
        *stage = Stage::Committed;
        let _ = std::fs::remove_dir_all(&self.tmp);
        Ok(())
    }

    /// Appends the manifest of `files` (paths in the temporary folder) to its run.toml (made
    /// with the marker alone if the command wrote none).
    fn seal_run_file(&self, files: &[String]) -> Result<()> {
        let mut list = Vec::with_capacity(files.len());
        for rel in files {
            let path = self.tmp.join(rel);
            let (size, sha256) = hash_file(&path).map_err(|e| Error::io(&path, e))?;
            list.push(Listed { path: rel.clone(), size, sha256 });
        }
        let manifest = Manifest { algorithm: HASH_ALGORITHM.into(), files: list };
        let path = self.tmp.join(RUN_FILE);
        let mut text = match std::fs::read_to_string(&path) {
            Ok(t) => t,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                format!("{RUN_FILE_MARKER} {}; the provenance of this folder\n", env!("CARGO_PKG_VERSION"))
            }
            Err(e) => return Err(Error::io(&path, e)),
        };
        if !text.ends_with('\n') {
            text.push('\n');
        }
        text.push('\n');
        text.push_str(&manifest.to_toml()?);
        std::fs::write(&path, text).map_err(|e| Error::io(&path, e))
    }
}

/// The regular files under `dir`, as `/`-separated paths after `prefix`.
fn list_files(dir: &Path, prefix: &str, out: &mut Vec<String>) -> std::io::Result<()> {
    for e in std::fs::read_dir(dir)? {
        let e = e?;
        let name = e.file_name().to_string_lossy().into_owned();
        let rel = if prefix.is_empty() { name } else { format!("{prefix}/{name}") };
        let t = e.file_type()?;
        if t.is_dir() {
            list_files(&e.path(), &rel, out)?;
        } else if t.is_file() {
            out.push(rel);
        }
    }
    Ok(())
}

/// Renames `from` to `to` (their folders made); across file systems (`--out` a mount point)
/// by a copy to a hidden temporary beside `to`, then a rename.
fn move_file(from: &Path, to: &Path) -> Result<()> {
    if let Some(p) = to.parent() {
        std::fs::create_dir_all(p).map_err(|e| Error::io(p, e))?;
    }
    match std::fs::rename(from, to) {
        Ok(()) => Ok(()),
        Err(e) if e.raw_os_error() == Some(libc::EXDEV) => {
            let name = to.file_name().unwrap_or_default().to_string_lossy();
            let tmp = to.with_file_name(format!(".{name}.{}.tmp", std::process::id()));
            let res = std::fs::copy(from, &tmp)
                .and_then(|_| std::fs::File::open(&tmp)?.sync_all())
                .and_then(|_| std::fs::rename(&tmp, to));
            res.map_err(|e| {
                let _ = std::fs::remove_file(&tmp);
                Error::io(to, e)
            })
        }
        Err(e) => Err(Error::io(to, e)),
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

/// Renames `a` to `b` unless `b` exists (Linux renameat2 RENAME_NOREPLACE).
#[cfg(target_os = "linux")]
pub fn rename_noreplace(a: &Path, b: &Path) -> std::io::Result<()> {
    use std::os::unix::ffi::OsStrExt;
    let c = |p: &Path| std::ffi::CString::new(p.as_os_str().as_bytes()).map_err(std::io::Error::other);
    let (ca, cb) = (c(a)?, c(b)?);
    // SAFETY: both are valid NUL-terminated paths; the call only renames.
    let r = unsafe {
        libc::renameat2(libc::AT_FDCWD, ca.as_ptr(), libc::AT_FDCWD, cb.as_ptr(), libc::RENAME_NOREPLACE)
    };
    if r == 0 {
        Ok(())
    } else {
        Err(std::io::Error::last_os_error())
    }
}

/// Without renameat2: refuses an existing `b`, then renames (a short race remains).
#[cfg(not(target_os = "linux"))]
pub fn rename_noreplace(a: &Path, b: &Path) -> std::io::Result<()> {
    if std::fs::symlink_metadata(b).is_ok() {
        return Err(std::io::Error::from_raw_os_error(libc::EEXIST));
    }
    std::fs::rename(a, b)
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

    /// A commit into an existing folder: the listed files replaced, a stale listed one
    /// removed, the user's entries (one written while the run was under way) kept.
    #[test]
    fn a_commit_replaces_listed_files_only() {
        let d = tempfile::tempdir().unwrap();
        let out = d.path().join("o");
        let first = OutDir::begin(&out, false).unwrap();
        std::fs::write(first.path().join("a.csv"), "1\n").unwrap();
        std::fs::create_dir(first.path().join("sub")).unwrap();
        std::fs::write(first.path().join("sub/b.csv"), "2\n").unwrap();
        first.commit().unwrap();
        assert!(matches!(standing(&out), Standing::Tribofe(ref m) if m.files.len() == 2));
        let second = OutDir::begin(&out, false).unwrap();
        std::fs::write(second.path().join("a.csv"), "3\n").unwrap();
        std::fs::write(out.join("note"), "mine").unwrap();
        second.commit().unwrap();
        assert_eq!(std::fs::read_to_string(out.join("a.csv")).unwrap(), "3\n");
        assert!(!out.join("sub").exists(), "the stale listed file and its emptied folder go");
        assert_eq!(std::fs::read_to_string(out.join("note")).unwrap(), "mine");
        assert!(matches!(standing(&out), Standing::Tribofe(ref m) if m.files.len() == 1));
    }

    /// A manifest naming a path outside the folder (or the run file) is no manifest: a
    /// crafted run.toml cannot make tribofe remove a file elsewhere.
    #[test]
    fn manifests_with_paths_outside_the_folder_are_refused() {
        let h = "0".repeat(64);
        for path in ["../x", "/etc/passwd", "a/../../x", "", "run.toml"] {
            let text = format!(
                "{RUN_FILE_MARKER}\n[manifest]\nalgorithm = \"sha256\"\n[[manifest.files]]\npath = \"{path}\"\nsize = 0\nsha256 = \"{h}\"\n"
            );
            assert!(Manifest::of_run_file(&text, RUN_FILE).is_none(), "{path:?}");
        }
        let ok = format!(
            "{RUN_FILE_MARKER}\n[manifest]\nalgorithm = \"sha256\"\n[[manifest.files]]\npath = \"a/b.csv\"\nsize = 0\nsha256 = \"{h}\"\n"
        );
        assert!(Manifest::of_run_file(&ok, RUN_FILE).is_some());
    }
}
