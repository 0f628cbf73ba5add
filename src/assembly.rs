//! Assembly of the reduced system T^T K T r = T^T (f - K G g) straight from element
//! matrices: the lower-triangular CSC pattern is built once from the mesh topology, then
//! element matrices are scattered into it in parallel (elements coloured so that no two
//! in one colour share a node unknown). The full matrix is never formed.

use crate::constraints::{Reduction, Target};
use crate::element::qua4::{stiffness_bbar, stiffness_im};
use crate::element::stiffness::{stiffness, Technology, MAX_DOFS};
use crate::element::ElementKind;
use crate::error::{Error, Result};
use crate::material::Material;
use crate::mesh::Mesh;
use rayon::prelude::*;

/// What is assembled: a mesh, its materials, which material each element has, and the
/// QUA4 technology.
#[derive(Debug, Clone)]
pub struct Model<'a> {
    pub mesh: &'a Mesh,
    pub materials: Vec<Material>,
    /// Material index per element; empty means every element uses `materials[0]`.
    pub element_material: Vec<u32>,
    /// Technology of QUA4 elements (other kinds always integrate fully).
    pub tech: Technology,
}

impl<'a> Model<'a> {
    pub fn new(mesh: &'a Mesh, material: Material) -> Self {
        Self { mesh, materials: vec![material], element_material: Vec::new(), tech: Technology::Full }
    }
    /// Technology element `e` uses: `tech` for QUA4, `Full` otherwise.
    pub fn technology(&self, e: usize) -> Technology {
        if self.mesh.kind(e) == ElementKind::Qua4 { self.tech } else { Technology::Full }
    }
    pub fn material(&self, e: usize) -> &Material {
        &self.materials[self.element_material.get(e).map_or(0, |&m| m as usize)]
    }
    pub fn n_full(&self) -> usize {
        2 * self.mesh.n_nodes()
    }
    /// Element stiffness into `k`; errors on a non-positive Jacobian naming the element.
    pub fn element_stiffness(&self, e: usize, k: &mut [f64]) -> Result<()> {
        let mesh = self.mesh;
        let nodes = mesh.element_nodes(e);
        let mut x = [[0.0; 2]; 9];
        for (a, &n) in nodes.iter().enumerate() {
            x[a] = mesh.nodes[n];
        }
        let (x, d) = (&x[..nodes.len()], &self.material(e).d_matrix());
        let det = match self.technology(e) {
            Technology::Full => stiffness(mesh.kind(e), x, d, k),
            Technology::SelectiveReduced => stiffness_bbar(x, d, k),
            Technology::IncompatibleModes => stiffness_im(x, d, k),
        };
        if det > 0.0 {
            Ok(())
        } else {
            Err(Error::Mesh(format!("{} has a non-positive Jacobian determinant ({det:.3e}) at an integration point: it is inverted or degenerate", mesh.describe_element(e))))
        }
    }
}

/// Lower-triangular CSC pattern of the reduced matrix (rows sorted within each column).
#[derive(Debug, Clone)]
pub struct Pattern {
    pub n: usize,
    pub col_ptr: Vec<usize>,
    pub row_idx: Vec<usize>,
}

impl Pattern {
    pub fn nnz(&self) -> usize {
        self.row_idx.len()
    }
    /// Position of entry (row, col), row >= col.
    #[inline]
    pub fn position(&self, row: usize, col: usize) -> usize {
        let s = self.col_ptr[col];
        let rows = &self.row_idx[s..self.col_ptr[col + 1]];
        s + rows.binary_search(&row).expect("entry outside the assembled pattern")
    }
}

/// Pattern and element colouring for one mesh and one set of constraints; reused for any
/// material values and load cases.
#[derive(Debug, Clone)]
pub struct Assembler {
    pub pattern: Pattern,
    colors: Vec<Vec<usize>>,
    /// Elements that found no free colour among 64; assembled on one thread.
    serial: Vec<usize>,
    /// Reduced unknowns from here on are extra DOFs (shared by many elements).
    first_extra: usize,
}

/// Reduced unknowns an element touches, sorted and unique.
fn element_unknowns(mesh: &Mesh, red: &Reduction, e: usize, out: &mut Vec<usize>) {
    out.clear();
    for &n in mesh.element_nodes(e) {
        for c in 0..2 {
            for &(t, _) in red.terms(2 * n + c) {
                if let Target::Free(k) = t {
                    out.push(k);
                }
            }
        }
    }
    out.sort_unstable();
    out.dedup();
}

