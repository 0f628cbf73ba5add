//! Precursor outputs: CSV tables and SVG figures (the paper's figs. 4 and 5, and the
//! FE-fed comparison). All quantities are the paper's dimensionless ones: positions in units
//! of L, forces in units of mu_s N.

use super::{finite, write_atomic};
use crate::precursors::discrete::{CellEvent, Run};
use crate::precursors::fe::{self, Comparison, SweepRow, UnitFields};
use crate::precursors::{loading_curve, Event, MapPoint, Params};
use crate::{Error, Result};
use plotters::prelude::*;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

const FONT: &str = "sans-serif";

fn plot_err(figure: &str) -> impl Fn(Box<dyn std::error::Error>) -> Error + '_ {
    move |e| Error::plot(figure, e)
}

/// Runs a plotting closure on an in-memory SVG of the given size.
pub(crate) fn render(
    figure: &str,
    size: (u32, u32),
    draw: impl FnOnce(
        &DrawingArea<SVGBackend, plotters::coord::Shift>,
    ) -> std::result::Result<(), Box<dyn std::error::Error>>,
) -> Result<String> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        root.fill(&WHITE).map_err(|e| plot_err(figure)(e.into()))?;
        draw(&root).map_err(plot_err(figure))?;
        root.present().map_err(|e| plot_err(figure)(e.into()))?;
    }
    Ok(svg)
}

fn opt<T: std::fmt::Display>(v: Option<T>) -> String {
    v.map_or(String::new(), |v| v.to_string())
}

/// `events.csv`: header `i,F,Fc,x,Fstar,stick_slip`, stick_slip 0 for a precursor, 1 after.
pub fn events_csv(events: &[Event]) -> Result<String> {
    let mut s = String::from("i,F,Fc,x,Fstar,stick_slip\n");
    for e in events {
        let (f, fc, x, fs) =
            (finite("F", e.f)?, finite("Fc", e.fc)?, finite("x", e.x)?, finite("Fstar", e.fstar)?);
        let _ = writeln!(s, "{},{f},{fc},{x},{fs},{}", e.i, u8::from(e.stick_slip));
    }
    Ok(s)
}

/// `loading.csv`: the vertices of the loading curve F(F^c), header `Fc,F`.
pub fn loading_csv(curve: &[(f64, f64)]) -> Result<String> {
    let mut s = String::from("Fc,F\n");
    for &(fc, f) in curve {
        let _ = writeln!(s, "{},{}", finite("Fc", fc)?, finite("F", f)?);
    }
    Ok(s)
}

/// The paper's fig. 4: loading curve F(F^c) (red), ideal elastic line F = F^c (black),
/// F_max (dashed) and each precursor's extent [-1/2, x_i] at its force F_i (blue, top axis).
pub fn fig4_svg(p: &Params, events: &[Event]) -> Result<String> {
    let curve = loading_curve(events);
    for &(fc, f) in &curve {
        finite("loading curve", fc)?;
        finite("loading curve", f)?;
    }
    let fc_top = curve.iter().fold(0.0_f64, |m, c| m.max(c.0)).max(1.0) * 1.02;
    let f_top = curve.iter().fold(p.f_max(), |m, c| m.max(c.1)) * 1.08;
    let f_max = p.f_max();
    render("fig4.svg", (900, 650), |root| {
        let mut chart = ChartBuilder::on(root)
            .caption(
                format!("Loading curve and precursors, r = {}, g = {} (paper fig. 4)", p.r(), p.g()),
                (FONT, 20),
            )
            .margin(15)
            .x_label_area_size(45)
            .top_x_label_area_size(45)
            .y_label_area_size(65)
            .build_cartesian_2d(0.0..fc_top, 0.0..f_top)?
            .set_secondary_coord(-0.5..0.5, 0.0..f_top);
        chart
            .configure_mesh()
            .x_desc("elastic force F^c / (mu_s N)  (dimensionless)")
            .y_desc("friction force F / (mu_s N)  (dimensionless)")
            .draw()?;
        chart
            .configure_secondary_axes()
            .x_desc("blue: precursor extent along the contact, x / L  (dimensionless)")
            .draw()?;
        let m = fc_top.min(f_top);
        chart
            .draw_series(LineSeries::new([(0.0, 0.0), (m, m)], BLACK.stroke_width(1)))?
            .label("ideal elastic loading F = F^c")
            .legend(|(x, y)| PathElement::new([(x, y), (x + 20, y)], BLACK));
        chart
            .draw_series(LineSeries::new(curve.iter().copied(), RED.stroke_width(2)))?
            .label("loading curve F(F^c)")
            .legend(|(x, y)| PathElement::new([(x, y), (x + 20, y)], RED.stroke_width(2)));
        chart
            .draw_series(DashedLineSeries::new(
                [(0.0, f_max), (fc_top, f_max)],
                6,
                4,
                BLACK.mix(0.6).stroke_width(1),
            ))?
            .label(format!("F_max = {f_max:.4}"))
            .legend(|(x, y)| PathElement::new([(x, y), (x + 20, y)], BLACK.mix(0.6)));
        let blue = BLUE.stroke_width(2);
        chart
            .draw_secondary_series(
                events
                    .iter()
                    .filter(|e| !e.stick_slip)
                    .map(|e| PathElement::new([(-0.5, e.f), (e.x, e.f)], blue)),
            )?
            .label("precursor i: from x = -1/2 to x_i, at height F_i")
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], blue));
        chart.draw_secondary_series(
            events.iter().filter(|e| !e.stick_slip).map(|e| Circle::new((e.x, e.f), 3, BLUE.filled())),
        )?;
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::LowerRight)
            .background_style(WHITE.mix(0.9))
            .border_style(BLACK)
            .label_font((FONT, 14))
            .draw()?;
        Ok(())
    })
}

