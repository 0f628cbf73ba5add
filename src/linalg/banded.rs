//! Banded LU with partial pivoting (the scheme of LAPACK's gbtrf/gbtrs, written for rows):
//! an m x m matrix with kl sub- and ku super-diagonals factors in O(m kl (kl + ku)) and
//! solves in O(m (2 kl + ku)). Row r is stored over the columns r - kl ..= r + kl + ku: the
//! extra kl columns hold the fill that row interchanges bring into U. Used by the event
//! solver's banded operator (`interface::banded`), whose free systems are unsymmetric.

use crate::error::{Error, Result};

/// A banded matrix being assembled, then factored in place.
#[derive(Debug, Clone)]
pub struct Banded {
    pub m: usize,
    pub kl: usize,
    pub ku: usize,
    /// Row-major, `w` = 2 kl + ku + 1 entries a row; entry (r, c) at r w + c + kl - r.
    a: Vec<f64>,
    /// Multipliers of each elimination step, kl a row.
    l: Vec<f64>,
    /// U's rows packed after the factorisation (columns r ..= r + kl + ku, kl + ku + 1 a row):
    /// the solves stream a third fewer bytes than through `a` (they are bandwidth bound).
    u: Vec<f64>,
    /// 1 / U's diagonal.
    dinv: Vec<f64>,
    piv: Vec<usize>,
    factored: bool,
}

impl Banded {
    pub fn zeros(m: usize, kl: usize, ku: usize) -> Banded {
        let w = 2 * kl + ku + 1;
        let span = kl + ku + 1;
        Banded {
            m,
            kl,
            ku,
            a: vec![0.0; m * w],
            l: vec![0.0; m * kl],
            u: vec![0.0; m * span],
            dinv: vec![0.0; m],
            piv: vec![0; m],
            factored: false,
        }
    }

    fn w(&self) -> usize {
        2 * self.kl + self.ku + 1
    }

    /// Clears the values for a new matrix of the same shape (no allocation).
    pub fn clear(&mut self) {
        self.a.iter_mut().for_each(|v| *v = 0.0);
        self.factored = false;
    }

    /// Adds v to entry (r, c); the entry must lie in the band (c - r in -kl ..= ku).
    #[inline]
    pub fn add(&mut self, r: usize, c: usize, v: f64) {
        debug_assert!(c + self.kl >= r && c <= r + self.ku, "({r}, {c}) outside the band");
        let w = self.w();
        self.a[r * w + c + self.kl - r] += v;
    }

    /// Factors in place, P A = L U. Errors on an exactly zero (or non-finite) pivot column;
    /// near-singularity is for the caller's residual check.
    pub fn factor(&mut self) -> Result<()> {
        let (m, kl, w) = (self.m, self.kl, self.w());
        let span = self.kl + self.ku + 1; // columns i ..= i + kl + ku of the pivot row
        for i in 0..m {
            let last = (i + kl).min(m - 1);
            // Pivot: largest |a(p, i)| over p in i ..= last.
            let (mut p, mut big) = (i, 0.0f64);
            for r in i..=last {
                let v = self.a[r * w + i + kl - r].abs();
                if v > big || v.is_nan() {
                    (p, big) = (r, v);
                }
            }
            if !(big > 0.0 && big.is_finite()) {
                return Err(Error::Singular {
                    detail: format!("banded LU: no usable pivot in column {i} of {m}"),
                    node: None,
                    component: None,
                });
            }
            self.piv[i] = p;
            if p != i {
                // Row p's entries (columns i ..= i + kl + ku) into row i's window and back.
                for c in i..(i + span).min(m) {
                    self.a.swap(i * w + c + kl - i, p * w + c + kl - p);
                }
            }
            let d = self.a[i * w + kl];
            let cmax = (i + span).min(m);
            for r in i + 1..=last {
                let q = self.a[r * w + i + kl - r] / d;
                self.l[i * kl + (r - i - 1)] = q;
                if q == 0.0 {
                    continue;
                }
                self.a[r * w + i + kl - r] = 0.0;
                let (top, bot) = self.a.split_at_mut(r * w);
                let src = &top[i * w + kl + 1..i * w + kl + (cmax - i)];
                let off = i + 1 + kl - r;
                let dst = &mut bot[off..off + src.len()];
                for (x, y) in dst.iter_mut().zip(src) {
                    *x -= q * y;
                }
            }
        }
        for (i, u) in self.u.chunks_exact_mut(span).enumerate() {
            u.copy_from_slice(&self.a[i * w + kl..i * w + kl + span]);
            self.dinv[i] = 1.0 / u[0];
        }
        self.factored = true;
        Ok(())
    }

