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

use crate::error::{Error, Result};
use crate::interface::banded::{BandedOperator, Rows};
use crate::interface::law::{Law, Rule};
use crate::linalg::banded::Banded;
use faer::linalg::solvers::DenseSolveCore;

mod kind;
pub mod tolerances;
mod weakening;

pub use kind::EventKind;

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

/// How each state set's system is solved: the dense condensed S with a bordered inverse
/// (the reference), or the block's sparse stiffness in x order, factored per solve
/// ([`crate::interface::banded`]); the two agree to round-off (tests/operator.rs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Operator {
    #[default]
    Dense,
    Banded,
}

impl Operator {
    pub fn name(&self) -> &'static str {
        match self {
            Operator::Dense => "dense",
            Operator::Banded => "banded",
        }
    }
}

/// The operator a run works on (see [`Operator`]).
#[derive(Clone, Copy)]
pub enum OperatorRef<'a> {
    /// Dense S at the drive height, (2n + 3)^2 row-major.
    Dense(&'a [f64]),
    Banded(&'a BandedOperator),
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
    /// Cap on recorded events (a run that needs more stops with [`Error::EventCap`]).
    pub max_events: usize,
    /// Keep every event's state (false: only the last, for studies that need the events
    /// alone; a state is ~40 bytes per node).
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
    /// Checked at every event: once cancelled, the run returns [`Error::Interrupted`].
    pub cancel: crate::Cancel,
    /// Which operator solves each state set (results equal to round-off).
    pub operator: Operator,
}

impl Default for Problem {
    fn default() -> Self {
        Self {
            n_force: 1.0,
            law: Law::Coulomb { mu: 0.5 },
            x_max: None,
            cycles: 10,
            max_events: 50_000,
            keep_states: true,
            creep_fraction: 1e-3,
            end_at_crossing: false,
            newton: false,
            cancel: crate::Cancel::new(),
            operator: Operator::Dense,
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

#[derive(Debug, Clone)]
pub struct Run {
    pub events: Vec<Event>,
    /// One state per event, or only the last one ([`Problem::keep_states`] false).
    pub states: Vec<State>,
    /// Largest [`Violations::max`] over every recorded state, kept or not.
    pub max_violation: f64,
    /// Tangential stiffness of the all-stuck interface dF/dX, N/m per m (F^c = k_bonded X).
    pub k_bonded: f64,
    pub sliding_events: usize,
    /// Bordering updates and full refactorisations of the free system.
    pub updates: usize,
    pub refreshes: usize,
}

/// Dense inverse of the free system, updated by bordering.
struct Free {
    /// DOF of each free position, and position of each DOF (usize::MAX if constrained).
    dofs: Vec<usize>,
    pos: Vec<usize>,
    /// Slip coefficient and Newton spring of each free position's row when the inverse was
    /// formed.
    coef: Vec<(f64, f64)>,
    /// Inverse, stride nd, top-left m x m used.
    inv: Vec<f64>,
}

impl Free {
    fn empty(nd: usize) -> Free {
        Free { dofs: vec![], pos: vec![usize::MAX; nd], coef: vec![], inv: vec![0.0; nd * nd] }
    }
}

struct Solver<'a> {
    s: &'a [f64],
    /// The banded operator and its workspace: then `s` is empty and the free inverse unused.
    banded: Option<(&'a BandedOperator, Banded)>,
    n: usize,
    nd: usize,
    law: Law,
    states: Vec<NodeState>,
    anchor: Vec<f64>,
    /// Per node: the coefficient of its slip row (mu_d, or the slip-weakening value), the
    /// threshold while stuck (mu_s; slip weakening: the value its slip has reached), the
    /// position where it last started slipping and its slip before that (since the last heal).
    mu_slip: Vec<f64>,
    mu_stick: Vec<f64>,
    slip0: Vec<f64>,
    slip_acc: Vec<f64>,
    /// Slip weakening's Newton linearisation of a slipping node's row: the spring
    /// k = (d mu/d slip) p on its own slip and the slip where it was taken (0: none).
    spring: Vec<f64>,
    spring_u: Vec<f64>,
    /// Rate fixes stick the slipping node running back fastest before any other change.
    /// Node order alone can cycle: a node at its threshold slips, runs back together with a
    /// slipping neighbour, sticks first (lower index) and slips again, where sticking the
    /// neighbour would have settled it.
    stick_fastest_first: bool,
    /// Open nodes that close only by penetrating while not separating: a corner at zero
    /// pressure can cycle stick, slip, open (its pressure falls) and close (its gap closes, or
    /// it penetrates by round-off while separating).
    hold_open: Vec<bool>,
    free: Free,
    /// The free set before the last bulk change: an instability's region and the re-stuck
    /// interface alternate, and each is a few bordering updates away from its previous self.
    spare: Option<Free>,
    updates: usize,
    refreshes: usize,
    fscale: f64,
    dscale: f64,
    n_force: f64,
    phase: Phase,
    creep: f64,
    /// S b0 and S b1 over the constrained values, or None to rebuild.
    g: Option<(Vec<f64>, Vec<f64>)>,
    g_updates: usize,
    /// The last solve's result, until the states, anchors, coefficients or phase change.
    last: Option<Affine>,
}

/// Affine solution b = b0 + lam b1, f = f0 + lam f1 over all DOFs.
#[derive(Clone)]
struct Affine {
    b0: Vec<f64>,
    b1: Vec<f64>,
    f0: Vec<f64>,
    f1: Vec<f64>,
}

impl Affine {
    fn b(&self, i: usize, lam: f64) -> f64 {
        self.b0[i] + lam * self.b1[i]
    }
    fn f(&self, i: usize, lam: f64) -> f64 {
        self.f0[i] + lam * self.f1[i]
    }
}

impl<'a> Solver<'a> {
    /// Every node in contact slipping, and at least one in contact (a whole slip).
    fn all_contact_slipping(&self) -> bool {
        self.states.iter().all(|s| *s != NodeState::Stick)
            && self.states.iter().any(|s| matches!(s, NodeState::Slip(_)))
    }

    fn iu(&self) -> usize {
        2 * self.n
    }
    fn iv(&self) -> usize {
        2 * self.n + 1
    }
    fn ith(&self) -> usize {
        2 * self.n + 2
    }

    /// Coefficient c of the slip row S[u_i] + c S[v_i] of DOF d (0 if not a slip row).
    fn slip_coef(&self, d: usize) -> f64 {
        if d < self.n {
            if let NodeState::Slip(s) = self.states[d] {
                return s * self.mu_slip[d];
            }
        }
        0.0
    }

    /// Row key of DOF d: its slip coefficient and Newton spring (what the inverse depends on).
    fn row_key(&self, d: usize) -> (f64, f64) {
        (self.slip_coef(d), if d < self.n { self.spring[d] } else { 0.0 })
    }

    /// Entry of the equation of DOF a on the unknown DOF b.
    fn a_entry(&self, a: usize, b: usize) -> f64 {
        let c = self.slip_coef(a);
        let mut v = self.s[a * self.nd + b];
        if c != 0.0 {
            v += c * self.s[(a + self.n) * self.nd + b];
        }
        if a == b && a < self.n {
            v += self.spring[a];
        }
        v
    }

    fn is_free(&self, d: usize) -> bool {
        let n = self.n;
        if d < n {
            !matches!(self.states[d], NodeState::Stick)
        } else if d < 2 * n {
            matches!(self.states[d - n], NodeState::Open)
        } else {
            d != self.iu()
        }
    }

    /// Full LU of the free system.
    fn refresh(&mut self) -> Result<()> {
        if self.banded.is_some() {
            return Ok(());
        }
        let nd = self.nd;
        let dofs: Vec<usize> = (0..nd).filter(|&d| self.is_free(d)).collect();
        let m = dofs.len();
        // faer's blocked LU: 5x nalgebra's at m = 400 (whole-interface relaxations).
        let a = faer::Mat::<f64>::from_fn(m, m, |i, j| self.a_entry(dofs[i], dofs[j]));
        let lu = a.partial_piv_lu();
        let u = lu.U();
        let (mut umin, mut umax) = (f64::INFINITY, 0.0f64);
        for i in 0..m {
            umin = umin.min(u[(i, i)].abs());
            umax = umax.max(u[(i, i)].abs());
        }
        let inv = lu.inverse();
        if m > 0 && !(umin > 1e-13 * umax) || (0..m).any(|i| (0..m).any(|j| !inv[(i, j)].is_finite())) {
            return Err(Error::Singular {
                detail: "the interface leaves the block free to move (every node open, or N <= 0)".into(),
                node: None,
                component: None,
            });
        }
        let coef: Vec<(f64, f64)> = dofs.iter().map(|&d| self.row_key(d)).collect();
        let f = &mut self.free;
        f.pos.iter_mut().for_each(|p| *p = usize::MAX);
        for (k, &d) in dofs.iter().enumerate() {
            f.pos[d] = k;
        }
        f.dofs = dofs;
        f.coef = coef;
        for i in 0..m {
            for j in 0..m {
                f.inv[i * nd + j] = inv[(i, j)];
            }
        }
        self.refreshes += 1;
        Ok(())
    }

    /// Removes DOF d from the free set (O(m^2)).
    fn remove(&mut self, d: usize) {
        if self.banded.is_some() {
            return;
        }
        let nd = self.nd;
        let f = &mut self.free;
        let k = f.pos[d];
        let m = f.dofs.len();
        let last = m - 1;
        if k != last {
            // Symmetric permutation: swap rows and columns k and last.
            for j in 0..m {
                f.inv.swap(k * nd + j, last * nd + j);
            }
            for i in 0..m {
                f.inv.swap(i * nd + k, i * nd + last);
            }
            let dl = f.dofs[last];
            f.dofs.swap(k, last);
            f.coef.swap(k, last);
            f.pos[dl] = k;
        }
        let s = f.inv[last * nd + last];
        for i in 0..last {
            let q = f.inv[i * nd + last] / s;
            if q != 0.0 {
                for j in 0..last {
                    f.inv[i * nd + j] -= q * f.inv[last * nd + j];
                }
            }
        }
        f.dofs.pop();
        f.coef.pop();
        f.pos[d] = usize::MAX;
        self.updates += 1;
    }

    /// Adds DOF d to the free set (its row uses the current state; O(m^2)).
    fn add(&mut self, d: usize) -> Result<()> {
        if self.banded.is_some() {
            return Ok(());
        }
        let nd = self.nd;
        let m = self.free.dofs.len();
        let c: Vec<f64> = self.free.dofs.iter().map(|&a| self.a_entry(a, d)).collect();
        let r: Vec<f64> = self.free.dofs.iter().map(|&b| self.a_entry(d, b)).collect();
        let delta = self.a_entry(d, d);
        let cd = self.row_key(d);
        let f = &mut self.free;
        let y: Vec<f64> = (0..m).map(|i| (0..m).map(|j| f.inv[i * nd + j] * c[j]).sum()).collect();
        let mut z = vec![0.0; m];
        for i in 0..m {
            let ri = r[i];
            if ri != 0.0 {
                for j in 0..m {
                    z[j] += ri * f.inv[i * nd + j];
                }
            }
        }
        let sigma = delta - (0..m).map(|i| r[i] * y[i]).sum::<f64>();
        let scale = self.s[d * nd + d].abs().max(f64::MIN_POSITIVE);
        f.dofs.push(d);
        f.coef.push(cd);
        f.pos[d] = m;
        if !(sigma.abs() > tolerances::PIVOT * scale) {
            return self.refresh();
        }
        for i in 0..m {
            let yi = y[i] / sigma;
            for j in 0..m {
                f.inv[i * nd + j] += yi * z[j];
            }
            f.inv[i * nd + m] = -yi;
        }
        for j in 0..m {
            f.inv[m * nd + j] = -z[j] / sigma;
        }
        f.inv[m * nd + m] = 1.0 / sigma;
        self.updates += 1;
        Ok(())
    }

    /// Changes node i's state, updating the free set.
    fn set_state(&mut self, i: usize, new: NodeState, anchor: f64) -> Result<()> {
        let (n, old) = (self.n, self.states[i]);
        // Keep g0 = S b0 current: a stuck node's anchor leaves or enters b0 (row i of S).
        let (nd, s) = (self.nd, self.s);
        if let Some((g0, _)) = &mut self.g {
            let mut axpy = |a: f64| {
                if a != 0.0 {
                    g0.iter_mut().zip(&s[i * nd..(i + 1) * nd]).for_each(|(g, v)| *g += a * v);
                }
            };
            if old == NodeState::Stick {
                axpy(-self.anchor[i]);
            }
            if new == NodeState::Stick {
                axpy(anchor);
            }
            self.g_updates += 1;
            if self.g_updates > 256 {
                self.g = None;
            }
        }
        let was_u = !matches!(old, NodeState::Stick);
        let was_v = matches!(old, NodeState::Open);
        if was_u {
            self.remove(i);
        }
        if was_v {
            self.remove(n + i);
        }
        self.enter(i, new, anchor);
        if !matches!(new, NodeState::Stick) {
            self.add(i)?;
        }
        if matches!(new, NodeState::Open) {
            self.add(n + i)?;
        }
        Ok(())
    }

    /// Changes many nodes at once: incremental below [`tolerances::BATCH`] changes; above, from whichever of
    /// the current and the spare inverse is fewer bordering updates away, or by one full LU
    /// when both are far (cheaper than O(m^2) per change when a whole region flips).
    fn set_many(&mut self, changes: &[(usize, NodeState, f64)]) -> Result<()> {
        if changes.len() < tolerances::BATCH {
            for &(i, st, a) in changes {
                self.set_state(i, st, a)?;
            }
            return Ok(());
        }
        for &(i, st, a) in changes {
            self.enter(i, st, a);
        }
        self.g = None;
        self.rebase()
    }

    /// Brings the free inverse to the current states after bulk changes.
    fn rebase(&mut self) -> Result<()> {
        if self.banded.is_some() {
            return Ok(());
        }
        let target: Vec<usize> = (0..self.nd).filter(|&d| self.is_free(d)).collect();
        let cost = |f: &Free| {
            let stale =
                f.dofs.iter().zip(&f.coef).filter(|&(&d, &c)| !self.is_free(d) || c != self.row_key(d));
            let fresh = target.iter().filter(|&&d| f.pos[d] == usize::MAX);
            stale.count() + fresh.count()
        };
        let here = cost(&self.free);
        let there = self.spare.as_ref().map_or(usize::MAX, cost);
        // Bordering is O(m^2) a change against O(m^3) for the LU; past ~m/8 changes the
        // drift and the cost favour the LU.
        let limit = (target.len() / 8).max(tolerances::BATCH);
        let spare = self.spare.get_or_insert_with(|| Free::empty(self.nd));
        if there < here.min(limit) || here > limit {
            std::mem::swap(&mut self.free, spare);
        }
        if here.min(there) > limit {
            return self.refresh();
        }
        let stale: Vec<usize> = self
            .free
            .dofs
            .iter()
            .zip(&self.free.coef)
            .filter(|&(&d, &c)| !self.is_free(d) || c != self.row_key(d))
            .map(|(&d, _)| d)
            .collect();
        for d in stale {
            self.remove(d);
        }
        for d in target {
            if self.free.pos[d] == usize::MAX {
                self.add(d)?;
            }
        }
        Ok(())
    }

    /// New coefficients of slipping nodes' rows (slip weakening): (node, mu, spring, the slip
    /// the spring is centred on).
    fn set_coefficients(&mut self, changes: &[(usize, f64, f64, f64)]) -> Result<()> {
        self.last = None;
        let small = changes.len() < tolerances::BATCH;
        for &(i, mu, k, u) in changes {
            if small {
                self.remove(i);
            }
            (self.mu_slip[i], self.spring[i], self.spring_u[i]) = (mu, k, u);
            if small {
                self.add(i)?;
            }
        }
        if small {
            Ok(())
        } else {
            self.refresh()
        }
    }

    /// Every node forgets its slip: thresholds back to mu_s (slip weakening's healing).
    fn heal_memory(&mut self) {
        self.slip_acc.iter_mut().for_each(|v| *v = 0.0);
        self.mu_stick.iter_mut().for_each(|v| *v = self.law.mu_s());
    }

    /// Node i's new state and its bookkeeping (the free set is the caller's).
    fn enter(&mut self, i: usize, new: NodeState, anchor: f64) {
        match (self.states[i], new) {
            (NodeState::Slip(_), NodeState::Slip(_)) => {}
            (_, NodeState::Slip(_)) => {
                self.mu_slip[i] = self.law.kinetic(self.slip_acc[i]);
                self.slip0[i] = if self.states[i] == NodeState::Stick { self.anchor[i] } else { 0.0 };
            }
            (NodeState::Slip(s), NodeState::Stick) if matches!(self.law, Law::SlipWeakening { .. }) => {
                self.slip_acc[i] += (s * (anchor - self.slip0[i])).max(0.0);
                self.mu_stick[i] = self.law.kinetic(self.slip_acc[i]);
            }
            _ => {}
        }
        if !matches!(new, NodeState::Slip(_)) {
            self.spring[i] = 0.0;
        }
        self.states[i] = new;
        self.anchor[i] = anchor;
        self.last = None;
    }

    /// The affine solution of the current state set.
    fn solve(&mut self) -> Result<Affine> {
        if let Some(a) = &self.last {
            return Ok(a.clone());
        }
        let a = self.solve_now()?;
        self.last = Some(a.clone());
        Ok(a)
    }

    /// The banded operator's solve of the current state set (one banded LU).
    fn solve_banded(&mut self) -> Result<Affine> {
        let (n, nd) = (self.n, self.nd);
        let free: Vec<bool> = (0..nd).map(|d| self.is_free(d)).collect();
        let mut b0 = vec![0.0; nd];
        let mut b1 = vec![0.0; nd];
        for i in 0..n {
            if matches!(self.states[i], NodeState::Stick) {
                b0[i] = self.anchor[i];
            }
        }
        let fk = match self.phase {
            Phase::Normal => (0.0, -self.n_force),
            Phase::Drive => {
                b1[self.iu()] = 1.0;
                (-self.n_force, 0.0)
            }
        };
        let coef: Vec<f64> = (0..n).map(|i| self.slip_coef(i)).collect();
        let rows = Rows {
            free: &free,
            b0: &b0,
            b1: &b1,
            coef: &coef,
            spring: &self.spring,
            spring_u: &self.spring_u,
            fk,
        };
        let (op, ws) = self.banded.as_mut().expect("banded operator");
        let x = op.solve(&rows, ws)?;
        self.refreshes += 1;
        Ok(Affine { b0: x.b0, b1: x.b1, f0: x.f0, f1: x.f1 })
    }

    fn solve_now(&mut self) -> Result<Affine> {
        if self.banded.is_some() {
            return self.solve_banded();
        }
        let nd = self.nd;
        let (iu, iv) = (self.iu(), self.iv());
        let mut b0 = vec![0.0; nd];
        let mut b1 = vec![0.0; nd];
        for i in 0..self.n {
            if matches!(self.states[i], NodeState::Stick) {
                b0[i] = self.anchor[i];
            }
        }
        if self.phase == Phase::Drive {
            b1[iu] = 1.0;
        }
        let (mut fk0, mut fk1) = (0.0, 0.0);
        match self.phase {
            Phase::Normal => fk1 = -self.n_force,
            Phase::Drive => fk0 = -self.n_force,
        }
        let s = self.s;
        // g = S b_c (the constrained values' forces), kept up to date by `set_state` (O(N) per
        // change) and rebuilt in one pass over S after bulk changes or 256 updates; the free
        // rows' right-hand sides are read from it, and f = g + sum_k z_k S[free_k, :].
        if self.g.is_none() {
            // S is symmetric: S b = sum over the nonzero b_j of b_j S[j, :] (contiguous rows).
            let mut g0 = vec![0.0; nd];
            let mut g1 = vec![0.0; nd];
            for (g, b) in [(&mut g0, &b0), (&mut g1, &b1)] {
                for (j, &bj) in b.iter().enumerate().filter(|(_, &v)| v != 0.0) {
                    g.iter_mut().zip(&s[j * nd..(j + 1) * nd]).for_each(|(g, v)| *g += bj * v);
                }
            }
            self.g = Some((g0, g1));
            self.g_updates = 0;
        }
        let (g0, g1) = self.g.clone().expect("set above");
        for attempt in 0..2 {
            let m = self.free.dofs.len();
            let mut r0 = vec![0.0; m];
            let mut r1 = vec![0.0; m];
            for (k, &a) in self.free.dofs.iter().enumerate() {
                let (mut s0, mut s1) = if a == iv { (fk0, fk1) } else { (0.0, 0.0) };
                s0 -= g0[a];
                s1 -= g1[a];
                let c = self.slip_coef(a);
                if c != 0.0 {
                    s0 -= c * g0[a + self.n];
                    s1 -= c * g1[a + self.n];
                }
                if a < self.n {
                    s0 += self.spring[a] * self.spring_u[a];
                }
                r0[k] = s0;
                r1[k] = s1;
            }
            let inv = &self.free.inv;
            let mut z0 = vec![0.0; m];
            let mut z1 = vec![0.0; m];
            for i in 0..m {
                let row = &inv[i * nd..i * nd + m];
                z0[i] = row.iter().zip(&r0).map(|(a, b)| a * b).sum();
                z1[i] = row.iter().zip(&r1).map(|(a, b)| a * b).sum();
            }
            let (mut c0, mut c1) = (b0.clone(), b1.clone());
            for (k, &a) in self.free.dofs.iter().enumerate() {
                c0[a] = z0[k];
                c1[a] = z1[k];
            }
            let (mut f0, mut f1) = (g0.clone(), g1.clone());
            for (k, &a) in self.free.dofs.iter().enumerate() {
                let (za, zb) = (z0[k], z1[k]);
                let row = &s[a * nd..(a + 1) * nd];
                for j in 0..nd {
                    f0[j] += za * row[j];
                    f1[j] += zb * row[j];
                }
            }
            // Residual of the free equations relative to the largest force: a drifting
            // inverse (many bordering updates) is rebuilt once.
            let mut res = 0.0f64;
            let big = f0.iter().chain(&f1).fold(1e-300f64, |m, v| m.max(v.abs()));
            for &a in self.free.dofs.iter() {
                let c = self.slip_coef(a);
                let (k, ku) = if a < self.n { (self.spring[a], self.spring_u[a]) } else { (0.0, 0.0) };
                let q0 = f0[a] + if c != 0.0 { c * f0[a + self.n] } else { 0.0 }
                    - if a == iv { fk0 } else { 0.0 }
                    + k * (c0[a] - ku);
                let q1 = f1[a] + if c != 0.0 { c * f1[a + self.n] } else { 0.0 }
                    - if a == iv { fk1 } else { 0.0 }
                    + k * c1[a];
                res = res.max(q0.abs()).max(q1.abs());
            }
            if res > tolerances::RESIDUAL * big && attempt == 0 {
                self.refresh()?;
                continue;
            }
            return Ok(Affine { b0: c0, b1: c1, f0, f1 });
        }
        unreachable!()
    }

    /// Applies one rate-consistency change at lam if any is needed; returns what it did.
    /// `Err`-free `Some(i)` with `need_instability` means a stuck node must start an
    /// instability (static-kinetic).
    fn rate_fix(&mut self, a: &Affine, lam: f64, allow_continuous_slip: bool) -> Result<Fix> {
        let n = self.n;
        let (tf, td) = (tolerances::STATE * self.fscale, tolerances::STATE * self.dscale);
        let (rate_f, rate_d) = self.rate_tols(a);
        if self.stick_fastest_first {
            // The slipping node running back fastest sticks first (see the field).
            let back = (0..n)
                .filter_map(|i| match self.states[i] {
                    NodeState::Slip(s) if s * a.b1[i] < -rate_d => Some((i, s * a.b1[i])),
                    _ => None,
                })
                .min_by(|x, y| x.1.total_cmp(&y.1));
            if let Some((i, _)) = back {
                self.set_state(i, NodeState::Stick, a.b(i, lam))?;
                return Ok(Fix::Changed(i, EventKind::Stick));
            }
        }
        let mut unstable = None;
        for i in 0..n {
            let mu_s = self.mu_stick[i];
            let (t, p, u, g) = (a.f(i, lam), a.f(n + i, lam), a.b(i, lam), a.b(n + i, lam));
            let (t1, p1, u1, g1) = (a.f1[i], a.f1[n + i], a.b1[i], a.b1[n + i]);
            match self.states[i] {
                NodeState::Stick | NodeState::Slip(_) => {
                    if p < -tf || (p <= tf && p1 < -rate_f) {
                        self.set_state(i, NodeState::Open, 0.0)?;
                        return Ok(Fix::Changed(i, EventKind::Open));
                    }
                }
                NodeState::Open => {
                    let close = if self.hold_open[i] {
                        g < -td && g1 <= rate_d
                    } else {
                        g < -td || (g <= td && g1 < -rate_d)
                    };
                    if close {
                        self.set_state(i, NodeState::Stick, u)?;
                        return Ok(Fix::Changed(i, EventKind::Close));
                    }
                }
            }
            if let NodeState::Slip(s) = self.states[i] {
                if s * u1 < -rate_d {
                    self.set_state(i, NodeState::Stick, u)?;
                    return Ok(Fix::Changed(i, EventKind::Stick));
                }
            }
            if self.states[i] == NodeState::Stick {
                let sg = if t.abs() > tf { t.signum() } else { t1.signum() };
                let excess = t.abs() - mu_s * p;
                if excess > tf || (excess >= -tf && sg * t1 - mu_s * p1 > rate_f) {
                    let creep = p < self.fscale * self.creep_fraction();
                    if allow_continuous_slip || creep {
                        self.set_state(i, NodeState::Slip(-sg), 0.0)?;
                        return Ok(Fix::Changed(
                            i,
                            if creep && !allow_continuous_slip { EventKind::Creep } else { EventKind::Slip },
                        ));
                    }
                    unstable = unstable.or(Some(i));
                }
            }
        }
        // An instability starts from a consistent state: every other change comes first.
        Ok(unstable.map_or(Fix::None, Fix::Instability))
    }

    fn creep_fraction(&self) -> f64 {
        self.creep
    }

    /// Rate thresholds (forces, displacements) below which a rate counts as zero.
    fn rate_tols(&self, a: &Affine) -> (f64, f64) {
        let n = self.n;
        let rf = (0..2 * n).map(|i| a.f1[i].abs()).fold(0.0, f64::max).max(1e-300) * tolerances::RATE;
        let rd = (0..2 * n).map(|i| a.b1[i].abs()).fold(0.0, f64::max).max(1e-300) * tolerances::RATE;
        (rf, rd)
    }

    /// Violations of the state at lam (prev_u: u at the previous record, for directions).
    fn violations(&self, a: &Affine, lam: f64, prev_u: Option<&[f64]>) -> Violations {
        let n = self.n;
        let (fs, ds) = (self.fscale, self.dscale);
        let mut v = Violations::default();
        let mu_s = self.law.mu_s();
        let mu_d = self.law.mu_d();
        for i in 0..n {
            let (t, p, u, g) = (a.f(i, lam), a.f(n + i, lam), a.b(i, lam), a.b(n + i, lam));
            v.pressure = v.pressure.max(-p / fs);
            v.gap = v.gap.max(-g / ds);
            v.complementarity = v.complementarity.max((p * g).abs() / (fs * ds));
            match self.states[i] {
                NodeState::Stick if mu_d < mu_s => {
                    v.overload = v.overload.max((t.abs() - self.mu_stick[i] * p) / fs)
                }
                NodeState::Stick => v.friction = v.friction.max((t.abs() - mu_s * p) / fs),
                NodeState::Slip(s) => {
                    v.friction = v.friction.max((t.abs() - self.mu_slip[i] * p).abs() / fs);
                    v.direction = v.direction.max(s * t / fs);
                    if let Some(pu) = prev_u {
                        v.direction = v.direction.max(-s * (u - pu[i]) / ds);
                    }
                }
                NodeState::Open => {
                    v.friction = v.friction.max(t.abs() / fs).max(p.abs() / fs);
                }
            }
        }
        // Equilibrium: the free rows' forces equal the applied ones.
        let nk = match self.phase {
            Phase::Normal => -self.n_force * lam,
            Phase::Drive => -self.n_force,
        };
        for d in 0..self.nd {
            if d == self.iu() {
                continue;
            }
            let target = if d == self.iv() {
                Some(nk)
            } else if d == self.ith() {
                Some(0.0)
            } else if self.is_free(d) {
                Some(if d < n { -self.slip_coef(d) * a.f(n + d, lam) } else { 0.0 })
            } else {
                None
            };
            if let Some(tg) = target {
                v.equilibrium = v.equilibrium.max((a.f(d, lam) - tg).abs() / fs);
            }
        }
        v
    }

    fn record(&self, a: &Affine, lam: f64, prev_u: Option<&[f64]>) -> State {
        let n = self.n;
        let x = if self.phase == Phase::Drive { lam } else { 0.0 };
        let nf = if self.phase == Phase::Normal { self.n_force * lam } else { self.n_force };
        State {
            phase: self.phase,
            x,
            n_force: nf,
            f: a.f(self.iu(), lam),
            tilt: a.b(self.ith(), lam),
            v: a.b(self.iv(), lam),
            t_force: (0..n).map(|i| a.f(i, lam)).collect(),
            p_force: (0..n).map(|i| a.f(n + i, lam)).collect(),
            u: (0..n).map(|i| a.b(i, lam)).collect(),
            gap: (0..n).map(|i| a.b(n + i, lam)).collect(),
            states: self.states.clone(),
            violations: self.violations(a, lam, prev_u),
        }
    }

    /// Smallest lam increment at which an inequality of the current states reaches equality:
    /// (increment, node, what).
    fn next_event(&self, a: &Affine, lam: f64) -> Option<(f64, usize, Hit)> {
        let n = self.n;
        let (rf, rd) = self.rate_tols(a);
        let mut best: Option<(f64, usize, Hit)> = None;
        let mut consider = |g: f64, g1: f64, i: usize, h: Hit| {
            let tol = if matches!(h, Hit::Close) { rd } else { rf };
            if g1 < -tol {
                let d = (g / -g1).max(0.0);
                if best.is_none_or(|b| d < b.0) {
                    best = Some((d, i, h));
                }
            }
        };
        for i in 0..n {
            let (t, p, g) = (a.f(i, lam), a.f(n + i, lam), a.b(n + i, lam));
            let (t1, p1, g1) = (a.f1[i], a.f1[n + i], a.b1[n + i]);
            match self.states[i] {
                NodeState::Stick => {
                    let mu_s = self.mu_stick[i];
                    consider(p, p1, i, Hit::Open);
                    consider(mu_s * p - t, mu_s * p1 - t1, i, Hit::Friction(-1.0));
                    consider(mu_s * p + t, mu_s * p1 + t1, i, Hit::Friction(1.0));
                }
                NodeState::Slip(_) => consider(p, p1, i, Hit::Open),
                NodeState::Open => consider(g, g1, i, Hit::Close),
            }
        }
        best
    }
}

#[derive(Debug, Clone, Copy)]
enum Fix {
    None,
    Changed(usize, EventKind),
    Instability(usize),
}

#[derive(Debug, Clone, Copy)]
enum Hit {
    Open,
    Close,
    /// Slip direction s that the threshold implies.
    Friction(f64),
}

/// Runs the loading history on the condensed S (at the drive height, see
/// [`crate::interface::condense::Condensed::at_height`]); `progress` gets a fraction in [0, 1].
pub fn run(s: &[f64], n: usize, pb: &Problem, progress: &dyn Fn(f64)) -> Result<Run> {
    run_with(OperatorRef::Dense(s), n, pb, progress)
}

/// [`run`] on either operator ([`Problem::operator`] is the caller's choice of which to build).
pub fn run_with(op: OperatorRef, n: usize, pb: &Problem, progress: &dyn Fn(f64)) -> Result<Run> {
    let nd = 2 * n + 3;
    let (s, banded): (&[f64], _) = match op {
        OperatorRef::Dense(s) => (s, None),
        OperatorRef::Banded(b) => (&[], Some((b, b.workspace()))),
    };
    let sizes_ok = match op {
        OperatorRef::Dense(s) => s.len() == nd * nd,
        OperatorRef::Banded(b) => b.n == n,
    };
    if !sizes_ok {
        return Err(Error::input("condensed system", "sizes do not match the interface"));
    }
    if !(pb.n_force.is_finite() && pb.n_force > 0.0) {
        return Err(Error::input("N", format!("{} N/m must be a positive number", pb.n_force)));
    }
    if let Some(x) = pb.x_max {
        if !(x.is_finite() && x > 0.0) {
            return Err(Error::input("x-max", format!("{x} m must be a positive number")));
        }
    }
    if !(pb.creep_fraction.is_finite() && pb.creep_fraction >= 0.0 && pb.creep_fraction < 1.0) {
        return Err(Error::input("creep fraction", "must be in [0, 1)"));
    }
    let mut sv = Solver {
        s,
        banded,
        n,
        nd,
        law: pb.law,
        states: vec![NodeState::Stick; n],
        anchor: vec![0.0; n],
        mu_slip: vec![pb.law.mu_d(); n],
        mu_stick: vec![pb.law.mu_s(); n],
        slip0: vec![0.0; n],
        slip_acc: vec![0.0; n],
        spring: vec![0.0; n],
        spring_u: vec![0.0; n],
        stick_fastest_first: false,
        hold_open: vec![false; n],
        free: Free::empty(nd),
        spare: None,
        updates: 0,
        refreshes: 0,
        fscale: pb.n_force / n as f64,
        dscale: 1.0,
        n_force: pb.n_force,
        phase: Phase::Drive,
        creep: pb.creep_fraction,
        g: None,
        g_updates: 0,
        last: None,
    };
    sv.refresh()?;
    // Bonded stiffness and the displacement scale (|V| under N) from the all-stuck solution.
    let a = sv.solve()?;
    let k_bonded = a.f1[sv.iu()];
    let v_scale = a.b0[sv.iv()].abs();
    if !(k_bonded > 0.0 && v_scale > 0.0) {
        return Err(Error::input(
            "condensed system",
            "the bonded block has no tangential or normal stiffness",
        ));
    }
    sv.dscale = v_scale;
    sv.phase = Phase::Normal;
    sv.g = None;
    sv.last = None;

    let mut out = Run {
        events: vec![],
        states: vec![],
        max_violation: 0.0,
        k_bonded,
        sliding_events: 0,
        updates: 0,
        refreshes: 0,
    };
    let max_fix = tolerances::max_changes(n);
    let is_sk = pb.law.weakens();
    let mut prev_u: Vec<f64> = vec![0.0; n];

    // Phase 1: N from 0 to its value; proportional loading, so the rate problem at 0 decides.
    let mut lam = 0.0;
    let mut pending: Option<(EventKind, usize)> = None;
    let mut idle = 0;
    let mut a;
    loop {
        a = settle_continuous(&mut sv, lam, true, max_fix, "normal loading")?;
        if let Some((kind, i)) = pending.take() {
            let st = sv.record(&a, lam, Some(&prev_u));
            prev_u.clone_from(&st.u);
            push(&mut out, pb, Event::simple(kind, &st, i), st)?;
        }
        match sv.next_event(&a, lam) {
            Some((d, i, h)) if lam + d < 1.0 => {
                idle = if d == 0.0 { idle + 1 } else { 0 };
                if idle > max_fix {
                    return Err(stuck_err("normal loading", lam));
                }
                lam += d;
                apply_hit(&mut sv, &a, lam, i, h)?;
                pending = Some((hit_kind(h), i));
            }
            _ => break,
        }
    }
    lam = 1.0;
    let st = sv.record(&a, lam, Some(&prev_u));
    let pre: Vec<usize> = (0..n).filter(|&i| matches!(st.states[i], NodeState::Slip(_))).collect();
    let mut ev = Event::simple(EventKind::NormalLoad, &st, pre.first().copied().unwrap_or(0));
    if !pre.is_empty() {
        ev.kind = EventKind::EdgePreslip;
    }
    prev_u.clone_from(&st.u);
    push(&mut out, pb, ev, st)?;

    // Phase 2: X from 0 with N held. Static-kinetic: the normal loading stops, so every
    // pre-slipped node sticks and re-arms to mu_s.
    sv.phase = Phase::Drive;
    sv.g = None;
    sv.last = None;
    lam = 0.0;
    if is_sk {
        for i in 0..n {
            if let NodeState::Slip(_) = sv.states[i] {
                sv.set_state(i, NodeState::Stick, prev_u[i])?;
            }
        }
    }
    if let Law::SlipWeakening { dc, .. } = pb.law {
        return weakening::drive(&mut sv, out, pb, dc, prev_u, progress);
    }
    let mut x_end = pb.x_max.unwrap_or(f64::INFINITY);
    let mut last_region: Option<(usize, usize)> = None;
    // Nodes slipped in an instability since the last whole-interface slip: an event nucleating
    // next to this set's run from the trailing edge is the tip advance of an arrested front.
    let mut slipped = vec![false; n];
    let frac = |out: &Run, lam: f64, x_end: f64| -> f64 {
        let by_x = if x_end.is_finite() { lam / x_end } else { 0.0 };
        let by_c = if is_sk { out.sliding_events as f64 / pb.cycles.max(1) as f64 } else { 0.0 };
        by_x.max(by_c).min(1.0)
    };
    let mut sliding_seen = false;
    idle = 0;
    loop {
        // Settle at this X: rate consistency, then (static-kinetic) instabilities.
        let mut fixes = 0;
        loop {
            a = sv.solve()?;
            match sv.rate_fix(&a, lam, !is_sk)? {
                Fix::None => break,
                Fix::Changed(i, what) => {
                    fixes += 1;
                    if fixes > max_fix {
                        return Err(stuck_err("drive", lam));
                    }
                    if what == EventKind::Creep {
                        slipped[i] = true; // a creeping corner has slipped (front crossing)
                    }
                    if matches!(what, EventKind::Open | EventKind::Close | EventKind::Creep)
                        && pending.is_none()
                    {
                        pending = Some((what, i));
                    }
                }
                Fix::Instability(i0) => {
                    fixes = 0;
                    if let Some((kind, i)) = pending.take() {
                        let st = sv.record(&a, lam, Some(&prev_u));
                        prev_u.clone_from(&st.u);
                        push(&mut out, pb, Event::simple(kind, &st, i), st)?;
                    }
                    let f_before = a.f(sv.iu(), lam);
                    let before = sv.states.clone();
                    let (region, backslip, all_slip) = instability(&mut sv, &a, lam, i0)?;
                    // Zeno guard: a node that relaxes alone twice in a row (the trailing corner
                    // as p -> 0) slides on continuously at mu_d (creep) until its slip rate
                    // reverses or it opens. It is recorded once the contact around it is
                    // consistent again (its pressure may fall below zero as it slides).
                    if region == (i0, i0) && last_region == Some((i0, i0)) {
                        let b = sv.solve()?;
                        let sg = if b.f(i0, lam) > 0.0 { -1.0 } else { 1.0 };
                        sv.set_state(i0, NodeState::Slip(sg), 0.0)?;
                        pending = Some((EventKind::Creep, i0));
                        continue;
                    }
                    let a2 = sv.solve()?;
                    let st = sv.record(&a2, lam, Some(&prev_u));
                    prev_u.clone_from(&st.u);
                    let kind = classify(&before, &sv.states, region, &mut slipped, pb.end_at_crossing);
                    if kind.ends_cycle() {
                        out.sliding_events += 1;
                    }
                    last_region = Some(region);
                    let ev = Event {
                        kind,
                        f: f_before,
                        x: lam,
                        node: i0,
                        region: Some(region),
                        f_relaxed: st.f,
                        backslip,
                        all_slipping: all_slip,
                    };
                    push(&mut out, pb, ev, st)?;
                    progress(frac(&out, lam, x_end));
                    if is_sk && out.sliding_events >= pb.cycles {
                        return finish(out, &sv);
                    }
                }
            }
        }
        if let Some((kind, i)) = pending.take() {
            let st = sv.record(&a, lam, Some(&prev_u));
            prev_u.clone_from(&st.u);
            push(&mut out, pb, Event::simple(kind, &st, i), st)?;
        }
        // Coulomb: the first whole-interface slip; by default the run ends 5 % further.
        if !is_sk && !sliding_seen && sv.all_contact_slipping() {
            sliding_seen = true;
            out.sliding_events += 1;
            let st = sv.record(&a, lam, Some(&prev_u));
            prev_u.clone_from(&st.u);
            push(&mut out, pb, Event::simple(EventKind::Sliding, &st, 0), st)?;
            if pb.x_max.is_none() {
                x_end = lam + 0.05 * lam.max(pb.n_force / k_bonded);
            }
        }
        let next = sv.next_event(&a, lam);
        if next.is_none_or(|(d, _, _)| lam + d >= x_end) {
            // Static-kinetic: every contact node creeping at mu_d is a steady whole slip that
            // no further event can end.
            if is_sk && next.is_none() && sv.all_contact_slipping() {
                out.sliding_events += 1;
                let st = sv.record(&a, lam, Some(&prev_u));
                let ev = Event { all_slipping: true, ..Event::simple(EventKind::Sliding, &st, 0) };
                push(&mut out, pb, ev, st)?;
                progress(1.0);
                return finish(out, &sv);
            }
            if !x_end.is_finite() {
                return Err(Error::input(
                    "x-max",
                    "the loading reaches no further event and no end was given; give --x-max",
                ));
            }
            lam = x_end;
            let st = sv.record(&a, lam, Some(&prev_u));
            push(&mut out, pb, Event::simple(EventKind::End, &st, 0), st)?;
            progress(1.0);
            return finish(out, &sv);
        }
        let (d, i, h) = next.unwrap();
        idle = if d == 0.0 { idle + 1 } else { 0 };
        if idle > max_fix {
            return Err(stuck_err("drive", lam));
        }
        lam += d;
        progress(frac(&out, lam, x_end));
        if is_sk && matches!(h, Hit::Friction(_)) {
            // The settle at the new X starts the instability (or creep).
            continue;
        }
        apply_hit(&mut sv, &a, lam, i, h)?;
        let kind = match h {
            Hit::Friction(_) => {
                let left = i > 0 && matches!(sv.states[i - 1], NodeState::Slip(_));
                let right = i + 1 < n && matches!(sv.states[i + 1], NodeState::Slip(_));
                if left || right {
                    EventKind::TipAdvance
                } else {
                    EventKind::Nucleation
                }
            }
            _ => hit_kind(h),
        };
        pending = Some((kind, i));
    }
}

/// Kind of an instability over `region` (first, last node) given the states before and after
/// it, and `slipped`, the nodes slipped in instabilities since the last whole-interface slip
/// (updated): `sliding` when the region covers every node in contact both before and after
/// (with the overdamped rule some may have re-stuck before the end of the relaxation; an
/// open or creeping corner that re-closes in the relaxation is no obstacle to a whole slip),
/// `precursor` when it starts at the first
/// contact node (the trailing edge), `tip-advance` when it touches the run of slipped nodes
/// grown from there (an arrested front creeping on), `nucleation` elsewhere; with `crossing`,
/// `crossing` for an event that is not a whole slip but completes the run of slipped (or
/// creeping) nodes from the first contact node to the last but one.
fn classify(
    before: &[NodeState],
    states: &[NodeState],
    region: (usize, usize),
    slipped: &mut [bool],
    crossing: bool,
) -> EventKind {
    let contact: Vec<usize> =
        (0..states.len()).filter(|&k| states[k] != NodeState::Open && before[k] != NodeState::Open).collect();
    let covers =
        contact.first().is_some_and(|&c0| region.0 <= c0) && contact.last().is_some_and(|&c1| region.1 >= c1);
    let kind = if covers {
        EventKind::Sliding
    } else if contact.first() == Some(&region.0) {
        EventKind::Precursor
    } else {
        let c0 = contact.first().copied().unwrap_or(0);
        let tip = (c0..states.len()).take_while(|&k| slipped[k]).last();
        if tip.is_some_and(|k| region.0 <= k + 1) {
            EventKind::TipAdvance
        } else {
            EventKind::Nucleation
        }
    };
    if kind != EventKind::Sliding {
        (region.0..=region.1).for_each(|k| slipped[k] = true);
    }
    // The leading corner node is left out: its pressure is singular in the discrete model
    // and it holds after every node behind it has slipped (overdamped rule at (0.5, 0.5)).
    let crossed = || {
        let (Some(&c0), Some(&c1)) = (contact.first(), contact.last()) else { return false };
        (c0..c1).all(|k| slipped[k] || states[k] == NodeState::Open || before[k] == NodeState::Open)
    };
    let kind = if kind != EventKind::Sliding && crossing && crossed() { EventKind::Crossing } else { kind };
    if kind.ends_cycle() {
        slipped.iter_mut().for_each(|v| *v = false);
    }
    kind
}

/// Rate-consistency changes at lam until none is needed (continuous slip allowed).
fn settle_continuous(sv: &mut Solver, lam: f64, cont: bool, cap: usize, what: &str) -> Result<Affine> {
    for _ in 0..cap {
        let a = sv.solve()?;
        match sv.rate_fix(&a, lam, cont)? {
            Fix::None => return Ok(a),
            Fix::Changed(..) => {}
            Fix::Instability(_) => return Err(stuck_err(what, lam)),
        }
    }
    Err(stuck_err(what, lam))
}

fn hit_kind(h: Hit) -> EventKind {
    match h {
        Hit::Open => EventKind::Open,
        Hit::Close => EventKind::Close,
        Hit::Friction(_) => EventKind::Slip,
    }
}

fn stuck_err(phase: &str, lam: f64) -> Error {
    Error::Untrustworthy {
        detail: format!("the state update at {phase} parameter {lam:.6e} cycles without settling"),
        hint: "report this case; try another mesh or friction coefficient".into(),
    }
}

/// Applies the transition that reached equality at lam.
fn apply_hit(sv: &mut Solver, a: &Affine, lam: f64, i: usize, h: Hit) -> Result<()> {
    let u = a.b(i, lam);
    match h {
        Hit::Open => sv.set_state(i, NodeState::Open, 0.0),
        Hit::Close => sv.set_state(i, NodeState::Stick, u),
        Hit::Friction(s) => sv.set_state(i, NodeState::Slip(s), 0.0),
    }
}

impl Event {
    /// Whether the event ends a stick-slip cycle (a whole slip, or a front crossing).
    pub fn ends_cycle(&self) -> bool {
        self.kind.ends_cycle()
    }

    fn simple(kind: EventKind, st: &State, node: usize) -> Event {
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

fn push(out: &mut Run, pb: &Problem, ev: Event, st: State) -> Result<()> {
    pb.cancel.check()?;
    if out.events.len() >= pb.max_events {
        let before_slide = out.events.iter().take_while(|e| !e.ends_cycle());
        return Err(Error::EventCap {
            cap: pb.max_events,
            x: st.x,
            f_over_n: st.f / pb.n_force,
            precursors: before_slide.filter(|e| e.kind == EventKind::Precursor).count(),
            f_peak_over_n: out.events.iter().map(|e| e.f).fold(st.f, f64::max) / pb.n_force,
        });
    }
    out.max_violation = out.max_violation.max(st.violations.max());
    if !pb.keep_states {
        out.states.clear();
    }
    out.events.push(ev);
    out.states.push(st);
    Ok(())
}

fn finish(mut out: Run, sv: &Solver) -> Result<Run> {
    out.updates = sv.updates;
    out.refreshes = sv.refreshes;
    Ok(out)
}

/// Static-kinetic instability nucleated at i0 at fixed X = lam: applies the rule, relaxes,
/// re-sticks everything in contact. Returns the slipped region (first, last node), the
/// number of region nodes that slipped backwards, and whether every contact node was slipping
/// at the end of the relaxation (whole-interface slip).
fn instability(sv: &mut Solver, a: &Affine, lam: f64, i0: usize) -> Result<((usize, usize), usize, bool)> {
    let n = sv.n;
    let tf = tolerances::STATE * sv.fscale;
    let td = tolerances::STATE * sv.dscale;
    let mu_d = sv.law.mu_d();
    let mu_s = sv.law.mu_s();
    let u_start: Vec<f64> = (0..n).map(|i| a.b(i, lam)).collect();
    let t_start: Vec<f64> = (0..n).map(|i| a.f(i, lam)).collect();
    let dir = |t: f64| if t > 0.0 { -1.0 } else { 1.0 };
    let rule = match sv.law {
        Law::StaticKinetic { rule, .. } => rule,
        Law::Coulomb { .. } | Law::SlipWeakening { .. } => Rule::Paper,
    };
    // Every contact node sticks at its current position to start with.
    for i in 0..n {
        if sv.states[i] != NodeState::Open && sv.states[i] != NodeState::Stick {
            sv.set_state(i, NodeState::Stick, u_start[i])?;
        } else if sv.states[i] == NodeState::Stick && sv.anchor[i] != u_start[i] {
            sv.anchor[i] = u_start[i];
            sv.g = None;
            sv.last = None;
        }
    }
    let mut in_region = vec![false; n];
    let cap = tolerances::max_changes(n);
    match rule {
        Rule::Paper => {
            let above =
                |i: usize| sv.states[i] != NodeState::Open && t_start[i].abs() >= mu_d * a.f(n + i, lam) - tf;
            let (mut lo, mut hi) = (i0, i0);
            while lo > 0 && above(lo - 1) {
                lo -= 1;
            }
            while hi + 1 < n && above(hi + 1) {
                hi += 1;
            }
            let ch: Vec<(usize, NodeState, f64)> =
                (lo..=hi).map(|i| (i, NodeState::Slip(dir(t_start[i])), 0.0)).collect();
            (lo..=hi).for_each(|i| in_region[i] = true);
            sv.set_many(&ch)?;
            // Contact consistency of the relaxed state.
            let mut settled = false;
            for _ in 0..cap {
                let b = sv.solve()?;
                let mut changed = false;
                for i in 0..n {
                    let (p, g) = (b.f(n + i, lam), b.b(n + i, lam));
                    if sv.states[i] != NodeState::Open && p < -tf {
                        sv.set_state(i, NodeState::Open, 0.0)?;
                        changed = true;
                        break;
                    }
                    if sv.states[i] == NodeState::Open && g < -td {
                        // It lands where it is now: sticking it at its position from before
                        // the relaxation would drag it back, pull it off again, and cycle.
                        sv.set_state(i, NodeState::Stick, b.b(i, lam))?;
                        changed = true;
                        break;
                    }
                }
                if !changed {
                    settled = true;
                    break;
                }
            }
            if !settled {
                return Err(stuck_err("paper-rule relaxation (contact)", lam));
            }
        }
        Rule::Overdamped => {
            let mut awake = vec![false; n];
            // Where each node last started slipping: a node that closed in the relaxation
            // starts from where it landed, not from the event's start.
            let mut u_join = u_start.clone();
            in_region[i0] = true;
            awake[i0] = true;
            sv.set_state(i0, NodeState::Slip(dir(t_start[i0])), 0.0)?;
            let mut settled = false;
            for _ in 0..cap {
                let b = sv.solve()?;
                // Contact first.
                let mut changed = false;
                for i in 0..n {
                    let (p, g) = (b.f(n + i, lam), b.b(n + i, lam));
                    if sv.states[i] != NodeState::Open && p < -tf {
                        sv.set_state(i, NodeState::Open, 0.0)?;
                        changed = true;
                        break;
                    }
                    if sv.states[i] == NodeState::Open && g < -td {
                        // It lands where it is now: sticking it at its position from before
                        // the relaxation would drag it back, pull it off again, and cycle.
                        sv.set_state(i, NodeState::Stick, b.b(i, lam))?;
                        u_join[i] = b.b(i, lam);
                        changed = true;
                        break;
                    }
                }
                if changed {
                    continue;
                }
                // Backward slip: the worst re-sticks where it started slipping.
                let worst = (0..n)
                    .filter_map(|i| match sv.states[i] {
                        NodeState::Slip(s) => Some((i, s * (b.b(i, lam) - u_join[i]))),
                        _ => None,
                    })
                    .filter(|&(_, d)| d < -td)
                    .min_by(|x, y| x.1.total_cmp(&y.1));
                if let Some((i, _)) = worst {
                    sv.set_state(i, NodeState::Stick, u_join[i])?;
                    continue;
                }
                // Cascade: every stuck node above its threshold joins.
                let join: Vec<(usize, f64)> = (0..n)
                    .filter(|&i| sv.states[i] == NodeState::Stick)
                    .filter_map(|i| {
                        let (t, p) = (b.f(i, lam), b.f(n + i, lam));
                        let thr = if awake[i] { mu_d } else { mu_s };
                        (t.abs() > thr * p + tf).then_some((i, dir(t)))
                    })
                    .collect();
                if join.is_empty() {
                    settled = true;
                    break;
                }
                let ch: Vec<(usize, NodeState, f64)> =
                    join.iter().map(|&(i, s)| (i, NodeState::Slip(s), 0.0)).collect();
                for &(i, _) in &join {
                    awake[i] = true;
                    in_region[i] = true;
                }
                sv.set_many(&ch)?;
            }
            if !settled {
                return Err(stuck_err("overdamped relaxation", lam));
            }
        }
    }
    let b = sv.solve()?;
    let all_slip = sv.all_contact_slipping();
    let mut backslip = 0;
    let mut ch = Vec::new();
    for i in 0..n {
        if let NodeState::Slip(s) = sv.states[i] {
            let u = b.b(i, lam);
            if s * (u - u_start[i]) < -td {
                backslip += 1;
            }
            ch.push((i, NodeState::Stick, u));
        }
    }
    sv.set_many(&ch)?;
    let first = (0..n).find(|&i| in_region[i]).unwrap_or(i0);
    let last = (0..n).rev().find(|&i| in_region[i]).unwrap_or(i0);
    Ok(((first, last), backslip, all_slip))
}
