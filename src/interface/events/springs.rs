//! Test fixture: a condensed operator small enough to solve by hand. n interface nodes at
//! x_i under a rigid plate, node i tied to it by a tangential spring kt_i and a normal spring
//! kn; the drive acts at height h above the interface. The plate point above node i moves by
//! (U_H + h theta, V + x_i theta), so the elastic energy is
//!   E = sum_i kt_i/2 (u_i - U_H - h theta)^2 + kn/2 (v_i - V - x_i theta)^2
//! and S is its Hessian over (u_0..u_{n-1}, v_0..v_{n-1}, U_H, V, theta): symmetric, positive
//! semi-definite, with the plate's rigid motions as its null space, like a condensed block.

use super::active::Solver;
use super::operator::Dense;
use super::Problem;

/// S of the spring model, row-major.
pub(super) fn operator(x: &[f64], kt: &[f64], kn: f64, h: f64) -> Vec<f64> {
    let n = x.len();
    let nd = 2 * n + 3;
    let (iu, iv, ith) = (2 * n, 2 * n + 1, 2 * n + 2);
    let mut s = vec![0.0; nd * nd];
    let mut spring = |k: f64, g: &[(usize, f64)]| {
        for &(a, ga) in g {
            for &(b, gb) in g {
                s[a * nd + b] += k * ga * gb;
            }
        }
    };
    for i in 0..n {
        spring(kt[i], &[(i, 1.0), (iu, -1.0), (ith, -h)]);
        spring(kn, &[(n + i, 1.0), (iv, -1.0), (ith, -x[i])]);
    }
    s
}

/// A solver on S as `run` starts it: every node stuck at 0, drive phase, the displacement
/// scale |V| under N.
pub(super) fn solver<'a>(s: &'a [f64], n: usize, pb: &Problem) -> Solver<'a> {
    let mut sv = Solver::new(Box::new(Dense::new(s, 2 * n + 3)), n, pb).unwrap();
    let a = sv.solve().unwrap();
    sv.dscale = a.b0[sv.set.iv().expect("the top plate's V")].abs();
    sv
}
