//! Output of `tribofe slide`: loading.csv, events.csv, states.csv (names and columns read by
//! scripts: keep them), fig4_fe.svg (loading curve F against F^c with the paper's analytic
//! iteration for the same r, g), fronts.svg (slip extents x/L against F/N) and, on request,
//! a ParaView series of the whole block's fields.

use super::table::{Column, Table};
use crate::error::Result;
use crate::interface::events::{NodeState, Phase, Summary};
use crate::io::{vtu, Field};
use crate::linalg::solve::SolverOptions;
#[cfg(feature = "plots")]
use crate::report::plot::{render, Legend, BLUE, RED};
use crate::report::{finite, write_atomic};
#[cfg(feature = "plots")]
use crate::studies::slide::{model_curve, ModelCurve};
use crate::studies::slide::{state_displacements, SlideResult};
#[cfg(feature = "plots")]
use plotters::prelude::*;
use std::path::{Path, PathBuf};

#[cfg(feature = "plots")]
const FONT: &str = "sans-serif";

/// loading.csv: one row per recorded state (every event's summary, kept states or not).
pub fn loading_csv(r: &SlideResult) -> Result<String> {
    loading_table(r).csv()
}

/// loading.csv's table: the one definition the CSV and the Python package's `loading` are
/// both made from (names, units, types).
pub fn loading_table(r: &SlideResult) -> Table {
    let s = &r.run.summaries;
    let f = |g: &dyn Fn(&Summary) -> f64| s.iter().map(g).collect::<Vec<f64>>();
    let count = |j: usize| s.iter().map(|st| i64::from(st.counts[j])).collect();
    let phase = |st: &Summary| if st.phase == Phase::Normal { "normal" } else { "drive" }.to_string();
    let columns = vec![
        Column::int("event", "-", (0..s.len() as i64).collect()),
        Column::text("phase", "-", s.iter().map(phase).collect()),
        Column::float("X_m", "m", f(&|st| st.x)),
        Column::float("F_N_per_m", "N/m", f(&|st| st.f)),
        Column::float("N_N_per_m", "N/m", f(&|st| st.n_force)),
        Column::float("Fc_N_per_m", "N/m", f(&|st| r.f_c(st.x))),
        Column::float("F_over_N", "1", f(&|st| if st.n_force > 0.0 { st.f / st.n_force } else { 0.0 })),
        Column::float("tilt_rad", "rad", f(&|st| st.tilt)),
        Column::float("V_m", "m", f(&|st| st.v)),
        Column::int("n_stick", "-", count(0)),
        Column::int("n_slip", "-", count(1)),
        Column::int("n_open", "-", count(2)),
        Column::float("max_violation", "1", f(&|st| st.max_violation)),
    ];
    Table { columns, digits: CSV_DIGITS }
}

/// slide's CSVs print 13 significant digits (`{:.12e}`, [`crate::io::csv::e12`]).
const CSV_DIGITS: usize = 13;

/// events.csv: one row per event.
pub fn events_csv(r: &SlideResult) -> Result<String> {
    events_table(r).csv()
}

/// events.csv's table, from [`SlideResult::event_columns`] (forces in units of mu_s N where
/// the name says so; violation and overload in units of N/n).
pub fn events_table(r: &SlideResult) -> Table {
    let ev = r.event_columns();
    let columns = vec![
        Column::int("event", "-", (0..ev.kind.len() as i64).collect()),
        Column::text("kind", "-", ev.kind.iter().map(|k| k.to_string()).collect()),
        Column::float("X_m", "m", ev.x_m),
        Column::float("F_N_per_m", "N/m", ev.f_n_per_m),
        Column::float("F_over_mu_s_N", "1", ev.f_over_mu_s_n),
        Column::float("Fc_over_mu_s_N", "1", ev.fc_over_mu_s_n),
        Column::float("x_nucleation_over_L", "1", ev.x_nucleation_over_l),
        Column::float("x_arrest_over_L", "1", ev.x_arrest_over_l),
        Column::float("region_first_over_L", "1", ev.region_first_over_l),
        Column::float("region_last_over_L", "1", ev.region_last_over_l),
        Column::float("slipped_length_over_L", "1", ev.slipped_length_over_l),
        Column::float("F_relaxed_over_mu_s_N", "1", ev.f_relaxed_over_mu_s_n),
        Column::int("backslip_nodes", "-", ev.backslip_nodes.iter().map(|&n| n as i64).collect()),
        Column::float("max_violation", "1", ev.max_violation),
        Column::float("overload", "1", ev.overload),
    ];
    Table { columns, digits: CSV_DIGITS }
}

