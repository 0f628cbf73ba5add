//! Two-domain substructuring: the reduced unknowns split into two halves and the separator
//! between them (`fem::ordering::bisection`). Each half with the separator ordered last is
//! a principal submatrix of K, hence positive definite. faer analyses each half and
//! [`crate::linalg::multifrontal`] factorises the two at once, one per core: threads inside a front
//! only help large dense fronts, which a thin strip lacks. The trailing block L_ss of each
//! factor gives that half's condensation onto the separator, L_ss L_ss^T = A_ss - A_sk
//! A_kk^-1 A_ks; their sum less A_ss (counted twice) is the separator's Schur complement, a
//! small dense matrix. The work done does not depend on the thread count, so neither do the
//! results.

use crate::error::{Error, Result};
use crate::linalg::multifrontal::{self, supernodal, AssemblyTree, DenseWork};
use crate::linalg::pattern::Bisection;
use crate::linalg::pattern::Pattern;
use crate::linalg::NonPositivePivot;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt;
use faer::linalg::cholesky::llt::factor::{LltError, LltRegularization};
use faer::linalg::matmul::triangular::{self, BlockStructure};
use faer::sparse::linalg::cholesky::supernodal::{SupernodalLltRef, SymbolicSupernodalCholesky};
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, SymbolicCholesky, SymmetricOrdering,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Accum, Conj, Mat, Par, Side};
use std::sync::Mutex;

/// Symbolic analysis of both halves; reusable for any values on the same pattern.
pub struct TwoDomain {
    parts: [Part; 2],
    separator: Vec<usize>,
    /// (row, column, position in the global values) of the separator block's lower triangle.
    sep_entries: Vec<(usize, usize, usize)>,
    /// Factor memory of each half from a dropped factor, for the next factorisation: a sweep
    /// then refactorises without first-touch page faults, which cost 0.2-2 s per GB on this VM.
    recycled: Mutex<[Vec<f64>; 2]>,
}

/// One half with the separator, in 32-bit indices (half the index traffic of usize in faer's
/// analysis and factorisation; 4e9 entries of L per half is far beyond this machine's memory).
struct Part {
    /// Reduced unknown of each local one: the half in elimination order, then the separator.
    unknowns: Vec<usize>,
    col_ptr: Vec<u32>,
    row_idx: Vec<u32>,
    /// Position in the global values of each local entry.
    gather: Vec<u32>,
    symbolic: SymbolicCholesky<u32>,
    tree: AssemblyTree,
}

/// Numeric factors of both halves and of the separator's Schur complement.
pub struct TwoDomainFactor {
    l: [Vec<f64>; 2],
    /// Trailing separator x separator block of each half's factor (lower triangular).
    l_ss: [Mat<f64>; 2],
    /// Cholesky factor of the Schur complement (lower triangle).
    schur: Mat<f64>,
    /// Core-seconds spent in dense kernels (both halves and the Schur complement).
    pub dense_seconds: f64,
}

impl TwoDomain {
    /// Analyses both halves. Errors when the split is not a partition of the unknowns or a
    /// matrix entry couples the two halves directly.
    pub fn analyse(pattern: &Pattern, split: &Bisection) -> Result<Self> {
        let n = pattern.n;
        const SEP: u8 = 2;
        let mut label = vec![u8::MAX; n];
        let groups = [&split.parts[0], &split.parts[1], &split.separator];
        for (g, list) in groups.iter().enumerate() {
            for &k in list.iter() {
                if k >= n || std::mem::replace(&mut label[k], g as u8) != u8::MAX {
                    return Err(Error::input(
                        "two-domain split",
                        format!("unknown {k} is out of range or listed twice"),
                    ));
                }
            }
        }
        if let Some(k) = label.iter().position(|&l| l == u8::MAX) {
            return Err(Error::input("two-domain split", format!("unknown {k} is in no part")));
        }
        let (a, b) = rayon::join(
            || Part::analyse(pattern, &split.parts[0], &split.separator),
            || Part::analyse(pattern, &split.parts[1], &split.separator),
        );
        let mut local = vec![usize::MAX; n];
        split.separator.iter().enumerate().for_each(|(s, &k)| local[k] = s);
        let mut sep_entries = Vec::new();
        for &j in &split.separator {
            for p in pattern.col(j) {
                let i = pattern.row_idx[p] as usize;
                if label[i] == SEP {
                    let (r, c) = (local[i], local[j]);
                    sep_entries.push((r.max(c), r.min(c), p));
                }
            }
        }
        Ok(Self {
            parts: [a?, b?],
            separator: split.separator.clone(),
            sep_entries,
            recycled: Default::default(),
        })
    }

