//! Feeding the discrete model with interface fields from an FE solution, and comparing with
//! the paper's linear fields on the same cells.
//!
//! Conversion (plane strain or plane stress, per unit out-of-plane width w, linear elasticity so fields
//! superpose; the interface is stuck everywhere in the FE solve, which is what loads the
//! model between events). Under normal load N and tangential force F:
//!   p(x)   = (N/L) p_per_n(x) + (F/L) p_per_f(x),
//!   tau(x) = (N/L) tau_per_n(x) + (F/L) tau_per_f(x).
//! Dividing stresses by the paper's unit mu_s N/L and writing F~ = F/(mu_s N):
//!   p~(x, F~) = p_per_n/mu_s + F~ p_per_f      so p0_k = p_per_n(k)/mu_s, dp_k = p_per_f(k);
//!   sigma~    = tau_per_n/mu_s + F~ tau_per_f  so sigma0_k = tau_per_n(k)/mu_s, s_k = tau_per_f(k).
//! Friction coefficients from (r, g) and the geometry: g = 6 mu_d H/L gives
//! mu_d = g/(6 H/L), and mu_s = mu_d/r. Check with the paper's fields: p_per_n = 1,
//! p_per_f = 12 (H/L) x/L gives dp = (2g/mu_d) x, the paper's p~ = 1/mu_s + (2g/mu_d) F~ x~.

use super::discrete::{self, CellEvent, Interface, Run};
use super::{Event, Params};
use crate::{Error, Result};

/// The FE unit-load fields at the interface nodes, sorted by x. Handed over by the FE scene.
#[derive(Debug, Clone, PartialEq)]
pub struct UnitFields {
    /// Node positions x/L, in [-1/2, 1/2].
    pub x_over_l: Vec<f64>,
    /// Tributary widths w/L, summing to 1.
    pub w_over_l: Vec<f64>,
    /// Pressure under a unit normal load N, divided by N/L (integrates to 1 over x/L).
    pub p_per_n: Vec<f64>,
    /// Shear under a unit normal load N, divided by N/L (~0 by symmetry).
    pub tau_per_n: Vec<f64>,
    /// Pressure under a unit tangential force F (N = 0), divided by F/L.
    pub p_per_f: Vec<f64>,
    /// Shear under a unit tangential force F (N = 0), divided by F/L (integrates to 1).
    pub tau_per_f: Vec<f64>,
    /// Height H of the tangential load above the interface, over L.
    pub h_over_l: f64,
    /// Block thickness t over L.
    pub t_over_l: f64,
}

/// The FE nodal quadrature of tau_per_f may miss 1 by the FE error; beyond this it is
/// treated as a wrong field rather than rescaled.
const TAU_SUM_TOL: f64 = 0.05;

impl UnitFields {
    /// The paper's linear fields on `n` equally spaced nodes laid out like FE interface
    /// nodes (p_per_n = 1, p_per_f = 12 (H/L) x/L, tau_per_f = 1, tau_per_n = 0): a
    /// stand-in for the FE scene and a test fixture.
    pub fn linear(n: usize, h_over_l: f64, t_over_l: f64) -> UnitFields {
        let (x, w) = discrete::tributary_nodes(n);
        UnitFields {
            p_per_f: x.iter().map(|&xk| 12.0 * h_over_l * xk).collect(),
            p_per_n: vec![1.0; n],
            tau_per_n: vec![0.0; n],
            tau_per_f: vec![1.0; n],
            x_over_l: x,
            w_over_l: w,
            h_over_l,
            t_over_l,
        }
    }

    /// The discrete model's inputs for (r, g); see the module doc for the derivation.
    /// tau_per_f is rescaled so that sum w s = 1 exactly (F must grow like F^c).
    pub fn to_interface(&self, p: &Params) -> Result<Interface> {
        for (name, v) in [("H/L", self.h_over_l), ("t/L", self.t_over_l)] {
            if !(v.is_finite() && v > 0.0) {
                return Err(Error::input(format!("{name} = {v}"), "must be a positive finite number"));
            }
        }
        let n = self.x_over_l.len();
        for (name, v) in [
            ("w_over_l", &self.w_over_l),
            ("p_per_n", &self.p_per_n),
            ("tau_per_n", &self.tau_per_n),
            ("p_per_f", &self.p_per_f),
            ("tau_per_f", &self.tau_per_f),
        ] {
            if v.len() != n {
                return Err(Error::input(
                    "FE unit fields",
                    format!("{name} has {} entries but x_over_l has {n}", v.len()),
                ));
            }
        }
        let tau_sum: f64 = self.w_over_l.iter().zip(&self.tau_per_f).map(|(w, t)| w * t).sum();
        // Negated so that a NaN sum is rejected too.
        if !((tau_sum - 1.0).abs() <= TAU_SUM_TOL) {
            return Err(Error::input(
                "FE unit fields",
                format!("tau_per_f integrates to {tau_sum}, not 1 within {TAU_SUM_TOL}: the interface shear must carry the tangential force"),
            ));
        }
        let mu_d = p.g() / (6.0 * self.h_over_l);
        let mu_s = mu_d / p.r();
        let iface = Interface {
            x: self.x_over_l.clone(),
            w: self.w_over_l.clone(),
            p0: self.p_per_n.iter().map(|v| v / mu_s).collect(),
            dp: self.p_per_f.clone(),
            s: self.tau_per_f.iter().map(|v| v / tau_sum).collect(),
            sigma0: self.tau_per_n.iter().map(|v| v / mu_s).collect(),
            mu_s,
            mu_d,
        };
        iface.validate()?;
        Ok(iface)
    }
}

