//! The bordered dense inverse of a square system restricted to a changing set of free DOFs.
//!
//! The set grows and shrinks one DOF at a time; each change updates the explicit inverse by
//! bordering in O(m^2) (Schur complement of the new row and column, or its reverse) instead of
//! a new O(m^3) factorisation. A small pivot, or a caller who changes many rows at once, falls
//! back to one full LU. A spare inverse keeps the set from before the last bulk change: an
//! instability's region and the re-stuck interface alternate, and each is a few bordering
//! updates away from its previous self.
//!
//! This type knows nothing of what the DOFs mean: it reads the matrix through [`Rows`].

use super::tolerances;
use crate::error::{Error, Result};
use faer::linalg::solvers::DenseSolveCore;

/// The matrix as the inverse sees it.
pub(crate) trait Rows {
    /// Whether DOF d is in the free set now.
    fn is_free(&self, d: usize) -> bool;
    /// Entry of the free system's row a on column b (both free).
    fn entry(&self, a: usize, b: usize) -> f64;
    /// What row d depends on besides the fixed matrix (equal keys: equal rows); an inverse
    /// formed with another key for a DOF is stale there.
    fn key(&self, d: usize) -> (f64, f64);
    /// Scale of row d's pivot: a Schur complement below [`tolerances::PIVOT`] of it is
    /// treated as zero.
    fn pivot_scale(&self, d: usize) -> f64;
}

/// Dense inverse of the free rows and columns.
struct Block {
    /// DOF of each free position, and position of each DOF (usize::MAX if not free).
    dofs: Vec<usize>,
    pos: Vec<usize>,
    /// Each free position's row key when the inverse was formed.
    keys: Vec<(f64, f64)>,
    /// Inverse, stride nd, top-left m x m used.
    inv: Vec<f64>,
}

impl Block {
    fn empty(nd: usize) -> Block {
        Block { dofs: vec![], pos: vec![usize::MAX; nd], keys: vec![], inv: vec![0.0; nd * nd] }
    }
}

/// The inverse of the free system, kept by bordering, with its spare and its counters.
pub(crate) struct Bordered {
    nd: usize,
    free: Block,
    spare: Option<Block>,
    /// Bordering updates and full refactorisations so far.
    pub updates: usize,
    pub refreshes: usize,
}

impl Bordered {
    /// An empty free set over nd DOFs.
    pub fn new(nd: usize) -> Bordered {
        Bordered { nd, free: Block::empty(nd), spare: None, updates: 0, refreshes: 0 }
    }

    /// The free DOFs in the inverse's order.
    pub fn dofs(&self) -> &[usize] {
        &self.free.dofs
    }

    /// Position of DOF d in [`Self::dofs`], if free.
    pub fn pos(&self, d: usize) -> Option<usize> {
        let p = self.free.pos[d];
        (p != usize::MAX).then_some(p)
    }

    /// Row k of the inverse (positions as in [`Self::dofs`]).
    pub fn row(&self, k: usize) -> &[f64] {
        let (nd, m) = (self.nd, self.free.dofs.len());
        &self.free.inv[k * nd..k * nd + m]
    }

