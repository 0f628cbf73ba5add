//! One banded factorisation reused across the event solver's state changes (issue 32).
//!
//! A coulomb event changes one node, so one or two rows of the free system M. Instead of a
//! factorisation per solve, the factor of a reference system M0 is kept and the rows replaced
//! since (the set R, at most [`Solving::rank_cap`]) enter through the capacitance (Woodbury):
//! M = M0 + E W (E the unit columns of R, W the row differences), so
//!   M^{-1} = M0^{-1} - Z C^{-1} W M0^{-1},  Z = M0^{-1} E,  C = I + W Z (|R| x |R|),
//! one band solve per row when it enters R. The previous solution x makes the usual solve
//! cheaper still: when only rows of R (and right-hand sides on them) changed, its residual
//! rho = b - M x lies on R, and M^{-1} E rho_R = Z C^{-1} rho_R needs no band solve at all.
//! Every solution is checked against the current rows (its residual, one sparse product) and
//! refined by the full Woodbury solve until it meets [`REFINE`]; past the rank cap, or if that
//! fails, the band is refactored at the current set (whose solve is the from-scratch path).
//!
//! About 700 lines: the low-rank bookkeeping, the residual checks and the small capacitance
//! LU are one algorithm whose invariants (R, Z, W Z and the carried residuals) must change
//! together; its test is in `reuse/tests.rs`.

use super::{BandedOperator, Factored, Rows};
use crate::error::Result;
use crate::interface::events::operator::{ActiveSet, Affine, Operator};
use crate::interface::events::{NodeState, Phase};
use crate::linalg::banded::Banded;

/// Rows replaced since the factorisation past which the band is refactored: a solve costs
/// O(|R| m) in Z C^{-1}, a factorisation O(m kl (kl + ku)) plus a band solve per row of Z
/// rebuilt; their balance at m = 6,411, kl = ku = 11 (coulomb at 801 nodes, ~1.2 rows an
/// event) is near |R| ~ 20. Caps of 8 to 48 timed the same within the noise of the loaded
/// machine (docs/speed.md). (A cost-based cap and a rule for state flips were tried for the
/// exact weakening path and dropped: they moved the stepped default's event sequence.)
pub const RANK_CAP: usize = 24;

/// Componentwise backward error accepted for a solution: every equation's residual within
/// this fraction of the size of its own terms (sum |M_rj x_j| + |b_r|), as LAPACK's
/// refinement aims for (xGERFS): 32 ulps, a few times the round-off of evaluating a row of
/// ~18 terms, so each equation holds to round-off whatever the scale of its forces.
pub const REFINE: f64 = 32.0 * f64::EPSILON;

/// A solution's residual b - M x, its equations' sizes (sum |M_rj x_j| + |b_r|) and K x.
type Checked = (Vec<f64>, Vec<f64>, Vec<f64>);

/// What a boundary row depends on besides K: free, slip coefficient, spring.
type Key = (bool, f64, f64);

/// The banded operator behind the event solver's seam, reusing one factor (module docs).
pub(crate) struct Solving<'a> {
    op: &'a BandedOperator,
    /// Band row -> boundary DOF (usize::MAX: interior).
    bnd: Vec<usize>,
    base: Option<Factored>,
    spare: Option<Banded>,
    /// Each boundary DOF's key and the border rows' free flags at the factorisation.
    ref_key: Vec<Key>,
    ref_border: [bool; 3],
    /// R: boundary DOFs whose rows changed since, the key each difference was formed with,
    /// the differences (sparse over the m + 3 columns), Z's columns (m + 3 each), W Z.
    in_r: Vec<usize>,
    r_dofs: Vec<usize>,
    r_key: Vec<Key>,
    w: Vec<Vec<(usize, f64)>>,
    z: Vec<Vec<f64>>,
    wz: Vec<Vec<f64>>,
    /// The last solve: its solutions, residuals, right-hand sides and row keys.
    last: Option<Last>,
    /// Rows allowed in R before a refactorisation (0: refactor for every changed set).
    pub rank_cap: usize,
    pub row_updates: usize,
    pub factorisations: usize,
}

