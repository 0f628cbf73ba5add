//! The drive phase under linear slip weakening.
//!
//! Between state changes the response is no longer linear in X (a slipping node's coefficient
//! depends on its slip), so X advances in steps: to the next threshold of a stuck node, open
//! or close (exact, as for the other laws), and by at most the X that the current slip rates
//! turn into D_c/20 of slip. At each X the coefficients are brought to their slips by fixed
//! point (each iterate a linear solve with the coefficients frozen; an overdamped relaxation
//! at fixed X). A stable slip patch converges in a few iterates; past its critical length the
//! iterates run away until the nodes reach mu_d or the front arrests: a step whose relaxation
//! moves some node by more than D_c/2 at fixed X (ten times what the step control allows a
//! stable step) is an instability. It is classified like a static-kinetic event, and when it
//! ends every node sticks and heals to mu_s, as in the paper's model. Between instabilities a
//! node keeps the slip it has accumulated since the last one, slipping or stuck: a node that
//! stops in a stable process zone resumes at the coefficient it had reached. A slipping node
//! whose relaxation would move it backwards within a step sticks where the step started.

use super::{
    classify, ends_cycle, finish, push, stuck_err, Affine, Event, Fix, NodeState, Problem, Run, Solver,
};
use crate::error::Result;

/// Steps per D_c of slip of the fastest slipping node (step control).
const STEPS_PER_DC: f64 = 20.0;

pub(super) fn drive(
    sv: &mut Solver,
    mut out: Run,
    pb: &Problem,
    dc: f64,
    mut prev_u: Vec<f64>,
    progress: &dyn Fn(f64),
) -> Result<Run> {
    let n = sv.n;
    let x_end = pb.x_max.unwrap_or(f64::INFINITY);
    let mut lam = 0.0;
    let mut slipped = vec![false; n];
    let cap = 20 * n + 100;
    let frac = |out: &Run, lam: f64| -> f64 {
        let by_x = if x_end.is_finite() { lam / x_end } else { 0.0 };
        by_x.max(out.sliding_events as f64 / pb.cycles.max(1) as f64).min(1.0)
    };
    let mut idle = 0;
    sv.heal_memory();
    loop {
        let a0 = sv.solve()?;
        let u_pre: Vec<f64> = (0..n).map(|i| a0.b(i, lam)).collect();
        let f_pre = a0.f(sv.iu(), lam);
        let states_pre = sv.states.clone();
        let mu_pre = sv.mu_slip.clone();
        let (a, touched) = settle(sv, lam, cap, &u_pre)?;
        let moved: Vec<f64> = (0..n).map(|i| (a.b(i, lam) - u_pre[i]).abs()).collect();
        let (i0, jump) =
            moved.iter().enumerate().fold((0, 0.0), |b, (i, &m)| if m > b.1 { (i, m) } else { b });
        if jump > 0.5 * dc {
            // Instability: the region is the connected run around the largest jump of nodes
            // that slipped in the relaxation by more than 1 % of D_c (a corner that crept a
            // little at the other end is not part of it).
            let went = |i: usize| touched[i] && moved[i] > 0.01 * dc;
            let mut first = i0;
            while first > 0 && went(first - 1) {
                first -= 1;
            }
            let mut last = i0;
            while last + 1 < n && went(last + 1) {
                last += 1;
            }
            let all_slipping = sv.all_contact_slipping();
            // Nucleation: the most weakened node slipping when the step began.
            let node = (first..=last)
                .filter(|&i| matches!(states_pre[i], NodeState::Slip(_)))
                .min_by(|&i, &j| mu_pre[i].total_cmp(&mu_pre[j]))
                .unwrap_or(i0);
            let kind = classify(&states_pre, &sv.states, (first, last), &mut slipped, pb.end_at_crossing);
            heal(sv, &a, lam)?;
            let b = sv.solve()?;
            let st = sv.record(&b, lam, Some(&prev_u));
            prev_u.clone_from(&st.u);
            if ends_cycle(kind) {
                out.sliding_events += 1;
            }
            let ev = Event {
                kind,
                f: f_pre,
                x: lam,
                node,
                region: Some((first, last)),
                f_relaxed: st.f,
                backslip: 0,
                all_slipping,
            };
            push(&mut out, pb, ev, st)?;
            progress(frac(&out, lam));
            if out.sliding_events >= pb.cycles {
                return finish(out, sv);
            }
            continue;
        }
        if sv.states != states_pre {
            // A stable change: nodes starting or stopping to slip, opening or closing.
            let i = (0..n).find(|&i| sv.states[i] != states_pre[i]).unwrap_or(0);
            let kind = match (states_pre[i], sv.states[i]) {
                (NodeState::Stick, NodeState::Slip(_)) => {
                    let next_to =
                        |k: Option<usize>| k.is_some_and(|k| matches!(sv.states[k], NodeState::Slip(_)));
                    let neighbour = next_to(i.checked_sub(1)) || next_to((i + 1 < n).then_some(i + 1));
                    if neighbour {
                        "tip-advance"
                    } else {
                        "nucleation"
                    }
                }
                (NodeState::Slip(_), NodeState::Stick) => "stick",
                (_, NodeState::Open) => "open",
                _ => "close",
            };
            let st = sv.record(&a, lam, Some(&prev_u));
            prev_u.clone_from(&st.u);
            push(&mut out, pb, Event::simple(kind, &st, i), st)?;
        }
        // Steady sliding: every contact node slipping at mu_d; nothing re-sticks any more.
        let steady = sv.all_contact_slipping()
            && (0..n).all(|i| sv.states[i] == NodeState::Open || sv.mu_slip[i] <= sv.law.mu_d());
        if steady {
            out.sliding_events += 1;
            let st = sv.record(&a, lam, Some(&prev_u));
            push(&mut out, pb, Event::simple("sliding", &st, 0), st)?;
            progress(1.0);
            return finish(out, sv);
        }
        // Next X: the next exact threshold, or the slip-rate step.
        let rate = (0..n)
            .filter(|&i| matches!(sv.states[i], NodeState::Slip(_)))
            .map(|i| a.b1[i].abs())
            .fold(0.0, f64::max);
        let by_slip = if rate > 0.0 { dc / STEPS_PER_DC / rate } else { f64::INFINITY };
        let by_event = sv.next_event(&a, lam).map_or(f64::INFINITY, |e| e.0);
        let d = by_slip.min(by_event);
        if lam + d >= x_end {
            if !x_end.is_finite() {
                return Err(crate::error::Error::input(
                    "x-max",
                    "the loading reaches no further event and no end was given; give --x-max",
                ));
            }
            let st = sv.record(&a, x_end, Some(&prev_u));
            push(&mut out, pb, Event::simple("end", &st, 0), st)?;
            progress(1.0);
            return finish(out, sv);
        }
        idle = if d == 0.0 { idle + 1 } else { 0 };
        if idle > cap {
            return Err(stuck_err("slip-weakening drive", lam));
        }
        // An exact threshold hit is applied by the next settle's rate problem.
        lam += d;
        progress(frac(&out, lam));
    }
}

