//! The paper's kinematics on a discretised interface with arbitrary fields.
//!
//! The contact is split into cells k (centres `x[k]` in [-1/2, 1/2], widths `w[k]`
//! summing to 1, in units of L). Units are the paper's: stresses in mu_s N/(wL), forces
//! in mu_s N. Between events the shear grows as sigma_k += s_k dF^c with sum_k w_k s_k = 1,
//! so the friction force F = sum_k w_k sigma_k grows like the elastic force F^c. The
//! pressure depends only on the total friction force (the paper's Goodman-like assumption):
//! p_k(F) = p0_k + F dp_k.
//!
//! An event, as in the paper:
//! 1. loading raises F until sigma_k = mu_s p_k(F) in some cell (nucleation; the lowest
//!    index wins ties, so the trailing side);
//! 2. the slip front spreads from that cell in both directions over the contiguous cells
//!    where sigma_k > mu_d p_k(F_i) (the relaxation happens only after arrest);
//! 3. the slipped cells relax to sigma_k = mu_d p_k(F_i).
//!
//! Step 3 is implicit in reality: after relaxation the force is F_i^* < F_i and the
//! pressure follows F_i^*, not F_i. The paper evaluates the relaxed field at F_i (the
//! relaxed shear r + 2 g F_i x below eq. (Fic)), and so do we, so that the paper's linear
//! fields reproduce eqs. (xi), (Fi*) and (Fi+1) up to the discretisation.
//! An event whose slipped region contains the leading-edge cell is stick-slip.
//! Shear is taken positive in the loading direction: back-slip (sigma_k < -mu p_k) is not
//! modelled.

use super::Params;
use crate::{Error, Result};

/// Sums of widths and of w_k s_k must be 1 to this relative accuracy.
const SUM_TOL: f64 = 1e-9;

/// Inputs of the discrete model; all per cell, sorted by x.
#[derive(Debug, Clone, PartialEq)]
pub struct Interface {
    /// Cell centres, x/L in [-1/2, 1/2].
    pub x: Vec<f64>,
    /// Cell widths, w/L, summing to 1.
    pub w: Vec<f64>,
    /// Pressure at F = 0 (units mu_s N/(wL)).
    pub p0: Vec<f64>,
    /// Pressure per unit friction force: p_k(F) = p0_k + F dp_k.
    pub dp: Vec<f64>,
    /// Shear increment per unit elastic force F^c; sum_k w_k s_k = 1.
    pub s: Vec<f64>,
    /// Shear at F^c = 0 (zero in the paper).
    pub sigma0: Vec<f64>,
    pub mu_s: f64,
    pub mu_d: f64,
}

/// Uniform cells on [-1/2, 1/2]: (centres, widths).
pub fn uniform_cells(n: usize) -> (Vec<f64>, Vec<f64>) {
    let h = 1.0 / n as f64;
    ((0..n).map(|k| -0.5 + (k as f64 + 0.5) * h).collect(), vec![h; n])
}

/// `n` (>= 2) equally spaced nodes from -1/2 to 1/2 with tributary widths (half at the two ends):
/// the layout of FE interface nodes. A node sits on the trailing edge, where the paper's
/// threshold is first reached, so the linear fields nucleate exactly as in eq. (F1).
pub fn tributary_nodes(n: usize) -> (Vec<f64>, Vec<f64>) {
    let h = 1.0 / (n as f64 - 1.0);
    let x = (0..n).map(|k| if k + 1 == n { 0.5 } else { -0.5 + k as f64 * h }).collect();
    let w = (0..n).map(|k| if k == 0 || k + 1 == n { h / 2.0 } else { h }).collect();
    (x, w)
}

impl Interface {
    /// The paper's fields on the given cells: p = 1/mu_s + (2g/mu_d) F x with
    /// mu_d = r mu_s, uniform shear increment s = 1 and no initial shear.
    pub fn linear(p: &Params, mu_s: f64, x: Vec<f64>, w: Vec<f64>) -> Interface {
        let mu_d = p.r() * mu_s;
        let slope = 2.0 * p.g() / mu_d;
        let n = x.len();
        Interface {
            dp: x.iter().map(|&xk| slope * xk).collect(),
            p0: vec![1.0 / mu_s; n],
            s: vec![1.0; n],
            sigma0: vec![0.0; n],
            x,
            w,
            mu_s,
            mu_d,
        }
    }

