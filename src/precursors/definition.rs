//! What a precursor of the frictional FE is: the one definition behind every count, F_i and
//! x_i that tribofe reports (`precursors --fe` and its series, `--map --fe`, `slide`, `sweep`,
//! `edges`, the Python package), so the same run gives the same numbers everywhere.
//!
//! The paper (Scheibert & Dysthe, EPL 2010) calls precursor an event that nucleates at the
//! trailing edge, arrests at x_i inside the contact, and comes before the first event that
//! reaches the leading edge; F_i is the force at which it nucleates, n the number of them. The
//! FE event solver records more than the model has, and each choice below says why:
//! - A *cascade* (all instabilities at one drive displacement X) is one event. The solver
//!   relaxes one slipped region at a time; when a relaxation overloads a stuck node the next
//!   instability follows at the same X, with no drive in between: one slip in time, which an
//!   independent contact solver sees as one (on the paper's scene the first long slip starts at
//!   F = 0.7319 mu_s N, the first of its two relaxations).
//! - *Where it nucleates*: at the trailing end of the stuck contact. The trailing corner
//!   opens (at most 0.31 t on fine meshes, validation/edges) or creeps at mu_d (2 nodes at
//!   h = t), and an instability's slipped region starts at the first node that neither
//!   opened nor creeps; the slip nucleates a few nodes further in (1.5 t on the paper's
//!   scene, 4 t at t/L = 1/1600). So: the cascade's first instability whose slipped region
//!   starts within [`ZONE_T`] t of the trailing edge x = -L/2 and whose nucleation node lies
//!   within [`ZONE_T`] t of that start. A slip nucleating deeper and spreading back to the
//!   edge is not one (the overdamped rule's re-slips inside the slipped zone). The slipped
//!   region is that instability's region joined with the cascade's regions that touch it.
//! - *Long*: a slipped region longer than [`LONG_T`] t; shorter ones are edge-zone slips.
//! - *Advancing* (the count n to compare with the paper's n): its arrest point lies more than
//!   [`ADVANCE_T`] t beyond the last counted one's (the trailing edge for the first). The
//!   model's precursors each move the front on; the FE adds renucleations that arrest within
//!   a few elements of the previous front, whose number grows with refinement.
//! - F_i is the drive force at the cascade's onset (the state before its first relaxation),
//!   x_i the arrest point: the last node of the slipped region. F_1, x_1 are those of the
//!   first advancing precursor.
//! - *Front advances* ([`advances`]), the paper's n where fronts do not restart at the edge:
//!   in elastodynamics an arrested front runs on by renucleating at its own tip (384 of 411
//!   instabilities on the paper's scene, validation/dynamics/paper), or at the tip of a
//!   quasi-static preslip zone longer than 5 t, which the trailing-edge rule above does not
//!   count. The front is the far end of the runs slipped since the cycle began (by its
//!   instabilities, and the preslip just before each) reached from the trailing edge across
//!   stuck gaps of at most [`ZONE_T`] t; a cascade advances it when it moves that end more
//!   than [`ADVANCE_T`] t beyond the last counted advance's.
//!
//! Plain data in, plain data out: the studies hand over their events as [`Slip`]s.

/// Width of the trailing-edge zone, in block thicknesses t: a precursor's slipped region
/// starts within it from x = -L/2 and its nucleation node lies within it from that start.
pub const ZONE_T: f64 = 5.0;
/// Slipped length above which a precursor is long, in t.
pub const LONG_T: f64 = 5.0;
/// Front advance above which a precursor counts in n, in t.
pub const ADVANCE_T: f64 = 5.0;

