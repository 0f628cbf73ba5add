//! The size limit: unknowns a run may have, carried by the scene (`mesh.max_dofs`,
//! `--max-dofs`) rather than by process-wide state, so two runs in one process can differ.

use crate::error::{Error, Result};

/// Memory one unknown of the check costs, bytes: 2.3 GB for 1.6e6 unknowns measured on
/// `tribofe check --thickness 2` (issue 16), rounded up.
pub const BYTES_PER_DOF: f64 = 1500.0;

/// Default ceiling whatever the memory: a check above it takes tens of seconds and writes
/// gigabytes of fields; larger runs are deliberate (`--max-dofs`), not a slip of units.
pub const DEFAULT_MAX_DOFS_CAP: usize = 1_500_000;

/// Half the memory this process may use ([`memory_bytes`]) over [`BYTES_PER_DOF`], at most
/// [`DEFAULT_MAX_DOFS_CAP`].
pub fn default_max_dofs() -> usize {
    ((0.5 * memory_bytes().0 / BYTES_PER_DOF) as usize).min(DEFAULT_MAX_DOFS_CAP)
}

/// This machine's memory, bytes (`MemTotal` of /proc/meminfo, 8 GiB where unknown).
pub fn total_bytes() -> f64 {
    std::fs::read_to_string("/proc/meminfo")
        .ok()
        .and_then(|s| {
            let line = s.lines().find(|l| l.starts_with("MemTotal:"))?.to_owned();
            line.split_whitespace().nth(1)?.parse::<f64>().ok().map(|kib| kib * 1024.0)
        })
        .unwrap_or(8.0 * (1u64 << 30) as f64)
}

/// The memory this process may use, bytes, and where that bound comes from: the smallest of
/// the machine's memory, the process limits RLIMIT_AS and RLIMIT_DATA (`ulimit -v`, `-d`)
/// and the memory.max of the process's cgroup (v2; memory.limit_in_bytes on v1). A run sized
/// by the machine alone would abort in the allocator under a tighter limit (issue 31).
pub fn memory_bytes() -> (f64, &'static str) {
    let mut best = (total_bytes(), "this machine's memory");
    let mut take = |b: Option<f64>, what: &'static str| {
        if let Some(b) = b.filter(|b| *b > 0.0 && *b < best.0) {
            best = (b, what);
        }
    };
    // Under a process limit, the threads' fixed reserves are not the run's to use: the workers'
    // and the main thread's packing buffers ([`THREAD_RESERVE_BYTES`]).
    let reserve = THREAD_RESERVE_BYTES * (rayon::current_num_threads() + 1) as f64;
    let room = |b: Option<f64>| b.map(|b| (b - reserve).max(1.0));
    take(room(rlimit(Rlim::As)), "the process limit RLIMIT_AS (ulimit -v, less the threads' reserves)");
    take(room(rlimit(Rlim::Data)), "the process limit RLIMIT_DATA (ulimit -d, less the threads' reserves)");
    take(cgroup_max(), "the cgroup's memory limit");
    best
}

/// Address space a thread reserves for good beyond its stack: glibc's malloc arena
/// (HEAP_MAX_SIZE, 64 MiB on 64-bit) and the dense products' packing buffer (private_gemm's,
/// 64 MiB, allocated at a thread's first product and kept).
pub const THREAD_RESERVE_BYTES: f64 = 64.0 * (1u64 << 20) as f64;

/// The smaller finite one of RLIMIT_AS and RLIMIT_DATA, bytes.
fn process_limit() -> Option<f64> {
    [rlimit(Rlim::As), rlimit(Rlim::Data)].into_iter().flatten().reduce(f64::min)
}

/// Under a process limit, the worker threads whose reserves ([`THREAD_RESERVE_BYTES`] each)
/// fit in a quarter of it (at least 1, at most the cores); None without a limit. Runs of
/// 20-70 MB aborted in the allocator (status 134) under limits of 100-400 MB: two workers,
/// the main thread and their 64 MiB buffers took the room the guard had counted on.
pub fn worker_threads() -> Option<usize> {
    let limit = process_limit()?;
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    Some(((0.25 * limit / THREAD_RESERVE_BYTES) as usize).clamp(1, cores))
}

/// Caps glibc's malloc arenas to fit the process limit: glibc gives threads that allocate at
/// once arenas of their own (up to 8 per core), each reserving [`THREAD_RESERVE_BYTES`] of
/// address space, which RLIMIT_AS counts. With a finite RLIMIT_AS or RLIMIT_DATA the arenas
/// may reserve at most an eighth of it (at least one: the threads then share the main heap,
/// slower only when many allocate at once); without one nothing changes. Returns the cap set,
/// if any. Call it before threads start (the command's `main`, the Python module's import).
pub fn fit_malloc_arenas() -> Option<usize> {
    let arenas = ((process_limit()? / 8.0 / THREAD_RESERVE_BYTES) as usize).clamp(1, 64);
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    {
        // SAFETY: mallopt only sets an allocator parameter; M_ARENA_MAX takes any count >= 1.
        if unsafe { libc::mallopt(libc::M_ARENA_MAX, arenas as libc::c_int) } == 1 {
            return Some(arenas);
        }
    }
    let _ = arenas;
    None
}

enum Rlim {
    As,
    Data,
}

