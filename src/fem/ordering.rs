//! Geometric nested dissection for meshes whose nodes lie on a (possibly graded) grid, such
//! as every mesh `mesher::Rectangle` builds and stacks of them. faer has no nested dissection
//! and its AMD is blind to geometry; on a grid we know perfect separators: one grid line of
//! nodes that no element straddles. Regions are bisected along their longer side, each half
//! ordered first and the separator last, down to small leaves.

use crate::fem::constraints::Reduction;
use crate::fem::mesh::Mesh;
pub use crate::linalg::pattern::Bisection;
use rayon::prelude::*;

/// Regions with at most this many grid points are ordered line by line (short side fastest).
/// Measured on the 1e6-DOF strip: 4 gives the least fill (16: +8 %, 256: +58 %).
const LEAF: usize = 4;

/// Fill-reducing permutation of the reduced unknowns (`perm[new] = old`), or None when the
/// nodes do not form a grid (then use AMD). The reduced numbering is node DOFs in node order,
/// extra DOFs last; extra DOFs (rigid bodies, coupled to many nodes) stay last.
pub fn nested_dissection(mesh: &Mesh, red: &Reduction) -> Option<Vec<usize>> {
    let grid = Grid::new(mesh)?;
    let mut nodes = Vec::with_capacity(mesh.n_nodes());
    grid.dissect([0, grid.gx], [0, grid.gy], &mut nodes);
    let mut perm = free_unknowns(&free_index(red), &nodes);
    perm.extend(red.n_free_nodes..red.n_free());
    (perm.len() == red.n_free()).then_some(perm)
}

/// The grid's first nested-dissection cut, or None when the nodes do not form a grid or a
/// half would be empty.
pub fn bisection(mesh: &Mesh, red: &Reduction) -> Option<Bisection> {
    let grid = Grid::new(mesh)?;
    let (x, y) = ([0, grid.gx], [0, grid.gy]);
    let [ra, rb, rs] = Grid::regions(x, y, grid.split(x, y)?);
    let (mut a, mut b, mut s) = (Vec::new(), Vec::new(), Vec::new());
    grid.dissect(ra[0], ra[1], &mut a);
    grid.dissect(rb[0], rb[1], &mut b);
    grid.emit(rs[0], rs[1], &mut s);
    let free = free_index(red);
    let parts = [free_unknowns(&free, &a), free_unknowns(&free, &b)];
    let mut separator = free_unknowns(&free, &s);
    separator.extend(red.n_free_nodes..red.n_free());
    let complete = parts[0].len() + parts[1].len() + separator.len() == red.n_free();
    (complete && parts.iter().all(|p| !p.is_empty())).then_some(Bisection { parts, separator })
}

/// The free unknown of each full DOF, usize::MAX for none.
fn free_index(red: &Reduction) -> Vec<usize> {
    let mut free = vec![usize::MAX; red.n_full];
    for (k, &d) in red.free_to_full.iter().enumerate() {
        free[d] = k;
    }
    free
}

/// The free unknowns of `nodes`, in that order (x before y); `free` from [`free_index`].
fn free_unknowns(free: &[usize], nodes: &[usize]) -> Vec<usize> {
    nodes.iter().flat_map(|&n| [free[2 * n], free[2 * n + 1]]).filter(|&k| k != usize::MAX).collect()
}

struct Grid {
    gx: usize,
    gy: usize,
    /// Node at grid point (i, j), index j * gx + i; usize::MAX where there is none.
    at: Vec<usize>,
    /// Whether grid line i (resp. j) can separate: no element has nodes on both sides of it.
    sep_x: Vec<bool>,
    sep_y: Vec<bool>,
}

impl Grid {
    fn new(mesh: &Mesh) -> Option<Self> {
        let n = mesh.n_nodes();
        if n == 0 {
            return None;
        }
        let scale =
            mesh.nodes.iter().fold(0.0f64, |m, p| m.max(p[0].abs()).max(p[1].abs())).max(f64::MIN_POSITIVE);
        let lines = |c: usize| -> Vec<f64> {
            let mut v: Vec<f64> = mesh.nodes.iter().map(|p| p[c]).collect();
            v.par_sort_unstable_by(f64::total_cmp);
            v.dedup_by(|a, b| (*a - *b).abs() <= 1e-9 * scale);
            v
        };
        let (xs, ys) = rayon::join(|| lines(0), || lines(1));
        let (gx, gy) = (xs.len(), ys.len());
        // An unstructured mesh has about as many distinct coordinates as nodes.
        if gx.checked_mul(gy)? > 2 * n {
            return None;
        }
        let index = |v: &[f64], x: f64| v.partition_point(|&a| a < x - 1e-9 * scale);
        let ij: Vec<(usize, usize)> =
            mesh.nodes.par_iter().map(|p| (index(&xs, p[0]), index(&ys, p[1]))).collect();
        let mut at = vec![usize::MAX; gx * gy];
        for (k, &(i, j)) in ij.iter().enumerate() {
            if std::mem::replace(&mut at[j * gx + i], k) != usize::MAX {
                return None;
            }
        }
        let (mut sep_x, mut sep_y) = (vec![true; gx], vec![true; gy]);
        for e in 0..mesh.n_elements() {
            let v = mesh.element_nodes(e);
            let (lo_i, hi_i) = v.iter().fold((usize::MAX, 0), |(a, b), &k| (a.min(ij[k].0), b.max(ij[k].0)));
            let (lo_j, hi_j) = v.iter().fold((usize::MAX, 0), |(a, b), &k| (a.min(ij[k].1), b.max(ij[k].1)));
            sep_x[lo_i + 1..hi_i.max(lo_i + 1)].iter_mut().for_each(|s| *s = false);
            sep_y[lo_j + 1..hi_j.max(lo_j + 1)].iter_mut().for_each(|s| *s = false);
        }
        Some(Self { gx, gy, at, sep_x, sep_y })
    }