fn ensure_dir(dir: &Path) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))
}

/// Writes `events.csv`, `loading.csv` and `fig4.svg` into `dir` (created if needed);
/// returns the paths written.
pub fn write_events(dir: &Path, p: &Params, events: &[Event]) -> Result<Vec<PathBuf>> {
    ensure_dir(dir)?;
    let files = [
        ("events.csv", events_csv(events)?),
        ("loading.csv", loading_csv(&loading_curve(events))?),
        ("fig4.svg", fig4_svg(p, events)?),
    ];
    write_all(dir, &files)
}

fn write_all(dir: &Path, files: &[(&str, String)]) -> Result<Vec<PathBuf>> {
    files
        .iter()
        .map(|(name, body)| {
            let path = dir.join(name);
            write_atomic(&path, body.as_bytes()).map(|_| path)
        })
        .collect()
}

/// `n_map.csv`: header `r,g,n`.
pub fn n_map_csv(map: &[MapPoint]) -> Result<String> {
    let mut s = String::from("r,g,n\n");
    for m in map {
        let _ = writeln!(s, "{},{},{}", finite("r", m.r)?, finite("g", m.g)?, m.n);
    }
    Ok(s)
}

/// Viridis, linearly interpolated between five anchors; `c` in [0, 1].
fn viridis(c: f64) -> RGBColor {
    const A: [(f64, f64, f64); 5] =
        [(68., 1., 84.), (59., 82., 139.), (33., 145., 140.), (94., 201., 98.), (253., 231., 37.)];
    let t = c.clamp(0.0, 1.0) * 4.0;
    let k = (t.floor() as usize).min(3);
    let u = t - k as f64;
    let mix = |a: f64, b: f64| (a + (b - a) * u).round() as u8;
    RGBColor(mix(A[k].0, A[k + 1].0), mix(A[k].1, A[k + 1].1), mix(A[k].2, A[k + 1].2))
}

/// The colour key of an n map (logarithmic in 1 + n) down the `key` area; returns the y below it.
fn n_key(
    key: &DrawingArea<SVGBackend, plotters::coord::Shift>,
    n_max: usize,
    colour: &dyn Fn(usize) -> RGBColor,
) -> std::result::Result<i32, Box<dyn std::error::Error>> {
    key.draw(&Text::new("n (log colour scale)", (0, 40), (FONT, 14)))?;
    let mut shown: Vec<usize> =
        [0, 1, 2, 5, 10, 20, 50, 100, 200, 500, 1000, 2000, 5000, 10000, 20000, 50000]
            .into_iter()
            .filter(|&v| v < n_max)
            .collect();
    shown.push(n_max);
    let mut y = 60;
    for &v in &shown {
        key.draw(&Rectangle::new([(10, y), (36, y + 20)], colour(v).filled()))?;
        let label = if v == n_max { format!("{v} (max)") } else { v.to_string() };
        key.draw(&Text::new(label, (44, y + 4), (FONT, 13)))?;
        y += 25;
    }
    Ok(y)
}

/// The paper's fig. 5: n(r, g) as a colour map (logarithmic in 1 + n, since n runs from 0
/// to thousands near (1, 1)), with a colour key and the no-precursor line g = (1-r)/2.
pub fn fig5_svg(map: &[MapPoint], resolution: usize) -> Result<String> {
    let n_max = map.iter().map(|m| m.n).max().unwrap_or(0);
    let colour =
        |n: usize| viridis(if n_max == 0 { 0.0 } else { (n as f64).ln_1p() / (n_max as f64).ln_1p() });
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
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.9))
            .border_style(BLACK)
            .label_font((FONT, 14))
            .draw()?;
        n_key(&key, n_max, &colour)?;
        Ok(())
    })
}

