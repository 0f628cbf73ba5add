//! `run.toml`, the provenance of an output folder: what produced it (tribofe's version and
//! source revision, the date, the host, the full command line and every option), the
//! effective scene, and the command's own key figures. One function writes it for every
//! command; its marker line also tells [`crate::io::outdir`] that the folder is tribofe's.

use crate::io::outdir::RUN_FILE_MARKER;
use crate::{Error, Result};
use serde::Serialize;

/// How the command was invoked: the arguments as typed and every option's effective value
/// (given or default), by option name. Built by the command-line front end.
#[derive(Debug, Clone, Default)]
pub struct Invocation {
    pub args: Vec<String>,
    pub options: toml::Table,
}

/// The `[tribofe]` table.
#[derive(Serialize)]
struct Provenance {
    version: &'static str,
    #[serde(skip_serializing_if = "Option::is_none")]
    revision: Option<&'static str>,
    #[serde(skip_serializing_if = "Option::is_none")]
    revision_dirty: Option<bool>,
    date_utc: String,
    #[serde(skip_serializing_if = "Option::is_none")]
    host: Option<String>,
    command: String,
    arguments: Vec<String>,
}

/// The text of `run.toml`: the marker line, `[tribofe]`, `[options]` (every option),
/// `[results]` (the command's figures: loads, coefficients...) and the effective scene under
/// `[scene.*]` (a scene file that reproduces the run) when the command has one.
pub fn run_toml<R: Serialize>(
    inv: &Invocation,
    scene: Option<&crate::scene::Scene>,
    results: &R,
) -> Result<String> {
    #[derive(Serialize)]
    struct Run<'a> {
        /// A mesh of the file's own shape: no verdict against the paper's model describes it.
        #[serde(skip_serializing_if = "Option::is_none")]
        geometry: Option<&'static str>,
        tribofe: Provenance,
        options: &'a toml::Table,
        /// Plane strain or stress, the width b, and what the forces are per.
        #[serde(skip_serializing_if = "Option::is_none")]
        out_of_plane: Option<OutOfPlane>,
        results: &'a toml::Value,
        #[serde(skip_serializing_if = "Option::is_none")]
        scene: Option<&'a crate::scene::Scene>,
    }
    let file_shape = scene.is_some_and(|s| s.mesh.geometry == crate::scene::MeshGeometry::File);
    let mut results = toml::Value::try_from(results).map_err(|e| Error::input("run.toml", e.to_string()))?;
    let out_of_plane = scene.map(|s| OutOfPlane {
        state: s.block.state.name(),
        width_m: s.block.width,
        forces: if s.block.width.is_some() {
            "per unit width (N/m) in the tables; each *_N_per_m result has a *_newtons twin, times width_m"
        } else {
            "per unit width (N/m)"
        },
    });
    if let Some(b) = scene.and_then(|s| s.block.width) {
        add_newtons(&mut results, b);
    }
    let results = &results;
    let run = Run {
        geometry: file_shape.then_some(crate::scene::FILE_GEOMETRY_NOTE),
        tribofe: Provenance {
            version: env!("CARGO_PKG_VERSION"),
            revision: option_env!("TRIBOFE_GIT_REVISION"),
            revision_dirty: option_env!("TRIBOFE_GIT_DIRTY").map(|d| d == "true"),
            date_utc: iso8601_utc(std::time::SystemTime::now()),
            host: host_name(),
            command: inv.args.iter().map(|a| shell_word(a)).collect::<Vec<_>>().join(" "),
            arguments: inv.args.clone(),
        },
        options: &inv.options,
        out_of_plane,
        results,
        scene,
    };
    let value = toml::Value::try_from(&run).map_err(|e| Error::input("run.toml", e.to_string()))?;
    refuse_non_finite(&value, "run.toml")?;
    let body = toml::to_string(&run).map_err(|e| Error::input("run.toml", e.to_string()))?;
    Ok(format!("{RUN_FILE_MARKER} {}; the provenance of this folder\n{body}", env!("CARGO_PKG_VERSION")))
}

#[derive(Serialize)]
struct OutOfPlane {
    state: &'static str,
    #[serde(skip_serializing_if = "Option::is_none")]
    width_m: Option<f64>,
    forces: &'static str,
}

/// Beside every `*_n_per_m` number in `v`, its `*_newtons` over the width `b` (m).
fn add_newtons(v: &mut toml::Value, b: f64) {
    match v {
        toml::Value::Table(t) => {
            let twins: Vec<(String, toml::Value)> = t
                .iter()
                .filter_map(|(k, x)| {
                    // Either spelling of the unit: n_force_n_per_m, n_force_N_per_m.
                    let stem = k
                        .len()
                        .checked_sub(8)
                        .filter(|&i| k.is_char_boundary(i) && k[i..].eq_ignore_ascii_case("_n_per_m"))
                        .map(|i| &k[..i])?;
                    Some((format!("{stem}_newtons"), toml::Value::Float(x.as_float()? * b)))
                })
                .collect();
            for (_, x) in t.iter_mut() {
                add_newtons(x, b);
            }
            t.extend(twins);
        }
        toml::Value::Array(a) => a.iter_mut().for_each(|x| add_newtons(x, b)),
        _ => {}
    }
}