    pub fn validate(&self) -> Result<()> {
        let n = self.x.len();
        if n < 2 {
            return Err(Error::input("interface", format!("{n} cells: need at least 2")));
        }
        for (name, v) in [
            ("x", &self.x),
            ("w", &self.w),
            ("p0", &self.p0),
            ("dp", &self.dp),
            ("s", &self.s),
            ("sigma0", &self.sigma0),
        ] {
            if v.len() != n {
                return Err(Error::input(
                    "interface",
                    format!("{name} has {} entries but x has {n}", v.len()),
                ));
            }
            if let Some(k) = v.iter().position(|a| !a.is_finite()) {
                return Err(Error::input(
                    "interface",
                    format!("{name}[{k}] = {} is not a finite number", v[k]),
                ));
            }
        }
        if let Some(k) = (1..n).find(|&k| self.x[k] <= self.x[k - 1]) {
            return Err(Error::input(
                "interface",
                format!(
                    "x must increase strictly; x[{k}] = {} <= x[{}] = {}",
                    self.x[k],
                    k - 1,
                    self.x[k - 1]
                ),
            ));
        }
        if self.x[0] < -0.5 - SUM_TOL || self.x[n - 1] > 0.5 + SUM_TOL {
            return Err(Error::input(
                "interface",
                format!(
                    "cell centres span [{}, {}], outside the contact [-1/2, 1/2]",
                    self.x[0],
                    self.x[n - 1]
                ),
            ));
        }
        if let Some(k) = self.w.iter().position(|&a| a <= 0.0) {
            return Err(Error::input("interface", format!("w[{k}] = {} must be > 0", self.w[k])));
        }
        let sum_w: f64 = self.w.iter().sum();
        if (sum_w - 1.0).abs() > SUM_TOL {
            return Err(Error::input("interface", format!("widths sum to {sum_w}, not 1 (units of L)")));
        }
        let sum_ws: f64 = self.w.iter().zip(&self.s).map(|(w, s)| w * s).sum();
        if (sum_ws - 1.0).abs() > SUM_TOL {
            return Err(Error::input(
                "interface",
                format!("sum w_k s_k = {sum_ws}, not 1: F would not grow like F^c"),
            ));
        }
        if let Some(k) = self.p0.iter().position(|&a| a <= 0.0) {
            return Err(Error::input(
                "interface",
                format!("p0[{k}] = {}: the unloaded contact must be in compression", self.p0[k]),
            ));
        }
        if !(self.mu_d.is_finite() && self.mu_s.is_finite() && 0.0 < self.mu_d && self.mu_d < self.mu_s) {
            return Err(Error::input(
                "interface",
                format!("mu_s = {}, mu_d = {}: need 0 < mu_d < mu_s", self.mu_s, self.mu_d),
            ));
        }
        Ok(())
    }

    fn p(&self, k: usize, f: f64) -> f64 {
        self.p0[k] + f * self.dp[k]
    }
}

/// One slip event of the discrete model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CellEvent {
    /// 1-based event index.
    pub i: usize,
    /// Friction force at nucleation, F_i.
    pub f: f64,
    /// Elastic force at nucleation, F_i^c.
    pub fc: f64,
    /// Cell where the static threshold is reached first, and its centre x/L.
    pub nucleation: usize,
    pub x_nucleation: f64,
    /// First and last slipped cell (inclusive).
    pub first: usize,
    pub last: usize,
    /// Arrest position: the leading boundary of the slipped region, -1/2 + sum_{k<=last} w_k.
    pub x: f64,
    /// Friction force after relaxation, F_i^*.
    pub fstar: f64,
    /// The slipped region contains the leading-edge cell.
    pub stick_slip: bool,
}

