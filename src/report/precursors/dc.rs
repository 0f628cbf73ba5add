//! The event-rule study (`precursors dc`): the `paper` rule next to slip-weakening with each
//! D_c, `dc.csv`, `dc.svg` and each run's folder.

#[cfg(feature = "plots")]
use super::super::plot::{log_range, render, Legend, BLUE, FONT, RED};
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
/// The D_c figure: F_1 and F_max, x_1, and the front-advancing count against D_c (log),
/// slip-weakening (points) next to the `paper` rule (dashed) and the model (solid).
pub fn dc_svg(rows: &[SeriesRow]) -> Result<String> {
    let ok: Vec<(f64, &PaperComparison)> =
        rows.iter().filter_map(|r| r.fig4.as_ref().ok().map(|f| (r.value, &f.cmp))).collect();
    let paper = ok.iter().find(|q| q.0 == 0.0).map(|q| q.1);
    let sw: Vec<(f64, &PaperComparison)> = ok.iter().filter(|q| q.0 > 0.0).copied().collect();
    let panels: [(&str, Series); 3] = [
        ("F / (mu_s N)", vec![("F_1", |c| (c.f1, c.f1_fe), BLUE), ("F_max", |c| (c.f_max, c.f_max_fe), RED)]),
        ("x_1 / L", vec![("x_1", |c| (c.x1, c.x1_fe), BLUE)]),
        ("n (FE: advancing > 5 t)", vec![("n", |c| (c.n as f64, Some(c.n_fe_advancing as f64)), BLUE)]),
    ];
    let xr = log_range(sw.iter().map(|q| q.0));
    render("dc.svg", (1350, 450), |root| {
        for (area, (ylab, series)) in root.split_evenly((1, 3)).iter().zip(&panels) {
            let yr = series_range(ok.iter().map(|q| q.1), series);
            let mut chart = ChartBuilder::on(area)
                .caption(*ylab, (FONT, 16))
                .margin(12)
                .x_label_area_size(40)
                .y_label_area_size(55)
                .build_cartesian_2d(xr.clone().log_scale(), yr)?;
            chart
                .configure_mesh()
                .x_labels(4)
                .x_desc("D_c (m)")
                .x_label_formatter(&|v| format!("{v:.0e}"))
                .draw()?;
            for &(name, get, col) in series {
                let pts: Vec<(f64, f64)> = sw.iter().filter_map(|(d, c)| get(c).1.map(|v| (*d, v))).collect();
                chart
                    .draw_series(LineSeries::new(pts.clone(), col.stroke_width(2)))?
                    .label(format!("{name}, slip-weakening"))
                    .legend(move |(x, y)| PathElement::new([(x, y), (x + 18, y)], col.stroke_width(2)));
                chart.draw_series(pts.into_iter().map(|q| Circle::new(q, 4, col.filled())))?;
                if let Some(pc) = paper {
                    let (m, f) = get(pc);
                    if let Some(f) = f {
                        chart
                            .draw_series(DashedLineSeries::new(
                                [(xr.start, f), (xr.end, f)],
                                6,
                                4,
                                col.stroke_width(1),
                            ))?
                            .label(format!("{name}, rule paper"))
                            .legend(move |(x, y)| {
                                PathElement::new([(x, y), (x + 18, y)], col.stroke_width(1))
                            });
                    }
                    chart
                        .draw_series(LineSeries::new(
                            [(xr.start, m), (xr.end, m)],
                            col.mix(0.4).stroke_width(3),
                        ))?
                        .label(format!("{name}, model"))
                        .legend(move |(x, y)| {
                            PathElement::new([(x, y), (x + 18, y)], col.mix(0.4).stroke_width(3))
                        });
                }
            }
            chart.legend_box(SeriesLabelPosition::MiddleRight)?;
        }
        Ok(())
    })
}

/// Writes the D_c study into `dir`: `dc.csv` (the series CSV, D_c_m = 0 for the `paper`
/// rule), `dc.svg`, `run.toml`, and each run's fig. 4 in `paper/` and `dc_<D_c>/`
/// (`events.csv`, `loading.csv`, `fig4_fe.svg`, `fronts.svg`, `run.toml`).
pub fn write_dc(
    dir: &Path,
    rows: &[SeriesRow],
    inv: &crate::report::run_file::Invocation,
    scene: &crate::scene::Scene,
) -> Result<Vec<PathBuf>> {
    ensure_dir(dir)?;
    let what: [(&str, f64); 0] = [];
    let files = [
        ("dc.csv", series_csv("Dc_m", "m", rows)?),
        #[cfg(feature = "plots")]
        ("dc.svg", dc_svg(rows)?),
        ("run.toml", crate::report::run_toml(inv, &what, scene)?),
    ];
    let mut written = write_all(dir, &files)?;
    for row in rows {
        let Ok(f) = &row.fig4 else { continue };
        let name = if row.value == 0.0 { "paper".to_string() } else { format!("dc_{:e}", row.value) };
        let sub = dir.join(&name);
        ensure_dir(&sub)?;
        let law = f.run.options.law;
        let what = [("law", law.name()), ("mu_s", law.mu_s().to_string()), ("mu_d", law.mu_d().to_string())];
        let header = crate::report::run_toml(inv, &what, scene)?;
        written.extend(crate::report::slide::write(&f.run, &sub, &header, false)?);
    }
    Ok(written)
}
