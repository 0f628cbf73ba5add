//! The scene-level frictional run: Scene -> condensed interface -> loading history (N, then
//! X at height H) -> events, states and classified events, as plain data.

use crate::error::{Error, Result};
use crate::fem::problem::{solve, LoadCase};
use crate::interface::banded::BandedOperator;
use crate::interface::condense::{boundary_model, condense_rig, Condensed};
use crate::interface::events::{self, run_with, Operator, OperatorRef, Problem, Run};
use crate::law::Law;
use crate::linalg::solve::SolverOptions;
use crate::precursors::definition::{self, Precursors, Slip};
use crate::precursors::{PAPER_G, PAPER_R};
use crate::progress::Progress;
use crate::scene::{Scene, SceneModel};
use std::time::Instant;

pub use super::slide_arrays::{contact_area_over_a0, EventColumns, StateField};

/// The options of a frictional run: the event solver's [`Problem`] itself (one options type).
pub type SlideOptions = Problem;

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

/// D_c below this fraction of the elastic slip scale tau t/G is refused: the drive steps X by
/// D_c/20 of slip of the fastest slipping node, so a cycle over X ~ tau t/G (the bonded
/// block's compliance times its peak force) can take ~20 (tau t/G)/D_c steps: 2e7 here.
pub const DC_MIN_OVER_SLIP_SCALE: f64 = 1e-6;

/// D_c whose nucleation length G D_c/((mu_s - mu_d) p) exceeds this many block lengths is
/// refused: no patch of the block can weaken into an instability, the interface slides
/// stably at mu_s and only a slip of order D_c would end the run.
pub const LC_MAX_OVER_LENGTH: f64 = 100.0;

/// The default event cap ([`Problem`]'s).
pub const DEFAULT_MAX_EVENTS: usize = 50_000;

/// The defaults of `tribofe slide` and `tribofe.slide` ([`Problem`]'s where it has them):
/// the law and rule by name, the normal force N (N/m) and the quasi-static run's cycles.
pub const DEFAULT_LAW: &str = "coulomb";
pub const DEFAULT_RULE: &str = "paper";
pub const DEFAULT_N_FORCE: f64 = 1.0;
pub const DEFAULT_CYCLES: usize = 10;

/// Largest --cycles: each cycle is at least one event, and the event cap bounds the run.
fn cycles_bound(o: &SlideOptions) -> usize {
    o.max_events
}

