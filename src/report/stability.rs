//! Outputs of the stability studies: one CSV and one SVG chart per study, and a readable
//! summary (`summary.txt`) with each study's findings.

use super::table::{Column, Table};
use super::{finite, write_atomic};
use crate::error::Result;
use crate::studies::convergence::ZoneErrors;
use crate::studies::stability::{
    CornerStudy, NuStudy, PlateRaw, PlateStudy, Results, ShapeCase, ShapePoint, ThinPoint,
};
#[cfg(feature = "plots")]
use plotters::prelude::*;
use std::fmt::Write as _;
use std::path::Path;

/// Writes the files of every study present; returns their names.
pub fn write(res: &Results, dir: &Path) -> Result<Vec<String>> {
    let mut files = Vec::new();
    let mut put = |name: String, text: String| -> Result<()> {
        write_atomic(&dir.join(&name), text.as_bytes())?;
        files.push(name);
        Ok(())
    };
    for (name, table) in tables(res)? {
        put(format!("{name}.csv"), table.csv()?)?;
    }
    #[cfg(feature = "plots")]
    {
        if let Some(p) = &res.plate {
            put("plate.svg".into(), plate_svg(p)?)?;
        }
        if let Some(n) = &res.nu {
            put("nu.svg".into(), nu_svg(n)?)?;
        }
        if let Some(s) = &res.shape {
            put("shape.svg".into(), shape_svg(s)?)?;
        }
        if let Some(t) = &res.thin {
            put("thin.svg".into(), thin_svg(t)?)?;
        }
        if let Some(c) = &res.corners {
            put("corners.svg".into(), corners_svg(c)?)?;
        }
    }
    put("summary.txt".into(), summary(res))?;
    Ok(files)
}

/// The table of every study present, by study name (`plate`, `nu`, `shape`, `thin`,
/// `corners`; the CSV is `<name>.csv`), in the order they run: the one definition the CSV
/// files and the Python package's tables are made from.
pub fn tables(res: &Results) -> Result<Vec<(&'static str, Table)>> {
    let mut out = Vec::new();
    if let Some(p) = &res.plate {
        out.push(("plate", plate_table(p)?));
    }
    if let Some(n) = &res.nu {
        out.push(("nu", nu_table(n)));
    }
    if let Some(s) = &res.shape {
        out.push(("shape", shape_table(s)));
    }
    if let Some(t) = &res.thin {
        out.push(("thin", thin_table(t)));
    }
    if let Some(c) = &res.corners {
        out.push(("corners", corners_table(c)));
    }
    Ok(out)
}

/// Significant digits of the studies' numbers.
const DIGITS: usize = 7;

/// A dimensionless column (errors in units of N/L, ratios, widths in units of t).
fn ratio<T>(name: &'static str, rows: &[T], get: impl Fn(&T) -> f64) -> Column {
    Column::float(name, "1", rows.iter().map(get).collect())
}

/// A dimensionless column that may have no value for a row (an empty cell).
fn maybe<T>(name: &'static str, unit: &'static str, rows: &[T], get: impl Fn(&T) -> Option<f64>) -> Column {
    Column::maybe(
        name,
        unit,
        rows.iter().map(|r| get(r).filter(|x| x.is_finite()).unwrap_or(f64::NAN)).collect(),
    )
}

/// The errors against the qua9 reference that nu.csv and shape.csv share (units of N/L): the
/// interior's and the edge zone's largest, then per quantity.
fn error_columns<T>(rows: &[T], get: impl Fn(&T) -> (f64, f64, &ZoneErrors)) -> [Column; 6] {
    [
        ratio("err_interior_max_over_pmean", rows, |x| get(x).0),
        ratio("err_edge_t_to_10t_over_pmean", rows, |x| get(x).1),
        ratio("err_interior_p", rows, |x| get(x).2.interior[0]),
        ratio("err_interior_tau", rows, |x| get(x).2.interior[1]),
        ratio("err_edge_p", rows, |x| get(x).2.edge[0]),
        ratio("err_edge_tau", rows, |x| get(x).2.edge[1]),
    ]
}

