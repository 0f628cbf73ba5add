//! Output of `tribofe edges`: preslip.csv and preslip.svg (pre-slip extent under N alone
//! against refinement), opening.csv (the trailing end under the drive against the first
//! precursor). Undefined figures are empty cells, never NaN.

use crate::error::Result;
#[cfg(feature = "plots")]
use crate::report::plot::{render, Legend, PALETTE};
use crate::report::table::{Column, Format, Table};
use crate::studies::edges::{Opening, Preslip};
#[cfg(feature = "plots")]
use plotters::prelude::*;

/// A parameter as given (the shortest decimal).
fn given(name: &'static str, unit: &'static str, v: Vec<f64>) -> Column {
    Column::float(name, unit, v).with_format(Format::Shortest)
}

/// t/h, the elements through the thickness: a count (whole by construction).
fn elements_through_t(v: impl Iterator<Item = f64>) -> Column {
    Column::int("t_over_h", "-", v.map(|k| k as i64).collect())
}

/// preslip.csv's table: per coulomb mu and refinement t/h the interface nodes and the
/// pre-slip extents from the left and right end (units of t). The one definition the CSV and
/// the Python package's table are made from.
pub fn preslip_table(rows: &[Preslip]) -> Table {
    Table {
        columns: vec![
            given("mu", "1", rows.iter().map(|r| r.mu).collect()),
            elements_through_t(rows.iter().map(|r| r.t_over_h)),
            Column::int("interface_nodes", "-", rows.iter().map(|r| r.nodes as i64).collect()),
            Column::float("left_extent_over_t", "1", rows.iter().map(|r| r.extent_t[0]).collect()),
            Column::float("right_extent_over_t", "1", rows.iter().map(|r| r.extent_t[1]).collect()),
        ],
        digits: 13,
    }
}

/// preslip.csv ([`preslip_table`]).
pub fn preslip_csv(rows: &[Preslip]) -> Result<String> {
    preslip_table(rows).csv()
}

/// opening.csv's table: per t/L, t/h and H/L the paper's g and F_1, the force and open length
/// when the trailing end first opens, the FE's F_1, the largest open length, whether the end
/// opens before the first precursor (`true`/`false`), the open nodes then and at most, and
/// the end element's length (forces in units of mu_s N, lengths in units of t; an empty cell
/// where a figure does not exist). The one definition the CSV and the Python package's table
/// are made from.
pub fn opening_table(rows: &[Opening]) -> Table {
    let num = |name: &'static str, get: fn(&Opening) -> f64| {
        Column::float(name, "1", rows.iter().map(get).collect())
    };
    let maybe = |name: &'static str, get: fn(&Opening) -> Option<f64>| {
        Column::maybe(name, "1", rows.iter().map(|r| get(r).unwrap_or(f64::NAN)).collect())
    };
    Table {
        columns: vec![
            given("t_over_L", "1", rows.iter().map(|r| r.t_over_l).collect()),
            elements_through_t(rows.iter().map(|r| r.t_over_h)),
            given("H_over_L", "1", rows.iter().map(|r| r.h_over_l).collect()),
            num("g", |r| r.g),
            num("F1_model_over_mu_s_N", |r| r.f1_model),
            maybe("F_open_over_mu_s_N", |r| r.f_open),
            maybe("open_length_over_t", |r| r.open_length_t),
            maybe("F1_fe_over_mu_s_N", |r| r.f1_fe),
            num("max_open_length_over_t", |r| r.max_open_t),
            Column::text(
                "opens_before_first_precursor",
                "-",
                rows.iter().map(|r| r.opens_first().to_string()).collect(),
            ),
            Column::maybe_int(
                "open_nodes",
                "-",
                rows.iter().map(|r| r.open_nodes.map(|n| n as i64)).collect(),
            ),
            Column::int("max_open_nodes", "-", rows.iter().map(|r| r.max_open_nodes as i64).collect()),
            num("end_element_over_t", |r| r.end_element_t),
        ],
        digits: 13,
    }
}

/// opening.csv ([`opening_table`]).
pub fn opening_csv(rows: &[Opening]) -> Result<String> {
    opening_table(rows).csv()
}

#[cfg(feature = "plots")]
/// Pre-slip extent (both ends) against t/h, one line per mu, log x.
pub fn preslip_svg(rows: &[Preslip]) -> Result<String> {
    let mut mus: Vec<f64> = rows.iter().map(|r| r.mu).collect();
    mus.sort_by(f64::total_cmp);
    mus.dedup();
    let kmax = rows.iter().map(|r| r.t_over_h).fold(2.0, f64::max);
    let ymax = rows.iter().flat_map(|r| r.extent_t).fold(0.5, f64::max) * 1.15;
    render("preslip.svg", (720, 480), |root| {
        let mut chart = ChartBuilder::on(root)
            .caption("Pre-slip under N alone: extent from each end vs refinement", ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(55)
            .build_cartesian_2d((1.0..kmax * 1.3).log_scale(), 0.0..ymax)?;
        chart
            .configure_mesh()
            .x_desc("elements through the thickness t/h")
            .y_desc("pre-slip extent / t")
            .draw()?;
        for (i, &mu) in mus.iter().enumerate() {
            let color = PALETTE[i % PALETTE.len()];
            let pts = |end: usize| -> Vec<(f64, f64)> {
                rows.iter().filter(|r| r.mu == mu).map(|r| (r.t_over_h, r.extent_t[end])).collect()
            };
            chart
                .draw_series(LineSeries::new(pts(0), color.stroke_width(2)))?
                .label(format!("mu = {mu} (left end; dashed: right)"))
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(2)));
            chart.draw_series(pts(0).into_iter().map(|p| Circle::new(p, 4, color.filled())))?;
            chart.draw_series(DashedLineSeries::new(pts(1), 6, 4, color.stroke_width(1)))?;
        }
        chart.legend_box(SeriesLabelPosition::MiddleRight)?;
        Ok(())
    })
}
