//! Outputs of `tribofe sweep`: one tidy CSV (one row per point and load case) and SVG maps of
//! the model's error and validity against the two first swept parameters.

use super::check::{summary_row, SUMMARY_HEADER, SUMMARY_UNITS};
use super::table::{Column, Table};
use super::write_atomic;
use crate::error::{Error, Result};
use crate::studies::slide::PaperComparison;
use crate::studies::sweep::{Axis, Param, Point, Verdict};
#[cfg(feature = "plots")]
use plotters::prelude::*;
use std::path::Path;

/// sweep.csv's table (one row per point and load case), the one schema the CSV is printed
/// from and a front end takes: 13 significant digits, the edge widths 7 (as check's
/// summary.csv); empty where a figure is undefined. With any frictional run, its columns (F
/// in units of mu_s N, x in units of L): the FE's precursor counts, first long precursor and
/// last stick-slip peak, then the paper's iteration; a point without a frictional comparison
/// ((r, g) outside the model's square) has them all empty.
pub fn table(points: &[Point]) -> Result<Table> {
    let rows: Vec<(&Point, usize)> = points
        .iter()
        .flat_map(|p| (0..p.result.cases.len().min(p.verdicts.len())).map(move |k| (p, k)))
        .collect();
    let summary = rows.iter().map(|(p, k)| summary_row(&p.result.cases[*k])).collect::<Result<Vec<_>>>()?;
    let f = |get: &dyn Fn(&Point, usize) -> f64| rows.iter().map(|(p, k)| get(p, *k)).collect::<Vec<f64>>();
    let opt = |get: &dyn Fn(&Point, usize) -> Option<f64>| {
        rows.iter().map(|(p, k)| get(p, *k).unwrap_or(f64::NAN)).collect::<Vec<f64>>()
    };
    let flag = |get: &dyn Fn(&Verdict) -> bool| {
        rows.iter().map(|(p, k)| i64::from(get(&p.verdicts[*k]))).collect::<Vec<i64>>()
    };
    let mut columns = vec![Column::int("point", "-", rows.iter().map(|(p, _)| p.index as i64 + 1).collect())];
    columns
        .extend(Param::ALL.iter().map(|q| Column::float(q.column(), q.unit(), f(&|p, _| q.get(&p.scene)))));
    columns.push(Column::text(
        "element",
        "-",
        rows.iter().map(|(p, _)| p.scene.mesh.element.clone()).collect(),
    ));
    for (j, (name, unit)) in SUMMARY_HEADER.split(',').zip(SUMMARY_UNITS).enumerate() {
        let column = Column::maybe(name, unit, summary.iter().map(|r| r[j].0.unwrap_or(f64::NAN)).collect());
        // summary_row's digits after the point (check's summary.csv prints the same).
        columns.push(match summary.first().map(|r| r[j].1) {
            Some(d) if d != 12 => column.with_digits(d + 1),
            _ => column,
        });
    }
    let ratio = |p: &Point,
                 k: usize,
                 a: fn(&crate::studies::check::Metrics) -> f64,
                 b: fn(&crate::studies::check::Metrics) -> f64| {
        let c = &p.result.cases[k];
        let (a, b) = (a(&c.metrics), b(&c.metrics));
        (c.fn_ratio != 0.0 && b != 0.0).then(|| a / b)
    };
    columns.extend([
        Column::maybe("slope_ratio", "1", opt(&|p, k| ratio(p, k, |m| m.slope_interior, |m| m.slope_model))),
        Column::maybe(
            "slope_ratio_corrected",
            "1",
            opt(&|p, k| ratio(p, k, |m| m.slope_interior, |m| m.slope_corrected)),
        ),
        Column::maybe(
            "shear_uniformity",
            "1",
            opt(&|p, k| {
                let c = &p.result.cases[k];
                (c.fn_ratio != 0.0).then(|| c.metrics.tau_center / c.fn_ratio)
            }),
        ),
        Column::float("edge_zone_fraction_L", "1", f(&|p, k| p.verdicts[k].edge_zone_fraction)),
        Column::maybe("tension_onset_FN", "1", opt(&|p, k| p.verdicts[k].tension_onset_fn)),
        Column::float("tension_onset_FN_model", "1", f(&|p, k| p.verdicts[k].tension_onset_fn_model)),
        Column::int("locking_prone", "-", flag(&|v| v.locking_prone)),
        Column::int("interior_ok", "-", flag(&|v| v.interior_ok)),
        Column::int("edges_ok", "-", flag(&|v| v.edges_ok)),
        Column::int("tension_ok", "-", flag(&|v| v.tension_ok)),
        Column::int("model_holds", "-", flag(&|v| v.holds())),
        Column::int("n_unknowns", "-", rows.iter().map(|(p, _)| p.result.stats.n_unknowns as i64).collect()),
    ]);
    if points.iter().any(|p| p.friction.is_some()) {
        let fr = |get: &dyn Fn(&PaperComparison) -> Option<f64>| {
            rows.iter()
                .map(|(p, _)| p.friction.as_ref().and_then(get).unwrap_or(f64::NAN))
                .collect::<Vec<f64>>()
        };
        let count = |get: &dyn Fn(&PaperComparison) -> usize| {
            rows.iter().map(|(p, _)| p.friction.as_ref().map(|f| get(f) as i64)).collect::<Vec<Option<i64>>>()
        };
        columns.extend([
            Column::maybe("friction_r", "1", fr(&|f| Some(f.r))),
            Column::maybe("friction_g", "1", fr(&|f| Some(f.g))),
            Column::maybe_int("fe_precursors", "-", count(&|f| f.n_fe)),
            Column::maybe_int("fe_precursors_longer_5t", "-", count(&|f| f.n_fe_long)),
            Column::maybe_int("fe_precursors_advancing_5t", "-", count(&|f| f.n_fe_advancing)),
            Column::maybe("fe_F1_over_mu_s_N", "1", fr(&|f| f.f1_fe)),
            Column::maybe("fe_x1_over_L", "1", fr(&|f| f.x1_fe)),
            Column::maybe("fe_Fmax_over_mu_s_N", "1", fr(&|f| f.f_max_fe)),
            Column::maybe_int("model_precursors", "-", count(&|f| f.n)),
            Column::maybe("model_F1_over_mu_s_N", "1", fr(&|f| Some(f.f1))),
            Column::maybe("model_x1_over_L", "1", fr(&|f| Some(f.x1))),
            Column::maybe("model_Fmax_over_mu_s_N", "1", fr(&|f| Some(f.f_max))),
        ]);
    }
    columns.push(Column::float("point_wall_s", "s", f(&|p, _| p.wall)));
    Ok(Table { columns, digits: 13 })
}

