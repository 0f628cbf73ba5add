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
    /// Neither, and the speed exceeds c_p: no wave from behind the front brought the load.
    /// Not separated here: load through the rigid plate (no wave speed; massless by
    /// default), or the threshold crossing running ahead of a front whose slip rate grows.
    /// The paper's first cycle: 10 of 3 634 rows, at most 1.23 c_p.
    AboveCp,
}

impl Cause {
    /// fronts_t.csv's `flag` (empty: none).
    pub fn name(self) -> &'static str {
        match self {
            Cause::None => "",
            Cause::Preslip => "preslip",
            Cause::Join => "join",
            Cause::AboveCp => "above_c_p",
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
/// nodes' positions, m; `thickness`: the block's, m; `c_p`: the P-wave speed, m/s.
pub fn arrivals(rec: &EventRecord, x: &[f64], thickness: f64, c_p: f64) -> Vec<Arrival> {
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
            let speed = slope_speed(&win);
            let cause = if win.iter().any(|p| preslip(p.0)) {
                Cause::Preslip
            } else if win.iter().any(|p| a[p.0] < p.2) {
                Cause::Join
            } else if !(speed <= c_p) {
                Cause::AboveCp
            } else {
                Cause::None
            };
            out.push(Arrival { node: j, side, own: a[j], front, speed, cause });
        }
    }
    out
}

/// 1 / (the least-squares slope of time against distance) over `win` (node, distance m,
/// time s), m/s; infinite when every point has the same time.
fn slope_speed(win: &[&(usize, f64, f64)]) -> f64 {
    let n = win.len() as f64;
    let (mr, mt) = win.iter().fold((0.0, 0.0), |s, p| (s.0 + p.1 / n, s.1 + p.2 / n));
    let (sxy, sxx) =
        win.iter().fold((0.0, 0.0), |s, p| (s.0 + (p.1 - mr) * (p.2 - mt), s.1 + (p.1 - mr).powi(2)));
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