/// Writes `n_map.csv` and `fig5.svg` into `dir` (created if needed); returns the paths.
pub fn write_map(dir: &Path, map: &[MapPoint], resolution: usize) -> Result<Vec<PathBuf>> {
    ensure_dir(dir)?;
    write_all(dir, &[("n_map.csv", n_map_csv(map)?), ("fig5.svg", fig5_svg(map, resolution)?)])
}

/// Precursor extents x_i against event index: the paper's analytic iteration vs the
/// discrete model fed with FE fields.
pub fn fe_extents_svg(c: &Comparison) -> Result<String> {
    let analytic: Vec<(f64, f64)> =
        c.analytic.iter().filter(|e| !e.stick_slip).map(|e| (e.i as f64, e.x)).collect();
    let fed: Vec<(f64, f64)> = c.fe.precursors().iter().map(|e| (e.i as f64, e.x)).collect();
    for &(_, x) in analytic.iter().chain(&fed) {
        finite("precursor extent", x)?;
    }
    let i_top = analytic.len().max(fed.len()).max(1) as f64 + 0.5;
    let n_text = |n: Option<usize>| n.map_or("not reached".to_string(), |n| n.to_string());
    render("fe_extents.svg", (900, 600), |root| {
        let mut chart = ChartBuilder::on(root)
            .caption(
                format!(
                    "Precursor extents, r = {}, g = {}, H/L = {}, t/L = {}: analytic n = {}, FE-fed n = {}",
                    c.params.r(),
                    c.params.g(),
                    c.h_over_l,
                    c.t_over_l,
                    n_text(c.analytic.iter().position(|e| e.stick_slip)),
                    n_text(c.fe.n_precursors())
                ),
                (FONT, 16),
            )
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(65)
            .build_cartesian_2d(0.5..i_top, -0.5..0.5)?;
        chart
            .configure_mesh()
            .x_desc("precursor index i")
            .x_label_formatter(&|v| format!("{v:.0}"))
            .y_desc("arrest position x_i / L  (dimensionless; trailing edge -1/2)")
            .draw()?;
        chart
            .draw_series(LineSeries::new(analytic.iter().copied(), BLUE.stroke_width(2)).point_size(4))?
            .label("analytic (paper's iteration)")
            .legend(|(x, y)| PathElement::new([(x, y), (x + 20, y)], BLUE.stroke_width(2)));
        chart
            .draw_series(LineSeries::new(fed.iter().copied(), RED.stroke_width(2)))?
            .label("discrete model on FE fields")
            .legend(|(x, y)| PathElement::new([(x, y), (x + 20, y)], RED.stroke_width(2)));
        chart.draw_series(fed.iter().map(|&(i, x)| Cross::new((i, x), 5, RED.stroke_width(2))))?;
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::LowerRight)
            .background_style(WHITE.mix(0.9))
            .border_style(BLACK)
            .label_font((FONT, 14))
            .draw()?;
        Ok(())
    })
}

fn run_csv_rows(s: &mut String, model: &str, run: &Run) -> Result<()> {
    for e in &run.events {
        let CellEvent { i, f, fc, x_nucleation, x, fstar, stick_slip, .. } = *e;
        let _ = writeln!(
            s,
            "{model},{i},{},{},{},{},{},{}",
            finite("F", f)?,
            finite("Fc", fc)?,
            finite("x_nucleation", x_nucleation)?,
            finite("x", x)?,
            finite("Fstar", fstar)?,
            u8::from(stick_slip)
        );
    }
    Ok(())
}

/// Both discrete runs of a comparison, long format:
/// `model,i,F,Fc,x_nucleation,x,Fstar,stick_slip` with model `fe` or `linear`.
pub fn comparison_csv(c: &Comparison) -> Result<String> {
    let mut s = String::from("model,i,F,Fc,x_nucleation,x,Fstar,stick_slip\n");
    run_csv_rows(&mut s, "fe", &c.fe)?;
    run_csv_rows(&mut s, "linear", &c.linear)?;
    Ok(s)
}

/// Writes `fe_events.csv` and `fe_extents.svg` for a comparison into `dir` (created if
/// needed); returns the paths.
pub fn write_comparison(dir: &Path, c: &Comparison) -> Result<Vec<PathBuf>> {
    ensure_dir(dir)?;
    write_all(dir, &[("fe_events.csv", comparison_csv(c)?), ("fe_extents.svg", fe_extents_svg(c)?)])
}

