//! The event-driven quasi-static solver on the condensed system.
//!
//! Unknowns per interface node i (forces from the flat on the block: T_i tangential,
//! P_i >= 0 normal; gap g_i = v_i >= 0): stick (u_i = anchor, v_i = 0; T, P reactions),
//! slip (v_i = 0, u_i free, T_i = -s_i mu P_i), open (T = P = 0, u_i, v_i free). The plate:
//! U_H prescribed (the loading parameter in the drive phase), V free under the force -N
//! (ramped in the normal phase), theta free under no moment. For a fixed set of states the
//! system is linear, so between events z = z0 + lambda z1 and the next event is the smallest
//! lambda at which an inequality reaches equality: exact, no stepping.
//!
//! The free unknowns' matrix (non-stick DOFs, V, theta) is unsymmetric (slip rows); its
//! inverse is kept and updated by bordering in O(m^2) when one DOF joins or leaves, and
//! rebuilt by a full LU only when the residual check of a solve says so.
//!
//! Files, in the order of Siconos' event-driven simulation (law, problem, events manager,
//! simulation) and deal.II step-41's loop (assemble, update the active set, solve):
//! - this file: the problem and the run's records (what goes in, what comes out);
//! - `kind`: the vocabulary of events; [`tolerances`]: every tolerance with its reason;
//! - `operator`: the condensed operator S behind a trait (the seam for another
//!   representation), its dense reference, and the affine solution; `inverse`: the bordered
//!   dense inverse of the free block that the reference keeps;
//! - `active`: the active-set system, the node states and every change to them;
//! - `search`: complementarity checks, the rate problem at a fixed load and the next event;
//! - `relax`: the instabilities of the static-kinetic law (the paper's rule, overdamped);
//! - `classify`: what an instability was (precursor, nucleation, tip advance, sliding...);
//! - `simulation`: [`run`], the normal phase then the drive phase; `weakening`: the drive
//!   phase under slip weakening;
//! - `handoff`: the door for a drive that is not the solver's own (`slide --dynamics`): the
//!   start-up, the recorder, the instability resolver (the quasi-static relaxation or a
//!   dynamic event) and `stepped`, the held mode's drive loop that calls it.

use crate::law::Law;
use crate::precursors::definition::Slip;
use std::sync::Arc;

mod active;
mod classify;
pub(crate) mod handoff;
mod inverse;
mod kind;
pub(crate) mod operator;
mod relax;
mod search;
mod simulation;
#[cfg(test)]
mod springs;
mod stepped;
pub mod tolerances;
mod weakening;

pub use kind::EventKind;
pub(crate) use simulation::check;
pub use simulation::{run, run_with};

#[derive(Debug, Clone, Copy, PartialEq)]
pub enum NodeState {
    Stick,
    /// Slip direction s = +1 or -1 (sign of the slip velocity).
    Slip(f64),
    Open,
}

impl NodeState {
    pub fn name(&self) -> &'static str {
        match self {
            NodeState::Stick => "stick",
            NodeState::Slip(_) => "slip",
            NodeState::Open => "open",
        }
    }
}

/// The loading phase: N ramped with X = 0, then X increased with N held.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Phase {
    Normal,
    Drive,
}

/// How each state set's system is solved: the dense condensed S with a bordered inverse (the
/// reference; O(n^2) per state change), or the block's sparse stiffness in x order factored
/// per solve ([`crate::interface::banded`]; O(n) per solve, no condensation). The two agree
/// to round-off (tests/it/operator.rs); banded pays off when many nodes change per event (thin
/// layers), dense when one does (coulomb).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Operator {
    #[default]
    Dense,
    Banded,
}

/// `slide` without `--operator`: the banded operator above this many interface nodes, the
/// dense reference at or below. Measured (docs/speed.md, `tribofe slide --mu 0.5 --states
/// none`, whole process): 401 nodes dense 0.61 s, banded 0.10 s; 801 nodes 2.55 s, 0.80 s;
/// the thin block t/L = 1/1600 (3,201 nodes) 49 s, 0.46 s; at 51 and 101 nodes both
/// 0.02 s or less, where the reference costs nothing and keeps its bytes.
pub const AUTO_BANDED_ABOVE: usize = 200;