    /// Sign of det A (+1 or -1) from the factor: U's diagonal and the row interchanges.
    pub fn det_sign(&self) -> f64 {
        assert!(self.factored, "det_sign before factor");
        let neg = self.dinv.iter().filter(|&&d| d < 0.0).count()
            + (0..self.m).filter(|&i| self.piv[i] != i).count();
        if neg % 2 == 0 {
            1.0
        } else {
            -1.0
        }
    }

    /// Solves A x = b in place for `k` right-hand sides stored one after another (m each).
    pub fn solve_in_place(&self, b: &mut [f64], k: usize) {
        assert!(self.factored, "solve before factor");
        let (m, kl) = (self.m, self.kl);
        let span = self.kl + self.ku + 1;
        for x in b.chunks_mut(m).take(k) {
            // Steps before the first nonzero entry less kl swap and eliminate zeros only (a
            // unit right-hand side, a column of the inverse, skips that part of L).
            let first = x.iter().position(|&v| v != 0.0).unwrap_or(m);
            for i in first.saturating_sub(kl)..m {
                let p = self.piv[i];
                if p != i {
                    x.swap(i, p);
                }
                let xi = x[i];
                if xi != 0.0 {
                    let last = (i + kl).min(m - 1);
                    let (l, xs) = (&self.l[i * kl..i * kl + (last - i)], &mut x[i + 1..=last]);
                    for (x, &l) in xs.iter_mut().zip(l) {
                        *x -= l * xi;
                    }
                }
            }
            for i in (0..m).rev() {
                let len = span.min(m - i);
                let row = &self.u[i * span..i * span + len];
                // The entries solved last enter the sum last, so that each row waits on the
                // one before it for two products only, not the whole sum (latency bound).
                let mut s = if len > 3 { dot(&row[3..], &x[i + 3..i + len]) } else { 0.0 };
                for c in (1..len.min(3)).rev() {
                    s += row[c] * x[i + c];
                }
                x[i] = (x[i] - s) * self.dinv[i];
            }
        }
    }
}

