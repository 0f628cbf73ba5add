//! Output files: CSV tables, SVG charts, field files. Every file is written to a temporary
//! name in the same directory and renamed, so a failure never leaves a partial result.

pub mod check;
pub mod convergence;
pub mod precursors;
pub mod slide;
pub mod stability;
pub mod sweep;

use crate::{Error, Result};
use std::io::Write;
use std::path::Path;

/// Writes `bytes` to a temporary file next to `path`, then renames it over `path`, so a
/// failure never leaves a partly written file. Creates missing parent directories; the
/// temporary file is removed on failure.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    let name = path
        .file_name()
        .ok_or_else(|| Error::input(format!("output path {}", path.display()), "has no file name"))?;
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    }
    let tmp = path.with_file_name(format!(".{}.{}.tmp", name.to_string_lossy(), std::process::id()));
    let res = std::fs::File::create(&tmp)
        .and_then(|mut f| f.write_all(bytes).and_then(|_| f.sync_all()))
        .and_then(|_| std::fs::rename(&tmp, path));
    res.map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        Error::io(path, e)
    })
}

/// Passes `v` through if finite: guards every number written to a file against NaN and infinities.
pub(crate) fn finite(what: &str, v: f64) -> Result<f64> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(Error::input(what, format!("{v} is not a finite number; refusing to write it")))
    }
}

/// CSV text from a header and rows; refuses non-finite numbers (never writes NaN).
pub fn csv(header: &str, rows: &[Vec<f64>]) -> Result<String> {
    let mut s = String::with_capacity(rows.len() * 16 * 8);
    s.push_str(header);
    s.push('\n');
    for (i, r) in rows.iter().enumerate() {
        let cells: Result<Vec<String>> = r
            .iter()
            .map(|&v| finite(&format!("row {} of '{header}'", i + 1), v).map(|v| format!("{v:.12e}")))
            .collect();
        s.push_str(&cells?.join(","));
        s.push('\n');
    }
    Ok(s)
}

/// Formats an F/N ratio as in file names: `0`, `0.41`, `0.82`.
pub fn ratio_label(r: f64) -> String {
    format!("{r}")
}
