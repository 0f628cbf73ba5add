//! Outputs of a convergence study: `convergence.csv`, the error-versus-DOFs chart per zone,
//! the error-versus-time chart with the Pareto front, and a readable summary.

use super::table::{Column, Table};
use super::write_atomic;
use crate::error::Result;
use crate::studies::convergence::{
    cheapest, edge_error, first_converged_width, orders, pareto_front, series, Run, Study,
};
#[cfg(feature = "plots")]
use plotters::prelude::*;
use std::fmt::Write as _;
use std::path::Path;

/// convergence.csv's table, one row per run (7 significant digits; errors and stresses in
/// units of N/L, edge widths in units of t, empty where a zone has no width; peak heap empty
/// when the runs were concurrent).
pub fn table(study: &Study) -> Table {
    let runs = &study.runs;
    let f = |get: &dyn Fn(&Run) -> f64| runs.iter().map(get).collect::<Vec<f64>>();
    let int = |get: &dyn Fn(&Run) -> usize| runs.iter().map(|r| get(r) as i64).collect::<Vec<i64>>();
    let width = |k: usize| runs.iter().map(|r| r.widths[k].unwrap_or(f64::NAN)).collect::<Vec<f64>>();
    let columns = vec![
        Column::text("family", "-", runs.iter().map(|r| r.family.name().to_string()).collect()),
        Column::text("element", "-", runs.iter().map(|r| r.element.clone()).collect()),
        Column::int("n_thick", "-", int(&|r| r.n_thick)),
        Column::float("h_over_t", "1", f(&|r| 1.0 / r.n_thick as f64)),
        Column::int("dofs", "-", int(&|r| r.dofs)),
        Column::int("elements", "-", int(&|r| r.n_elements)),
        Column::float("t_pattern_s", "s", f(&|r| r.timings.pattern)),
        Column::float("t_assembly_s", "s", f(&|r| r.timings.assembly)),
        Column::float("t_symbolic_s", "s", f(&|r| r.timings.symbolic)),
        Column::float("t_numeric_s", "s", f(&|r| r.timings.numeric)),
        Column::float("t_solve_s", "s", f(&|r| r.timings.solve)),
        Column::float("t_run_s", "s", f(&|r| r.wall)),
        Column::float("factor_mib", "MiB", f(&|r| r.factor_mib)),
        Column::maybe("peak_heap_mib", "MiB", f(&|r| r.peak_mib.unwrap_or(f64::NAN))),
        Column::float("err_interior_p", "1", f(&|r| r.errors.interior[0])),
        Column::float("err_interior_tau", "1", f(&|r| r.errors.interior[1])),
        Column::float("err_edge_p", "1", f(&|r| r.errors.edge[0])),
        Column::float("err_edge_tau", "1", f(&|r| r.errors.edge[1])),
        Column::float("err_end_p", "1", f(&|r| r.errors.end[0])),
        Column::float("err_end_tau", "1", f(&|r| r.errors.end[1])),
        Column::float("slope", "1", f(&|r| r.slope)),
        Column::float("tau_center", "1", f(&|r| r.tau_center)),
        Column::maybe("edge_p_left_t", "1", width(0)),
        Column::maybe("edge_p_right_t", "1", width(1)),
        Column::maybe("edge_tau_left_t", "1", width(2)),
        Column::maybe("edge_tau_right_t", "1", width(3)),
        Column::float("p_end_right", "1", f(&|r| r.p_end[1])),
        Column::float("tau_end_right", "1", f(&|r| r.tau_end[1])),
        Column::int("is_reference", "-", (0..runs.len()).map(|i| i64::from(i == study.reference)).collect()),
    ];
    Table { columns, digits: 7 }
}

/// convergence.csv, printed from [`table`].
pub fn csv(study: &Study) -> Result<String> {
    table(study).csv()
}

