//! The run's steps that read the static state: a recorded [`State`] from the static path,
//! settling the node states at a load, the kind of a state change, slip bookkeeping and a
//! dynamic event's arrest.

use crate::dynamics::driven::EventRecord;
use crate::dynamics::statics::{Load, Node, Path, Statics};
use crate::error::{Error, Result};
use crate::interface::events::{EventKind, NodeState, Phase, State, Violations};

pub(super) fn to_state(st: &Statics, p: &Path, lam: f64, phase: Phase) -> State {
    let n = st.n;
    let n_force = if phase == Phase::Normal { lam } else { st.n_force };
    let x = if phase == Phase::Normal { 0.0 } else { lam };
    let states: Vec<NodeState> = st
        .nodes
        .iter()
        .map(|s| match *s {
            Node::Stick { .. } => NodeState::Stick,
            Node::Slip { s } => NodeState::Slip(s),
            Node::Open => NodeState::Open,
        })
        .collect();
    let t_force: Vec<f64> = (0..n).map(|i| p.f(i, lam)).collect();
    let p_force: Vec<f64> = (0..n).map(|i| p.f(n + i, lam)).collect();
    // Friction and pressure violations relative to N/n.
    let scale = (n_force / n as f64).max(f64::MIN_POSITIVE);
    let mut v = Violations::default();
    for i in 0..n {
        if st.nodes[i] != Node::Open {
            v.pressure = v.pressure.max(-p_force[i] / scale);
            v.friction = v.friction.max((t_force[i].abs() - st.mu[i] * p_force[i]) / scale);
        }
    }
    v.equilibrium = (p.f(2 * n + 1, lam) + n_force).abs() / scale;
    State {
        phase,
        x,
        n_force,
        f: p.f(2 * n, lam),
        tilt: p.b(2 * n + 2, lam),
        v: p.b(2 * n + 1, lam),
        t_force,
        p_force,
        u: (0..n).map(|i| p.b(i, lam)).collect(),
        gap: (0..n).map(|i| p.b(n + i, lam)).collect(),
        states,
        violations: v,
    }
}

/// Solves and repairs the states at lam until they are consistent; applies changes to `st`.
pub(super) fn settle(
    st: &mut Statics,
    load: Load,
    lam: f64,
    ftol: f64,
    gtol: f64,
    cap: usize,
) -> Result<Path> {
    for _ in 0..cap {
        let p = st.solve(load)?;
        match st.violation(&p, lam, ftol, gtol) {
            None => return Ok(p),
            Some((i, to)) => {
                st.nodes[i] = match to {
                    Node::Stick { .. } => Node::Stick { anchor: p.b(i, lam) },
                    o => o,
                };
            }
        }
    }
    Err(Error::Untrustworthy {
        detail: format!("the static interface states did not settle in {cap} changes"),
        hint: "report the command line".into(),
    })
}

pub(super) fn change_kind(from: Node, to: Node) -> EventKind {
    match (from, to) {
        (_, Node::Open) => EventKind::Open,
        (Node::Open, _) => EventKind::Close,
        (_, Node::Slip { .. }) => EventKind::Slip,
        _ => EventKind::Stick,
    }
}

/// Slip path of the slipping nodes from lam to l along p.
pub(super) fn add_slip(st: &Statics, p: &Path, lam: f64, l: f64, slip: &mut [f64]) {
    for i in 0..st.n {
        if let Node::Slip { .. } = st.nodes[i] {
            slip[i] += (p.b1[i] * (l - lam)).abs();
        }
    }
}

pub(super) fn add_slip_done(st: &Statics, p: &Path, lam: f64, l: f64, slip: &mut [f64], done: &mut [f64]) {
    for i in 0..st.n {
        if let Node::Slip { .. } = st.nodes[i] {
            let ds = (p.b1[i] * (l - lam)).abs();
            slip[i] += ds;
            done[i] += ds;
        }
    }
}

/// The front's arrest (the first sample at which the tip is at its final position) and the
/// share of the force drop made before it.
pub(super) fn arrest(rec: &EventRecord, f_onset: f64, f_after: f64) -> Option<(f64, Option<f64>)> {
    let last = rec.tip.iter().rev().find(|x| x.is_finite())?;
    let k = rec.tip.iter().position(|x| x == last)?;
    let t = rec.t[k];
    let drop = f_onset - f_after;
    let frac = (drop.abs() > 0.0).then(|| (f_onset - rec.force[k]) / drop);
    Some((t, frac))
}