impl Operator {
    /// The default for an interface of `n` nodes over `rows` node rows through the thickness
    /// (None: not known before the mesh is read, a mesh file: the reference): banded above
    /// [`AUTO_BANDED_ABOVE`] nodes while rows^2 <= n / 2. A banded factorisation costs
    /// O(n rows^3) against the dense inverse's O(n^2) per state change, so thick blocks stay
    /// dense; measured crossovers (static-kinetic, docs/speed.md): between 10 and 20 rows at
    /// 401 nodes, near 20 at 801.
    pub fn for_interface(n: Option<usize>, rows: f64) -> Operator {
        match n {
            Some(n) if n > AUTO_BANDED_ABOVE && rows * rows <= n as f64 / 2.0 => Operator::Banded,
            _ => Operator::Dense,
        }
    }

    /// The default for `scene`: [`Self::for_interface`] of its structured mesh's interface
    /// nodes and rows (a mesh file, the side push: the reference). `slide` and its Python
    /// function both choose by it.
    pub fn for_scene(scene: &crate::scene::Scene) -> Operator {
        // The side push borders more than the top plate's three DOFs: the dense reference.
        if !scene.loading.rig.is_top_plate() {
            return Operator::Dense;
        }
        Self::for_interface(Self::interface_nodes(scene), Self::band_rows(scene))
    }

    /// Interface nodes of the scene's structured mesh (None for a mesh file: known once it is
    /// read).
    pub fn interface_nodes(scene: &crate::scene::Scene) -> Option<usize> {
        scene.mesh.file.is_none().then(|| scene.estimate_nx() as usize + 1)
    }

    /// Node rows through the block's thickness (element rows times the element's order).
    pub fn band_rows(scene: &crate::scene::Scene) -> f64 {
        scene.estimate_rows() * scene.element().map_or(1.0, |e| e.kind.order() as f64)
    }

    pub fn name(&self) -> &'static str {
        match self {
            Operator::Dense => "dense",
            Operator::Banded => "banded",
        }
    }
}

/// What the event solver does with each boundary DOF after the interface's 2n (the rig's
/// border, in order): the loading rig as data, one solver for every rig.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BorderRole {
    /// Prescribed: 0 in the normal phase, the loading parameter X in the drive phase (the top
    /// plate's U_H, the pusher's U_p, or the far end of the pusher's spring). F is its force.
    Drive,
    /// Free under the normal force -N (ramped in the normal phase, held after): a plate's V.
    Normal,
    /// Free under no force (the sliding plate's U, a sprung pusher's U_p).
    Free,
    /// Free under no moment: a plate's rotation theta (reported as its tilt).
    Tilt,
    /// The uniform pressure's amplitude: prescribed to the normal force reached (lambda N in the
    /// normal phase, N after); its column in S is the held boundary's reactions to the
    /// pressure of a unit N, its own row is never an equation.
    Pressure,
}

/// The top-plate rig's border: U_H, V, theta.
pub const TOP_PLATE: [BorderRole; 3] = [BorderRole::Drive, BorderRole::Normal, BorderRole::Tilt];

/// The operator a run works on (see [`Operator`]).
#[derive(Clone, Copy)]
pub enum OperatorRef<'a> {
    /// Dense S at the drive height, (2n + k)^2 row-major, over the interface and the rig's k
    /// border DOFs of the given roles.
    Dense(&'a [f64], &'a [BorderRole]),
    Banded(&'a crate::interface::banded::BandedOperator),
}