impl<'a> Solving<'a> {
    pub fn new(op: &'a BandedOperator) -> Solving<'a> {
        Solving::with_rank_cap(op, RANK_CAP)
    }

    pub fn with_rank_cap(op: &'a BandedOperator, rank_cap: usize) -> Solving<'a> {
        Solving {
            op,
            bnd: op.bnd(),
            base: None,
            spare: Some(op.workspace()),
            ref_key: vec![],
            ref_border: [false; 3],
            in_r: vec![usize::MAX; 2 * op.n],
            r_dofs: vec![],
            r_key: vec![],
            w: vec![],
            z: vec![],
            wz: vec![],
            last: None,
            rank_cap,
            row_updates: 0,
            factorisations: 0,
        }
    }

    fn key(rows: &Rows, n: usize, d: usize) -> Key {
        if d < n {
            (rows.free[d], rows.coef[d], rows.spring[d])
        } else {
            (rows.free[d], 0.0, 0.0)
        }
    }

    /// Row of boundary DOF d under `key`, sparse over the m + 3 columns (as
    /// [`BandedOperator::lhs`] evaluates it).
    fn row_of(&self, d: usize, key: Key) -> Vec<(usize, f64)> {
        let op = self.op;
        let r = op.pos(d);
        if !key.0 {
            return vec![(r, op.scale)];
        }
        let (c, v) = op.row(r);
        let mut out: Vec<(usize, f64)> = c.iter().copied().zip(v.iter().copied()).collect();
        if key.1 != 0.0 {
            let (c, v) = op.row(op.pv[d]);
            out.extend(c.iter().zip(v).map(|(&c, &v)| (c, key.1 * v)));
        }
        if key.2 != 0.0 {
            out.push((r, key.2));
        }
        out
    }

    /// Row of d now minus its row at the factorisation.
    fn delta(&self, d: usize, key: Key) -> Vec<(usize, f64)> {
        let mut all = self.row_of(d, key);
        all.extend(self.row_of(d, self.ref_key[d]).into_iter().map(|(c, v)| (c, -v)));
        all.sort_by_key(|e| e.0);
        let mut out: Vec<(usize, f64)> = Vec::with_capacity(all.len());
        for (c, v) in all {
            match out.last_mut() {
                Some(l) if l.0 == c => l.1 += v,
                _ => out.push((c, v)),
            }
        }
        out.retain(|e| e.1 != 0.0);
        out
    }

    /// Factors the current rows afresh; R empties.
    fn refactor(&mut self, rows: &Rows) -> Result<()> {
        let n = self.op.n;
        let lu = match (self.base.take(), self.spare.take()) {
            (Some(f), _) => f.into_band(),
            (None, Some(b)) => b,
            (None, None) => self.op.workspace(),
        };
        let (f, _, _) = self.op.factor(rows, lu)?;
        self.base = Some(f);
        self.ref_key = (0..2 * n).map(|d| Self::key(rows, n, d)).collect();
        self.ref_border = [0, 1, 2].map(|p| rows.free[2 * n + p]);
        for &d in &self.r_dofs {
            self.in_r[d] = usize::MAX;
        }
        self.r_dofs.clear();
        self.r_key.clear();
        self.w.clear();
        self.z.clear();
        self.wz.clear();
        self.factorisations += 1;
        Ok(())
    }

    /// Brings R up to the current rows, refactoring when it would pass the cap.
    fn update(&mut self, rows: &Rows) -> Result<()> {
        self.op.check_sizes(rows)?;
        let n = self.op.n;
        let border = [0, 1, 2].map(|p| rows.free[2 * n + p]);
        if self.base.is_none() || border != self.ref_border {
            return self.refactor(rows);
        }
        let keys: Vec<Key> = (0..2 * n).map(|d| Self::key(rows, n, d)).collect();
        let fresh = (0..2 * n).filter(|&d| self.in_r[d] == usize::MAX && keys[d] != self.ref_key[d]).count();
        if self.r_dofs.len() + fresh > self.rank_cap {
            return self.refactor(rows);
        }
        for d in 0..2 * n {
            let k = self.in_r[d];
            if k == usize::MAX && keys[d] != self.ref_key[d] {
                self.add_row(d, keys[d])?;
            } else if k != usize::MAX && keys[d] != self.r_key[k] {
                self.w[k] = self.delta(d, keys[d]);
                self.r_key[k] = keys[d];
                for j in 0..self.z.len() {
                    self.wz[k][j] = sparse_dot(&self.w[k], &self.z[j]);
                }
            }
        }
        Ok(())
    }

    /// d's row enters R: its Z column (one band solve) and its row and column of W Z.
    fn add_row(&mut self, d: usize, key: Key) -> Result<()> {
        let (m, r) = (self.op.m, self.op.pos(d));
        let mut e = vec![0.0; m];
        e[r] = 1.0;
        let mut z = vec![0.0; m + 3];
        self.base.as_ref().expect("factored").apply(&mut e, [0.0; 3], &mut z)?;
        let w = self.delta(d, key);
        let k = self.z.len();
        for i in 0..k {
            let v = sparse_dot(&self.w[i], &z);
            self.wz[i].push(v);
        }
        let mut row: Vec<f64> = self.z.iter().map(|zj| sparse_dot(&w, zj)).collect();
        row.push(sparse_dot(&w, &z));
        self.wz.push(row);
        self.in_r[d] = k;
        self.r_dofs.push(d);
        self.r_key.push(key);
        self.w.push(w);
        self.z.push(z);
        self.row_updates += 1;
        Ok(())
    }

    /// LU of the capacitance C = I + W Z (None: R is empty, or C is too ill-conditioned to
    /// trust, which the caller answers with a refactorisation).
    fn capacitance(&self) -> Option<Lu> {
        let k = self.z.len();
        let a: Vec<f64> = (0..k)
            .flat_map(|i| (0..k).map(move |j| (i, j)))
            .map(|(i, j)| self.wz[i][j] + f64::from(i == j))
            .collect();
        Lu::new(a, k)
    }

    /// M^{-1} rho by Woodbury (one band solve): x0 = M0^{-1} rho, x0 - Z C^{-1} W x0.
    fn woodbury(&self, rho: &[f64], cap: Option<&Lu>) -> Result<Vec<f64>> {
        let m = self.op.m;
        let mut z = rho[..m].to_vec();
        let mut x = vec![0.0; m + 3];
        self.base.as_ref().expect("factored").apply(&mut z, [rho[m], rho[m + 1], rho[m + 2]], &mut x)?;
        if let Some(lu) = cap {
            let t: Vec<f64> = self.w.iter().map(|w| sparse_dot(w, &x)).collect();
            let y = lu.solve(t);
            self.sub_zy(&mut x, &y, -1.0);
        }
        Ok(x)
    }

    /// x_k += Z y for each (k, y) of `ys` (at most two), reading Z once: the same sums, in
    /// the same order, as [`Self::sub_zy`] for each.
    fn add_zy(&self, xs: &mut [Vec<f64>], ys: &[(usize, Vec<f64>)]) {
        let (xa, xb, ya, yb) = match ys {
            [] => return,
            [(k, y)] => return self.sub_zy(&mut xs[*k], y, 1.0),
            [(0, ya), (1, yb)] => {
                let (a, b) = xs.split_at_mut(1);
                (&mut a[0], &mut b[0], ya, yb)
            }
            _ => {
                for (k, y) in ys {
                    self.sub_zy(&mut xs[*k], y, 1.0);
                }
                return;
            }
        };
        for ((zj, &a), &b) in self.z.iter().zip(ya).zip(yb) {
            match (a != 0.0, b != 0.0) {
                (true, true) => {
                    for ((x, y), z) in xa.iter_mut().zip(xb.iter_mut()).zip(zj) {
                        *x += a * z;
                        *y += b * z;
                    }
                }
                (true, false) => xa.iter_mut().zip(zj).for_each(|(x, z)| *x += a * z),
                (false, true) => xb.iter_mut().zip(zj).for_each(|(x, z)| *x += b * z),
                (false, false) => {}
            }
        }
    }

    /// x += s Z y.
    fn sub_zy(&self, x: &mut [f64], y: &[f64], s: f64) {
        for (zj, &yj) in self.z.iter().zip(y) {
            let a = s * yj;
            if a != 0.0 {
                x.iter_mut().zip(zj).for_each(|(x, z)| *x += a * z);
            }
        }
    }

    /// Right-hand sides of the m + 3 equations (lambda^0, lambda^1).
    fn rhs(&self, rows: &Rows) -> [Vec<f64>; 2] {
        let op = self.op;
        let (n, m) = (op.n, op.m);
        let mut b = [vec![0.0; m + 3], vec![0.0; m + 3]];
        for r in 0..m {
            let d = self.bnd[r];
            if d == usize::MAX {
                continue;
            }
            if !rows.free[d] {
                b[0][r] = op.scale * rows.b0[d];
                b[1][r] = op.scale * rows.b1[d];
                continue;
            }
            if let Some(&e) = rows.load.get(d) {
                b[0][r] += e;
            }
            if d < n && rows.spring[d] != 0.0 {
                b[0][r] += rows.spring[d] * rows.spring_u[d];
            }
        }
        let s = op.border_rhs(rows);
        for p in 0..3 {
            b[0][m + p] = s[0][p];
            b[1][m + p] = s[1][p];
        }
        b
    }

    /// Left-hand side of equation r (band row, or m + p for the plate's DOF p) at x, given
    /// K x's entries through `kx`.
    fn lhs_with(&self, rows: &Rows, r: usize, x: &[f64], kx: impl Fn(usize) -> f64) -> f64 {
        let op = self.op;
        let (n, m) = (op.n, op.m);
        let d = if r < m { self.bnd[r] } else { 2 * n + r - m };
        if d == usize::MAX {
            kx(r)
        } else if !rows.free[d] {
            op.scale * x[r]
        } else if d < n {
            let mut v = kx(r);
            if rows.coef[d] != 0.0 {
                v += rows.coef[d] * kx(op.pv[d]);
            }
            v + rows.spring[d] * x[r]
        } else {
            kx(r)
        }
    }

    /// b - M x at equation r alone.
    fn residual_at(&self, rows: &Rows, r: usize, x: &[f64], b: &[f64]) -> f64 {
        let kx = |q: usize| {
            let (c, v) = self.op.row(q);
            c.iter().zip(v).map(|(&c, &v)| v * x[c]).sum::<f64>()
        };
        b[r] - self.lhs_with(rows, r, x, kx)
    }

    /// rho = b - M x over the m + 3 equations for each (x, b) pair (one pass over K), each
    /// equation's size sum |M_rj x_j| + |b_r|, and K x (for the forces f = K x at the end).
    fn residuals(&self, rows: &Rows, x: &[Vec<f64>], b: &[Vec<f64>]) -> Vec<Checked> {
        let nu = self.op.m + 3;
        let k = x.len();
        let mut kx = vec![vec![0.0; nu]; k];
        let mut ka = vec![vec![0.0; nu]; k];
        match (x, &mut kx[..], &mut ka[..]) {
            ([x0, x1], [kx0, kx1], [ka0, ka1]) => self.op.product2(x0, x1, [kx0, ka0, kx1, ka1]),
            ([x0], [kx0], [ka0]) => {
                let (mut k1, mut a1) = (vec![0.0; nu], vec![0.0; nu]);
                self.op.product2(x0, x0, [kx0, ka0, &mut k1, &mut a1]);
            }
            _ => unreachable!("one or two right-hand sides"),
        }
        kx.into_iter()
            .zip(ka)
            .enumerate()
            .map(|(j, (kx, ka))| {
                let rho = (0..nu).map(|r| b[j][r] - self.lhs_with(rows, r, &x[j], |q| kx[q])).collect();
                let den = (0..nu).map(|r| self.size_at(rows, r, &x[j], |q| ka[q]) + b[j][r].abs()).collect();
                (rho, den, kx)
            })
            .collect()
    }

    /// sum |M_rj x_j| of equation r, given sum |K_qj x_j| through `ka`.
    fn size_at(&self, rows: &Rows, r: usize, x: &[f64], ka: impl Fn(usize) -> f64) -> f64 {
        let op = self.op;
        let (n, m) = (op.n, op.m);
        let d = if r < m { self.bnd[r] } else { 2 * n + r - m };
        if d == usize::MAX {
            ka(r)
        } else if !rows.free[d] {
            op.scale * x[r].abs()
        } else if d < n {
            ka(r) + rows.coef[d].abs() * ka(op.pv[d]) + (rows.spring[d] * x[r]).abs()
        } else {
            ka(r)
        }
    }

    /// Largest |rho_r| / size_r over the equations `keep` passes (0 where both vanish).
    fn backward_error(rho: &[f64], den: &[f64], keep: impl Fn(usize) -> bool) -> f64 {
        let mut w = 0.0f64;
        for (r, (&p, &d)) in rho.iter().zip(den).enumerate() {
            if p != 0.0 && keep(r) {
                w = w.max(p.abs() / d);
            }
        }
        w
    }

    /// Prescribed entries of x exactly as given (`vals`: per boundary DOF).
    fn pin(&self, rows: &Rows, x: &mut [f64], vals: &[f64]) {
        for d in (0..self.op.dim()).filter(|&d| !rows.free[d]) {
            x[self.op.pos(d)] = vals[d];
        }
    }

    /// Solutions of the current rows for right-hand sides b (prescribed values `vals`), from
    /// guesses (x, rho, size) if given: the low-rank step when a guess's residual lies on R,
    /// then refinement by Woodbury until every equation meets [`REFINE`]. Returns the
    /// solutions, their residuals and sizes, and whether they met it.
    fn solve_many(
        &self,
        rows: &Rows,
        b: &[Vec<f64>],
        vals: &[&[f64]],
        guess: Option<&[Guess]>,
        cap: Option<&Lu>,
    ) -> Result<(Vec<Vec<f64>>, Vec<Checked>, bool)> {
        let m = self.op.m;
        let mut xs = Vec::with_capacity(b.len());
        // Low-rank steps C^{-1} rho_R, applied below in one pass over Z for every solution.
        let mut low: Vec<(usize, Vec<f64>)> = Vec::new();
        for (k, bk) in b.iter().enumerate() {
            let x = match guess {
                _ if bk.iter().all(|&v| v == 0.0) => vec![0.0; m + 3],
                Some(g) => {
                    let (mut x, rho, den) = (g[k].x.clone(), &g[k].res, &g[k].den);
                    let off_r = |r: usize| {
                        !(r < m && self.bnd[r] != usize::MAX && self.in_r[self.bnd[r]] != usize::MAX)
                    };
                    if Self::backward_error(rho, den, off_r) <= REFINE {
                        if let Some(lu) = cap {
                            let rr: Vec<f64> = self.r_dofs.iter().map(|&d| rho[self.op.pos(d)]).collect();
                            low.push((k, lu.solve(rr)));
                        }
                    } else {
                        let dx = self.woodbury(rho, cap)?;
                        x.iter_mut().zip(&dx).for_each(|(x, d)| *x += d);
                    }
                    x
                }
                None => self.woodbury(bk, cap)?,
            };
            xs.push(x);
        }
        self.add_zy(&mut xs, &low);
        for (x, v) in xs.iter_mut().zip(vals) {
            self.pin(rows, x, v);
        }
        let mut ok = false;
        let mut res = vec![];
        for step in 0..4 {
            res = self.residuals(rows, &xs, b);
            let bad: Vec<usize> = (0..b.len())
                .filter(|&k| !(Self::backward_error(&res[k].0, &res[k].1, |_| true) <= REFINE))
                .collect();
            ok = bad.is_empty();
            if ok || step == 3 || xs.iter().flatten().any(|v| !v.is_finite()) {
                break;
            }
            for k in bad {
                let dx = self.woodbury(&res[k].0, cap)?;
                xs[k].iter_mut().zip(&dx).for_each(|(x, d)| *x += d);
                self.pin(rows, &mut xs[k], vals[k]);
            }
        }
        Ok((xs, res, ok))
    }

    /// Solutions of the current rows (see [`Self::solve_many`]); refactors once if the
    /// low-rank solution does not converge, and accepts a fresh factor's refined solution as
    /// the from-scratch banded path does, unless it is not finite.
    fn solve_full(
        &mut self,
        rows: &Rows,
        b: &[Vec<f64>],
        vals: &[&[f64]],
        guess: Option<&[Guess]>,
    ) -> Result<(Vec<Vec<f64>>, Vec<Checked>)> {
        self.update(rows)?;
        for attempt in 0..2 {
            let cap = self.capacitance();
            if cap.is_some() || self.z.is_empty() {
                let (x, rho, ok) = self.solve_many(rows, b, vals, guess, cap.as_ref())?;
                let finite = x.iter().flatten().all(|v| v.is_finite());
                if ok || (attempt == 1 && finite) {
                    return Ok((x, rho));
                }
            }
            if attempt == 0 {
                self.refactor(rows)?;
            }
        }
        Err(super::singular())
    }

    fn rows_of<'r>(set: &'r ActiveSet, bufs: &'r RowBufs, load: &'r [f64], pins: bool) -> Rows<'r> {
        Rows {
            free: &bufs.free,
            b0: &bufs.b0,
            b1: &bufs.b1,
            coef: &bufs.coef,
            spring: &set.spring,
            spring_u: if pins { &set.spring_u } else { &bufs.zero },
            fk: if pins { set.v_force() } else { (0.0, 0.0) },
            load,
        }
    }
}

