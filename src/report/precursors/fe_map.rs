//! The FE fig. 5 (`precursors fe-map`): per (r, g) cell the frictional FE's counts next to the
//! model's, `fig5_fe.csv`, `boundary_fe.csv` and `fig5_fe.svg`.

#[cfg(feature = "plots")]
use super::super::plot::{n_colour, n_key, render, FONT, RED};
use super::super::table::{Column, Format, Table};
use super::super::{ensure_dir, opt, write_all};
use crate::studies::precursors_fe::Cell;
use crate::Result;
#[cfg(feature = "plots")]
use plotters::prelude::*;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// `fig5_fe.csv`'s table: per cell the model's n and F_max, then per rule its status (done,
/// capped, refused, or empty when not run), the three counts, the first cycle's peak, the
/// events, the worst violation, the wall time, for a capped run the precursors and the peak
/// force reached at the cap, and for a finished one what ended its cycle (whole-slip or
/// crossing). The one definition the CSV and the Python package's `table` are made from.
pub fn fe_fig5_table(cells: &[Cell]) -> Table {
    use crate::studies::precursors_fe::{CellRun, RULES};
    let shortest = |name: String, v: Vec<f64>| Column::maybe(name, "1", v).with_format(Format::Shortest);
    let mut columns = vec![
        Column::float("r", "1", cells.iter().map(|c| c.r).collect()).with_format(Format::Shortest),
        Column::float("g", "1", cells.iter().map(|c| c.g).collect()).with_format(Format::Shortest),
        Column::int("model_precursors", "-", cells.iter().map(|c| c.n_model as i64).collect()),
        Column::float("model_Fmax_over_mu_s_N", "1", cells.iter().map(|c| c.f_max_model).collect())
            .with_format(Format::Shortest),
    ];
    // A finished run's numbers: n, n > 5 t, n advancing, events, F_max, the worst violation.
    struct Done {
        counts: [usize; 4],
        f_max: Option<f64>,
        violation: f64,
    }
    for (k, rule) in RULES.iter().enumerate() {
        let runs: Vec<Option<&CellRun>> = cells.iter().map(|c| c.runs[k].as_ref()).collect();
        let done: Vec<Option<Done>> = runs
            .iter()
            .map(|r| match r {
                Some(&CellRun::Done { n, n_long, n_advancing, events, f_max, violation, .. }) => {
                    Some(Done { counts: [n, n_long, n_advancing, events], f_max, violation })
                }
                _ => None,
            })
            .collect();
        let count = |i: usize| done.iter().map(|d| d.as_ref().map(|d| d.counts[i] as i64)).collect();
        // A capped run's precursors and peak force at the cap.
        let cap: Vec<Option<(usize, f64)>> = runs
            .iter()
            .map(|r| match r {
                Some(&CellRun::Capped { precursors, f_peak, .. }) => Some((precursors, f_peak)),
                _ => None,
            })
            .collect();
        let name = |what: &str| format!("{}_{what}", rule.name());
        columns.extend([
            Column::text(
                name("status"),
                "-",
                runs.iter().map(|r| r.map_or("", |r| r.status()).into()).collect(),
            ),
            Column::maybe_int(name("precursors"), "-", count(0)),
            Column::maybe_int(name("precursors_longer_5t"), "-", count(1)),
            Column::maybe_int(name("precursors_advancing_5t"), "-", count(2)),
            shortest(
                name("Fmax_over_mu_s_N"),
                done.iter().map(|d| d.as_ref().and_then(|d| d.f_max).unwrap_or(f64::NAN)).collect(),
            ),
            Column::maybe_int(name("events"), "-", count(3)),
            Column::maybe(
                name("max_violation_over_N_per_n"),
                "1",
                done.iter().map(|d| d.as_ref().map_or(f64::NAN, |d| d.violation)).collect(),
            )
            .with_format(Format::ShortestSci),
            Column::maybe(
                name("seconds"),
                "s",
                runs.iter().map(|r| r.map_or(f64::NAN, |r| r.seconds())).collect(),
            )
            .with_format(Format::Fixed(3)),
            Column::maybe_int(
                name("precursors_at_cap"),
                "-",
                cap.iter().map(|c| c.map(|c| c.0 as i64)).collect(),
            ),
            shortest(
                name("Fpeak_at_cap_over_mu_s_N"),
                cap.iter().map(|c| c.map_or(f64::NAN, |c| c.1)).collect(),
            ),
            Column::text(
                name("cycle_end"),
                "-",
                runs.iter()
                    .map(|r| match r {
                        Some(CellRun::Done { crossing: true, .. }) => "crossing".into(),
                        Some(CellRun::Done { crossing: false, .. }) => "whole-slip".into(),
                        _ => String::new(),
                    })
                    .collect(),
            ),
        ]);
    }
    Table { columns, digits: 17 }
}

/// `fig5_fe.csv` ([`fe_fig5_table`]).
pub fn fe_fig5_csv(cells: &[Cell]) -> Result<String> {
    fe_fig5_table(cells).csv()
}

