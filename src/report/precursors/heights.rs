//! The height-of-drive study (`precursors heights`): `heights.csv`, `heights.svg`.

#[cfg(feature = "plots")]
use super::super::plot::{render, Legend, BLUE, FONT, RED};
use super::super::{ensure_dir, write_all};
use super::series_csv;
#[cfg(feature = "plots")]
use super::{series_range, Series};
use crate::studies::precursors_fe::SeriesRow;
use crate::studies::slide::PaperComparison;
use crate::Result;
#[cfg(feature = "plots")]
use plotters::prelude::*;
use std::path::{Path, PathBuf};

#[cfg(feature = "plots")]
/// The height-of-drive figure: n, F_1 and F_max, and x_1 against g = 6 mu_d H/L, the FE
/// (`paper` rule, points) next to the model (lines), at fixed friction coefficients.
pub fn heights_svg(rows: &[SeriesRow]) -> Result<String> {
    let ok: Vec<&PaperComparison> =
        rows.iter().filter_map(|r| r.fig4.as_ref().ok().map(|f| &f.cmp)).collect();
    let panels: [(&str, &str, Series); 3] = [
        (
            "precursors (FE: advancing the front > 5 t)",
            "n",
            vec![("n", |c| (c.n as f64, Some(c.n_fe_advancing as f64)), BLUE)],
        ),
        (
            "first precursor and peak (FE: first whole slip)",
            "F / (mu_s N)",
            vec![("F_1", |c| (c.f1, c.f1_fe), BLUE), ("F_max", |c| (c.f_max, c.f_max_fe), RED)],
        ),
        ("first precursor's arrest", "x_1 / L", vec![("x_1", |c| (c.x1, c.x1_fe), BLUE)]),
    ];
    render("heights.svg", (1350, 450), |root| {
        for (area, (title, ylab, series)) in root.split_evenly((1, 3)).iter().zip(&panels) {
            let yr = series_range(ok.iter().copied(), series);
            let mut chart = ChartBuilder::on(area)
                .caption(*title, (FONT, 16))
                .margin(12)
                .x_label_area_size(40)
                .y_label_area_size(55)
                .build_cartesian_2d(0.0..1.0, yr)?;
            chart.configure_mesh().x_desc("g = 6 mu_d H / L").y_desc(*ylab).draw()?;
            for &(name, get, col) in series {
                let model: Vec<(f64, f64)> = ok.iter().map(|c| (c.g, get(c).0)).collect();
                let fe: Vec<(f64, f64)> = ok.iter().filter_map(|c| get(c).1.map(|v| (c.g, v))).collect();
                chart
                    .draw_series(LineSeries::new(model, col.stroke_width(2)))?
                    .label(format!("{name}, model"))
                    .legend(move |(x, y)| PathElement::new([(x, y), (x + 18, y)], col.stroke_width(2)));
                chart
                    .draw_series(fe.into_iter().map(|q| Circle::new(q, 4, col.filled())))?
                    .label(format!("{name}, FE"))
                    .legend(move |(x, y)| Circle::new((x + 9, y), 4, col.filled()));
            }
            chart.legend_box(SeriesLabelPosition::UpperLeft)?;
        }
        Ok(())
    })
}

/// Writes the height-of-drive study (`heights.csv`, `heights.svg`, `run.toml`) into `dir`.
pub fn write_heights(
    dir: &Path,
    mu: (f64, f64),
    rows: &[SeriesRow],
    inv: &crate::report::run_file::Invocation,
    scene: &crate::scene::Scene,
) -> Result<Vec<PathBuf>> {
    ensure_dir(dir)?;
    let what = [("mu_s", mu.0), ("mu_d", mu.1)];
    let files = [
        ("heights.csv", series_csv("H_over_L", "1", rows)?),
        #[cfg(feature = "plots")]
        ("heights.svg", heights_svg(rows)?),
        ("run.toml", crate::report::run_toml(inv, &what, scene)?),
    ];
    write_all(dir, &files)
}
