//! K u on a regular grid of identical QUA4 elements (every mesh `Rectangle` builds without
//! grading) as a node-wise stencil: the four elements around a node collapse into nine 2x2
//! blocks, so each node's force is read off its 3 x 3 neighbourhood in three consecutive node
//! rows. No connectivity is read, nothing is scattered, and each node's sum is the same
//! expression whoever computes it: bands of rows on several threads give the same bits as one.

/// Grid offsets (column, row) of a QUA4 element's local nodes 0..3 from its first node.
const OFF: [(isize, isize); 4] = [(0, 0), (1, 0), (1, 1), (0, 1)];

/// taps[r][t] = [coefficient into f_x, into f_y] of the DOF t (0..6: x, y of nodes i-1, i,
/// i+1) of node row j - 1 + r, for node (i, j).
type Taps = [[[f64; 2]; 6]; 3];

#[derive(Debug, Clone)]
pub(super) struct Grid {
    /// Elements per row and per column; node (i, j) is j (nx + 1) + i, element (ci, cj) is
    /// cj nx + ci with nodes (ci, cj), (ci+1, cj), (ci+1, cj+1), (ci, cj+1).
    nx: usize,
    ny: usize,
    /// One set of taps per mask of the four elements around a node that exist (bit a: the
    /// element in which the node is local node a), so edges and corners need no special code.
    taps: Box<[Taps; 16]>,
}

/// Fewest nodes worth a thread of their own (spawning one costs about 20-50 us, the stencil
/// about 5 ns per node).
pub(super) const MIN_NODES_PER_THREAD: usize = 16_384;

impl Grid {
    /// The grid `conn` numbers, if it is one and `kmats` holds its single element matrix.
    pub(super) fn detect(conn: &[[u32; 4]], n_nodes: usize, kmats: &[[f64; 64]]) -> Option<Grid> {
        let ([k], Some(first)) = (kmats, conn.first()) else { return None };
        let gx = first[3] as usize;
        if gx < 2 || !conn.len().is_multiple_of(gx - 1) {
            return None;
        }
        let (nx, ny) = (gx - 1, conn.len() / (gx - 1));
        if n_nodes != gx * (ny + 1) {
            return None;
        }
        let regular = conn.iter().enumerate().all(|(e, c)| {
            let n0 = (e / nx * gx + e % nx) as u32;
            *c == [n0, n0 + 1, n0 + gx as u32 + 1, n0 + gx as u32]
        });
        if !regular {
            return None;
        }
        let mut taps = Box::new([[[[0.0; 2]; 6]; 3]; 16]);
        for (mask, t) in taps.iter_mut().enumerate() {
            for a in (0..4).filter(|a| mask >> a & 1 == 1) {
                for b in 0..4 {
                    let (dx, dy) = (OFF[b].0 - OFF[a].0, OFF[b].1 - OFF[a].1);
                    let (r, w) = ((dy + 1) as usize, (dx + 1) as usize);
                    for c in 0..2 {
                        for m in 0..2 {
                            t[r][2 * w + m][c] += k[8 * (2 * a + c) + 2 * b + m];
                        }
                    }
                }
            }
        }
        Some(Grid { nx, ny, taps })
    }

    /// DOFs in a node row.
    pub(super) fn row_len(&self) -> usize {
        2 * (self.nx + 1)
    }

    /// Node rows per band for up to `threads` threads (all rows when one band).
    fn rows_per_band(&self, threads: usize) -> usize {
        let rows = self.ny + 1;
        let bands = threads.min(rows * (self.nx + 1) / MIN_NODES_PER_THREAD).clamp(1, rows);
        rows.div_ceil(bands)
    }

    /// out = K u on up to `threads` threads, each a band of node rows.
    pub(super) fn apply(&self, u: &[f64], out: &mut [f64], threads: usize) {
        let (rows, row_len) = (self.ny + 1, 2 * (self.nx + 1));
        let per = self.rows_per_band(threads);
        if per == rows {
            self.rows(u, out, 0);
            return;
        }
        let bands: Vec<&mut [f64]> = out.chunks_mut(per * row_len).collect();
        run_bands(bands, &|b, chunk: &mut [f64]| self.rows(u, chunk, b * per));
    }