/// `boundary_fe.csv`: per r, the paper's no-precursor line (1 - r)/2, the model grid's and
/// each rule's lowest g with a precursor (empty where unknown or none).
pub fn fe_boundary_csv(cells: &[Cell]) -> Result<String> {
    use crate::studies::precursors_fe::{boundary, RULES};
    let mut s = String::from("r,paper_line_g,model_first_g");
    for rule in RULES {
        let _ = write!(s, ",{}_first_g", rule.name());
    }
    s.push('\n');
    let per_rule: Vec<_> = (0..RULES.len()).map(|k| boundary(cells, k)).collect();
    for (i, &(r, model, _)) in per_rule[0].iter().enumerate() {
        let _ = write!(s, "{r},{},{}", (1.0 - r) / 2.0, opt(model));
        for b in &per_rule {
            let _ = write!(s, ",{}", opt(b[i].2));
        }
        s.push('\n');
    }
    Ok(s)
}

#[cfg(feature = "plots")]
/// FE fig. 5 next to the analytic one: one panel for the model's n and one per rule run for
/// the FE's front-advancing count, on one logarithmic colour scale; capped cells grey,
/// refused ones black; the paper's line g = (1 - r)/2 in red, the FE's measured boundary as
/// white dots.
pub fn fe_fig5_svg(cells: &[Cell], resolution: usize) -> Result<String> {
    use crate::studies::precursors_fe::{boundary, CellRun, RULES};
    let ran: Vec<usize> = (0..RULES.len()).filter(|&k| cells.iter().any(|c| c.runs[k].is_some())).collect();
    let n_of = |c: &Cell, k: Option<usize>| match k {
        None => Some(c.n_model),
        Some(k) => c.runs[k].and_then(|r| r.n_advancing()),
    };
    let n_max = cells
        .iter()
        .flat_map(|c| {
            std::iter::once(None).chain(ran.iter().map(|&k| Some(k))).filter_map(move |k| n_of(c, k))
        })
        .max()
        .unwrap_or(0);
    let colour = |n: usize| n_colour(n, n_max);
    let half = 0.5 / resolution as f64;
    let panels: Vec<Option<usize>> = std::iter::once(None).chain(ran.iter().map(|&k| Some(k))).collect();
    let w = 460;
    render("fig5_fe.svg", (w * panels.len() as u32 + 170, 500), |root| {
        let (main, key) = root.split_horizontally(w * panels.len() as u32);
        for (area, &k) in main.split_evenly((1, panels.len())).iter().zip(&panels) {
            let title = match k {
                None => "model: n".to_string(),
                Some(k) => format!("FE, rule {}: n advancing > 5 t", RULES[k].name()),
            };
            let mut chart = ChartBuilder::on(area)
                .caption(title, (FONT, 17))
                .margin(12)
                .x_label_area_size(40)
                .y_label_area_size(50)
                .build_cartesian_2d(0.0..1.0, 0.0..1.0)?;
            chart
                .configure_mesh()
                .disable_mesh()
                .x_desc("r = mu_d / mu_s")
                .y_desc("g = 6 mu_d H / L")
                .draw()?;
            chart.draw_series(cells.iter().map(|c| {
                let fill = match (k, n_of(c, k)) {
                    (_, Some(n)) => colour(n),
                    (Some(k), None) => match c.runs[k] {
                        Some(CellRun::Capped { .. }) => RGBColor(160, 160, 160),
                        Some(_) => BLACK,
                        None => WHITE,
                    },
                    (None, None) => WHITE,
                };
                Rectangle::new([(c.r - half, c.g - half), (c.r + half, c.g + half)], fill.filled())
            }))?;
            chart.draw_series(LineSeries::new([(0.0, 0.5), (1.0, 0.0)], RED.stroke_width(2)))?;
            if let Some(k) = k {
                chart.draw_series(
                    boundary(cells, k)
                        .into_iter()
                        .filter_map(|(r, _, g)| g.map(|g| Circle::new((r, g - half), 3, WHITE.filled()))),
                )?;
            }
        }
        let mut y = n_key(&key, n_max)?;
        for (fill, what) in [(RGBColor(160, 160, 160), "event cap"), (BLACK, "refused")] {
            key.draw(&Rectangle::new([(10, y), (36, y + 20)], fill.filled()))?;
            key.draw(&Text::new(what, (44, y + 4), (FONT, 13)))?;
            y += 25;
        }
        key.draw(&PathElement::new([(10, y + 10), (36, y + 10)], RED.stroke_width(2)))?;
        key.draw(&Text::new("g = (1-r)/2", (44, y + 4), (FONT, 13)))?;
        key.draw(&Circle::new((23, y + 35), 3, BLACK.filled()))?;
        key.draw(&Circle::new((23, y + 35), 2, WHITE.filled()))?;
        key.draw(&Text::new("FE boundary", (44, y + 29), (FONT, 13)))?;
        Ok(())
    })
}

/// Writes the FE fig. 5 (`fig5_fe.csv`, `boundary_fe.csv`, `fig5_fe.svg`, `run.toml`) into
/// `dir`; returns the paths.
pub fn write_fe_fig5(
    dir: &Path,
    cells: &[Cell],
    resolution: usize,
    what: &[(&str, String)],
    inv: &crate::report::run_file::Invocation,
    scene: &crate::scene::Scene,
) -> Result<Vec<PathBuf>> {
    ensure_dir(dir)?;
    let files = [
        ("fig5_fe.csv", fe_fig5_csv(cells)?),
        ("boundary_fe.csv", fe_boundary_csv(cells)?),
        #[cfg(feature = "plots")]
        ("fig5_fe.svg", fe_fig5_svg(cells, resolution)?),
        ("run.toml", crate::report::run_toml(inv, &what, scene)?),
    ];
    write_all(dir, &files)
}
