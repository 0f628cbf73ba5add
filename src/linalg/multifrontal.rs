//! Multifrontal numeric Cholesky on faer's supernodal symbolic structure, writing the factor in
//! faer's layout so that faer's supernodal solves read it as their own.
//!
//! faer's numeric factorisation is left-looking: every supernode gathers, from each descendant
//! that updates it, one small product scattered into its columns. On a thin strip most
//! supernodes are narrow (50,000 per half of the 1e6-DOF strip), and those many small calls
//! took 2-3x the time faer's own dense kernels need on the same fronts. Here each supernode
//! costs one dense Cholesky, one triangular solve and one rank-w update: the update matrix is
//! handed to the parent supernode and added into its front (extend-add).

use super::NonPositivePivot;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt;
use faer::linalg::cholesky::llt::factor::{LltError, LltRegularization};
use faer::linalg::matmul::triangular::{self, BlockStructure};
use faer::sparse::linalg::cholesky::supernodal::SymbolicSupernodalCholesky;
use faer::sparse::linalg::cholesky::{SymbolicCholesky, SymbolicCholeskyRaw};
use faer::{Accum, MatMut, Par};

/// Children of each supernode in the assembly tree.
pub struct AssemblyTree {
    child_ptr: Vec<u32>,
    children: Vec<u32>,
}

impl AssemblyTree {
    /// The tree of `s`, or `None` when a supernode's rows are not all in its parent's front
    /// (or not sorted), which a multifrontal factorisation needs.
    pub fn new(s: &SymbolicSupernodalCholesky<u32>) -> Option<Self> {
        let ns = s.n_supernodes();
        let (begin, end) = (s.supernode_begin(), s.supernode_end());
        let mut owner = vec![0u32; s.nrows()];
        for k in 0..ns {
            owner[begin[k] as usize..end[k] as usize].fill(k as u32);
        }
        let mut parent = vec![u32::MAX; ns];
        for (k, par) in parent.iter_mut().enumerate() {
            let rows = pattern(s, k);
            let Some(&first) = rows.first() else { continue };
            let p = owner[first as usize] as usize;
            // Rows past the parent's columns must be in the parent's pattern (both sorted).
            let mut prow = pattern(s, p).iter().peekable();
            for (i, &r) in rows.iter().enumerate() {
                if i > 0 && r <= rows[i - 1] {
                    return None;
                }
                if r >= end[p] {
                    while prow.next_if(|&&q| q < r).is_some() {}
                    prow.next_if_eq(&&r)?;
                }
            }
            *par = p as u32;
        }
        let mut child_ptr = vec![0u32; ns + 1];
        parent.iter().filter(|&&p| p != u32::MAX).for_each(|&p| child_ptr[p as usize + 1] += 1);
        for k in 0..ns {
            child_ptr[k + 1] += child_ptr[k];
        }
        let (mut children, mut next) = (vec![0u32; child_ptr[ns] as usize], child_ptr.clone());
        for (k, &p) in parent.iter().enumerate().filter(|(_, &p)| p != u32::MAX) {
            children[next[p as usize] as usize] = k as u32;
            next[p as usize] += 1;
        }
        Some(Self { child_ptr, children })
    }

    fn children(&self, k: usize) -> &[u32] {
        &self.children[self.child_ptr[k] as usize..self.child_ptr[k + 1] as usize]
    }
}

/// The supernodal structure of an analysis forced to be supernodal.
pub(crate) fn supernodal(s: &SymbolicCholesky<u32>) -> &SymbolicSupernodalCholesky<u32> {
    match s.raw() {
        SymbolicCholeskyRaw::Supernodal(s) => s,
        SymbolicCholeskyRaw::Simplicial(_) => unreachable!("analysed with FORCE_SUPERNODAL"),
    }
}

/// Rows below the diagonal block of supernode `k`.
fn pattern(s: &SymbolicSupernodalCholesky<u32>, k: usize) -> &[u32] {
    let rp = s.col_ptr_for_row_idx();
    &s.row_idx()[rp[k] as usize..rp[k + 1] as usize]
}

/// Upper bounds of the supernode widths by which [`DenseWork`] sorts the dense kernels' work.
pub const WIDTH_CLASSES: [usize; 4] = [8, 32, 64, usize::MAX];

