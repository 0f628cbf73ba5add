//! Precursor outputs, one file per study: CSV tables and SVG figures (the paper's figs. 4 and
//! 5, their FE counterparts, the thin-layer, height and D_c series, the bonded-field
//! comparison). All quantities are the paper's dimensionless ones: positions in units of L,
//! forces in units of mu_s N. Here: the columns shared by the FE studies' tables.
//!
//! Imports: each study file uses only the plotting module (`report::plot`), the shared writers
//! (`report`'s `write_all`, `finite`, ..., and [`crate::report::slide::write`] for a run's
//! folder) and the shared columns here; `fe.rs` writes the model's folder through `model.rs`.

mod bonded;
mod dc;
mod fe;
mod fe_map;
mod heights;
mod map;
mod model;
mod thin_layer;

pub use bonded::{comparison_csv, comparison_table, sweep_csv, sweep_table, write_comparison, write_sweep};
pub use dc::write_dc;
pub use fe::{fe_fig4_summary_table, write_fe_fig4};
pub use fe_map::{fe_boundary_csv, fe_fig5_csv, fe_fig5_table, write_fe_fig5};
pub use heights::write_heights;
pub use map::{n_map_csv, n_map_table, write_map};
pub use model::{events_csv, events_table, loading_csv, loading_table, write_events};
pub use thin_layer::write_thin_layer;
/// The figures, with the `plots` feature.
#[cfg(feature = "plots")]
pub use {
    bonded::fe_extents_svg, dc::dc_svg, fe_map::fe_fig5_svg, heights::heights_svg, map::fig5_svg,
    model::fig4_svg, thin_layer::thin_layer_svg,
};

use super::table::{Column, Format, Table};
use crate::studies::precursors_fe::{Fig4, SeriesRow};
#[cfg(feature = "plots")]
use crate::studies::slide::PaperComparison;
use crate::Result;
#[cfg(feature = "plots")]
use plotters::prelude::RGBColor;

/// A series' table (`thin_layer.csv`, `heights.csv`, `dc.csv`): per value of `param` (its
/// unit `unit`) the model's n, F_1, x_1 and F_max, the run's counts, F_1, x_1 and first
/// whole-slip peak, their deviations (relative; x_1 in units of t), the field checks, the
/// worst violation and the wall time; a refused run's row holds only its value and time.
/// The one definition the CSV and the Python package's tables are made from.
pub fn series_table(param: &'static str, unit: &'static str, rows: &[SeriesRow]) -> Table {
    let ok: Vec<Option<&Fig4>> = rows.iter().map(|r| r.fig4.as_ref().ok()).collect();
    // A number of a finished run (None: an empty cell), printed as the shortest decimal.
    let num = |name: &'static str, get: &dyn Fn(&Fig4) -> Option<f64>| {
        Column::maybe(name, "1", ok.iter().map(|f| f.and_then(get).unwrap_or(f64::NAN)).collect())
            .with_format(Format::Shortest)
    };
    let sci = |name: &'static str, get: &dyn Fn(&Fig4) -> Option<f64>| {
        num(name, get).with_format(Format::ShortestSci)
    };
    let count = |name: &'static str, get: &dyn Fn(&Fig4) -> usize| {
        Column::maybe_int(name, "-", ok.iter().map(|f| f.map(|f| get(f) as i64)).collect())
    };
    let rel = |v: Option<f64>, m: f64| v.map(|v| v / m - 1.0);
    let columns = vec![
        Column::float(param, unit, rows.iter().map(|r| r.value).collect()).with_format(Format::Shortest),
        num("r", &|f| Some(f.cmp.r)),
        num("g", &|f| Some(f.cmp.g)),
        count("model_precursors", &|f| f.cmp.n),
        num("model_F1_over_mu_s_N", &|f| Some(f.cmp.f1)),
        num("model_x1_over_L", &|f| Some(f.cmp.x1)),
        num("model_Fmax_over_mu_s_N", &|f| Some(f.cmp.f_max)),
        count("precursors", &|f| f.cmp.n_fe),
        count("precursors_longer_5t", &|f| f.cmp.n_fe_long),
        count("precursors_advancing_5t", &|f| f.cmp.n_fe_advancing),
        num("F1_over_mu_s_N", &|f| f.cmp.f1_fe),
        num("x1_over_L", &|f| f.cmp.x1_fe),
        num("Fmax_over_mu_s_N", &|f| f.cmp.f_max_fe),
        num("F1_rel_dev", &|f| rel(f.cmp.f1_fe, f.cmp.f1)),
        num("x1_dev_over_t", &|f| {
            let t_over_l = f.run.condensed.t / f.run.condensed.l;
            f.cmp.x1_fe.map(|x| (x - f.cmp.x1) / t_over_l)
        }),
        num("Fmax_rel_dev", &|f| rel(f.cmp.f_max_fe, f.cmp.f_max)),
        sci("shear_far_rel_dev", &|f| f.fields.shear_far),
        sci("shear_tip_rel_excess", &|f| f.fields.shear_tip),
        sci("pressure_dev_over_pmean", &|f| f.fields.pressure),
        num("F_corner_over_mu_s_N", &|f| f.fields.f_corner),
        num("x_nucleation_over_L", &|f| f.fields.x_nucleation),
        sci("max_violation_over_N_per_n", &|f| Some(f.worst_violation)),
        Column::float("seconds", "s", rows.iter().map(|r| r.seconds).collect()).with_format(Format::Fixed(3)),
    ];
    Table { columns, digits: 17 }
}

/// A series' CSV ([`series_table`]).
pub fn series_csv(param: &'static str, unit: &'static str, rows: &[SeriesRow]) -> Result<String> {
    series_table(param, unit, rows).csv()
}

#[cfg(feature = "plots")]
/// A model value and the FE's (if any) of one quantity of a [`PaperComparison`].
type Pair = fn(&PaperComparison) -> (f64, Option<f64>);

#[cfg(feature = "plots")]
/// Named, coloured quantities drawn on one panel.
type Series<'a> = Vec<(&'a str, Pair, RGBColor)>;

#[cfg(feature = "plots")]
/// A y range covering the model and FE values of `series` over `cmps`, padded by 8 %.
fn series_range<'a>(
    cmps: impl Iterator<Item = &'a PaperComparison>,
    series: &[(&str, Pair, RGBColor)],
) -> std::ops::Range<f64> {
    super::plot::padded_range(
        cmps.flat_map(|c| series.iter().flat_map(move |s| std::iter::once((s.1)(c).0).chain((s.1)(c).1))),
    )
}
