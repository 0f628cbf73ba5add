//! The quasi-static loading between dynamic events, exact and without stepping, on the
//! condensed block + rigid plate (S of [`crate::interface::condense`] at the drive height H).
//!
//! Boundary vector b = (u_0..u_{n-1}, v_0..v_{n-1}, U_H, V, theta); the forces that hold it
//! are f = S b: T_i = f_i and P_i = f_{n+i} are the flat's forces on node i, F = f_{2n} the
//! drive's. Each node is stuck at an anchor (u_i = a_i, v_i = 0), slipping (v_i = 0,
//! T_i = -s mu_i P_i with its coefficient mu_i frozen over the segment) or open
//! (T_i = P_i = 0); the plate's V is loaded by -N and theta by no moment. For a fixed set of
//! states b is affine in the load parameter (N in the normal phase, U_H in the drive), so the
//! next change (a threshold |T| = mu P, P = 0, a gap closing, a slip rate reversing, or a
//! slipping node weakening by D_c/20) is found exactly, as in the event solver
//! (`interface::events`), of which this is a small dense re-implementation: the two are
//! cross-checked on Coulomb friction (tests/dynamics.rs).

use crate::error::{Error, Result};
use nalgebra::{DMatrix, DVector};

/// One equation: coefficients over rows of S, its target at lambda = 0, the target's slope.
type Equation = (Vec<(usize, f64)>, f64, f64);

/// State of one interface node in the static phase.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Node {
    Stick {
        anchor: f64,
    },
    /// Slip direction s = +1 or -1.
    Slip {
        s: f64,
    },
    Open,
}

/// Which load the parameter lambda is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Load {
    /// lambda = N (N/m) with U_H = 0.
    Normal,
    /// lambda = U_H (m) with N held.
    Drive,
}

/// b(lambda) = b0 + lambda b1 and f = S b = f0 + lambda f1 for one set of states.
#[derive(Debug, Clone)]
pub struct Path {
    pub b0: Vec<f64>,
    pub b1: Vec<f64>,
    pub f0: Vec<f64>,
    pub f1: Vec<f64>,
}

impl Path {
    pub fn b(&self, k: usize, lam: f64) -> f64 {
        self.b0[k] + lam * self.b1[k]
    }
    pub fn f(&self, k: usize, lam: f64) -> f64 {
        self.f0[k] + lam * self.f1[k]
    }
}

/// The static interface: S at height H, the node states and their frozen coefficients.
#[derive(Debug, Clone)]
pub struct Statics {
    pub n: usize,
    s: Vec<f64>,
    pub nodes: Vec<Node>,
    /// Coefficient of each node: its threshold when stuck, its friction when slipping.
    pub mu: Vec<f64>,
    /// N held in the drive phase, N/m.
    pub n_force: f64,
}

impl Statics {
    /// `s`: the condensed matrix at the drive height ((2n + 3)^2, row-major).
    pub fn new(s: Vec<f64>, n: usize, mu_s: f64) -> Self {
        assert_eq!(s.len(), (2 * n + 3).pow(2));
        Self { n, s, nodes: vec![Node::Stick { anchor: 0.0 }; n], mu: vec![mu_s; n], n_force: 0.0 }
    }

    pub fn dim(&self) -> usize {
        2 * self.n + 3
    }

    fn s_times(&self, b: &[f64]) -> Vec<f64> {
        let nd = self.dim();
        (0..nd).map(|i| self.s[i * nd..(i + 1) * nd].iter().zip(b).map(|(a, x)| a * x).sum()).collect()
    }

    /// The affine path of the current states under `load`.
    pub fn solve(&self, load: Load) -> Result<Path> {
        let (n, nd) = (self.n, self.dim());
        let (iu, iv, ith) = (2 * n, 2 * n + 1, 2 * n + 2);
        // Known parts of b: k0 + lambda k1; targets of the equations: t0 + lambda t1.
        let (mut k0, mut k1) = (vec![0.0; nd], vec![0.0; nd]);
        let mut unknown = Vec::new();
        // Equations as (coefficients over rows of S, target at lambda 0, target slope).
        let mut eqs: Vec<Equation> = Vec::new();
        for i in 0..n {
            match self.nodes[i] {
                Node::Stick { anchor } => k0[i] = anchor,
                Node::Slip { s } => {
                    unknown.push(i);
                    eqs.push((vec![(i, 1.0), (n + i, s * self.mu[i])], 0.0, 0.0));
                }
                Node::Open => {
                    unknown.push(i);
                    unknown.push(n + i);
                    eqs.push((vec![(i, 1.0)], 0.0, 0.0));
                    eqs.push((vec![(n + i, 1.0)], 0.0, 0.0));
                }
            }
        }
        unknown.push(iv);
        unknown.push(ith);
        match load {
            Load::Normal => eqs.push((vec![(iv, 1.0)], 0.0, -1.0)),
            Load::Drive => {
                k1[iu] = 1.0;
                eqs.push((vec![(iv, 1.0)], -self.n_force, 0.0));
            }
        }
        eqs.push((vec![(ith, 1.0)], 0.0, 0.0));
        let m = unknown.len();
        let a = DMatrix::from_fn(m, m, |e, k| {
            eqs[e].0.iter().map(|&(row, c)| c * self.s[row * nd + unknown[k]]).sum::<f64>()
        });
        let (sk0, sk1) = (self.s_times(&k0), self.s_times(&k1));
        let rhs = |sk: &[f64], t: &dyn Fn(&Equation) -> f64| {
            DVector::from_fn(m, |e, _| t(&eqs[e]) - eqs[e].0.iter().map(|&(row, c)| c * sk[row]).sum::<f64>())
        };
        let (r0, r1) = (rhs(&sk0, &|e| e.1), rhs(&sk1, &|e| e.2));
        let lu = a.lu();
        let (z0, z1) = match (lu.solve(&r0), lu.solve(&r1)) {
            (Some(z0), Some(z1)) => (z0, z1),
            _ => {
                return Err(Error::Singular {
                    detail: "the static interface system is singular (every node open or slipping?)".into(),
                    node: None,
                    component: None,
                })
            }
        };
        let (mut b0, mut b1) = (k0, k1);
        for (k, &j) in unknown.iter().enumerate() {
            b0[j] = z0[k];
            b1[j] = z1[k];
        }
        let (f0, f1) = (self.s_times(&b0), self.s_times(&b1));
        if b0.iter().chain(&b1).chain(&f0).chain(&f1).any(|v| !v.is_finite()) {
            return Err(Error::Untrustworthy {
                detail: "the static interface solve produced non-finite values".into(),
                hint: "check the scene's material and mesh".into(),
            });
        }
        Ok(Path { b0, b1, f0, f1 })
    }

