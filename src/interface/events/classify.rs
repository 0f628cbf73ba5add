//! The classification of instabilities: where an event's slipped region lies relative to the
//! contact and to the front grown from the trailing edge since the last cycle.

use super::{EventKind, NodeState};

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
pub(super) fn classify(
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
    let open = |k: usize| states[k] == NodeState::Open || before[k] == NodeState::Open;
    let kind = if kind != EventKind::Sliding && crossing && crossed(slipped, open) {
        EventKind::Crossing
    } else {
        kind
    };
    if kind.ends_cycle() {
        slipped.iter_mut().for_each(|v| *v = false);
    }
    kind
}

/// Whether the nodes `slipped` (or `open`) run from the first contact node to the last but
/// one: a front crossing. The leading corner node is left out: its pressure is singular in the
/// discrete model and it holds after every node behind it has slipped (overdamped rule at
/// (0.5, 0.5)). The quasi-static and the dynamic classifications share it.
pub(crate) fn crossed(slipped: &[bool], open: impl Fn(usize) -> bool) -> bool {
    let contact = || (0..slipped.len()).filter(|&k| !open(k));
    let (Some(c0), Some(c1)) = (contact().next(), contact().next_back()) else { return false };
    (c0..c1).all(|k| slipped[k] || open(k))
}

#[cfg(test)]
mod tests {
    use super::*;
    use NodeState::{Open, Stick};

    /// One cycle on five nodes in contact: a precursor from the trailing edge, a tip advance
    /// next to it, a nucleation ahead of the front, then a whole slip that clears the memory.
    #[test]
    fn a_cycle_of_hand_made_events() {
        let st = [Stick; 5];
        let mut slipped = [false; 5];
        assert_eq!(classify(&st, &st, (0, 1), &mut slipped, false), EventKind::Precursor);
        assert_eq!(slipped, [true, true, false, false, false]);
        assert_eq!(classify(&st, &st, (2, 2), &mut slipped, false), EventKind::TipAdvance);
        assert_eq!(classify(&st, &st, (4, 4), &mut slipped, false), EventKind::Nucleation);
        assert_eq!(slipped, [true, true, true, false, true]);
        assert_eq!(classify(&st, &st, (0, 4), &mut slipped, false), EventKind::Sliding);
        assert_eq!(slipped, [false; 5], "a whole slip ends the cycle");
    }

    /// An open trailing node moves the trailing edge; with `crossing`, the event that completes
    /// the slipped run up to the node before the leading corner ends the cycle.
    #[test]
    fn open_nodes_and_front_crossings() {
        let st = [Open, Stick, Stick, Stick, Stick];
        let mut slipped = [false; 5];
        assert_eq!(classify(&st, &st, (1, 2), &mut slipped, true), EventKind::Precursor);
        // The region covers every node in contact: a whole slip even though node 0 is open.
        let mut s2 = slipped;
        assert_eq!(classify(&st, &st, (1, 4), &mut s2, true), EventKind::Sliding);
        // Node 3 joins the run 1..=2: nodes 0 (open) to 3 have slipped, the leading corner
        // (node 4) holds: a crossing, which clears the memory.
        assert_eq!(classify(&st, &st, (3, 3), &mut slipped, true), EventKind::Crossing);
        assert_eq!(slipped, [false; 5]);
        // Without `crossing` the same event is a tip advance.
        let mut slipped = [false, true, true, false, false];
        assert_eq!(classify(&st, &st, (3, 3), &mut slipped, false), EventKind::TipAdvance);
    }
}