/// Refuses, before any work, the options that make a frictional run degenerate or
/// unbounded, naming the flag and the reason: a coulomb mu = 0 (the whole interface slides
/// as soon as it is loaded: nothing to compute, and no mu_s N to scale the results by), D_c outside the range the mesh and the block
/// represent ([`DC_MIN_OVER_SLIP_SCALE`], [`LC_MAX_OVER_LENGTH`]), more cycles than the
/// event cap allows, no event cap.
pub fn check_options(scene: &Scene, o: &SlideOptions) -> Result<()> {
    // N, X_max: the event solver's own checks, here so that every mode (quasi-static,
    // --dynamics, the constant-velocity drive) refuses them before any work.
    events::check(o)?;
    // Every mode stops once `cycles` cycles have ended (the dynamic one under Coulomb too):
    // 0 would end the run at its first event, whatever X_max.
    if o.cycles == 0 {
        return Err(Error::input(
            "cycles",
            "0: a run ends after this many cycles (or at x-max, if sooner); give at least 1",
        ));
    }
    if o.max_events == 0 {
        return Err(Error::input("--max-events", "0: a run records at least the normal load"));
    }
    if o.law.weakens() && o.cycles > cycles_bound(o) {
        return Err(Error::input(
            "--cycles",
            format!(
                "{}: above --max-events = {} (each stick-slip cycle takes at least one event); lower --cycles or raise --max-events",
                o.cycles,
                o.max_events
            ),
        ));
    }
    if scene.mesh.file.is_none() {
        // Interface nodes of the structured mesh (the run checks again with the exact count,
        // and for a mesh file).
        let n = scene.estimate_nx() + 1.0;
        if o.keep_states || o.operator == Operator::Dense {
            // The dense condensed system first: it is the size that matters most (names --h).
            crate::scene::limits::check_interface(n as usize)?;
        }
        check_records(o, n as usize, "about ")?;
    }
    check_n_force(scene, o.n_force)?;
    if !scene.loading.rig.is_top_plate() && o.operator == Operator::Banded {
        return Err(Error::input(
            "--operator",
            "banded: the banded operator borders the top plate's three DOFs only; the side push runs on --operator dense",
        ));
    }
    if let Some(x) = o.x_max {
        if x > scene.block.length {
            return Err(Error::input(
                "--x-max",
                format!(
                    "{x:e} m is beyond the block's length L = {} m: the interface model is one of small displacements; give X <= L",
                    scene.block.length
                ),
            ));
        }
    }
    if let Law::Coulomb { mu } = o.law {
        // Every result is in units of mu_s N (F/(mu_s N), fig. 4, the precursor heights): 0
        // made them infinite (Python's curve_F_over_mu_s_N), with or without --x-max.
        if mu == 0.0 {
            return Err(Error::input(
                "--mu",
                "0: every result of slide is in units of mu_s N (F/(mu_s N), fig. 4), which is 0 without friction, and without friction the whole interface slides as soon as it is loaded: there are no events to compute; give mu > 0 (a nearly frictionless interface: a small mu such as 1e-3)",
            ));
        }
    }
    if let Law::SlipWeakening { mu_s, mu_d, dc } = o.law {
        let b = &scene.block;
        let g = b.young / (2.0 * (1.0 + b.poisson));
        let p = o.n_force / b.length;
        let slip = mu_s * p * b.thickness / g; // tau t / G at the static peak
        let lc = |d: f64| g * d / ((mu_s - mu_d) * p);
        let (lo, hi) = (DC_MIN_OVER_SLIP_SCALE * slip, LC_MAX_OVER_LENGTH * b.length * (mu_s - mu_d) * p / g);
        let at = format!(
            "the elastic slip scale tau t/G = {slip:.3e} m (tau = mu_s N/L, G = E/(2(1 + nu))), h = {:.3e} m; D_c = {dc:.3e} m gives a nucleation length G D_c/((mu_s - mu_d) N/L) of {:.3e} h",
            scene.mesh.h,
            lc(dc) / scene.mesh.h
        );
        if dc < lo {
            return Err(Error::input(
                "--dc",
                format!(
                    "{dc:e} m is below {lo:.3e} m = {DC_MIN_OVER_SLIP_SCALE:e} tau t/G: the slip-rate step control (D_c/20 of slip per step) would need up to ~{:.0e} steps per cycle; {at}; this is the static-kinetic limit: use --law static-kinetic, or D_c >= {lo:.1e} m",
                    20.0 * slip / dc
                ),
            ));
        }
        if dc > hi {
            return Err(Error::input(
                "--dc",
                format!(
                    "{dc:e} m is above {hi:.3e} m, where the nucleation length reaches {LC_MAX_OVER_LENGTH} block lengths: no patch can weaken into an instability and the interface would slide stably at mu_s until a slip of order D_c; {at}; use D_c <= {hi:.1e} m (or --law coulomb --mu mu_s)"
                ),
            ));
        }
    }
    Ok(())
}

/// Refuses a normal force N (N/m) the model cannot represent, naming it `N` (the command's
/// `--n-force`): not a positive number, or a mean pressure N/L outside [1e-100 N/m over L, E].
/// Called by [`check_options`] and by whatever derives a scale from N before it
/// ([`crate::studies::dynamic_slide::physics`]).
pub fn check_n_force(scene: &Scene, n_force: f64) -> Result<()> {
    crate::error::positive("N", n_force)?;
    // The model is linear and of small strains: a mean pressure N/L above E is a strain of
    // order one; below 1e-100 N/m the displacements underflow into subnormals (N = 1e-308
    // gave X = 4.9e-314 m and violations of 8 % with exit 0).
    let (p, e) = (n_force / scene.block.length, scene.block.young);
    if n_force < 1e-100 || p > e {
        return Err(Error::input(
            "--n-force",
            format!(
                "{n_force:e} N/m: the mean pressure N/L = {p:e} Pa must lie between 1e-100 N/m over L and Young's modulus E = {e:e} Pa (the interface model is linear and of small strains)"
            ),
        ));
    }
    Ok(())
}