/// The first cycle's front advances ([`crate::precursors::definition::advances`]), one row
/// each; `precursor` is 1 where the same cascade is a counted precursor of the one definition.
pub fn advances_csv(r: &SlideResult) -> Result<String> {
    advances_table(r).csv()
}

/// advances.csv's table ([`advances_csv`]).
pub fn advances_table(r: &SlideResult) -> Table {
    let k = r.options.law.mu_s() * r.options.n_force;
    let c = &r.condensed;
    let counted: Vec<usize> = crate::studies::slide::precursors(r).counted().map(|p| p.first_event).collect();
    let adv = crate::studies::slide::front_advances(r);
    let f =
        |g: &dyn Fn(&crate::precursors::definition::Advance) -> f64| adv.iter().map(g).collect::<Vec<f64>>();
    let columns = vec![
        Column::int("advance", "-", (1..=adv.len() as i64).collect()),
        Column::int("event", "-", adv.iter().map(|a| a.first_event as i64).collect()),
        Column::float("X_m", "m", f(&|a| r.run.events[a.first_event].x)),
        Column::float("F_over_mu_s_N", "1", f(&|a| a.f / k)),
        Column::float("front_over_L", "1", f(&|a| c.x[a.front] / c.l)),
        Column::float("x_nucleation_over_L", "1", f(&|a| c.x[a.node] / c.l)),
        Column::int(
            "precursor",
            "-",
            adv.iter().map(|a| i64::from(counted.contains(&a.first_event))).collect(),
        ),
    ];
    Table { columns, digits: CSV_DIGITS }
}

/// One row per state and interface node. The bytes are those `{:.12e}` gives
/// ([`crate::io::csv::push_e12`]), formatted in chunks of states on the rayon pool and
/// joined in order (804 states x 801 nodes: 3.2e6 numbers, 61 MB).
pub fn states_csv(r: &SlideResult) -> Result<String> {
    // Only ASCII is written.
    String::from_utf8(states_bytes(r)?).map_err(|e| crate::error::Error::input("states.csv", e.to_string()))
}