/// Equilibrium at fixed X with every slipping node's coefficient at its slip: state changes
/// first (one at a time, as for the other laws), then the coefficients. Returns the solution
/// and the nodes that slipped at some iterate.
fn settle(sv: &mut Solver, lam: f64, cap: usize, u_pre: &[f64]) -> Result<(Affine, Vec<bool>)> {
    let n = sv.n;
    // Looser than the state tolerances (1e-9): a node set slipping at its threshold by its
    // rate may settle a force tolerance's worth behind where it stood.
    let td = 1e-6 * sv.dscale;
    let mut touched = vec![false; n];
    // A relaxation may run through every node and its coefficients converge geometrically.
    for _ in 0..50 * cap {
        let a = sv.solve()?;
        if let Fix::Changed(..) = sv.rate_fix(&a, lam, true)? {
            continue;
        }
        let mut change = Vec::new();
        let mut back = None;
        for i in 0..n {
            if let NodeState::Slip(s) = sv.states[i] {
                touched[i] = true;
                let u = a.b(i, lam);
                if s * (u - u_pre[i]) < -td {
                    back = Some(i);
                    break;
                }
                let mu = sv.law.kinetic(sv.slip_acc[i] + s * (u - sv.slip0[i]));
                if (mu - sv.mu_slip[i]).abs() > 1e-12 * sv.law.mu_s() {
                    change.push((i, mu));
                }
            }
        }
        if let Some(i) = back {
            sv.set_state(i, NodeState::Stick, u_pre[i])?;
            continue;
        }
        if change.is_empty() {
            return Ok((a, touched));
        }
        sv.set_coefficients(&change)?;
    }
    Err(stuck_err("slip-weakening relaxation", lam))
}

/// Every slipping node sticks where it is and heals to mu_s (end of an instability).
fn heal(sv: &mut Solver, a: &Affine, lam: f64) -> Result<()> {
    let ch: Vec<(usize, NodeState, f64)> = (0..sv.n)
        .filter(|&i| matches!(sv.states[i], NodeState::Slip(_)))
        .map(|i| (i, NodeState::Stick, a.b(i, lam)))
        .collect();
    sv.set_many(&ch)?;
    sv.heal_memory();
    Ok(())
}
