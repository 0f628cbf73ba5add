//! Outputs of the stability studies: one CSV and one SVG chart per study, and a readable
//! summary (`summary.txt`) with each study's findings.

use super::{finite, write_atomic};
use crate::error::Result;
use crate::studies::stability::{
    CornerStudy, NuStudy, PlateStudy, Results, ShapeCase, ShapePoint, ThinPoint,
};
#[cfg(feature = "plots")]
use plotters::prelude::*;
use std::fmt::Write as _;
use std::path::Path;

/// Writes the files of every study present; returns their names.
pub fn write(res: &Results, dir: &Path) -> Result<Vec<String>> {
    let mut files = Vec::new();
    let mut put = |name: &str, text: String| -> Result<()> {
        write_atomic(&dir.join(name), text.as_bytes())?;
        files.push(name.to_string());
        Ok(())
    };
    if let Some(p) = &res.plate {
        put("plate.csv", plate_csv(p)?)?;
        #[cfg(feature = "plots")]
        put("plate.svg", plate_svg(p)?)?;
    }
    if let Some(n) = &res.nu {
        put("nu.csv", nu_csv(n)?)?;
        #[cfg(feature = "plots")]
        put("nu.svg", nu_svg(n)?)?;
    }
    if let Some(s) = &res.shape {
        put("shape.csv", shape_csv(s)?)?;
        #[cfg(feature = "plots")]
        put("shape.svg", shape_svg(s)?)?;
    }
    if let Some(t) = &res.thin {
        put("thin.csv", thin_csv(t)?)?;
        #[cfg(feature = "plots")]
        put("thin.svg", thin_svg(t)?)?;
    }
    if let Some(c) = &res.corners {
        put("corners.csv", corners_csv(c)?)?;
        #[cfg(feature = "plots")]
        put("corners.svg", corners_svg(c)?)?;
    }
    put("summary.txt", summary(res))?;
    Ok(files)
}

fn num(what: &str, v: f64) -> Result<String> {
    finite(what, v).map(|v| format!("{v:.6e}"))
}

fn opt(v: Option<f64>) -> String {
    v.filter(|x| x.is_finite()).map_or(String::new(), |x| format!("{x:.6e}"))
}

fn table(header: &str, rows: Vec<Vec<String>>) -> String {
    let mut s = format!("{header}\n");
    for r in rows {
        s.push_str(&r.join(","));
        s.push('\n');
    }
    s
}

pub const PLATE_HEADER: &str = "n_thick,plate_ratio,solved,err_p_over_pmean,err_tau_over_pmean,backward_error,condition_estimate,digits_lost,tilt_rel_diff,err_refined_over_pmean,refinement_steps,refused_by_default,time_s,symbolic_s";

pub fn plate_csv(p: &PlateStudy) -> Result<String> {
    let mut rows = Vec::new();
    for q in &p.points {
        let mut r =
            vec![q.n_thick.to_string(), num("plate ratio", q.ratio)?, u8::from(q.raw.is_some()).to_string()];
        match &q.raw {
            Some(x) => {
                for v in [x.err_p, x.err_tau, x.backward_error, x.condition, x.condition.log10(), x.tilt_rel]
                {
                    r.push(num("plate.csv", v)?);
                }
            }
            None => r.extend(std::iter::repeat_n(String::new(), 6)),
        }
        r.push(opt(q.refined.map(|x| x.0)));
        r.push(q.refined.map_or(String::new(), |x| x.1.to_string()));
        r.push(u8::from(q.refused.is_some()).to_string());
        r.push(opt(q.raw.as_ref().map(|x| x.time)));
        r.push(opt(q.raw.as_ref().map(|x| x.symbolic_time)));
        rows.push(r);
    }
    Ok(table(PLATE_HEADER, rows))
}

pub fn nu_csv(n: &NuStudy) -> Result<String> {
    let mut rows = Vec::new();
    for q in &n.points {
        let mut r = vec![num("nu", q.nu)?, q.element.clone()];
        for v in [
            q.err,
            q.err_edge_far,
            q.errors.interior[0],
            q.errors.interior[1],
            q.errors.edge[0],
            q.errors.edge[1],
            q.oscillation,
            q.p0_closed,
            q.modulus_ratio,
        ] {
            r.push(num("nu.csv", v)?);
        }
        rows.push(r);
    }
    Ok(table("nu,element,err_interior_max_over_pmean,err_edge_t_to_10t_over_pmean,err_interior_p,err_interior_tau,err_edge_p,err_edge_tau,oscillation_over_pmean,p0_over_closed_form,N_over_L_strain_over_lambda_plus_2G", rows))
}

pub fn shape_csv(s: &[ShapePoint]) -> Result<String> {
    let mut rows = Vec::new();
    for q in s {
        let mut r = vec![
            q.case.name().to_string(),
            q.element.clone(),
            num("shape", q.param)?,
            q.n_elements.to_string(),
        ];
        for v in [
            q.err,
            q.err_edge_far,
            q.errors.interior[0],
            q.errors.interior[1],
            q.errors.edge[0],
            q.errors.edge[1],
            q.min_jacobian_rel,
        ] {
            r.push(num("shape.csv", v)?);
        }
        rows.push(r);
    }
    Ok(table("case,element,aspect_or_distortion_over_h,elements,err_interior_max_over_pmean,err_edge_t_to_10t_over_pmean,err_interior_p,err_interior_tau,err_edge_p,err_edge_tau,min_jacobian_rel", rows))
}

pub fn thin_csv(t: &[ThinPoint]) -> Result<String> {
    let mut rows = Vec::new();
    for q in t {
        let mut r = vec![
            num("t/L", q.t_over_l)?,
            q.nx.to_string(),
            q.dofs.to_string(),
            u8::from(q.graded).to_string(),
        ];
        for v in [q.condition, q.backward_error, q.fill, q.time, q.slope, q.slope_rel_err, q.tau_dev] {
            r.push(num("thin.csv", v)?);
        }
        r.extend(q.widths.iter().map(|w| opt(*w)));
        rows.push(r);
    }
    Ok(table("t_over_L,nx,dofs,graded,condition_estimate,backward_error,fill_nnzL_over_nnzK,time_s,slope_interior,slope_rel_err,tau_dev_over_pmean,edge_p_left_t,edge_p_right_t,edge_tau_left_t,edge_tau_right_t", rows))
}

pub fn corners_csv(c: &CornerStudy) -> Result<String> {
    let mut rows = Vec::new();
    for (i, r) in c.study.runs.iter().enumerate() {
        let mut row = vec![r.n_thick.to_string(), r.dofs.to_string()];
        let inc = if i >= 2 { Some(c.increment_ratios[i - 2]) } else { None };
        for v in [r.p_end[1], r.tau_end[1], r.balance, r.slope] {
            row.push(num("corners.csv", v)?);
        }
        row.push(opt(inc));
        row.extend(r.widths.iter().map(|w| opt(*w)));
        rows.push(row);
    }
    Ok(table("n_thick,dofs,p_end_right,tau_end_right,balance_rel_err,slope_interior,increment_ratio,edge_p_left_t,edge_p_right_t,edge_tau_left_t,edge_tau_right_t", rows))
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
