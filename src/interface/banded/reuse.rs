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

use super::{BandedOperator, Factored, Rows};
use crate::error::Result;
use crate::interface::events::operator::{ActiveSet, Affine, Operator};
use crate::interface::events::{NodeState, Phase};
use crate::linalg::banded::Banded;

/// Rows replaced since the factorisation past which the band is refactored: a solve costs
/// O(|R| m) in Z C^{-1}, a factorisation O(m kl (kl + ku)) plus |R| band solves to rebuild Z;
/// 24 was the fastest of 8, 16, 24, 32, 64 on the coulomb run at 801 nodes (docs/speed.md).
pub const RANK_CAP: usize = 24;

/// Residual of every equation, relative to the size of its terms (the largest |b| and
/// scale |x|), below which a solution is accepted: two orders above the round-off of
/// evaluating it (~18 terms a row), far below the event solver's state tolerances.
pub const REFINE: f64 = 1e-13;

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
    /// The last solution (lambda^0, lambda^1), m + 3 each.
    x: Option<[Vec<f64>; 2]>,
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
            x: None,
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
        let a: Vec<f64> =
            (0..k).flat_map(|i| (0..k).map(move |j| (i, j))).map(|(i, j)| self.wz[i][j] + f64::from(i == j)).collect();
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

    /// rho = b - M x over the m + 3 equations, and the size of their terms (max |b|, scale |x|).
    fn residual(&self, rows: &Rows, x: &[f64], b: &[f64]) -> (Vec<f64>, f64) {
        let op = self.op;
        let (n, m) = (op.n, op.m);
        let kx: Vec<f64> = (0..m + 3)
            .map(|r| {
                let (c, v) = op.row(r);
                c.iter().zip(v).map(|(&c, &v)| v * x[c]).sum()
            })
            .collect();
        let mut rho = vec![0.0; m + 3];
        for r in 0..m + 3 {
            let d = if r < m { self.bnd[r] } else { 2 * n + r - m };
            let lhs = if d == usize::MAX {
                kx[r]
            } else if !rows.free[d] {
                op.scale * x[r]
            } else if d < n {
                let mut v = kx[r];
                if rows.coef[d] != 0.0 {
                    v += rows.coef[d] * kx[op.pv[d]];
                }
                v + rows.spring[d] * x[r]
            } else {
                kx[r]
            };
            rho[r] = b[r] - lhs;
        }
        let xs = x.iter().fold(0.0f64, |s, v| s.max(v.abs())) * op.scale;
        let big = b.iter().fold(xs, |s, v| s.max(v.abs()));
        (rho, big)
    }

    /// The solution of the current rows for right-hand side b, from the guess `x` if given:
    /// the low-rank step when the guess's residual lies on R, then refinement by Woodbury.
    fn solve_one(&self, rows: &Rows, b: &[f64], guess: Option<&[f64]>, cap: Option<&Lu>) -> Result<(Vec<f64>, bool)> {
        let m = self.op.m;
        if b.iter().all(|&v| v == 0.0) {
            // No load: the solution is zero (a relative residual would have no scale).
            return Ok((vec![0.0; m + 3], true));
        }
        let mut x = match guess {
            Some(g) => {
                let mut x = g.to_vec();
                let (rho, big) = self.residual(rows, &x, b);
                let on_r = |r: usize| r < m && self.bnd[r] != usize::MAX && self.in_r[self.bnd[r]] != usize::MAX;
                let rest = (0..m + 3).filter(|&r| !on_r(r)).fold(0.0f64, |s, r| s.max(rho[r].abs()));
                if rest <= REFINE * big {
                    if let Some(lu) = cap {
                        let rr: Vec<f64> = self.r_dofs.iter().map(|&d| rho[self.op.pos(d)]).collect();
                        self.sub_zy(&mut x, &lu.solve(rr), 1.0);
                    }
                } else {
                    let dx = self.woodbury(&rho, cap)?;
                    x.iter_mut().zip(&dx).for_each(|(x, d)| *x += d);
                }
                x
            }
            None => self.woodbury(b, cap)?,
        };
        for _ in 0..3 {
            let (rho, big) = self.residual(rows, &x, b);
            let worst = rho.iter().fold(0.0f64, |s, v| s.max(v.abs()));
            if !worst.is_finite() {
                return Ok((x, false));
            }
            if worst <= REFINE * big {
                return Ok((x, true));
            }
            let dx = self.woodbury(&rho, cap)?;
            x.iter_mut().zip(&dx).for_each(|(x, d)| *x += d);
        }
        let (rho, big) = self.residual(rows, &x, b);
        let worst = rho.iter().fold(0.0f64, |s, v| s.max(v.abs()));
        if std::env::var("SPEED_DEBUG").is_ok() {
            let r = (0..rho.len()).max_by(|&a, &c| rho[a].abs().total_cmp(&rho[c].abs())).unwrap();
            let d = if r < self.op.m { self.bnd[r] } else { 2 * self.op.n + r - self.op.m };
            let xm = x.iter().fold(0.0f64, |s, v| s.max(v.abs()));
            let bm = b.iter().fold(0.0f64, |s, v| s.max(v.abs()));
            eprintln!("refine fail: {:.2e} rank {} row {r} d {d} rho {:.3e} big {big:.3e} xmax {xm:.3e} bmax {bm:.3e} scale {:.3e}", worst / big, self.z.len(), rho[r], self.op.scale);
        }
        Ok((x, worst <= REFINE * big))
    }

    /// Full solutions of the current rows for right-hand sides `b` (guesses: the last solution
    /// if `reuse`); refactors once if R's solution does not converge.
    fn solve_full(&mut self, rows: &Rows, b: &[Vec<f64>], reuse: bool) -> Result<Vec<Vec<f64>>> {
        self.update(rows)?;
        for attempt in 0..2 {
            let cap = self.capacitance();
            let mut out = Vec::with_capacity(b.len());
            let mut ok = cap.is_some() || self.z.is_empty();
            for (k, bk) in b.iter().enumerate() {
                if !ok && attempt == 0 {
                    break;
                }
                let guess = if reuse { self.x.as_ref().map(|x| x[k].as_slice()) } else { None };
                let (x, good) = self.solve_one(rows, bk, guess, cap.as_ref())?;
                ok &= good;
                out.push(x);
            }
            if ok {
                return Ok(out);
            }
            if attempt == 0 {
                self.refactor(rows)?;
            } else {
                // A fresh factor that refinement cannot bring to REFINE: accept it as the
                // from-scratch banded path does (its residual is checked by the caller's
                // state tolerances), unless it is not finite.
                if out.len() == b.len() && out.iter().flatten().all(|v| v.is_finite()) {
                    return Ok(out);
                }
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
        let b = self.rhs(&rows);
        let x = self.solve_full(&rows, &b, true)?;
        let mut full: [Vec<f64>; 2] = x.try_into().map_err(|_| super::singular())?;
        let s = self.op.finish(&rows, &mut full);
        self.x = Some(full);
        Ok(Affine { b0: s.b0, b1: s.b1, f0: s.f0, f1: s.f1 })
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
            let b = self.rhs(&rows);
            let mut x: [Vec<f64>; 2] = [self.solve_full(&rows, &b[..1], false)?.remove(0), vec![0.0; self.op.m + 3]];
            let s = self.op.finish(&rows, &mut x);
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
}
