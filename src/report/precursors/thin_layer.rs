//! The thin-layer study (`precursors thin-layer`): `thin_layer.csv`, `thin_layer.svg`.

#[cfg(feature = "plots")]
use super::super::plot::{log_range, render, Legend, BLUE, FONT, GREEN, RED};
use super::super::{ensure_dir, write_all};
use super::series_csv;
use crate::precursors::Params;
use crate::studies::precursors_fe::{Fig4, SeriesRow};
use crate::studies::slide::PaperComparison;
use crate::Result;
#[cfg(feature = "plots")]
use plotters::prelude::*;
use std::path::{Path, PathBuf};

#[cfg(feature = "plots")]
/// The thin-layer figure: |F_1 - model|/model, |x_1 - model|/L and |F_max - model|/model
/// against t/L (log-log), and the front-advancing count against t/L with the model's n.
pub fn thin_layer_svg(p: &Params, rows: &[SeriesRow]) -> Result<String> {
    let n = crate::precursors::n_precursors(p)?;
    let ok: Vec<(f64, &Fig4)> =
        rows.iter().filter_map(|r| r.fig4.as_ref().ok().map(|f| (r.value, f))).collect();
    type Get = fn(&PaperComparison) -> Option<f64>;
    let series: [(&str, Get, RGBColor); 3] = [
        ("|F_1 - model| / model", |c| c.f1_fe.map(|v| (v / c.f1 - 1.0).abs()), BLUE),
        ("|x_1 - model| / L", |c| c.x1_fe.map(|v| (v - c.x1).abs()), RED),
        ("|F_max - model| / model", |c| c.f_max_fe.map(|v| (v / c.f_max - 1.0).abs()), GREEN),
    ];
    let pts = |g: Get| -> Vec<(f64, f64)> {
        ok.iter().filter_map(|(tl, f)| g(&f.cmp).filter(|v| *v > 0.0).map(|v| (*tl, v))).collect()
    };
    let xr = log_range(ok.iter().map(|q| q.0));
    render("thin_layer.svg", (1100, 480), |root| {
        let (left, right) = root.split_horizontally(560);
        let all: Vec<f64> = series.iter().flat_map(|s| pts(s.1)).map(|q| q.1).collect();
        let mut chart = ChartBuilder::on(&left)
            .caption(format!("rule paper against the model, (r, g) = ({}, {})", p.r(), p.g()), (FONT, 16))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(xr.clone().log_scale(), log_range(all.into_iter()).log_scale())?;
        chart
            .configure_mesh()
            .x_desc("t / L")
            .y_desc("deviation (dimensionless)")
            .x_label_formatter(&|v| format!("{v:.0e}"))
            .y_label_formatter(&|v| format!("{v:.0e}"))
            .draw()?;
        for (name, g, col) in series {
            let line = pts(g);
            chart
                .draw_series(LineSeries::new(line.clone(), col.stroke_width(2)))?
                .label(name)
                .legend(move |(x, y)| PathElement::new([(x, y), (x + 18, y)], col.stroke_width(2)));
            chart.draw_series(line.into_iter().map(|q| Circle::new(q, 3, col.filled())))?;
        }
        chart.legend_box(SeriesLabelPosition::MiddleRight)?;
        let counts: Vec<(f64, f64)> = ok.iter().map(|(tl, f)| (*tl, f.cmp.n_fe_advancing as f64)).collect();
        let ymax = counts.iter().map(|q| q.1).fold(n as f64, f64::max) * 1.2 + 1.0;
        let mut chart = ChartBuilder::on(&right)
            .caption("precursors before the first whole slip", (FONT, 16))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(50)
            .build_cartesian_2d(xr.log_scale(), 0.0..ymax)?;
        chart
            .configure_mesh()
            .x_desc("t / L")
            .y_desc("n")
            .x_label_formatter(&|v| format!("{v:.0e}"))
            .draw()?;
        chart
            .draw_series(LineSeries::new(counts.clone(), BLUE.stroke_width(2)))?
            .label("FE, rule paper: advancing the front > 5 t")
            .legend(|(x, y)| PathElement::new([(x, y), (x + 18, y)], BLUE.stroke_width(2)));
        chart.draw_series(counts.into_iter().map(|q| Circle::new(q, 3, BLUE.filled())))?;
        let (x0, x1) = (
            ok.iter().map(|q| q.0).fold(f64::INFINITY, f64::min),
            ok.iter().map(|q| q.0).fold(0.0, f64::max),
        );
        chart
            .draw_series(LineSeries::new([(x0, n as f64), (x1, n as f64)], BLACK.stroke_width(2)))?
            .label(format!("model: n = {n}"))
            .legend(|(x, y)| PathElement::new([(x, y), (x + 18, y)], BLACK.stroke_width(2)));
        chart.legend_box(SeriesLabelPosition::MiddleRight)?;
        Ok(())
    })
}

/// Writes the thin-layer study (`thin_layer.csv`, `thin_layer.svg`, `run.toml`) into `dir`.
pub fn write_thin_layer(
    dir: &Path,
    p: &Params,
    rows: &[SeriesRow],
    inv: &crate::report::run_file::Invocation,
    scene: &crate::scene::Scene,
) -> Result<Vec<PathBuf>> {
    ensure_dir(dir)?;
    let what = [("r", p.r()), ("g", p.g())];
    let files = [
        ("thin_layer.csv", series_csv("t_over_L", "1", rows)?),
        #[cfg(feature = "plots")]
        ("thin_layer.svg", thin_layer_svg(p, rows)?),
        ("run.toml", crate::report::run_toml(inv, &what, scene)?),
    ];
    write_all(dir, &files)
}