/// sweep.csv printed from [`table`], with its header line if `with_header` (every file
/// `sweep` writes has it, shards included, so each reads alone; [`merge`] joins shards).
pub fn csv(points: &[Point], with_header: bool) -> Result<String> {
    let text = table(points)?.csv()?;
    Ok(if with_header {
        text
    } else {
        text.split_once('\n').map_or(String::new(), |(_, rows)| rows.to_string())
    })
}

/// Shard `(i, n)` of a shard file name `sweep_<i>of<n>.csv`.
pub fn shard_of(name: &str) -> Option<(usize, usize)> {
    let (i, n) = name.strip_prefix("sweep_")?.strip_suffix(".csv")?.split_once("of")?;
    Some((i.parse().ok()?, n.parse().ok()?))
}

/// Joins shard tables, given as (file name `sweep_<i>of<n>.csv`, text), into the whole sweep's
/// table: one header, rows in shard order. Every shard 1..=n must be there once and all must
/// share one header; a shard written rows-only (before shards carried the header) takes it
/// from the others. Point numbers must increase from shard to shard.
pub fn merge(parts: &[(String, String)]) -> Result<String> {
    let mut shards: Vec<(usize, usize, &str, &str)> = Vec::new();
    for (name, text) in parts {
        let (i, n) = shard_of(name).filter(|&(i, n)| i >= 1 && i <= n).ok_or_else(|| {
            Error::input(
                crate::error::quote(name),
                "is not a shard file name sweep_<I>of<N>.csv with 1 <= I <= N",
            )
        })?;
        shards.push((i, n, name, text));
    }
    shards.sort_by_key(|s| s.0);
    let n =
        shards.first().ok_or_else(|| Error::input("--merge", "no shard file sweep_<I>of<N>.csv found"))?.1;
    if let Some(s) = shards.iter().find(|s| s.1 != n) {
        return Err(Error::input(s.2, format!("is a shard of {} but others are of {n}: not one sweep", s.1)));
    }
    if let Some(w) = shards.windows(2).find(|w| w[0].0 == w[1].0) {
        return Err(Error::input(
            w[1].2,
            format!("shard {} is given twice ({} and {})", w[0].0, w[0].2, w[1].2),
        ));
    }
    let have: Vec<usize> = shards.iter().map(|s| s.0).collect();
    let missing: Vec<String> =
        (1..=n).filter(|i| !have.contains(i)).map(|i| format!("sweep_{i}of{n}.csv")).collect();
    if !missing.is_empty() {
        return Err(Error::input(
            "--merge",
            format!("missing shard(s) {}: run them or add their folder", missing.join(", ")),
        ));
    }
    let is_header = |l: &str| l.starts_with("point,");
    let header = shards
        .iter()
        .filter_map(|s| s.3.lines().next().filter(|l| is_header(l)))
        .next()
        .ok_or_else(|| Error::input("--merge", "no shard has a header line"))?;
    let mut out = format!("{header}\n");
    let mut last_point = 0usize;
    for (_, _, name, text) in &shards {
        let mut lines = text.lines().peekable();
        match lines.peek() {
            Some(l) if is_header(l) && *l != header => {
                return Err(Error::input(*name, "has another header than the other shards: not one sweep"))
            }
            Some(l) if is_header(l) => {
                lines.next();
            }
            _ => {}
        }
        let mut first = true;
        for (k, line) in lines.enumerate().filter(|(_, l)| !l.trim().is_empty()) {
            let point: usize = line.split(',').next().and_then(|v| v.parse().ok()).ok_or_else(|| {
                Error::input(
                    *name,
                    format!("row {}: no point number in '{}'", k + 1, crate::error::quote(line)),
                )
            })?;
            if point < last_point || (first && point == last_point) {
                return Err(Error::input(
                    *name,
                    format!(
                        "row {}: point {point} does not follow point {last_point} of the shards before",
                        k + 1
                    ),
                ));
            }
            first = false;
            last_point = point;
            out.push_str(line);
            out.push('\n');
        }
    }
    Ok(out)
}

