//! Output files: CSV tables, SVG charts, field files. Every file is written to a temporary
//! name in the same directory and renamed, so a failure never leaves a partial result.

// Without the `plots` feature the figures' inputs and helpers go unused by design.
#![cfg_attr(not(feature = "plots"), allow(unused))]

pub mod check;
pub mod convergence;
pub mod dynamic_slide;
pub mod edges;
#[cfg(feature = "plots")]
pub(crate) mod plot;
pub mod precursors;
pub mod run_file;
pub mod rupture;
pub mod slide;
pub mod spacetime;
pub mod stability;
pub mod sweep;
pub mod table;

use crate::{Error, Result};

/// Whether this build draws the SVG figures (the `plots` feature); without it the writers skip
/// them and write the tables alone.
pub const FIGURES: bool = cfg!(feature = "plots");
use std::io::Write;
use std::path::{Path, PathBuf};

/// Writes `bytes` to a temporary file next to `path`, then renames it over `path`, so a
/// failure never leaves a partly written file. Creates missing parent directories; the
/// temporary file is removed on failure.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    if path.extension().is_some_and(|e| e == "csv") {
        refuse_non_finite_cells(path, bytes)?;
    }
    let _writing = crate::io::outdir::write_guard(path)?;
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

/// The guard of every CSV file written: a cell that reads as NaN or an infinity is refused
/// (an error naming the file, line and column), never written as a result.
fn refuse_non_finite_cells(path: &Path, bytes: &[u8]) -> Result<()> {
    // Line by line as `str::lines` splits them; a line whose cells all surely parse finite
    // (or not at all) skips the parse (states.csv: 3e6 numbers).
    for (i, raw) in bytes.split(|&b| b == b'\n').enumerate() {
        let raw = raw.strip_suffix(b"\r").unwrap_or(raw);
        if raw.split(|&b| b == b',').all(crate::io::csv::surely_finite) {
            continue;
        }
        let line = String::from_utf8_lossy(raw);
        for (j, cell) in line.split(',').enumerate() {
            if cell.trim().parse::<f64>().is_ok_and(|v| !v.is_finite()) {
                return Err(Error::input(
                    format!("{} line {} column {}", path.display(), i + 1, j + 1),
                    format!("'{}' is not a finite number; refusing to write it as a result", cell.trim()),
                ));
            }
        }
    }
    Ok(())
}

/// `run.toml` ([`run_file::run_toml`]) with the command's figures `cases` under `[results]`:
/// `(name, value)` pairs as keys, a list of records as `[[results.cases]]`.
pub fn run_toml<C: serde::Serialize>(
    inv: &run_file::Invocation,
    cases: &C,
    scene: &crate::scene::Scene,
) -> Result<String> {
    let v = toml::Value::try_from(cases).map_err(|e| Error::input("run.toml", e.to_string()))?;
    let pair = |x: &toml::Value| match x.as_array().map(|a| &a[..]) {
        Some([toml::Value::String(k), v]) => Some((k.clone(), v.clone())),
        _ => None,
    };
    let results: toml::Table = match v {
        toml::Value::Table(t) => t,
        toml::Value::Array(a) if a.iter().all(|x| pair(x).is_some()) => a.iter().filter_map(pair).collect(),
        v => [("cases".to_string(), v)].into_iter().collect(),
    };
    run_file::run_toml(inv, Some(scene), &results)
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

/// Creates `dir` and its parents if missing.
pub(crate) fn ensure_dir(dir: &Path) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))
}

/// Writes each `(name, text)` into `dir` ([`write_atomic`]); returns the paths written.
pub(crate) fn write_all(dir: &Path, files: &[(&str, String)]) -> Result<Vec<PathBuf>> {
    files
        .iter()
        .map(|(name, body)| {
            let path = dir.join(name);
            write_atomic(&path, body.as_bytes()).map(|_| path)
        })
        .collect()
}

/// An optional CSV cell: the value, or empty.
pub(crate) fn opt<T: std::fmt::Display>(v: Option<T>) -> String {
    v.map_or(String::new(), |v| v.to_string())
}