/// [`states_csv`]'s bytes (61 MB at h = 0.5 mm: not checked again as UTF-8). Needs a run
/// that kept its states ([`crate::interface::events::Problem::keep_states`]).
fn states_bytes(r: &SlideResult) -> Result<Vec<u8>> {
    use rayon::prelude::*;
    needs_states(r, "states.csv")?;
    let c = &r.condensed;
    let pm = r.p_mean();
    // contact_area_over_A0 last: the columns before it keep their places for scripts.
    let header = "event,x_over_L,p_over_pmean,tau_over_pmean,slip_m,gap_m,state,contact_area_over_A0\n";
    let x: Vec<f64> = (0..c.n).map(|i| c.x[i] / c.l).collect();
    let chunk = |k0: usize, states: &[crate::interface::events::State]| -> Result<Vec<u8>> {
        let mut b = Vec::with_capacity(states.len() * c.n * 96);
        let put = |b: &mut Vec<u8>, what: &str, v: f64| -> Result<()> {
            crate::io::csv::push_e12(b, finite(what, v)?);
            b.push(b',');
            Ok(())
        };
        for (k, st) in (k0..).zip(states) {
            let tag = format!("{k},");
            let area = crate::studies::slide::contact_area_over_a0(&st.p_force, &c.w, c.l);
            for i in 0..c.n {
                b.extend_from_slice(tag.as_bytes());
                put(&mut b, "x", x[i])?;
                put(&mut b, "p", st.p_force[i] / c.w[i] / pm)?;
                put(&mut b, "tau", -st.t_force[i] / c.w[i] / pm)?;
                put(&mut b, "slip", st.u[i])?;
                put(&mut b, "gap", st.gap[i])?;
                b.extend_from_slice(st.states[i].name().as_bytes());
                b.push(b',');
                crate::io::csv::push_e12(&mut b, finite("contact_area_over_A0", area[i])?);
                b.push(b'\n');
            }
        }
        Ok(b)
    };
    const STATES_PER_CHUNK: usize = 32;
    let parts: Vec<Result<Vec<u8>>> = r
        .run
        .states
        .par_chunks(STATES_PER_CHUNK)
        .enumerate()
        .map(|(j, s)| chunk(j * STATES_PER_CHUNK, s))
        .collect();
    let mut out = Vec::with_capacity(
        header.len() + parts.iter().map(|p| p.as_ref().map_or(0, Vec::len)).sum::<usize>(),
    );
    out.extend_from_slice(header.as_bytes());
    // The first error in row order, as a sequential writer would report it.
    for p in parts {
        out.extend_from_slice(&p?);
    }
    Ok(out)
}

/// Refuses a reader of every event's state (`what`) on a run that kept only its last.
fn needs_states(r: &SlideResult, what: &str) -> Result<()> {
    if r.run.has_all_states() {
        return Ok(());
    }
    Err(crate::error::Error::input(
        what,
        format!(
            "needs the interface state of every event, but the run kept only its last of {} (keep_states false, `--states none`): run with the states kept",
            r.run.events.len()
        ),
    ))
}

/// The FE loading curve (F^c, F)/(mu_s N) of the drive phase: each instability is a vertical
/// drop from its force to its relaxed force.
pub fn fe_curve(r: &SlideResult) -> Vec<(f64, f64)> {
    let k = r.options.law.mu_s() * r.options.n_force;
    let mut pts = vec![(0.0, 0.0)];
    for (e, st) in r.run.events.iter().zip(&r.run.summaries) {
        if st.phase != Phase::Drive {
            continue;
        }
        pts.push((r.f_c(e.x) / k, e.f / k));
        pts.push((r.f_c(e.x) / k, e.f_relaxed / k));
    }
    pts
}

#[cfg(feature = "plots")]
/// The FE loading curve ([`fe_curve`]) against the paper's iteration for the same (r, g)
/// ([`crate::studies::slide::model_curve`], computed by the study layer).
pub fn fig4_svg(r: &SlideResult, model: &ModelCurve) -> Result<String> {
    // mu_s = 0 (a frictionless run to a given X) has no mu_s N to scale by: F/(mu_s N) is
    // infinite, and an infinite axis sent plotters' tick search into an endless loop.
    let fe: Vec<(f64, f64)> =
        fe_curve(r).into_iter().filter(|p| p.0.is_finite() && p.1.is_finite()).collect();
    let law = r.options.law;
    let (rr, g, analytic) = (model.r, model.g, &model.points);
    let all = fe.iter().chain(analytic.iter().flatten());
    let fc_top = all.clone().fold(0.1f64, |m, p| m.max(p.0)) * 1.05;
    let f_top = all.fold(0.1f64, |m, p| m.max(p.1)) * 1.1;
    render("fig4_fe.svg", (900, 650), |root| {
        let mut chart = ChartBuilder::on(root)
            .caption(format!("Loading curve, FE {} (r = {rr:.3}, g = {g:.3})", law.name()), (FONT, 20))
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(65)
            .build_cartesian_2d(0.0..fc_top, 0.0..f_top)?;
        chart
            .configure_mesh()
            .x_desc("elastic force F^c / (mu_s N) = k_bonded X / (mu_s N)  (dimensionless)")
            .y_desc("friction force F / (mu_s N)  (dimensionless)")
            .draw()?;
        let m = fc_top.min(f_top);
        chart
            .draw_series(LineSeries::new([(0.0, 0.0), (m, m)], BLACK.stroke_width(1)))?
            .label("ideal elastic loading F = F^c")
            .legend(|(x, y)| PathElement::new([(x, y), (x + 20, y)], BLACK));
        chart
            .draw_series(LineSeries::new(fe.iter().copied(), RED.stroke_width(2)))?
            .label("FE event by event")
            .legend(|(x, y)| PathElement::new([(x, y), (x + 20, y)], RED.stroke_width(2)));
        if let Some(a) = analytic {
            chart
                .draw_series(LineSeries::new(a.iter().copied(), BLUE.stroke_width(1)))?
                .label("paper's analytic iteration")
                .legend(|(x, y)| PathElement::new([(x, y), (x + 20, y)], BLUE));
        }
        chart.legend_box(SeriesLabelPosition::LowerRight)?;
        Ok(())
    })
}