/// FE-fed vs paper's-linear discrete runs on the same cells, and the analytic iteration.
#[derive(Debug, Clone)]
pub struct Comparison {
    pub params: Params,
    pub h_over_l: f64,
    pub t_over_l: f64,
    pub mu_s: f64,
    pub mu_d: f64,
    /// Discrete model on the FE fields.
    pub fe: Run,
    /// Discrete model on the paper's linear fields, same cells and friction coefficients.
    pub linear: Run,
    /// The paper's analytic iteration, as many events as `linear`.
    pub analytic: Vec<Event>,
    /// F_1(FE) - F_1(linear).
    pub d_f1: f64,
    /// Precursor lengths (x_i + 1/2), FE minus linear, for the precursors both runs have.
    pub d_lengths: Vec<f64>,
    /// n(FE) - n(linear); None if either run never reached stick-slip.
    pub d_n: Option<i64>,
    /// Stick-slip limit force, FE minus linear; None if either run never reached stick-slip.
    pub d_f_max: Option<f64>,
}

/// Runs the discrete model on the FE fields and on the paper's linear fields on the same
/// cells, for the control parameters (r, g), with at most `n_events` events each.
/// This is the entry point for `tribofe precursors --fe`.
pub fn compare(fields: &UnitFields, r: f64, g: f64, n_events: usize) -> Result<Comparison> {
    let p = Params::new(r, g)?;
    let fe_iface = fields.to_interface(&p)?;
    let lin_iface = Interface::linear(&p, fe_iface.mu_s, fe_iface.x.clone(), fe_iface.w.clone());
    let fe = discrete::simulate(&fe_iface, n_events)?;
    let linear = discrete::simulate(&lin_iface, n_events)?;
    let (Some(fe1), Some(lin1)) = (fe.events.first(), linear.events.first()) else {
        return Err(Error::input(
            "FE unit fields",
            "no slip event: the static threshold is never reached under tangential loading",
        ));
    };
    let length = |e: &CellEvent| e.x + 0.5;
    let d_lengths =
        fe.precursors().iter().zip(linear.precursors()).map(|(a, b)| length(a) - length(b)).collect();
    let d_n = fe.n_precursors().zip(linear.n_precursors()).map(|(a, b)| a as i64 - b as i64);
    let d_f_max = fe.f_limit().zip(linear.f_limit()).map(|(a, b)| a - b);
    Ok(Comparison {
        params: p,
        h_over_l: fields.h_over_l,
        t_over_l: fields.t_over_l,
        mu_s: fe_iface.mu_s,
        mu_d: fe_iface.mu_d,
        d_f1: fe1.f - lin1.f,
        analytic: super::simulate(&p, linear.events.len()),
        fe,
        linear,
        d_lengths,
        d_n,
        d_f_max,
    })
}

/// One geometry of a [`sweep`].
#[derive(Debug, Clone, PartialEq)]
pub struct SweepRow {
    pub h_over_l: f64,
    pub t_over_l: f64,
    pub n_fe: Option<usize>,
    pub n_linear: Option<usize>,
    pub f1_fe: f64,
    pub f1_linear: f64,
    pub f_max_fe: Option<f64>,
    pub f_max_linear: Option<f64>,
    /// Largest |difference| in precursor length (x_i + 1/2) over the common precursors.
    pub max_abs_d_length: f64,
    /// Why the model could not be run on this geometry (e.g. the FE pressure opens the
    /// contact at the trailing edge); the figures above are then meaningless (zero).
    pub outside_model: Option<String>,
}

/// [`compare`] over every (H/L, t/L) pair, at fixed (r, g). `fields(h, t)` returns the FE unit
/// fields for that geometry (typically one FE solve per call).
pub fn sweep(
    h_over_l: &[f64],
    t_over_l: &[f64],
    r: f64,
    g: f64,
    n_events: usize,
    mut fields: impl FnMut(f64, f64) -> Result<UnitFields>,
) -> Result<Vec<SweepRow>> {
    let mut rows = Vec::with_capacity(h_over_l.len() * t_over_l.len());
    for &h in h_over_l {
        for &t in t_over_l {
            let uf = fields(h, t)?;
            if uf.h_over_l != h || uf.t_over_l != t {
                return Err(Error::input(
                    "FE unit fields",
                    format!(
                        "asked for H/L = {h}, t/L = {t}, got fields for H/L = {}, t/L = {}",
                        uf.h_over_l, uf.t_over_l
                    ),
                ));
            }
            // A geometry outside the model (contact opening) is a finding, not a failure.
            let c = match compare(&uf, r, g, n_events) {
                Ok(c) => c,
                Err(e) => {
                    rows.push(SweepRow {
                        h_over_l: h,
                        t_over_l: t,
                        n_fe: None,
                        n_linear: None,
                        f1_fe: 0.0,
                        f1_linear: 0.0,
                        f_max_fe: None,
                        f_max_linear: None,
                        max_abs_d_length: 0.0,
                        outside_model: Some(e.to_string()),
                    });
                    continue;
                }
            };
            rows.push(SweepRow {
                h_over_l: h,
                t_over_l: t,
                n_fe: c.fe.n_precursors(),
                n_linear: c.linear.n_precursors(),
                f1_fe: c.fe.events[0].f,
                f1_linear: c.linear.events[0].f,
                f_max_fe: c.fe.f_limit(),
                f_max_linear: c.linear.f_limit(),
                max_abs_d_length: c.d_lengths.iter().fold(0.0, |m, d| m.max(d.abs())),
                outside_model: None,
            });
        }
    }
    Ok(rows)
}
