//! Outputs of `tribofe sweep`: one tidy CSV (one row per point and load case) and SVG maps of
//! the model's error and validity against the two first swept parameters.

use super::check::{cell, summary_row, SUMMARY_HEADER};
use super::write_atomic;
use crate::error::{Error, Result};
use crate::studies::sweep::{Axis, Param, Point};
#[cfg(feature = "plots")]
use plotters::prelude::*;
use std::path::Path;

/// Columns of the frictional run (F in units of mu_s N, x in units of L): the FE's precursor
/// counts, first long precursor and last stick-slip peak, then the paper's iteration.
const FRICTION_HEADER: &str = "friction_r,friction_g,fe_precursors,fe_precursors_longer_5t,fe_precursors_advancing_5t,fe_F1_over_mu_s_N,fe_x1_over_L,fe_Fmax_over_mu_s_N,model_precursors,model_F1_over_mu_s_N,model_x1_over_L,model_Fmax_over_mu_s_N";

pub fn header(friction: bool) -> String {
    let inputs: Vec<&str> = Param::ALL.iter().map(|p| p.column()).collect();
    format!(
        "point,{},element,{SUMMARY_HEADER},slope_ratio,slope_ratio_corrected,shear_uniformity,edge_zone_fraction_L,tension_onset_FN,tension_onset_FN_model,locking_prone,interior_ok,edges_ok,tension_ok,model_holds,n_unknowns,{}point_wall_s",
        inputs.join(","),
        if friction { format!("{FRICTION_HEADER},") } else { String::new() }
    )
}

/// One cell of the table: a whole number, a number printed with the given digits after the
/// point (None: an empty cell), or text.
enum Cell {
    Int(i64),
    Num(Option<f64>, usize),
    Text(String),
}

impl Cell {
    fn num(v: f64) -> Cell {
        Cell::Num(Some(v), 12)
    }
    fn opt(v: Option<f64>) -> Cell {
        Cell::Num(v, 12)
    }
    fn count(n: usize) -> Cell {
        Cell::Int(n as i64)
    }
    fn text(&self) -> String {
        match self {
            Cell::Int(i) => i.to_string(),
            Cell::Num(v, digits) => cell(*v, *digits),
            Cell::Text(t) => t.clone(),
        }
    }
}

/// A column of the table as an array: whole numbers, numbers (NaN where the CSV cell is
/// empty) or text.
#[derive(Debug, Clone, PartialEq)]
pub enum Column {
    Int(Vec<i64>),
    Float(Vec<f64>),
    Text(Vec<String>),
}

/// The rows of the table (the cells of [`header`]'s columns), one per point and load case.
fn rows(points: &[Point]) -> Result<Vec<Vec<Cell>>> {
    let friction = points.iter().any(|p| p.friction.is_some());
    let mut rows = Vec::new();
    for p in points {
        for (c, v) in p.result.cases.iter().zip(&p.verdicts) {
            let m = &c.metrics;
            let ratio = |a: f64, b: f64| if c.fn_ratio != 0.0 && b != 0.0 { Some(a / b) } else { None };
            let mut cells = vec![Cell::count(p.index + 1)];
            cells.extend(Param::ALL.iter().map(|q| Cell::num(q.get(&p.scene))));
            cells.push(Cell::Text(p.scene.mesh.element.clone()));
            cells.extend(summary_row(c)?.into_iter().map(|(v, d)| Cell::Num(v, d)));
            cells.push(Cell::opt(ratio(m.slope_interior, m.slope_model)));
            cells.push(Cell::opt(ratio(m.slope_interior, m.slope_corrected)));
            cells.push(Cell::opt(ratio(m.tau_center, c.fn_ratio)));
            cells.push(Cell::num(v.edge_zone_fraction));
            cells.push(Cell::opt(v.tension_onset_fn));
            cells.push(Cell::num(v.tension_onset_fn_model));
            for b in [v.locking_prone, v.interior_ok, v.edges_ok, v.tension_ok, v.holds()] {
                cells.push(Cell::Int(i64::from(b)));
            }
            cells.push(Cell::count(p.result.stats.n_unknowns));
            if friction {
                match &p.friction {
                    Some(f) => cells.extend([
                        Cell::num(f.r),
                        Cell::num(f.g),
                        Cell::count(f.n_fe),
                        Cell::count(f.n_fe_long),
                        Cell::count(f.n_fe_advancing),
                        Cell::opt(f.f1_fe),
                        Cell::opt(f.x1_fe),
                        Cell::opt(f.f_max_fe),
                        Cell::count(f.n),
                        Cell::num(f.f1),
                        Cell::num(f.x1),
                        Cell::num(f.f_max),
                    ]),
                    // A point without a frictional comparison (r, g outside the model's
                    // square): every friction column empty.
                    None => cells.extend(FRICTION_HEADER.split(',').map(|_| Cell::opt(None))),
                }
            }
            cells.push(Cell::num(p.wall));
            rows.push(cells);
        }
    }
    Ok(rows)
}

/// The table, with its header line if `with_header` (every file `sweep` writes has it, shards
/// included, so each reads alone; [`merge`] joins shards).
pub fn csv(points: &[Point], with_header: bool) -> Result<String> {
    let mut s = String::new();
    if with_header {
        s.push_str(&header(points.iter().any(|p| p.friction.is_some())));
        s.push('\n');
    }
    for row in rows(points)? {
        let cells: Vec<String> = row.iter().map(Cell::text).collect();
        s.push_str(&cells.join(","));
        s.push('\n');
    }
    Ok(s)
}

/// The table of [`csv`] as named columns (the header's names), for hosts that hand it to
/// numpy or a data frame: the same numbers, not parsed back from text (the CSV prints edge
/// widths to 7 significant digits, the others to 13). A column whose cells are all whole
/// numbers is [`Column::Int`]; one mixing numbers and empty cells is [`Column::Float`].
pub fn columns(points: &[Point]) -> Result<Vec<(String, Column)>> {
    let names = header(points.iter().any(|p| p.friction.is_some()));
    let rows = rows(points)?;
    let mut out = Vec::new();
    for (j, name) in names.split(',').enumerate() {
        let cells: Vec<&Cell> = rows.iter().filter_map(|r| r.get(j)).collect();
        let column = if !cells.is_empty() && cells.iter().all(|c| matches!(c, Cell::Int(_))) {
            Column::Int(cells.iter().map(|c| if let Cell::Int(i) = c { *i } else { 0 }).collect())
        } else if cells.iter().all(|c| !matches!(c, Cell::Text(_))) {
            Column::Float(
                cells
                    .iter()
                    .map(|c| match c {
                        Cell::Int(i) => *i as f64,
                        Cell::Num(v, _) => v.unwrap_or(f64::NAN),
                        Cell::Text(_) => f64::NAN,
                    })
                    .collect(),
            )
        } else {
            Column::Text(cells.iter().map(|c| c.text()).collect())
        };
        out.push((name.to_string(), column));
    }
    Ok(out)
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
