//! The active-set system: the node states, their anchors and the law's memory, and every
//! change to them, each notified to the operator in the order it is made (the dense
//! operator's round-off depends on that order).

use super::operator::{ActiveSet, Affine, Operator};
use super::{tolerances, NodeState, Phase, Problem};
use crate::error::Result;
use crate::law::Law;

pub(crate) struct Solver<'a> {
    law: Law,
    /// States, anchors, slip coefficients and springs, phase: what the operator solves for.
    pub(super) set: ActiveSet,
    op: Box<dyn Operator + 'a>,
    /// Per node: the threshold while stuck (mu_s; slip weakening: the value its slip has
    /// reached), the position where it last started slipping and its slip before that (since
    /// the last heal).
    mu_stick: Vec<f64>,
    slip0: Vec<f64>,
    slip_acc: Vec<f64>,
    /// Rate fixes stick the slipping node running back fastest before any other change.
    /// Node order alone can cycle: a node at its threshold slips, runs back together with a
    /// slipping neighbour, sticks first (lower index) and slips again, where sticking the
    /// neighbour would have settled it.
    pub(super) stick_fastest_first: bool,
    /// The exact weakening path is being followed: a node that starts slipping gets its
    /// row's tangent spring at once ([`super::simulation::settle_continuous`]).
    pub(super) tangent: bool,
    /// Set by that settle where a node's joining leaves no stable branch (cleared by the path).
    pub(super) lost: bool,
    /// Open nodes that close only by penetrating while not separating: a corner at zero
    /// pressure can cycle stick, slip, open (its pressure falls) and close (its gap closes, or
    /// it penetrates by round-off while separating).
    pub(super) hold_open: Vec<bool>,
    /// Force and displacement scales of the state tolerances: N/n and |V| under N bonded.
    pub(super) fscale: f64,
    pub(super) dscale: f64,
    pub(super) creep: f64,
    /// The last solve's result, until the states, anchors, coefficients or phase change.
    last: Option<Affine>,
    /// Checked at every fresh solve, so every loop of the solver (events, relaxations,
    /// Newton) stops soon after a host cancels, whether or not it reports progress.
    cancel: crate::Cancel,
}