/// What the run is asked to do.
#[derive(Debug, Clone)]
pub struct Problem {
    /// Normal force, N/m.
    pub n_force: f64,
    pub law: Law,
    /// Stop at this X (m), or after `cycles` whole-interface slips (static-kinetic), whichever
    /// first; for coulomb, None = 5 % past the first whole-interface slip.
    pub x_max: Option<f64>,
    pub cycles: usize,
    /// Cap on recorded events (a run that needs more stops with [`crate::Error::EventCap`]).
    pub max_events: usize,
    /// Keep every event's [`State`] (false: only the last one; every event's [`Summary`] is
    /// kept either way). A state is ~48 bytes per node ([`STATE_BYTES_PER_NODE`]), an event
    /// with its summary ~0.2 kB plus 8 bytes per run of slipping nodes ([`Summary::bytes`]).
    pub keep_states: bool,
    /// Static-kinetic: nodes whose pressure force is below this fraction of the mean nodal
    /// force N/n slide continuously at mu_d (creep) instead of triggering an instability
    /// (the Zeno sequence of ever smaller events as p -> 0 at the trailing corner).
    pub creep_fraction: f64,
    /// Static-kinetic: a cycle also ends at a front crossing, the event after which the nodes
    /// slipped since the last cycle's end make one run from the trailing contact node to the
    /// one before the leading corner (kind EventKind::Crossing; the overdamped rule's front crosses in
    /// many events and its one-event whole slip may come long after, validation/precursors).
    pub end_at_crossing: bool,
    /// Slip weakening: each relaxation's coefficients by Newton where a stable equilibrium is
    /// near (the same equilibria in a few iterates instead of hundreds); false (the default):
    /// fixed point, the reference, with Newton only for a relaxation still unsettled after
    /// 10^4 iterates (a patch near its critical length). Event sequences amplify round-off
    /// differences after ~100 events, so the two give different event counts for long runs
    /// (validation/friction/README.md).
    pub newton: bool,
    /// Checked at every event and every fresh solve of the active-set system (so inside every
    /// relaxation too): once cancelled, the run returns [`crate::Error::Interrupted`].
    pub cancel: crate::Cancel,
    /// Which operator solves each state set (results equal to round-off).
    pub operator: Operator,
    /// Called once per recorded event (see [`Observer`]); None: no call.
    pub observer: Option<Observer>,
    /// How the held mode's static loading (`slide --dynamics`) follows slip weakening.
    pub weakening: Weakening,
}

/// How the held mode's static loading follows slip weakening between dynamic events
/// (`stepped`): each slipping node's coefficient brought to its slip every D_c/N of slip (the
/// default, `--weakening-steps N`; its onsets lag by up to (mu_s - mu_d)/N of strength), or
/// exactly, by continuation in X (`--exact-weakening`). Steps is the default because the exact
/// path measured ~10x slower on the paper's scene (its onsets start creeping dynamic events
/// from the fold) and fails on (0.7, 0.5) (docs/speed.md).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Weakening {
    Exact,
    #[default]
    Steps,
}

impl Weakening {
    pub fn name(&self) -> &'static str {
        match self {
            Weakening::Exact => "exact",
            Weakening::Steps => "steps",
        }
    }
}

/// A host's view of a run while it is recorded: called once per recorded event, in order, with
/// the event's index in [`Run::events`], the event and the state after it. It sees the events
/// even when the run keeps no states ([`Problem::keep_states`]) and when the run ends without a
/// [`Run`] ([`crate::Error::EventCap`], [`crate::Error::Interrupted`]): that is how a study
/// counts a capped run's precursors through [`crate::precursors::definition`]. It is called on
/// the run's own thread, inside the event loop, so it should be short; state it keeps is the
/// host's (behind a `Mutex` or an atomic: the observer is `Send + Sync`, as runs go to threads).
#[derive(Clone)]
pub struct Observer(Arc<ObserverFn>);

/// The observer's call: (index in [`Run::events`], event, state after it).
type ObserverFn = dyn Fn(usize, &Event, &State) + Send + Sync;

impl Observer {
    pub fn new(f: impl Fn(usize, &Event, &State) + Send + Sync + 'static) -> Observer {
        Observer(Arc::new(f))
    }

    pub(super) fn call(&self, index: usize, ev: &Event, st: &State) {
        (self.0)(index, ev, st)
    }
}

impl std::fmt::Debug for Observer {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("Observer")
    }
}

impl Default for Problem {
    fn default() -> Self {
        Self {
            n_force: crate::studies::slide::DEFAULT_N_FORCE,
            law: Law::Coulomb { mu: 0.5 },
            x_max: None,
            cycles: crate::studies::slide::DEFAULT_CYCLES,
            max_events: crate::studies::slide::DEFAULT_MAX_EVENTS,
            keep_states: true,
            creep_fraction: 1e-3,
            end_at_crossing: false,
            newton: false,
            cancel: crate::Cancel::new(),
            operator: Operator::Dense,
            observer: None,
            weakening: Weakening::Steps,
        }
    }
}

/// Largest violations of one recorded state, relative to the mean nodal force N/n (forces)
/// or to the displacement scale N t/(E* L) (gaps).
#[derive(Debug, Clone, Copy, Default)]
pub struct Violations {
    pub equilibrium: f64,
    pub pressure: f64,
    pub gap: f64,
    pub complementarity: f64,
    pub friction: f64,
    /// Slip against its direction since the previous recorded state (slipping nodes), or
    /// |T| not opposing the slip direction.
    pub direction: f64,
    /// Static-kinetic only, not a violation: the largest (|T| - mu_s P)/(N/n) of a stuck node
    /// right after a relaxation; that node nucleates the next event at the same X.
    pub overload: f64,
}

