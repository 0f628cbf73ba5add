//! The size limit: unknowns a run may have, carried by the scene (`mesh.max_dofs`,
//! `--max-dofs`) rather than by process-wide state, so two runs in one process can differ.

use crate::error::{Error, Result};

/// Memory one unknown of the check costs, bytes: 2.3 GB for 1.6e6 unknowns measured on
/// `tribofe check --thickness 2` (issue 16), rounded up.
pub const BYTES_PER_DOF: f64 = 1500.0;

/// Default ceiling whatever the memory: a check above it takes tens of seconds and writes
/// gigabytes of fields; larger runs are deliberate (`--max-dofs`), not a slip of units.
pub const DEFAULT_MAX_DOFS_CAP: usize = 1_500_000;

/// Half the machine's memory ([`total_bytes`]) over [`BYTES_PER_DOF`], at most
/// [`DEFAULT_MAX_DOFS_CAP`].
pub fn default_max_dofs() -> usize {
    ((0.5 * total_bytes() / BYTES_PER_DOF) as usize).min(DEFAULT_MAX_DOFS_CAP)
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

/// The limit to apply: `limit` if given, else [`default_max_dofs`]; 0 is refused.
pub fn effective(limit: Option<usize>) -> Result<usize> {
    match limit {
        Some(0) => {
            Err(Error::input("--max-dofs (mesh.max_dofs)", "0: the limit must allow at least one unknown"))
        }
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

/// Dense matrices of (2n + 3)^2 doubles a frictional run holds at once: the condensed S, its
/// copy at the drive height, the inverse of the free system and its spare, and one more (a
/// parallel study's clone).
pub const DENSE_COPIES: f64 = 5.0;

/// Refuses a frictional interface of `n` nodes whose dense condensed system would not fit in
/// half this machine's memory, naming the size and what to change.
pub fn check_interface(n: usize) -> Result<()> {
    let nd = (2 * n + 3) as f64;
    let need = DENSE_COPIES * nd * nd * 8.0;
    let have = 0.5 * total_bytes();
    if need > have {
        let gib = |b: f64| b / (1u64 << 30) as f64;
        return Err(Error::input(
            "mesh.h (--h)",
            format!(
                "the frictional interface would have {n} nodes: its dense condensed system needs about {:.1} GiB ({DENSE_COPIES} matrices of (2n + 3)^2 doubles), above half this machine's memory ({:.1} GiB); make h along the interface {:.1}x larger or the block shorter",
                gib(need),
                gib(have),
                (need / have).sqrt()
            ),
        ));
    }
    Ok(())
}
