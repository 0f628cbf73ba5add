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

pub use bonded::{comparison_csv, sweep_csv, write_comparison, write_sweep};
pub use dc::write_dc;
pub use fe::{fe_fig4_summary_table, write_fe_fig4};
pub use fe_map::{fe_boundary_csv, fe_fig5_csv, fe_fig5_table, write_fe_fig5};
pub use heights::write_heights;
pub use map::{n_map_csv, write_map};
pub use model::{events_csv, events_table, loading_csv, loading_table, write_events};
pub use thin_layer::write_thin_layer;
/// The figures, with the `plots` feature.
#[cfg(feature = "plots")]
pub use {
    bonded::fe_extents_svg, dc::dc_svg, fe_map::fe_fig5_svg, heights::heights_svg, map::fig5_svg,
    model::fig4_svg, thin_layer::thin_layer_svg,
};

use super::opt;
use crate::studies::precursors_fe::{FieldChecks, SeriesRow};
use crate::studies::slide::PaperComparison;
use crate::Result;
#[cfg(feature = "plots")]
use plotters::prelude::RGBColor;
use std::fmt::Write as _;

/// Header fragment and values of a run's counts, first precursor and peak for CSVs.
const FE_COLUMNS: &str =
    "precursors,precursors_longer_5t,precursors_advancing_5t,F1_over_mu_s_N,x1_over_L,Fmax_over_mu_s_N";

fn fe_values(c: &PaperComparison) -> String {
    format!(
        "{},{},{},{},{},{}",
        c.n_fe,
        c.n_fe_long,
        c.n_fe_advancing,
        opt(c.f1_fe),
        opt(c.x1_fe),
        opt(c.f_max_fe)
    )
}

/// Header fragment and values of [`FieldChecks`] for CSVs.
const FIELD_COLUMNS: &str =
    "shear_far_rel_dev,shear_tip_rel_excess,pressure_dev_over_pmean,F_corner_over_mu_s_N,x_nucleation_over_L";

fn field_values(f: &FieldChecks) -> String {
    format!(
        "{},{},{},{},{}",
        opt(f.shear_far.map(|v| format!("{v:e}"))),
        opt(f.shear_tip.map(|v| format!("{v:e}"))),
        opt(f.pressure.map(|v| format!("{v:e}"))),
        opt(f.f_corner),
        opt(f.x_nucleation)
    )
}

/// A series' CSV (`thin_layer.csv`, `heights.csv`): per value of `param` the model's n, F_1,
/// x_1 and F_max, the `paper` rule's front-advancing count, F_1, x_1 and first whole-slip peak,
/// their deviations (relative; x_1 in units of t), the field checks, the worst violation and
/// the wall time.
pub fn series_csv(param: &str, rows: &[SeriesRow]) -> Result<String> {
    let mut s = format!(
        "{param},r,g,model_precursors,model_F1_over_mu_s_N,model_x1_over_L,model_Fmax_over_mu_s_N,{FE_COLUMNS},F1_rel_dev,x1_dev_over_t,Fmax_rel_dev,{FIELD_COLUMNS},max_violation_over_N_per_n,seconds\n"
    );
    for row in rows {
        let Ok(f) = &row.fig4 else {
            let _ = writeln!(s, "{}{}{:.3}", row.value, ",".repeat(22), row.seconds);
            continue;
        };
        let c = &f.cmp;
        let t_over_l = f.run.condensed.t / f.run.condensed.l;
        let rel = |v: Option<f64>, m: f64| opt(v.map(|v| v / m - 1.0));
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{},{},{},{},{},{:e},{:.3}",
            row.value,
            c.r,
            c.g,
            c.n,
            c.f1,
            c.x1,
            c.f_max,
            fe_values(c),
            rel(c.f1_fe, c.f1),
            opt(c.x1_fe.map(|x| (x - c.x1) / t_over_l)),
            rel(c.f_max_fe, c.f_max),
            field_values(&f.fields),
            f.worst_violation,
            row.seconds
        );
    }
    Ok(s)
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