/// The events whose records fit in half the memory this process may use: per event its
/// [`events::Event`] and [`events::Summary`] always, and its [`events::State`] (T, P, u, gap
/// and state of each of the `n` nodes) when `keep_states` ([`events::bytes_per_event`]).
fn records_fit(o: &SlideOptions, n: usize) -> usize {
    let per = events::bytes_per_event(n, o.keep_states);
    (0.5 * crate::scene::limits::memory_bytes().0 / per) as usize
}

/// Refuses a run whose records could not fit in any case: fewer events fit in half the memory
/// than its normal load and cycles need. A larger cap (the default 50 000) is not refused for
/// room it may never use: the run stops when its records fill that half ([`records_capped`]).
/// A cap raised above the default ([`DEFAULT_MAX_EVENTS`]) is a request for that many
/// events, refused up front when they cannot fit.
fn check_records(o: &SlideOptions, n: usize, about: &str) -> Result<()> {
    let per = events::bytes_per_event(n, o.keep_states);
    if o.max_events > DEFAULT_MAX_EVENTS {
        let what = format!(
            "keeping up to {} {} of {about}{n} interface nodes ({per:.0} bytes an event)",
            o.max_events,
            if o.keep_states { "states" } else { "event summaries" }
        );
        let hint = format!(
            "lower --max-events (at most the default {DEFAULT_MAX_EVENTS} is capped by the memory instead), or keep summaries only with `slide --states none`"
        );
        crate::scene::limits::check_bytes(o.max_events as f64 * per, "--max-events", &what, &hint)?;
    }
    let least = if o.law.weakens() { o.cycles + 1 } else { 2 }.min(o.max_events);
    let what = format!(
        "recording the {least} events this run needs at least ({}) of {about}{n} interface nodes ({per:.0} bytes an event)",
        if o.keep_states { "with their states" } else { "summaries only" }
    );
    let hint = if o.keep_states {
        "lower --cycles, or keep no states (`slide --states none`: no states.csv)"
    } else {
        "lower --cycles"
    };
    crate::scene::limits::check_bytes(least as f64 * per, "--max-events", &what, hint)
}

/// The run on `o` with its event cap lowered to the records that fit ([`records_fit`]); that
/// cap met is refused naming the memory, not --max-events.
fn records_capped(o: &SlideOptions, n: usize, run: impl FnOnce(&SlideOptions) -> Result<Run>) -> Result<Run> {
    let fit = records_fit(o, n);
    if fit >= o.max_events {
        return run(o);
    }
    let capped = SlideOptions { max_events: fit.max(1), ..o.clone() };
    run(&capped).map_err(|e| match e {
        Error::EventCap { cap, x, f_over_n, .. } if cap == capped.max_events => {
            let (mem, source) = crate::scene::limits::memory_bytes();
            Error::input(
                "--max-events",
                format!(
                    "the records of {cap} events ({:.0} bytes each) fill half of {source} ({}) at X = {x:.6e} m, F/N = {f_over_n:.6}, below the cap of {}; keep no states (`slide --states none`), lower --x-max or --cycles, or run with more memory",
                    events::bytes_per_event(n, o.keep_states),
                    crate::scene::limits::bytes_text(mem),
                    o.max_events
                ),
            )
        }
        e => e,
    })
}

/// Condenses and runs; `progress` gets the fraction of the drive done at each event. With
/// [`Operator::Banded`] it builds the banded operator instead of the condensation; the
/// result's `condensed` then has an empty `s` and reports the block stiffness' symmetry and
/// rigid-motion checks.
pub fn run(scene: &Scene, o: &SlideOptions, progress: Progress) -> Result<SlideResult> {
    check_options(scene, o)?;
    let clock = Instant::now();
    if o.operator == Operator::Banded {
        let op = BandedOperator::new(scene, scene.loading.height)?;
        let c = Condensed::of_banded(scene, &op);
        return run_banded(scene, &op, c, clock.elapsed().as_secs_f64(), o, progress);
    }
    let c = condense_rig(scene, &SolverOptions::default())?;
    let condense_s = clock.elapsed().as_secs_f64();
    run_condensed(scene, c, condense_s, o, progress)
}