impl Assembler {
    pub fn new(mesh: &Mesh, red: &Reduction) -> Result<Self> {
        let n = red.n_free();
        if n == 0 {
            return Err(Error::input("boundary conditions", "every DOF is prescribed: nothing to solve"));
        }
        let ne = mesh.n_elements();
        // Unknowns per element (CSR), then elements per unknown (its transpose).
        let mut e_ptr = vec![0usize];
        let mut e_unk = Vec::new();
        let mut buf = Vec::new();
        for e in 0..ne {
            element_unknowns(mesh, red, e, &mut buf);
            e_unk.extend_from_slice(&buf);
            e_ptr.push(e_unk.len());
        }
        let mut u_ptr = vec![0usize; n + 1];
        e_unk.iter().for_each(|&k| u_ptr[k + 1] += 1);
        for k in 0..n {
            u_ptr[k + 1] += u_ptr[k];
        }
        let mut u_elem = vec![0usize; e_unk.len()];
        let mut fill = u_ptr.clone();
        for e in 0..ne {
            for &k in &e_unk[e_ptr[e]..e_ptr[e + 1]] {
                u_elem[fill[k]] = e;
                fill[k] += 1;
            }
        }
        // Column j holds the unknowns >= j that share an element with j. Built in chunks of
        // columns with one reusable buffer each: a Vec per column cost 3x more (1e6 columns).
        const COLS: usize = 8192;
        let chunks: Vec<(Vec<usize>, Vec<usize>)> = (0..n.div_ceil(COLS))
            .into_par_iter()
            .map(|c| {
                let (mut len, mut rows, mut buf) = (Vec::with_capacity(COLS), Vec::new(), Vec::new());
                for j in c * COLS..n.min((c + 1) * COLS) {
                    buf.clear();
                    buf.push(j); // kept even if no element touches j, so the pivot error names it
                    for &e in &u_elem[u_ptr[j]..u_ptr[j + 1]] {
                        buf.extend(e_unk[e_ptr[e]..e_ptr[e + 1]].iter().filter(|&&i| i > j));
                    }
                    buf.sort_unstable();
                    buf.dedup();
                    len.push(buf.len());
                    rows.extend_from_slice(&buf);
                }
                (len, rows)
            })
            .collect();
        let mut col_ptr = Vec::with_capacity(n + 1);
        col_ptr.push(0);
        let mut row_idx = Vec::with_capacity(chunks.iter().map(|c| c.1.len()).sum());
        for (len, rows) in &chunks {
            len.iter().for_each(|l| col_ptr.push(col_ptr.last().unwrap() + l));
            row_idx.extend_from_slice(rows);
        }
        // Greedy colouring on node unknowns (extra DOFs are accumulated per chunk instead).
        let first_extra = red.n_free_nodes;
        let mut used = vec![0u64; first_extra];
        let mut colors: Vec<Vec<usize>> = Vec::new();
        let mut serial = Vec::new();
        for e in 0..ne {
            let unk = &e_unk[e_ptr[e]..e_ptr[e + 1]];
            let taken = unk.iter().filter(|&&k| k < first_extra).fold(0u64, |m, &k| m | used[k]);
            if taken == u64::MAX {
                serial.push(e);
                continue;
            }
            let c = taken.trailing_ones() as usize;
            unk.iter().filter(|&&k| k < first_extra).for_each(|&k| used[k] |= 1 << c);
            if colors.len() <= c {
                colors.resize(c + 1, Vec::new());
            }
            colors[c].push(e);
        }
        Ok(Self { pattern: Pattern { n, col_ptr, row_idx }, colors, serial, first_extra })
    }

    /// Number of element colours (parallel passes).
    pub fn n_colors(&self) -> usize {
        self.colors.len() + usize::from(!self.serial.is_empty())
    }

