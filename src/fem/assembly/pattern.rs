//! The lower-triangular CSC pattern of the reduced matrix and the element colouring, built
//! once per mesh and constraints: by node adjacency when no DOF refers to another node's
//! unknown (the fast path), from each element's unknowns otherwise.

use crate::error::{Error, Result};
use crate::fem::constraints::{Reduction, Target};
use crate::fem::mesh::Mesh;
use crate::linalg::pattern::Pattern;
use rayon::prelude::*;

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
pub(super) fn by_unknowns(mesh: &Mesh, red: &Reduction) -> Result<(Pattern, Vec<Vec<usize>>, Vec<usize>)> {
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
pub(super) fn by_nodes(mesh: &Mesh, red: &Reduction) -> Option<(Pattern, Vec<Vec<usize>>, Vec<usize>)> {
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
