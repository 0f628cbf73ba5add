//! Precursors from the frictional FE itself (issue 18): the paper's fig. 4 and fig. 5
//! recomputed on a scene, the interface condensed once and reused for every rule and cell;
//! the model's field assumptions measured on a run ([`FieldChecks`]); and the one-parameter
//! series that test its limits: thin layer ([`thin_layer`]), height of the drive
//! ([`heights`]) and event rule against D_c ([`dc_series`]). The corners are
//! `studies::edges`.
//!
//! What counts as a precursor, its F_i and x_i: [`crate::precursors::definition`], the one
//! definition every count here goes through (via [`compare_paper`] and
//! [`crate::studies::slide::precursors`]).

use crate::error::Result;
use crate::interface::condense::{condense, Condensed};
use crate::interface::events::{EventKind, NodeState, Observer};
use crate::law::{Law, Rule};
use crate::linalg::solve::SolverOptions;
use crate::precursors::definition::{self, Precursors, Slip, ZONE_T};
use crate::progress::Progress;
use crate::scene::Scene;
use crate::studies::slide::{
    coefficients_from_rg, compare_paper, precursors, run_condensed, PaperComparison, SlideOptions,
    SlideResult,
};
use rayon::prelude::*;
use std::sync::{Arc, Mutex, PoisonError};

mod series;
use series::interrupted;
pub use series::*;

/// The two event rules compared in both figures.
pub const RULES: [Rule; 2] = [Rule::Paper, Rule::Overdamped];

/// Stick-slip cycles of each fig. 4 run by default (`precursors fe`, `tribofe.precursors.fe_fig4`).
pub const DEFAULT_FIG4_CYCLES: usize = 2;

/// The fig. 5 map's default grid (cells per axis) and event cap per cell (`precursors fe-map`,
/// `tribofe.precursors.fe_fig5`).
pub const DEFAULT_FIG5_RESOLUTION: usize = 20;
pub const DEFAULT_FIG5_MAX_EVENTS: usize = 2000;
pub const DEFAULT_FIG5_RULES: [Rule; 1] = [Rule::Paper];

/// The event cap of each run of the D_c series by default (`precursors dc`,
/// `tribofe.precursors.dc`).
pub const DEFAULT_DC_MAX_EVENTS: usize = 2000;

/// The earlier comparison (`precursors bonded`): the 1D model fed with the scene's bonded
/// unit interface fields next to the paper's linear fields on the same cells, `events` events
/// each (at most [`crate::precursors::MAX_EVENTS`]); `cancel` stops it before and after the
/// FE solve.
pub fn bonded(
    scene: &Scene,
    r: f64,
    g: f64,
    events: usize,
    cancel: &crate::Cancel,
) -> Result<crate::precursors::fe::Comparison> {
    crate::precursors::check_events(events)?;
    cancel.check()?;
    let fields = crate::studies::check::run(scene, &SolverOptions::default())?.0.unit;
    cancel.check()?;
    crate::precursors::fe::compare(&fields, r, g, events)
}

/// The bonded sweep's geometries (`precursors bonded --sweep`): H/L and t/L as multiples of
/// the scene's.
pub const BONDED_SWEEP_H: [f64; 4] = [0.25, 0.5, 1.0, 2.0];
pub const BONDED_SWEEP_T: [f64; 4] = [0.5, 1.0, 2.0, 4.0];

/// `precursors bonded --sweep`: the earlier comparison ([`crate::precursors::fe::sweep`]) at
/// (r, g) over H/L and t/L around the scene's ([`BONDED_SWEEP_H`] x [`BONDED_SWEEP_T`], H/L
/// outer), one bonded check per geometry on the scene's mesh size, no coarser than t/2;
/// `events` events per discrete run. Reports each geometry before its solve (the fraction of
/// the geometries done) and stops there once `cancel` is cancelled.
pub fn bonded_sweep(
    scene: &Scene,
    r: f64,
    g: f64,
    events: usize,
    cancel: &crate::Cancel,
    progress: Progress,
) -> Result<Vec<crate::precursors::fe::SweepRow>> {
    crate::precursors::check_events(events)?;
    let l = scene.block.length;
    let (h0, t0) = (scene.loading.height / l, scene.block.thickness / l);
    let hs = BONDED_SWEEP_H.map(|k| k * h0);
    let ts = BONDED_SWEEP_T.map(|k| k * t0);
    let total = (hs.len() * ts.len()) as f64;
    let mut done = 0.0;
    crate::precursors::fe::sweep(&hs, &ts, r, g, events, |h, t| {
        cancel.check()?;
        progress.tick(&crate::Tick {
            fraction: Some(done / total),
            message: &format!("sweep: H/L = {h}, t/L = {t}"),
            item: None,
        });
        done += 1.0;
        let mut s = scene.clone();
        s.loading.height = h * l;
        s.block.thickness = t * l;
        s.mesh.h = s.mesh.h.min(s.block.thickness / 2.0);
        let mut f = crate::studies::check::run(&s, &SolverOptions::default())?.0.unit;
        (f.h_over_l, f.t_over_l) = (h, t); // exact keys for the table
        Ok(f)
    })
}