fn count<T>(name: &'static str, rows: &[T], get: impl Fn(&T) -> usize) -> Column {
    Column::int(name, "-", rows.iter().map(|r| get(r) as i64).collect())
}

/// The four edge-zone widths (units of t; empty where a profile has none).
fn widths<T>(rows: &[T], get: impl Fn(&T) -> [Option<f64>; 4]) -> [Column; 4] {
    let w = |k: usize, name: &'static str| maybe(name, "1", rows, |r| get(r)[k]);
    [w(0, "edge_p_left_t"), w(1, "edge_p_right_t"), w(2, "edge_tau_left_t"), w(3, "edge_tau_right_t")]
}

/// plate.csv's table: per mesh (elements through t) and E_plate/E_block whether the raw solve
/// succeeded, its errors against the rigid plate (units of N/L), backward error, condition
/// estimate and digits lost, the tilt's relative difference, the error with forced iterative
/// refinement and its steps, whether the default check refuses it, and the wall times (s).
/// A failed solve's cells are empty.
pub fn plate_table(p: &PlateStudy) -> Result<Table> {
    let q = &p.points;
    // A solved point's figures must be numbers: a non-finite one is a bug, never an empty cell.
    let raw = |name: &'static str, get: fn(&PlateRaw) -> f64| -> Result<Column> {
        for r in q.iter().filter_map(|x| x.raw.as_ref()) {
            finite(name, get(r))?;
        }
        Ok(maybe(name, "1", q, |x| x.raw.as_ref().map(get)))
    };
    Ok(Table {
        columns: vec![
            count("n_thick", q, |x| x.n_thick),
            ratio("plate_ratio", q, |x| x.ratio),
            count("solved", q, |x| usize::from(x.raw.is_some())),
            raw("err_p_over_pmean", |r| r.err_p)?,
            raw("err_tau_over_pmean", |r| r.err_tau)?,
            raw("backward_error", |r| r.backward_error)?,
            raw("condition_estimate", |r| r.condition)?,
            raw("digits_lost", |r| r.condition.log10())?,
            raw("tilt_rel_diff", |r| r.tilt_rel)?,
            maybe("err_refined_over_pmean", "1", q, |x| x.refined.map(|r| r.0)),
            Column::maybe_int(
                "refinement_steps",
                "-",
                q.iter().map(|x| x.refined.map(|r| r.1 as i64)).collect(),
            ),
            count("refused_by_default", q, |x| usize::from(x.refused.is_some())),
            maybe("time_s", "s", q, |x| x.raw.as_ref().map(|r| r.time)),
            maybe("symbolic_s", "s", q, |x| x.raw.as_ref().map(|r| r.symbolic_time)),
        ],
        digits: DIGITS,
    })
}

/// nu.csv's table: per Poisson's ratio and element the largest errors against the qua9
/// reference (units of N/L: interior, edge zone t..10 t, and per quantity), the edge zone's
/// oscillation, p(0) over the closed-form confined compression, and N/L over the strain times
/// lambda + 2G (dimensionless).
pub fn nu_table(n: &NuStudy) -> Table {
    let q = &n.points;
    Table {
        columns: vec![
            ratio("nu", q, |x| x.nu),
            Column::text("element", "-", q.iter().map(|x| x.element.clone()).collect()),
        ]
        .into_iter()
        .chain(error_columns(q, |x| (x.err, x.err_edge_far, &x.errors)))
        .chain([
            ratio("oscillation_over_pmean", q, |x| x.oscillation),
            ratio("p0_over_closed_form", q, |x| x.p0_closed),
            ratio("N_over_L_strain_over_lambda_plus_2G", q, |x| x.modulus_ratio),
        ])
        .collect(),
        digits: DIGITS,
    }
}

