//! Assembly of the reduced system T^T K T r = T^T (f - K G g) straight from element
//! matrices: the lower-triangular CSC pattern is built once from the mesh topology, then
//! element matrices are scattered into it in parallel (elements coloured so that no two
//! in one colour share a node unknown). The full matrix is never formed.

use crate::error::{Error, Result};
use crate::fem::constraints::{Reduction, Target};
use crate::fem::element::qua4::{stiffness_bbar, stiffness_im};
use crate::fem::element::stiffness::{stiffness, Technology, MAX_DOFS, MAX_NODES};
use crate::fem::element::ElementKind;
use crate::fem::material::Material;
use crate::fem::mesh::Mesh;
use nalgebra::Matrix3;
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
        if self.mesh.kind(e) == ElementKind::Qua4 {
            self.tech
        } else {
            Technology::Full
        }
    }
    pub fn material(&self, e: usize) -> &Material {
        &self.materials[self.element_material.get(e).map_or(0, |&m| m as usize)]
    }
    pub fn n_full(&self) -> usize {
        2 * self.mesh.n_nodes()
    }
    /// Element stiffness into `k`; errors on a non-positive Jacobian naming the element.
    pub fn element_stiffness(&self, e: usize, k: &mut [f64]) -> Result<()> {
        self.element_stiffness_with(e, &self.material(e).d_matrix(), k)
    }

    /// Element stiffness with the element's D matrix given (computed once per material).
    fn element_stiffness_with(&self, e: usize, d: &Matrix3<f64>, k: &mut [f64]) -> Result<()> {
        let mesh = self.mesh;
        let nodes = mesh.element_nodes(e);
        let mut x = [[0.0; 2]; 9];
        for (a, &n) in nodes.iter().enumerate() {
            x[a] = mesh.nodes[n];
        }
        let x = &x[..nodes.len()];
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

/// Lower-triangular CSC pattern of the reduced matrix (rows sorted within each column), in
/// 32-bit indices: half the memory and index traffic of usize (37 MB less at 1e6 DOFs);
/// [`Assembler::new`] refuses a matrix with 2^32 stored entries or more.
#[derive(Debug, Clone)]
pub struct Pattern {
    pub n: usize,
    pub col_ptr: Vec<u32>,
    pub row_idx: Vec<u32>,
}

impl Pattern {
    pub fn nnz(&self) -> usize {
        self.row_idx.len()
    }
    /// Positions of column j's entries.
    #[inline]
    pub fn col(&self, j: usize) -> std::ops::Range<usize> {
        self.col_ptr[j] as usize..self.col_ptr[j + 1] as usize
    }
    /// Position of entry (row, col), row >= col.
    #[inline]
    pub fn position(&self, row: usize, col: usize) -> usize {
        let c = self.col(col);
        c.start + self.row_idx[c].binary_search(&(row as u32)).expect("entry outside the assembled pattern")
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
    /// Per node, its x unknown k when its DOFs are exactly the unknowns k and k + 1 and no
    /// other DOF refers to them; usize::MAX otherwise. Elements of such nodes take the
    /// fast scatter.
    plain: Vec<usize>,
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

/// Columns per parallel chunk of the pattern build (one reusable buffer per chunk: a Vec
/// per column cost 3x more at 1e6 columns).
const COLS: usize = 8192;

/// Joins per-chunk (column lengths, rows) into a pattern, copying the rows in parallel; None
/// when the entries do not fit 32-bit indices.
fn join_columns<R: Copy + Send>(
    n: usize,
    chunks: Vec<(Vec<usize>, Vec<R>)>,
    narrow: impl Fn(R) -> u32 + Sync,
) -> Option<Pattern> {
    let total: usize = chunks.iter().map(|c| c.1.len()).sum();
    if total >= u32::MAX as usize || n >= u32::MAX as usize {
        return None;
    }
    let mut col_ptr = Vec::with_capacity(n + 1);
    col_ptr.push(0u32);
    chunks.iter().flat_map(|c| &c.0).for_each(|&l| col_ptr.push(col_ptr.last().unwrap() + l as u32));
    debug_assert_eq!(col_ptr.len(), n + 1);
    let mut row_idx = vec![0u32; total];
    crate::memory::advise_huge_pages(&row_idx);
    let (mut outs, mut rest) = (Vec::with_capacity(chunks.len()), row_idx.as_mut_slice());
    for (_, rows) in &chunks {
        let (head, tail) = rest.split_at_mut(rows.len());
        outs.push(head);
        rest = tail;
    }
    chunks
        .into_par_iter()
        .zip(outs)
        .for_each(|((_, rows), out)| out.iter_mut().zip(rows).for_each(|(o, r)| *o = narrow(r)));
    Some(Pattern { n, col_ptr, row_idx })
}

/// Pattern and colouring from the unknowns of each element, for any reduction.
fn by_unknowns(mesh: &Mesh, red: &Reduction) -> Result<(Pattern, Vec<Vec<usize>>, Vec<usize>)> {
    let n = red.n_free();
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
    // Column j holds the unknowns >= j that share an element with j.
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
    let pattern = join_columns(n, chunks, |r| r as u32).ok_or_else(|| {
        Error::input(
            "mesh",
            format!("the matrix of {n} unknowns has 2^32 or more stored entries, beyond 32-bit indices"),
        )
    })?;
    // Greedy colouring on node unknowns (extra DOFs are accumulated per chunk instead).
    let fe = red.n_free_nodes;
    let (colors, serial) = colour(ne, |e| &e_unk[e_ptr[e]..e_ptr[e + 1]], fe, |k| k < fe);
    Ok((pattern, colors, serial))
}

/// Greedy colouring: each element takes the first colour that none of its conflict keys
/// (those with `counts(k)`, keys < `nk`) already has; elements finding none of 64 go to the
/// serial list.
fn colour<'a>(
    ne: usize,
    keys: impl Fn(usize) -> &'a [usize],
    nk: usize,
    counts: impl Fn(usize) -> bool,
) -> (Vec<Vec<usize>>, Vec<usize>) {
    let mut used = vec![0u64; nk];
    let mut colors: Vec<Vec<usize>> = Vec::new();
    let mut serial = Vec::new();
    for e in 0..ne {
        let unk = keys(e);
        let taken = unk.iter().filter(|&&k| counts(k)).fold(0u64, |m, &k| m | used[k]);
        if taken == u64::MAX {
            serial.push(e);
            continue;
        }
        let c = taken.trailing_ones() as usize;
        unk.iter().filter(|&&k| counts(k)).for_each(|&k| used[k] |= 1 << c);
        if colors.len() <= c {
            colors.resize(c + 1, Vec::new());
        }
        colors[c].push(e);
    }
    (colors, serial)
}

/// The same pattern and colouring as [`by_unknowns`], built from node adjacency: valid when
/// no DOF refers to another node's unknown (ties only to extra DOFs, as for a rigid plate),
/// so the elements touching a node unknown are those of its node and, since node unknowns
/// follow node order, a column's rows come sorted from the sorted neighbour nodes. None when
/// some tie refers to a node unknown.
fn by_nodes(mesh: &Mesh, red: &Reduction) -> Option<(Pattern, Vec<Vec<usize>>, Vec<usize>)> {
    let (nn, ne, n, fe) = (mesh.n_nodes(), mesh.n_elements(), red.n_free(), red.n_free_nodes);
    if n - fe > 4096 || ne.max(n) > u32::MAX as usize {
        return None; // the extra-DOF table below is dense; elements and rows are held as u32
    }
    // Unknowns of each node, sorted: its own node unknowns, then extra DOFs.
    let mut u_ptr = Vec::with_capacity(nn + 1);
    let mut u_idx = Vec::with_capacity(2 * nn);
    u_ptr.push(0);
    let mut buf = Vec::new();
    for m in 0..nn {
        buf.clear();
        for d in [2 * m, 2 * m + 1] {
            for &(t, _) in red.terms(d) {
                if let Target::Free(k) = t {
                    if k < fe && red.free_to_full[k] != d {
                        return None;
                    }
                    buf.push(k);
                }
            }
        }
        buf.sort_unstable();
        buf.dedup();
        u_idx.extend_from_slice(&buf);
        u_ptr.push(u_idx.len());
    }
    let unk = |m: usize| &u_idx[u_ptr[m]..u_ptr[m + 1]];
    // Elements per node (CSR; u32 halves the memory to fill).
    let mut n_ptr = vec![0usize; nn + 1];
    (0..ne).for_each(|e| mesh.element_nodes(e).iter().for_each(|&m| n_ptr[m + 1] += 1));
    for m in 0..nn {
        n_ptr[m + 1] += n_ptr[m];
    }
    let mut n_elem = vec![0u32; n_ptr[nn]];
    let mut fill = n_ptr[..nn].to_vec();
    for e in 0..ne {
        for &m in mesh.element_nodes(e) {
            n_elem[fill[m]] = e as u32;
            fill[m] += 1;
        }
    }
    // Node unknowns: per chunk of nodes, each node's rows (the unknowns of its sorted
    // neighbours) serve all its own columns. Rows held as u32 until joined: half the fresh
    // memory (37 MB less at strip50).
    let node_chunks: Vec<(Vec<usize>, Vec<u32>)> = (0..nn.div_ceil(COLS / 2))
        .into_par_iter()
        .map(|c| {
            // ~10 rows per column on QUA4 grids: one allocation in the common case.
            let (mut len, mut rows) = (Vec::with_capacity(COLS), Vec::with_capacity(10 * COLS));
            let (mut nb, mut col, mut extra) = (Vec::new(), Vec::new(), Vec::new());
            for m in c * (COLS / 2)..nn.min((c + 1) * (COLS / 2)) {
                let own: &[usize] = &unk(m)[..unk(m).partition_point(|&k| k < fe)];
                if own.is_empty() {
                    continue;
                }
                nb.clear();
                nb.push(m); // kept even if no element touches m, so the pivot error names it
                n_elem[n_ptr[m]..n_ptr[m + 1]]
                    .iter()
                    .for_each(|&e| nb.extend_from_slice(mesh.element_nodes(e as usize)));
                nb.sort_unstable();
                nb.dedup();
                col.clear();
                extra.clear();
                for &p in &nb {
                    for &k in unk(p) {
                        if k < fe {
                            col.push(k)
                        } else {
                            extra.push(k)
                        }
                    }
                }
                extra.sort_unstable();
                extra.dedup();
                debug_assert!(col.windows(2).all(|w| w[0] < w[1]), "node unknowns follow node order");
                for &j in own {
                    let from = col.partition_point(|&k| k < j);
                    len.push(col.len() - from + extra.len());
                    rows.extend(col[from..].iter().chain(&extra).map(|&k| k as u32));
                }
            }
            (len, rows)
        })
        .collect();
    // Extra DOFs: those >= j sharing an element with j (a few unknowns, so a dense table).
    let nx = n - fe;
    let mut pair = vec![false; nx * nx];
    let mut ex = Vec::new();
    for e in 0..ne {
        ex.clear();
        mesh.element_nodes(e)
            .iter()
            .for_each(|&m| ex.extend(unk(m).iter().filter(|&&k| k >= fe).map(|&k| k - fe)));
        for &i in &ex {
            for &j in &ex {
                pair[i * nx + j] = true;
            }
        }
    }
    let (mut len, mut rows) = (Vec::with_capacity(nx), Vec::new());
    for j in 0..nx {
        let before = rows.len();
        rows.push((fe + j) as u32);
        rows.extend((j + 1..nx).filter(|&i| pair[i * nx + j]).map(|i| (fe + i) as u32));
        len.push(rows.len() - before);
    }
    let mut chunks = node_chunks;
    chunks.push((len, rows));
    let pattern = join_columns(n, chunks, |r| r)?;
    // Colouring on nodes owning unknowns: the same as on their unknowns, since an element
    // touching such a node touches all its unknowns.
    let owner: Vec<bool> = (0..nn).map(|m| unk(m).first().is_some_and(|&k| k < fe)).collect();
    let (colors, serial) = colour(ne, |e| mesh.element_nodes(e), nn, |m| owner[m]);
    Some((pattern, colors, serial))
}

impl Assembler {
    pub fn new(mesh: &Mesh, red: &Reduction) -> Result<Self> {
        if red.n_free() == 0 {
            return Err(Error::input("boundary conditions", "every DOF is prescribed: nothing to solve"));
        }
        let fe = red.n_free_nodes;
        let (pattern, colors, serial, fast) = match by_nodes(mesh, red) {
            Some((p, c, s)) => (p, c, s, true),
            None => {
                let (p, c, s) = by_unknowns(mesh, red)?;
                (p, c, s, false)
            }
        };
        let plain = (0..mesh.n_nodes())
            .map(|m| match (red.terms(2 * m), red.terms(2 * m + 1)) {
                (&[(Target::Free(kx), cx)], &[(Target::Free(ky), cy)])
                    if fast && ky == kx + 1 && ky < fe && cx == 1.0 && cy == 1.0 =>
                {
                    kx
                }
                _ => usize::MAX,
            })
            .collect();
        Ok(Self { pattern, colors, serial, first_extra: fe, plain })
    }

    /// Pattern and colouring by the general construction, whatever the reduction (for tests
    /// of the node-level one).
    #[cfg(test)]
    fn new_general(mesh: &Mesh, red: &Reduction) -> Self {
        let (pattern, colors, serial) = by_unknowns(mesh, red).unwrap();
        Self {
            pattern,
            colors,
            serial,
            first_extra: red.n_free_nodes,
            plain: vec![usize::MAX; mesh.n_nodes()],
        }
    }

    /// Number of element colours (parallel passes).
    pub fn n_colors(&self) -> usize {
        self.colors.len() + usize::from(!self.serial.is_empty())
    }

    /// Assembles the reduced matrix values (lower triangle) and the reduced right-hand sides
    /// for each load case: `loads[c]` is the full nodal force vector (may be empty) and
    /// `prescribed[c]` the prescribed values g. Returns (values, rhs column-major n x cases).
    pub fn assemble(
        &self,
        model: &Model,
        red: &Reduction,
        loads: &[Vec<f64>],
        prescribed: &[Vec<f64>],
    ) -> Result<(Vec<f64>, Vec<f64>)> {
        let n = self.pattern.n;
        let nc = prescribed.len();
        if loads.len() != nc || prescribed.iter().any(|g| g.len() != red.n_fixed()) {
            return Err(Error::input(
                "load cases",
                format!("need {} prescribed values and one load vector per case", red.n_fixed()),
            ));
        }
        let mut values = vec![0.0; self.pattern.nnz()];
        crate::memory::advise_huge_pages(&values);
        let mut rhs = vec![0.0; n * nc];
        let nx = n - self.first_extra;
        let (vptr, rptr) = (SyncPtr(values.as_mut_ptr()), SyncPtr(rhs.as_mut_ptr()));
        let d: Vec<Matrix3<f64>> = model.materials.iter().map(|m| m.d_matrix()).collect();
        let mesh = model.mesh;
        // Entries between extra DOFs, and their rhs rows, are summed per chunk of elements.
        let new_extra = || Extra { k: vec![0.0; nx * nx], f: vec![0.0; nx * nc] };
        let run = |elems: &[usize], acc: &mut Extra| -> Result<()> {
            let (mut ke, mut ks) = ([0.0; MAX_DOFS * MAX_DOFS], [0usize; MAX_NODES]);
            for &e in elems {
                model.element_stiffness_with(
                    e,
                    &d[model.element_material.get(e).map_or(0, |&m| m as usize)],
                    &mut ke,
                )?;
                let nodes = mesh.element_nodes(e);
                nodes.iter().zip(&mut ks).for_each(|(&m, k)| *k = self.plain[m]);
                // SAFETY: elements processed concurrently share no node unknown (colouring), so
                // the columns and rhs rows they write are disjoint.
                unsafe {
                    if ks[..nodes.len()].iter().all(|&k| k != usize::MAX) {
                        self.scatter_plain(&ks[..nodes.len()], &ke, &vptr);
                    } else {
                        self.scatter(mesh, red, e, &ke, prescribed, &vptr, &rptr, &mut acc.k, &mut acc.f);
                    }
                }
            }
            Ok(())
        };
        // Extra-DOF sums over fixed chunks merged in order: bitwise the same for any thread count.
        let mut total = new_extra();
        for color in &self.colors {
            let parts = color.par_chunks(EXTRA_CHUNK).map(|c| {
                let mut acc = new_extra();
                run(c, &mut acc).map(|_| acc)
            });
            for b in parts.collect::<Result<Vec<_>>>()? {
                total.k.iter_mut().zip(&b.k).for_each(|(x, y)| *x += y);
                total.f.iter_mut().zip(&b.f).for_each(|(x, y)| *x += y);
            }
        }
        run(&self.serial, &mut total)?;
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

    /// Adds the element matrix of an element whose every node has the plain unknowns
    /// ks[a], ks[a] + 1: one pattern search per node pair places its 2x2 block, since rows
    /// k, k + 1 are adjacent in a column and column k + 1 is column k without row k.
    /// Bitwise the same sums as [`Assembler::scatter`] (coefficients 1).
    ///
    /// # Safety
    /// No other thread may write the columns of these unknowns meanwhile.
    unsafe fn scatter_plain(&self, ks: &[usize], ke: &[f64], vptr: &SyncPtr) {
        let nd = 2 * ks.len();
        let mut ord = [0usize; MAX_NODES];
        let ord = &mut ord[..ks.len()];
        ord.iter_mut().enumerate().for_each(|(i, o)| *o = i);
        ord.sort_unstable_by_key(|&a| ks[a]);
        let (cp, ri) = (&self.pattern.col_ptr, &self.pattern.row_idx);
        // Every index written is checked against the pattern first (raw writes below).
        let add = |p: usize, v: f64| *vptr.0.add(p) += v;
        for (i, &b) in ord.iter().enumerate() {
            let kb = ks[b];
            let (s0, s1, s2) = (cp[kb] as usize, cp[kb + 1] as usize, cp[kb + 2] as usize);
            let kb32 = kb as u32;
            assert!(
                s1 - s0 == s2 - s1 + 1
                    && s0 + 1 < s1
                    && ri[s0] == kb32
                    && ri[s0 + 1] == kb32 + 1
                    && ri[s1] == kb32 + 1,
                "entry outside the assembled pattern"
            );
            let (bx, by) = (2 * b * nd + 2 * b, (2 * b + 1) * nd + 2 * b);
            add(s0, ke[bx]);
            add(s0 + 1, ke[by]);
            add(s1, ke[by + 1]);
            let mut p = s0 + 2;
            for &a in &ord[i + 1..] {
                let ka = ks[a] as u32;
                p += ri[p..s1].partition_point(|&r| r < ka);
                let q = p - s0 + s1 - 1;
                assert!(
                    p + 1 < s1 && ri[p] == ka && ri[p + 1] == ka + 1,
                    "entry outside the assembled pattern"
                );
                let (ax, ay) = (2 * a * nd + 2 * b, (2 * a + 1) * nd + 2 * b);
                add(p, ke[ax]);
                add(p + 1, ke[ay]);
                add(q, ke[ax + 1]);
                add(q + 1, ke[ay + 1]);
                p += 2;
            }
        }
    }

    /// Adds one element matrix into the reduced system through the reduction terms.
    #[allow(clippy::too_many_arguments)]
    unsafe fn scatter(
        &self,
        mesh: &Mesh,
        red: &Reduction,
        e: usize,
        ke: &[f64],
        g: &[Vec<f64>],
        vptr: &SyncPtr,
        rptr: &SyncPtr,
        xk: &mut [f64],
        xf: &mut [f64],
    ) {
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
}

/// A raw pointer shared across threads that write disjoint entries.
struct SyncPtr(*mut f64);
unsafe impl Sync for SyncPtr {}
unsafe impl Send for SyncPtr {}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{PlateModel, Scene};

    /// The paper's strip with h = t / ny, interior nodes moved so elements are not rectangles.
    fn strip(ny: usize, element: &str, plate: PlateModel) -> crate::scene::SceneModel {
        let mut s = Scene::default();
        s.mesh.h = s.block.thickness / ny as f64;
        s.mesh.n_thick = Some(ny);
        s.mesh.element = element.into();
        s.plate.model = plate;
        let mut sm = s.build().unwrap();
        let (h, t) = (s.mesh.h, s.block.thickness);
        for (k, p) in sm.mesh.nodes.iter_mut().enumerate() {
            if p[1] > 0.0 && p[1] < t {
                p[0] += 0.1 * h * (((k * 7) % 11) as f64 / 11.0 - 0.5);
                p[1] += 0.1 * h * (((k * 5) % 13) as f64 / 13.0 - 0.5);
            }
        }
        sm
    }

    fn cases() -> Vec<crate::scene::SceneModel> {
        vec![
            strip(4, "qua4", PlateModel::Rigid),
            strip(3, "qua8", PlateModel::Rigid),
            strip(2, "tri6", PlateModel::Rigid),
            strip(3, "qua4-im", PlateModel::Rigid),
            strip(2, "qua4", PlateModel::Elastic),
        ]
    }

    #[test]
    fn node_pattern_and_colouring_match_the_general_ones() {
        for sm in cases() {
            let red = sm.constraints.reduce().unwrap();
            assert!(by_nodes(&sm.mesh, &red).is_some());
            let (a, b) = (Assembler::new(&sm.mesh, &red).unwrap(), Assembler::new_general(&sm.mesh, &red));
            assert_eq!((&a.pattern.col_ptr, &a.pattern.row_idx), (&b.pattern.col_ptr, &b.pattern.row_idx));
            assert_eq!((&a.colors, &a.serial), (&b.colors, &b.serial));
            assert!(a.plain.iter().any(|&k| k != usize::MAX));
        }
    }

    #[test]
    fn ties_between_nodes_take_the_general_construction() {
        let sm = strip(2, "qua4", PlateModel::Rigid);
        let mut c = sm.constraints.clone();
        // An interior node's u follows its right neighbour's (row 1 of the 400 x 2 grid).
        c.tie(crate::fem::constraints::dof(406, 0), &[(crate::fem::constraints::dof(407, 0), 0.5)]);
        let red = c.reduce().unwrap();
        assert!(by_nodes(&sm.mesh, &red).is_none());
        let a = Assembler::new(&sm.mesh, &red).unwrap();
        assert!(a.plain.iter().all(|&k| k == usize::MAX));
    }

    #[test]
    fn fast_scatter_is_bitwise_the_general_one_and_matches_a_matrix_free_product() {
        for sm in cases() {
            let model = sm.model();
            let red = sm.constraints.reduce().unwrap();
            let g: Vec<Vec<f64>> = (0..2)
                .map(|c| (0..red.n_fixed()).map(|j| ((j * 7 + c * 3) % 5) as f64 - 2.0).collect())
                .collect();
            let f: Vec<Vec<f64>> = vec![(0..red.n_full).map(|d| (d % 7) as f64).collect(), vec![]];
            let (a, b) = (Assembler::new(&sm.mesh, &red).unwrap(), Assembler::new_general(&sm.mesh, &red));
            let (va, ra) = a.assemble(&model, &red, &f, &g).unwrap();
            let (vb, rb) = b.assemble(&model, &red, &f, &g).unwrap();
            assert!(va.iter().zip(&vb).all(|(x, y)| x.to_bits() == y.to_bits()), "matrix values differ");
            assert!(ra.iter().zip(&rb).all(|(x, y)| x.to_bits() == y.to_bits()), "right-hand sides differ");
            // K x from the stored lower triangle against T^T (sum_e K_e (T x)_e).
            let p = &a.pattern;
            let x: Vec<f64> = (0..p.n).map(|i| ((i * 13) % 17) as f64 / 17.0 - 0.4).collect();
            let mut kx = vec![0.0; p.n];
            for j in 0..p.n {
                for k in p.col(j) {
                    let i = p.row_idx[k] as usize;
                    kx[i] += va[k] * x[j];
                    if i != j {
                        kx[j] += va[k] * x[i];
                    }
                }
            }
            let u = red.expand(&x, &vec![0.0; red.n_fixed()]);
            let all: Vec<usize> = (0..sm.mesh.n_elements()).collect();
            let mut fu = crate::fem::recovery::internal_forces(&model, &u, &all).unwrap();
            fu.resize(red.n_full, 0.0);
            let mut want = vec![0.0; p.n];
            red.project_add(&fu, &mut want);
            let scale = want.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let err = kx.iter().zip(&want).fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
            assert!(err <= 1e-12 * scale, "K x off by {:.2e} relative", err / scale);
        }
    }
}