/// One rule's FE fig. 4 next to the analytic iteration (forces in units of mu_s N, x in L).
#[derive(Debug, Clone)]
pub struct Fig4 {
    /// The static-kinetic rule (`paper` for slip-weakening runs: the law is in `run`).
    pub rule: Rule,
    pub cmp: PaperComparison,
    /// Arrest positions x_i/L of the counted (advancing) precursors, i = 1..n.
    pub x_fe: Vec<f64>,
    /// Analytic x_1..x_n.
    pub x_model: Vec<f64>,
    /// Stick-slip peaks F/(mu_s N) of the `sliding` events.
    pub peaks: Vec<f64>,
    /// Worst contact/friction violation over all states (Violations::max).
    pub worst_violation: f64,
    /// The model's field assumptions measured on this run.
    pub fields: FieldChecks,
    /// The whole run (events, states), for the report.
    pub run: SlideResult,
}

/// The static-kinetic law of (r, g) on `scene` with `rule`.
fn sk(scene: &Scene, r: f64, g: f64, rule: Rule) -> Result<Law> {
    let (ms, md) = coefficients_from_rg(scene, r, g)?;
    Law::static_kinetic(ms, md, rule)
}

/// One run with the options `o` on the condensed interface, next to the iteration at (r, g).
fn fig4_on(
    scene: &Scene,
    c: &Condensed,
    r: f64,
    g: f64,
    o: SlideOptions,
    progress: Progress,
) -> Result<Fig4> {
    let rule = o.law.rule();
    // Cycles end as the model's do, when the slip has crossed the interface.
    let o = SlideOptions { end_at_crossing: true, ..o };
    let res = run_condensed(scene, c.clone(), 0.0, &o, progress)?;
    let cmp = compare_paper(&res)
        .ok_or_else(|| crate::Error::input("r, g", "outside the accessible square 0 < r, g < 1"))?;
    let p = crate::precursors::Params::new(r, g)?;
    let ev = crate::precursors::simulate(&p, cmp.n.max(1));
    let evs = &res.run.events;
    let cx = &res.condensed;
    Ok(Fig4 {
        rule,
        cmp,
        x_fe: precursors(&res).counted().map(|q| cx.x[q.arrest()] / cx.l).collect(),
        x_model: ev.iter().take(cmp.n).map(|e| e.x).collect(),
        peaks: evs.iter().filter(|e| e.ends_cycle()).map(|e| e.f / (o.law.mu_s() * o.n_force)).collect(),
        worst_violation: res.run.max_violation,
        fields: field_checks(&res),
        run: res,
    })
}

/// The model's assumptions on the interface fields, measured on the states of a run before its
/// first whole-interface slip (dimensionless; "interior": farther than 5 t from both ends).
#[derive(Debug, Clone, Copy, Default)]
pub struct FieldChecks {
    /// Assumption 1 (homogeneous shear): over the states after the counted precursors, the
    /// largest |tau - F^c/L|/(F^c/L) on interior nodes that never slipped and lie more than
    /// 5 t ahead of the front (F^c = k_bonded X, the shear an all-stuck interface carries).
    pub shear_far: Option<f64>,
    /// The largest tau/(F^c/L) - 1 at the first node ahead of an arrested front (its
    /// crack-tip concentration, which the model leaves out).
    pub shear_tip: Option<f64>,
    /// Assumption 2 (linear pressure set by F alone): the largest |p - (N/L + 12 F H x/L^3)|
    /// over N/L on interior contact nodes, over every state (None: no interior contact node,
    /// a block shorter than 10 t).
    pub pressure: Option<f64>,
    /// Assumption 3: F/(mu_s N) when the trailing node first opens or creeps (None: not
    /// before the first whole slip), and x/L where the first counted precursor nucleated.
    pub f_corner: Option<f64>,
    pub x_nucleation: Option<f64>,
}

