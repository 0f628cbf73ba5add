//! What an event is: the vocabulary of `events.csv`, typed, so a misspelt kind is a compile
//! error instead of a count that is silently zero.

/// The kind of an event of the event-driven run (one recorded state follows each).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum EventKind {
    /// End of the normal loading with no node slipping.
    NormalLoad,
    /// End of the normal loading with the ends pre-slipped outwards.
    EdgePreslip,
    /// An instability whose slipped region starts at the first contact node (the trailing edge).
    Precursor,
    /// An instability (or a friction hit) away from the trailing edge and from an arrested front.
    Nucleation,
    /// An instability (or a friction hit) next to the run of slipped nodes grown from the
    /// trailing edge: an arrested front moving on.
    TipAdvance,
    /// An instability over every node in contact: a whole-interface slip (ends a cycle).
    Sliding,
    /// Not a whole slip, but it completes the run of slipped nodes across the interface
    /// ([`super::Problem::end_at_crossing`]; ends a cycle).
    Crossing,
    /// A node starts slipping continuously (no instability).
    Slip,
    /// A slipping node sticks.
    Stick,
    /// A node loses contact.
    Open,
    /// An open node closes.
    Close,
    /// A node with almost no pressure slides on continuously at mu_d (the Zeno guard).
    Creep,
    /// The end of the run (X reached x-max).
    End,
    /// A state sampled along a constant-velocity drive (`slide --dynamics --drive-velocity`):
    /// a row of the loading curve, not an event.
    Sample,
}

impl EventKind {
    pub const ALL: [EventKind; 14] = [
        EventKind::NormalLoad,
        EventKind::EdgePreslip,
        EventKind::Precursor,
        EventKind::Nucleation,
        EventKind::TipAdvance,
        EventKind::Sliding,
        EventKind::Crossing,
        EventKind::Slip,
        EventKind::Stick,
        EventKind::Open,
        EventKind::Close,
        EventKind::Creep,
        EventKind::End,
        EventKind::Sample,
    ];

    /// The name written in `events.csv`.
    pub fn name(self) -> &'static str {
        match self {
            EventKind::NormalLoad => "normal-load",
            EventKind::EdgePreslip => "edge-preslip",
            EventKind::Precursor => "precursor",
            EventKind::Nucleation => "nucleation",
            EventKind::TipAdvance => "tip-advance",
            EventKind::Sliding => "sliding",
            EventKind::Crossing => "crossing",
            EventKind::Slip => "slip",
            EventKind::Stick => "stick",
            EventKind::Open => "open",
            EventKind::Close => "close",
            EventKind::Creep => "creep",
            EventKind::End => "end",
            EventKind::Sample => "sample",
        }
    }

    /// Whether an event of this kind ends a stick-slip cycle (a whole slip, or a front crossing).
    pub fn ends_cycle(self) -> bool {
        matches!(self, EventKind::Sliding | EventKind::Crossing)
    }
}

impl std::fmt::Display for EventKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::EventKind;

    #[test]
    fn names_are_distinct_and_two_kinds_end_a_cycle() {
        let mut names: Vec<_> = EventKind::ALL.iter().map(|k| k.name()).collect();
        names.sort();
        names.dedup();
        assert_eq!(names.len(), EventKind::ALL.len());
        let ending: Vec<_> = EventKind::ALL.iter().filter(|k| k.ends_cycle()).collect();
        assert_eq!(ending, [&EventKind::Sliding, &EventKind::Crossing]);
    }
}