impl Violations {
    pub fn max(&self) -> f64 {
        [self.equilibrium, self.pressure, self.gap, self.complementarity, self.friction, self.direction]
            .into_iter()
            .fold(0.0, f64::max)
    }
}

/// The interface after an event.
#[derive(Debug, Clone)]
pub struct State {
    pub phase: Phase,
    /// Plate horizontal displacement at height H, m; N reached, N/m.
    pub x: f64,
    pub n_force: f64,
    /// Friction force F = force of the drive on the plate, N/m; plate tilt theta, rad; V, m.
    pub f: f64,
    pub tilt: f64,
    pub v: f64,
    /// Per node: T, P (N/m), u (m: slip, the flat is at rest), gap v (m), state.
    pub t_force: Vec<f64>,
    pub p_force: Vec<f64>,
    pub u: Vec<f64>,
    pub gap: Vec<f64>,
    pub states: Vec<NodeState>,
    pub violations: Violations,
}

impl State {
    pub fn counts(&self) -> [usize; 3] {
        let mut c = [0; 3];
        for s in &self.states {
            c[match s {
                NodeState::Stick => 0,
                NodeState::Slip(_) => 1,
                NodeState::Open => 2,
            }] += 1;
        }
        c
    }
}

/// One event (one recorded state follows it).
#[derive(Debug, Clone)]
pub struct Event {
    /// What happened.
    pub kind: EventKind,
    /// Force before the event's relaxation (instabilities) or at it, N/m; X, m.
    pub f: f64,
    pub x: f64,
    /// Nucleation node and the slipped region (first, last node) when there is one.
    pub node: usize,
    pub region: Option<(usize, usize)>,
    /// Force after relaxation, N/m (= f for continuous events).
    pub f_relaxed: f64,
    /// Nodes of the region that slipped backwards during the relaxation (paper rule).
    pub backslip: usize,
    /// Every contact node slipping at the end of the relaxation (then F* = mu_d N).
    pub all_slipping: bool,
}

/// Bytes a kept [`State`] takes per interface node: T, P, u, gap (4 f64) and the node state
/// (an enum of 16 bytes); plus [`STATE_BYTES_FIXED`] a state.
pub const STATE_BYTES_PER_NODE: f64 = 48.0;
pub const STATE_BYTES_FIXED: f64 = 200.0;

/// What the reports read of one recorded state, kept for every event whether or not the run
/// keeps its [`State`]s ([`Problem::keep_states`]): loading.csv's row, events.csv's violation
/// and overload, fronts.svg's runs of slipping nodes and the trailing slip front
/// ([`crate::studies::slide::trailing_front`]). Equal to [`Summary::of`] the state it sums up.
#[derive(Debug, Clone, PartialEq)]
pub struct Summary {
    pub phase: Phase,
    /// As the [`State`]'s: X (m), N reached and F (N/m), tilt (rad), V (m).
    pub x: f64,
    pub n_force: f64,
    pub f: f64,
    pub tilt: f64,
    pub v: f64,
    /// Nodes sticking, slipping, open ([`State::counts`]).
    pub counts: [u32; 3],
    /// [`Violations::max`] and [`Violations::overload`] of the state.
    pub max_violation: f64,
    pub overload: f64,
    /// The first node not open (None: every node open).
    pub first_contact: Option<u32>,
    /// First and last node of each run of consecutive slipping nodes, in node order.
    pub slip_runs: Vec<(u32, u32)>,
}

impl Summary {
    /// The summary of a state (node indices fit u32: the interface is bounded far below by
    /// [`crate::scene::limits::check_interface`]).
    pub fn of(st: &State) -> Summary {
        let slipping = |i: usize| matches!(st.states[i], NodeState::Slip(_));
        let n = st.states.len();
        let mut slip_runs = Vec::new();
        let mut i = 0;
        while i < n {
            if slipping(i) {
                let j = (i..n).find(|&k| !slipping(k)).unwrap_or(n);
                slip_runs.push((i as u32, (j - 1) as u32));
                i = j;
            } else {
                i += 1;
            }
        }
        let [a, b, c] = st.counts();
        Summary {
            phase: st.phase,
            x: st.x,
            n_force: st.n_force,
            f: st.f,
            tilt: st.tilt,
            v: st.v,
            counts: [a as u32, b as u32, c as u32],
            max_violation: st.violations.max(),
            overload: st.violations.overload,
            first_contact: st.states.iter().position(|s| *s != NodeState::Open).map(|k| k as u32),
            slip_runs,
        }
    }