/// The definition in one line, printed under every summary that reports precursors.
pub const DEFINITION: &str = "precursor: the instabilities at one drive X (one cascade) before the cycle ends, nucleating at the trailing edge (slip starting within 5 t of x = -L/2, nucleus within 5 t of that start; from x = +L/2 instead when H < t/2, where the block's own couple makes the pressure lowest at the leading edge); long: slipped > 5 t; n (compare with the paper's n): those whose arrest lies > 5 t beyond the last counted one's; F_i: drive force at the cascade's onset; x_i: its arrest point";
/// The front-advance count in one line, printed where it is reported.
pub const ADVANCES: &str = "front advance: a cascade before the cycle ends that moves the front, the far end of the runs slipped since the cycle began (by its instabilities, and quasi-statically before each) reached from the edge of lowest pressure (trailing, or leading when H < t/2) across stuck gaps of at most 5 t, more than 5 t beyond the last counted advance's; F: drive force at its onset; x: the new front";

/// One instability of a frictional run, as the definition reads it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Slip {
    /// Index of the event in the run's event list (carried through to [`Precursor`]).
    pub event: usize,
    /// Drive displacement X, m: instabilities at the same X form one cascade.
    pub x_drive: f64,
    /// Drive force before its relaxation (any unit: F_i comes out in it).
    pub f: f64,
    /// Nucleation node and slipped region (first, last node): indices into the node positions.
    pub node: usize,
    pub region: (usize, usize),
    /// It ends the stick-slip cycle (a whole slip or a front crossing).
    pub ends_cycle: bool,
    /// The first run of slipping nodes (first, last node) in the state just before it, where
    /// known: quasi-static preslip, which joins a front to the trailing edge when it starts
    /// there ([`advances`]; the trailing-edge rule of [`find`] does not read it).
    pub preslip: Option<(usize, usize)>,
}

/// One precursor (a cascade).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Precursor {
    /// Events of the cascade's first and last instability (the state after `last_event` is the
    /// arrested one).
    pub first_event: usize,
    pub last_event: usize,
    /// F_i: the drive force at the cascade's onset, in the unit of [`Slip::f`].
    pub f: f64,
    /// Nucleation node (within the trailing-edge zone) and slipped region (first, last node).
    pub node: usize,
    pub region: (usize, usize),
    /// Slipped region longer than [`LONG_T`] t.
    pub long: bool,
    /// Counted in n: arrest more than [`ADVANCE_T`] t beyond the last counted precursor's.
    pub advancing: bool,
}

impl Precursor {
    /// x_i: the arrest node (the region's last).
    pub fn arrest(&self) -> usize {
        self.region.1
    }
}

/// The precursors of a run's first cycle, in order.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Precursors {
    pub all: Vec<Precursor>,
}

impl Precursors {
    /// n: the advancing precursors (the count to compare with the paper's n).
    pub fn n(&self) -> usize {
        self.counted().count()
    }
    /// Those with a slipped region longer than [`LONG_T`] t.
    pub fn n_long(&self) -> usize {
        self.all.iter().filter(|p| p.long).count()
    }
    /// Every precursor, advancing or not.
    pub fn n_all(&self) -> usize {
        self.all.len()
    }
    /// The advancing precursors, i = 1..n.
    pub fn counted(&self) -> impl Iterator<Item = &Precursor> {
        self.all.iter().filter(|p| p.advancing)
    }
    /// The first advancing precursor (F_1, x_1).
    pub fn first(&self) -> Option<&Precursor> {
        self.counted().next()
    }
}

/// One advance of the slip front ([`advances`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Advance {
    /// Event of the cascade's first instability.
    pub first_event: usize,
    /// Drive force at the cascade's onset, in the unit of [`Slip::f`].
    pub f: f64,
    /// The front after the cascade: the last node of the run slipped from the trailing edge.
    pub front: usize,
    /// Nucleation node of the cascade's first instability behind the new front.
    pub node: usize,
}

