//! A dynamic event's fronts from arrival times (fronts_t.csv; issue 43). A base node is
//! reached when its |v_x| first exceeds the arrival rate ([`super::physics::arrival_rate`],
//! recorded per explicit step: [`EventRecord::arrival`]). From the first node reached, a front
//! runs each way; it reaches a node when every node between them has arrived (the running
//! largest arrival outward), so a patch that started on its own ahead of it is crossed at
//! once when the two join. The speed is the least-squares slope of distance against that
//! time over a window of [`SPEED_WINDOW_THICKNESSES`] t either side: one step (~1/200 of a
//! thickness period on the paper's mesh) over the window's ~2 t / c is a 1-3 % error at
//! c_s to c_p, where the speed between two neighbours would be 10-20 %.

use crate::dynamics::driven::EventRecord;

/// Half-width of the speed's window, in block thicknesses t: a thin layer's front carries
/// its stress concentration over about t (shear lag), so its speed is defined on that scale.
pub const SPEED_WINDOW_THICKNESSES: f64 = 1.0;

/// Why a speed may exceed what a running front can reach (c_p): named where it applies,
/// whatever the speed, so that no speed above c_p goes without a cause unseen.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Cause {
    None,
    /// The window holds a node that had slipped before the event (slip memory past the
    /// record's threshold, D_c/100, at the onset): the nucleating zone, already at its
    /// strength, starts to move at once rather than being reached by a running front.
    Preslip,
    /// The window holds a node that arrived before the front reached it: a patch that
    /// started on its own, which the front joins (its position jumps).
    Join,
}

impl Cause {
    /// fronts_t.csv's `flag` (empty: none).
    pub fn name(self) -> &'static str {
        match self {
            Cause::None => "",
            Cause::Preslip => "preslip",
            Cause::Join => "join",
        }
    }
}

/// One base node reached by the event's front.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Arrival {
    pub node: usize,
    /// -1: the front running toward -x, +1 toward +x, 0: the first node reached.
    pub side: i32,
    /// The node's own arrival, and when the front reached it (the largest arrival between
    /// it and the first node), s since the onset.
    pub own: f64,
    pub front: f64,
    /// The front's speed there, m/s (infinite: the window's nodes were reached at once;
    /// NaN at the first node).
    pub speed: f64,
    pub cause: Cause,
}

/// The event's front: the first node reached, then each side outward to the end of the run
/// of nodes reached (nodes of patches that never join it are left out). `x`: the base
/// nodes' positions, m; `thickness`: the block's, m.
pub fn arrivals(rec: &EventRecord, x: &[f64], thickness: f64) -> Vec<Arrival> {
    let a = &rec.arrival;
    let Some(c) = (0..a.len()).filter(|&i| a[i].is_finite()).min_by(|&i, &j| a[i].total_cmp(&a[j])) else {
        return vec![];
    };
    let preslip = |i: usize| rec.d_pre.get(i).is_some_and(|&d| d > rec.threshold);
    let first = Arrival {
        node: c,
        side: 0,
        own: a[c],
        front: a[c],
        speed: f64::NAN,
        cause: if preslip(c) { Cause::Preslip } else { Cause::None },
    };
    let mut out = vec![first];
    let w = SPEED_WINDOW_THICKNESSES * thickness;
    for side in [-1i32, 1] {
        // The path outward: (node, distance from the first node, front time).
        let mut path = vec![(c, 0.0, a[c])];
        let mut i = c;
        while let Some(j) = i.checked_add_signed(side as isize).filter(|&j| j < a.len() && a[j].is_finite()) {
            let front = path.last().map_or(a[j], |p| p.2.max(a[j]));
            path.push((j, (x[j] - x[c]).abs(), front));
            i = j;
        }
        let r_max = path.last().map_or(0.0, |p| p.1);
        let eps = 1e-9 * thickness;
        for &(j, r, front) in &path[1..] {
            // The window, shifted inward at the run's ends to keep its width.
            let lo = (r - w).min(r_max - 2.0 * w).max(0.0);
            let win: Vec<&(usize, f64, f64)> =
                path.iter().filter(|p| p.1 >= lo - eps && p.1 <= lo + 2.0 * w + eps).collect();
            let cause = if win.iter().any(|p| preslip(p.0)) {
                Cause::Preslip
            } else if win.iter().any(|p| a[p.0] < p.2) {
                Cause::Join
            } else {
                Cause::None
            };
            out.push(Arrival { node: j, side, own: a[j], front, speed: slope_speed(&win), cause });
        }
    }
    out
}

/// 1 / (the least-squares slope of time against distance) over `win` (node, distance m,
/// time s), m/s; infinite when every point has the same time.
fn slope_speed(win: &[&(usize, f64, f64)]) -> f64 {
    let n = win.len() as f64;
    let (mr, mt) = win.iter().fold((0.0, 0.0), |s, p| (s.0 + p.1 / n, s.1 + p.2 / n));
    let (sxy, sxx) = win.iter().fold((0.0, 0.0), |s, p| (s.0 + (p.1 - mr) * (p.2 - mt), s.1 + (p.1 - mr).powi(2)));
    if sxx == 0.0 {
        return f64::NAN;
    }
    let beta = sxy / sxx;
    if beta > 0.0 {
        1.0 / beta
    } else {
        f64::INFINITY
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn record(arrival: Vec<f64>) -> EventRecord {
        let n = arrival.len();
        EventRecord { arrival, d_pre: vec![0.0; n], threshold: 1e-9, ..Default::default() }
    }

    #[test]
    fn a_steady_front_has_its_speed_and_a_patch_ahead_is_a_join() {
        // Nodes 1 mm apart, t = 2 mm: a front from node 3 at 0.5 m/s to the right and
        // 0.25 m/s to the left, exactly; then node 8 arrives early (a patch of its own).
        let x: Vec<f64> = (0..12).map(|i| i as f64 * 1e-3).collect();
        let mut a: Vec<f64> = x.iter().map(|&xi| if xi >= 3e-3 { (xi - 3e-3) / 0.5 } else { (3e-3 - xi) / 0.25 }).collect();
        let r = arrivals(&record(a.clone()), &x, 2e-3);
        assert_eq!((r[0].node, r[0].side), (3, 0));
        assert_eq!(r.len(), 12);
        for f in &r[1..] {
            let want = if f.side > 0 { 0.5 } else { 0.25 };
            assert!((f.speed / want - 1.0).abs() < 1e-12, "{f:?}");
            assert_eq!(f.cause, Cause::None);
        }
        a[8] = 1e-3; // before the front's 10 ms
        let r = arrivals(&record(a), &x, 2e-3);
        let at = |k: usize| r.iter().find(|f| f.node == k).unwrap();
        assert_eq!(at(8).front, 10e-3, "the front reaches 8 when 7 has arrived");
        assert_eq!(at(8).cause, Cause::Join);
        assert_eq!(at(4).cause, Cause::None, "8 is 4 mm = 2 t from 4: outside its window");
        // A node that slipped before the event flags the windows holding it.
        let mut rec = record(vec![0.0, 1.0, 2.0, 3.0]);
        rec.d_pre[0] = 1.0;
        let r = arrivals(&rec, &x[..4], 1e-3);
        assert!(r[0].cause == Cause::Preslip && r[1].cause == Cause::Preslip && r[3].cause == Cause::None, "{r:?}");
    }
}
