//! The earlier comparison (`precursors bonded`): the 1D model fed with the bonded FE
//! interface fields next to the paper's linear fields, `fe_events.csv`, `fe_extents.svg` and
//! the H/L, t/L sweep `fe_sweep.csv`.

#[cfg(feature = "plots")]
use super::super::plot::{render, Legend, BLUE, FONT, RED};
use super::super::table::{Column, Format, Table};
use super::super::{ensure_dir, finite, write_all, write_atomic};
use crate::precursors::discrete::{CellEvent, Run};
use crate::precursors::fe::{Comparison, SweepRow};
use crate::Result;
#[cfg(feature = "plots")]
use plotters::prelude::*;
use std::path::{Path, PathBuf};

#[cfg(feature = "plots")]
/// Precursor extents x_i against event index: the paper's analytic iteration vs the
/// discrete model fed with FE fields.
pub fn fe_extents_svg(c: &Comparison) -> Result<String> {
    let analytic: Vec<(f64, f64)> =
        c.analytic.iter().filter(|e| !e.stick_slip).map(|e| (e.i as f64, e.x)).collect();
    let fed: Vec<(f64, f64)> = c.fe.precursors().iter().map(|e| (e.i as f64, e.x)).collect();
    for &(_, x) in analytic.iter().chain(&fed) {
        finite("precursor extent", x)?;
    }
    let i_top = analytic.len().max(fed.len()).max(1) as f64 + 0.5;
    let n_text = |n: Option<usize>| n.map_or("not reached".to_string(), |n| n.to_string());
    render("fe_extents.svg", (900, 600), |root| {
        let mut chart = ChartBuilder::on(root)
            .caption(
                format!(
                    "Precursor extents, r = {}, g = {}, H/L = {}, t/L = {}: analytic n = {}, FE-fed n = {}",
                    c.params.r(),
                    c.params.g(),
                    c.h_over_l,
                    c.t_over_l,
                    n_text(c.analytic.iter().position(|e| e.stick_slip)),
                    n_text(c.fe.n_precursors())
                ),
                (FONT, 16),
            )
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(65)
            .build_cartesian_2d(0.5..i_top, -0.5..0.5)?;
        chart
            .configure_mesh()
            .x_desc("precursor index i")
            .x_label_formatter(&|v| format!("{v:.0}"))
            .y_desc("arrest position x_i / L  (dimensionless; trailing edge -1/2)")
            .draw()?;
        chart
            .draw_series(LineSeries::new(analytic.iter().copied(), BLUE.stroke_width(2)).point_size(4))?
            .label("analytic (paper's iteration)")
            .legend(|(x, y)| PathElement::new([(x, y), (x + 20, y)], BLUE.stroke_width(2)));
        chart
            .draw_series(LineSeries::new(fed.iter().copied(), RED.stroke_width(2)))?
            .label("discrete model on FE fields")
            .legend(|(x, y)| PathElement::new([(x, y), (x + 20, y)], RED.stroke_width(2)));
        chart.draw_series(fed.iter().map(|&(i, x)| Cross::new((i, x), 5, RED.stroke_width(2))))?;
        chart.legend_box(SeriesLabelPosition::LowerRight)?;
        Ok(())
    })
}

/// `fe_events.csv`'s table: both discrete runs of a comparison, long format (`model` `fe`
/// then `linear`): event i, F, F^c, nucleation and arrest x, F^*, and whether it is the
/// stick-slip event (1) or a precursor (0); forces in units of mu_s N, x in units of L. The
/// one definition the CSV and the Python package's table are made from.
pub fn comparison_table(c: &Comparison) -> Table {
    let events: Vec<(&str, &CellEvent)> = [("fe", &c.fe), ("linear", &c.linear)]
        .into_iter()
        .flat_map(|(model, run): (&str, &Run)| run.events.iter().map(move |e| (model, e)))
        .collect();
    let num = |name: &'static str, get: fn(&CellEvent) -> f64| {
        Column::float(name, "1", events.iter().map(|(_, e)| get(e)).collect()).with_format(Format::Shortest)
    };
    Table {
        columns: vec![
            Column::text("model", "-", events.iter().map(|(m, _)| m.to_string()).collect()),
            Column::int("i", "-", events.iter().map(|(_, e)| e.i as i64).collect()),
            num("F", |e| e.f),
            num("Fc", |e| e.fc),
            num("x_nucleation", |e| e.x_nucleation),
            num("x", |e| e.x),
            num("Fstar", |e| e.fstar),
            Column::int("stick_slip", "-", events.iter().map(|(_, e)| i64::from(e.stick_slip)).collect()),
        ],
        digits: 17,
    }
}