/// The last solve's solutions (lambda^0, lambda^1; m + 3 each), right-hand sides b and row
/// keys: the next solve's starting point.
struct Last {
    g: [Guess; 2],
    b: [Vec<f64>; 2],
    keys: Vec<Key>,
}

/// A solution x, its residual b - M x and its equations' sizes (sum |M_rj x_j| + |b_r|).
struct Guess {
    x: Vec<f64>,
    res: Vec<f64>,
    den: Vec<f64>,
}

/// The per-solve vectors of [`Rows`] built from an [`ActiveSet`].
struct RowBufs {
    free: Vec<bool>,
    b0: Vec<f64>,
    b1: Vec<f64>,
    coef: Vec<f64>,
    zero: Vec<f64>,
}

impl RowBufs {
    fn new(set: &ActiveSet, pins: bool) -> RowBufs {
        let (n, nd) = (set.n, set.nd());
        let mut b0 = vec![0.0; nd];
        let mut b1 = vec![0.0; nd];
        if pins {
            for i in 0..n {
                if set.states[i] == NodeState::Stick {
                    b0[i] = set.anchor[i];
                }
            }
            if set.phase == Phase::Drive {
                b1[set.iu()] = 1.0;
            }
        }
        RowBufs {
            free: (0..nd).map(|d| set.is_free(d)).collect(),
            b0,
            b1,
            coef: (0..n).map(|i| set.slip_coef(i)).collect(),
            zero: vec![0.0; n],
        }
    }
}