    /// One pass over the node rows for a fused explicit step: for each row j, K u of the row
    /// (and K v if `v` is given) into row buffers, then `row(j, ku, kv, outs_j)` with row j's
    /// slices of `outs`; returns its results in row order. u and v are only read (the update
    /// writes elsewhere), so bands of rows run on up to `threads` threads with the same bits.
    pub(super) fn sweep<const N: usize, A: Send>(
        &self,
        u: &[f64],
        v: Option<&[f64]>,
        outs: [&mut [f64]; N],
        threads: usize,
        row: impl Fn(usize, &[f64], &[f64], [&mut [f64]; N]) -> A + Sync,
    ) -> Vec<A> {
        let (rows, row_len) = (self.ny + 1, self.row_len());
        let band = |j0: usize, mut outs: [&mut [f64]; N]| -> Vec<A> {
            let (mut ku, mut kv) = (vec![0.0; row_len], vec![0.0; if v.is_some() { row_len } else { 0 }]);
            let n_rows = outs.first().map_or(0, |o| o.len() / row_len);
            (0..n_rows)
                .map(|dj| {
                    let j = j0 + dj;
                    self.row(u, j, &mut ku);
                    if let Some(v) = v {
                        self.row(v, j, &mut kv);
                    }
                    let mut it = outs.iter_mut().map(|o| &mut o[dj * row_len..(dj + 1) * row_len]);
                    row(j, &ku, &kv, std::array::from_fn(|_| it.next().expect("N arrays")))
                })
                .collect()
        };
        let per = self.rows_per_band(threads);
        if per == rows {
            return band(0, outs);
        }
        let mut chunks = outs.map(|o| o.chunks_mut(per * row_len));
        let bands: Vec<[&mut [f64]; N]> = (0..rows.div_ceil(per))
            .map(|_| std::array::from_fn(|k| chunks[k].next().expect("one chunk per band")))
            .collect();
        run_bands(bands, &|b, c| band(b * per, c)).into_iter().flatten().collect()
    }

    /// The forces of the node rows j0.. that `out` covers.
    fn rows(&self, u: &[f64], out: &mut [f64], j0: usize) {
        let row_len = 2 * (self.nx + 1);
        for (dj, o) in out.chunks_mut(row_len).enumerate() {
            self.row(u, j0 + dj, o);
        }
    }

    /// Forces of node row j into `out` (2 (nx + 1) values). With AVX (checked at run time,
    /// x86-64) the same loop is compiled 4 doubles wide: 2.2x faster, and the same bits,
    /// since only mul and add are used (no FMA, whose single rounding would change them).
    pub(super) fn row(&self, u: &[f64], j: usize, out: &mut [f64]) {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx") {
            // SAFETY: the CPU has AVX, the only feature row_avx is compiled with.
            return unsafe { self.row_avx(u, j, out) };
        }
        self.row_any(u, j, out)
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx")]
    fn row_avx(&self, u: &[f64], j: usize, out: &mut [f64]) {
        self.row_any(u, j, out)
    }

    #[inline(always)]
    pub(super) fn row_any(&self, u: &[f64], j: usize, out: &mut [f64]) {
        let (nx, ny) = (self.nx, self.ny);
        let row_len = 2 * (nx + 1);
        let row = |j: usize| &u[j * row_len..(j + 1) * row_len];
        // Elements present around a node of this row: below it (local 2, 3) if j >= 1,
        // above it (local 0, 1) if j < ny; left (1, 2) if i >= 1, right (0, 3) if i < nx.
        let row_mask = if j >= 1 { 0b1100 } else { 0 } | if j < ny { 0b0011 } else { 0 };
        let rows = [(j >= 1).then(|| row(j - 1)), Some(row(j)), (j < ny).then(|| row(j + 1))];
        let taps = &self.taps[row_mask];
        match rows {
            [Some(a), Some(b), Some(c)] => interior([&taps[0], &taps[1], &taps[2]], [a, b, c], out, nx),
            [None, Some(b), Some(c)] => interior([&taps[1], &taps[2]], [b, c], out, nx),
            [Some(a), Some(b), None] => interior([&taps[0], &taps[1]], [a, b], out, nx),
            _ => interior([&taps[1]], [row(j)], out, nx),
        }
        for (i, mask) in [(0, row_mask & 0b1001), (nx, row_mask & 0b0110)] {
            let f = edge_node(&self.taps[mask], &rows, i, nx);
            out[2 * i..2 * i + 2].copy_from_slice(&f);
        }
    }
}