    /// The separator line nearest the middle of the longer side (the other side if none):
    /// (true, i) for grid column i, (false, j) for grid row j.
    fn split(&self, x: [usize; 2], y: [usize; 2]) -> Option<(bool, usize)> {
        let pick = |r: [usize; 2], ok: &[bool]| {
            (r[0] + 1..r[1].saturating_sub(1))
                .filter(|&s| ok[s])
                .min_by_key(|&s| (2 * s).abs_diff(r[0] + r[1] - 1))
        };
        if x[1] - x[0] >= y[1] - y[0] {
            pick(x, &self.sep_x).map(|s| (true, s)).or_else(|| pick(y, &self.sep_y).map(|s| (false, s)))
        } else {
            pick(y, &self.sep_y).map(|s| (false, s)).or_else(|| pick(x, &self.sep_x).map(|s| (true, s)))
        }
    }

    /// Appends the nodes of region [x0, x1) x [y0, y1) in elimination order.
    fn dissect(&self, x: [usize; 2], y: [usize; 2], out: &mut Vec<usize>) {
        let (w, h) = (x[1] - x[0], y[1] - y[0]);
        if w == 0 || h == 0 {
            return;
        }
        match if w * h <= LEAF { None } else { self.split(x, y) } {
            Some(cut) => {
                let [a, b, s] = Self::regions(x, y, cut);
                self.dissect(a[0], a[1], out);
                self.dissect(b[0], b[1], out);
                self.emit(s[0], s[1], out);
            }
            None => self.emit(x, y, out),
        }
    }

    /// The two halves and the separator line of region [x0, x1) x [y0, y1) cut by `cut`
    /// (from [`Grid::split`]), each as its (x range, y range).
    fn regions(x: [usize; 2], y: [usize; 2], cut: (bool, usize)) -> [[[usize; 2]; 2]; 3] {
        match cut {
            (true, s) => [[[x[0], s], y], [[s + 1, x[1]], y], [[s, s + 1], y]],
            (false, s) => [[x, [y[0], s]], [x, [s + 1, y[1]]], [x, [s, s + 1]]],
        }
    }

    /// Appends the nodes of a region line by line, the shorter side varying fastest.
    fn emit(&self, x: [usize; 2], y: [usize; 2], out: &mut Vec<usize>) {
        let mut push = |i: usize, j: usize| {
            let k = self.at[j * self.gx + i];
            if k != usize::MAX {
                out.push(k);
            }
        };
        if x[1] - x[0] >= y[1] - y[0] {
            (x[0]..x[1]).for_each(|i| (y[0]..y[1]).for_each(|j| push(i, j)));
        } else {
            (y[0]..y[1]).for_each(|j| (x[0]..x[1]).for_each(|i| push(i, j)));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::constraints::{dof, Constraints};
    use crate::fem::element::ElementKind;
    use crate::fem::mesher::Rectangle;

    #[test]
    fn permutation_of_the_free_unknowns_with_extra_last() {
        for kind in ElementKind::ALL {
            let m = Rectangle::new(0.0, 3.0, 0.0, 1.0, 24, 5).kind(kind).build().unwrap();
            let mut c = Constraints::new(m.n_nodes());
            let th = c.add_extra_dof("theta");
            for n in m.set_nodes("bottom").unwrap() {
                c.fix(dof(n, 0));
                c.fix(dof(n, 1));
            }
            for n in m.set_nodes("top").unwrap() {
                c.tie(dof(n, 1), &[(th, m.nodes[n][0])]);
            }
            let red = c.reduce().unwrap();
            let p = nested_dissection(&m, &red).expect("a grid");
            let mut seen = vec![false; red.n_free()];
            p.iter().for_each(|&k| seen[k] = true);
            assert!(seen.iter().all(|&s| s) && p.len() == red.n_free(), "{kind:?}");
            assert_eq!(*p.last().unwrap(), red.n_free() - 1);
        }
    }
}