/// The dense kernels' work in one factorisation (Cholesky, triangular solve and rank-w update
/// per supernode), by supernode width (`WIDTH_CLASSES`): their rate on these fronts bounds
/// the whole factorisation's, and the narrow fronts of a strip are where it falls.
#[derive(Clone, Copy, Debug, Default)]
pub struct DenseWork {
    /// Supernodes, flops (sum over their columns of (column count)^2, as
    /// `substructure::supernodal_flops`) and seconds in the kernels, per width class.
    pub by_width: [(usize, f64, f64); 4],
}

/// Flops of a supernode `w` columns wide with `r` rows below them: the sum over its columns of
/// (column count)^2.
pub(crate) fn supernode_flops(w: usize, r: usize) -> f64 {
    (0..w).map(|j| ((w - j + r) as f64).powi(2)).sum()
}

impl DenseWork {
    fn add(&mut self, w: usize, r: usize, seconds: f64) {
        let class = &mut self.by_width[WIDTH_CLASSES.iter().position(|&m| w <= m).unwrap_or(3)];
        class.0 += 1;
        class.1 += supernode_flops(w, r);
        class.2 += seconds;
    }

    /// Both factorisations' work.
    pub fn merge(mut self, other: &Self) -> Self {
        for (a, b) in self.by_width.iter_mut().zip(&other.by_width) {
            *a = (a.0 + b.0, a.1 + b.1, a.2 + b.2);
        }
        self
    }

    /// Seconds in the dense kernels.
    pub fn seconds(&self) -> f64 {
        self.by_width.iter().map(|c| c.2).sum()
    }
}

/// Factorises the matrix whose lower triangle is given column by column (`col_ptr`,
/// `row_idx` with row >= column, rows in any order; `value(p)` is entry p) into `l`
/// (`s.len_val()` long, any contents). Returns the dense kernels' work; a non-positive pivot
/// is returned with its column.
pub fn factorize(
    s: &SymbolicSupernodalCholesky<u32>,
    tree: &AssemblyTree,
    col_ptr: &[u32],
    row_idx: &[u32],
    value: impl Fn(usize) -> f64,
    l: &mut [f64],
) -> Result<DenseWork, NonPositivePivot> {
    let ns = s.n_supernodes();
    let (begin, end, val_ptr) = (s.supernode_begin(), s.supernode_end(), s.col_ptr_for_val());
    let widest = (0..ns).map(|k| (end[k] - begin[k]) as usize).max().unwrap_or(0);
    let mut mem =
        MemBuffer::new(llt::factor::cholesky_in_place_scratch::<f64>(widest, Par::Seq, Default::default()));
    // Position in the current front of each row; rows of a front are its columns, then its
    // pattern, so positions grow with the row and the lower triangle maps to the lower one.
    let mut pos = vec![0u32; s.nrows()];
    let (mut map, mut taken) = (Vec::new(), Vec::new());
    // Update matrix (r x r, lower triangle) of each supernode until its parent takes it.
    let mut update: Vec<Vec<f64>> = (0..ns).map(|_| Vec::new()).collect();
    // Consumed update buffers are reused: fresh large ones would be mapped and unmapped each time.
    let mut spare: Vec<Vec<f64>> = Vec::new();
    let mut dense = DenseWork::default();
    for k in 0..ns {
        let (b, e) = (begin[k] as usize, end[k] as usize);
        let rows = pattern(s, k);
        let (w, r) = (e - b, rows.len());
        let h = w + r;
        (b..e).for_each(|j| pos[j] = (j - b) as u32);
        rows.iter().enumerate().for_each(|(i, &row)| pos[row as usize] = (w + i) as u32);
        let panel = &mut l[val_ptr[k] as usize..val_ptr[k + 1] as usize];
        // Written before it is read: a fresh zero page read first is mapped shared and then
        // copied on the first write, with a TLB flush on every core.
        panel.fill(0.0);
        for j in b..e {
            let column = &mut panel[(j - b) * h..(j - b + 1) * h];
            for p in col_ptr[j] as usize..col_ptr[j + 1] as usize {
                column[pos[row_idx[p] as usize] as usize] += value(p);
            }
        }
        // The smallest spare that fits, else a new one (growing a spare would copy it). Its
        // contents do not matter: the rank-w update below overwrites the lower triangle.
        let fit =
            (0..spare.len()).filter(|&i| spare[i].capacity() >= r * r).min_by_key(|&i| spare[i].capacity());
        let mut u = fit.map(|i| spare.swap_remove(i)).unwrap_or_else(|| Vec::with_capacity(r * r));
        if u.len() < r * r {
            u.resize(r * r, 0.0);
        }
        u.truncate(r * r);
        // The children's columns that fall on this supernode's columns go into the panel now;
        // the rest go into the update matrix once the rank-w update has written it.
        taken.clear();
        for &c in tree.children(k) {
            let uc = std::mem::take(&mut update[c as usize]);
            front_rows(pattern(s, c as usize), &pos, &mut map);
            let split = map.partition_point(|&p| p < w);
            extend_add(&map, &uc, 0..split, panel, h, 0);
            taken.push((c, split, uc));
        }
        let clock = std::time::Instant::now();
        let (mut top, mut bottom) = MatMut::from_column_major_slice_mut(panel, h, w).split_at_row_mut(w);
        if let Err(LltError::NonPositivePivot { index }) = llt::factor::cholesky_in_place(
            top.as_mut(),
            LltRegularization::default(),
            Par::Seq,
            MemStack::new(&mut mem),
            Default::default(),
        ) {
            return Err(NonPositivePivot { unknown: b + index });
        }
        if r > 0 {
            faer::linalg::triangular_solve::solve_lower_triangular_in_place(
                top.as_ref(),
                bottom.as_mut().transpose_mut(),
                Par::Seq,
            );
            let um = MatMut::from_column_major_slice_mut(&mut u, r, r);
            triangular::matmul(
                um,
                BlockStructure::TriangularLower,
                Accum::Replace,
                bottom.as_ref(),
                BlockStructure::Rectangular,
                bottom.as_ref().transpose(),
                BlockStructure::Rectangular,
                -1.0,
                Par::Seq,
            );
        }
        dense.add(w, r, clock.elapsed().as_secs_f64());
        for (c, split, uc) in taken.drain(..) {
            front_rows(pattern(s, c as usize), &pos, &mut map);
            extend_add(&map, &uc, split..map.len(), &mut u, r, w);
            spare.push(uc);
        }
        if r > 0 {
            update[k] = u;
        } else {
            spare.push(u);
        }
    }
    Ok(dense)
}

