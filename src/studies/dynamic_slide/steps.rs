//! The held mode's steps on the event solver's active set: the static state after a dynamic
//! event, what an event was, and its arrest.

use crate::dynamics::driven::{arrest_sample, DynState, EventRecord};
use crate::error::Result;
use crate::interface::events::handoff::{crossed, settle_continuous, Affine, Solver};
use crate::interface::events::{EventKind, NodeState};

/// The static state after a dynamic event at U_H = lam: every base node anchored where the
/// event left it (or open), its slip memory the event's (healed to 0 when some node weakened
/// fully, an instability: every node, or with `slipped_only` those whose event slip passed
/// the event's threshold), the states made consistent.
pub(super) fn anchor_after(
    sv: &mut Solver,
    base: &[usize],
    ds: &DynState,
    ev: &EventRecord,
    slipped_only: bool,
    lam: f64,
    cap: usize,
) -> Result<Affine> {
    let change: Vec<(usize, NodeState, f64)> = base
        .iter()
        .enumerate()
        .map(
            |(b, &k)| if ev.open[b] { (b, NodeState::Open, 0.0) } else { (b, NodeState::Stick, ds.u[2 * k]) },
        )
        .collect();
    sv.set_many(&change)?;
    if ev.weakened && !slipped_only {
        sv.heal_memory();
    } else if ev.weakened {
        for (b, &d) in ds.d.iter().enumerate() {
            sv.set_slip_memory(b, if ev.slip[b] > ev.threshold { 0.0 } else { d });
        }
    } else {
        for (b, &d) in ds.d.iter().enumerate() {
            sv.set_slip_memory(b, d);
        }
    }
    settle_continuous(sv, lam, true, cap, "drive after a dynamic event")
}

/// What a dynamic event was, its nucleation node and slipped run (nodes whose event slip
/// passed D_c/100, around the nucleation node): see [`kind_of`].
pub(super) fn classify_event(ev: &EventRecord, dc: f64, n: usize) -> (EventKind, usize, (usize, usize)) {
    let went: Vec<bool> = ev.slip.iter().take(n).map(|&s| s > dc / 100.0).collect();
    kind_of(ev, &went)
}

/// The kind, nucleation node and slipped run (the nodes that `went`, around the nucleation
/// node) of an event: `precursor` (the run starts at the first contact node), `nucleation`
/// (elsewhere), `sliding` (every contact node), `slip` (no node weakened fully, or no
/// nucleation: not an instability).
pub(super) fn kind_of(ev: &EventRecord, went: &[bool]) -> (EventKind, usize, (usize, usize)) {
    let n = went.len();
    let node = ev.nucleation.unwrap_or(0);
    let (a, b) = crate::numeric::run_around(node, n, |k| went[k]);
    let first_contact = (0..n).find(|&k| !ev.open[k] || went[k]).unwrap_or(0);
    let last_contact = (0..n).rev().find(|&k| !ev.open[k] || went[k]).unwrap_or(n - 1);
    let kind = if !ev.weakened || ev.nucleation.is_none() {
        EventKind::Slip
    } else if a <= first_contact && b >= last_contact {
        EventKind::Sliding
    } else if a <= first_contact {
        EventKind::Precursor
    } else {
        EventKind::Nucleation
    };
    (kind, node, (a, b))
}

/// With `on`, a `crossing`: an instability that is not a whole slip but completes the run of
/// nodes slipped by instabilities since the last cycle end (`slipped`, updated) from the first
/// contact node to the last but one, open nodes no obstacle (the quasi-static solver's rule,
/// [`crate::interface::events::Problem::end_at_crossing`]). `open`: the nodes open after it.
pub(super) fn crossing(
    kind: EventKind,
    region: (usize, usize),
    open: &[bool],
    slipped: &mut [bool],
    on: bool,
) -> EventKind {
    if matches!(kind, EventKind::Precursor | EventKind::Nucleation) {
        (region.0..=region.1).for_each(|k| slipped[k] = true);
    }
    let crossed = crossed(slipped, |k| open[k]);
    let kind = if on && matches!(kind, EventKind::Precursor | EventKind::Nucleation) && crossed {
        EventKind::Crossing
    } else {
        kind
    };
    if kind.ends_cycle() {
        slipped.iter_mut().for_each(|v| *v = false);
    }
    kind
}

/// The front's arrest time ([`arrest_sample`]) and the force drop made by then over the
/// event's, (F_onset - F(t_arrest)) / (F_onset - F_after): not a share, it exceeds 1 when the
/// force undershoots its final value at the arrest and recovers after.
pub(super) fn arrest(rec: &EventRecord, f_onset: f64, f_after: f64) -> Option<(f64, Option<f64>)> {
    let k = arrest_sample(&rec.tip)?;
    let t = rec.t[k];
    let drop = f_onset - f_after;
    let frac = (drop.abs() > 0.0).then(|| (f_onset - rec.force[k]) / drop);
    Some((t, frac))
}

#[cfg(test)]
mod tests {
    use super::*;
    use EventKind::{Crossing, Nucleation, Precursor, Sliding, Slip};

    /// Eight nodes, the last one open: a precursor, an unconnected nucleation and the
    /// instability joining them complete the run 0..=6 (the last contact node left out), so
    /// the third is a crossing and the record clears; without `on` it stays a nucleation.
    #[test]
    fn the_instability_completing_the_slipped_run_is_a_crossing() {
        let mut open = [false; 8];
        open[7] = true;
        for on in [true, false] {
            let mut slipped = [false; 8];
            assert_eq!(crossing(Precursor, (0, 2), &open, &mut slipped, on), Precursor);
            assert_eq!(crossing(Slip, (3, 3), &open, &mut slipped, on), Slip); // not an instability
            assert_eq!(crossing(Nucleation, (5, 5), &open, &mut slipped, on), Nucleation);
            let joined = crossing(Nucleation, (3, 4), &open, &mut slipped, on);
            assert_eq!(joined, if on { Crossing } else { Nucleation });
            assert_eq!(slipped.iter().filter(|&&s| s).count(), if on { 0 } else { 6 });
        }
        // A whole slip ends the cycle by itself and clears the record.
        let mut slipped = [true, false, false, false, false, false, false, false];
        assert_eq!(crossing(Sliding, (0, 6), &open, &mut slipped, true), Sliding);
        assert!(!slipped.iter().any(|&s| s));
    }
}