    pub fn factor_nnz(&self) -> usize {
        self.parts.iter().map(|p| p.symbolic.len_val()).sum::<usize>()
            + self.separator.len() * (self.separator.len() + 1) / 2
    }

    /// Flops of both halves' factorisations plus the Schur complement's: two triangular
    /// products and one dense Cholesky, m^3 / 3 each.
    pub fn factor_flops(&self) -> f64 {
        let m = self.separator.len() as f64;
        self.parts.iter().map(|p| supernodal_flops(supernodal(&p.symbolic))).sum::<f64>() + m * m * m
    }

    /// Numeric factorisation; a non-positive pivot is returned as its reduced unknown.
    pub fn factorize(&self, values: &[f64]) -> std::result::Result<TwoDomainFactor, NonPositivePivot> {
        let m = self.separator.len();
        let [wa, wb] = std::mem::take(&mut *self.recycled());
        let (a, b) =
            rayon::join(|| self.parts[0].factorize(values, m, wa), || self.parts[1].factorize(values, m, wb));
        let ((la, sa, da), (lb, sb, db)) = (a?, b?);
        let clock = std::time::Instant::now();
        // S = L_ss,a L_ss,a^T + L_ss,b L_ss,b^T - A_ss, lower triangle only (triangular
        // products: m^3/3 flops each instead of 2 m^3).
        let mut schur = Mat::<f64>::zeros(m, m);
        for &(r, c, p) in &self.sep_entries {
            schur[(r, c)] -= values[p];
        }
        for l in [&sa, &sb] {
            triangular::matmul(
                schur.as_mut(),
                BlockStructure::TriangularLower,
                Accum::Add,
                l.as_ref(),
                BlockStructure::TriangularLower,
                l.transpose(),
                BlockStructure::TriangularUpper,
                1.0,
                Par::Seq,
            );
        }
        let mut mem =
            MemBuffer::new(llt::factor::cholesky_in_place_scratch::<f64>(m, Par::Seq, Default::default()));
        match llt::factor::cholesky_in_place(
            schur.as_mut(),
            LltRegularization::default(),
            Par::Seq,
            MemStack::new(&mut mem),
            Default::default(),
        ) {
            Ok(_) => Ok(TwoDomainFactor {
                l: [la, lb],
                l_ss: [sa, sb],
                schur,
                dense_seconds: da + db + clock.elapsed().as_secs_f64(),
            }),
            Err(LltError::NonPositivePivot { index }) => {
                Err(NonPositivePivot { unknown: self.separator[index.min(m - 1)] })
            }
        }
    }

    /// The numeric factors of the two halves alone (faer's layout, one per core, into `l`,
    /// resized when needed), by our multifrontal code or by faer's own left-looking one: the
    /// two are compared in `tests/it/parallel.rs` and `benches/kernels.rs`.
    /// Returns the dense kernels' work of both halves (ours; none for faer's).
    pub fn factor_halves(
        &self,
        values: &[f64],
        left_looking: bool,
        l: &mut [Vec<f64>; 2],
    ) -> std::result::Result<DenseWork, NonPositivePivot> {
        let [la, lb] = l;
        let half = |part: &Part, l: &mut Vec<f64>| {
            l.resize(part.symbolic.len_val(), 0.0);
            if left_looking {
                part.numeric_left_looking(values, l).map(|_| DenseWork::default())
            } else {
                part.numeric(values, l)
            }
        };
        let (a, b) = rayon::join(|| half(&self.parts[0], la), || half(&self.parts[1], lb));
        Ok(a?.merge(&b?))
    }

