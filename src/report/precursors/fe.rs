//! The FE fig. 4 (`precursors fe`): `summary.csv` (the model's row, then one per event rule),
//! the model's folder and one folder per rule.

use super::super::table::{Column, Format, Table};
use super::super::{ensure_dir, write_all};
use crate::precursors::{Event, Params};
use crate::studies::precursors_fe::Fig4;
use crate::Result;
use std::path::{Path, PathBuf};

/// `summary.csv`'s table: the analytic iteration's row (`model`), then one row per rule of
/// [`crate::studies::precursors_fe::RULES`] (empty cells where a run was refused): the counts,
/// F_1 and F_max in units of mu_s N, x_1 in units of L, the worst violation, the field
/// checks and the front advances' count, F_1 and x_1. The one definition the CSV and the Python package's `summary` are made from.
pub fn fe_fig4_summary_table(p: &Params, runs: &[Result<Fig4>]) -> Result<Table> {
    use crate::studies::precursors_fe::RULES;
    let n = crate::precursors::n_precursors(p)? as i64;
    let x1 = crate::precursors::simulate(p, 1).first().map_or(f64::NAN, |e| e.x);
    let ok: Vec<Option<&Fig4>> = runs.iter().map(|r| r.as_ref().ok()).collect();
    // The model's row, then the runs'.
    let count = |model: i64, f: fn(&Fig4) -> usize| -> Vec<Option<i64>> {
        std::iter::once(Some(model)).chain(ok.iter().map(|r| r.map(|r| f(r) as i64))).collect()
    };
    let num = |model: f64, f: &dyn Fn(&Fig4) -> Option<f64>| -> Vec<f64> {
        std::iter::once(model).chain(ok.iter().map(|r| r.and_then(f).unwrap_or(f64::NAN))).collect()
    };
    let short = |name: &'static str, v: Vec<f64>| Column::maybe(name, "1", v).with_format(Format::Shortest);
    let sci = |name: &'static str, v: Vec<f64>| Column::maybe(name, "1", v).with_format(Format::ShortestSci);
    let mut source = vec!["model".to_string()];
    source.extend(RULES.iter().take(runs.len()).map(|r| r.name().to_string()));
    Ok(Table {
        columns: vec![
            Column::text("source", "-", source),
            Column::maybe_int("precursors", "-", count(n, |r| r.cmp.n_fe)),
            Column::maybe_int("precursors_longer_5t", "-", count(n, |r| r.cmp.n_fe_long)),
            Column::maybe_int("precursors_advancing_5t", "-", count(n, |r| r.cmp.n_fe_advancing)),
            short("F1_over_mu_s_N", num(p.f1(), &|r| r.cmp.f1_fe)),
            short("x1_over_L", num(x1, &|r| r.cmp.x1_fe)),
            short("Fmax_over_mu_s_N", num(p.f_max(), &|r| r.cmp.f_max_fe)),
            sci("worst_violation_over_N_per_n", num(f64::NAN, &|r| Some(r.worst_violation))),
            // The model holds its field assumptions exactly.
            sci("shear_far_rel_dev", num(0.0, &|r| r.fields.shear_far)),
            sci("shear_tip_rel_excess", num(0.0, &|r| r.fields.shear_tip)),
            sci("pressure_dev_over_pmean", num(0.0, &|r| r.fields.pressure)),
            short("F_corner_over_mu_s_N", num(f64::NAN, &|r| r.fields.f_corner)),
            short("x_nucleation_over_L", num(-0.5, &|r| r.fields.x_nucleation)),
            // The front advances (crate::precursors::definition::ADVANCES); each of the
            // model's precursors is one, from the trailing edge.
            Column::maybe_int("front_advances", "-", count(n, |r| r.cmp.n_front)),
            short("F1_front_over_mu_s_N", num(p.f1(), &|r| r.cmp.f1_front)),
            short("x1_front_over_L", num(x1, &|r| r.cmp.x1_front)),
        ],
        digits: 17,
    })
}

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
    let mut written = super::model::write_events(&dir.join("model"), p, model)?;
    for (rule, run) in crate::studies::precursors_fe::RULES.iter().zip(runs) {
        let name = rule.name();
        let Ok(r) = run else { continue };
        let sub = dir.join(name);
        ensure_dir(&sub)?;
        let law = r.run.options.law;
        let what =
            [("rule", name.to_string()), ("mu_s", law.mu_s().to_string()), ("mu_d", law.mu_d().to_string())];
        let header = crate::report::run_toml(inv, &what, scene)?;
        written.extend(crate::report::slide::write(&r.run, &sub, &header, false)?);
    }
    written.extend(write_all(dir, &[("summary.csv", fe_fig4_summary_table(p, runs)?.csv()?)])?);
    Ok(written)
}