/// The front advances among `slips` (a run's instabilities in order) on the interface nodes
/// `x` (m, ascending from the trailing edge) under a block of thickness `t` (m), up to the
/// first cascade that ends the cycle. A tip renucleation counts as well as a slip restarting
/// at the trailing edge.
pub fn advances(slips: &[Slip], x: &[f64], t: f64) -> Vec<Advance> {
    let mut out = Vec::new();
    let Some(&x0) = x.first() else { return out };
    let mut counted = x0;
    // The cycle's slipped runs (node ranges): sorted, disjoint, not touching.
    let mut runs: Vec<(usize, usize)> = Vec::new();
    for cascade in cascades(slips) {
        if cascade.iter().any(|s| s.ends_cycle) {
            break;
        }
        runs.extend(cascade.iter().map(|s| (s.region.0.min(s.node), s.region.1.max(s.node))));
        runs.extend(cascade.iter().filter_map(|s| s.preslip));
        runs.sort_unstable();
        runs.dedup_by(|next, kept| {
            let touches = next.0 <= kept.1 + 1;
            if touches {
                kept.1 = kept.1.max(next.1);
            }
            touches
        });
        // The front: the far end of the runs reached from the trailing edge across stuck gaps
        // of at most ZONE_T t (the definition's resolution: an open corner, a lone slipping
        // node, a renucleation just ahead of an arrested tip).
        let mut b = None;
        let mut reach = x0;
        for &(c, d) in &runs {
            let (Some(&xc), Some(&xd)) = (x.get(c), x.get(d)) else { break };
            if xc - reach > ZONE_T * t {
                break;
            }
            if xd >= reach {
                (b, reach) = (Some(d), xd);
            }
        }
        let Some(b) = b else { continue };
        let xb = reach;
        if xb > counted + ADVANCE_T * t {
            counted = xb;
            let seed = cascade.iter().find(|s| s.region.1 <= b).unwrap_or(&cascade[0]);
            out.push(Advance { first_event: cascade[0].event, f: cascade[0].f, front: b, node: seed.node });
        }
    }
    out
}

/// The edge the first cycle's slip nucleates at: where the interior pressure is lowest. The
/// paper's torque makes it the trailing edge (x = -L/2); where the pressure slope reverses (H
/// below t/2, where the block's own shear couple wins: the interior slope goes like H - t/2,
/// docs/check.md) it is the leading edge, and the definitions run from there
/// ([`find_from_edge`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Edge {
    Trailing,
    Leading,
}

impl Edge {
    pub fn name(self) -> &'static str {
        match self {
            Edge::Trailing => "trailing",
            Edge::Leading => "leading",
        }
    }

    /// The edge of lowest interior pressure for a drive at height `h` over a block `t` thick.
    pub fn of_lowest_pressure(h: f64, t: f64) -> Edge {
        if h < 0.5 * t {
            Edge::Leading
        } else {
            Edge::Trailing
        }
    }
}

/// `slips` and `x` seen from the leading edge: x -> -x, node i -> n - 1 - i, so that the
/// definitions, written from x[0], run from the other edge.
fn mirrored(slips: &[Slip], x: &[f64]) -> (Vec<Slip>, Vec<f64>) {
    let n = x.len();
    let m = |i: usize| n.saturating_sub(1).saturating_sub(i);
    let xs = x.iter().rev().map(|v| -v).collect();
    let ss = slips
        .iter()
        .map(|s| Slip {
            node: m(s.node),
            region: (m(s.region.1), m(s.region.0)),
            preslip: s.preslip.map(|(a, b)| (m(b), m(a))),
            ..*s
        })
        .collect();
    (ss, xs)
}

/// [`find`] from `edge`; node indices are the caller's. From the leading edge a precursor's
/// `region` is (start, arrest) in the direction the front ran, so [`Precursor::arrest`] stays
/// its arrest node.
pub fn find_from_edge(edge: Edge, slips: &[Slip], x: &[f64], t: f64) -> (Edge, Precursors) {
    match edge {
        Edge::Trailing => (Edge::Trailing, find(slips, x, t)),
        Edge::Leading => {
            let (ss, xs) = mirrored(slips, x);
            let m = |i: usize| x.len() - 1 - i;
            let mut p = find(&ss, &xs, t);
            for q in &mut p.all {
                q.node = m(q.node);
                q.region = (m(q.region.0), m(q.region.1));
            }
            (Edge::Leading, p)
        }
    }
}