    /// Full LU of the free system: the free DOFs in ascending order.
    pub fn refresh(&mut self, rows: &dyn Rows) -> Result<()> {
        let nd = self.nd;
        let dofs: Vec<usize> = (0..nd).filter(|&d| rows.is_free(d)).collect();
        let m = dofs.len();
        // faer's blocked LU: 5x nalgebra's at m = 400 (whole-interface relaxations).
        let a = faer::Mat::<f64>::from_fn(m, m, |i, j| rows.entry(dofs[i], dofs[j]));
        let lu = a.partial_piv_lu();
        let u = lu.U();
        let (mut umin, mut umax) = (f64::INFINITY, 0.0f64);
        for i in 0..m {
            umin = umin.min(u[(i, i)].abs());
            umax = umax.max(u[(i, i)].abs());
        }
        let inv = lu.inverse();
        if m > 0 && !(umin > tolerances::SINGULAR * umax)
            || (0..m).any(|i| (0..m).any(|j| !inv[(i, j)].is_finite()))
        {
            return Err(Error::Singular {
                detail: "the interface leaves the block free to move (every node open, or N <= 0)".into(),
                node: None,
                component: None,
            });
        }
        let keys: Vec<(f64, f64)> = dofs.iter().map(|&d| rows.key(d)).collect();
        let f = &mut self.free;
        f.pos.iter_mut().for_each(|p| *p = usize::MAX);
        for (k, &d) in dofs.iter().enumerate() {
            f.pos[d] = k;
        }
        f.dofs = dofs;
        f.keys = keys;
        for i in 0..m {
            for j in 0..m {
                f.inv[i * nd + j] = inv[(i, j)];
            }
        }
        self.refreshes += 1;
        Ok(())
    }

    /// Removes DOF d from the free set (O(m^2)); d must be free.
    pub fn remove(&mut self, d: usize) {
        let nd = self.nd;
        let f = &mut self.free;
        let k = f.pos[d];
        let m = f.dofs.len();
        let last = m - 1;
        if k != last {
            // Symmetric permutation: swap rows and columns k and last.
            for j in 0..m {
                f.inv.swap(k * nd + j, last * nd + j);
            }
            for i in 0..m {
                f.inv.swap(i * nd + k, i * nd + last);
            }
            let dl = f.dofs[last];
            f.dofs.swap(k, last);
            f.keys.swap(k, last);
            f.pos[dl] = k;
        }
        let s = f.inv[last * nd + last];
        for i in 0..last {
            let q = f.inv[i * nd + last] / s;
            if q != 0.0 {
                for j in 0..last {
                    f.inv[i * nd + j] -= q * f.inv[last * nd + j];
                }
            }
        }
        f.dofs.pop();
        f.keys.pop();
        f.pos[d] = usize::MAX;
        self.updates += 1;
    }

    /// Adds DOF d to the free set with its current row (O(m^2)); a pivot below
    /// [`tolerances::PIVOT`] of [`Rows::pivot_scale`] refactorises instead.
    pub fn add(&mut self, d: usize, rows: &dyn Rows) -> Result<()> {
        let nd = self.nd;
        let m = self.free.dofs.len();
        let c: Vec<f64> = self.free.dofs.iter().map(|&a| rows.entry(a, d)).collect();
        let r: Vec<f64> = self.free.dofs.iter().map(|&b| rows.entry(d, b)).collect();
        let delta = rows.entry(d, d);
        let cd = rows.key(d);
        let f = &mut self.free;
        let y: Vec<f64> = (0..m).map(|i| (0..m).map(|j| f.inv[i * nd + j] * c[j]).sum()).collect();
        let mut z = vec![0.0; m];
        for i in 0..m {
            let ri = r[i];
            if ri != 0.0 {
                for j in 0..m {
                    z[j] += ri * f.inv[i * nd + j];
                }
            }
        }
        let sigma = delta - (0..m).map(|i| r[i] * y[i]).sum::<f64>();
        let scale = rows.pivot_scale(d);
        f.dofs.push(d);
        f.keys.push(cd);
        f.pos[d] = m;
        if !(sigma.abs() > tolerances::PIVOT * scale) {
            return self.refresh(rows);
        }
        for i in 0..m {
            let yi = y[i] / sigma;
            for j in 0..m {
                f.inv[i * nd + j] += yi * z[j];
            }
            f.inv[i * nd + m] = -yi;
        }
        for j in 0..m {
            f.inv[m * nd + j] = -z[j] / sigma;
        }
        f.inv[m * nd + m] = 1.0 / sigma;
        self.updates += 1;
        Ok(())
    }