/// A map: file name, title (with its unit), whether the value is a yes/no verdict, value per
/// (point, case).
type Quantity = (&'static str, &'static str, bool, fn(&Point, usize) -> Option<f64>);

/// With the frictional run: the FE's last stick-slip peak against the model's F_max, and
/// the FE's precursors that advance the front by more than 5 t before the first whole slip.
const FRICTION_MAPS: [Quantity; 2] = [
    ("map_friction_fmax_ratio.svg", "stick-slip peak FE / model F_max (dimensionless)", false, |p, _| {
        p.friction.and_then(|f| Some(f.f_max_fe? / f.f_max))
    }),
    ("map_friction_precursors.svg", "FE precursors advancing the front > 5 t (count)", false, |p, _| {
        p.friction.map(|f| f.n_fe_advancing as f64)
    }),
];

const MAPS: [Quantity; 7] = [
    ("map_slope_ratio.svg", "interior slope FE / model (dimensionless)", false, |p, c| {
        let m = &p.result.cases[c].metrics;
        (p.result.cases[c].fn_ratio != 0.0).then(|| m.slope_interior / m.slope_model)
    }),
    (
        "map_slope_ratio_corrected.svg",
        "interior slope FE / corrected model (dimensionless)",
        false,
        |p, c| {
            let m = &p.result.cases[c].metrics;
            (p.result.cases[c].fn_ratio != 0.0).then(|| m.slope_interior / m.slope_corrected)
        },
    ),
    ("map_shear_uniformity.svg", "tau(0) / (F/N) (dimensionless)", false, |p, c| {
        let k = &p.result.cases[c];
        (k.fn_ratio != 0.0).then(|| k.metrics.tau_center / k.fn_ratio)
    }),
    ("map_edge_zones.svg", "widest edge zone / L (dimensionless)", false, |p, c| {
        Some(p.verdicts[c].edge_zone_fraction)
    }),
    (
        "map_tension_onset.svg",
        "F/N at tension one t inside the trailing end (dimensionless)",
        false,
        |p, c| p.verdicts[c].tension_onset_fn,
    ),
    ("map_residual_corrected.svg", "interior |p - corrected| / (N/L) (dimensionless)", false, |p, c| {
        Some(p.result.cases[c].metrics.interior_dev_p_corrected)
    }),
    ("map_verdict.svg", "verdict: the paper's model holds", true, |p, c| {
        Some(f64::from(u8::from(p.verdicts[c].holds())))
    }),
];

