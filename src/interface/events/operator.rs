//! The seam between the event solver and the condensed operator S.
//!
//! The solver decides states (the active set); an [`Operator`] holds S (2n + 3 DOFs: u_0..u_{n-1},
//! v_0..v_{n-1}, U_H, V, theta) and solves the system of the current [`ActiveSet`] for the
//! [`Affine`] response in the load parameter lambda. [`Dense`] is the reference: the dense S and
//! the bordered inverse of its free block ([`super::inverse`]).

use super::inverse::{Bordered, Rows};
use super::{tolerances, BorderRole, NodeState, Phase};
use crate::error::Result;

/// The active set an operator solves for, owned by the solver: per node its state, the anchor
/// of a stuck node (its prescribed u, m), the magnitude of its slip coefficient and its Newton
/// spring (N/m per m, centred on `spring_u`, m); the loading phase and the normal force.
pub(crate) struct ActiveSet {
    pub n: usize,
    pub states: Vec<NodeState>,
    pub anchor: Vec<f64>,
    pub mu_slip: Vec<f64>,
    pub spring: Vec<f64>,
    pub spring_u: Vec<f64>,
    pub phase: Phase,
    /// N, N/m.
    pub n_force: f64,
    /// The rig's border DOFs after the interface's 2n, the drive first
    /// ([`super::TOP_PLATE`]: U_H, V, theta).
    pub border: Vec<BorderRole>,
}

impl ActiveSet {
    /// Number of DOFs, 2n + k (k border DOFs).
    pub fn nd(&self) -> usize {
        2 * self.n + self.border.len()
    }
    /// The driven DOF (the border's first).
    pub fn iu(&self) -> usize {
        2 * self.n
    }
    /// The DOF loaded by -N (a plate's V), if the rig has one.
    pub fn iv(&self) -> Option<usize> {
        self.border.iter().position(|&r| r == BorderRole::Normal).map(|p| 2 * self.n + p)
    }
    /// A plate's rotation, if the rig has one.
    pub fn ith(&self) -> Option<usize> {
        self.border.iter().position(|&r| r == BorderRole::Tilt).map(|p| 2 * self.n + p)
    }
    /// Role of border DOF d (>= 2n).
    fn role(&self, d: usize) -> BorderRole {
        self.border[d - 2 * self.n]
    }

    /// Whether DOF d is unknown: u_i of a node not stuck, v_i of an open node, the border's
    /// DOFs under a force (V, theta; the drive and the pressure's amplitude are prescribed).
    pub fn is_free(&self, d: usize) -> bool {
        let n = self.n;
        if d < n {
            !matches!(self.states[d], NodeState::Stick)
        } else if d < 2 * n {
            matches!(self.states[d - n], NodeState::Open)
        } else {
            matches!(self.role(d), BorderRole::Normal | BorderRole::Free | BorderRole::Tilt)
        }
    }

    /// Prescribed value of border DOF d (>= 2n), b0 + lambda b1: the drive 0 then lambda, the
    /// pressure's amplitude lambda N then N; (0, 0) for a free DOF.
    pub fn pinned(&self, d: usize) -> (f64, f64) {
        match (self.role(d), self.phase) {
            (BorderRole::Drive, Phase::Drive) => (0.0, 1.0),
            (BorderRole::Pressure, Phase::Normal) => (0.0, self.n_force),
            (BorderRole::Pressure, Phase::Drive) => (self.n_force, 0.0),
            _ => (0.0, 0.0),
        }
    }

    /// External force on DOF d, f0 + lambda f1 (N/m): [`Self::v_force`] on the DOF loaded by
    /// N, 0 elsewhere.
    pub fn ext_force(&self, d: usize) -> (f64, f64) {
        if d >= 2 * self.n && self.role(d) == BorderRole::Normal {
            self.v_force()
        } else {
            (0.0, 0.0)
        }
    }

    /// Coefficient c of the slip row S[u_i] + c S[v_i] of DOF d (0 if not a slip row).
    pub fn slip_coef(&self, d: usize) -> f64 {
        if d < self.n {
            if let NodeState::Slip(s) = self.states[d] {
                return s * self.mu_slip[d];
            }
        }
        0.0
    }

    /// Newton spring of DOF d's row and the u it is centred on ((0, 0) for none).
    pub fn spring(&self, d: usize) -> (f64, f64) {
        if d < self.n {
            (self.spring[d], self.spring_u[d])
        } else {
            (0.0, 0.0)
        }
    }