/// Measures [`FieldChecks`] on a run that kept its states (it reads each state's per-node
/// pressures: the [`crate::interface::events::Summary`]s do not hold them).
pub fn field_checks(res: &SlideResult) -> FieldChecks {
    let c = &res.condensed;
    let (evs, states) = (&res.run.events, &res.run.states);
    let first = evs.iter().position(|e| e.ends_cycle()).unwrap_or(evs.len()).min(states.len());
    let (pm, h, edge) = (res.p_mean(), res.scene.loading.height, ZONE_T * c.t);
    let interior = |i: usize| (c.x[i] - c.x[0]).min(c.x[c.n - 1] - c.x[i]) > edge;
    let pre = precursors(res);
    let mut out =
        FieldChecks { x_nucleation: pre.first().map(|q| c.x[q.node] / c.l), ..FieldChecks::default() };
    let mut slipped = vec![false; c.n];
    let mut front = None::<usize>;
    let max_opt = |a: Option<f64>, b: f64| Some(a.map_or(b, |a| a.max(b)));
    for (k, (e, st)) in evs[..first].iter().zip(&states[..first]).enumerate() {
        for i in (0..c.n).filter(|&i| interior(i) && st.states[i] != NodeState::Open) {
            let linear = pm + 12.0 * st.f * h * c.x[i] / c.l.powi(3);
            out.pressure = max_opt(out.pressure, (st.p_force[i] / c.w[i] - linear).abs() / pm);
        }
        if out.f_corner.is_none() && e.node == 0 && matches!(e.kind, EventKind::Open | EventKind::Creep) {
            out.f_corner = Some(st.f / (res.options.law.mu_s() * res.options.n_force));
        }
        if let Some((a, b)) = e.region {
            (a..=b).for_each(|k| slipped[k] = true);
        }
        // The state after a precursor's last instability is the arrested one.
        let Some(q) = pre.all.iter().find(|q| q.last_event == k) else { continue };
        let b = q.arrest();
        front = Some(front.map_or(b, |f| f.max(b)));
        let f = front.unwrap_or(b);
        let tau_c = res.f_c(st.x) / c.l;
        if f + 1 < c.n && tau_c > 0.0 {
            let tau = |i: usize| -st.t_force[i] / c.w[i];
            out.shear_tip = max_opt(out.shear_tip, tau(f + 1) / tau_c - 1.0);
            for i in (f + 1..c.n).filter(|&i| interior(i) && !slipped[i] && c.x[i] - c.x[f] > edge) {
                out.shear_far = max_opt(out.shear_far, (tau(i) - tau_c).abs() / tau_c);
            }
        }
    }
    out
}

/// FE fig. 4 for (r, g) on `scene`, one condensation for both rules; each rule's run may
/// be refused on its own (the overdamped relaxation can cycle without settling), but a
/// cancel ends the whole call; `progress` gets the fraction of the two runs done.
pub fn fig4(
    scene: &Scene,
    r: f64,
    g: f64,
    cycles: usize,
    cancel: &crate::Cancel,
    progress: Progress,
) -> Result<Vec<Result<Fig4>>> {
    fig4_with(scene, r, g, cycles, crate::law::PaperOptions::default(), cancel, progress)
}