#[cfg(feature = "plots")]
/// Space-time picture, one row per event of the drive phase (the row of events.csv, so rows
/// never overlap however many precursors there are): each instability's slipped extent x/L
/// (blue for a precursor, dark red for a slip of the whole interface) and, for continuous slip
/// (coulomb, creep), each state's runs of slipping nodes (light red); on the right, F/N at
/// each event on the same rows, so the force of each front can be read across.
pub fn fronts_svg(r: &SlideResult) -> Result<String> {
    let c = &r.condensed;
    let n = r.options.n_force;
    let mut segs: Vec<(f64, f64, f64, bool)> = Vec::new();
    let mut runs: Vec<(f64, f64, f64)> = Vec::new();
    let mut force: Vec<(f64, f64)> = Vec::new();
    for (k, (e, st)) in r.run.events.iter().zip(&r.run.summaries).enumerate() {
        if st.phase != Phase::Drive {
            continue;
        }
        let y = k as f64;
        force.push((st.f / n, y));
        if let Some((a, b)) = e.region {
            segs.push((
                c.x[a] / c.l,
                c.x[b] / c.l,
                y,
                e.kind == crate::interface::events::EventKind::Sliding || (a == 0 && b + 1 == c.n),
            ));
        }
        for &(i, j) in &st.slip_runs {
            runs.push((c.x[i as usize] / c.l, c.x[j as usize] / c.l, y));
        }
    }
    let (y0, y1) = force.iter().fold((f64::MAX, f64::MIN), |(a, b), p| (a.min(p.1), b.max(p.1)));
    // Room above the last row for the legend.
    let (y0, y1) = if y0 <= y1 { (y0 - 0.5, y1 + 0.5 + 0.16 * (y1 - y0 + 1.0)) } else { (0.0, 1.0) };
    let f_top = force.iter().fold(0.1f64, |m, p| m.max(p.0)) * 1.05;
    let f_bottom = force.iter().fold(0.0f64, |m, p| m.min(p.0));
    // Row thickness: a full row each while they are wider than a pixel.
    let rows = (y1 - y0).max(1.0);
    let width = ((500.0 / rows).floor() as u32).clamp(1, 4);
    let slips = segs.iter().filter(|s| s.3).count();
    render("fronts.svg", (1000, 700), |root| {
        let root = root.titled(
            &format!(
                "Slip fronts, FE {}: {} instabilities ({} whole-interface slips)",
                r.options.law.name(),
                segs.len(),
                slips
            ),
            (FONT, 19),
        )?;
        let (left, right) = root.split_horizontally(740);
        let mut chart = ChartBuilder::on(&left)
            .margin(12)
            .x_label_area_size(45)
            .y_label_area_size(70)
            .build_cartesian_2d(-0.5..0.5, y0..y1)?;
        chart
            .configure_mesh()
            .disable_y_mesh()
            .x_desc("position along the interface x / L (trailing edge -1/2)  (dimensionless)")
            .y_desc("event (row of events.csv, drive phase)")
            .y_label_formatter(&|v: &f64| format!("{v:.0}"))
            .draw()?;
        let light = RGBColor(240, 130, 130);
        let dark = RGBColor(150, 0, 0);
        chart
            .draw_series(
                runs.iter().map(|&(a, b, y)| PathElement::new([(a, y), (b, y)], light.stroke_width(width))),
            )?
            .label("slipping nodes of each state (continuous slip)")
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], light.stroke_width(3)));
        chart
            .draw_series(
                segs.iter()
                    .filter(|s| !s.3)
                    .map(|&(a, b, y, _)| PathElement::new([(a, y), (b, y)], BLUE.stroke_width(width))),
            )?
            .label("extent of each precursor")
            .legend(|(x, y)| PathElement::new([(x, y), (x + 20, y)], BLUE.stroke_width(3)));
        chart
            .draw_series(
                segs.iter()
                    .filter(|s| s.3)
                    .map(|&(a, b, y, _)| PathElement::new([(a, y), (b, y)], dark.stroke_width(width))),
            )?
            .label("slip of the whole interface")
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], dark.stroke_width(3)));
        chart.legend_box(SeriesLabelPosition::UpperLeft)?;
        let mut f_chart = ChartBuilder::on(&right)
            .margin(12)
            .x_label_area_size(45)
            .y_label_area_size(10)
            .build_cartesian_2d(f_bottom..f_top, y0..y1)?;
        f_chart
            .configure_mesh()
            .disable_y_mesh()
            .y_labels(0)
            .x_labels(4)
            .x_desc("F / N at the event (dimensionless)")
            .draw()?;
        f_chart.draw_series(LineSeries::new(force.iter().copied(), BLACK.stroke_width(1)))?;
        Ok(())
    })
}