pub fn write(study: &Study, dir: &Path) -> Result<()> {
    write_atomic(&dir.join("convergence.csv"), csv(study)?.as_bytes())?;
    #[cfg(feature = "plots")]
    write_atomic(&dir.join("error_vs_dofs.svg"), error_vs_dofs(study)?.as_bytes())?;
    #[cfg(feature = "plots")]
    write_atomic(&dir.join("error_vs_time.svg"), error_vs_time(study)?.as_bytes())?;
    write_atomic(&dir.join("summary.txt"), summary(study, None).as_bytes())
}

/// Readable summary: runs, orders, widths, end-node growth, and the cheapest run for `tol`.
pub fn summary(study: &Study, tol: Option<f64>) -> String {
    let mut s = String::new();
    let rf = &study.runs[study.reference];
    let _ = writeln!(
        s,
        "reference: {} {} h = t/{} ({} DOFs); errors below are max |difference| from it in units of N/L",
        rf.family.name(),
        rf.element,
        rf.n_thick,
        rf.dofs
    );
    let _ = writeln!(
        s,
        "{:<8} {:<9} {:>5} {:>9} {:>9} | {:>9} {:>9} | {:>9} {:>9} | {:>9} {:>9} | {:>8} {:>8}",
        "family",
        "element",
        "t/h",
        "DOFs",
        "time s",
        "int p",
        "int tau",
        "edge p",
        "edge tau",
        "end p",
        "end tau",
        "wp R t",
        "wtau R t"
    );
    for r in &study.runs {
        let e = &r.errors;
        let w = |v: Option<f64>| v.map_or("-".to_string(), |x| format!("{x:.3}"));
        let _ = writeln!(
            s,
            "{:<8} {:<9} {:>5} {:>9} {:>9.3} | {:>9.2e} {:>9.2e} | {:>9.2e} {:>9.2e} | {:>9.2e} {:>9.2e} | {:>8} {:>8}",
            r.family.name(), r.element, r.n_thick, r.dofs, r.wall, e.interior[0], e.interior[1], e.edge[0], e.edge[1], e.end[0], e.end[1], w(r.widths[1]), w(r.widths[3])
        );
    }
    let _ = writeln!(s, "\nobserved orders by self-convergence over the three finest meshes of each series (interior p, interior tau, edge p, edge tau):");
    for sr in series(study) {
        let r = &study.runs[sr[0]];
        if let Some(o) = orders(study, &sr) {
            let _ = writeln!(
                s,
                "  {:<8} {:<9} {:>6.2} {:>6.2} {:>6.2} {:>6.2}",
                r.family.name(),
                r.element,
                o[0],
                o[1],
                o[2],
                o[3]
            );
        }
    }
    let _ = writeln!(s, "\nedge-zone widths (units of t) of the finest run of each series, and the coarsest mesh from which on they agree to 2 significant digits:");
    for sr in series(study) {
        let last = &study.runs[*sr.last().unwrap()];
        let first = first_converged_width(study, &sr);
        let names = ["p left", "p right", "tau left", "tau right"];
        let cells: Vec<String> = (0..4)
            .map(|k| match (last.widths[k], first[k]) {
                (Some(w), Some(i)) => format!("{} {w:.3} (from t/{})", names[k], study.runs[i].n_thick),
                (Some(w), None) => format!("{} {w:.3} (not converged)", names[k]),
                _ => format!("{} -", names[k]),
            })
            .collect();
        let prev = sr.len().checked_sub(2).map(|i| &study.runs[sr[i]]);
        let unc = prev.map_or("-".to_string(), |p| {
            let d: Vec<String> = (0..4)
                .map(|k| match (last.widths[k], p.widths[k]) {
                    (Some(a), Some(b)) => format!("{:.3}", (a - b).abs()),
                    _ => "-".into(),
                })
                .collect();
            d.join("/")
        });
        let _ = writeln!(
            s,
            "  {:<8} {:<9} t/{:<3} {} | change from the previous mesh {unc}",
            last.family.name(),
            last.element,
            last.n_thick,
            cells.join(", ")
        );
    }
    let _ = writeln!(s, "\nend-node values under refinement (uniform family; the corner is singular, so they must NOT converge):");
    for sr in series(study) {
        let r0 = &study.runs[sr[0]];
        if r0.family != crate::studies::convergence::Family::Uniform {
            continue;
        }
        let vals: Vec<String> = sr
            .iter()
            .map(|&i| format!("t/{}: {:.3}", study.runs[i].n_thick, study.runs[i].p_end[1]))
            .collect();
        let ratios: Vec<String> = sr
            .windows(3)
            .map(|w| {
                let v = |i: usize| study.runs[w[i]].p_end[1];
                format!("{:.3}", (v(2) - v(1)) / (v(1) - v(0)))
            })
            .collect();
        let _ = writeln!(
            s,
            "  {:<9} p(+L/2): {}  | ratio of successive increments {}",
            r0.element,
            vals.join(", "),
            ratios.join(", ")
        );
    }
    theory(&mut s, study);
    if !study.skipped.is_empty() {
        let _ = writeln!(s, "\nskipped (over the DOF budget): {}", study.skipped.join("; "));
    }
    if let Some(tol) = tol {
        match cheapest(study, tol) {
            Some(r) => {
                let _ = writeln!(s, "\ncheapest run (fewest unknowns) reaching edge-zone error <= {tol:e} N/L: {} {} h = t/{} ({} DOFs; {:.3} s, error {:.2e})", r.family.name(), r.element, r.n_thick, r.dofs, r.wall, edge_error(r));
            }
            None => {
                let _ =
                    writeln!(s, "\nno run reaches edge-zone error <= {tol:e} N/L (other than the reference)");
            }
        }
    }
    s
}

