//! The run's steps on the event solver's active set: the slip-weakening relaxation at a fixed
//! drive (stable, or the onset of a dynamic event), the static state after an event, what an
//! event was, and its arrest.

use crate::dynamics::driven::{arrest_sample, DynState, EventRecord};
use crate::error::Result;
use crate::interface::events::active::Solver;
use crate::interface::events::operator::Affine;
use crate::interface::events::simulation::settle_continuous;
use crate::interface::events::{EventKind, NodeState};

/// Fixed-point iterates of one relaxation before it counts as unstable.
const FIXED_POINT_ITERATES: usize = 30;

/// Brings the slipping coefficients to their slips at fixed U_H = lam by fixed point (each
/// iterate one solve with the coefficients frozen, the states made consistent after it).
/// None: it settled (an iterate moved no slipping node by 1e-3 D_c); Some(the last iterate):
/// it diverged (an iterate moved a node by more than D_c/2, or 30 iterates did not settle),
/// so the patch is unstable and the event runs dynamically from there. `done`: slip since
/// each coefficient was last brought to its slip (reset for the slipping nodes).
pub(super) fn relax(
    sv: &mut Solver,
    a: &Affine,
    lam: f64,
    dc: f64,
    cap: usize,
    done: &mut [f64],
) -> Result<Option<Affine>> {
    let (n, law) = (sv.n(), sv.law());
    let mut a_cur = a.clone();
    for _ in 0..FIXED_POINT_ITERATES {
        let mut change = Vec::new();
        for k in 0..n {
            if let NodeState::Slip(_) = sv.states()[k] {
                done[k] = 0.0;
                let mu = law.kinetic(sv.slip_memory(k, a_cur.b(k, lam)));
                if mu != sv.mu_slip(k) {
                    change.push((k, mu, 0.0, 0.0));
                }
            }
        }
        sv.set_coefficients(&change)?;
        let a_new = settle_continuous(sv, lam, true, cap, "slip-weakening relaxation")?;
        let jump = (0..n)
            .filter(|&k| matches!(sv.states()[k], NodeState::Slip(_)))
            .map(|k| (a_new.b(k, lam) - a_cur.b(k, lam)).abs())
            .fold(0.0, f64::max);
        a_cur = a_new;
        if jump < 1e-3 * dc {
            return Ok(None);
        }
        if jump > 0.5 * dc {
            break;
        }
    }
    Ok(Some(a_cur))
}

/// The static state after a dynamic event at U_H = lam: every base node anchored where the
/// event left it (or open), its slip memory the event's (healed to 0 when some node weakened
/// fully, an instability: every node, or with `slipped_only` those whose event slip passed
/// the event's threshold), the states made consistent.
#[allow(clippy::too_many_arguments)]
pub(super) fn anchor_after(
    sv: &mut Solver,
    base: &[usize],
    ds: &DynState,
    ev: &EventRecord,
    slipped_only: bool,
    lam: f64,
    cap: usize,
    done: &mut [f64],
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
    done.iter_mut().for_each(|v| *v = 0.0);
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
    let (mut a, mut b) = (node, node);
    while a > 0 && went[a - 1] {
        a -= 1;
    }
    while b + 1 < n && went[b + 1] {
        b += 1;
    }
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
    let crossed = crate::interface::events::classify::crossed(slipped, |k| open[k]);
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
