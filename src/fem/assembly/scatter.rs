//! Scattering element matrices into the shared CSC values. The only unsafe code of the
//! assembly: threads write through one raw pointer, disjoint by the element colouring.

use super::Assembler;
use crate::fem::constraints::{Reduction, Target};
use crate::fem::element::stiffness::MAX_NODES;
use crate::fem::mesh::Mesh;

impl Assembler {
    /// Adds the element matrix of an element whose every node has the plain unknowns
    /// ks[a], ks[a] + 1: one pattern search per node pair places its 2x2 block, since rows
    /// k, k + 1 are adjacent in a column and column k + 1 is column k without row k.
    /// Bitwise the same sums as [`Assembler::scatter`] (coefficients 1).
    ///
    /// # Safety
    /// No other thread may write the columns of these unknowns meanwhile.
    pub(super) unsafe fn scatter_plain(&self, ks: &[usize], ke: &[f64], vptr: &SyncPtr) {
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
    pub(super) unsafe fn scatter(
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

/// A raw pointer shared across threads that write disjoint entries.
pub(super) struct SyncPtr(pub(super) *mut f64);
unsafe impl Sync for SyncPtr {}
unsafe impl Send for SyncPtr {}