/// [`fig4`] with the `paper` rule's conventions `paper` (the overdamped run is unchanged).
pub fn fig4_with(
    scene: &Scene,
    r: f64,
    g: f64,
    cycles: usize,
    paper: crate::law::PaperOptions,
    cancel: &crate::Cancel,
    progress: Progress,
) -> Result<Vec<Result<Fig4>>> {
    // Here, not in a front end: the command and the package refuse the same counts.
    if cycles == 0 {
        return Err(crate::Error::input("--cycles", "need at least one whole-interface slip"));
    }
    let cap = SlideOptions::default().max_events;
    if cycles > cap {
        return Err(crate::Error::input(
            "--cycles",
            format!("{cycles}: above the event cap of {cap} (each cycle takes at least one event)"),
        ));
    }
    let c = condense(scene, &SolverOptions::default())?;
    let mut out = Vec::with_capacity(RULES.len());
    for (k, &rule) in RULES.iter().enumerate() {
        let part = |x: f64| progress.fraction((k as f64 + x) / RULES.len() as f64);
        let run = sk(scene, r, g, rule)
            .and_then(|law| if rule == Rule::Paper { law.with_paper_options(paper) } else { Ok(law) })
            .and_then(|law| {
                let o = SlideOptions { law, cycles, cancel: cancel.clone(), ..Default::default() };
                fig4_on(scene, &c, r, g, o, Progress::new(&|t| part(t.fraction.unwrap_or(0.0))))
            });
        interrupted(&run)?;
        out.push(run);
    }
    Ok(out)
}

/// One rule's run in one cell of FE fig. 5.
#[derive(Debug, Clone, Copy)]
pub enum CellRun {
    /// Reached the end of the first cycle: a whole-interface slip, or (`crossing`) a front
    /// crossing ([`crate::interface::events::Problem::end_at_crossing`]). Counts as in
    /// [`PaperComparison`]; the peak F/(mu_s N) that ended it; the events, the worst
    /// violation (N/n) and the wall time, s.
    Done {
        crossing: bool,
        n: usize,
        n_long: usize,
        n_advancing: usize,
        f_max: Option<f64>,
        events: usize,
        violation: f64,
        seconds: f64,
    },
    /// Needed more than the cap of events before the end of its first cycle: the precursors
    /// of the recorded events by the one definition ([`SlipLog::at_cap`]: every precursor,
    /// advancing or not, as `n` of [`CellRun::Done`]; a lower bound on the finished run's) and
    /// the largest F reached, in units of mu_s N.
    Capped { seconds: f64, precursors: usize, f_peak: f64 },
    /// Refused by the event solver (a relaxation that did not settle...).
    Refused { seconds: f64 },
}

impl CellRun {
    pub fn status(&self) -> &'static str {
        match self {
            CellRun::Done { .. } => "done",
            CellRun::Capped { .. } => "capped",
            CellRun::Refused { .. } => "refused",
        }
    }
    pub fn seconds(&self) -> f64 {
        match *self {
            CellRun::Done { seconds, .. }
            | CellRun::Capped { seconds, .. }
            | CellRun::Refused { seconds } => seconds,
        }
    }
    /// The front-advancing count (the least mesh-sensitive) of a finished run.
    pub fn n_advancing(&self) -> Option<usize> {
        match *self {
            CellRun::Done { n_advancing, .. } => Some(n_advancing),
            _ => None,
        }
    }
}

/// A run's instabilities as the precursor definition reads them ([`Slip`]s), collected while
/// the run is recorded through [`crate::interface::events::Problem::observer`]: a run that ends
/// at its event cap returns no events, but its log still has them.
#[derive(Debug, Clone, Default)]
pub struct SlipLog(Arc<Mutex<Vec<Slip>>>);

impl SlipLog {
    pub fn new() -> SlipLog {
        SlipLog::default()
    }

    /// The observer that fills this log (put it in the run's options).
    pub fn observer(&self) -> Observer {
        let log = self.0.clone();
        Observer::new(move |k, e, _| {
            if let Some(s) = e.slip(k) {
                log.lock().unwrap_or_else(PoisonError::into_inner).push(s);
            }
        })
    }

    /// The slips logged so far, in order.
    pub fn slips(&self) -> Vec<Slip> {
        self.0.lock().unwrap_or_else(PoisonError::into_inner).clone()
    }

    /// The precursors of a run stopped by its event cap at drive displacement `x_stop` (m,
    /// [`crate::Error::EventCap`]'s x), by [`definition::find`] on the interface nodes `x` (m)
    /// under a block of thickness `t` (m). The cascade at `x_stop` is left out: the cap cut
    /// it, and it may still grow, or end the cycle (then it is no precursor); so every count
    /// is a lower bound on the finished run's.
    pub fn at_cap(&self, x_stop: f64, x: &[f64], t: f64) -> Precursors {
        let mut slips = self.slips();
        slips.retain(|s| s.x_drive != x_stop);
        definition::find(&slips, x, t)
    }
}