impl<'a> Solver<'a> {
    /// Every node stuck at 0 in the drive phase, the operator's free system formed.
    pub(super) fn new(op: Box<dyn Operator + 'a>, n: usize, pb: &Problem) -> Result<Solver<'a>> {
        let set = ActiveSet {
            n,
            states: vec![NodeState::Stick; n],
            anchor: vec![0.0; n],
            mu_slip: vec![pb.law.mu_d(); n],
            spring: vec![0.0; n],
            spring_u: vec![0.0; n],
            phase: Phase::Drive,
            n_force: pb.n_force,
            border: op.border(),
        };
        let mut sv = Solver {
            law: pb.law,
            set,
            op,
            mu_stick: vec![pb.law.mu_s(); n],
            slip0: vec![0.0; n],
            slip_acc: vec![0.0; n],
            stick_fastest_first: false,
            tangent: false,
            lost: false,
            hold_open: vec![false; n],
            fscale: pb.n_force / n as f64,
            dscale: 1.0,
            creep: pb.creep_fraction,
            last: None,
            cancel: pb.cancel.clone(),
        };
        sv.op.refresh(&sv.set)?;
        Ok(sv)
    }

    pub(crate) fn n(&self) -> usize {
        self.set.n
    }
    pub(crate) fn states(&self) -> &[NodeState] {
        &self.set.states
    }
    pub(crate) fn iu(&self) -> usize {
        self.set.iu()
    }

    /// Displacement scale of the state tolerances, m.
    pub(super) fn dscale(&self) -> f64 {
        self.dscale
    }
    pub(super) fn law(&self) -> Law {
        self.law
    }
    /// Node i's slip coefficient (its magnitude, when slipping) and Newton spring.
    pub(super) fn mu_slip(&self, i: usize) -> f64 {
        self.set.mu_slip[i]
    }
    pub(super) fn spring(&self, i: usize) -> f64 {
        self.set.spring[i]
    }
    /// Where a stuck node is held, m.
    pub(super) fn anchor(&self, i: usize) -> f64 {
        self.set.anchor[i]
    }

    /// Until [`Self::release`]: rate fixes stick the slipping node running back fastest
    /// first (`by_speed`), and open node i (if given) closes only by penetrating while not
    /// separating (see the fields).
    pub(super) fn hold(&mut self, by_speed: bool, open: Option<usize>) {
        self.stick_fastest_first |= by_speed;
        if let Some(i) = open {
            self.hold_open[i] = true;
        }
    }
    pub(super) fn release(&mut self) {
        self.stick_fastest_first = false;
        self.hold_open.iter_mut().for_each(|h| *h = false);
    }

    /// Node i's stuck threshold (mu_s, or slip weakening's reached value).
    pub(super) fn mu_stick(&self, i: usize) -> f64 {
        self.mu_stick[i]
    }

    /// Node i's slip since the last heal if it is at u now (slipping in direction s).
    pub(super) fn slip_at(&self, i: usize, s: f64, u: f64) -> f64 {
        self.slip_acc[i] + s * (u - self.slip0[i])
    }

    /// Every node in contact slipping, and at least one in contact (a whole slip).
    pub(super) fn all_contact_slipping(&self) -> bool {
        let st = &self.set.states;
        st.iter().all(|s| *s != NodeState::Stick) && st.iter().any(|s| matches!(s, NodeState::Slip(_)))
    }

    /// Switches the loading phase (the prescribed values change).
    pub(super) fn set_phase(&mut self, phase: Phase) {
        self.set.phase = phase;
        self.op.pins_moved();
        self.last = None;
    }

    /// Moves a stuck node's anchor without a state change.
    pub(super) fn move_anchor(&mut self, i: usize, u: f64) {
        self.set.anchor[i] = u;
        self.op.pins_moved();
        self.last = None;
    }

    /// Changes node i's state, updating the operator.
    pub(super) fn set_state(&mut self, i: usize, new: NodeState, anchor: f64) -> Result<()> {
        let (old, old_anchor) = (self.set.states[i], self.set.anchor[i]);
        self.enter(i, new, anchor);
        self.op.change(&self.set, i, old, old_anchor)
    }

    /// Changes many nodes at once: one by one below [`tolerances::BATCH`] changes; above, as
    /// one bulk change (cheaper than O(m^2) per change when a whole region flips).
    pub(crate) fn set_many(&mut self, changes: &[(usize, NodeState, f64)]) -> Result<()> {
        if changes.len() < tolerances::BATCH {
            for &(i, st, a) in changes {
                self.set_state(i, st, a)?;
            }
            return Ok(());
        }
        for &(i, st, a) in changes {
            self.enter(i, st, a);
        }
        self.op.bulk(&self.set)
    }

    /// New coefficients of slipping nodes' rows (slip weakening): (node, mu, spring, the slip
    /// the spring is centred on).
    pub(super) fn set_coefficients(&mut self, changes: &[(usize, f64, f64, f64)]) -> Result<()> {
        self.last = None;
        let small = changes.len() < tolerances::BATCH;
        for &(i, mu, k, u) in changes {
            (self.set.mu_slip[i], self.set.spring[i], self.set.spring_u[i]) = (mu, k, u);
            if small {
                self.op.coefficient(&self.set, i)?;
            }
        }
        if small {
            Ok(())
        } else {
            self.op.refresh(&self.set)
        }
    }

    /// Node i's slip since the last heal, at u if it is slipping (slip weakening's memory).
    pub(crate) fn slip_memory(&self, i: usize, u: f64) -> f64 {
        match self.set.states[i] {
            NodeState::Slip(s) => self.slip_at(i, s, u),
            _ => self.slip_acc[i],
        }
    }

    /// Sets a node's slip memory (not slipping: its stuck threshold follows), for a caller
    /// that moved the nodes itself (`slide --dynamics` after an elastodynamic event).
    pub(crate) fn set_slip_memory(&mut self, i: usize, slip: f64) {
        self.slip_acc[i] = slip;
        if !matches!(self.set.states[i], NodeState::Slip(_)) {
            self.mu_stick[i] = self.law.kinetic(slip);
        }
    }

    /// Every node forgets its slip: thresholds back to mu_s (slip weakening's healing).
    pub(crate) fn heal_memory(&mut self) {
        self.slip_acc.iter_mut().for_each(|v| *v = 0.0);
        let mu_s = self.law.mu_s();
        self.mu_stick.iter_mut().for_each(|v| *v = mu_s);
    }

    /// Node i's new state and its bookkeeping (the operator is the caller's).
    fn enter(&mut self, i: usize, new: NodeState, anchor: f64) {
        let set = &mut self.set;
        match (set.states[i], new) {
            (NodeState::Slip(_), NodeState::Slip(_)) => {}
            (_, NodeState::Slip(_)) => {
                set.mu_slip[i] = self.law.kinetic(self.slip_acc[i]);
                self.slip0[i] = if set.states[i] == NodeState::Stick { set.anchor[i] } else { 0.0 };
            }
            (NodeState::Slip(s), NodeState::Stick) if matches!(self.law, Law::SlipWeakening { .. }) => {
                self.slip_acc[i] += (s * (anchor - self.slip0[i])).max(0.0);
                self.mu_stick[i] = self.law.kinetic(self.slip_acc[i]);
            }
            _ => {}
        }
        if !matches!(new, NodeState::Slip(_)) {
            set.spring[i] = 0.0;
        }
        set.states[i] = new;
        set.anchor[i] = anchor;
        self.last = None;
    }

    /// The affine solution of the current state set.
    pub(super) fn solve(&mut self) -> Result<Affine> {
        if let Some(a) = &self.last {
            return Ok(a.clone());
        }
        self.cancel.check()?;
        let a = self.op.solve(&self.set)?;
        self.last = Some(a.clone());
        Ok(a)
    }

    /// Entries of the free system's inverse at these free DOFs (row-major).
    pub(super) fn inverse_block(&mut self, dofs: &[usize]) -> Result<Vec<f64>> {
        self.op.inverse_block(&self.set, dofs)
    }

    /// Sign of the free system's determinant, where the operator keeps it (see
    /// [`Operator::det_sign`]).
    pub(super) fn det_sign(&mut self) -> Result<Option<f64>> {
        self.op.det_sign(&self.set)
    }

    /// Incremental updates and full factorisations of the operator so far.
    pub(super) fn counts(&self) -> (usize, usize) {
        self.op.counts()
    }
}