#[cfg(feature = "plots")]
const COLORS: [RGBColor; 12] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(23, 190, 207),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(0, 0, 128),
    RGBColor(128, 0, 0),
];

#[cfg(feature = "plots")]
use super::plot::{render, Legend, FONT};

#[cfg(feature = "plots")]
/// Error (max of p and tau) against DOFs, log-log, one panel per zone.
pub fn error_vs_dofs(study: &Study) -> Result<String> {
    render("error_vs_dofs.svg", (1200, 420), |root| {
        let panels = root.split_evenly((1, 3));
        type Zone = (&'static str, fn(&crate::studies::convergence::ZoneErrors) -> f64);
        let zones: [Zone; 3] = [
            ("interior (|x| < L/2 - 10 t)", |e| e.interior[0].max(e.interior[1])),
            ("edge zones (t/4 to 10 t from the ends)", |e| e.edge[0].max(e.edge[1])),
            ("end nodes (singular: no convergence)", |e| e.end[0].max(e.end[1])),
        ];
        for (panel, (title, f)) in panels.iter().zip(zones) {
            let pts: Vec<(f64, f64)> = study
                .runs
                .iter()
                .enumerate()
                .filter(|(i, _)| *i != study.reference)
                .map(|(_, r)| (r.dofs as f64, f(&r.errors)))
                .collect();
            let mut chart = ChartBuilder::on(panel)
                .caption(title, (FONT, 14))
                .margin(10)
                .x_label_area_size(40)
                .y_label_area_size(60)
                .build_cartesian_2d(
                    super::plot::log_range(pts.iter().map(|p| p.0)).log_scale(),
                    super::plot::log_range(pts.iter().map(|p| p.1)).log_scale(),
                )?;
            chart
                .configure_mesh()
                .x_desc("DOFs")
                .y_desc("max |error| / (N/L)")
                .x_label_formatter(&|v| format!("{v:.0e}"))
                .y_label_formatter(&|v| format!("{v:.0e}"))
                .draw()?;
            for (k, sr) in series(study).iter().enumerate() {
                let col = COLORS[k % COLORS.len()];
                let r0 = &study.runs[sr[0]];
                let line: Vec<(f64, f64)> = sr
                    .iter()
                    .filter(|&&i| i != study.reference)
                    .map(|&i| (study.runs[i].dofs as f64, f(&study.runs[i].errors)))
                    .filter(|p| p.1 > 0.0)
                    .collect();
                chart
                    .draw_series(LineSeries::new(line.clone(), col.stroke_width(2)))?
                    .label(format!("{} {}", r0.element, r0.family.name()))
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], col.stroke_width(2)));
                chart.draw_series(line.iter().map(|&p| Circle::new(p, 3, col.filled())))?;
            }
            chart.legend_box(SeriesLabelPosition::MiddleRight)?;
        }
        Ok(())
    })
}