/// Writes every output into `dir`, `states.csv` (~40 bytes per node and state, hundreds of MB
/// for long runs) only if `states` (which needs a run that kept its states); `header` is the
/// run.toml text (what produced the files). Every other file reads [`Run::summaries`], so
/// it is the same whether or not the run kept its states.
///
/// [`Run::summaries`]: crate::interface::events::Run::summaries
pub fn write(r: &SlideResult, dir: &Path, header: &str, states: bool) -> Result<Vec<PathBuf>> {
    if states {
        needs_states(r, "states.csv")?;
    }
    // states.csv (most of the output's time: formatting, the CSV guard, the copy into the
    // page cache) is made and written beside the other files; errors are reported in the
    // files' order, as one after another would.
    let others = || -> Result<Vec<PathBuf>> {
        let mut files = vec![("loading.csv", loading_csv(r)?), ("events.csv", events_csv(r)?)];
        if r.options.law.weakens() {
            files.push(("advances.csv", advances_csv(r)?));
        }
        #[cfg(feature = "plots")]
        files.extend([("fig4_fe.svg", fig4_svg(r, &model_curve(r))?), ("fronts.svg", fronts_svg(r)?)]);
        files.push(("run.toml", header.to_string()));
        let mut out = Vec::new();
        for (name, text) in files {
            let p = dir.join(name);
            write_atomic(&p, text.as_bytes())?;
            out.push(p);
        }
        Ok(out)
    };
    let states_file = || -> Result<Option<PathBuf>> {
        if !states {
            return Ok(None);
        }
        let p = dir.join("states.csv");
        write_atomic(&p, &states_bytes(r)?)?;
        Ok(Some(p))
    };
    let (out, st) = rayon::join(others, states_file);
    let mut out = out?;
    out.extend(st?);
    Ok(out)
}