/// Runs [`fe::sweep`] and writes it to `path` as CSV with header
/// `H_over_L,t_over_L,n_fe,n_linear,F1_fe,F1_linear,Fmax_fe,Fmax_linear,max_abs_d_length,outside_model`
/// (forces in units of mu_s N, lengths in units of L; an empty n or Fmax field means the
/// run did not reach stick-slip within `n_events`; `outside_model` says why a geometry could
/// not be run, its figures then left empty).
pub fn sweep_table(
    path: &Path,
    h_over_l: &[f64],
    t_over_l: &[f64],
    r: f64,
    g: f64,
    n_events: usize,
    fields: impl FnMut(f64, f64) -> Result<UnitFields>,
) -> Result<Vec<SweepRow>> {
    let rows = fe::sweep(h_over_l, t_over_l, r, g, n_events, fields)?;
    let mut s = String::from("H_over_L,t_over_L,n_fe,n_linear,F1_fe,F1_linear,Fmax_fe,Fmax_linear,max_abs_d_length,outside_model\n");
    for w in &rows {
        if let Some(why) = &w.outside_model {
            let _ = writeln!(
                s,
                "{},{},,,,,,,,\"{}\"",
                finite("H/L", w.h_over_l)?,
                finite("t/L", w.t_over_l)?,
                why.replace('"', "'")
            );
            continue;
        }
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{},{},",
            finite("H/L", w.h_over_l)?,
            finite("t/L", w.t_over_l)?,
            opt(w.n_fe),
            opt(w.n_linear),
            finite("F1_fe", w.f1_fe)?,
            finite("F1_linear", w.f1_linear)?,
            opt(w.f_max_fe.map(|v| finite("Fmax_fe", v)).transpose()?),
            opt(w.f_max_linear.map(|v| finite("Fmax_linear", v)).transpose()?),
            finite("max_abs_d_length", w.max_abs_d_length)?
        );
    }
    write_atomic(path, s.as_bytes())?;
    Ok(rows)
}

/// `precursors --fe` into `dir`: `summary.csv` (the analytic iteration, then one row per rule
/// of [`crate::studies::precursors_fe::RULES`], `-` where a run was refused), `model/` (as
/// [`write_events`]) and a folder per rule (as [`crate::report::slide::write`], no states).
pub fn write_fe_fig4(
    dir: &Path,
    p: &Params,
    model: &[Event],
    runs: &[Result<crate::studies::precursors_fe::Fig4>],
    inv: &super::run_file::Invocation,
    scene: &crate::scene::Scene,
) -> Result<Vec<PathBuf>> {
    let n = crate::precursors::n_precursors(p)?;
    let x1 = model.first().map_or(f64::NAN, |e| e.x);
    let mut s = format!("source,{FE_COLUMNS},worst_violation_over_N_per_n,{FIELD_COLUMNS}\n");
    let _ = writeln!(
        s,
        "model,{n},{n},{n},{},{},{},,0,0,0,,-0.5",
        finite("F_1", p.f1())?,
        finite("x_1", x1)?,
        p.f_max()
    );
    let mut written = write_events(&dir.join("model"), p, model)?;
    for (rule, run) in crate::studies::precursors_fe::RULES.iter().zip(runs) {
        let name = rule.name();
        let Ok(r) = run else {
            let _ = writeln!(s, "{name},,,,,,,,,,,,");
            continue;
        };
        let _ =
            writeln!(s, "{name},{},{:e},{}", fe_values(&r.cmp), r.worst_violation, field_values(&r.fields));
        let sub = dir.join(name);
        ensure_dir(&sub)?;
        let law = r.run.options.law;
        let what =
            [("rule", name.to_string()), ("mu_s", law.mu_s().to_string()), ("mu_d", law.mu_d().to_string())];
        let header = super::run_toml(inv, &what, scene)?;
        written.extend(super::slide::write(&r.run, &sub, &header, false)?);
    }
    written.extend(write_all(dir, &[("summary.csv", s)])?);
    Ok(written)
}

