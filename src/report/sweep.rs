//! Outputs of `tribofe sweep`: one tidy CSV (one row per point and load case) and SVG maps of
//! the model's error and validity against the two first swept parameters.

use super::check::{summary_csv, SUMMARY_HEADER};
use super::write_atomic;
use crate::error::{Error, Result};
use crate::studies::sweep::{Axis, Param, Point};
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

fn e(v: f64) -> String {
    format!("{v:.12e}")
}
fn opt(v: Option<f64>) -> String {
    v.map_or(String::new(), e)
}

/// The table, with its header line if `with_header` (every file `sweep` writes has it, shards
/// included, so each reads alone; [`merge`] joins shards).
pub fn csv(points: &[Point], with_header: bool) -> Result<String> {
    let mut s = String::new();
    let friction = points.iter().any(|p| p.friction.is_some());
    if with_header {
        s.push_str(&header(friction));
        s.push('\n');
    }
    for p in points {
        let summary = summary_csv(&p.result)?;
        for ((c, line), v) in p.result.cases.iter().zip(summary.lines().skip(1)).zip(&p.verdicts) {
            let m = &c.metrics;
            let ratio = |a: f64, b: f64| if c.fn_ratio != 0.0 && b != 0.0 { Some(a / b) } else { None };
            let mut cells = vec![(p.index + 1).to_string()];
            cells.extend(Param::ALL.iter().map(|q| e(q.get(&p.scene))));
            cells.push(p.scene.mesh.element.clone());
            cells.push(line.to_string());
            cells.push(opt(ratio(m.slope_interior, m.slope_model)));
            cells.push(opt(ratio(m.slope_interior, m.slope_corrected)));
            cells.push(opt(ratio(m.tau_center, c.fn_ratio)));
            cells.push(e(v.edge_zone_fraction));
            cells.push(opt(v.tension_onset_fn));
            cells.push(e(v.tension_onset_fn_model));
            for b in [v.locking_prone, v.interior_ok, v.edges_ok, v.tension_ok, v.holds()] {
                cells.push(u8::from(b).to_string());
            }
            cells.push(p.result.stats.n_unknowns.to_string());
            if friction {
                match &p.friction {
                    Some(f) => cells.extend([
                        e(f.r),
                        e(f.g),
                        f.n_fe.to_string(),
                        f.n_fe_long.to_string(),
                        f.n_fe_advancing.to_string(),
                        opt(f.f1_fe),
                        opt(f.x1_fe),
                        opt(f.f_max_fe),
                        f.n.to_string(),
                        e(f.f1),
                        e(f.x1),
                        e(f.f_max),
                    ]),
                    None => cells.extend(std::iter::repeat_n(String::new(), 11)),
                }
            }
            cells.push(e(p.wall));
            s.push_str(&cells.join(","));
            s.push('\n');
        }
    }
    Ok(s)
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

/// A map: name, title, value per (point, case).
type Quantity = (&'static str, &'static str, fn(&Point, usize) -> Option<f64>);

/// With the frictional run: the FE's last stick-slip peak against the model's F_max, and
/// the FE's precursors that advance the front by more than 5 t before the first whole slip.
const FRICTION_MAPS: [Quantity; 2] = [
    ("map_friction_fmax_ratio.svg", "stick-slip peak FE / model F_max", |p, _| {
        p.friction.and_then(|f| Some(f.f_max_fe? / f.f_max))
    }),
    ("map_friction_precursors.svg", "FE precursors advancing the front > 5 t", |p, _| {
        p.friction.map(|f| f.n_fe_advancing as f64)
    }),
];

const MAPS: [Quantity; 7] = [
    ("map_slope_ratio.svg", "interior slope FE / model", |p, c| {
        let m = &p.result.cases[c].metrics;
        (p.result.cases[c].fn_ratio != 0.0).then(|| m.slope_interior / m.slope_model)
    }),
    ("map_slope_ratio_corrected.svg", "interior slope FE / corrected model", |p, c| {
        let m = &p.result.cases[c].metrics;
        (p.result.cases[c].fn_ratio != 0.0).then(|| m.slope_interior / m.slope_corrected)
    }),
    ("map_shear_uniformity.svg", "tau(0) / (F/N)", |p, c| {
        let k = &p.result.cases[c];
        (k.fn_ratio != 0.0).then(|| k.metrics.tau_center / k.fn_ratio)
    }),
    ("map_edge_zones.svg", "widest edge zone / L", |p, c| Some(p.verdicts[c].edge_zone_fraction)),
    ("map_tension_onset.svg", "F/N at tension one t inside the trailing end", |p, c| {
        p.verdicts[c].tension_onset_fn
    }),
    ("map_residual_corrected.svg", "interior |p - corrected| / (N/L)", |p, c| {
        Some(p.result.cases[c].metrics.interior_dev_p_corrected)
    }),
    ("map_verdict.svg", "model holds (1) or not (0)", |p, c| {
        Some(f64::from(u8::from(p.verdicts[c].holds())))
    }),
];

/// Writes the maps over the first two axes with more than one value, for the largest F/N;
/// the other axes at their first value. Returns the files written (none with < 2 such axes).
pub fn write_maps(points: &[Point], axes: &[Axis], dir: &Path) -> Result<Vec<String>> {
    let multi: Vec<usize> = (0..axes.len()).filter(|&i| axes[i].values.len() > 1).collect();
    if multi.len() < 2 {
        return Ok(vec![]);
    }
    let (ax, ay) = (&axes[multi[0]], &axes[multi[1]]);
    let mut written = Vec::new();
    let friction = points.iter().any(|p| p.friction.is_some());
    let extra = if friction { &FRICTION_MAPS[..] } else { &[] };
    for &(file, title, f) in MAPS.iter().chain(extra) {
        let mut cells = Vec::new();
        for p in points {
            let fixed_ok = axes
                .iter()
                .enumerate()
                .all(|(i, a)| i == multi[0] || i == multi[1] || a.param.get(&p.scene) == a.values[0]);
            if !fixed_ok {
                continue;
            }
            let c = p.result.cases.len() - 1;
            let ix = ax.values.iter().position(|&v| v == ax.param.get(&p.scene));
            let iy = ay.values.iter().position(|&v| v == ay.param.get(&p.scene));
            if let (Some(ix), Some(iy)) = (ix, iy) {
                cells.push((ix, iy, f(p, c)));
            }
        }
        let fn_ratio = points.first().map_or(0.0, |p| p.result.cases.last().map_or(0.0, |c| c.fn_ratio));
        let svg = heat_map(&format!("{title}, F/N = {fn_ratio}"), ax, ay, &cells)?;
        write_atomic(&dir.join(file), svg.as_bytes())?;
        written.push(file.to_string());
    }
    Ok(written)
}

fn err(e: impl std::fmt::Display) -> Error {
    Error::input("sweep map", e.to_string())
}

fn heat_map(title: &str, ax: &Axis, ay: &Axis, cells: &[(usize, usize, Option<f64>)]) -> Result<String> {
    let vals: Vec<f64> = cells.iter().filter_map(|c| c.2).filter(|v| v.is_finite()).collect();
    let (lo, hi) = vals.iter().fold((f64::MAX, f64::MIN), |(a, b), &v| (a.min(v), b.max(v)));
    let (nx, ny) = (ax.values.len(), ay.values.len());
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (900, 640)).into_drawing_area();
        root.fill(&WHITE).map_err(err)?;
        let at = |vals: &[f64], i: f64| -> String {
            let k = i.round();
            if (i - k).abs() > 1e-6 || k < 0.0 {
                return String::new();
            }
            vals.get(k as usize).map_or(String::new(), |v| format!("{v:.3e}"))
        };
        let xl = |i: &f64| at(&ax.values, *i);
        let yl = |i: &f64| at(&ay.values, *i);
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 20))
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(80)
            .build_cartesian_2d(-0.5f64..nx as f64 - 0.5, -0.5f64..ny as f64 - 0.5)
            .map_err(err)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_labels(nx.min(16))
            .y_labels(ny.min(16))
            .x_label_formatter(&xl)
            .y_label_formatter(&yl)
            .x_desc(ax.param.column())
            .y_desc(ay.param.column())
            .draw()
            .map_err(err)?;
        for &(ix, iy, v) in cells {
            let color = match v {
                Some(v) if v.is_finite() => {
                    let f = if hi > lo { (v - lo) / (hi - lo) } else { 0.5 };
                    RGBColor(
                        (40.0 + 215.0 * f) as u8,
                        (90.0 + 80.0 * (1.0 - (2.0 * f - 1.0).abs())) as u8,
                        (255.0 - 215.0 * f) as u8,
                    )
                }
                _ => RGBColor(200, 200, 200),
            };
            let (x0, y0) = (ix as f64 - 0.5, iy as f64 - 0.5);
            chart
                .draw_series(std::iter::once(Rectangle::new(
                    [(x0, y0), (x0 + 1.0, y0 + 1.0)],
                    color.filled(),
                )))
                .map_err(err)?;
            if nx * ny <= 400 {
                let label = v.map_or("-".to_string(), |v| format!("{v:.3}"));
                chart
                    .draw_series(std::iter::once(Text::new(label, (x0 + 0.1, y0 + 0.6), ("sans-serif", 11))))
                    .map_err(err)?;
            }
        }
        root.present().map_err(err)?;
    }
    Ok(svg)
}