fn sparse_dot(w: &[(usize, f64)], x: &[f64]) -> f64 {
    w.iter().map(|&(c, v)| v * x[c]).sum()
}

/// Dense LU with partial pivoting of the small capacitance matrix.
struct Lu {
    a: Vec<f64>,
    piv: Vec<usize>,
    k: usize,
}

impl Lu {
    /// None if a pivot falls below 1e-12 of the largest entry (C nearly singular: M0 and M
    /// too far apart for the low-rank path to be accurate) or k = 0.
    fn new(mut a: Vec<f64>, k: usize) -> Option<Lu> {
        if k == 0 {
            return None;
        }
        let big = a.iter().fold(0.0f64, |s, v| s.max(v.abs()));
        let mut piv = vec![0; k];
        for i in 0..k {
            let p = (i..k).max_by(|&x, &y| a[x * k + i].abs().total_cmp(&a[y * k + i].abs()))?;
            if !(a[p * k + i].abs() > 1e-12 * big) {
                return None;
            }
            piv[i] = p;
            if p != i {
                for c in 0..k {
                    a.swap(i * k + c, p * k + c);
                }
            }
            for r in i + 1..k {
                let q = a[r * k + i] / a[i * k + i];
                a[r * k + i] = q;
                for c in i + 1..k {
                    a[r * k + c] -= q * a[i * k + c];
                }
            }
        }
        Some(Lu { a, piv, k })
    }