/// shape.csv's table: per mesh family (`case`), element and aspect ratio or distortion
/// amplitude (units of h) the elements and the largest errors against the qua9 reference
/// (units of N/L), and the smallest Jacobian relative to its mean.
pub fn shape_table(s: &[ShapePoint]) -> Table {
    Table {
        columns: vec![
            Column::text("case", "-", s.iter().map(|x| x.case.name().to_string()).collect()),
            Column::text("element", "-", s.iter().map(|x| x.element.clone()).collect()),
            ratio("aspect_or_distortion_over_h", s, |x| x.param),
            count("elements", s, |x| x.n_elements),
        ]
        .into_iter()
        .chain(error_columns(s, |x| (x.err, x.err_edge_far, &x.errors)))
        .chain([ratio("min_jacobian_rel", s, |x| x.min_jacobian_rel)])
        .collect(),
        digits: DIGITS,
    }
}

/// thin.csv's table: per t/L the elements along the block, unknowns, whether the mesh was
/// graded to stay within the DOF limit, the condition estimate, backward error, fill of the
/// factor, wall time (s), the interior slope of p and its relative error against the model's
/// 12 (F/N)(H/L), the deviation of tau from uniform (units of N/L) and the edge widths (units
/// of t).
pub fn thin_table(t: &[ThinPoint]) -> Table {
    let mut columns = vec![
        ratio("t_over_L", t, |x| x.t_over_l),
        count("nx", t, |x| x.nx),
        count("dofs", t, |x| x.dofs),
        count("graded", t, |x| usize::from(x.graded)),
        ratio("condition_estimate", t, |x| x.condition),
        ratio("backward_error", t, |x| x.backward_error),
        ratio("fill_nnzL_over_nnzK", t, |x| x.fill),
        Column::float("time_s", "s", t.iter().map(|x| x.time).collect()),
        ratio("slope_interior", t, |x| x.slope),
        ratio("slope_rel_err", t, |x| x.slope_rel_err),
        ratio("tau_dev_over_pmean", t, |x| x.tau_dev),
    ];
    columns.extend(widths(t, |x| x.widths));
    Table { columns, digits: DIGITS }
}

/// corners.csv's table: per uniform qua4 mesh (elements through t) the unknowns, p and tau at
/// the right end node (units of N/L), the force balance's relative error, the interior slope,
/// the ratio of successive end-value increments (from the third mesh on) and the edge widths
/// (units of t).
pub fn corners_table(c: &CornerStudy) -> Table {
    let r = &c.study.runs;
    let mut columns = vec![
        count("n_thick", r, |x| x.n_thick),
        count("dofs", r, |x| x.dofs),
        ratio("p_end_right", r, |x| x.p_end[1]),
        ratio("tau_end_right", r, |x| x.tau_end[1]),
        ratio("balance_rel_err", r, |x| x.balance),
        ratio("slope_interior", r, |x| x.slope),
        Column::maybe(
            "increment_ratio",
            "1",
            (0..r.len()).map(|i| if i >= 2 { c.increment_ratios[i - 2] } else { f64::NAN }).collect(),
        ),
    ];
    columns.extend(widths(r, |x| x.widths));
    Table { columns, digits: DIGITS }
}

// ---------------------------------------------------------------- summary

fn e(v: f64) -> String {
    format!("{v:.1e}")
}