/// [`advances`] from `edge`; node indices are the caller's.
pub fn advances_from_edge(edge: Edge, slips: &[Slip], x: &[f64], t: f64) -> (Edge, Vec<Advance>) {
    match edge {
        Edge::Trailing => (Edge::Trailing, advances(slips, x, t)),
        Edge::Leading => {
            let (ss, xs) = mirrored(slips, x);
            let m = |i: usize| x.len() - 1 - i;
            let a = advances(&ss, &xs, t)
                .into_iter()
                .map(|a| Advance { front: m(a.front), node: m(a.node), ..a })
                .collect();
            (Edge::Leading, a)
        }
    }
}

/// `slips` split into cascades: runs of equal drive X.
fn cascades(slips: &[Slip]) -> impl Iterator<Item = &[Slip]> {
    slips.chunk_by(|a, b| a.x_drive == b.x_drive)
}

/// The precursors among `slips` (a run's instabilities in order) on an interface whose nodes
/// lie at `x` (m, ascending from the trailing edge, `x[0]`) under a block of thickness `t` (m),
/// up to the first cascade that ends the cycle.
pub fn find(slips: &[Slip], x: &[f64], t: f64) -> Precursors {
    let mut all = Vec::new();
    let mut front = x.first().copied().unwrap_or(0.0);
    for cascade in cascades(slips) {
        if cascade.iter().any(|s| s.ends_cycle) {
            break;
        }
        if let Some(p) = precursor(cascade, x, t) {
            let advancing = x[p.region.1] > front + ADVANCE_T * t;
            if advancing {
                front = x[p.region.1];
            }
            all.push(Precursor { advancing, ..p });
        }
    }
    Precursors { all }
}