/// Axis title with its unit.
pub fn axis_title(p: Param) -> &'static str {
    match p {
        Param::Length => "block length L (m)",
        Param::Thickness => "block thickness t (m)",
        Param::Height => "loading height H (m)",
        Param::Young => "Young's modulus E (Pa)",
        Param::Poisson => "Poisson's ratio nu (dimensionless)",
    }
}

/// Without the `plots` feature: no figure, none written.
#[cfg(not(feature = "plots"))]
pub fn write_maps(_points: &[Point], _axes: &[Axis], _dir: &Path) -> Result<Vec<String>> {
    Ok(vec![])
}

#[cfg(feature = "plots")]
/// Writes one figure per quantity for the largest F/N: a map over the first two axes with
/// more than one value (the other axes at their first value, stated in the title), or a line
/// plot when only one axis has several values. Returns the files written (none when no axis
/// has two values).
pub fn write_maps(points: &[Point], axes: &[Axis], dir: &Path) -> Result<Vec<String>> {
    let multi: Vec<usize> = (0..axes.len()).filter(|&i| axes[i].values.len() > 1).collect();
    if multi.is_empty() {
        return Ok(vec![]);
    }
    let shown = &multi[..multi.len().min(2)];
    // The slice: every other multi-valued axis at its first value.
    let slice: Vec<String> = multi[shown.len()..]
        .iter()
        .map(|&i| {
            let a = &axes[i];
            let unit = match a.param {
                Param::Poisson => "",
                Param::Young => " Pa",
                _ => " m",
            };
            format!("{} = {:.4e}{unit} (first of its {} values)", a.param.flag(), a.values[0], a.values.len())
        })
        .collect();
    let mut written = Vec::new();
    let friction = points.iter().any(|p| p.friction.is_some());
    let extra = if friction { &FRICTION_MAPS[..] } else { &[] };
    let fn_ratio = points.first().map_or(0.0, |p| p.result.cases.last().map_or(0.0, |c| c.fn_ratio));
    for &(file, title, boolean, f) in MAPS.iter().chain(extra) {
        let mut cells = Vec::new();
        for p in points {
            let fixed_ok = axes
                .iter()
                .enumerate()
                .all(|(i, a)| shown.contains(&i) || a.param.get(&p.scene) == a.values[0]);
            if !fixed_ok {
                continue;
            }
            let c = p.result.cases.len() - 1;
            let pos = |a: &Axis| a.values.iter().position(|&v| v == a.param.get(&p.scene));
            let iy = if shown.len() == 2 { pos(&axes[shown[1]]) } else { Some(0) };
            if let (Some(ix), Some(iy)) = (pos(&axes[shown[0]]), iy) {
                cells.push((ix, iy, f(p, c).filter(|v| v.is_finite())));
            }
        }
        let mut heading = format!("{title}, F/N = {fn_ratio}");
        if !slice.is_empty() {
            heading.push_str(&format!("; slice at {}", slice.join(", ")));
        }
        let q = Figure { file, title: &heading, short: title, boolean };
        let svg = match shown {
            [x, y] => heat_map(&q, &axes[*x], &axes[*y], &cells)?,
            _ => line_plot(&q, &axes[shown[0]], &cells)?,
        };
        write_atomic(&dir.join(file), svg.as_bytes())?;
        written.push(file.to_string());
    }
    Ok(written)
}

#[cfg(feature = "plots")]
use super::plot::{render, Area, Drawn, Legend, FONT};

#[cfg(feature = "plots")]
/// What a figure shows: its file name, the full title, the quantity's name (colour bar, y
/// axis), and whether it is a yes/no verdict (categorical colours, no scale).
struct Figure<'a> {
    file: &'a str,
    title: &'a str,
    short: &'a str,
    boolean: bool,
}

#[cfg(feature = "plots")]
const HOLDS: RGBColor = RGBColor(44, 160, 44);
#[cfg(feature = "plots")]
const FAILS: RGBColor = RGBColor(214, 39, 40);
#[cfg(feature = "plots")]
const MISSING: RGBColor = RGBColor(200, 200, 200);

#[cfg(feature = "plots")]
/// Sequential colour scale from blue (0) to red (1).
fn scale(f: f64) -> RGBColor {
    let f = f.clamp(0.0, 1.0);
    RGBColor(
        (40.0 + 215.0 * f) as u8,
        (90.0 + 80.0 * (1.0 - (2.0 * f - 1.0).abs())) as u8,
        (255.0 - 215.0 * f) as u8,
    )
}