pub fn summary(res: &Results) -> String {
    let mut s = String::new();
    if let Some(p) = &res.plate {
        let _ = writeln!(s, "== plate: elastic plate (E_plate/E_block) against the exact rigid plate; errors max over nodes and F/N cases, units of N/L");
        let _ = writeln!(
            s,
            "{:>4} {:>7} {:>9} {:>9} {:>9} {:>9} {:>7} {:>9} {:>9} {:>8}",
            "t/h",
            "ratio",
            "err p",
            "err tau",
            "backward",
            "cond",
            "digits",
            "tilt rel",
            "refined",
            "default"
        );
        for q in &p.points {
            let refused = if q.refused.is_some() { "refused" } else { "accepted" };
            match &q.raw {
                Some(r) => {
                    let _ = writeln!(
                        s,
                        "{:>4} {:>7.0e} {:>9} {:>9} {:>9} {:>9} {:>7.1} {:>9} {:>9} {:>8}",
                        q.n_thick,
                        q.ratio,
                        e(r.err_p),
                        e(r.err_tau),
                        e(r.backward_error),
                        e(r.condition),
                        r.condition.log10(),
                        e(r.tilt_rel),
                        q.refined.map_or("-".into(), |x| e(x.0)),
                        refused
                    );
                }
                None => {
                    let _ = writeln!(
                        s,
                        "{:>4} {:>7.0e} solve failed: {} ({refused})",
                        q.n_thick,
                        q.ratio,
                        q.failure.as_deref().unwrap_or("")
                    );
                }
            }
        }
        for f in &p.findings {
            let _ = writeln!(
                s,
                "t/{}: error stops falling at ratio {:.0e} (error {}); round-off takes over (error > 10x the smallest) at {}; tribofe refuses from {}; digits lost at 1e12: {}",
                f.n_thick,
                f.best_ratio,
                e(f.best_err),
                f.roundoff_ratio.map_or("-".into(), |r| format!("{r:.0e}")),
                f.first_refused.map_or("-".into(), |r| format!("{r:.0e}")),
                f.digits_lost_1e12.map_or("-".into(), |d| format!("{d:.1}"))
            );
        }
        let _ = writeln!(s, "pattern + symbolic analysis: built once per mesh and reused at every point of the sweep (redone at each point it would cost {:.0} % of each solve)\n", 100.0 * p.symbolic_share);
    }
    if let Some(n) = &res.nu {
        let _ = writeln!(s, "== nu: max error against qua9 references (units of N/L): interior, edge t..10 t | edge-zone oscillation of p, tau | p(0) / closed form (F/N = 0)");
        let els: Vec<&String> = n.points.iter().map(|q| &q.element).fold(Vec::new(), |mut v, x| {
            if !v.contains(&x) {
                v.push(x)
            }
            v
        });
        let _ = writeln!(s, "{:>7} {}", "nu", els.iter().map(|x| format!("{x:>35}")).collect::<String>());
        for &(nu, p0) in &n.reference_p0 {
            let cells: String = n
                .points
                .iter()
                .filter(|q| q.nu == nu)
                .map(|q| {
                    format!(
                        "{:>8} {:>8} {:>8} {:>7.4}",
                        e(q.err),
                        e(q.err_edge_far),
                        e(q.oscillation),
                        q.p0_closed
                    )
                })
                .map(|c| format!("{c:>35}"))
                .collect();
            let _ = writeln!(s, "{nu:>7} {cells}   (reference p(0)/closed form {p0:.5})");
        }
        s.push('\n');
    }
    if let Some(sh) = &res.shape {
        let _ = writeln!(s, "== shape: max error against the qua9 reference, interior / edge zone t..10 t from the ends (units of N/L)");
        for case in [ShapeCase::Graded, ShapeCase::Uniform, ShapeCase::Distorted, ShapeCase::Unstructured] {
            let what = match case {
                ShapeCase::Distorted => "amplitude/h",
                ShapeCase::Unstructured => "Gmsh mesh; the number is the worst min/mean Jacobian",
                _ => "aspect",
            };
            let mut els: Vec<&str> = sh.iter().map(|q| q.element.as_str()).collect();
            els.dedup();
            let _ = writeln!(s, "{} ({what}):", case.name());
            for el in els {
                let label = |q: &crate::studies::stability::ShapePoint| {
                    if case == ShapeCase::Unstructured {
                        format!("{:.2}", q.min_jacobian_rel)
                    } else {
                        format!("{}", q.param)
                    }
                };
                let cells: Vec<String> = sh
                    .iter()
                    .filter(|q| q.case == case && q.element == el)
                    .map(|q| format!("{}: {}/{}", label(q), e(q.err), e(q.err_edge_far)))
                    .collect();
                if cells.is_empty() {
                    continue;
                }
                let _ = writeln!(s, "  {el:<9} {}", cells.join("  "));
            }
        }
        s.push('\n');
    }
    if let Some(t) = &res.thin {
        let _ = writeln!(s, "== thin: t/L sweep, qua4, fixed elements through the thickness (rigid plate)");
        let _ = writeln!(
            s,
            "{:>7} {:>7} {:>8} {:>9} {:>9} {:>6} {:>7} {:>9} {:>9} {:>9} {:>15}",
            "t/L",
            "nx",
            "DOFs",
            "cond",
            "backward",
            "fill",
            "time s",
            "slope",
            "slope err",
            "tau dev",
            "widths p/tau R"
        );
        for q in t {
            let w = |v: Option<f64>| v.map_or("-".into(), |x| format!("{x:.2}"));
            let _ = writeln!(
                s,
                "{:>7.0e} {:>7} {:>8} {:>9} {:>9} {:>6.2} {:>7.2} {:>9.5} {:>9} {:>9} {:>15}{}",
                q.t_over_l,
                q.nx,
                q.dofs,
                e(q.condition),
                e(q.backward_error),
                q.fill,
                q.time,
                q.slope,
                e(q.slope_rel_err),
                e(q.tau_dev),
                format!("{}/{}", w(q.widths[1]), w(q.widths[3])),
                if q.graded { " (graded: DOF budget)" } else { "" }
            );
        }
        s.push('\n');
    }
    if let Some(c) = &res.corners {
        let _ = writeln!(
            s,
            "== corners: uniform qua4, h = t/1 .. t/{}",
            c.study.runs.last().map_or(0, |r| r.n_thick)
        );
        for r in &c.study.runs {
            let w = |v: Option<f64>| v.map_or("-".into(), |x| format!("{x:.3}"));
            let _ = writeln!(
                s,
                "  t/{:<3} p(+L/2) {:>8.4}  balance {}  slope {:.6}  widths p {}/{} tau {}/{} t",
                r.n_thick,
                r.p_end[1],
                e(r.balance),
                r.slope,
                w(r.widths[0]),
                w(r.widths[1]),
                w(r.widths[2]),
                w(r.widths[3])
            );
        }
        let ratios: Vec<String> = c.increment_ratios.iter().map(|x| format!("{x:.3}")).collect();
        let _ = writeln!(s, "ratios of successive end-value increments: {} -> factor {:.3} per halving, exponent lambda = 1 - log2(factor) = {:.3}", ratios.join(", "), c.factor, c.lambda_measured);
        let _ = writeln!(s, "Williams clamped-free 90 degree corner (plane strain, nu = {}): lambda = {:.4}, factor 2^(1 - lambda) = {:.3}", c.nu, c.lambda_williams, c.factor_williams);
    }
    s
}