/// Runs on an existing condensation of `scene`'s mesh and material (any H, law, N).
pub fn run_condensed(
    scene: &Scene,
    c: Condensed,
    condense_s: f64,
    o: &SlideOptions,
    progress: Progress,
) -> Result<SlideResult> {
    if o.operator == Operator::Banded {
        // The condensation's S is not used: the banded operator is built from the scene.
        let clock = Instant::now();
        let op = BandedOperator::new(scene, scene.loading.height)?;
        let built = condense_s + clock.elapsed().as_secs_f64();
        return run_banded(scene, &op, c, built, o, progress);
    }
    if c.s.len() != c.dim() * c.dim() {
        return Err(Error::input(
            "condensed system",
            "holds no dense S (built for the banded operator): run it through studies::slide::run",
        ));
    }
    let s = c.at_height(scene.loading.height);
    let border = c.border.clone();
    run_on(scene, OperatorRef::Dense(&s, &border), c, condense_s, o, progress)
}

/// The run on the banded operator; `c` carries the interface's positions and widths (its S,
/// if any, is not used).
fn run_banded(
    scene: &Scene,
    op: &BandedOperator,
    c: Condensed,
    condense_s: f64,
    o: &SlideOptions,
    progress: Progress,
) -> Result<SlideResult> {
    if op.n != c.n {
        return Err(Error::input("scene", "the condensed interface does not match the scene's mesh"));
    }
    run_on(scene, OperatorRef::Banded(op), c, condense_s, o, progress)
}