    /// Row key of DOF d: its slip coefficient and Newton spring (what the free rows depend on
    /// besides S).
    pub fn row_key(&self, d: usize) -> (f64, f64) {
        (self.slip_coef(d), self.spring(d).0)
    }

    /// External force on V, f0 + lambda f1 (N/m): -N ramped in the normal phase, held after.
    pub fn v_force(&self) -> (f64, f64) {
        match self.phase {
            Phase::Normal => (0.0, -self.n_force),
            Phase::Drive => (-self.n_force, 0.0),
        }
    }
}

/// Affine solution b = b0 + lambda b1 (displacements, m), f = f0 + lambda f1 = S b (forces,
/// N/m) over all 2n + 3 DOFs.
#[derive(Clone)]
pub(crate) struct Affine {
    pub b0: Vec<f64>,
    pub b1: Vec<f64>,
    pub f0: Vec<f64>,
    pub f1: Vec<f64>,
}

impl Affine {
    pub fn b(&self, i: usize, lam: f64) -> f64 {
        self.b0[i] + lam * self.b1[i]
    }
    pub fn f(&self, i: usize, lam: f64) -> f64 {
        self.f0[i] + lam * self.f1[i]
    }
}

/// The condensed operator S as the event solver uses it.
///
/// Contract. The system of an [`ActiveSet`]: constrained DOFs take prescribed values affine in
/// lambda (a stuck node's u_i = anchor_i, a node in contact's v_i = 0, U_H = 0 in the normal
/// phase and = lambda in the drive phase); every free DOF d has the equation
///   (S b)_d + c_d (S b)_{d+n} + k_d (b_d - u_k,d) = e_d,
/// with c_d = [`ActiveSet::slip_coef`] (a slipping u-row: T = -s mu P), (k, u_k) =
/// [`ActiveSet::spring`], e = [`ActiveSet::v_force`] on V and 0 elsewhere (theta: no moment,
/// an open node's T = P = 0). [`Operator::solve`] returns the [`Affine`] b and f = S b over all
/// DOFs. Every change of the set is notified in the order the solver makes it, after the
/// set holds it; an implementation may update incrementally (the dense reference must, to keep
/// the committed outputs byte for byte) or mark itself dirty and refactorise on the next solve.
/// Equations must be solved to the residual [`tolerances::RESIDUAL`] of the largest force.
pub(crate) trait Operator {
    /// The set has changed arbitrarily (start of a run, or many coefficients at once): form
    /// its free system afresh. Err if singular (the interface leaves the block free to move).
    fn refresh(&mut self, set: &ActiveSet) -> Result<()>;
    /// Node i has changed from `old` (stuck at `old_anchor` if stuck) to `set.states[i]`
    /// (stuck at `set.anchor[i]`).
    fn change(&mut self, set: &ActiveSet, i: usize, old: NodeState, old_anchor: f64) -> Result<()>;
    /// Many nodes have changed at once (each already in `set`).
    fn bulk(&mut self, set: &ActiveSet) -> Result<()>;
    /// Node i's slip coefficient or spring has changed, its state not.
    fn coefficient(&mut self, set: &ActiveSet, i: usize) -> Result<()>;
    /// Prescribed values have changed outside [`Self::change`] (anchors moved, phase switched).
    fn pins_moved(&mut self);
    /// The affine solution of the set.
    fn solve(&mut self, set: &ActiveSet) -> Result<Affine>;
    /// Entries of the free system's inverse at the given free DOFs' rows and columns,
    /// row-major (slip weakening's stability test of a Newton equilibrium).
    fn inverse_block(&mut self, set: &ActiveSet, dofs: &[usize]) -> Result<Vec<f64>>;
    /// Incremental updates and full factorisations so far (reported in [`super::Run`]).
    fn counts(&self) -> (usize, usize);
    /// Sign of the free system's determinant where the representation has it for the cost of
    /// a solve (the banded factor and its capacitance); None: not kept (the caller tests
    /// stability another way). The exact weakening path's test of a tangent's stability.
    fn det_sign(&mut self, _set: &ActiveSet) -> Result<Option<f64>> {
        Ok(None)
    }
    /// The rig's border roles after the interface's 2n DOFs (the top plate's unless the
    /// representation holds another rig).
    fn border(&self) -> Vec<BorderRole> {
        super::TOP_PLATE.to_vec()
    }
}