    /// Brings the inverse to the current free set and keys after bulk changes: from whichever
    /// of the current and the spare inverse is fewer bordering updates away, or by one full
    /// LU when both are far.
    pub fn rebase(&mut self, rows: &dyn Rows) -> Result<()> {
        let target: Vec<usize> = (0..self.nd).filter(|&d| rows.is_free(d)).collect();
        let stale = |d: usize, k: &(f64, f64)| !rows.is_free(d) || *k != rows.key(d);
        let cost = |f: &Block| {
            let old = f.dofs.iter().zip(&f.keys).filter(|&(&d, k)| stale(d, k));
            let fresh = target.iter().filter(|&&d| f.pos[d] == usize::MAX);
            old.count() + fresh.count()
        };
        let here = cost(&self.free);
        let there = self.spare.as_ref().map_or(usize::MAX, cost);
        // Bordering is O(m^2) a change against O(m^3) for the LU; past ~m/8 changes the
        // drift and the cost favour the LU.
        let limit = (target.len() / 8).max(tolerances::BATCH);
        let nd = self.nd;
        let spare = self.spare.get_or_insert_with(|| Block::empty(nd));
        if there < here.min(limit) || here > limit {
            std::mem::swap(&mut self.free, spare);
        }
        if here.min(there) > limit {
            return self.refresh(rows);
        }
        let old: Vec<usize> = (self.free.dofs.iter().zip(&self.free.keys))
            .filter(|&(&d, k)| stale(d, k))
            .map(|(&d, _)| d)
            .collect();
        for d in old {
            self.remove(d);
        }
        for d in target {
            if self.free.pos[d] == usize::MAX {
                self.add(d, rows)?;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fixed matrix with a free mask and per-row keys that scale a row.
    struct Mat {
        nd: usize,
        a: Vec<f64>,
        free: Vec<bool>,
        key: Vec<f64>,
    }

    impl Rows for Mat {
        fn is_free(&self, d: usize) -> bool {
            self.free[d]
        }
        fn entry(&self, a: usize, b: usize) -> f64 {
            self.a[a * self.nd + b] * self.key[a]
        }
        fn key(&self, d: usize) -> (f64, f64) {
            (self.key[d], 0.0)
        }
        fn pivot_scale(&self, d: usize) -> f64 {
            self.a[d * self.nd + d].abs()
        }
    }

    /// Deterministic uniform numbers in [-1, 1) (xorshift).
    fn rng(seed: u64) -> impl FnMut() -> f64 {
        let mut x = seed;
        move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 52) as f64 - 1.0
        }
    }

    /// Unsymmetric, diagonally dominant (well conditioned on every principal submatrix).
    fn random(nd: usize, seed: u64) -> Mat {
        let mut r = rng(seed);
        let mut a: Vec<f64> = (0..nd * nd).map(|_| r()).collect();
        for i in 0..nd {
            a[i * nd + i] = nd as f64 + 1.0 + r();
        }
        Mat { nd, a, free: vec![false; nd], key: vec![1.0; nd] }
    }

    /// Largest |inverse - direct inverse| relative to the largest entry of the direct one,
    /// over the free set in the inverse's order.
    fn error(b: &Bordered, m: &Mat) -> f64 {
        let dofs = b.dofs().to_vec();
        let k = dofs.len();
        let mut want: Vec<usize> = (0..m.nd).filter(|&d| m.free[d]).collect();
        let mut got = dofs.clone();
        want.sort();
        got.sort();
        assert_eq!(got, want, "free set");
        let a = faer::Mat::<f64>::from_fn(k, k, |i, j| m.entry(dofs[i], dofs[j]));
        let inv = a.partial_piv_lu().inverse();
        let big = (0..k)
            .flat_map(|i| (0..k).map(move |j| (i, j)))
            .fold(0.0f64, |s, (i, j)| s.max(inv[(i, j)].abs()));
        let mut e = 0.0f64;
        for i in 0..k {
            for j in 0..k {
                e = e.max((b.row(i)[j] - inv[(i, j)]).abs());
            }
        }
        e / big
    }

    #[test]
    fn bordering_matches_a_direct_inverse_after_adds_and_removes() {
        let nd = 24;
        let mut m = random(nd, 7);
        let mut b = Bordered::new(nd);
        for d in (0..nd).step_by(2) {
            m.free[d] = true;
        }
        b.refresh(&m).unwrap();
        assert!(error(&b, &m) < 1e-14);
        let mut r = rng(11);
        for step in 0..200 {
            let d = ((r() + 1.0) * 0.5 * nd as f64) as usize % nd;
            if m.free[d] && b.dofs().len() > 1 {
                m.free[d] = false;
                b.remove(d);
            } else if !m.free[d] {
                m.free[d] = true;
                b.add(d, &m).unwrap();
            }
            // Each update costs a few ulps of the largest entry; 200 of them stay far below.
            assert!(error(&b, &m) < 1e-12, "step {step}: {}", error(&b, &m));
        }
        assert_eq!(b.refreshes, 1, "no pivot fell back on a dominant matrix");
        assert!(b.updates > 150);
    }

    #[test]
    fn a_small_pivot_refactorises_and_a_singular_system_is_refused() {
        // [[1, 1], [1, 1 + e]]: bordering DOF 1 onto DOF 0 gives the pivot e.
        let e = 1e-12;
        let mut m =
            Mat { nd: 2, a: vec![1.0, 1.0, 1.0, 1.0 + e], free: vec![true, false], key: vec![1.0; 2] };
        let mut b = Bordered::new(2);
        b.refresh(&m).unwrap();
        m.free[1] = true;
        b.add(1, &m).unwrap();
        assert_eq!((b.updates, b.refreshes), (0, 2), "the add fell back on a full LU");
        assert_eq!(b.dofs(), &[0, 1]);
        // Exact inverse 1/e [[1 + e, -1], [-1, 1]]; the LU of a matrix this ill conditioned
        // is exact to about cond * eps = 4e12 * 1.1e-16 ~ 4e-4 relative.
        let want = [(1.0 + e) / e, -1.0 / e, -1.0 / e, 1.0 / e];
        let got = [b.row(0)[0], b.row(0)[1], b.row(1)[0], b.row(1)[1]];
        for (g, w) in got.iter().zip(want) {
            assert!((g - w).abs() < 1e-3 * w.abs(), "{g} vs {w}");
        }
        // Exactly singular: refused.
        let s = Mat { nd: 2, a: vec![1.0, 1.0, 1.0, 1.0], free: vec![true, true], key: vec![1.0; 2] };
        assert!(matches!(Bordered::new(2).refresh(&s), Err(Error::Singular { .. })));
    }

    #[test]
    fn rebase_reuses_the_spare_after_a_bulk_change_and_back() {
        let nd = 80;
        let mut m = random(nd, 3);
        m.free.iter_mut().for_each(|f| *f = true);
        let mut b = Bordered::new(nd);
        b.refresh(&m).unwrap();
        // A region of 40 DOFs leaves (more than BATCH, more than m/8): a full LU.
        (20..60).for_each(|d| m.free[d] = false);
        b.rebase(&m).unwrap();
        assert_eq!(b.refreshes, 2);
        assert!(error(&b, &m) < 1e-13);
        // It comes back with one row rescaled: the spare (the full set) is one update away.
        (20..60).for_each(|d| m.free[d] = true);
        m.key[5] = 0.5;
        let before = b.updates;
        b.rebase(&m).unwrap();
        assert_eq!(b.refreshes, 2, "from the spare, not a new LU");
        assert_eq!(b.updates - before, 2, "remove and re-add the rescaled row");
        assert!(error(&b, &m) < 1e-13);
    }
}