/// The checks every run makes before its first event, then the event solver on `op`.
fn run_on(
    scene: &Scene,
    op: OperatorRef,
    c: Condensed,
    condense_s: f64,
    o: &SlideOptions,
    progress: Progress,
) -> Result<SlideResult> {
    let clock = Instant::now();
    check_options(scene, o)?;
    check_records(o, c.n, "")?;
    let run = records_capped(o, c.n, |o| run_with(op, c.n, o, &|x| progress.fraction(x)))?;
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
/// Needs a run that kept its states ([`Problem::keep_states`]).
pub fn state_displacements(
    res: &SlideResult,
    states: &[usize],
    opts: &SolverOptions,
) -> Result<(SceneModel, Vec<Vec<f64>>)> {
    if !res.run.has_all_states() {
        return Err(Error::input(
            "state",
            "the run kept only its last state (keep_states false): the fields of an event need a run that keeps its states",
        ));
    }
    if !res.scene.loading.rig.is_top_plate() {
        return Err(Error::input(
            "--fields",
            "the block's fields of a side-pushed run are not written yet (the states keep the top plate's U, V, theta only)",
        ));
    }
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
    if scene.arm() == 0.0 {
        return Err(Error::input(
            "--g",
            "at --height 0 g = 6 mu_d H/L is 0 whatever the coefficients, so (r, g) cannot set them: give --mu-s and --mu-d (or neither, for the paper's)",
        ));
    }
    if p.g() == 0.0 {
        return Err(Error::input(
            "--g",
            "g = 6 mu_d H/L = 0 is the control case without torque, H = 0: give --height 0 (with --mu-s and --mu-d, or neither for the paper's)",
        ));
    }
    let mu_d = p.g() * scene.block.length / (6.0 * scene.arm());
    Ok((mu_d / p.r(), mu_d))
}

/// The default coefficients: the paper's (r, g) = (0.9, 0.35) at the scene's H/L; at H = 0
/// (the control case, where g is 0 whatever the coefficients) and under the side push (whose
/// push height is no plate's H: g there would put mu_d = 2.9 under a pusher at 0.02 L) at the
/// paper's H/L = 0.1, so they keep the paper's friction, mu_s = 0.648, mu_d = 0.583.
pub fn default_coefficients(scene: &Scene) -> Result<(f64, f64)> {
    if scene.arm() == 0.0 || !scene.loading.rig.is_top_plate() {
        let paper = Scene::default();
        let mu_d = PAPER_G * paper.block.length / (6.0 * paper.loading.height);
        return Ok((mu_d / PAPER_R, mu_d));
    }
    coefficients_from_rg(scene, PAPER_R, PAPER_G)
}

/// Front of the slip zone grown from the trailing edge (x = -L/2) of a state: x/L midway
/// between the last slipping node of the run that starts at the first contact node (open
/// trailing nodes are skipped) and the next node; None when that first contact node sticks.
/// Read off the state's [`events::Summary`], so states need not be kept.
pub fn trailing_front(res: &SlideResult, state: usize) -> Option<f64> {
    let st = &res.run.summaries[state];
    let c = &res.condensed;
    let c0 = st.first_contact?;
    // The run of slipping nodes that starts at the first contact node, if it slips.
    let &(_, last) = st.slip_runs.iter().find(|r| r.0 == c0)?;
    let k = last as usize + 1;
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
    let g = 6.0 * mu * res.scene.arm() / l;
    let mut d = Vec::new();
    for (k, st) in res.run.summaries.iter().enumerate() {
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
    /// FE, by [`crate::precursors::definition`]: every precursor of the first cycle, the long
    /// ones, the advancing ones (n, the count to compare with the model's), the first advancing
    /// one (F at its onset, arrest x/L), and the last stick-slip peak.
    pub n_fe: usize,
    pub n_fe_long: usize,
    pub n_fe_advancing: usize,
    pub f1_fe: Option<f64>,
    pub x1_fe: Option<f64>,
    pub f_max_fe: Option<f64>,
    /// FE front advances ([`definition::advances`]): their count, the first one's force at
    /// onset and new front x/L (the paper's n, F_1, x_1 where fronts run on from their tips).
    pub n_front: usize,
    pub f1_front: Option<f64>,
    pub x1_front: Option<f64>,
}

/// The precursors of a run's first cycle ([`crate::precursors::definition`]); forces F_i in
/// N/m.
pub fn precursors(res: &SlideResult) -> Precursors {
    definition::find_from_edge(nucleating_edge(res), &slips(res), &res.condensed.x, res.condensed.t).1
}

/// The edge [`precursors`] and [`front_advances`] count from: that of the lowest interior
/// pressure ([`definition::Edge::of_lowest_pressure`]); under side push the pushed, trailing
/// edge at any push height (p = N/L + 12 F h x/L^3: no top shear adds a couple).
pub fn nucleating_edge(res: &SlideResult) -> definition::Edge {
    if !res.scene.loading.rig.is_top_plate() {
        return definition::Edge::Trailing;
    }
    definition::Edge::of_lowest_pressure(res.scene.arm(), res.scene.block.thickness)
}

/// The front advances of a run's first cycle ([`definition::advances`]); forces in N/m.
pub fn front_advances(res: &SlideResult) -> Vec<definition::Advance> {
    definition::advances_from_edge(nucleating_edge(res), &slips(res), &res.condensed.x, res.condensed.t).1
}

/// The run's instabilities, each with the preslip of the state before it (its first run of
/// slipping nodes: [`Slip::preslip`]).
fn slips(res: &SlideResult) -> Vec<Slip> {
    let before = |k: usize| {
        let s = res.run.summaries.get(k.checked_sub(1)?)?;
        s.slip_runs.first().map(|&(a, b)| (a as usize, b as usize))
    };
    res.run
        .events
        .iter()
        .enumerate()
        .filter_map(|(k, e)| e.slip(k).map(|s| Slip { preslip: before(k), ..s }))
        .collect()
}

pub fn compare_paper(res: &SlideResult) -> Option<PaperComparison> {
    if !res.options.law.weakens() {
        return None;
    }
    let (mu_s, mu_d) = (res.options.law.mu_s(), res.options.law.mu_d());
    let c = &res.condensed;
    let (r, g) = (mu_d / mu_s, 6.0 * mu_d * res.scene.arm() / c.l);
    let p = crate::precursors::Params::new(r, g).ok()?;
    let ev = crate::precursors::simulate(&p, 1);
    let k = mu_s * res.options.n_force;
    let pre = precursors(res);
    let adv = front_advances(res);
    Some(PaperComparison {
        r,
        g,
        n: crate::precursors::n_precursors(&p).ok()?,
        f1: ev[0].f,
        x1: ev[0].x,
        f_max: p.f_max(),
        n_fe: pre.n_all(),
        n_fe_long: pre.n_long(),
        n_fe_advancing: pre.n(),
        f1_fe: pre.first().map(|q| q.f / k),
        x1_fe: pre.first().map(|q| c.x[q.arrest()] / c.l),
        f_max_fe: res.run.events.iter().rfind(|e| e.ends_cycle()).map(|e| e.f / k),
        n_front: adv.len(),
        f1_front: adv.first().map(|a| a.f / k),
        x1_front: adv.first().map(|a| c.x[a.front] / c.l),
    })
}

/// The paper's analytic loading curve for a run (fig. 4): its (r, g) = (mu_d/mu_s,
/// 6 mu_d H/L) and the iteration's (F^c, F)/(mu_s N) through the run's whole slips plus the
/// model's precursors. `points` is None for a law that does not weaken (coulomb) and for
/// (r, g) outside the model's square 0 < r, g < 1.
#[derive(Debug, Clone)]
pub struct ModelCurve {
    pub r: f64,
    pub g: f64,
    pub points: Option<Vec<(f64, f64)>>,
}

/// The paper's iteration for the (r, g) of `res` ([`ModelCurve`]), drawn by `fig4_fe.svg`
/// next to the FE curve.
pub fn model_curve(res: &SlideResult) -> ModelCurve {
    let law = res.options.law;
    let (r, g) = (law.mu_d() / law.mu_s(), 6.0 * law.mu_d() * res.scene.arm() / res.condensed.l);
    let points = match crate::precursors::Params::new(r, g) {
        Ok(p) if law.weakens() => {
            let n = res.run.sliding_events.max(1) + crate::precursors::n_precursors(&p).unwrap_or(0);
            Some(crate::precursors::loading_curve(&crate::precursors::simulate(&p, n)))
        }
        _ => None,
    };
    ModelCurve { r, g, points }
}

/// A friction law as a user names it (the `slide` command's flags, the Python package's
/// keywords): the law's name and whichever coefficients were given. Default: the commands'
/// law and rule ([`DEFAULT_LAW`], [`DEFAULT_RULE`]), no value given.
#[derive(Debug, Clone)]
pub struct LawChoice {
    /// coulomb, static-kinetic, slip-weakening or rate-state.
    pub law: String,
    pub mu: Option<f64>,
    pub mu_s: Option<f64>,
    pub mu_d: Option<f64>,
    /// The paper's r = mu_d/mu_s and g = 6 mu_d H/L (g alone sets coulomb's mu).
    pub r: Option<f64>,
    pub g: Option<f64>,
    /// Relaxation rule of static-kinetic: paper or overdamped.
    pub rule: String,
    /// Weakening slip, m (slip-weakening only).
    pub dc: Option<f64>,
    /// Rate-and-state's parameters (rate-state only).
    pub rate_state: RateStateChoice,
    /// The `[law]` keys [`Self::with_scene`] filled in (for the refusals' names).
    pub from_scene: Vec<&'static str>,
}

impl Default for LawChoice {
    fn default() -> Self {
        Self {
            law: DEFAULT_LAW.into(),
            rule: DEFAULT_RULE.into(),
            mu: None,
            mu_s: None,
            mu_d: None,
            r: None,
            g: None,
            dc: None,
            rate_state: RateStateChoice::default(),
            from_scene: vec![],
        }
    }
}

/// Rate-and-state as a user gives it (`--a --b --l-rs --f0 [--v0 --state-law --theta0]`):
/// a, b, L (m) and f_0 are physics and must be given; V_0 defaults to
/// [`DEFAULT_RS_V0`], the state law to aging, theta_0 to L / V_0 (steady sliding at V_0).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RateStateChoice {
    pub a: Option<f64>,
    pub b: Option<f64>,
    pub l_rs: Option<f64>,
    pub v0: Option<f64>,
    pub f0: Option<f64>,
    /// aging or slip.
    pub state_law: Option<String>,
    pub theta0: Option<f64>,
}

/// Rate-and-state's reference slip rate when none is given, m/s (a laboratory scale: the
/// coefficients a, b, f_0 are quoted at about 1 um/s; Dieterich 1979, Marone 1998).
pub const DEFAULT_RS_V0: f64 = 1e-6;

impl RateStateChoice {
    fn given(&self) -> Option<&'static str> {
        [
            (self.a.is_some(), "--a"),
            (self.b.is_some(), "--b"),
            (self.l_rs.is_some(), "--l-rs"),
            (self.v0.is_some(), "--v0"),
            (self.f0.is_some(), "--f0"),
            (self.state_law.is_some(), "--state-law"),
            (self.theta0.is_some(), "--theta0"),
        ]
        .into_iter()
        .find(|g| g.0)
        .map(|g| g.1)
    }

    fn law(&self) -> Result<Law> {
        let need = |v: Option<f64>, flag: &str, what: &str| {
            v.ok_or_else(|| Error::input(flag, format!("rate-state needs {flag}, {what}")))
        };
        let a = need(self.a, "--a", "the direct effect a")?;
        let b = need(self.b, "--b", "the evolution effect b (b > a: rate weakening)")?;
        let l = need(self.l_rs, "--l-rs", "the state-evolution distance L in m")?;
        let f0 = need(self.f0, "--f0", "the steady-state coefficient f_0 at V_0")?;
        let kind = match self.state_law.as_deref().unwrap_or("aging") {
            "aging" => crate::law::StateLaw::Aging,
            "slip" => crate::law::StateLaw::Slip,
            other => {
                return Err(Error::input(
                    "--state-law",
                    format!("'{}': use aging or slip", crate::error::quote(other)),
                ))
            }
        };
        let mut r = crate::law::RateState::new(a, b, l, self.v0.unwrap_or(DEFAULT_RS_V0), f0, kind)?;
        if let Some(t) = self.theta0 {
            r = r.with_theta0(t)?;
        }
        Ok(Law::RateState(r))
    }
}

