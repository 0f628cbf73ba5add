//! The scene-level frictional run: Scene -> condensed interface -> loading history (N, then
//! X at height H) -> events, states and classified events, as plain data.

use crate::error::{Error, Result};
use crate::fem::problem::{solve, LoadCase};
use crate::interface::condense::{boundary_model, condense, Condensed};
use crate::interface::events::EventKind;
use crate::interface::events::{run as run_events, NodeState, Problem, Run};
use crate::interface::law::Law;
use crate::linalg::solve::SolverOptions;
use crate::scene::{Scene, SceneModel};
use std::time::Instant;

#[derive(Debug, Clone)]
pub struct SlideOptions {
    pub law: Law,
    /// Normal force, N/m.
    pub n_force: f64,
    pub x_max: Option<f64>,
    pub cycles: usize,
    pub max_events: usize,
    /// See [`Problem::keep_states`].
    pub keep_states: bool,
    pub creep_fraction: f64,
    /// See [`Problem::end_at_crossing`].
    pub end_at_crossing: bool,
    /// See [`Problem::newton`].
    pub newton: bool,
    /// See [`Problem::cancel`].
    pub cancel: crate::Cancel,
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
            keep_states: p.keep_states,
            creep_fraction: p.creep_fraction,
            end_at_crossing: p.end_at_crossing,
            newton: p.newton,
            cancel: p.cancel,
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
        keep_states: o.keep_states,
        creep_fraction: o.creep_fraction,
        end_at_crossing: o.end_at_crossing,
        newton: o.newton,
        cancel: o.cancel.clone(),
    };
    if o.cycles == 0 && o.x_max.is_none() && o.law.weakens() {
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

/// Displacements of the whole block and plate in the given states (indices into
/// `res.run.states`): every interface and plate DOF prescribed at the state's value, one
/// factorisation, one right-hand side per state. Returns the model they live on (the plate's
/// U is referred to the block top there) and one full displacement vector per state, m.
pub fn state_displacements(
    res: &SlideResult,
    states: &[usize],
    opts: &SolverOptions,
) -> Result<(SceneModel, Vec<Vec<f64>>)> {
    let (sm, bdofs) = boundary_model(&res.scene)?;
    let n = res.condensed.n;
    if sm.interface.len() != n {
        return Err(Error::input("scene", "the result's interface does not match its scene's mesh"));
    }
    let nf = sm.constraints.n_fixed();
    let slots: Vec<usize> = bdofs.iter().map(|&d| sm.constraints.fixed_slot(d).unwrap()).collect();
    // The states' U is at height H; the model's at the block top: U0 = U_H + (H - t) theta.
    let arm = res.scene.loading.height - res.scene.block.thickness;
    let cases = states
        .iter()
        .map(|&k| {
            let st = res.run.states.get(k).ok_or_else(|| {
                Error::input("state", format!("{k} is past the last state ({})", res.run.states.len()))
            })?;
            let b = st.u.iter().chain(&st.gap).copied().chain([st.x + arm * st.tilt, st.v, st.tilt]);
            let mut g = vec![0.0; nf];
            for (slot, v) in slots.iter().zip(b) {
                g[*slot] = v;
            }
            Ok(LoadCase { prescribed: g, forces: vec![] })
        })
        .collect::<Result<Vec<_>>>()?;
    let sol = solve(&sm.model(), &sm.constraints, &cases, opts, "")?;
    Ok((sm, sol.u))
}

/// Coefficients from the paper's (r, g) at the scene's H/L: mu_d = g L/(6 H), mu_s = mu_d/r.
pub fn coefficients_from_rg(scene: &Scene, r: f64, g: f64) -> Result<(f64, f64)> {
    let p = crate::precursors::Params::new(r, g)?;
    let mu_d = p.g() * scene.block.length / (6.0 * scene.loading.height);
    Ok((mu_d / p.r(), mu_d))
}

/// Front of the slip zone grown from the trailing edge (x = -L/2) of a state: x/L midway
/// between the last slipping node of the run that starts at the first contact node (open
/// trailing nodes are skipped) and the next node; None when that first contact node sticks.
pub fn trailing_front(res: &SlideResult, state: usize) -> Option<f64> {
    let st = &res.run.states[state];
    let c = &res.condensed;
    let c0 = st.states.iter().position(|s| *s != NodeState::Open)?;
    if !matches!(st.states[c0], NodeState::Slip(_)) {
        return None;
    }
    let k = (c0..c.n).find(|&k| !matches!(st.states[k], NodeState::Slip(_))).unwrap_or(c.n);
    if k >= c.n {
        return Some(0.5);
    }
    Some(0.5 * (c.x[k - 1] + c.x[k]) / c.l)
}

/// The coulomb slip front against the thin-layer closed form
/// F/(mu N) = 1/(1 + g (1/2 - x_s/L)^2): offsets (x_s,FE - x_s,closed form)/t over the drive
/// states whose closed-form front lies in |x_s| < 0.3 L (away from both edge zones).
#[derive(Debug, Clone, Copy)]
pub struct FrontOffset {
    pub mean_t: f64,
    pub min_t: f64,
    pub max_t: f64,
    pub samples: usize,
}

pub fn front_offset(res: &SlideResult) -> Option<FrontOffset> {
    let Law::Coulomb { mu } = res.options.law else { return None };
    let (l, t) = (res.condensed.l, res.condensed.t);
    let g = 6.0 * mu * res.scene.loading.height / l;
    let mut d = Vec::new();
    for (k, st) in res.run.states.iter().enumerate() {
        if st.phase != crate::interface::events::Phase::Drive || mu == 0.0 {
            continue;
        }
        let phi = st.f / (mu * res.options.n_force);
        if let (Some(xf), Some(xc)) = (trailing_front(res, k), crate::analytical::partial_slip::front(g, phi))
        {
            if xc.abs() < 0.3 {
                d.push((xf - xc) * l / t);
            }
        }
    }
    if d.is_empty() {
        return None;
    }
    Some(FrontOffset {
        mean_t: d.iter().sum::<f64>() / d.len() as f64,
        min_t: d.iter().cloned().fold(f64::INFINITY, f64::min),
        max_t: d.iter().cloned().fold(f64::NEG_INFINITY, f64::max),
        samples: d.len(),
    })
}

/// The static-kinetic run against the paper's analytic iteration for the same (r, g).
#[derive(Debug, Clone, Copy)]
pub struct PaperComparison {
    pub r: f64,
    pub g: f64,
    /// Analytic: number of precursors, F_1, x_1 (dimensionless, F in units of mu_s N), F_max.
    pub n: usize,
    pub f1: f64,
    pub x1: f64,
    pub f_max: f64,
    /// FE: precursors (events from the trailing edge) before the first whole-interface slip,
    /// those longer than 5 t, those that advance the front (see [`ADVANCE_T`]), the first long
    /// one (F, arrest x/L), and the last stick-slip peak.
    pub n_fe: usize,
    pub n_fe_long: usize,
    pub n_fe_advancing: usize,
    pub f1_fe: Option<f64>,
    pub x1_fe: Option<f64>,
    pub f_max_fe: Option<f64>,
}

/// A precursor counts as advancing the front when its arrest point lies more than this many t
/// beyond the farthest arrest point of the precursors before it (the first: when it is longer
/// than this): renucleations that stop within the edge zone or a few elements of the previous
/// front are not the paper's precursors, and their number grows with refinement.
pub const ADVANCE_T: f64 = 5.0;

pub fn compare_paper(res: &SlideResult) -> Option<PaperComparison> {
    if !res.options.law.weakens() {
        return None;
    }
    let (mu_s, mu_d) = (res.options.law.mu_s(), res.options.law.mu_d());
    let c = &res.condensed;
    let (r, g) = (mu_d / mu_s, 6.0 * mu_d * res.scene.loading.height / c.l);
    let p = crate::precursors::Params::new(r, g).ok()?;
    let ev = crate::precursors::simulate(&p, 1);
    let k = mu_s * res.options.n_force;
    let evs = &res.run.events;
    let first_slide = evs.iter().position(|e| e.ends_cycle()).unwrap_or(evs.len());
    let pre: Vec<_> = evs[..first_slide].iter().filter(|e| e.kind == EventKind::Precursor).collect();
    let long: Vec<_> =
        pre.iter().filter(|e| e.region.is_some_and(|(a, b)| c.x[b] - c.x[a] > ADVANCE_T * c.t)).collect();
    let mut front = c.x[0];
    let mut n_fe_advancing = 0;
    for e in &pre {
        if let Some((_, b)) = e.region {
            if c.x[b] > front + ADVANCE_T * c.t {
                n_fe_advancing += 1;
                front = c.x[b];
            }
        }
    }
    Some(PaperComparison {
        r,
        g,
        n: crate::precursors::n_precursors(&p).ok()?,
        f1: ev[0].f,
        x1: ev[0].x,
        f_max: p.f_max(),
        n_fe: pre.len(),
        n_fe_long: long.len(),
        n_fe_advancing,
        f1_fe: long.first().map(|e| e.f / k),
        x1_fe: long.first().and_then(|e| e.region).map(|(_, b)| c.x[b] / c.l),
        f_max_fe: evs.iter().rfind(|e| e.ends_cycle()).map(|e| e.f / k),
    })
}