/// Result of [`simulate`].
#[derive(Debug, Clone, PartialEq)]
pub struct Run {
    pub events: Vec<CellEvent>,
    /// True when the run stopped because the stick-slip became periodic (two successive
    /// stick-slip events with the same F to 1e-12): further events would repeat it.
    pub periodic: bool,
}

impl Run {
    /// Number of precursors: events before the first stick-slip one; None if the run never
    /// reached stick-slip.
    pub fn n_precursors(&self) -> Option<usize> {
        self.events.iter().position(|e| e.stick_slip)
    }

    /// The force the stick-slip tends to: F of the last event, if it is stick-slip (exact
    /// when `periodic`, otherwise the latest estimate).
    pub fn f_limit(&self) -> Option<f64> {
        self.events.last().filter(|e| e.stick_slip).map(|e| e.f)
    }

    pub fn precursors(&self) -> &[CellEvent] {
        &self.events[..self.n_precursors().unwrap_or(self.events.len())]
    }
}

/// Runs up to `max_events` events (fewer if the stick-slip becomes periodic, or if no cell
/// can ever reach its static threshold because s_k <= mu_s dp_k wherever it is not reached).
/// Errors if the interface is invalid or the pressure turns negative in a cell at an event
/// (the contact would open, which the model does not describe).
pub fn simulate(iface: &Interface, max_events: usize) -> Result<Run> {
    iface.validate()?;
    let n = iface.x.len();
    let (mu_s, mu_d) = (iface.mu_s, iface.mu_d);
    let mut sigma = iface.sigma0.clone();
    let mut f: f64 = iface.w.iter().zip(&sigma).map(|(w, s)| w * s).sum();
    // F^c - F: the accumulated relaxation drops (eq. Fic).
    let mut drops = 0.0;
    let mut events: Vec<CellEvent> = Vec::new();
    let mut periodic = false;
    while events.len() < max_events {
        // Loading increment t to the first cell reaching mu_s p_k(F + t):
        // sigma_k + s_k t = mu_s (p_k(F) + t dp_k).
        let mut best: Option<(f64, usize)> = None;
        for k in 0..n {
            let margin = mu_s * iface.p(k, f) - sigma[k];
            let rate = iface.s[k] - mu_s * iface.dp[k];
            let t = if margin <= 0.0 {
                0.0
            } else if rate > 0.0 {
                margin / rate
            } else {
                continue;
            };
            if best.is_none_or(|(tb, _)| t < tb) {
                best = Some((t, k));
            }
        }
        let Some((t, nuc)) = best else { break };
        for (sk, s) in sigma.iter_mut().zip(&iface.s) {
            *sk += s * t;
        }
        f += t;
        if let Some(k) = (0..n).find(|&k| iface.p(k, f) <= 0.0) {
            return Err(Error::input(
                "pressure field",
                format!(
                    "p = {} <= 0 in cell {k} (x = {}) at F = {f}: the contact opens, outside the model",
                    iface.p(k, f),
                    iface.x[k]
                ),
            ));
        }
        let slips = |k: usize| sigma[k] > mu_d * iface.p(k, f);
        let (first, last) = crate::numeric::run_around(nuc, n, slips);
        for k in first..=last {
            sigma[k] = mu_d * iface.p(k, f);
        }
        let fstar: f64 = iface.w.iter().zip(&sigma).map(|(w, s)| w * s).sum();
        let stick_slip = last == n - 1;
        let ev = CellEvent {
            i: events.len() + 1,
            f,
            fc: f + drops,
            nucleation: nuc,
            x_nucleation: iface.x[nuc],
            first,
            last,
            x: -0.5 + iface.w[..=last].iter().sum::<f64>(),
            fstar,
            stick_slip,
        };
        drops += f - fstar;
        f = fstar;
        let repeat =
            events.last().is_some_and(|p| p.stick_slip && (p.f - ev.f).abs() <= 1e-12 * ev.f.abs().max(1.0));
        events.push(ev);
        if stick_slip && repeat {
            periodic = true;
            break;
        }
    }
    Ok(Run { events, periodic })
}