    /// Upper bound of the bytes one recorded event takes when states are not kept, on an
    /// interface of `n` nodes: its [`Event`] and [`Summary`] and the most runs of slipping
    /// nodes a state can have ((n + 1)/2, 8 bytes each).
    pub fn bytes(n: usize) -> f64 {
        (std::mem::size_of::<Event>() + std::mem::size_of::<Summary>()) as f64 + 8.0 * n.div_ceil(2) as f64
    }
}

/// Bytes the records of one event take on an interface of `n` nodes: its state, event and
/// summary when states are kept ([`Problem::keep_states`]), else the event and summary alone.
pub fn bytes_per_event(n: usize, keep_states: bool) -> f64 {
    let summary = Summary::bytes(n);
    if keep_states {
        summary + STATE_BYTES_PER_NODE * n as f64 + STATE_BYTES_FIXED
    } else {
        summary
    }
}

#[derive(Debug, Clone)]
pub struct Run {
    pub events: Vec<Event>,
    /// One state per event, or only the last one ([`Problem::keep_states`] false). Readers
    /// that need the per-node fields of every event (states.csv, `--fields`, the field
    /// arrays, the precursor field checks, the edge study) need a run that kept them; the
    /// reports of the loading and the events read [`Run::summaries`].
    pub states: Vec<State>,
    /// One per event, always.
    pub summaries: Vec<Summary>,
    /// Largest [`Violations::max`] over every recorded state, kept or not.
    pub max_violation: f64,
    /// Tangential stiffness of the all-stuck interface dF/dX, N/m per m (F^c = k_bonded X).
    pub k_bonded: f64,
    pub sliding_events: usize,
    /// Dense operator: bordering updates and full refactorisations of the free system; banded:
    /// low-rank row updates and band factorisations.
    pub updates: usize,
    pub refreshes: usize,
    /// The exact weakening path's onsets (held mode): per instability, X (m) and F (N/m) at
    /// the fold where its equilibrium branch ends (the dynamic event starts just past it).
    pub folds: Vec<(f64, f64)>,
}

impl Run {
    /// An empty run (no event yet) of bonded stiffness `k_bonded`.
    pub(super) fn new(k_bonded: f64) -> Run {
        Run {
            events: vec![],
            states: vec![],
            summaries: vec![],
            max_violation: 0.0,
            k_bonded,
            sliding_events: 0,
            updates: 0,
            refreshes: 0,
            folds: vec![],
        }
    }

    /// Whether every event's state is here (the run kept its states).
    pub fn has_all_states(&self) -> bool {
        self.states.len() == self.events.len()
    }

    /// Records one event and the state after it: its summary always, the state itself if
    /// `keep_states` (else it replaces the one kept).
    pub(crate) fn push(&mut self, ev: Event, st: State, keep_states: bool) {
        self.max_violation = self.max_violation.max(st.violations.max());
        self.summaries.push(Summary::of(&st));
        if !keep_states {
            self.states.clear();
        }
        self.events.push(ev);
        self.states.push(st);
    }
}

impl Event {
    /// Whether the event ends a stick-slip cycle (a whole slip, or a front crossing).
    pub fn ends_cycle(&self) -> bool {
        self.kind.ends_cycle()
    }

    /// The event as the precursor definition reads it ([`crate::precursors::definition`]):
    /// an instability (one with a slipped region), `index` its place in [`Run::events`]; None
    /// for a continuous event. The one mapping from events to [`Slip`]s every count goes through.
    pub fn slip(&self, index: usize) -> Option<Slip> {
        self.region.map(|region| Slip {
            event: index,
            x_drive: self.x,
            f: self.f,
            node: self.node,
            region,
            ends_cycle: self.ends_cycle(),
            preslip: None,
        })
    }

    pub(crate) fn simple(kind: EventKind, st: &State, node: usize) -> Event {
        Event {
            kind,
            f: st.f,
            x: st.x,
            node,
            region: None,
            f_relaxed: st.f,
            backslip: 0,
            all_slipping: false,
        }
    }
}