/// Places in the current front of a child's rows.
fn front_rows(rows: &[u32], pos: &[u32], map: &mut Vec<usize>) {
    map.clear();
    map.extend(rows.iter().map(|&row| pos[row as usize] as usize));
}

/// Adds columns `cols` of a child's update matrix `uc` (lower triangle, column-major) into the
/// front: child row i is front row `map[i]`, and front entry (i, j) is `dst[(j - off) * ld + i - off]`.
fn extend_add(
    map: &[usize],
    uc: &[f64],
    cols: std::ops::Range<usize>,
    dst: &mut [f64],
    ld: usize,
    off: usize,
) {
    let rc = map.len();
    for jc in cols {
        let col = &mut dst[(map[jc] - off) * ld..(map[jc] - off + 1) * ld];
        for (&pi, &v) in map[jc..].iter().zip(&uc[jc * rc + jc..(jc + 1) * rc]) {
            col[pi - off] += v;
        }
    }
}

/// Forward substitution L y = b in place, for the k columns of `y` (n x k, column-major), on a
/// factor in faer's supernodal layout. faer's own solve makes a few dense calls per
/// supernode, which for a handful of right-hand sides and 50,000 narrow supernodes per half
/// cost more than the pass over L itself; here each column of L is read once and used for
/// every right-hand side while it is in L1.
pub fn forward_solve(s: &SymbolicSupernodalCholesky<u32>, l: &[f64], y: &mut [f64], k: usize) {
    let n = s.nrows();
    // Updates to the rows below a supernode, gathered contiguously and scattered once.
    let mut t = vec![0.0; widest_pattern(s) * k];
    for sn in 0..s.n_supernodes() {
        let (b, w, rows, panel) = supernode(s, l, sn);
        let (e, r) = (b + w, rows.len());
        let h = w + r;
        t[..r * k].fill(0.0);
        for j in 0..w {
            let col = &panel[j * h..(j + 1) * h];
            for c in 0..k {
                let yc = &mut y[c * n + b..c * n + e];
                let xj = yc[j] / col[j];
                yc[j] = xj;
                yc[j + 1..].iter_mut().zip(&col[j + 1..w]).for_each(|(yi, &lij)| *yi -= lij * xj);
                t[c * r..(c + 1) * r].iter_mut().zip(&col[w..]).for_each(|(ti, &lij)| *ti -= lij * xj);
            }
        }
        for c in 0..k {
            rows.iter().zip(&t[c * r..(c + 1) * r]).for_each(|(&row, &ti)| y[c * n + row as usize] += ti);
        }
    }
}