    /// Forward then backward solve of each half alone (one per core) with the factors of
    /// [`TwoDomain::factor_halves`], `k` columns of each half's length in `y`, by our
    /// substitution or by faer's supernodal one: compared in `tests/it/parallel.rs` and
    /// `benches/kernels.rs`.
    pub fn solve_halves(&self, l: &[Vec<f64>; 2], y: &mut [Vec<f64>; 2], k: usize, faer: bool) {
        let half = |h: usize, y: &mut Vec<f64>| {
            let part = &self.parts[h];
            y.resize(part.unknowns.len() * k, 1.0);
            for forward in [true, false] {
                if faer {
                    part.solve_faer(&l[h], y, k, forward);
                } else {
                    part.solve(&l[h], y, k, forward);
                }
            }
        };
        let [ya, yb] = y;
        rayon::join(|| half(0, ya), || half(1, yb));
    }

    /// Keeps the factor's memory for the next [`TwoDomain::factorize`].
    pub fn recycle(&self, f: &mut TwoDomainFactor) {
        *self.recycled() = std::mem::take(&mut f.l);
    }

    fn recycled(&self) -> std::sync::MutexGuard<'_, [Vec<f64>; 2]> {
        // A panic elsewhere cannot leave the buffers inconsistent: any contents will do.
        self.recycled.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Solves in place for `k` right-hand sides stored column-major in `b` (n x k).
    pub fn solve_in_place(&self, f: &TwoDomainFactor, b: &mut [f64], k: usize) {
        let n = b.len() / k.max(1);
        let m = self.separator.len();
        let forward = |h: usize| {
            let part = &self.parts[h];
            let nl = part.unknowns.len();
            let mut y = vec![0.0; nl * k];
            for c in 0..k {
                for (l, &g) in part.unknowns.iter().enumerate() {
                    y[c * nl + l] = b[c * n + g];
                }
            }
            part.solve(&f.l[h], &mut y, k, true);
            // c_h = L_ss y_s = b_s - A_sh A_hh^-1 b_h, this half's condensed right-hand side.
            let ys = Mat::<f64>::from_fn(m, k, |i, c| y[c * nl + nl - m + i]);
            let mut ch = Mat::<f64>::zeros(m, k);
            triangular::matmul(
                ch.as_mut(),
                BlockStructure::Rectangular,
                Accum::Replace,
                f.l_ss[h].as_ref(),
                BlockStructure::TriangularLower,
                ys.as_ref(),
                BlockStructure::Rectangular,
                1.0,
                Par::Seq,
            );
            (y, ch)
        };
        let ((mut ya, ca), (mut yb, cb)) = rayon::join(|| forward(0), || forward(1));
        let mut xs = Mat::<f64>::from_fn(m, k, |i, c| ca[(i, c)] + cb[(i, c)] - b[c * n + self.separator[i]]);
        let mut mem = MemBuffer::new(llt::solve::solve_in_place_scratch::<f64>(m, k, Par::Seq));
        llt::solve::solve_in_place_with_conj(
            f.schur.as_ref(),
            Conj::No,
            xs.as_mut(),
            Par::Seq,
            MemStack::new(&mut mem),
        );
        // With the separator part of y set to L_ss^T x_s, the backward solve returns the
        // half's unknowns for the separator fixed at x_s.
        let backward = |h: usize, y: &mut Vec<f64>| {
            let part = &self.parts[h];
            let nl = part.unknowns.len();
            let mut t = Mat::<f64>::zeros(m, k);
            faer::linalg::matmul::matmul(
                t.as_mut(),
                Accum::Replace,
                f.l_ss[h].transpose(),
                xs.as_ref(),
                1.0,
                Par::Seq,
            );
            for c in 0..k {
                for i in 0..m {
                    y[c * nl + nl - m + i] = t[(i, c)];
                }
            }
            part.solve(&f.l[h], y, k, false);
        };
        rayon::join(|| backward(0, &mut ya), || backward(1, &mut yb));
        for (h, y) in [ya, yb].iter().enumerate() {
            let part = &self.parts[h];
            let nl = part.unknowns.len();
            for c in 0..k {
                for (l, &g) in part.unknowns[..nl - m].iter().enumerate() {
                    b[c * n + g] = y[c * nl + l];
                }
            }
        }
        for c in 0..k {
            for (i, &g) in self.separator.iter().enumerate() {
                b[c * n + g] = xs[(i, c)];
            }
        }
    }
}