/// `work(b, item)` for every item b: the first on this thread, the others on scoped threads
/// (an item whose thread cannot be spawned runs here afterwards, rather than a panic);
/// results in item order.
fn run_bands<T: Send, R: Send>(items: Vec<T>, work: &(impl Fn(usize, T) -> R + Sync)) -> Vec<R> {
    let mut slots: Vec<Option<T>> = items.into_iter().map(Some).collect();
    let mut out: Vec<Option<R>> = (0..slots.len()).map(|_| None).collect();
    std::thread::scope(|s| {
        let mut it = slots.iter_mut().enumerate();
        let first = it.next();
        let spawned: Vec<_> = it
            .filter_map(|(b, slot)| {
                let h = std::thread::Builder::new().spawn_scoped(s, move || slot.take().map(|t| work(b, t)));
                h.ok().map(|h| (b, h))
            })
            .collect();
        if let Some((_, slot)) = first {
            out[0] = slot.take().map(|t| work(0, t));
        }
        for (b, h) in spawned {
            out[b] = h.join().unwrap_or_else(|e| std::panic::resume_unwind(e));
        }
    });
    for (b, slot) in slots.iter_mut().enumerate() {
        if let Some(t) = slot.take() {
            out[b] = Some(work(b, t));
        }
    }
    out.into_iter().map(|r| r.expect("every band ran")).collect()
}

/// Nodes 1..nx of a row: every neighbour exists, so the loop has no branch and vectorises
/// (two nodes' (f_x, f_y) per iteration: one 4-wide register, or two 2-wide ones). Rows
/// whose taps are all zero are left out. Each sum runs over r, then t, whatever the width.
#[inline(always)]
fn interior<const R: usize>(taps: [&[[f64; 2]; 6]; R], rows: [&[f64]; R], out: &mut [f64], nx: usize) {
    let mut i = 1;
    while i + 1 < nx {
        let mut f = [0.0f64; 4];
        for r in 0..R {
            let w: &[f64; 8] = rows[r][2 * i - 2..2 * i + 6].try_into().expect("8 DOFs");
            for t in 0..6 {
                f[0] += taps[r][t][0] * w[t];
                f[1] += taps[r][t][1] * w[t];
                f[2] += taps[r][t][0] * w[t + 2];
                f[3] += taps[r][t][1] * w[t + 2];
            }
        }
        out[2 * i..2 * i + 4].copy_from_slice(&f);
        i += 2;
    }
    for i in i..nx {
        let mut f = [0.0f64; 2];
        for r in 0..R {
            let w: &[f64; 6] = rows[r][2 * i - 2..2 * i + 4].try_into().expect("6 DOFs");
            for t in 0..6 {
                f[0] += taps[r][t][0] * w[t];
                f[1] += taps[r][t][1] * w[t];
            }
        }
        out[2 * i] = f[0];
        out[2 * i + 1] = f[1];
    }
}

/// Node i (0 or nx) of a row, skipping the neighbours off the grid (their taps are zero).
fn edge_node(taps: &Taps, rows: &[Option<&[f64]>; 3], i: usize, nx: usize) -> [f64; 2] {
    let mut f = [0.0f64; 2];
    for (r, row) in rows.iter().enumerate() {
        let Some(row) = row else { continue };
        for t in 0..6 {
            let n = i + t / 2;
            if n == 0 || n > nx + 1 {
                continue;
            }
            let x = row[2 * (n - 1) + t % 2];
            f[0] += taps[r][t][0] * x;
            f[1] += taps[r][t][1] * x;
        }
    }
    f
}