    /// Tangential stiffness of the all-stuck interface dF/dU_H, N/m per m.
    pub fn k_bonded(&self) -> Result<f64> {
        let mut all = self.clone();
        all.nodes = vec![Node::Stick { anchor: 0.0 }; self.n];
        Ok(all.solve(Load::Drive)?.f1[2 * self.n])
    }

    /// The most violated state at lambda (force tolerance `ftol` N/m, gap tolerance `gtol` m),
    /// with the state it must take; None when the states are consistent.
    pub fn violation(&self, p: &Path, lam: f64, ftol: f64, gtol: f64) -> Option<(usize, Node)> {
        let n = self.n;
        // A slip rate below this (round-off of the interface rates) is no reversal.
        let rtol = 1e-9 * p.b1[..n].iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let mut worst: Option<(f64, usize, Node)> = None;
        let mut take = |v: f64, i: usize, to: Node| {
            if worst.is_none_or(|w| v > w.0) {
                worst = Some((v, i, to));
            }
        };
        for i in 0..n {
            let (t, pn, u, g) = (p.f(i, lam), p.f(n + i, lam), p.b(i, lam), p.b(n + i, lam));
            match self.nodes[i] {
                Node::Stick { .. } => {
                    if pn < -ftol {
                        take(-pn / ftol, i, Node::Open);
                    } else if t.abs() > self.mu[i] * pn + ftol {
                        take((t.abs() - self.mu[i] * pn) / ftol, i, Node::Slip { s: -t.signum() });
                    }
                }
                Node::Slip { s } => {
                    if pn < -ftol {
                        take(-pn / ftol, i, Node::Open);
                    } else if s * p.b1[i] < -rtol {
                        // Slipping backwards as the load grows: it sticks where it is.
                        take(1.0, i, Node::Stick { anchor: u });
                    }
                }
                Node::Open => {
                    if g < -gtol {
                        take(-g / gtol, i, Node::Stick { anchor: u });
                    }
                }
            }
        }
        worst.map(|w| (w.1, w.2))
    }

    /// The first lambda in (lam, lam_end] at which a state must change along `p`, with the
    /// node and its new state; `weaken`: for slip weakening, the slip each node may still make
    /// before its frozen coefficient must be brought to its slip: a slipping node reaching it
    /// stops the segment (node state unchanged). None: the path reaches lam_end.
    pub fn next_change(
        &self,
        p: &Path,
        lam: f64,
        lam_end: f64,
        weaken: Option<&[f64]>,
    ) -> Option<(f64, usize, Node)> {
        let n = self.n;
        let mut best: Option<(f64, usize, Node)> = None;
        let mut cand = |l: f64, i: usize, to: Node| {
            if l <= lam_end && best.is_none_or(|b| l < b.0) {
                best = Some((l, i, to));
            }
        };
        // g0 + lambda g1 >= 0 crossing zero beyond lam (g at lam clamped at 0 from below).
        let cross = |g0: f64, g1: f64| -> Option<f64> {
            if g1 < 0.0 {
                let at = (g0 + lam * g1).max(0.0);
                Some(lam + at / -g1)
            } else {
                None
            }
        };
        for i in 0..n {
            let (t0, t1, p0, p1) = (p.f0[i], p.f1[i], p.f0[n + i], p.f1[n + i]);
            match self.nodes[i] {
                Node::Stick { .. } => {
                    let mu = self.mu[i];
                    if let Some(l) = cross(p0, p1) {
                        cand(l, i, Node::Open);
                    }
                    if let Some(l) = cross(mu * p0 - t0, mu * p1 - t1) {
                        cand(l, i, Node::Slip { s: -1.0 });
                    }
                    if let Some(l) = cross(mu * p0 + t0, mu * p1 + t1) {
                        cand(l, i, Node::Slip { s: 1.0 });
                    }
                }
                Node::Slip { s } => {
                    if let Some(l) = cross(p0, p1) {
                        cand(l, i, Node::Open);
                    }
                    if let Some(left) = weaken {
                        let rate = (s * p.b1[i]).abs();
                        if rate > 0.0 && left[i].is_finite() {
                            cand(lam + left[i].max(0.0) / rate, i, self.nodes[i]);
                        }
                    }
                }
                Node::Open => {
                    if let Some(l) = cross(p.b0[n + i], p.b1[n + i]) {
                        cand(l, i, Node::Stick { anchor: 0.0 });
                    }
                }
            }
        }
        best
    }
}