/// Backward substitution L^T x = y in place, as [`forward_solve`].
pub fn backward_solve(s: &SymbolicSupernodalCholesky<u32>, l: &[f64], y: &mut [f64], k: usize) {
    let n = s.nrows();
    // The solved unknowns below a supernode, gathered contiguously once.
    let mut t = vec![0.0; widest_pattern(s) * k];
    for sn in (0..s.n_supernodes()).rev() {
        let (b, w, rows, panel) = supernode(s, l, sn);
        let (e, r) = (b + w, rows.len());
        let h = w + r;
        for c in 0..k {
            t[c * r..(c + 1) * r].iter_mut().zip(rows).for_each(|(ti, &row)| *ti = y[c * n + row as usize]);
        }
        // The rows below first, then the diagonal block.
        for j in 0..w {
            let col = &panel[j * h + w..(j + 1) * h];
            for c in 0..k {
                y[c * n + b + j] -= dot(col, &t[c * r..(c + 1) * r]);
            }
        }
        for j in (0..w).rev() {
            let col = &panel[j * h..j * h + w];
            for c in 0..k {
                let yc = &mut y[c * n + b..c * n + e];
                yc[j] = (yc[j] - dot(&col[j + 1..], &yc[j + 1..])) / col[j];
            }
        }
    }
}

/// Supernode `sn` of the factor `l`: its first column, its width, the rows below its diagonal
/// block, and its panel (column-major; rows: its own columns, then those rows).
fn supernode<'a>(
    s: &'a SymbolicSupernodalCholesky<u32>,
    l: &'a [f64],
    sn: usize,
) -> (usize, usize, &'a [u32], &'a [f64]) {
    let (b, vp) = (s.supernode_begin()[sn] as usize, s.col_ptr_for_val());
    (b, s.supernode_end()[sn] as usize - b, pattern(s, sn), &l[vp[sn] as usize..vp[sn + 1] as usize])
}

fn widest_pattern(s: &SymbolicSupernodalCholesky<u32>) -> usize {
    s.col_ptr_for_row_idx().windows(2).map(|w| (w[1] - w[0]) as usize).max().unwrap_or(0)
}