/// `fig5_fe.csv`: per cell the model's n and F_max, then per rule its status (done, capped,
/// refused, or empty when not run), the three counts, the first cycle's peak, the events, the
/// worst violation, the wall time, for a capped run the precursors and the peak force reached
/// at the cap, and for a finished one what ended its cycle (whole-slip or crossing).
pub fn fe_fig5_csv(cells: &[crate::studies::precursors_fe::Cell]) -> Result<String> {
    use crate::studies::precursors_fe::{CellRun, RULES};
    let mut s = String::from("r,g,model_precursors,model_Fmax_over_mu_s_N");
    for rule in RULES {
        let k = rule.name();
        let _ = write!(
            s,
            ",{k}_status,{k}_precursors,{k}_precursors_longer_5t,{k}_precursors_advancing_5t,{k}_Fmax_over_mu_s_N,{k}_events,{k}_max_violation_over_N_per_n,{k}_seconds,{k}_precursors_at_cap,{k}_Fpeak_at_cap_over_mu_s_N,{k}_cycle_end"
        );
    }
    s.push('\n');
    for c in cells {
        let _ = write!(
            s,
            "{},{},{},{}",
            finite("r", c.r)?,
            finite("g", c.g)?,
            c.n_model,
            finite("F_max", c.f_max_model)?
        );
        for run in &c.runs {
            match run {
                Some(CellRun::Done {
                    crossing,
                    n,
                    n_long,
                    n_advancing,
                    f_max,
                    events,
                    violation,
                    seconds,
                }) => {
                    let end = if *crossing { "crossing" } else { "whole-slip" };
                    let _ = write!(
                        s,
                        ",done,{n},{n_long},{n_advancing},{},{events},{violation:e},{seconds:.3},,,{end}",
                        opt(*f_max)
                    );
                }
                Some(CellRun::Capped { seconds, precursors, f_peak }) => {
                    let _ =
                        write!(s, ",capped,,,,,,,{seconds:.3},{precursors},{},", finite("F peak", *f_peak)?);
                }
                Some(CellRun::Refused { seconds }) => {
                    let _ = write!(s, ",refused,,,,,,,{seconds:.3},,,");
                }
                None => s.push_str(",,,,,,,,,,,"),
            }
        }
        s.push('\n');
    }
    Ok(s)
}

/// `boundary_fe.csv`: per r, the paper's no-precursor line (1 - r)/2, the model grid's and
/// each rule's lowest g with a precursor (empty where unknown or none).
pub fn fe_boundary_csv(cells: &[crate::studies::precursors_fe::Cell]) -> Result<String> {
    use crate::studies::precursors_fe::{boundary, RULES};
    let mut s = String::from("r,paper_line_g,model_first_g");
    for rule in RULES {
        let _ = write!(s, ",{}_first_g", rule.name());
    }
    s.push('\n');
    let per_rule: Vec<_> = (0..RULES.len()).map(|k| boundary(cells, k)).collect();
    for (i, &(r, model, _)) in per_rule[0].iter().enumerate() {
        let _ = write!(s, "{r},{},{}", (1.0 - r) / 2.0, opt(model));
        for b in &per_rule {
            let _ = write!(s, ",{}", opt(b[i].2));
        }
        s.push('\n');
    }
    Ok(s)
}

/// FE fig. 5 next to the analytic one: one panel for the model's n and one per rule run for
/// the FE's front-advancing count, on one logarithmic colour scale; capped cells grey,
/// refused ones black; the paper's line g = (1 - r)/2 in red, the FE's measured boundary as
/// white dots.
pub fn fe_fig5_svg(cells: &[crate::studies::precursors_fe::Cell], resolution: usize) -> Result<String> {
    use crate::studies::precursors_fe::{boundary, CellRun, RULES};
    let ran: Vec<usize> = (0..RULES.len()).filter(|&k| cells.iter().any(|c| c.runs[k].is_some())).collect();
    let n_of = |c: &crate::studies::precursors_fe::Cell, k: Option<usize>| match k {
        None => Some(c.n_model),
        Some(k) => c.runs[k].and_then(|r| r.n_advancing()),
    };
    let n_max = cells
        .iter()
        .flat_map(|c| {
            std::iter::once(None).chain(ran.iter().map(|&k| Some(k))).filter_map(move |k| n_of(c, k))
        })
        .max()
        .unwrap_or(0);
    let colour =
        |n: usize| viridis(if n_max == 0 { 0.0 } else { (n as f64).ln_1p() / (n_max as f64).ln_1p() });
    let half = 0.5 / resolution as f64;
    let panels: Vec<Option<usize>> = std::iter::once(None).chain(ran.iter().map(|&k| Some(k))).collect();
    let w = 460;
    render("fig5_fe.svg", (w * panels.len() as u32 + 170, 500), |root| {
        let (main, key) = root.split_horizontally(w * panels.len() as u32);
        for (area, &k) in main.split_evenly((1, panels.len())).iter().zip(&panels) {
            let title = match k {
                None => "model: n".to_string(),
                Some(k) => format!("FE, rule {}: n advancing > 5 t", RULES[k].name()),
            };
            let mut chart = ChartBuilder::on(area)
                .caption(title, (FONT, 17))
                .margin(12)
                .x_label_area_size(40)
                .y_label_area_size(50)
                .build_cartesian_2d(0.0..1.0, 0.0..1.0)?;
            chart
                .configure_mesh()
                .disable_mesh()
                .x_desc("r = mu_d / mu_s")
                .y_desc("g = 6 mu_d H / L")
                .draw()?;
            chart.draw_series(cells.iter().map(|c| {
                let fill = match (k, n_of(c, k)) {
                    (_, Some(n)) => colour(n),
                    (Some(k), None) => match c.runs[k] {
                        Some(CellRun::Capped { .. }) => RGBColor(160, 160, 160),
                        Some(_) => BLACK,
                        None => WHITE,
                    },
                    (None, None) => WHITE,
                };
                Rectangle::new([(c.r - half, c.g - half), (c.r + half, c.g + half)], fill.filled())
            }))?;
            chart.draw_series(LineSeries::new([(0.0, 0.5), (1.0, 0.0)], RED.stroke_width(2)))?;
            if let Some(k) = k {
                chart.draw_series(
                    boundary(cells, k)
                        .into_iter()
                        .filter_map(|(r, _, g)| g.map(|g| Circle::new((r, g - half), 3, WHITE.filled()))),
                )?;
            }
        }
        let mut y = n_key(&key, n_max, &colour)?;
        for (fill, what) in [(RGBColor(160, 160, 160), "event cap"), (BLACK, "refused")] {
            key.draw(&Rectangle::new([(10, y), (36, y + 20)], fill.filled()))?;
            key.draw(&Text::new(what, (44, y + 4), (FONT, 13)))?;
            y += 25;
        }
        key.draw(&PathElement::new([(10, y + 10), (36, y + 10)], RED.stroke_width(2)))?;
        key.draw(&Text::new("g = (1-r)/2", (44, y + 4), (FONT, 13)))?;
        key.draw(&Circle::new((23, y + 35), 3, BLACK.filled()))?;
        key.draw(&Circle::new((23, y + 35), 2, WHITE.filled()))?;
        key.draw(&Text::new("FE boundary", (44, y + 29), (FONT, 13)))?;
        Ok(())
    })
}