/// sum a_i b_i over the shorter of the two, in four interleaved partial sums (a single running
/// sum is bound by the latency of its additions: the back substitution's rows, ~20 terms).
#[inline]
pub fn dot(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len().min(b.len());
    let (a, b) = (&a[..n], &b[..n]);
    let mut s = [0.0f64; 4];
    let (ac, bc) = (a.chunks_exact(4), b.chunks_exact(4));
    let (ar, br) = (ac.remainder(), bc.remainder());
    for (x, y) in ac.zip(bc) {
        for k in 0..4 {
            s[k] += x[k] * y[k];
        }
    }
    let mut t = (s[0] + s[2]) + (s[1] + s[3]);
    for (x, y) in ar.iter().zip(br) {
        t += x * y;
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A random banded matrix (deterministic LCG), dense copy alongside.
    fn random(m: usize, kl: usize, ku: usize, seed: u64, weak_diag: bool) -> (Banded, Vec<f64>) {
        let mut s = seed;
        let mut rnd = || {
            s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            ((s >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
        };
        let mut b = Banded::zeros(m, kl, ku);
        let mut d = vec![0.0; m * m];
        for r in 0..m {
            for c in r.saturating_sub(kl)..(r + ku + 1).min(m) {
                // Well conditioned: a dominant diagonal, or (weak_diag) a small diagonal and a
                // dominant first subdiagonal, which forces a row interchange at every step.
                let big = (kl + ku + 2) as f64;
                let v = if weak_diag && r == c && r + 1 < m {
                    1e-3 * rnd()
                } else if (weak_diag && r == c + 1) || (r == c && (!weak_diag || r + 1 == m)) {
                    big + rnd()
                } else {
                    rnd()
                };
                b.add(r, c, v);
                d[r * m + c] = v;
            }
        }
        (b, d)
    }

    fn check(m: usize, kl: usize, ku: usize, weak: bool) {
        let (mut b, d) = random(m, kl, ku, 7 + m as u64 + 31 * kl as u64 + ku as u64, weak);
        b.factor().unwrap();
        // x_true known; rhs = A x_true; two right-hand sides.
        let xt: Vec<f64> = (0..2 * m).map(|i| ((i * 37 % 11) as f64) - 5.0).collect();
        let mut rhs = vec![0.0; 2 * m];
        for k in 0..2 {
            for r in 0..m {
                rhs[k * m + r] = (0..m).map(|c| d[r * m + c] * xt[k * m + c]).sum();
            }
        }
        // Dense LU of the same matrix (faer) as the reference.
        let a = faer::Mat::<f64>::from_fn(m, m, |i, j| d[i * m + j]);
        let lu = a.partial_piv_lu();
        let rb = faer::Mat::<f64>::from_fn(m, 2, |i, k| rhs[k * m + i]);
        let xd = faer::linalg::solvers::Solve::solve(&lu, &rb);
        let b_rhs = rhs.clone();
        b.solve_in_place(&mut rhs, 2);
        let scale = xt.iter().fold(0.0f64, |s, v| s.max(v.abs()));
        let amax = d.iter().fold(0.0f64, |s, v| s.max(v.abs()));
        for k in 0..2 {
            let x = &rhs[k * m..(k + 1) * m];
            let xmax = x.iter().fold(0.0f64, |s, v| s.max(v.abs()));
            for r in 0..m {
                // Backward stability: the residual is round-off of |A| |x|, whatever the
                // conditioning (partial pivoting's growth is small on these bands).
                let res: f64 = (0..m).map(|c| d[r * m + c] * x[c]).sum::<f64>() - b_rhs[k * m + r];
                assert!(
                    res.abs() < 1e-13 * amax * xmax * (kl + ku + 1) as f64,
                    "m {m} kl {kl} ku {ku}: residual {res:e}"
                );
            }
            if !weak {
                // Dominant diagonal: condition ~ 1, so both solutions equal x_true to round-off.
                for i in 0..m {
                    let (x, y) = (x[i], xd[(i, k)]);
                    assert!((x - y).abs() < 1e-12 * scale, "m {m} kl {kl} ku {ku}: x[{i}] {x} vs dense {y}");
                    assert!((x - xt[k * m + i]).abs() < 1e-12 * scale, "x[{i}] {x} vs {}", xt[k * m + i]);
                }
            }
        }
    }

    #[test]
    fn matches_dense_lu() {
        for &(m, kl, ku) in
            &[(1, 0, 0), (5, 1, 1), (20, 2, 3), (40, 5, 1), (60, 0, 4), (30, 7, 7), (12, 11, 11)]
        {
            check(m, kl, ku, false);
            // A weak diagonal needs a subdiagonal to pivot on (upper triangular: ill-conditioned).
            if kl > 0 {
                check(m, kl, ku, true);
            }
        }
    }

    #[test]
    fn dots_match_plain_sums() {
        for n in 0..23 {
            let a: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).sin()).collect();
            let x: Vec<f64> = (0..n).map(|i| (i as f64 * 1.3).cos() - 0.2).collect();
            let y: Vec<f64> = (0..n).map(|i| 1.0 / (i as f64 + 1.5)).collect();
            let plain = |v: &[f64]| a.iter().zip(v).map(|(a, v)| a * v).sum::<f64>();
            let size = |v: &[f64]| a.iter().zip(v).map(|(a, v)| (a * v).abs()).sum::<f64>();
            // Reordered sums of n terms: within n ulps of the sum of magnitudes.
            let tol = |v: &[f64]| (n as f64 + 1.0) * f64::EPSILON * size(v);
            assert!((dot(&a, &x) - plain(&x)).abs() <= tol(&x), "n {n}");
            assert!((dot(&a, &y) - plain(&y)).abs() <= tol(&y), "n {n}");
        }
    }

    #[test]
    fn singular_is_refused() {
        let mut b = Banded::zeros(3, 1, 1);
        b.add(0, 0, 1.0);
        b.add(1, 0, 1.0);
        // Column 1 and 2 all zero.
        assert!(b.factor().is_err());
    }
}