    /// Sign of det C: the diagonal of U and the row interchanges.
    fn det_sign(&self) -> f64 {
        let k = self.k;
        let neg = (0..k).filter(|&i| self.a[i * k + i] < 0.0).count()
            + (0..k).filter(|&i| self.piv[i] != i).count();
        if neg % 2 == 0 {
            1.0
        } else {
            -1.0
        }
    }

    fn solve(&self, mut b: Vec<f64>) -> Vec<f64> {
        let (a, k) = (&self.a, self.k);
        for i in 0..k {
            b.swap(i, self.piv[i]);
            for r in i + 1..k {
                b[r] -= a[r * k + i] * b[i];
            }
        }
        for i in (0..k).rev() {
            let s: f64 = (i + 1..k).map(|c| a[i * k + c] * b[c]).sum();
            b[i] = (b[i] - s) / a[i * k + i];
        }
        b
    }
}

impl Operator for Solving<'_> {
    fn refresh(&mut self, _: &ActiveSet) -> Result<()> {
        Ok(())
    }
    fn change(&mut self, _: &ActiveSet, _: usize, _: NodeState, _: f64) -> Result<()> {
        Ok(())
    }
    fn bulk(&mut self, _: &ActiveSet) -> Result<()> {
        Ok(())
    }
    fn coefficient(&mut self, _: &ActiveSet, _: usize) -> Result<()> {
        Ok(())
    }
    fn pins_moved(&mut self) {}

    /// The rows are compared with the factor's at every solve (O(n)), so the change
    /// notifications carry nothing this operator needs.
    fn solve(&mut self, set: &ActiveSet) -> Result<Affine> {
        let bufs = RowBufs::new(set, true);
        let rows = Self::rows_of(set, &bufs, &[], true);
        self.op.check_sizes(&rows)?;
        let n = self.op.n;
        let keys: Vec<Key> = (0..2 * n).map(|d| Self::key(&rows, n, d)).collect();
        let b = self.rhs(&rows);
        // The last solutions' residuals under the current rows: the stored ones, moved by the
        // right-hand sides' changes, and recomputed on the rows that changed (their sizes
        // kept from the last check: they only choose between the low-rank and the full step).
        let guess = self.last.take().map(|mut l| {
            for (k, g) in l.g.iter_mut().enumerate() {
                for (r, v) in g.res.iter_mut().enumerate() {
                    *v += b[k][r] - l.b[k][r];
                }
                for d in (0..2 * n).filter(|&d| keys[d] != l.keys[d]) {
                    let r = self.op.pos(d);
                    g.res[r] = self.residual_at(&rows, r, &g.x, &b[k]);
                }
            }
            l
        });
        let vals = [rows.b0, rows.b1];
        let (x, res) = self.solve_full(&rows, &b, &vals, guess.as_ref().map(|l| &l.g[..]))?;
        let mut full: [Vec<f64>; 2] = x.try_into().map_err(|_| super::singular())?;
        let [(r0, d0, k0), (r1, d1, k1)]: [Checked; 2] = res.try_into().map_err(|_| super::singular())?;
        let sol = self.op.finish(&rows, &mut full, Some([&k0, &k1]));
        let [x0, x1] = full;
        let g = [Guess { x: x0, res: r0, den: d0 }, Guess { x: x1, res: r1, den: d1 }];
        self.last = Some(Last { g, b, keys });
        Ok(Affine { b0: sol.b0, b1: sol.b1, f0: sol.f0, f1: sol.f1 })
    }

    /// Column j of the inverse is the response to a unit load on free equation j with every
    /// prescribed value zero.
    fn inverse_block(&mut self, set: &ActiveSet, dofs: &[usize]) -> Result<Vec<f64>> {
        let k = dofs.len();
        let mut out = vec![0.0; k * k];
        let bufs = RowBufs::new(set, false);
        let mut load = vec![0.0; set.nd()];
        for (j, &dj) in dofs.iter().enumerate() {
            load[dj] = 1.0;
            let rows = Self::rows_of(set, &bufs, &load, false);
            let [b0, _] = self.rhs(&rows);
            let (mut x, _) = self.solve_full(&rows, &[b0], &[rows.b0], None)?;
            let mut x = [x.remove(0), vec![0.0; self.op.m + 3]];
            let s = self.op.finish(&rows, &mut x, None);
            load[dj] = 0.0;
            for (i, &di) in dofs.iter().enumerate() {
                out[i * k + j] = s.b0[di];
            }
        }
        Ok(out)
    }

    fn counts(&self) -> (usize, usize) {
        (self.row_updates, self.factorisations)
    }

    /// det M = det M0 det C (matrix determinant lemma): the factor's sign and the
    /// capacitance's, no extra solve; a capacitance too ill-conditioned to trust refactors.
    fn det_sign(&mut self, set: &ActiveSet) -> Result<Option<f64>> {
        let bufs = RowBufs::new(set, true);
        let rows = Self::rows_of(set, &bufs, &[], true);
        self.update(&rows)?;
        let cap = match self.capacitance() {
            Some(c) => c.det_sign(),
            None if self.z.is_empty() => 1.0,
            None => {
                self.refactor(&rows)?;
                1.0
            }
        };
        Ok(Some(self.base.as_ref().expect("factored").det_sign() * cap))
    }
}

#[cfg(test)]
mod tests;