/// The transpose of a square CSC pattern.
fn transpose(ptr: &[u32], idx: &[u32]) -> (Vec<u32>, Vec<u32>) {
    let n = ptr.len() - 1;
    let mut t_ptr = vec![0u32; n + 1];
    idx.iter().for_each(|&r| t_ptr[r as usize + 1] += 1);
    for c in 0..n {
        t_ptr[c + 1] += t_ptr[c];
    }
    let (mut t_idx, mut next) = (vec![0u32; idx.len()], t_ptr.clone());
    for c in 0..n {
        for &r in &idx[ptr[c] as usize..ptr[c + 1] as usize] {
            t_idx[next[r as usize] as usize] = c as u32;
            next[r as usize] += 1;
        }
    }
    (t_ptr, t_idx)
}

/// Sum over the columns of L of (column count)^2.
pub fn supernodal_flops<I: faer::Index>(s: &SymbolicSupernodalCholesky<I>) -> f64 {
    let (begin, end, rows) = (s.supernode_begin(), s.supernode_end(), s.col_ptr_for_row_idx());
    (0..s.n_supernodes())
        .map(|k| multifrontal::supernode_flops(end[k].zx() - begin[k].zx(), rows[k + 1].zx() - rows[k].zx()))
        .sum()
}

impl Part {
    fn analyse(pattern: &Pattern, half: &[usize], separator: &[usize]) -> Result<Self> {
        let unknowns: Vec<usize> = half.iter().chain(separator).copied().collect();
        let nl = unknowns.len();
        // The pattern's entries fit 32-bit indices (checked where it is built); the factor's
        // may not.
        let too_big =
            || Error::input("two-domain split", format!("a half with {nl} unknowns exceeds 32-bit indices"));
        let mut local = vec![u32::MAX; pattern.n];
        unknowns.iter().enumerate().for_each(|(l, &g)| local[g] = l as u32);
        // Global lower-triangle entries inside this part, moved to the local lower triangle
        // (column = the smaller local index): count, then fill.
        // An entry outside the part in a column of the half couples the halves directly (the
        // other half's columns are checked by its own part).
        let mut col_ptr = vec![0u32; nl + 1];
        for (jl, &j) in unknowns.iter().enumerate() {
            for &i in &pattern.row_idx[pattern.col(j)] {
                let il = local[i as usize];
                if il != u32::MAX {
                    col_ptr[il.min(jl as u32) as usize + 1] += 1;
                } else if jl < half.len() {
                    return Err(Error::input(
                        "two-domain split",
                        format!("unknowns {j} and {i} couple the two halves directly"),
                    ));
                }
            }
        }
        for c in 0..nl {
            col_ptr[c + 1] += col_ptr[c];
        }
        let nnz = col_ptr[nl] as usize;
        let (mut row_idx, mut gather, mut fill) = (vec![0u32; nnz], vec![0u32; nnz], col_ptr.clone());
        for (jl, &j) in unknowns.iter().enumerate() {
            let jl = jl as u32;
            for p in pattern.col(j) {
                let il = local[pattern.row_idx[p] as usize];
                if il != u32::MAX {
                    let c = il.min(jl) as usize;
                    row_idx[fill[c] as usize] = il.max(jl);
                    gather[fill[c] as usize] = p as u32;
                    fill[c] += 1;
                }
            }
        }
        // Rows stay unsorted: faer's analysis and factorisation do not need them sorted (they
        // get unsorted ones from their own permutation). faer 0.24 analyses an unpermuted
        // (`Identity`) matrix as an upper triangle but factorises the lower one as is: the
        // analysis gets the transposed pattern, the factorisation no copy.
        let (up_ptr, up_idx) = transpose(&col_ptr, &row_idx);
        let upper = SymbolicSparseColMatRef::new_unsorted_checked(nl, nl, &up_ptr, None, &up_idx);
        let params = CholeskySymbolicParams {
            supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
            ..Default::default()
        };
        let symbolic = factorize_symbolic_cholesky(upper, Side::Upper, SymmetricOrdering::Identity, params)
            .map_err(|e| match e {
            faer::sparse::FaerError::IndexOverflow => too_big(),
            e => Error::input("symbolic factorisation", format!("{e:?}")),
        })?;
        let tree = AssemblyTree::new(supernodal(&symbolic)).ok_or_else(|| Error::input("symbolic factorisation", "faer's supernodes do not form an assembly tree (a supernode's rows are missing from its parent's)"))?;
        Ok(Self { unknowns, col_ptr, row_idx, gather, symbolic, tree })
    }