/// The dense reference: S row-major, the bordered inverse of the free block, and g = S b_c,
/// the constrained values' forces, kept current change by change.
pub(crate) struct Dense<'a> {
    s: &'a [f64],
    nd: usize,
    inv: Bordered,
    /// S b0 and S b1 over the constrained values, or None to rebuild.
    g: Option<(Vec<f64>, Vec<f64>)>,
    g_updates: usize,
    border: Vec<BorderRole>,
}

impl<'a> Dense<'a> {
    /// S: nd x nd row-major, symmetric, of the top-plate rig.
    pub fn new(s: &'a [f64], nd: usize) -> Dense<'a> {
        Dense { s, nd, inv: Bordered::new(nd), g: None, g_updates: 0, border: super::TOP_PLATE.to_vec() }
    }

    /// S of a rig whose border DOFs (after the interface's 2n) have the roles `border`; nd is
    /// sqrt(len S).
    pub fn with_border(s: &'a [f64], border: &[BorderRole]) -> Dense<'a> {
        let nd = (s.len() as f64).sqrt().round() as usize;
        Dense { border: border.to_vec(), ..Dense::new(s, nd) }
    }
}

/// The free system's rows of the dense S under an active set.
struct View<'b> {
    s: &'b [f64],
    set: &'b ActiveSet,
}

impl Rows for View<'_> {
    fn is_free(&self, d: usize) -> bool {
        self.set.is_free(d)
    }
    fn entry(&self, a: usize, b: usize) -> f64 {
        let (n, nd) = (self.set.n, self.set.nd());
        let c = self.set.slip_coef(a);
        let mut v = self.s[a * nd + b];
        if c != 0.0 {
            v += c * self.s[(a + n) * nd + b];
        }
        if a == b && a < n {
            v += self.set.spring[a];
        }
        v
    }
    fn key(&self, d: usize) -> (f64, f64) {
        self.set.row_key(d)
    }
    fn pivot_scale(&self, d: usize) -> f64 {
        self.s[d * self.set.nd() + d].abs().max(f64::MIN_POSITIVE)
    }
}

