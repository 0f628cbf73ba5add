//! Precursors from the frictional FE itself (issue 18): the paper's fig. 4 and fig. 5
//! recomputed on a scene, the interface condensed once and reused for every rule and cell.
//!
//! What counts as a precursor: an event classified `precursor` (slip nucleated at the
//! trailing edge and arrested inside the contact) before the first `sliding` event. Edge
//! pre-slip, tip advances of an arrested front, creep, open/close are not counted;
//! `nucleation` events mark an instability's onset and are not counted on their own.
//! `n_long` also drops precursors no longer than 5 t (edge-zone events).
//!
//! Not done yet: the height-of-drive study and the assumption table (issue 18); the corners
//! are `studies::edges`, D_c is `slide --law slip-weakening`.

use crate::error::Result;
use crate::interface::condense::{condense, Condensed};
use crate::interface::law::{Law, Rule};
use crate::linalg::solve::SolverOptions;
use crate::scene::Scene;
use crate::studies::slide::{
    coefficients_from_rg, compare_paper, run_condensed, PaperComparison, SlideOptions, SlideResult,
};
use rayon::prelude::*;

/// The two event rules compared in both figures.
pub const RULES: [Rule; 2] = [Rule::Paper, Rule::Overdamped];

/// One rule's FE fig. 4 next to the analytic iteration (forces in units of mu_s N, x in L).
#[derive(Debug, Clone)]
pub struct Fig4 {
    pub rule: Rule,
    pub cmp: PaperComparison,
    /// Arrest positions x_i/L of the counted precursors, in order.
    pub x_fe: Vec<f64>,
    /// Analytic x_1..x_n.
    pub x_model: Vec<f64>,
    /// Stick-slip peaks F/(mu_s N) of the `sliding` events.
    pub peaks: Vec<f64>,
    /// Worst contact/friction violation over all states (Violations::max).
    pub worst_violation: f64,
    /// The whole run (events, states), for the report.
    pub run: SlideResult,
}

fn opts(scene: &Scene, r: f64, g: f64, rule: Rule, cycles: usize) -> Result<SlideOptions> {
    let (ms, md) = coefficients_from_rg(scene, r, g)?;
    Ok(SlideOptions { law: Law::static_kinetic(ms, md, rule)?, cycles, ..Default::default() })
}

fn fig4_on(scene: &Scene, c: &Condensed, r: f64, g: f64, rule: Rule, cycles: usize) -> Result<Fig4> {
    let o = opts(scene, r, g, rule, cycles)?;
    let res = run_condensed(scene, c.clone(), 0.0, &o, &|_| {})?;
    let cmp = compare_paper(&res)
        .ok_or_else(|| crate::Error::input("r, g", "outside the accessible square 0 < r, g < 1"))?;
    let p = crate::precursors::Params::new(r, g)?;
    let ev = crate::precursors::simulate(&p, cmp.n.max(1));
    let evs = &res.run.events;
    let first = evs.iter().position(|e| e.kind == "sliding").unwrap_or(evs.len());
    let cx = &res.condensed;
    Ok(Fig4 {
        rule,
        cmp,
        x_fe: evs[..first]
            .iter()
            .filter(|e| e.kind == "precursor")
            .filter_map(|e| e.region.map(|(_, b)| cx.x[b] / cx.l))
            .collect(),
        x_model: ev.iter().take(cmp.n).map(|e| e.x).collect(),
        peaks: evs.iter().filter(|e| e.kind == "sliding").map(|e| e.f / (o.law.mu_s() * o.n_force)).collect(),
        worst_violation: res.run.max_violation,
        run: res,
    })
}

/// FE fig. 4 for (r, g) on `scene`, one condensation for both rules; each rule's run may
/// be refused on its own (the overdamped relaxation can cycle without settling).
pub fn fig4(scene: &Scene, r: f64, g: f64, cycles: usize) -> Result<Vec<Result<Fig4>>> {
    let c = condense(scene, &SolverOptions::default())?;
    Ok(RULES.iter().map(|&rule| fig4_on(scene, &c, r, g, rule, cycles)).collect())
}

/// One rule's run in one cell of FE fig. 5.
#[derive(Debug, Clone, Copy)]
pub enum CellRun {
    /// Reached the first whole-interface slip. Counts as in [`PaperComparison`]; the first
    /// slip's peak F/(mu_s N); the events, the worst violation (N/n) and the wall time, s.
    Done {
        n: usize,
        n_long: usize,
        n_advancing: usize,
        f_max: Option<f64>,
        events: usize,
        violation: f64,
        seconds: f64,
    },
    /// Needed more than the cap of events before the first whole slip.
    Capped { seconds: f64 },
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
            CellRun::Done { seconds, .. } | CellRun::Capped { seconds } | CellRun::Refused { seconds } => {
                seconds
            }
        }
    }
    /// The mesh-stable count (front-advancing precursors) of a finished run.
    pub fn n_advancing(&self) -> Option<usize> {
        match *self {
            CellRun::Done { n_advancing, .. } => Some(n_advancing),
            _ => None,
        }
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
/// `max_events` events (then [`CellRun::Capped`]); `progress` is called after each cell.
pub fn fig5(
    scene: &Scene,
    resolution: usize,
    rules: &[Rule],
    max_events: usize,
    progress: &(dyn Fn() + Sync),
) -> Result<Vec<Cell>> {
    let model = crate::precursors::n_map(resolution)?;
    let c = condense(scene, &SolverOptions::default())?;
    model
        .par_iter()
        .map(|m| {
            let p = crate::precursors::Params::new(m.r, m.g)?;
            let mut cell = Cell { r: m.r, g: m.g, n_model: m.n, f_max_model: p.f_max(), runs: [None; 2] };
            for (k, &rule) in RULES.iter().enumerate().filter(|(_, r)| rules.contains(r)) {
                let o = SlideOptions { max_events, keep_states: false, ..opts(scene, m.r, m.g, rule, 1)? };
                let clock = std::time::Instant::now();
                let res = run_condensed(scene, c.clone(), 0.0, &o, &|_| {});
                let seconds = clock.elapsed().as_secs_f64();
                cell.runs[k] = Some(match res {
                    Ok(res) => {
                        let cmp = compare_paper(&res).ok_or_else(|| {
                            crate::Error::input("r, g", "outside the accessible square 0 < r, g < 1")
                        })?;
                        CellRun::Done {
                            n: cmp.n_fe,
                            n_long: cmp.n_fe_long,
                            n_advancing: cmp.n_fe_advancing,
                            f_max: cmp.f_max_fe,
                            events: res.run.events.len(),
                            violation: res.run.max_violation,
                            seconds,
                        }
                    }
                    Err(crate::Error::EventCap { .. }) => CellRun::Capped { seconds },
                    Err(crate::Error::Untrustworthy { .. } | crate::Error::Singular { .. }) => {
                        CellRun::Refused { seconds }
                    }
                    Err(e) => return Err(e),
                });
            }
            progress();
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