/// Writes the FE fig. 5 (`fig5_fe.csv`, `boundary_fe.csv`, `fig5_fe.svg`, `run.toml`) into
/// `dir`; returns the paths.
pub fn write_fe_fig5(
    dir: &Path,
    cells: &[crate::studies::precursors_fe::Cell],
    resolution: usize,
    what: &[(&str, String)],
    inv: &super::run_file::Invocation,
    scene: &crate::scene::Scene,
) -> Result<Vec<PathBuf>> {
    ensure_dir(dir)?;
    write_all(
        dir,
        &[
            ("fig5_fe.csv", fe_fig5_csv(cells)?),
            ("boundary_fe.csv", fe_boundary_csv(cells)?),
            ("fig5_fe.svg", fe_fig5_svg(cells, resolution)?),
            ("run.toml", super::run_toml(inv, &what, scene)?),
        ],
    )
}

/// Header fragment and values of a run's counts, first precursor and peak for CSVs.
const FE_COLUMNS: &str =
    "precursors,precursors_longer_5t,precursors_advancing_5t,F1_over_mu_s_N,x1_over_L,Fmax_over_mu_s_N";

fn fe_values(c: &crate::studies::slide::PaperComparison) -> String {
    format!(
        "{},{},{},{},{},{}",
        c.n_fe,
        c.n_fe_long,
        c.n_fe_advancing,
        opt(c.f1_fe),
        opt(c.x1_fe),
        opt(c.f_max_fe)
    )
}

/// Header fragment and values of [`crate::studies::precursors_fe::FieldChecks`] for CSVs.
const FIELD_COLUMNS: &str =
    "shear_far_rel_dev,shear_tip_rel_excess,pressure_dev_over_pmean,F_corner_over_mu_s_N,x_nucleation_over_L";

fn field_values(f: &crate::studies::precursors_fe::FieldChecks) -> String {
    format!(
        "{},{},{},{},{}",
        opt(f.shear_far.map(|v| format!("{v:e}"))),
        opt(f.shear_tip.map(|v| format!("{v:e}"))),
        opt(f.pressure.map(|v| format!("{v:e}"))),
        opt(f.f_corner),
        opt(f.x_nucleation)
    )
}