/// The whole block through the run: for each picked state `fields_<state>.vtu` (ParaView)
/// and/or `fields_<state>.msh` (Gmsh) as `format` asks, with displacement, nodal stresses, von
/// Mises, `interface_state` (0 stick, 1 slip, 2 open, -1 off the interface) and `event` (the
/// state's row in loading.csv, the same at every node); with .vtu, `fields.pvd`, whose
/// timestep is the drive X in m (pick the states with [`field_states`]: one per X). Needs a
/// run that kept its states (refused otherwise).
pub fn write_fields(
    r: &SlideResult,
    picks: &[usize],
    dir: &Path,
    opts: &SolverOptions,
    format: crate::io::FieldFormat,
) -> Result<Vec<PathBuf>> {
    if format == crate::io::FieldFormat::None || picks.is_empty() {
        return Ok(Vec::new());
    }
    needs_states(r, "fields")?;
    if let Some(w) = picks.windows(2).find(|w| r.run.states[w[1]].x <= r.run.states[w[0]].x) {
        return Err(crate::error::Error::input(
            "fields",
            format!("states {} and {} do not advance X: the .pvd needs increasing X", w[0], w[1]),
        ));
    }
    let (sm, us) = state_displacements(r, picks, opts)?;
    let model = sm.model();
    let mut written = Vec::new();
    let mut pvd = Vec::new();
    for (&k, u) in picks.iter().zip(&us) {
        let mut state = vec![-1.0; sm.mesh.n_nodes()];
        for (&node, s) in sm.interface.iter().zip(&r.run.states[k].states) {
            state[node] = match s {
                NodeState::Stick => 0.0,
                NodeState::Slip(_) => 1.0,
                NodeState::Open => 2.0,
            };
        }
        let mut point = Field::solution_fields(&model, u);
        point.push(Field::scalar("interface_state", state));
        point.push(Field::scalar("event", vec![k as f64; sm.mesh.n_nodes()]));
        if format.vtu() {
            let path = dir.join(format!("fields_{k:06}.vtu"));
            vtu::write_vtu(&path, &sm.mesh, &point, &[])?;
            pvd.push((r.run.states[k].x, path));
        }
        if format.msh() {
            let path = dir.join(format!("fields_{k:06}.msh"));
            crate::io::gmsh_post::write_msh(&path, &sm.mesh, &point, &[])?;
            written.push(path);
        }
    }
    if format.vtu() {
        let entries: Vec<(f64, &Path)> = pvd.iter().map(|(x, p)| (*x, p.as_path())).collect();
        vtu::write_pvd(&dir.join("fields.pvd"), &entries)?;
        written.extend(pvd.into_iter().map(|(_, p)| p));
        written.push(dir.join("fields.pvd"));
    }
    Ok(written)
}

/// Up to `k` states for the field files, one per drive X (the settled state, the last at
/// that X: an instability relaxes at fixed X, so its intermediate states share the X),
/// spread evenly over the run, the first and last X included. Read off the summaries; the
/// picks index the states, so [`write_fields`] needs a run that kept them.
pub fn field_states(r: &SlideResult, k: usize) -> Vec<usize> {
    let s = &r.run.summaries;
    let settled: Vec<usize> = (0..s.len()).filter(|&i| i + 1 == s.len() || s[i + 1].x != s[i].x).collect();
    spread(settled.len(), k.min(settled.len())).into_iter().map(|i| settled[i]).collect()
}

/// `k` state indices spread evenly over `n` states, the first and last included.
pub fn spread(n: usize, k: usize) -> Vec<usize> {
    // More picks than states would repeat them (and i (n - 1) could overflow).
    let k = k.min(n);
    match (n, k) {
        (0, _) | (_, 0) => vec![],
        (_, 1) => vec![n - 1],
        _ => {
            let mut v: Vec<usize> = (0..k).map(|i| (i * (n - 1) + (k - 1) / 2) / (k - 1)).collect();
            v.dedup();
            v
        }
    }
}

/// Counts of each event kind, in first-seen order.
pub fn kind_counts(r: &SlideResult) -> Vec<(&'static str, usize)> {
    let mut v: Vec<(&'static str, usize)> = Vec::new();
    for e in &r.run.events {
        match v.iter_mut().find(|k| k.0 == e.kind.name()) {
            Some(k) => k.1 += 1,
            None => v.push((e.kind.name(), 1)),
        }
    }
    v
}
