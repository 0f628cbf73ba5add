//! The paper's own iteration for one (r, g): `events.csv`, `loading.csv` and fig. 4
//! (`fig4.svg`). Forces in units of mu_s N, positions in units of L.

#[cfg(feature = "plots")]
use super::super::plot::{render, Legend, BLUE, FONT, RED};
use super::super::table::{Column, Format, Table};
use super::super::{ensure_dir, finite, write_all};
use crate::precursors::{loading_curve, Event, Params};
use crate::Result;
#[cfg(feature = "plots")]
use plotters::prelude::*;
use std::path::{Path, PathBuf};

/// `events.csv`'s table: per event its index, F_i, F_i^c and the relaxed force F_i^* in
/// units of mu_s N, the arrest x_i in units of L, and stick_slip (0 for a precursor, 1 after),
/// at full precision (the shortest decimals that read back: the values are exact fractions
/// of r and g). The one definition the CSV and the Python package's `events` are made from.
pub fn events_table(events: &[Event]) -> Table {
    let col = |name: &'static str, f: fn(&Event) -> f64| {
        Column::float(name, "1", events.iter().map(f).collect()).with_format(Format::Shortest)
    };
    Table {
        columns: vec![
            Column::int("event", "-", events.iter().map(|e| e.i as i64).collect()),
            col("F_over_mu_s_N", |e| e.f),
            col("Fc_over_mu_s_N", |e| e.fc),
            col("x_arrest_over_L", |e| e.x),
            col("F_relaxed_over_mu_s_N", |e| e.fstar),
            Column::int("stick_slip", "-", events.iter().map(|e| i64::from(e.stick_slip)).collect()),
        ],
        digits: 17,
    }
}

/// `events.csv` ([`events_table`]).
pub fn events_csv(events: &[Event]) -> Result<String> {
    events_table(events).csv()
}

/// `loading.csv`'s table: the vertices of the loading curve F(F^c), both in units of mu_s N.
pub fn loading_table(curve: &[(f64, f64)]) -> Table {
    let col = |name: &'static str, f: fn(&(f64, f64)) -> f64| {
        Column::float(name, "1", curve.iter().map(f).collect()).with_format(Format::Shortest)
    };
    Table { columns: vec![col("Fc_over_mu_s_N", |c| c.0), col("F_over_mu_s_N", |c| c.1)], digits: 17 }
}

/// `loading.csv` ([`loading_table`]).
pub fn loading_csv(curve: &[(f64, f64)]) -> Result<String> {
    loading_table(curve).csv()
}

#[cfg(feature = "plots")]
/// The paper's fig. 4: loading curve F(F^c) (red), ideal elastic line F = F^c (black),
/// F_max (dashed) and each precursor's extent [-1/2, x_i] at its force F_i (blue, top axis).
pub fn fig4_svg(p: &Params, events: &[Event]) -> Result<String> {
    let curve = loading_curve(events);
    for &(fc, f) in &curve {
        finite("loading curve", fc)?;
        finite("loading curve", f)?;
    }
    let fc_top = curve.iter().fold(0.0_f64, |m, c| m.max(c.0)).max(1.0) * 1.02;
    let f_top = curve.iter().fold(p.f_max(), |m, c| m.max(c.1)) * 1.08;
    let f_max = p.f_max();
    render("fig4.svg", (900, 650), |root| {
        let mut chart = ChartBuilder::on(root)
            .caption(
                format!("Loading curve and precursors, r = {}, g = {} (paper fig. 4)", p.r(), p.g()),
                (FONT, 20),
            )
            .margin(15)
            .x_label_area_size(45)
            .top_x_label_area_size(45)
            .y_label_area_size(65)
            .build_cartesian_2d(0.0..fc_top, 0.0..f_top)?
            .set_secondary_coord(-0.5..0.5, 0.0..f_top);
        chart
            .configure_mesh()
            .x_desc("elastic force F^c / (mu_s N)  (dimensionless)")
            .y_desc("friction force F / (mu_s N)  (dimensionless)")
            .draw()?;
        chart
            .configure_secondary_axes()
            .x_desc("blue: precursor extent along the contact, x / L  (dimensionless)")
            .draw()?;
        let m = fc_top.min(f_top);
        chart
            .draw_series(LineSeries::new([(0.0, 0.0), (m, m)], BLACK.stroke_width(1)))?
            .label("ideal elastic loading F = F^c")
            .legend(|(x, y)| PathElement::new([(x, y), (x + 20, y)], BLACK));
        chart
            .draw_series(LineSeries::new(curve.iter().copied(), RED.stroke_width(2)))?
            .label("loading curve F(F^c)")
            .legend(|(x, y)| PathElement::new([(x, y), (x + 20, y)], RED.stroke_width(2)));
        chart
            .draw_series(DashedLineSeries::new(
                [(0.0, f_max), (fc_top, f_max)],
                6,
                4,
                BLACK.mix(0.6).stroke_width(1),
            ))?
            .label(format!("F_max = {f_max:.4}"))
            .legend(|(x, y)| PathElement::new([(x, y), (x + 20, y)], BLACK.mix(0.6)));
        let blue = BLUE.stroke_width(2);
        chart
            .draw_secondary_series(
                events
                    .iter()
                    .filter(|e| !e.stick_slip)
                    .map(|e| PathElement::new([(-0.5, e.f), (e.x, e.f)], blue)),
            )?
            .label("precursor i: from x = -1/2 to x_i, at height F_i")
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], blue));
        chart.draw_secondary_series(
            events.iter().filter(|e| !e.stick_slip).map(|e| Circle::new((e.x, e.f), 3, BLUE.filled())),
        )?;
        chart.legend_box(SeriesLabelPosition::LowerRight)?;
        Ok(())
    })
}

/// Writes `events.csv`, `loading.csv` and `fig4.svg` into `dir` (created if needed);
/// returns the paths written.
pub fn write_events(dir: &Path, p: &Params, events: &[Event]) -> Result<Vec<PathBuf>> {
    ensure_dir(dir)?;
    let mut files =
        vec![("events.csv", events_csv(events)?), ("loading.csv", loading_csv(&loading_curve(events))?)];
    #[cfg(feature = "plots")]
    files.push(("fig4.svg", fig4_svg(p, events)?));
    write_all(dir, &files)
}