/// One cell of FE fig. 5: the analytic n and F_max, and per rule (order of [`RULES`]) the FE
/// run, None for a rule not asked for.
#[derive(Debug, Clone, Copy)]
pub struct Cell {
    pub r: f64,
    pub g: f64,
    pub n_model: usize,
    pub f_max_model: f64,
    pub runs: [Option<CellRun>; 2],
}

/// n(r, g) at the centres of a `resolution` x `resolution` grid over (0,1)^2 (as
/// [`crate::precursors::n_map`], g fastest), FE for the `rules` given, cells in parallel, the
/// interface condensed once; each run stops at the first whole-interface slip or after
/// `max_events` events (then [`CellRun::Capped`]); `progress` gets the fraction of the cells
/// done after each (from any thread).
pub fn fig5(
    scene: &Scene,
    resolution: usize,
    rules: &[Rule],
    max_events: usize,
    cancel: &crate::Cancel,
    progress: Progress,
) -> Result<Vec<Cell>> {
    let model = crate::precursors::n_map(resolution, cancel)?;
    let c = condense(scene, &SolverOptions::default())?;
    let done = std::sync::atomic::AtomicUsize::new(0);
    model
        .par_iter()
        .map(|m| {
            let p = crate::precursors::Params::new(m.r, m.g)?;
            let mut cell = Cell { r: m.r, g: m.g, n_model: m.n, f_max_model: p.f_max(), runs: [None; 2] };
            for (k, &rule) in RULES.iter().enumerate().filter(|(_, r)| rules.contains(r)) {
                // The run's slips, so a capped run is counted by the one definition too.
                let log = SlipLog::new();
                let o = SlideOptions {
                    law: sk(scene, m.r, m.g, rule)?,
                    cycles: 1,
                    max_events,
                    keep_states: false,
                    end_at_crossing: true,
                    cancel: cancel.clone(),
                    observer: Some(log.observer()),
                    ..Default::default()
                };
                let clock = std::time::Instant::now();
                let res = run_condensed(scene, c.clone(), 0.0, &o, Progress::none());
                let seconds = clock.elapsed().as_secs_f64();
                cell.runs[k] = Some(match res {
                    Ok(res) => {
                        let cmp = compare_paper(&res).ok_or_else(|| {
                            crate::Error::input("r, g", "outside the accessible square 0 < r, g < 1")
                        })?;
                        CellRun::Done {
                            crossing: res
                                .run
                                .events
                                .iter()
                                .find(|e| e.ends_cycle())
                                .is_some_and(|e| e.kind == EventKind::Crossing),
                            n: cmp.n_fe,
                            n_long: cmp.n_fe_long,
                            n_advancing: cmp.n_fe_advancing,
                            f_max: cmp.f_max_fe,
                            events: res.run.events.len(),
                            violation: res.run.max_violation,
                            seconds,
                        }
                    }
                    Err(crate::Error::EventCap { x, f_peak_over_n, .. }) => CellRun::Capped {
                        seconds,
                        precursors: log.at_cap(x, &c.x, c.t).n_all(),
                        f_peak: f_peak_over_n / o.law.mu_s(),
                    },
                    // One cell's failure is that cell's result, not the map's.
                    Err(e @ crate::Error::Interrupted) => return Err(e),
                    Err(_) => CellRun::Refused { seconds },
                });
            }
            let k = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
            progress.fraction(k as f64 / model.len() as f64);
            Ok(cell)
        })
        .collect()
}

/// The measured no-precursor boundary of one rule (index into [`RULES`]) in a fig. 5 grid:
/// per r column (ascending), the model's lowest g with n > 0 and the FE's lowest g whose run
/// made a front-advancing precursor. The FE value is None when no finished cell of the
/// column made one, or when a capped or refused cell lies below it (the boundary is then
/// unknown).
pub fn boundary(cells: &[Cell], rule: usize) -> Vec<(f64, Option<f64>, Option<f64>)> {
    let mut rs: Vec<f64> = cells.iter().map(|c| c.r).collect();
    rs.sort_by(f64::total_cmp);
    rs.dedup();
    rs.into_iter()
        .map(|r| {
            let mut col: Vec<&Cell> = cells.iter().filter(|c| c.r == r).collect();
            col.sort_by(|a, b| a.g.total_cmp(&b.g));
            let model = col.iter().find(|c| c.n_model > 0).map(|c| c.g);
            let mut fe = None;
            for c in &col {
                match c.runs[rule].as_ref().map(|run| run.n_advancing()) {
                    Some(Some(0)) => {}
                    Some(Some(_)) => {
                        fe = Some(c.g);
                        break;
                    }
                    _ => break,
                }
            }
            (r, model, fe)
        })
        .collect()
}

