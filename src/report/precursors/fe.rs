//! The FE fig. 4 (`precursors fe`): `summary.csv` (the model's row, then one per event rule),
//! the model's folder and one folder per rule.

use super::super::{ensure_dir, finite, write_all};
use super::{fe_values, field_values, FE_COLUMNS, FIELD_COLUMNS};
use crate::precursors::{Event, Params};
use crate::studies::precursors_fe::Fig4;
use crate::Result;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// `precursors --fe` into `dir`: `summary.csv` (the analytic iteration, then one row per rule
/// of [`crate::studies::precursors_fe::RULES`], `-` where a run was refused), `model/` (as
/// [`super::write_events`]) and a folder per rule (as [`crate::report::slide::write`], no states).
pub fn write_fe_fig4(
    dir: &Path,
    p: &Params,
    model: &[Event],
    runs: &[Result<Fig4>],
    inv: &crate::report::run_file::Invocation,
    scene: &crate::scene::Scene,
) -> Result<Vec<PathBuf>> {
    let n = crate::precursors::n_precursors(p)?;
    let x1 = model.first().map_or(f64::NAN, |e| e.x);
    let mut s = format!("source,{FE_COLUMNS},worst_violation_over_N_per_n,{FIELD_COLUMNS}\n");
    let _ = writeln!(
        s,
        "model,{n},{n},{n},{},{},{},,0,0,0,,-0.5",
        finite("F_1", p.f1())?,
        finite("x_1", x1)?,
        p.f_max()
    );
    let mut written = super::model::write_events(&dir.join("model"), p, model)?;
    for (rule, run) in crate::studies::precursors_fe::RULES.iter().zip(runs) {
        let name = rule.name();
        let Ok(r) = run else {
            let _ = writeln!(s, "{name},,,,,,,,,,,,");
            continue;
        };
        let _ =
            writeln!(s, "{name},{},{:e},{}", fe_values(&r.cmp), r.worst_violation, field_values(&r.fields));
        let sub = dir.join(name);
        ensure_dir(&sub)?;
        let law = r.run.options.law;
        let what =
            [("rule", name.to_string()), ("mu_s", law.mu_s().to_string()), ("mu_d", law.mu_d().to_string())];
        let header = crate::report::run_toml(inv, &what, scene)?;
        written.extend(crate::report::slide::write(&r.run, &sub, &header, false)?);
    }
    written.extend(write_all(dir, &[("summary.csv", s)])?);
    Ok(written)
}