    /// Assembles the reduced matrix values (lower triangle) and the reduced right-hand sides
    /// for each load case: `loads[c]` is the full nodal force vector (may be empty) and
    /// `prescribed[c]` the prescribed values g. Returns (values, rhs column-major n x cases).
    pub fn assemble(&self, model: &Model, red: &Reduction, loads: &[Vec<f64>], prescribed: &[Vec<f64>]) -> Result<(Vec<f64>, Vec<f64>)> {
        let n = self.pattern.n;
        let nc = prescribed.len();
        if loads.len() != nc || prescribed.iter().any(|g| g.len() != red.n_fixed()) {
            return Err(Error::input("load cases", format!("need {} prescribed values and one load vector per case", red.n_fixed())));
        }
        let mut values = vec![0.0; self.pattern.nnz()];
        let mut rhs = vec![0.0; n * nc];
        let nx = n - self.first_extra;
        let (vptr, rptr) = (SyncPtr(values.as_mut_ptr()), SyncPtr(rhs.as_mut_ptr()));
        // Entries between extra DOFs, and their rhs rows, are summed per thread.
        let init = || Extra { k: vec![0.0; nx * nx], f: vec![0.0; nx * nc], ke: [0.0; MAX_DOFS * MAX_DOFS] };
        let step = |mut acc: Extra, &e: &usize| -> Result<Extra> {
            model.element_stiffness(e, &mut acc.ke)?;
            // SAFETY: elements processed concurrently share no node unknown (colouring), so
            // the columns and rhs rows they write are disjoint.
            unsafe { self.scatter(model.mesh, red, e, &acc.ke, prescribed, &vptr, &rptr, &mut acc.k, &mut acc.f) };
            Ok(acc)
        };
        let merge = |mut a: Extra, b: Extra| -> Result<Extra> {
            a.k.iter_mut().zip(&b.k).for_each(|(x, y)| *x += y);
            a.f.iter_mut().zip(&b.f).for_each(|(x, y)| *x += y);
            Ok(a)
        };
        // Extra-DOF sums over fixed chunks merged in order: bitwise the same for any thread count.
        let mut total = init();
        for color in &self.colors {
            let parts = color.par_chunks(EXTRA_CHUNK).map(|c| c.iter().try_fold(init(), step)).collect::<Result<Vec<_>>>()?;
            total = parts.into_iter().try_fold(total, merge)?;
        }
        total = self.serial.iter().try_fold(total, step)?;
        for i in 0..nx {
            for j in 0..=i {
                let v = total.k[i * nx + j];
                if v != 0.0 {
                    values[self.pattern.position(self.first_extra + i, self.first_extra + j)] += v;
                }
            }
            for c in 0..nc {
                rhs[c * n + self.first_extra + i] += total.f[i * nc + c];
            }
        }
        for (c, f) in loads.iter().enumerate() {
            if !f.is_empty() {
                red.project_add(f, &mut rhs[c * n..(c + 1) * n]);
            }
        }
        Ok((values, rhs))
    }

    /// Adds one element matrix into the reduced system through the reduction terms.
    #[allow(clippy::too_many_arguments)]
    unsafe fn scatter(&self, mesh: &Mesh, red: &Reduction, e: usize, ke: &[f64], g: &[Vec<f64>], vptr: &SyncPtr, rptr: &SyncPtr, xk: &mut [f64], xf: &mut [f64]) {
        let nodes = mesh.element_nodes(e);
        let nd = 2 * nodes.len();
        let (n, fe, nc) = (self.pattern.n, self.first_extra, g.len());
        let nx = n - fe;
        for a in 0..nd {
            let ta = red.terms(2 * nodes[a / 2] + a % 2);
            for b in 0..nd {
                let kab = ke[a * nd + b];
                if kab == 0.0 {
                    continue;
                }
                let tb = red.terms(2 * nodes[b / 2] + b % 2);
                for &(ra, ca) in ta {
                    let Target::Free(ra) = ra else { continue };
                    for &(rb, cb) in tb {
                        let v = ca * cb * kab;
                        match rb {
                            Target::Free(rb) if ra >= rb => {
                                if ra >= fe && rb >= fe {
                                    xk[(ra - fe) * nx + (rb - fe)] += v;
                                } else {
                                    *vptr.0.add(self.pattern.position(ra, rb)) += v;
                                }
                            }
                            Target::Free(_) => {}
                            Target::Fixed(j) => {
                                for c in 0..nc {
                                    let f = v * g[c][j];
                                    if ra >= fe {
                                        xf[(ra - fe) * nc + c] -= f;
                                    } else {
                                        *rptr.0.add(c * n + ra) -= f;
                                    }
                                }
                            }
                        }
                    }
                }
            }
        }
    }
}

/// Elements per chunk of the per-chunk extra-DOF accumulators.
const EXTRA_CHUNK: usize = 2048;

struct Extra {
    k: Vec<f64>,
    f: Vec<f64>,
    ke: [f64; MAX_DOFS * MAX_DOFS],
}

/// A raw pointer shared across threads that write disjoint entries.
struct SyncPtr(*mut f64);
unsafe impl Sync for SyncPtr {}
unsafe impl Send for SyncPtr {}
