//! The scene-level frictional run: Scene -> condensed interface -> loading history (N, then
//! X at height H) -> events, states and classified events, as plain data.

use crate::error::{Error, Result};
use crate::interface::condense::{condense, Condensed};
use crate::interface::events::{run as run_events, NodeState, Problem, Run};
use crate::interface::law::Law;
use crate::linalg::solve::SolverOptions;
use crate::scene::Scene;
use std::time::Instant;

#[derive(Debug, Clone)]
pub struct SlideOptions {
    pub law: Law,
    /// Normal force, N/m.
    pub n_force: f64,
    pub x_max: Option<f64>,
    pub cycles: usize,
    pub max_events: usize,
    pub creep_fraction: f64,
}

impl Default for SlideOptions {
    fn default() -> Self {
        let p = Problem::default();
        Self {
            law: p.law,
            n_force: 1.0,
            x_max: None,
            cycles: p.cycles,
            max_events: p.max_events,
            creep_fraction: p.creep_fraction,
        }
    }
}

#[derive(Debug, Clone)]
pub struct SlideResult {
    pub scene: Scene,
    pub options: SlideOptions,
    pub condensed: Condensed,
    pub run: Run,
    /// Wall time of the condensation and of the event loop, s.
    pub condense_s: f64,
    pub events_s: f64,
}

impl SlideResult {
    /// Mean pressure N/L, Pa.
    pub fn p_mean(&self) -> f64 {
        self.options.n_force / self.condensed.l
    }

    /// The elastic force F^c = k_bonded X of a state, N/m.
    pub fn f_c(&self, x: f64) -> f64 {
        self.run.k_bonded * x
    }
}

/// Condenses and runs.
pub fn run(scene: &Scene, o: &SlideOptions, progress: &dyn Fn(f64)) -> Result<SlideResult> {
    let clock = Instant::now();
    let c = condense(scene, &SolverOptions::default())?;
    let condense_s = clock.elapsed().as_secs_f64();
    run_condensed(scene, c, condense_s, o, progress)
}

/// Runs on an existing condensation of `scene`'s mesh and material (any H, law, N).
pub fn run_condensed(
    scene: &Scene,
    c: Condensed,
    condense_s: f64,
    o: &SlideOptions,
    progress: &dyn Fn(f64),
) -> Result<SlideResult> {
    let clock = Instant::now();
    let s = c.at_height(scene.loading.height);
    let pb = Problem {
        n_force: o.n_force,
        law: o.law,
        x_max: o.x_max,
        cycles: o.cycles,
        max_events: o.max_events,
        creep_fraction: o.creep_fraction,
    };
    if o.cycles == 0 && o.x_max.is_none() && matches!(o.law, Law::StaticKinetic { .. }) {
        return Err(Error::input("cycles", "need at least one stick-slip cycle, or an x-max"));
    }
    let run = run_events(&s, c.n, &pb, progress)?;
    Ok(SlideResult {
        scene: scene.clone(),
        options: o.clone(),
        condensed: c,
        run,
        condense_s,
        events_s: clock.elapsed().as_secs_f64(),
    })
}

/// Coefficients from the paper's (r, g) at the scene's H/L: mu_d = g L/(6 H), mu_s = mu_d/r.
pub fn coefficients_from_rg(scene: &Scene, r: f64, g: f64) -> Result<(f64, f64)> {
    let p = crate::precursors::Params::new(r, g)?;
    let mu_d = p.g() * scene.block.length / (6.0 * scene.loading.height);
    Ok((mu_d / p.r(), mu_d))
}

/// Front of the slip zone grown from the trailing edge (x = -L/2) of a state: x/L midway
/// between the last slipping node of the leading run from node 0 and the next node; None
/// when node 0 does not slip.
pub fn trailing_front(res: &SlideResult, state: usize) -> Option<f64> {
    let st = &res.run.states[state];
    let c = &res.condensed;
    if !matches!(st.states[0], NodeState::Slip(_)) {
        return None;
    }
    let k = st.states.iter().position(|s| !matches!(s, NodeState::Slip(_))).unwrap_or(c.n);
    if k >= c.n {
        return Some(0.5);
    }
    Some(0.5 * (c.x[k - 1] + c.x[k]) / c.l)
}