#[cfg(feature = "plots")]
/// Decimals that tell the values of a range apart (3 at least, 10 at most).
fn decimals(lo: f64, hi: f64) -> usize {
    let span = hi - lo;
    if span > 0.0 && span.is_finite() {
        (2.0 - span.log10().floor()).clamp(3.0, 10.0) as usize
    } else {
        3
    }
}

#[cfg(feature = "plots")]
fn value_range(cells: &[(usize, usize, Option<f64>)]) -> (f64, f64) {
    cells.iter().filter_map(|c| c.2).fold((f64::MAX, f64::MIN), |(a, b), v| (a.min(v), b.max(v)))
}

#[cfg(feature = "plots")]
/// Tick label of value `i` of an axis (the grid's values, not an index).
fn tick(vals: &[f64], i: f64) -> String {
    let k = i.round();
    if (i - k).abs() > 1e-6 || k < 0.0 {
        return String::new();
    }
    vals.get(k as usize).map_or(String::new(), |v| format!("{v:.3e}"))
}

#[cfg(feature = "plots")]
fn heat_map(q: &Figure, ax: &Axis, ay: &Axis, cells: &[(usize, usize, Option<f64>)]) -> Result<String> {
    let (lo, hi) = value_range(cells);
    let (nx, ny) = (ax.values.len(), ay.values.len());
    render(q.file, (1000, 660), |root| {
        let root = root.titled(q.title, (FONT, 17))?;
        let (main, side) = root.split_horizontally(820);
        let xl = |i: &f64| tick(&ax.values, *i);
        let yl = |i: &f64| tick(&ay.values, *i);
        let mut chart = ChartBuilder::on(&main)
            .margin(15)
            .x_label_area_size(50)
            .y_label_area_size(90)
            .build_cartesian_2d(-0.5f64..nx as f64 - 0.5, -0.5f64..ny as f64 - 0.5)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_labels(nx.min(16))
            .y_labels(ny.min(16))
            .x_label_formatter(&xl)
            .y_label_formatter(&yl)
            .x_desc(axis_title(ax.param))
            .y_desc(axis_title(ay.param))
            .axis_desc_style((FONT, 15))
            .draw()?;
        let colour = |v: Option<f64>| match v {
            Some(v) if q.boolean => {
                if v != 0.0 {
                    HOLDS
                } else {
                    FAILS
                }
            }
            Some(v) => scale(if hi > lo { (v - lo) / (hi - lo) } else { 0.5 }),
            None => MISSING,
        };
        for &(ix, iy, v) in cells {
            let (x0, y0) = (ix as f64 - 0.5, iy as f64 - 0.5);
            chart.draw_series(std::iter::once(Rectangle::new(
                [(x0, y0), (x0 + 1.0, y0 + 1.0)],
                colour(v).filled(),
            )))?;
            if nx * ny <= 400 {
                let label = match v {
                    None => "-".to_string(),
                    Some(v) if q.boolean => (if v != 0.0 { "holds" } else { "fails" }).to_string(),
                    Some(v) => format!("{v:.*}", decimals(lo, hi)),
                };
                chart.draw_series(std::iter::once(Text::new(label, (x0 + 0.08, y0 + 0.55), (FONT, 11))))?;
            }
        }
        side_key(&side, q, lo, hi)
    })
}

