//! Precursors to frictional sliding: the quasistatic 1D model of Scheibert & Dysthe,
//! "Role of friction-induced torque in stick-slip motion" (EPL), and extensions.
//!
//! Everything is dimensionless as in the paper: coordinates in units of the contact length
//! L (the contact spans x in [-1/2, 1/2], trailing edge at -1/2), forces in units of mu_s N,
//! stresses in units of mu_s N/(wL). Two control parameters: r = mu_d/mu_s and
//! g = 6 mu_d H/L. The pressure is p(x, F) = 1/mu_s + (2g/mu_d) F x, so the static and
//! kinetic thresholds are mu_s p = 1 + 2(g/r) F x and mu_d p = r + 2 g F x.
//!
//! - this module: the paper's analytic event iteration (eqs. F1, Fic, xi, Fi*, Fi+1);
//! - [`discrete`]: the same kinematics on a cell-discretised interface with arbitrary
//!   pressure and shear profiles;
//! - [`fe`]: feeding the discrete model with unit-load fields from an FE solution;
//! - [`definition`]: what a precursor of the frictional FE's event runs is (the one definition
//!   behind every FE count, F_i and x_i tribofe reports).

pub mod definition;
pub mod discrete;
pub mod fe;

use crate::{Error, Result};
use rayon::prelude::*;

/// The paper's fig. 4 case (r, g): the default of every front end (`precursors --r/--g`,
/// the Python package) and the default coefficients of the frictional laws.
pub const PAPER_R: f64 = 0.9;
pub const PAPER_G: f64 = 0.35;

/// Upper bound on the number of precursors [`n_precursors`] will iterate through before
/// giving up; n grows without bound as (r, g) -> (1, 1) (about 2500 at r = g = 0.9875).
pub const MAX_PRECURSORS: usize = 10_000_000;

/// Cells per axis of the n(r, g) map by default (`precursors map`, `tribofe.precursors.map`).
pub const DEFAULT_MAP_RESOLUTION: usize = 40;

/// Events of each discrete run of the bonded comparison by default (`precursors bonded`,
/// `tribofe.precursors.bonded`), and the cap of the iteration run to convergence.
pub const DEFAULT_EVENTS: usize = 200;

/// Largest event count asked for: the iteration reaches its stick-slip limit cycle within
/// ~200 events, and each event printed and written costs ~100 bytes (10 MB at the cap).
pub const MAX_EVENTS: usize = 100_000;

/// Refuses an event count above [`MAX_EVENTS`] (`--events`).
pub fn check_events(n: usize) -> Result<()> {
    if n > MAX_EVENTS {
        return Err(Error::input(
            "--events",
            format!("{n}: at most {MAX_EVENTS} (the iteration settles on its stick-slip cycle within ~200 events)"),
        ));
    }
    Ok(())
}

/// Control parameters (r, g), validated to the accessible square 0 < r < 1, 0 < g < 1.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Params {
    r: f64,
    g: f64,
}

impl Params {
    /// Validates r = mu_d/mu_s and g = 6 mu_d H/L (paper, Results: "0<r<1 and 0<g<1").
    pub fn new(r: f64, g: f64) -> Result<Params> {
        let bad = |name: &str, v: f64, why: &str| Err(Error::input(format!("{name} = {v}"), why));
        if !r.is_finite() {
            return bad("r", r, "r = mu_d/mu_s must be a finite number");
        }
        if !g.is_finite() {
            return bad("g", g, "g = 6 mu_d H/L must be a finite number");
        }
        if r <= 0.0 {
            return bad("r", r, "r = mu_d/mu_s must be > 0 since friction coefficients are positive");
        }
        if r >= 1.0 {
            return bad("r", r, "r = mu_d/mu_s must be < 1 since mu_s > mu_d");
        }
        // g = 0 (H = 0) is the paper's control case: uniform pressure, the whole interface
        // reaches mu_s at once, F_1 = F_max = 1 and n = 0 (x_1 is past the leading edge).
        if g < 0.0 {
            return bad("g", g, "g = 6 mu_d H/L must be >= 0 (H >= 0: the drive at or above the interface; g = 0 is the control case without torque)");
        }
        if g >= 1.0 {
            return bad(
                "g",
                g,
                "g must be < 1 so the trailing-edge pressure stays positive (r - g F_max > 0)",
            );
        }
        Ok(Params { r, g })
    }

    pub fn r(&self) -> f64 {
        self.r
    }

    pub fn g(&self) -> f64 {
        self.g
    }

    /// Force at the first event, eq. (F1): F_1 = 1/(1 + g/r).
    pub fn f1(&self) -> f64 {
        1.0 / (1.0 + self.g / self.r)
    }

    /// Peak force of the periodic stick-slip, F_max = 1/(1 + g(1-r)/r): the fixed point of
    /// eq. (Fi+1) with F_i^* = r.
    pub fn f_max(&self) -> f64 {
        1.0 / (1.0 + self.g * (1.0 - self.r) / self.r)
    }

    /// The no-precursor line g = (1-r)/2: for g below it x_1 > 1/2 and the first event is
    /// already macroscopic stick-slip (paper, Results).
    pub fn no_precursor_g(r: f64) -> f64 {
        (1.0 - r) / 2.0
    }
}

