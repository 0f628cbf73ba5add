//! Output files: CSV tables, SVG charts, field files. Every file is written to a temporary
//! name in the same directory and renamed, so a failure never leaves a partial result.

pub mod check;

use crate::error::{Error, Result};
use std::path::Path;

/// Writes `bytes` to `path` atomically (temp file + rename), creating parent directories.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    }
    let tmp = path.with_extension(format!("{}.tmp", path.extension().and_then(|e| e.to_str()).unwrap_or("")));
    std::fs::write(&tmp, bytes).map_err(|e| Error::io(&tmp, e))?;
    std::fs::rename(&tmp, path).map_err(|e| Error::io(path, e))
}

/// CSV text from a header and rows; refuses non-finite numbers (never writes NaN).
pub fn csv(header: &str, rows: &[Vec<f64>]) -> Result<String> {
    let mut s = String::with_capacity(rows.len() * 16 * 8);
    s.push_str(header);
    s.push('\n');
    for (i, r) in rows.iter().enumerate() {
        if let Some(v) = r.iter().find(|v| !v.is_finite()) {
            return Err(Error::input("output", format!("row {} of table '{header}' holds {v}; refusing to write a non-finite result", i + 1)));
        }
        let cells: Vec<String> = r.iter().map(|v| format!("{v:.12e}")).collect();
        s.push_str(&cells.join(","));
        s.push('\n');
    }
    Ok(s)
}

/// Formats an F/N ratio as in file names: `0`, `0.41`, `0.82`.
pub fn ratio_label(r: f64) -> String {
    format!("{r}")
}