/// Both discrete runs of a comparison ([`comparison_table`]), header
/// `model,i,F,Fc,x_nucleation,x,Fstar,stick_slip`.
pub fn comparison_csv(c: &Comparison) -> Result<String> {
    comparison_table(c).csv()
}

/// Writes `fe_events.csv` and `fe_extents.svg` for a comparison into `dir` (created if
/// needed); returns the paths.
pub fn write_comparison(dir: &Path, c: &Comparison) -> Result<Vec<PathBuf>> {
    ensure_dir(dir)?;
    let mut files = vec![("fe_events.csv", comparison_csv(c)?)];
    #[cfg(feature = "plots")]
    files.push(("fe_extents.svg", fe_extents_svg(c)?));
    write_all(dir, &files)
}

/// `fe_sweep.csv`'s table, the sweep of [`crate::precursors::fe::sweep`]: per H/L and t/L
/// the precursors of the FE-fed and the linear run, their F_1 and stick-slip F_max (units of
/// mu_s N) and the largest difference in precursor length (units of L); an empty n or F_max
/// where a run did not reach stick-slip within its events; `outside_model` says why a
/// geometry could not be run (quoted), its figures then empty. The one definition the CSV and
/// the Python package's table are made from.
pub fn sweep_table(rows: &[SweepRow]) -> Result<Table> {
    // A run geometry's figures must be numbers: a non-finite one is a bug, never an empty cell.
    for w in rows.iter().filter(|w| w.outside_model.is_none()) {
        for (name, v) in [
            ("F1_fe", Some(w.f1_fe)),
            ("F1_linear", Some(w.f1_linear)),
            ("Fmax_fe", w.f_max_fe),
            ("Fmax_linear", w.f_max_linear),
            ("max_abs_d_length", Some(w.max_abs_d_length)),
        ] {
            v.map(|v| finite(name, v)).transpose()?;
        }
    }
    let run = |w: &SweepRow, v: Option<f64>| v.filter(|_| w.outside_model.is_none()).unwrap_or(f64::NAN);
    let num = |name: &'static str, get: &dyn Fn(&SweepRow) -> Option<f64>| {
        Column::maybe(name, "1", rows.iter().map(|w| run(w, get(w))).collect()).with_format(Format::Shortest)
    };
    let count = |name: &'static str, get: fn(&SweepRow) -> Option<usize>| {
        Column::maybe_int(name, "-", rows.iter().map(|w| get(w).map(|n| n as i64)).collect())
    };
    Ok(Table {
        columns: vec![
            Column::float("H_over_L", "1", rows.iter().map(|w| w.h_over_l).collect())
                .with_format(Format::Shortest),
            Column::float("t_over_L", "1", rows.iter().map(|w| w.t_over_l).collect())
                .with_format(Format::Shortest),
            count("n_fe", |w| w.n_fe),
            count("n_linear", |w| w.n_linear),
            num("F1_fe", &|w| Some(w.f1_fe)),
            num("F1_linear", &|w| Some(w.f1_linear)),
            num("Fmax_fe", &|w| w.f_max_fe),
            num("Fmax_linear", &|w| w.f_max_linear),
            num("max_abs_d_length", &|w| Some(w.max_abs_d_length)),
            Column::text(
                "outside_model",
                "-",
                rows.iter().map(|w| w.outside_model.clone().unwrap_or_default()).collect(),
            )
            .with_format(Format::Quoted),
        ],
        digits: 17,
    })
}

/// `fe_sweep.csv` ([`sweep_table`]), header
/// `H_over_L,t_over_L,n_fe,n_linear,F1_fe,F1_linear,Fmax_fe,Fmax_linear,max_abs_d_length,outside_model`.
pub fn sweep_csv(rows: &[SweepRow]) -> Result<String> {
    sweep_table(rows)?.csv()
}

/// Writes [`sweep_csv`] to `path`.
pub fn write_sweep(path: &Path, rows: &[SweepRow]) -> Result<()> {
    write_atomic(path, sweep_csv(rows)?.as_bytes())
}
