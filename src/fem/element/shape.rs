//! Shape functions N_i and their reference derivatives dN_i/dxi, dN_i/deta.
//! Quads live on [-1, 1]^2 (QUA8 is serendipity, QUA9 Lagrange); triangles on the unit
//! triangle with area coordinates L0 = 1 - r - s, L1 = r, L2 = s.

use super::ElementKind;

/// Fills `n[i]` and `dn[i] = [dN_i/dxi, dN_i/deta]` for the kind's nodes at `xi`.
pub fn eval(kind: ElementKind, xi: [f64; 2], n: &mut [f64], dn: &mut [[f64; 2]]) {
    let [x, y] = xi;
    match kind {
        ElementKind::Qua4 => {
            for (i, &[a, b]) in kind.reference_nodes().iter().enumerate() {
                n[i] = 0.25 * (1.0 + a * x) * (1.0 + b * y);
                dn[i] = [0.25 * a * (1.0 + b * y), 0.25 * b * (1.0 + a * x)];
            }
        }
        ElementKind::Qua8 => {
            for (i, &[a, b]) in kind.reference_nodes().iter().enumerate() {
                if i < 4 {
                    n[i] = 0.25 * (1.0 + a * x) * (1.0 + b * y) * (a * x + b * y - 1.0);
                    dn[i] = [
                        0.25 * a * (1.0 + b * y) * (2.0 * a * x + b * y),
                        0.25 * b * (1.0 + a * x) * (a * x + 2.0 * b * y),
                    ];
                } else if a == 0.0 {
                    n[i] = 0.5 * (1.0 - x * x) * (1.0 + b * y);
                    dn[i] = [-x * (1.0 + b * y), 0.5 * b * (1.0 - x * x)];
                } else {
                    n[i] = 0.5 * (1.0 + a * x) * (1.0 - y * y);
                    dn[i] = [0.5 * a * (1.0 - y * y), -y * (1.0 + a * x)];
                }
            }
        }
        ElementKind::Qua9 => {
            // Tensor product of 1D quadratic Lagrange polynomials at -1, 0, 1.
            let l = |t: f64, a: f64| -> (f64, f64) {
                if a < 0.0 {
                    (0.5 * t * (t - 1.0), t - 0.5)
                } else if a > 0.0 {
                    (0.5 * t * (t + 1.0), t + 0.5)
                } else {
                    (1.0 - t * t, -2.0 * t)
                }
            };
            for (i, &[a, b]) in kind.reference_nodes().iter().enumerate() {
                let ((lx, dlx), (ly, dly)) = (l(x, a), l(y, b));
                n[i] = lx * ly;
                dn[i] = [dlx * ly, lx * dly];
            }
        }
        ElementKind::Tri3 => {
            n[0] = 1.0 - x - y;
            n[1] = x;
            n[2] = y;
            dn[0] = [-1.0, -1.0];
            dn[1] = [1.0, 0.0];
            dn[2] = [0.0, 1.0];
        }
        ElementKind::Tri6 => {
            let l0 = 1.0 - x - y;
            n[0] = l0 * (2.0 * l0 - 1.0);
            n[1] = x * (2.0 * x - 1.0);
            n[2] = y * (2.0 * y - 1.0);
            n[3] = 4.0 * l0 * x;
            n[4] = 4.0 * x * y;
            n[5] = 4.0 * y * l0;
            dn[0] = [1.0 - 4.0 * l0, 1.0 - 4.0 * l0];
            dn[1] = [4.0 * x - 1.0, 0.0];
            dn[2] = [0.0, 4.0 * y - 1.0];
            dn[3] = [4.0 * (l0 - x), -4.0 * x];
            dn[4] = [4.0 * y, 4.0 * x];
            dn[5] = [-4.0 * y, 4.0 * (l0 - y)];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kronecker_partition_and_derivatives() {
        for kind in ElementKind::ALL {
            let nn = kind.n_nodes();
            let (mut n, mut dn) = (vec![0.0; nn], vec![[0.0; 2]; nn]);
            for (j, &p) in kind.reference_nodes().iter().enumerate() {
                eval(kind, p, &mut n, &mut dn);
                for i in 0..nn {
                    let want = if i == j { 1.0 } else { 0.0 };
                    assert!((n[i] - want).abs() < 1e-14, "{kind:?} N{i} at node {j}");
                }
            }
            // Partition of unity and finite-difference derivative check at an interior point.
            let p = [0.21, 0.13];
            eval(kind, p, &mut n, &mut dn);
            assert!((n.iter().sum::<f64>() - 1.0).abs() < 1e-14);
            let h = 1e-6;
            let (mut np, mut nm, mut d) = (vec![0.0; nn], vec![0.0; nn], vec![[0.0; 2]; nn]);
            for k in 0..2 {
                let (mut a, mut b) = (p, p);
                a[k] += h;
                b[k] -= h;
                eval(kind, a, &mut np, &mut d);
                eval(kind, b, &mut nm, &mut d);
                for i in 0..nn {
                    assert!(((np[i] - nm[i]) / (2.0 * h) - dn[i][k]).abs() < 1e-8, "{kind:?} dN{i}/dxi{k}");
                }
            }
        }
    }
}