/// Refuses a NaN or infinite number anywhere in `v` (`at` names the key).
fn refuse_non_finite(v: &toml::Value, at: &str) -> Result<()> {
    match v {
        toml::Value::Float(x) if !x.is_finite() => {
            Err(Error::input(at, format!("{x} is not a finite number; refusing to write it")))
        }
        toml::Value::Array(a) => a.iter().try_for_each(|x| refuse_non_finite(x, at)),
        toml::Value::Table(t) => t.iter().try_for_each(|(k, x)| refuse_non_finite(x, &format!("{at}: {k}"))),
        _ => Ok(()),
    }
}

/// Writes [`run_toml`] as `dir/run.toml`.
pub fn write<R: Serialize>(
    dir: &std::path::Path,
    inv: &Invocation,
    scene: Option<&crate::scene::Scene>,
    results: &R,
) -> Result<()> {
    super::write_atomic(&dir.join(crate::io::outdir::RUN_FILE), run_toml(inv, scene, results)?.as_bytes())
}

/// No results beyond the files: an empty `[results]` table.
#[derive(Serialize)]
pub struct NoResults {}

/// `a` as one POSIX shell word: bare when it holds only plain characters, else in single
/// quotes; control characters are written as `$'\xNN'` so the line stays one printable line.
pub fn shell_word(a: &str) -> String {
    if !a.is_empty() && a.chars().all(|c| c.is_ascii_alphanumeric() || "-_./,:=+@%".contains(c)) {
        return a.to_string();
    }
    let mut out = String::from("'");
    for c in a.chars() {
        match c {
            '\'' => out.push_str("'\\''"),
            c if c.is_control() => {
                let mut buf = [0u8; 4];
                out.push('\'');
                for b in c.encode_utf8(&mut buf).bytes() {
                    out.push_str(&format!("$'\\x{b:02x}'"));
                }
                out.push('\'');
            }
            c => out.push(c),
        }
    }
    out.push('\'');
    out
}

/// `t` as `YYYY-MM-DDTHH:MM:SSZ` (UTC), from the days since 1970 (Hinnant's civil-from-days).
pub fn iso8601_utc(t: std::time::SystemTime) -> String {
    let secs = t.duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.as_secs()) as i64;
    let (days, rem) = (secs.div_euclid(86_400), secs.rem_euclid(86_400));
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!("{year:04}-{month:02}-{day:02}T{:02}:{:02}:{:02}Z", rem / 3600, rem % 3600 / 60, rem % 60)
}

/// The machine's host name, if the system gives one.
fn host_name() -> Option<String> {
    let mut buf = [0u8; 256];
    // SAFETY: gethostname writes at most buf.len() bytes into buf.
    let r = unsafe { libc::gethostname(buf.as_mut_ptr().cast(), buf.len()) };
    if r != 0 {
        return None;
    }
    let end = buf.iter().position(|&b| b == 0).unwrap_or(buf.len());
    let name = String::from_utf8_lossy(&buf[..end]).into_owned();
    (!name.is_empty()).then_some(name)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::{Duration, UNIX_EPOCH};

    #[test]
    fn dates_match_known_instants() {
        assert_eq!(iso8601_utc(UNIX_EPOCH), "1970-01-01T00:00:00Z");
        // 2000-02-29 12:34:56 UTC: a leap day of a century leap year.
        assert_eq!(iso8601_utc(UNIX_EPOCH + Duration::from_secs(951_827_696)), "2000-02-29T12:34:56Z");
        // 2026-11-25 00:00:00 UTC.
        assert_eq!(iso8601_utc(UNIX_EPOCH + Duration::from_secs(1_795_564_800)), "2026-11-25T00:00:00Z");
    }

    #[test]
    fn shell_words_quote_spaces_quotes_and_control_bytes() {
        assert_eq!(shell_word("--out"), "--out");
        assert_eq!(shell_word("a b"), "'a b'");
        assert_eq!(shell_word("it's"), "'it'\\''s'");
        assert_eq!(shell_word("a\u{1b}b"), "'a'$'\\x1b''b'");
        assert_eq!(shell_word(""), "''");
    }

    #[test]
    fn run_file_parses_back_with_its_marker_and_tables() {
        let mut options = toml::Table::new();
        options.insert("out".into(), toml::Value::String("x".into()));
        let inv = Invocation { args: vec!["tribofe".into(), "check".into()], options };
        let text = run_toml(&inv, Some(&crate::scene::Scene::default()), &NoResults {}).unwrap();
        assert!(text.starts_with(RUN_FILE_MARKER));
        let v: toml::Table = text.parse().unwrap();
        assert_eq!(v["tribofe"]["version"].as_str(), Some(env!("CARGO_PKG_VERSION")));
        assert_eq!(v["tribofe"]["command"].as_str(), Some("tribofe check"));
        assert_eq!(v["options"]["out"].as_str(), Some("x"));
        assert!(v["scene"]["block"].is_table());
    }
}