/// One rule's FE fig. 5 against the model, over the finished cells.
#[derive(Debug, Clone, Copy)]
pub struct Fig5Stats {
    /// Cells where FE and model agree on "precursors or none".
    pub agree: usize,
    pub done: usize,
    /// FE first cycle's peak over the model's F_max, minus 1: median, least, largest.
    pub f_max_dev: Option<[f64; 3]>,
    /// Front-advancing count over the model's n where n >= 3: median, least, largest.
    pub n_ratio: Option<[f64; 3]>,
    /// The FE's boundary minus the paper's line (1 - r)/2 at the cell's lower edge, over the
    /// columns where it is known: least, largest.
    pub boundary_offset: Option<[f64; 2]>,
    /// Adjacent finished cells of a column where the upper one has fewer front-advancing
    /// precursors than the lower one.
    pub decreases_in_g: usize,
    /// Capped cells: how many, how many of them had already passed the model's F_max, and
    /// their precursors at the cap (median, least, largest).
    pub capped: usize,
    pub capped_above_f_max: usize,
    pub capped_precursors: Option<[f64; 3]>,
    /// Finished cells whose cycle ended at a front crossing, not a whole slip.
    pub crossings: usize,
}

fn spread(mut v: Vec<f64>) -> Option<[f64; 3]> {
    v.sort_by(f64::total_cmp);
    (!v.is_empty()).then(|| [v[v.len() / 2], v[0], v[v.len() - 1]])
}

/// [`Fig5Stats`] of rule `k` (index into [`RULES`]) on a grid of the given resolution.
pub fn fig5_stats(cells: &[Cell], k: usize, resolution: usize) -> Fig5Stats {
    let done: Vec<(&Cell, CellRun)> =
        cells.iter().filter_map(|c| c.runs[k].filter(|r| r.status() == "done").map(|r| (c, r))).collect();
    let capped: Vec<(&Cell, usize, f64)> = cells
        .iter()
        .filter_map(|c| match c.runs[k] {
            Some(CellRun::Capped { precursors, f_peak, .. }) => Some((c, precursors, f_peak)),
            _ => None,
        })
        .collect();
    let half = 0.5 / resolution as f64;
    let offsets: Vec<f64> =
        boundary(cells, k).iter().filter_map(|&(r, _, g)| g.map(|g| g - half - (1.0 - r) / 2.0)).collect();
    let mut decreases = 0;
    let mut by_r: Vec<&(&Cell, CellRun)> = done.iter().collect();
    by_r.sort_by(|a, b| a.0.r.total_cmp(&b.0.r).then(a.0.g.total_cmp(&b.0.g)));
    for w in by_r.windows(2) {
        if w[0].0.r == w[1].0.r && w[1].1.n_advancing() < w[0].1.n_advancing() {
            decreases += 1;
        }
    }
    Fig5Stats {
        agree: done
            .iter()
            .filter(|(c, r)| r.n_advancing().is_some_and(|n| (n > 0) == (c.n_model > 0)))
            .count(),
        done: done.len(),
        f_max_dev: spread(
            done.iter()
                .filter_map(|(c, r)| match r {
                    CellRun::Done { f_max: Some(f), .. } => Some(f / c.f_max_model - 1.0),
                    _ => None,
                })
                .collect(),
        ),
        n_ratio: spread(
            done.iter()
                .filter(|(c, _)| c.n_model >= 3)
                .filter_map(|(c, r)| r.n_advancing().map(|n| n as f64 / c.n_model as f64))
                .collect(),
        ),
        boundary_offset: spread(offsets).map(|[_, lo, hi]| [lo, hi]),
        decreases_in_g: decreases,
        crossings: done.iter().filter(|(_, r)| matches!(r, CellRun::Done { crossing: true, .. })).count(),
        capped: capped.len(),
        capped_above_f_max: capped.iter().filter(|&&(c, _, f)| f > c.f_max_model).count(),
        capped_precursors: spread(capped.iter().map(|&(_, n, _)| n as f64).collect()),
    }
}