    /// Factor values (in `l`'s memory when it fits), the trailing m x m block of L and the
    /// seconds in dense kernels, or the reduced unknown of a bad pivot.
    fn factorize(
        &self,
        values: &[f64],
        m: usize,
        mut l: Vec<f64>,
    ) -> std::result::Result<(Vec<f64>, Mat<f64>, f64), NonPositivePivot> {
        let nl = self.unknowns.len();
        let s = supernodal(&self.symbolic);
        if l.len() != self.symbolic.len_val() {
            l = vec![0.0; self.symbolic.len_val()];
        }
        let dense = self.numeric(values, &mut l)?.seconds();
        // Trailing block: every column >= nl - m, rows from the supernodes holding them.
        let llt = SupernodalLltRef::new(s, &l);
        let first = nl - m;
        let mut l_ss = Mat::<f64>::zeros(m, m);
        for sn in (0..s.n_supernodes()).rev() {
            let node = llt.supernode(sn);
            let (begin, width) = (node.start(), node.val().ncols());
            if begin + width <= first {
                break;
            }
            let rows: Vec<usize> =
                (begin..begin + width).chain(node.pattern().iter().map(|&r| r as usize)).collect();
            for j in begin.max(first)..begin + width {
                for (q, &r) in rows.iter().enumerate().filter(|(_, &r)| r >= j) {
                    l_ss[(r - first, j - first)] = node.val()[(q, j - begin)];
                }
            }
        }
        Ok((l, l_ss, dense))
    }

    fn numeric(&self, values: &[f64], l: &mut [f64]) -> std::result::Result<DenseWork, NonPositivePivot> {
        multifrontal::factorize(
            supernodal(&self.symbolic),
            &self.tree,
            &self.col_ptr,
            &self.row_idx,
            |p| values[self.gather[p] as usize],
            l,
        )
        .map_err(|e| NonPositivePivot { unknown: self.unknowns[e.unknown] })
    }

    /// faer's own (left-looking) numeric factorisation on the same structure.
    fn numeric_left_looking(
        &self,
        values: &[f64],
        l: &mut [f64],
    ) -> std::result::Result<(), NonPositivePivot> {
        let nl = self.unknowns.len();
        let local: Vec<f64> = self.gather.iter().map(|&p| values[p as usize]).collect();
        let a = SparseColMatRef::new(
            SymbolicSparseColMatRef::new_unsorted_checked(nl, nl, &self.col_ptr, None, &self.row_idx),
            &local,
        );
        let mut mem =
            MemBuffer::new(self.symbolic.factorize_numeric_llt_scratch::<f64>(Par::Seq, Default::default()));
        match self.symbolic.factorize_numeric_llt(
            l,
            a,
            Side::Lower,
            LltRegularization::default(),
            Par::Seq,
            MemStack::new(&mut mem),
            Default::default(),
        ) {
            Err(LltError::NonPositivePivot { index }) => {
                Err(NonPositivePivot { unknown: self.unknowns[index.min(nl - 1)] })
            }
            Ok(_) => Ok(()),
        }
    }

    /// [`Part::solve`] by faer's supernodal solve.
    fn solve_faer(&self, l: &[f64], y: &mut [f64], k: usize, forward: bool) {
        let s = supernodal(&self.symbolic);
        let llt = SupernodalLltRef::new(s, l);
        let mut mem = MemBuffer::new(s.solve_in_place_scratch::<f64>(k, Par::Seq));
        let rhs = faer::MatMut::from_column_major_slice_mut(y, self.unknowns.len(), k);
        if forward {
            llt.l_solve_with_conj(Conj::No, rhs, Par::Seq, MemStack::new(&mut mem));
        } else {
            llt.l_transpose_solve_with_conj(Conj::No, rhs, Par::Seq, MemStack::new(&mut mem));
        }
    }

    /// Forward (L y = b) or backward (L^T x = y) solve in place, k columns of local length.
    fn solve(&self, l: &[f64], y: &mut [f64], k: usize, forward: bool) {
        let s = supernodal(&self.symbolic);
        if forward {
            multifrontal::forward_solve(s, l, y, k);
        } else {
            multifrontal::backward_solve(s, l, y, k);
        }
    }
}