/// The soft limit, bytes; None when unlimited or unknown.
fn rlimit(which: Rlim) -> Option<f64> {
    #[cfg(unix)]
    {
        let res = match which {
            Rlim::As => libc::RLIMIT_AS,
            Rlim::Data => libc::RLIMIT_DATA,
        };
        let mut r = libc::rlimit { rlim_cur: 0, rlim_max: 0 };
        // SAFETY: getrlimit writes only into `r`, a valid rlimit.
        let ok = unsafe { libc::getrlimit(res, &mut r) } == 0;
        (ok && r.rlim_cur != libc::RLIM_INFINITY).then_some(r.rlim_cur as f64)
    }
    #[cfg(not(unix))]
    {
        let _ = which;
        None
    }
}

/// The process's cgroup memory limit, bytes: memory.max (v2) or memory.limit_in_bytes (v1)
/// of the cgroup named in /proc/self/cgroup; None where absent or "max".
fn cgroup_max() -> Option<f64> {
    let groups = std::fs::read_to_string("/proc/self/cgroup").ok()?;
    let read = |p: String| -> Option<f64> { std::fs::read_to_string(p).ok()?.trim().parse::<f64>().ok() };
    for line in groups.lines() {
        let mut f = line.splitn(3, ':');
        let (id, ctl, path) = (f.next()?, f.next()?, f.next()?);
        let found = if id == "0" && ctl.is_empty() {
            read(format!("/sys/fs/cgroup{path}/memory.max"))
        } else if ctl.split(',').any(|c| c == "memory") {
            // v1 reports "no limit" as a huge number, above the machine's memory.
            read(format!("/sys/fs/cgroup/memory{path}/memory.limit_in_bytes"))
        } else {
            None
        };
        if found.is_some() {
            return found;
        }
    }
    None
}

/// Largest `--max-dofs` accepted.
pub const MAX_DOFS_LIMIT: usize = 1_000_000_000_000;

/// The limit to apply: `limit` if given, else [`default_max_dofs`]; 0 is refused.
pub fn effective(limit: Option<usize>) -> Result<usize> {
    match limit {
        Some(0) => {
            Err(Error::input("--max-dofs (mesh.max_dofs)", "0: the limit must allow at least one unknown"))
        }
        // Far above any machine, and within what run.toml (a TOML integer, i64) can record.
        Some(n) if n > MAX_DOFS_LIMIT => Err(Error::input(
            "--max-dofs (mesh.max_dofs)",
            format!("{n}: at most {MAX_DOFS_LIMIT:e} unknowns (1.5 PB at {BYTES_PER_DOF} bytes each)"),
        )),
        Some(n) => Ok(n),
        None => Ok(default_max_dofs()),
    }
}

/// Refuses `dofs` estimated unknowns above the limit, with the memory they would take and
/// `suggestion` (what to change), given the factor by which the element size must grow to fit
/// (unknowns scale as 1/h^2).
pub fn check(dofs: f64, limit: Option<usize>, suggestion: impl FnOnce(f64) -> String) -> Result<()> {
    let limit = effective(limit)?;
    if dofs > limit as f64 {
        return Err(Error::TooLarge {
            dofs,
            gib: dofs * BYTES_PER_DOF / (1u64 << 30) as f64,
            limit,
            suggestion: suggestion((dofs / limit as f64).sqrt()),
        });
    }
    Ok(())
}

pub use crate::error::bytes_text;

/// Dense matrices of (2n + 3)^2 doubles a frictional run holds at once: the condensed S, its
/// copy at the drive height, the inverse of the free system and its spare, and one more (a
/// parallel study's clone).
pub const DENSE_COPIES: f64 = 5.0;

/// Refuses a frictional interface of `n` nodes whose dense condensed system would not fit in
/// half the memory this process may use ([`memory_bytes`]), naming the size and what to change.
pub fn check_interface(n: usize) -> Result<()> {
    let nd = (2 * n + 3) as f64;
    let need = DENSE_COPIES * nd * nd * 8.0;
    let (mem, source) = memory_bytes();
    let have = 0.5 * mem;
    if need > have {
        return Err(Error::input(
            "mesh.h (--h)",
            format!(
                "the frictional interface would have {n} nodes: its dense condensed system needs about {} ({DENSE_COPIES} matrices of (2n + 3)^2 doubles), above half of {source} ({}); make h along the interface {:.1}x larger or the block shorter",
                bytes_text(need),
                bytes_text(have),
                (need / have).sqrt()
            ),
        ));
    }
    Ok(())
}

/// Refuses a step that would hold about `need` bytes at once when that is above half the
/// memory this process may use ([`memory_bytes`]): refused before the allocation, with the
/// flag to change, instead of an abort in the allocator.
pub fn check_bytes(need: f64, flag: &str, what: &str, hint: &str) -> Result<()> {
    let (mem, source) = memory_bytes();
    if need > 0.5 * mem {
        return Err(Error::input(
            flag,
            format!(
                "{what} needs about {}, above half of {source} ({}); {hint}",
                bytes_text(need),
                bytes_text(mem)
            ),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::bytes_text;

    #[test]
    fn bytes_are_printed_in_the_unit_that_fits() {
        assert_eq!(bytes_text(10.7 * (1u64 << 30) as f64), "10.7 GiB");
        assert_eq!(bytes_text(9.24 * (1u64 << 20) as f64), "9.2 MiB");
        assert_eq!(bytes_text(1.0), "1 bytes");
        assert_eq!(bytes_text(4096.0), "4.0 KiB");
    }
}