/// A series' CSV (`thin_layer.csv`, `heights.csv`): per value of `param` the model's n, F_1,
/// x_1 and F_max, the `paper` rule's front-advancing count, F_1, x_1 and first whole-slip peak,
/// their deviations (relative; x_1 in units of t), the field checks, the worst violation and
/// the wall time.
pub fn series_csv(param: &str, rows: &[crate::studies::precursors_fe::SeriesRow]) -> Result<String> {
    let mut s = format!(
        "{param},r,g,model_precursors,model_F1_over_mu_s_N,model_x1_over_L,model_Fmax_over_mu_s_N,{FE_COLUMNS},F1_rel_dev,x1_dev_over_t,Fmax_rel_dev,{FIELD_COLUMNS},max_violation_over_N_per_n,seconds\n"
    );
    for row in rows {
        let Ok(f) = &row.fig4 else {
            let _ = writeln!(s, "{}{}{:.3}", row.value, ",".repeat(22), row.seconds);
            continue;
        };
        let c = &f.cmp;
        let t_over_l = f.run.condensed.t / f.run.condensed.l;
        let rel = |v: Option<f64>, m: f64| opt(v.map(|v| v / m - 1.0));
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{},{},{},{},{},{:e},{:.3}",
            row.value,
            c.r,
            c.g,
            c.n,
            c.f1,
            c.x1,
            c.f_max,
            fe_values(c),
            rel(c.f1_fe, c.f1),
            opt(c.x1_fe.map(|x| (x - c.x1) / t_over_l)),
            rel(c.f_max_fe, c.f_max),
            field_values(&f.fields),
            f.worst_violation,
            row.seconds
        );
    }
    Ok(s)
}

/// The thin-layer figure: |F_1 - model|/model, |x_1 - model|/L and |F_max - model|/model
/// against t/L (log-log), and the front-advancing count against t/L with the model's n.
pub fn thin_layer_svg(p: &Params, rows: &[crate::studies::precursors_fe::SeriesRow]) -> Result<String> {
    let n = crate::precursors::n_precursors(p)?;
    let ok: Vec<(f64, &crate::studies::precursors_fe::Fig4)> =
        rows.iter().filter_map(|r| r.fig4.as_ref().ok().map(|f| (r.value, f))).collect();
    type Get = fn(&crate::studies::slide::PaperComparison) -> Option<f64>;
    let series: [(&str, Get, RGBColor); 3] = [
        ("|F_1 - model| / model", |c| c.f1_fe.map(|v| (v / c.f1 - 1.0).abs()), BLUE),
        ("|x_1 - model| / L", |c| c.x1_fe.map(|v| (v - c.x1).abs()), RED),
        ("|F_max - model| / model", |c| c.f_max_fe.map(|v| (v / c.f_max - 1.0).abs()), GREEN),
    ];
    let pts = |g: Get| -> Vec<(f64, f64)> {
        ok.iter().filter_map(|(tl, f)| g(&f.cmp).filter(|v| *v > 0.0).map(|v| (*tl, v))).collect()
    };
    let xr = super::log_range(ok.iter().map(|q| q.0));
    render("thin_layer.svg", (1100, 480), |root| {
        let (left, right) = root.split_horizontally(560);
        let all: Vec<f64> = series.iter().flat_map(|s| pts(s.1)).map(|q| q.1).collect();
        let mut chart = ChartBuilder::on(&left)
            .caption(format!("rule paper against the model, (r, g) = ({}, {})", p.r(), p.g()), (FONT, 16))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(xr.clone().log_scale(), super::log_range(all.into_iter()).log_scale())?;
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
        chart.configure_series_labels().background_style(WHITE.mix(0.85)).border_style(BLACK).draw()?;
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
        chart.configure_series_labels().background_style(WHITE.mix(0.85)).border_style(BLACK).draw()?;
        Ok(())
    })
}

/// Writes the thin-layer study (`thin_layer.csv`, `thin_layer.svg`, `run.toml`) into `dir`.
pub fn write_thin_layer(
    dir: &Path,
    p: &Params,
    rows: &[crate::studies::precursors_fe::SeriesRow],
    inv: &super::run_file::Invocation,
    scene: &crate::scene::Scene,
) -> Result<Vec<PathBuf>> {
    ensure_dir(dir)?;
    let what = [("r", p.r()), ("g", p.g())];
    write_all(
        dir,
        &[
            ("thin_layer.csv", series_csv("t_over_L", rows)?),
            ("thin_layer.svg", thin_layer_svg(p, rows)?),
            ("run.toml", super::run_toml(inv, &what, scene)?),
        ],
    )
}

/// A model value and the FE's (if any) of one quantity of a [`PaperComparison`].
type Pair = fn(&crate::studies::slide::PaperComparison) -> (f64, Option<f64>);
/// Named, coloured quantities drawn on one panel.
type Series<'a> = Vec<(&'a str, Pair, RGBColor)>;

