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
        worst_violation: res.run.states.iter().map(|s| s.violations.max()).fold(0.0, f64::max),
        run: res,
    })
}

/// FE fig. 4 for (r, g) on `scene`, one condensation for both rules; each rule's run may
/// be refused on its own (the overdamped relaxation can cycle without settling).
pub fn fig4(scene: &Scene, r: f64, g: f64, cycles: usize) -> Result<Vec<Result<Fig4>>> {
    let c = condense(scene, &SolverOptions::default())?;
    Ok(RULES.iter().map(|&rule| fig4_on(scene, &c, r, g, rule, cycles)).collect())
}

/// One cell of FE fig. 5.
#[derive(Debug, Clone, Copy)]
pub struct Cell {
    pub r: f64,
    pub g: f64,
    pub n_model: usize,
    /// Per rule (order of [`RULES`]): counted precursors, those longer than 5 t, and those
    /// advancing the front by more than 5 t (the mesh-stable count, [`crate::studies::slide::ADVANCE_T`]); None where
    /// the FE run refused (a numerical refusal, or the event cap).
    pub n_fe: [Option<usize>; 2],
    pub n_fe_long: [Option<usize>; 2],
    pub n_fe_advancing: [Option<usize>; 2],
}

/// n(r, g) at the centres of a `resolution` x `resolution` grid over (0,1)^2 (as
/// [`crate::precursors::n_map`], g fastest), FE for the `rules` given (the others stay None),
/// cells in parallel, the interface condensed once; `progress` is called after each cell.
pub fn fig5(
    scene: &Scene,
    resolution: usize,
    rules: &[Rule],
    progress: &(dyn Fn() + Sync),
) -> Result<Vec<Cell>> {
    let model = crate::precursors::n_map(resolution)?;
    let c = condense(scene, &SolverOptions::default())?;
    model
        .par_iter()
        .map(|m| {
            let mut cell = Cell {
                r: m.r,
                g: m.g,
                n_model: m.n,
                n_fe: [None; 2],
                n_fe_long: [None; 2],
                n_fe_advancing: [None; 2],
            };
            for (k, &rule) in RULES.iter().enumerate().filter(|(_, r)| rules.contains(r)) {
                let o = opts(scene, m.r, m.g, rule, 1)?;
                if let Some(cmp) =
                    run_condensed(scene, c.clone(), 0.0, &o, &|_| {}).ok().and_then(|r| compare_paper(&r))
                {
                    cell.n_fe[k] = Some(cmp.n_fe);
                    cell.n_fe_long[k] = Some(cmp.n_fe_long);
                    cell.n_fe_advancing[k] = Some(cmp.n_fe_advancing);
                }
            }
            progress();
            Ok(cell)
        })
        .collect()
}