/// The cascade as a precursor (not yet judged advancing), or None when none of its
/// instabilities nucleates at the trailing edge.
fn precursor(cascade: &[Slip], x: &[f64], t: f64) -> Option<Precursor> {
    let at_edge = |s: &&Slip| {
        let (Some(&xa), Some(&xn)) = (x.get(s.region.0), x.get(s.node)) else { return false };
        xa - x[0] <= ZONE_T * t && (xn - xa).abs() <= ZONE_T * t
    };
    let seed = cascade.iter().find(at_edge)?;
    let (mut a, mut b) = (seed.region.0.min(seed.node), seed.region.1.max(seed.node));
    // Join the regions that touch the slipped run, until none does.
    let mut grown = true;
    while grown {
        grown = false;
        for s in cascade {
            let (c, d) = s.region;
            if c <= b + 1 && d + 1 >= a && (c < a || d > b) {
                (a, b) = (a.min(c), b.max(d));
                grown = true;
            }
        }
    }
    // Regions come from the same interface as `x`; one that does not is no precursor.
    let (&xa, &xb) = (x.get(a)?, x.get(b)?);
    Some(Precursor {
        first_event: cascade[0].event,
        last_event: cascade[cascade.len() - 1].event,
        f: cascade[0].f,
        node: seed.node,
        region: (a, b),
        long: xb - xa > LONG_T * t,
        advancing: false,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 101 nodes 1 mm apart under t = 2 mm: the zone, long and advance lengths are 10 mm
    /// (10 node spacings).
    fn nodes() -> (Vec<f64>, f64) {
        ((0..101).map(|i| i as f64 * 1e-3).collect(), 2e-3)
    }

    fn slip(event: usize, x_drive: f64, f: f64, node: usize, region: (usize, usize)) -> Slip {
        Slip { event, x_drive, f, node, region, ends_cycle: false, preslip: None }
    }

    #[test]
    fn a_short_slip_at_the_trailing_edge_is_not_long_nor_counted() {
        let (x, t) = nodes();
        let p = find(&[slip(0, 1.0, 0.5, 0, (0, 3))], &x, t);
        assert_eq!((p.n_all(), p.n_long(), p.n()), (1, 0, 0));
        assert!(p.first().is_none());
    }

    #[test]
    fn a_long_slip_from_the_trailing_edge_is_a_precursor_with_its_arrest() {
        let (x, t) = nodes();
        let p = find(&[slip(3, 1.0, 0.7, 1, (1, 40))], &x, t);
        assert_eq!((p.n_all(), p.n_long(), p.n()), (1, 1, 1));
        let first = p.first().unwrap();
        assert_eq!((first.f, first.arrest(), first.first_event), (0.7, 40, 3));
    }

    #[test]
    fn nucleation_outside_the_trailing_zone_is_no_precursor_even_if_the_slip_reaches_the_edge() {
        let (x, t) = nodes();
        // Node 11 is 11 mm = 5.5 t from the edge; the region spreads back to node 0.
        let p = find(&[slip(0, 1.0, 0.7, 11, (0, 40))], &x, t);
        assert_eq!(p.n_all(), 0);
        // Node 9 is 3.5 t from its region's start: inside.
        let p = find(&[slip(0, 1.0, 0.7, 9, (2, 40))], &x, t);
        assert_eq!(p.n(), 1);
        // Behind an open or creeping corner of 3 t: the nucleus 4 t further in is at the edge
        // (7 t from x = -L/2); a region starting 6 t in is not.
        assert_eq!(find(&[slip(0, 1.0, 0.7, 14, (6, 40))], &x, t).n(), 1);
        assert_eq!(find(&[slip(0, 1.0, 0.7, 14, (12, 40))], &x, t).n_all(), 0);
    }

    #[test]
    fn one_that_does_not_advance_the_front_is_not_counted_in_n() {
        let (x, t) = nodes();
        let slips = [
            slip(0, 1.0, 0.70, 0, (0, 40)),
            // Arrests 5 t short of the front: long, not advancing.
            slip(1, 2.0, 0.72, 0, (0, 30)),
            // 4 mm = 2 t beyond the front: not advancing.
            slip(2, 3.0, 0.74, 0, (0, 44)),
            // 11 mm beyond the last counted arrest (node 40): advancing.
            slip(3, 4.0, 0.76, 0, (0, 51)),
        ];
        let p = find(&slips, &x, t);
        assert_eq!((p.n_all(), p.n_long(), p.n()), (4, 4, 2));
        let counted: Vec<usize> = p.counted().map(|q| q.arrest()).collect();
        assert_eq!(counted, [40, 51]);
        // Slips that all restart at the trailing edge advance the front where they count in n.
        let fronts: Vec<usize> = advances(&slips, &x, t).iter().map(|a| a.front).collect();
        assert_eq!(fronts, counted);
    }

    #[test]
    fn f_i_is_the_force_at_the_onset_of_a_cascade_not_of_its_follow_up() {
        let (x, t) = nodes();
        // The paper's scene, events 5 and 6: nucleation 5 nodes in, then at the same X the
        // follow-up from the first contact node starts at the first one's relaxed force.
        let slips = [
            slip(5, 3.39e-6, 0.7319, 5, (2, 60)),
            slip(6, 3.39e-6, 0.7264, 1, (1, 60)),
            // A leading-edge slip in the same cascade, apart from the run: not joined.
            slip(7, 3.39e-6, 0.7262, 99, (97, 100)),
        ];
        let p = find(&slips, &x, t);
        assert_eq!(p.n_all(), 1);
        let q = p.first().unwrap();
        assert_eq!((q.f, q.region, q.node, q.first_event, q.last_event), (0.7319, (1, 60), 5, 5, 7));
    }

    #[test]
    fn a_cascade_that_starts_away_from_the_edge_is_a_precursor_when_one_of_its_slips_nucleates_there() {
        let (x, t) = nodes();
        let slips = [slip(0, 1.0, 0.80, 99, (98, 100)), slip(1, 1.0, 0.79, 0, (0, 30))];
        let q = *find(&slips, &x, t).first().unwrap();
        // The drive force when the cascade began, and only the run grown from the edge.
        assert_eq!((q.f, q.region), (0.80, (0, 30)));
    }

    #[test]
    fn touching_regions_join_and_the_cycle_end_stops_the_count() {
        let (x, t) = nodes();
        let slips = [
            slip(0, 1.0, 0.7, 0, (0, 20)),
            slip(1, 1.0, 0.69, 30, (21, 35)),
            slip(2, 2.0, 0.8, 0, (0, 60)),
            Slip { ends_cycle: true, ..slip(3, 3.0, 0.9, 0, (0, 100)) },
            slip(4, 4.0, 0.7, 0, (0, 90)),
        ];
        let p = find(&slips, &x, t);
        assert_eq!(p.all.iter().map(|q| q.region).collect::<Vec<_>>(), [(0, 35), (0, 60)]);
        // A precursor cascading into a whole slip at the same X is the stick-slip event.
        let mut s = slips;
        s[3].x_drive = 2.0;
        assert_eq!(find(&s, &x, t).n_all(), 1);
    }

    fn fronts(slips: &[Slip]) -> Vec<usize> {
        let (x, t) = nodes();
        advances(slips, &x, t).iter().map(|a| a.front).collect()
    }

    #[test]
    fn a_front_advances_by_renucleating_at_its_tip_which_the_trailing_edge_rule_does_not_count() {
        let (x, t) = nodes();
        let slips = [
            slip(0, 1.0, 0.70, 0, (0, 20)),
            // Nucleates at the arrested tip and runs 7.5 t on: an advance, no precursor.
            slip(1, 2.0, 0.72, 21, (20, 35)),
            // 2.5 t on: not counted.
            slip(2, 3.0, 0.74, 36, (36, 40)),
            // 6.5 t beyond the last counted front (node 35), by two steps: counted.
            slip(3, 4.0, 0.76, 41, (41, 48)),
        ];
        let a = advances(&slips, &x, t);
        assert_eq!(
            a.iter().map(|a| (a.front, a.node, a.first_event)).collect::<Vec<_>>(),
            [(20, 0, 0), (35, 21, 1), (48, 41, 3)]
        );
        assert_eq!(a[1].f, 0.72);
        assert_eq!(find(&slips, &x, t).n(), 1);
    }

    #[test]
    fn a_detached_slip_is_no_advance_until_a_later_one_joins_it_to_the_front() {
        let slips =
            [slip(0, 1.0, 0.7, 0, (0, 20)), slip(1, 2.0, 0.7, 60, (55, 70)), slip(2, 3.0, 0.7, 30, (21, 54))];
        assert_eq!(fronts(&slips), [20, 70]);
        // Slipped runs joined across the gap are joined in either order of their ends.
        let slips =
            [slip(0, 1.0, 0.7, 60, (55, 70)), slip(1, 2.0, 0.7, 40, (40, 54)), slip(2, 3.0, 0.7, 0, (0, 39))];
        assert_eq!(fronts(&slips), [70]);
    }

    #[test]
    fn a_slip_from_the_edge_nucleating_behind_a_preslip_zone_is_an_advance_though_no_precursor() {
        // The thin block (t/L = 1/400): the first instability slips from the edge but nucleates
        // 6.5 t in, at the tip of the corner's preslip zone.
        let (x, t) = nodes();
        let slips = [slip(0, 1.0, 0.7285, 13, (0, 26))];
        assert_eq!(find(&slips, &x, t).n_all(), 0);
        assert_eq!(fronts(&slips), [26]);
        // A run starting more than 5 t from the edge is no front, unless the preslip before
        // it joins it to the edge.
        assert!(fronts(&[slip(0, 1.0, 0.7, 13, (11, 40))]).is_empty());
        let joined = Slip { preslip: Some((0, 10)), ..slip(0, 1.0, 0.7, 13, (11, 40)) };
        assert_eq!(fronts(&[joined]), [40]);
        // A preslip zone alone, with no instability, moves no front; one apart from the
        // slipped run joins nothing.
        let apart = Slip { preslip: Some((0, 0)), ..slip(0, 1.0, 0.7, 13, (11, 40)) };
        assert!(fronts(&[apart]).is_empty());
        // A stuck gap of 5 t or less (here 3 t) does not part the runs.
        let near = Slip { preslip: Some((0, 5)), ..slip(0, 1.0, 0.7, 13, (11, 40)) };
        assert_eq!(fronts(&[near]), [40]);
        // A lone slipping node at the edge, apart from a run that starts in the zone too
        // (node 8, 4 t in), does not hide that run's front.
        let lone = [
            slip(0, 1.0, 0.7, 9, (8, 30)),
            Slip { preslip: Some((0, 0)), ..slip(1, 2.0, 0.7, 31, (31, 50)) },
        ];
        assert_eq!(fronts(&lone), [30, 50]);
    }

    #[test]
    fn the_cycle_end_stops_the_advances() {
        let slips = [
            slip(0, 1.0, 0.70, 0, (0, 40)),
            Slip { ends_cycle: true, ..slip(1, 2.0, 0.9, 0, (0, 100)) },
            slip(2, 3.0, 0.7, 0, (0, 90)),
        ];
        assert_eq!(fronts(&slips), [40]);
    }

    #[test]
    fn a_run_nucleating_at_the_leading_edge_is_counted_from_there() {
        // Nodes 1 t apart; three cascades from the leading edge, the mirror of three from the
        // trailing edge: the same count and forces, positions mirrored, the edge named.
        let t = 1.0;
        let x: Vec<f64> = (0..101).map(|i| i as f64 - 50.0).collect();
        let slip = |k: usize, node: usize, region: (usize, usize)| Slip {
            event: k,
            x_drive: k as f64,
            f: 0.7 + 0.01 * k as f64,
            node,
            region,
            ends_cycle: false,
            preslip: None,
        };
        let trailing = [slip(0, 1, (0, 20)), slip(1, 2, (0, 40)), slip(2, 1, (0, 60))];
        let leading = [slip(0, 99, (80, 100)), slip(1, 98, (60, 100)), slip(2, 99, (40, 100))];
        let (et, pt) = find_from_edge(Edge::Trailing, &trailing, &x, t);
        let (el, pl) = find_from_edge(Edge::Leading, &leading, &x, t);
        assert_eq!((et, el), (Edge::Trailing, Edge::Leading));
        assert_eq!((pt.n(), pl.n()), (3, 3));
        for (a, b) in pt.counted().zip(pl.counted()) {
            assert_eq!(a.f, b.f);
            assert_eq!(x[a.arrest()], -x[b.arrest()]);
        }
        assert_eq!(pl.first().unwrap().arrest(), 80);
        // The trailing-edge rule alone finds none of the leading ones.
        assert_eq!(find(&leading, &x, t).n_all(), 0);
        let (_, al) = advances_from_edge(Edge::Leading, &leading, &x, t);
        assert_eq!(
            (Edge::of_lowest_pressure(0.04, 0.002), Edge::of_lowest_pressure(0.0, 0.002)),
            (Edge::Trailing, Edge::Leading)
        );
        assert_eq!(al.iter().map(|a| a.front).collect::<Vec<_>>(), vec![80, 60, 40]);
    }
}