// ---------------------------------------------------------------- charts

/// The report layer's series colours ([`super::plot::PALETTE`]).
#[cfg(feature = "plots")]
use super::plot::{render, Legend, FONT, PALETTE as COLORS};

#[cfg(feature = "plots")]
type Series = (String, Vec<(f64, f64)>);

#[cfg(feature = "plots")]
/// Log-log panels side by side, each with titled series (positive values only).
fn panels(figure: &str, size: (u32, u32), specs: &[(&str, &str, &str, Vec<Series>)]) -> Result<String> {
    render(figure, size, |root| {
        let areas = root.split_evenly((1, specs.len()));
        for (area, (title, xd, yd, series)) in areas.iter().zip(specs) {
            let pts = || {
                series.iter().flat_map(|s| s.1.iter()).filter(|p| p.0 > 0.0 && p.1 > 0.0 && p.1.is_finite())
            };
            let mut chart = ChartBuilder::on(area)
                .caption(*title, (FONT, 14))
                .margin(10)
                .x_label_area_size(40)
                .y_label_area_size(60)
                .build_cartesian_2d(
                    super::plot::log_range(pts().map(|p| p.0)).log_scale(),
                    super::plot::log_range(pts().map(|p| p.1)).log_scale(),
                )?;
            chart
                .configure_mesh()
                .x_desc(*xd)
                .y_desc(*yd)
                .x_label_formatter(&|v| format!("{v:.0e}"))
                .y_label_formatter(&|v| format!("{v:.0e}"))
                .draw()?;
            for (k, (name, line)) in series.iter().enumerate() {
                let col = COLORS[k % COLORS.len()];
                let line: Vec<(f64, f64)> =
                    line.iter().cloned().filter(|p| p.0 > 0.0 && p.1 > 0.0 && p.1.is_finite()).collect();
                chart
                    .draw_series(LineSeries::new(line.clone(), col.stroke_width(2)))?
                    .label(name.clone())
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], col.stroke_width(2)));
                chart.draw_series(line.iter().map(|&p| Circle::new(p, 3, col.filled())))?;
            }
            chart.legend_box(SeriesLabelPosition::MiddleRight)?;
        }
        Ok(())
    })
}