#[cfg(feature = "plots")]
/// The colour bar (continuous) or the categorical key (verdicts), with the grey of no value.
fn side_key(area: &Area, q: &Figure, lo: f64, hi: f64) -> Drawn {
    let font = (FONT, 13);
    let swatch = |y: i32, c: RGBColor, label: &str| -> Drawn {
        area.draw(&Rectangle::new([(10, y), (32, y + 18)], c.filled()))?;
        area.draw(&Rectangle::new([(10, y), (32, y + 18)], BLACK.stroke_width(1)))?;
        area.draw(&Text::new(label.to_string(), (38, y + 3), font))?;
        Ok(())
    };
    if q.boolean || !(hi >= lo) {
        let mut y = 40;
        if q.boolean {
            swatch(y, HOLDS, "holds (1)")?;
            swatch(y + 28, FAILS, "fails (0)")?;
            y += 56;
        }
        return swatch(y, MISSING, "no value");
    }
    let (lo, hi) = if hi > lo { (lo, hi) } else { (lo - 0.5, hi + 0.5) };
    let mut bar = ChartBuilder::on(area)
        .margin_top(30)
        .margin_bottom(110)
        .margin_right(5)
        .y_label_area_size(0)
        .right_y_label_area_size(70)
        .build_cartesian_2d(0.0f64..1.0, lo..hi)?;
    bar.configure_mesh()
        .disable_mesh()
        .disable_x_axis()
        .y_labels(6)
        .y_label_formatter(&|v: &f64| format!("{v:.*}", decimals(lo, hi)))
        .draw()?;
    let steps = 100;
    bar.draw_series((0..steps).map(|k| {
        let (a, b) =
            (lo + (hi - lo) * k as f64 / steps as f64, lo + (hi - lo) * (k + 1) as f64 / steps as f64);
        Rectangle::new([(0.0, a), (1.0, b)], scale((k as f64 + 0.5) / steps as f64).filled())
    }))?;
    let (_, h) = area.dim_in_pixel();
    swatch(h as i32 - 95, MISSING, "no value")?;
    area.draw(&Text::new("colour scale:".to_string(), (8, 8), font))?;
    Ok(())
}

#[cfg(feature = "plots")]
/// One swept parameter: the quantity against it (verdicts as holds / fails).
fn line_plot(q: &Figure, ax: &Axis, cells: &[(usize, usize, Option<f64>)]) -> Result<String> {
    let mut pts: Vec<(f64, f64)> = cells.iter().filter_map(|&(i, _, v)| Some((ax.values[i], v?))).collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (xlo, xhi) = ax.values.iter().fold((f64::MAX, f64::MIN), |(a, b), &v| (a.min(v), b.max(v)));
    let pad = if xhi > xlo { 0.05 * (xhi - xlo) } else { 0.5 * xlo.abs().max(1e-12) };
    let (lo, hi) = if q.boolean { (0.0, 1.0) } else { value_range(cells) };
    let (lo, hi) = match (lo <= hi, hi > lo) {
        (false, _) => (0.0, 1.0),
        (true, true) => (lo - 0.08 * (hi - lo), hi + 0.08 * (hi - lo)),
        (true, false) => (lo - 0.5 * lo.abs().max(1e-12), hi + 0.5 * hi.abs().max(1e-12)),
    };
    let (lo, hi) = if q.boolean { (-0.3, 1.3) } else { (lo, hi) };
    let missing: Vec<f64> = cells.iter().filter(|c| c.2.is_none()).map(|c| ax.values[c.0]).collect();
    render(q.file, (900, 560), |root| {
        let mut chart = ChartBuilder::on(root)
            .caption(q.title, (FONT, 17))
            .margin(15)
            .x_label_area_size(50)
            .y_label_area_size(90)
            .build_cartesian_2d((xlo - pad)..(xhi + pad), lo..hi)?;
        let yl = |v: &f64| {
            if !q.boolean {
                format!("{v:.*}", decimals(lo, hi))
            } else if (v - 1.0).abs() < 1e-9 {
                "holds".into()
            } else if v.abs() < 1e-9 {
                "fails".into()
            } else {
                String::new()
            }
        };
        let mut mesh = chart.configure_mesh();
        mesh.x_desc(axis_title(ax.param))
            .y_desc(if q.boolean { "verdict" } else { q.short })
            .axis_desc_style((FONT, 15))
            .x_label_formatter(&|v: &f64| format!("{v:.3e}"))
            .y_label_formatter(&yl);
        if q.boolean {
            mesh.y_labels(14);
        }
        mesh.draw()?;
        if !q.boolean {
            chart.draw_series(LineSeries::new(pts.clone(), BLUE.stroke_width(2)))?;
        }
        chart.draw_series(pts.iter().map(|&(x, y)| {
            let c = if !q.boolean {
                BLUE
            } else if y != 0.0 {
                HOLDS
            } else {
                FAILS
            };
            Circle::new((x, y), 5, c.filled())
        }))?;
        if !missing.is_empty() {
            let y = lo + 0.04 * (hi - lo);
            chart
                .draw_series(missing.iter().map(|&x| Cross::new((x, y), 5, MISSING.stroke_width(2))))?
                .label("no value at this point")
                .legend(|(x, y)| Cross::new((x, y), 5, MISSING.stroke_width(2)));
            chart.legend_box(SeriesLabelPosition::MiddleRight)?;
        }
        Ok(())
    })
}