#[cfg(feature = "plots")]
/// Edge-zone error against wall time per run, every series, with the Pareto front marked.
pub fn error_vs_time(study: &Study) -> Result<String> {
    let idx: Vec<usize> = (0..study.runs.len()).filter(|&i| i != study.reference).collect();
    let pts: Vec<(f64, f64)> =
        idx.iter().map(|&i| (study.runs[i].wall, edge_error(&study.runs[i]))).collect();
    let front: Vec<(f64, f64)> = pareto_front(&pts).into_iter().map(|k| pts[k]).collect();
    render("error_vs_time.svg", (900, 600), |root| {
        let mut chart = ChartBuilder::on(root)
            .caption(
                "Accuracy against time: edge-zone error vs wall time per run (black line: Pareto front)",
                (FONT, 15),
            )
            .margin(12)
            .x_label_area_size(45)
            .y_label_area_size(65)
            .build_cartesian_2d(
                super::plot::log_range(pts.iter().map(|p| p.0)).log_scale(),
                super::plot::log_range(pts.iter().map(|p| p.1)).log_scale(),
            )?;
        chart
            .configure_mesh()
            .x_desc("wall time of the run, s")
            .y_desc("edge-zone max |error| / (N/L)")
            .x_label_formatter(&|v| format!("{v:.0e}"))
            .y_label_formatter(&|v| format!("{v:.0e}"))
            .draw()?;
        chart
            .draw_series(LineSeries::new(front.clone(), BLACK.stroke_width(2)))?
            .label("Pareto front")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], BLACK.stroke_width(2)));
        for (k, sr) in series(study).iter().enumerate() {
            let col = COLORS[k % COLORS.len()];
            let r0 = &study.runs[sr[0]];
            let p: Vec<(f64, f64)> = sr
                .iter()
                .filter(|&&i| i != study.reference)
                .map(|&i| (study.runs[i].wall, edge_error(&study.runs[i])))
                .filter(|p| p.1 > 0.0)
                .collect();
            chart
                .draw_series(p.iter().map(|&q| Circle::new(q, 4, col.filled())))?
                .label(format!("{} {}", r0.element, r0.family.name()))
                .legend(move |(x, y)| Circle::new((x + 8, y), 4, col.filled()));
            chart.draw_series(LineSeries::new(p, col.mix(0.5)))?;
        }
        chart.legend_box(SeriesLabelPosition::MiddleRight)
    })
}

/// The study next to the theory: Williams' corner exponent against the growth of the end
/// values, and the clamped-strip decay modes against the decay fitted on the reference.
fn theory(s: &mut String, study: &Study) {
    let (nu, th) = (study.nu, &study.theory);
    let _ = writeln!(
        s,
        "  Williams (clamped-free 90-degree corner, plane strain, nu = {nu}): lambda = {:.4}, stress ~ r^-{:.4}, end values grow by 2^(1 - lambda) = {:.4} per halving of h",
        th.lambda.re, th.singularity, th.growth_per_halving
    );
    let _ = writeln!(
        s,
        "  pollution (Babuska): the corner singularity limits every element, even quadratic ones, to order 2 lambda = {:.2} in the smooth zones (compare the orders above)",
        2.0 * th.lambda.re
    );
    let k = th.decay_fitted;
    let f = |v: Option<f64>| v.map_or("-".to_string(), |x| format!("{x:.3}"));
    let _ = writeln!(s, "\nedge decay fitted on the reference, |deviation from the far field| ~ exp(-k d/t): k = p {}/{} (left/right), tau {}/{}", f(k[0]), f(k[1]), f(k[2]), f(k[3]));
    for (name, (root, dist)) in ["compression-class", "shear-class"].iter().zip(th.strip) {
        let _ = writeln!(s, "  strip clamped on both faces, {name} slowest mode: s t = {:.4}{:+.4}i, k = {:.3}, falls to 5 % within {:.2} t", root.re, root.im, root.re, dist);
    }
}