#[cfg(feature = "plots")]
pub fn plate_svg(p: &PlateStudy) -> Result<String> {
    let mut left = Vec::new();
    let mut right = Vec::new();
    for f in &p.findings {
        let pts: Vec<_> = p.points.iter().filter(|q| q.n_thick == f.n_thick).collect();
        let get = |g: &dyn Fn(&crate::studies::stability::PlateRaw) -> f64| {
            pts.iter().filter_map(|q| q.raw.as_ref().map(|r| (q.ratio, g(r)))).collect::<Vec<_>>()
        };
        left.push((format!("error vs rigid, h = t/{}", f.n_thick), get(&|r| r.err())));
        left.push((format!("cond x eps, h = t/{}", f.n_thick), get(&|r| r.condition * f64::EPSILON)));
        right.push((format!("condition estimate, h = t/{}", f.n_thick), get(&|r| r.condition)));
        right
            .push((format!("backward error x 1e16, h = t/{}", f.n_thick), get(&|r| r.backward_error * 1e16)));
    }
    panels(
        "plate.svg",
        (1300, 480),
        &[
            ("Elastic plate vs exact rigid plate", "E_plate / E_block", "max |error| / (N/L)", left),
            ("Conditioning", "E_plate / E_block", "dimensionless", right),
        ],
    )
}

#[cfg(feature = "plots")]
pub fn nu_svg(n: &NuStudy) -> Result<String> {
    let mut els: Vec<&String> = n.points.iter().map(|q| &q.element).collect();
    els.sort();
    els.dedup();
    let by = |f: &dyn Fn(&crate::studies::stability::NuPoint) -> f64| -> Vec<Series> {
        els.iter()
            .map(|el| {
                (
                    el.to_string(),
                    n.points.iter().filter(|q| &q.element == *el).map(|q| (0.5 - q.nu, f(q))).collect(),
                )
            })
            .collect()
    };
    panels(
        "nu.svg",
        (1300, 480),
        &[
            (
                "Interior profile error vs incompressibility",
                "0.5 - nu",
                "max |error| / (N/L)",
                by(&|q| q.err),
            ),
            (
                "Edge-zone oscillation (excess over reference)",
                "0.5 - nu",
                "max |2nd difference of p| / (N/L)",
                by(&|q| q.oscillation),
            ),
        ],
    )
}