/// Dot product with eight partial sums, so that the additions do not wait on each other
/// (`benches/kernels.rs`: the backward solve of strip t/50 is 10 % faster than with four).
fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut acc = [0.0; 8];
    let (ca, cb) = (a.chunks_exact(8), b.chunks_exact(8));
    let tail: f64 = ca.remainder().iter().zip(cb.remainder()).map(|(x, y)| x * y).sum();
    for (x, y) in ca.zip(cb) {
        for q in 0..8 {
            acc[q] += x[q] * y[q];
        }
    }
    ((acc[0] + acc[4]) + (acc[2] + acc[6])) + ((acc[1] + acc[5]) + (acc[3] + acc[7])) + tail
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::sparse::linalg::cholesky::{
        factorize_symbolic_cholesky, CholeskySymbolicParams, SymmetricOrdering,
    };
    use faer::sparse::linalg::SupernodalThreshold;
    use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
    use faer::Side;

    /// Lower triangle (CSC) of a 9-point-stencil matrix on an nx x ny grid, natural order:
    /// diagonal `diag`, off-diagonals in [-1, 0) varying with the entry.
    fn grid(nx: usize, ny: usize, diag: impl Fn(usize) -> f64) -> (Vec<u32>, Vec<u32>, Vec<f64>) {
        let (mut ptr, mut idx, mut val) = (vec![0u32], Vec::new(), Vec::new());
        for j in 0..nx * ny {
            let (x, y) = ((j % nx) as isize, (j / nx) as isize);
            // The node itself and its neighbours later in the natural order.
            for (dx, dy) in [(0, 0), (1, 0), (-1, 1), (0, 1), (1, 1)] {
                let (xi, yi) = (x + dx, y + dy);
                if xi < 0 || xi >= nx as isize || yi >= ny as isize {
                    continue;
                }
                let i = yi as usize * nx + xi as usize;
                idx.push(i as u32);
                val.push(if i == j { diag(j) } else { -0.5 - ((i * 7 + j * 3) % 5) as f64 / 10.0 });
            }
            ptr.push(idx.len() as u32);
        }
        (ptr, idx, val)
    }

    fn symbolic(ptr: &[u32], idx: &[u32]) -> SymbolicCholesky<u32> {
        let n = ptr.len() - 1;
        let a = SymbolicSparseColMatRef::new_unsorted_checked(n, n, ptr, None, idx);
        let params = CholeskySymbolicParams {
            supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
            ..Default::default()
        };
        // The lower triangle read as the upper triangle of the transpose: same structure.
        let upper = a.transpose().to_col_major().unwrap();
        factorize_symbolic_cholesky(upper.as_ref(), Side::Upper, SymmetricOrdering::Identity, params).unwrap()
    }

    /// Largest difference between our factor and faer's left-looking numeric one, over the
    /// lower triangles (the strict upper part of each diagonal block is not part of L), and the
    /// most children any supernode has in the assembly tree.
    fn difference_from_faer(ptr: &[u32], idx: &[u32], val: &[f64]) -> (f64, usize) {
        let sym = symbolic(ptr, idx);
        let s = supernodal(&sym);
        let tree = AssemblyTree::new(s).expect("faer's supernodes form an assembly tree");
        let mut ours = vec![f64::NAN; s.len_val()];
        let dense = factorize(s, &tree, ptr, idx, |p| val[p], &mut ours).unwrap();
        assert!(dense.seconds() > 0.0);
        assert_eq!(dense.by_width.iter().map(|c| c.0).sum::<usize>(), s.n_supernodes());
        // Every column's count squared, once: the same total as the analysis gives.
        let flops: f64 = dense.by_width.iter().map(|c| c.1).sum();
        assert_eq!(flops, crate::linalg::substructure::supernodal_flops(s));
        let n = ptr.len() - 1;
        let a =
            SparseColMatRef::new(SymbolicSparseColMatRef::new_unsorted_checked(n, n, ptr, None, idx), val);
        let mut theirs = vec![0.0; s.len_val()];
        let mut mem = MemBuffer::new(sym.factorize_numeric_llt_scratch::<f64>(Par::Seq, Default::default()));
        sym.factorize_numeric_llt(
            &mut theirs,
            a,
            Side::Lower,
            LltRegularization::default(),
            Par::Seq,
            MemStack::new(&mut mem),
            Default::default(),
        )
        .unwrap();
        let (begin, end, vp) = (s.supernode_begin(), s.supernode_end(), s.col_ptr_for_val());
        let mut worst = 0.0f64;
        for k in 0..s.n_supernodes() {
            let w = (end[k] - begin[k]) as usize;
            let h = (vp[k + 1] - vp[k]) as usize / w;
            for j in 0..w {
                for i in j..h {
                    let q = vp[k] as usize + j * h + i;
                    worst = worst.max((ours[q] - theirs[q]).abs());
                }
            }
        }
        let most_children = (0..s.n_supernodes()).map(|k| tree.children(k).len()).max().unwrap_or(0);
        (worst, most_children)
    }

    /// Same factor as faer's left-looking numeric, to round-off (entries of L are O(1) here).
    #[test]
    fn matches_faer_numeric() {
        let (ptr, idx, val) = grid(23, 17, |j| 8.0 + (j % 3) as f64);
        assert!(
            supernodal(&symbolic(&ptr, &idx)).n_supernodes() > 20,
            "the test needs a tree, not one front"
        );
        let (worst, _) = difference_from_faer(&ptr, &idx, &val);
        assert!(worst < 1e-13, "largest difference {worst:e}");
    }

    /// Lower triangle (CSC) of a random matrix whose elimination tree is a random tree: each
    /// column's parent is one of the next `span` columns and it couples to a random subset of
    /// its ancestors, so supernodes get many children and fronts many extend-adds. Strictly
    /// diagonally dominant, hence SPD with O(1) factor entries.
    fn random_tree_matrix(n: usize, span: usize, seed: u64) -> (Vec<u32>, Vec<u32>, Vec<f64>) {
        let mut state = seed;
        let mut next = move || {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (state >> 33) as usize
        };
        let parent: Vec<usize> =
            (0..n).map(|j| if j + 1 < n { j + 1 + next() % span.min(n - 1 - j) } else { n }).collect();
        let mut cols: Vec<Vec<(usize, f64)>> = vec![Vec::new(); n];
        let mut off_sum = vec![0.0; n];
        for j in 0..n {
            let mut a = parent[j];
            let mut first = true;
            while a < n {
                if first || next() % 3 == 0 {
                    let v = -0.1 - (next() % 9) as f64 / 10.0;
                    cols[j].push((a, v));
                    off_sum[j] += v.abs();
                    off_sum[a] += v.abs();
                }
                first = false;
                a = parent[a];
            }
        }
        let (mut ptr, mut idx, mut val) = (vec![0u32], Vec::new(), Vec::new());
        for j in 0..n {
            idx.push(j as u32);
            val.push(off_sum[j] + 1.0);
            for &(i, v) in &cols[j] {
                idx.push(i as u32);
                val.push(v);
            }
            ptr.push(idx.len() as u32);
        }
        (ptr, idx, val)
    }

    /// Branching assembly trees (a chain-shaped grid tree does not exercise extend-add from
    /// several children): random trees with up to dozens of children per supernode, twenty seeds.
    #[test]
    fn matches_faer_numeric_on_random_branching_trees() {
        let mut most = 0;
        for seed in 0..20 {
            let (ptr, idx, val) =
                random_tree_matrix(200 + 15 * seed as usize, 2 + (7 * seed as usize) % 60, seed);
            let (worst, children) = difference_from_faer(&ptr, &idx, &val);
            assert!(worst < 1e-13, "seed {seed}: largest difference {worst:e}");
            most = most.max(children);
        }
        assert!(most >= 9, "the trees branch too little: at most {most} children");
    }

    /// No right-hand side: the substitutions do nothing and do not fail.
    #[test]
    fn substitutions_with_no_right_hand_side() {
        let (ptr, idx, val) = grid(5, 4, |_| 8.0);
        let sym = symbolic(&ptr, &idx);
        let s = supernodal(&sym);
        let mut l = vec![0.0; s.len_val()];
        factorize(s, &AssemblyTree::new(s).unwrap(), &ptr, &idx, |p| val[p], &mut l).unwrap();
        let mut y: Vec<f64> = Vec::new();
        forward_solve(s, &l, &mut y, 0);
        backward_solve(s, &l, &mut y, 0);
        assert!(y.is_empty());
    }

    /// Our forward and backward substitutions solve A x = b to a residual of round-off size,
    /// ||b - A x||_inf <= 1e-14 ||A||_inf ||x||_inf (a backward-stable solve gives a small multiple
    /// of eps), for several right-hand sides at once.
    #[test]
    fn substitutions_solve_the_system() {
        let (ptr, idx, val) = grid(23, 17, |j| 8.0 + (j % 3) as f64);
        let sym = symbolic(&ptr, &idx);
        let s = supernodal(&sym);
        let tree = AssemblyTree::new(s).unwrap();
        let mut l = vec![0.0; s.len_val()];
        factorize(s, &tree, &ptr, &idx, |p| val[p], &mut l).unwrap();
        let (n, k) = (ptr.len() - 1, 3);
        let b: Vec<f64> = (0..n * k).map(|i| ((i * 37) % 11) as f64 - 5.0).collect();
        let mut x = b.clone();
        forward_solve(s, &l, &mut x, k);
        backward_solve(s, &l, &mut x, k);
        // A x from the lower triangle, and ||A||_inf.
        let (mut ax, mut row_sum) = (vec![0.0; n * k], vec![0.0; n]);
        for j in 0..n {
            for p in ptr[j] as usize..ptr[j + 1] as usize {
                let i = idx[p] as usize;
                for c in 0..k {
                    ax[c * n + i] += val[p] * x[c * n + j];
                    if i != j {
                        ax[c * n + j] += val[p] * x[c * n + i];
                    }
                }
                row_sum[i] += val[p].abs();
                if i != j {
                    row_sum[j] += val[p].abs();
                }
            }
        }
        let norm_a = row_sum.iter().fold(0.0f64, |m, &v| m.max(v));
        let norm_x = x.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let residual = b.iter().zip(&ax).fold(0.0f64, |m, (p, q)| m.max((p - q).abs()));
        assert!(
            residual <= 1e-14 * norm_a * norm_x,
            "residual {residual:e}, ||A|| ||x|| = {:e}",
            norm_a * norm_x
        );
    }

    /// A matrix that is not positive definite fails at the first column whose Schur
    /// complement pivot is not positive, the same one faer names.
    #[test]
    fn names_the_first_bad_pivot() {
        let bad = 300;
        let (ptr, idx, val) = grid(23, 17, |j| if j == bad { -1.0 } else { 8.0 });
        let sym = symbolic(&ptr, &idx);
        let s = supernodal(&sym);
        let tree = AssemblyTree::new(s).unwrap();
        let mut l = vec![0.0; s.len_val()];
        assert_eq!(
            factorize(s, &tree, &ptr, &idx, |p| val[p], &mut l).err(),
            Some(NonPositivePivot { unknown: bad })
        );
    }
}
