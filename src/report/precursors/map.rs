//! The model's n(r, g) over the (r, g) square (the paper's fig. 5): `n_map.csv`, `fig5.svg`.

#[cfg(feature = "plots")]
use super::super::plot::{n_colour, n_key, render, Legend, FONT, RED};
use super::super::table::{Column, Format, Table};
use super::super::{ensure_dir, write_all};
use crate::precursors::MapPoint;
use crate::Result;
#[cfg(feature = "plots")]
use plotters::prelude::*;
use std::path::{Path, PathBuf};

/// `n_map.csv`'s table: per cell centre r, g (the shortest decimals) and the model's n. The
/// one definition the CSV and the Python package's table are made from.
pub fn n_map_table(map: &[MapPoint]) -> Table {
    let shortest =
        |name: &'static str, v: Vec<f64>| Column::float(name, "1", v).with_format(Format::Shortest);
    Table {
        columns: vec![
            shortest("r", map.iter().map(|m| m.r).collect()),
            shortest("g", map.iter().map(|m| m.g).collect()),
            Column::int("n", "-", map.iter().map(|m| m.n as i64).collect()),
        ],
        digits: 17,
    }
}

/// `n_map.csv` ([`n_map_table`]): header `r,g,n`.
pub fn n_map_csv(map: &[MapPoint]) -> Result<String> {
    n_map_table(map).csv()
}

#[cfg(feature = "plots")]
/// The paper's fig. 5: n(r, g) as a colour map (logarithmic in 1 + n, since n runs from 0
/// to thousands near (1, 1)), with a colour key and the no-precursor line g = (1-r)/2.
pub fn fig5_svg(map: &[MapPoint], resolution: usize) -> Result<String> {
    let n_max = map.iter().map(|m| m.n).max().unwrap_or(0);
    let colour = |n: usize| n_colour(n, n_max);
    let half = 0.5 / resolution as f64;
    render("fig5.svg", (900, 720), |root| {
        let (main, key) = root.split_horizontally(760);
        let mut chart = ChartBuilder::on(&main)
            .caption("Number of precursors n(r, g) (paper fig. 5)", (FONT, 20))
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(60)
            .build_cartesian_2d(0.0..1.0, 0.0..1.0)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc("r = mu_d / mu_s  (dimensionless)")
            .y_desc("g = 6 mu_d H / L  (dimensionless)")
            .draw()?;
        chart.draw_series(map.iter().map(|m| {
            Rectangle::new([(m.r - half, m.g - half), (m.r + half, m.g + half)], colour(m.n).filled())
        }))?;
        chart
            .draw_series(LineSeries::new([(0.0, 0.5), (1.0, 0.0)], RED.stroke_width(3)))?
            .label("g = (1 - r)/2: no precursor below")
            .legend(|(x, y)| PathElement::new([(x, y), (x + 20, y)], RED.stroke_width(3)));
        chart.legend_box(SeriesLabelPosition::UpperRight)?;
        n_key(&key, n_max)?;
        Ok(())
    })
}

/// Writes `n_map.csv` and `fig5.svg` into `dir` (created if needed); returns the paths.
pub fn write_map(dir: &Path, map: &[MapPoint], resolution: usize) -> Result<Vec<PathBuf>> {
    ensure_dir(dir)?;
    let mut files = vec![("n_map.csv", n_map_csv(map)?)];
    #[cfg(feature = "plots")]
    files.push(("fig5.svg", fig5_svg(map, resolution)?));
    write_all(dir, &files)
}