#[cfg(feature = "plots")]
pub fn shape_svg(s: &[ShapePoint]) -> Result<String> {
    let mut els: Vec<&str> = s.iter().map(|q| q.element.as_str()).collect();
    els.dedup();
    // Interior error, or the edge error (t .. 10 t) where the ends are elongated too.
    let by = |case: ShapeCase, shift: f64, edge: bool| -> Vec<Series> {
        els.iter()
            .map(|el| {
                (
                    el.to_string(),
                    s.iter()
                        .filter(|q| q.case == case && q.element == *el)
                        .map(|q| (q.param + shift, if edge { q.err_edge_far } else { q.err }))
                        .collect(),
                )
            })
            .collect()
    };
    panels(
        "shape.svg",
        (1500, 480),
        &[
            (
                "Graded: elongated only in the interior",
                "largest aspect ratio",
                "interior max |error| / (N/L)",
                by(ShapeCase::Graded, 0.0, false),
            ),
            (
                "Uniform: elongated everywhere",
                "aspect ratio",
                "edge (t..10 t) max |error| / (N/L)",
                by(ShapeCase::Uniform, 0.0, true),
            ),
            (
                "Distorted quads (x axis: 0.01 + amplitude/h)",
                "0.01 + amplitude / h",
                "interior max |error| / (N/L)",
                by(ShapeCase::Distorted, 0.01, false),
            ),
        ],
    )
}

#[cfg(feature = "plots")]
pub fn thin_svg(t: &[ThinPoint]) -> Result<String> {
    let line = |f: &dyn Fn(&ThinPoint) -> f64| t.iter().map(|q| (q.t_over_l, f(q))).collect::<Vec<_>>();
    panels(
        "thin.svg",
        (1300, 480),
        &[
            (
                "Conditioning and fill",
                "t / L",
                "dimensionless",
                vec![
                    ("condition estimate".into(), line(&|q| q.condition)),
                    ("fill nnz(L)/nnz(K)".into(), line(&|q| q.fill)),
                    ("backward error x 1e16".into(), line(&|q| q.backward_error * 1e16)),
                ],
            ),
            (
                "Model accuracy",
                "t / L",
                "dimensionless",
                vec![
                    ("interior slope rel. error".into(), line(&|q| q.slope_rel_err)),
                    ("tau deviation / (N/L)".into(), line(&|q| q.tau_dev)),
                    ("edge width p right / t".into(), line(&|q| q.widths[1].unwrap_or(0.0))),
                    ("edge width tau right / t".into(), line(&|q| q.widths[3].unwrap_or(0.0))),
                ],
            ),
        ],
    )
}

#[cfg(feature = "plots")]
pub fn corners_svg(c: &CornerStudy) -> Result<String> {
    let runs = &c.study.runs;
    let h = |r: &crate::studies::convergence::Run| 1.0 / r.n_thick as f64;
    let inc: Vec<(f64, f64)> =
        runs.windows(2).map(|w| (h(&w[1]), (w[1].p_end[1] - w[0].p_end[1]).abs())).collect();
    let fin = runs.last().unwrap();
    let diff = |f: &dyn Fn(&crate::studies::convergence::Run) -> f64| {
        runs[..runs.len() - 1].iter().map(|r| (h(r), (f(r) - f(fin)).abs())).collect::<Vec<_>>()
    };
    panels(
        "corners.svg",
        (1300, 480),
        &[
            (
                "End node p(+L/2): diverges",
                "h / t",
                "value or increment / (N/L)",
                vec![
                    ("p(+L/2)".into(), runs.iter().map(|r| (h(r), r.p_end[1])).collect()),
                    ("|increment|".into(), inc),
                ],
            ),
            (
                "Integrated quantities: converge",
                "h / t",
                "|difference from finest| (balance: rel. error)",
                vec![
                    ("interior slope".into(), diff(&|r| r.slope)),
                    ("edge width p right / t".into(), diff(&|r| r.widths[1].unwrap_or(0.0))),
                    ("edge width tau right / t".into(), diff(&|r| r.widths[3].unwrap_or(0.0))),
                    ("balance (N, F, FH)".into(), runs.iter().map(|r| (h(r), r.balance)).collect()),
                ],
            ),
        ],
    )
}