impl Operator for Dense<'_> {
    fn refresh(&mut self, set: &ActiveSet) -> Result<()> {
        self.inv.refresh(&View { s: self.s, set })
    }

    fn change(&mut self, set: &ActiveSet, i: usize, old: NodeState, old_anchor: f64) -> Result<()> {
        let (n, nd, s) = (set.n, self.nd, self.s);
        let new = set.states[i];
        // Keep g0 = S b0 current: a stuck node's anchor leaves or enters b0 (row i of S).
        if let Some((g0, _)) = &mut self.g {
            let mut axpy = |a: f64| {
                if a != 0.0 {
                    g0.iter_mut().zip(&s[i * nd..(i + 1) * nd]).for_each(|(g, v)| *g += a * v);
                }
            };
            if old == NodeState::Stick {
                axpy(-old_anchor);
            }
            if new == NodeState::Stick {
                axpy(set.anchor[i]);
            }
            self.g_updates += 1;
            if self.g_updates > tolerances::REBUILD {
                self.g = None;
            }
        }
        if !matches!(old, NodeState::Stick) {
            self.inv.remove(i);
        }
        if matches!(old, NodeState::Open) {
            self.inv.remove(n + i);
        }
        let view = View { s, set };
        if !matches!(new, NodeState::Stick) {
            self.inv.add(i, &view)?;
        }
        if matches!(new, NodeState::Open) {
            self.inv.add(n + i, &view)?;
        }
        Ok(())
    }

    fn bulk(&mut self, set: &ActiveSet) -> Result<()> {
        self.g = None;
        self.inv.rebase(&View { s: self.s, set })
    }

    fn coefficient(&mut self, set: &ActiveSet, i: usize) -> Result<()> {
        self.inv.remove(i);
        self.inv.add(i, &View { s: self.s, set })
    }

    fn pins_moved(&mut self) {
        self.g = None;
    }

    fn solve(&mut self, set: &ActiveSet) -> Result<Affine> {
        let (n, nd) = (set.n, self.nd);
        let mut b0 = vec![0.0; nd];
        let mut b1 = vec![0.0; nd];
        for i in 0..n {
            if matches!(set.states[i], NodeState::Stick) {
                b0[i] = set.anchor[i];
            }
        }
        for d in 2 * n..nd {
            (b0[d], b1[d]) = set.pinned(d);
        }
        let s = self.s;
        // g = S b_c (the constrained values' forces), kept up to date by `change` (O(N) per
        // change) and rebuilt in one pass over S after bulk changes or [`tolerances::REBUILD`] updates; the free
        // rows' right-hand sides are read from it, and f = g + sum_k z_k S[free_k, :].
        if self.g.is_none() {
            // S is symmetric: S b = sum over the nonzero b_j of b_j S[j, :] (contiguous rows).
            let mut g0 = vec![0.0; nd];
            let mut g1 = vec![0.0; nd];
            for (g, b) in [(&mut g0, &b0), (&mut g1, &b1)] {
                for (j, &bj) in b.iter().enumerate().filter(|(_, &v)| v != 0.0) {
                    g.iter_mut().zip(&s[j * nd..(j + 1) * nd]).for_each(|(g, v)| *g += bj * v);
                }
            }
            self.g = Some((g0, g1));
            self.g_updates = 0;
        }
        let (g0, g1) = self.g.clone().expect("set above");
        for attempt in 0..2 {
            let dofs = self.inv.dofs();
            let m = dofs.len();
            let mut r0 = vec![0.0; m];
            let mut r1 = vec![0.0; m];
            for (k, &a) in dofs.iter().enumerate() {
                let (mut s0, mut s1) = set.ext_force(a);
                s0 -= g0[a];
                s1 -= g1[a];
                let c = set.slip_coef(a);
                if c != 0.0 {
                    s0 -= c * g0[a + n];
                    s1 -= c * g1[a + n];
                }
                if a < n {
                    s0 += set.spring[a] * set.spring_u[a];
                }
                r0[k] = s0;
                r1[k] = s1;
            }
            let mut z0 = vec![0.0; m];
            let mut z1 = vec![0.0; m];
            for i in 0..m {
                let row = self.inv.row(i);
                z0[i] = row.iter().zip(&r0).map(|(a, b)| a * b).sum();
                z1[i] = row.iter().zip(&r1).map(|(a, b)| a * b).sum();
            }
            let (mut c0, mut c1) = (b0.clone(), b1.clone());
            for (k, &a) in dofs.iter().enumerate() {
                c0[a] = z0[k];
                c1[a] = z1[k];
            }
            let (mut f0, mut f1) = (g0.clone(), g1.clone());
            for (k, &a) in dofs.iter().enumerate() {
                let (za, zb) = (z0[k], z1[k]);
                let row = &s[a * nd..(a + 1) * nd];
                for j in 0..nd {
                    f0[j] += za * row[j];
                    f1[j] += zb * row[j];
                }
            }
            // Residual of the free equations relative to the largest force: a drifting
            // inverse (many bordering updates) is rebuilt once.
            let mut res = 0.0f64;
            let big = f0.iter().chain(&f1).fold(1e-300f64, |m, v| m.max(v.abs()));
            for &a in dofs {
                let c = set.slip_coef(a);
                let (k, ku) = set.spring(a);
                let (e0, e1) = set.ext_force(a);
                let q0 = f0[a] + if c != 0.0 { c * f0[a + n] } else { 0.0 } - e0 + k * (c0[a] - ku);
                let q1 = f1[a] + if c != 0.0 { c * f1[a + n] } else { 0.0 } - e1 + k * c1[a];
                res = res.max(q0.abs()).max(q1.abs());
            }
            if res > tolerances::RESIDUAL * big && attempt == 0 {
                self.refresh(set)?;
                continue;
            }
            return Ok(Affine { b0: c0, b1: c1, f0, f1 });
        }
        unreachable!("the second attempt returns")
    }

    fn inverse_block(&mut self, _set: &ActiveSet, dofs: &[usize]) -> Result<Vec<f64>> {
        let pos: Vec<usize> = dofs.iter().map(|&d| self.inv.pos(d).expect("a free DOF")).collect();
        Ok(pos
            .iter()
            .flat_map(|&r| pos.iter().map(move |&c| (r, c)))
            .map(|(r, c)| self.inv.row(r)[c])
            .collect())
    }

    fn counts(&self) -> (usize, usize) {
        (self.inv.updates, self.inv.refreshes)
    }

    fn border(&self) -> Vec<BorderRole> {
        self.border.clone()
    }
}