impl LawChoice {
    /// This choice with the scene's `[law]` values wherever the front end gave none;
    /// `law_given`, `rule_given`: whether `--law`/`--rule` (which have defaults) were given.
    /// A refusal of a value taken from the scene names its key (`[law] dc`).
    pub fn with_scene(mut self, t: &crate::scene::LawTable, law_given: bool, rule_given: bool) -> Self {
        let mut from = vec![];
        let mut take = |mine: &mut Option<f64>, theirs: Option<f64>, key: &'static str| {
            if mine.is_none() && theirs.is_some() {
                *mine = theirs;
                from.push(key);
            }
        };
        take(&mut self.mu, t.mu, "mu");
        take(&mut self.mu_s, t.mu_s, "mu_s");
        take(&mut self.mu_d, t.mu_d, "mu_d");
        take(&mut self.r, t.r, "r");
        take(&mut self.g, t.g, "g");
        take(&mut self.dc, t.dc, "dc");
        let rs = &mut self.rate_state;
        take(&mut rs.a, t.a, "a");
        take(&mut rs.b, t.b, "b");
        take(&mut rs.l_rs, t.l_rs, "l_rs");
        take(&mut rs.v0, t.v0, "v0");
        take(&mut rs.f0, t.f0, "f0");
        take(&mut rs.theta0, t.theta0, "theta0");
        if rs.state_law.is_none() && t.state_law.is_some() {
            rs.state_law = t.state_law.clone();
            from.push("state_law");
        }
        if let (false, Some(k)) = (law_given, &t.kind) {
            self.law = k.clone();
            from.push("kind");
        }
        if let (false, Some(r)) = (rule_given, &t.rule) {
            self.rule = r.clone();
            from.push("rule");
        }
        self.from_scene = from;
        self
    }

    /// Refuses the event rule's options given with a law they cannot act on (the front ends'
    /// one check): `rule` with a law other than static-kinetic, `residual` or `backslip`
    /// unless static-kinetic with the paper rule. Named as flags (`--rule`); Python renders
    /// them as keywords.
    pub fn check_rule_options(
        &self,
        rule_given: bool,
        residual_given: bool,
        backslip_given: bool,
    ) -> Result<()> {
        if rule_given && self.law != "static-kinetic" {
            return Err(Error::input("--rule", "the event rule belongs to --law static-kinetic"));
        }
        for (flag, given) in [("--residual", residual_given), ("--backslip", backslip_given)] {
            if given && (self.law != "static-kinetic" || self.rule != "paper") {
                return Err(Error::input(
                    flag,
                    "a convention of the paper rule: belongs to --law static-kinetic --rule paper",
                ));
            }
        }
        Ok(())
    }

    /// The law on `scene`, a refusal of a scene value naming its `[law]` key.
    pub fn law(&self, scene: &Scene) -> Result<Law> {
        self.build(scene).map_err(|e| match e {
            Error::Input { what, why } => {
                let flag = |k: &str| {
                    if k == "kind" {
                        "--law".to_string()
                    } else {
                        format!("--{}", k.replace('_', "-"))
                    }
                };
                match self
                    .from_scene
                    .iter()
                    .find(|k| what == flag(k) || what == k.replace('_', "-") || what == **k)
                {
                    Some(k) => Error::Input { what: format!("[law] {k}"), why },
                    None => Error::Input { what, why },
                }
            }
            e => e,
        })
    }

    /// The law on `scene` (g and r need its L and H), or the refusal naming what to give.
    /// Defaults: coulomb mu = 0.5; the other laws the paper's (r, g) = (0.9, 0.35).
    fn build(&self, scene: &Scene) -> Result<Law> {
        let rule: crate::law::Rule = self.rule.parse()?;
        if self.law == "rate-state" {
            let other = [
                (self.mu.is_some(), "--mu"),
                (self.mu_s.is_some(), "--mu-s"),
                (self.mu_d.is_some(), "--mu-d"),
            ]
            .into_iter()
            .chain([(self.r.is_some(), "--r"), (self.g.is_some(), "--g"), (self.dc.is_some(), "--dc")])
            .find(|g| g.0);
            if let Some((_, flag)) = other {
                return Err(Error::input(flag, "belongs to the rate-free laws: rate-state takes --a --b --l-rs --f0 [--v0 --state-law --theta0]"));
            }
            return self.rate_state.law();
        }
        if let Some(flag) = self.rate_state.given() {
            return Err(Error::input(flag, "belongs to --law rate-state"));
        }
        match self.law.as_str() {
            "coulomb" => {
                if self.mu_s.is_some() || self.mu_d.is_some() || self.r.is_some() {
                    return Err(Error::input(
                        "law",
                        "coulomb takes --mu (or --g alone), not --mu-s/--mu-d/--r",
                    ));
                }
                if self.dc.is_some() {
                    return Err(Error::input("dc", "--dc belongs to --law slip-weakening"));
                }
                let mu = match (self.mu, self.g) {
                    (Some(m), None) => m,
                    (None, Some(g)) if scene.arm() > 0.0 => g * scene.block.length / (6.0 * scene.arm()),
                    (None, Some(_)) => {
                        return Err(Error::input("--g", "at --height 0 g is 0 whatever mu: give --mu"))
                    }
                    (None, None) => 0.5,
                    _ => return Err(Error::input("mu", "give --mu or --g, not both")),
                };
                Law::coulomb(mu)
            }
            "static-kinetic" | "slip-weakening" => {
                if self.mu.is_some() {
                    return Err(Error::input(
                        "mu",
                        format!("{} takes --mu-s and --mu-d (or --r and --g)", self.law),
                    ));
                }
                let (ms, md) = match (self.mu_s, self.mu_d, self.r, self.g) {
                    (Some(s), Some(d), None, None) => (s, d),
                    (None, None, Some(r), Some(g)) => coefficients_from_rg(scene, r, g)?,
                    (None, None, None, None) => default_coefficients(scene)?,
                    _ => {
                        return Err(Error::input(
                            "mu-s/mu-d",
                            "give both --mu-s and --mu-d, or both --r and --g",
                        ))
                    }
                };
                match self.dc {
                    None if self.law == "slip-weakening" => {
                        Err(Error::input("dc", "slip-weakening needs --dc, the weakening slip distance in m"))
                    }
                    Some(_) if self.law != "slip-weakening" => {
                        Err(Error::input("dc", "--dc belongs to --law slip-weakening"))
                    }
                    Some(dc) => Law::slip_weakening(ms, md, dc),
                    None => Law::static_kinetic(ms, md, rule),
                }
            }
            other => Err(Error::input(
                "law",
                format!(
                    "'{}': use coulomb, static-kinetic, slip-weakening or rate-state",
                    crate::error::quote(other)
                ),
            )),
        }
    }
}