/// A y range covering the model and FE values of `series` over `cmps`, padded by 8 %.
fn series_range<'a>(
    cmps: impl Iterator<Item = &'a crate::studies::slide::PaperComparison>,
    series: &[(&str, Pair, RGBColor)],
) -> std::ops::Range<f64> {
    let (lo, hi) = cmps
        .flat_map(|c| series.iter().flat_map(move |s| std::iter::once((s.1)(c).0).chain((s.1)(c).1)))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)));
    if !(lo.is_finite() && hi.is_finite()) {
        // No finished run: an empty range would send plotters' tick search into a loop.
        return 0.0..1.0;
    }
    let pad = 0.08 * (hi - lo).max(1e-3);
    (lo - pad)..(hi + pad)
}

/// The height-of-drive figure: n, F_1 and F_max, and x_1 against g = 6 mu_d H/L, the FE
/// (`paper` rule, points) next to the model (lines), at fixed friction coefficients.
pub fn heights_svg(rows: &[crate::studies::precursors_fe::SeriesRow]) -> Result<String> {
    let ok: Vec<&crate::studies::slide::PaperComparison> =
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
            chart
                .configure_series_labels()
                .position(SeriesLabelPosition::UpperLeft)
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK)
                .draw()?;
        }
        Ok(())
    })
}

/// Writes the height-of-drive study (`heights.csv`, `heights.svg`, `run.toml`) into `dir`.
pub fn write_heights(
    dir: &Path,
    mu: (f64, f64),
    rows: &[crate::studies::precursors_fe::SeriesRow],
    inv: &super::run_file::Invocation,
    scene: &crate::scene::Scene,
) -> Result<Vec<PathBuf>> {
    ensure_dir(dir)?;
    let what = [("mu_s", mu.0), ("mu_d", mu.1)];
    write_all(
        dir,
        &[
            ("heights.csv", series_csv("H_over_L", rows)?),
            ("heights.svg", heights_svg(rows)?),
            ("run.toml", super::run_toml(inv, &what, scene)?),
        ],
    )
}

/// The D_c figure: F_1 and F_max, x_1, and the front-advancing count against D_c (log),
/// slip-weakening (points) next to the `paper` rule (dashed) and the model (solid).
pub fn dc_svg(rows: &[crate::studies::precursors_fe::SeriesRow]) -> Result<String> {
    use crate::studies::slide::PaperComparison;
    let ok: Vec<(f64, &PaperComparison)> =
        rows.iter().filter_map(|r| r.fig4.as_ref().ok().map(|f| (r.value, &f.cmp))).collect();
    let paper = ok.iter().find(|q| q.0 == 0.0).map(|q| q.1);
    let sw: Vec<(f64, &PaperComparison)> = ok.iter().filter(|q| q.0 > 0.0).copied().collect();
    let panels: [(&str, Series); 3] = [
        ("F / (mu_s N)", vec![("F_1", |c| (c.f1, c.f1_fe), BLUE), ("F_max", |c| (c.f_max, c.f_max_fe), RED)]),
        ("x_1 / L", vec![("x_1", |c| (c.x1, c.x1_fe), BLUE)]),
        ("n (FE: advancing > 5 t)", vec![("n", |c| (c.n as f64, Some(c.n_fe_advancing as f64)), BLUE)]),
    ];
    let xr = super::log_range(sw.iter().map(|q| q.0));
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
            chart.configure_series_labels().background_style(WHITE.mix(0.85)).border_style(BLACK).draw()?;
        }
        Ok(())
    })
}

/// Writes the D_c study into `dir`: `dc.csv` (the series CSV, D_c_m = 0 for the `paper`
/// rule), `dc.svg`, `run.toml`, and each run's fig. 4 in `paper/` and `dc_<D_c>/`
/// (`events.csv`, `loading.csv`, `fig4_fe.svg`, `fronts.svg`, `run.toml`).
pub fn write_dc(
    dir: &Path,
    rows: &[crate::studies::precursors_fe::SeriesRow],
    inv: &super::run_file::Invocation,
    scene: &crate::scene::Scene,
) -> Result<Vec<PathBuf>> {
    ensure_dir(dir)?;
    let what: [(&str, f64); 0] = [];
    let mut written = write_all(
        dir,
        &[
            ("dc.csv", series_csv("Dc_m", rows)?),
            ("dc.svg", dc_svg(rows)?),
            ("run.toml", super::run_toml(inv, &what, scene)?),
        ],
    )?;
    for row in rows {
        let Ok(f) = &row.fig4 else { continue };
        let name = if row.value == 0.0 { "paper".to_string() } else { format!("dc_{:e}", row.value) };
        let sub = dir.join(&name);
        ensure_dir(&sub)?;
        let law = f.run.options.law;
        let what = [("law", law.name()), ("mu_s", law.mu_s().to_string()), ("mu_d", law.mu_d().to_string())];
        let header = super::run_toml(inv, &what, scene)?;
        written.extend(super::slide::write(&f.run, &sub, &header, false)?);
    }
    Ok(written)
}