/// One slip event of the analytic model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Event {
    /// 1-based event index.
    pub i: usize,
    /// Friction force when the event nucleates, F_i.
    pub f: f64,
    /// Elastic force at nucleation, F_i^c (eq. Fic).
    pub fc: f64,
    /// Arrest position x_i (eq. xi); 1/2 once the event spans the whole contact.
    pub x: f64,
    /// Relaxed force after the event, F_i^* (eq. Fi*); r in stick-slip.
    pub fstar: f64,
    /// False for a precursor, true once the event reaches the leading edge.
    pub stick_slip: bool,
}

/// The event sequence of the paper as an endless iterator (eqs. F1, Fic, xi, Fi*, Fi+1).
#[derive(Debug, Clone)]
pub struct Events {
    r: f64,
    g: f64,
    i: usize,
    f: f64,
    /// Sum over past events of (F_j - F_j^*), the drops that separate F^c from F (eq. Fic).
    drops: f64,
    stick_slip: bool,
}

impl Events {
    pub fn new(p: &Params) -> Events {
        Events { r: p.r, g: p.g, i: 0, f: p.f1(), drops: 0.0, stick_slip: false }
    }
}

impl Iterator for Events {
    type Item = Event;

    fn next(&mut self) -> Option<Event> {
        let (r, g, f) = (self.r, self.g, self.f);
        self.i += 1;
        // Eq. (Fic).
        let fc = f + self.drops;
        // Eq. (xi): mu_d p(x_i, F_i) = F_i^c. Past the leading edge the whole contact slips
        // and relaxes to mu_d p, whose integral is r (paper, end of the iteration section).
        let x_arrest = (fc - r) / (2.0 * f * g);
        self.stick_slip |= x_arrest > 0.5;
        let (x, fstar) = if self.stick_slip {
            (0.5, r)
        } else {
            // Eq. (Fi*): the trapezoid under the relaxed field r + 2 g F_i x on [-1/2, x_i].
            (x_arrest, fc - 0.5 * (x_arrest + 0.5) * (fc - r * (1.0 - g * f / r)))
        };
        self.drops += f - fstar;
        // Eq. (Fi+1): the trailing edge, relaxed to mu_d p(-1/2, F_i), reloads to mu_s p(-1/2, F_{i+1}).
        self.f = (1.0 - r + fstar + g * f) / (1.0 + g / r);
        Some(Event { i: self.i, f, fc, x, fstar, stick_slip: self.stick_slip })
    }
}

/// The first `n_events` events.
pub fn simulate(p: &Params, n_events: usize) -> Vec<Event> {
    Events::new(p).take(n_events).collect()
}

/// Events up to and including the first stick-slip event with |F_i - F_max| < `tol`, or
/// `max_events` events, whichever comes first.
pub fn simulate_to_convergence(p: &Params, tol: f64, max_events: usize) -> Vec<Event> {
    let f_max = p.f_max();
    let mut out = Vec::new();
    for e in Events::new(p).take(max_events) {
        out.push(e);
        if e.stick_slip && (e.f - f_max).abs() < tol {
            break;
        }
    }
    out
}

/// Number of precursors n: the events before the first one with x > 1/2.
pub fn n_precursors(p: &Params) -> Result<usize> {
    Events::new(p).take(MAX_PRECURSORS + 1).position(|e| e.stick_slip).ok_or_else(|| {
        Error::input(
            format!("(r, g) = ({}, {})", p.r, p.g),
            format!("more than {MAX_PRECURSORS} precursors; the count diverges as r and g approach 1"),
        )
    })
}

/// F_max = 1/(1 + g(1-r)/r), the force the stick-slip peaks tend to (paper, Results).
pub fn f_max(p: &Params) -> f64 {
    p.f_max()
}

/// Vertices of the loading curve F(F^c) (paper, fig. 4): the elastic line F = F^c from the
/// origin to the first event, then for each event a vertical drop (F_i^c, F_i) ->
/// (F_i^c, F_i^*) followed by slope-1 reloading to the next event.
pub fn loading_curve(events: &[Event]) -> Vec<(f64, f64)> {
    let mut pts = Vec::with_capacity(2 * events.len() + 1);
    pts.push((0.0, 0.0));
    for e in events {
        pts.push((e.fc, e.f));
        pts.push((e.fc, e.fstar));
    }
    pts
}

/// One point of the n(r, g) map (paper, fig. 5).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MapPoint {
    pub r: f64,
    pub g: f64,
    pub n: usize,
}

/// n(r, g) at the centres of a `resolution` x `resolution` grid over (0,1)^2, ordered with
/// g varying fastest; computed in parallel, each cell stopping at once when `cancel` is
/// cancelled.
pub fn n_map(resolution: usize, cancel: &crate::Cancel) -> Result<Vec<MapPoint>> {
    if !(2..=400).contains(&resolution) {
        return Err(Error::input(
            format!("resolution = {resolution}"),
            "must be in 2..=400: cells nearer (1, 1) need ever more precursors to iterate",
        ));
    }
    let centre = |k: usize| (k as f64 + 0.5) / resolution as f64;
    (0..resolution * resolution)
        .into_par_iter()
        .map(|k| {
            cancel.check()?;
            let (r, g) = (centre(k / resolution), centre(k % resolution));
            Ok(MapPoint { r, g, n: n_precursors(&Params::new(r, g)?)? })
        })
        .collect()
}
