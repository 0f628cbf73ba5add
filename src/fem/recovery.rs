//! Post-processing of a displacement field: strains and stresses at integration points
//! (with sigma_zz of plane strain), nodal stresses extrapolated from the integration points
//! and averaged between elements, internal forces K u for consistent reactions, and
//! error norms against exact fields.

use crate::fem::assembly::Model;
use crate::fem::element::qua4::StrainCorrection;
use crate::fem::element::stiffness::{accurate_rule, map_point, stiffness_rule, strain, MAX_DOFS, MAX_NODES};
use crate::fem::element::ElementKind;
use nalgebra::DMatrix;
use rayon::prelude::*;
use std::sync::OnceLock;

/// Stress components (sigma_xx, sigma_yy, sigma_xy, sigma_zz), Pa.
pub type Stress = [f64; 4];

/// Von Mises equivalent stress of a plane-strain state, Pa.
pub fn von_mises(s: &Stress) -> f64 {
    let [xx, yy, xy, zz] = *s;
    (0.5 * ((xx - yy).powi(2) + (yy - zz).powi(2) + (zz - xx).powi(2)) + 3.0 * xy * xy).sqrt()
}

fn element_dofs(model: &Model, e: usize, u: &[f64]) -> ([[f64; 2]; MAX_NODES], [f64; MAX_DOFS]) {
    let nodes = model.mesh.element_nodes(e);
    let (mut x, mut ue) = ([[0.0; 2]; MAX_NODES], [0.0; MAX_DOFS]);
    for (a, &n) in nodes.iter().enumerate() {
        x[a] = model.mesh.nodes[n];
        ue[2 * a] = u[2 * n];
        ue[2 * a + 1] = u[2 * n + 1];
    }
    (x, ue)
}

/// Stresses at the stiffness integration points of element `e` (in rule order), from the
/// strains the element itself uses (B-bar strains for SRI, modes included for IM).
pub fn gauss_stresses(model: &Model, e: usize, u: &[f64]) -> Vec<Stress> {
    let kind = model.mesh.kind(e);
    let nn = kind.n_nodes();
    let (x, ue) = element_dofs(model, e, u);
    let mat = model.material(e);
    let d = mat.d_matrix();
    let corr = StrainCorrection::new(model.technology(e), &x[..nn], &d, &ue);
    stiffness_rule(kind)
        .iter()
        .map(|q| {
            let p = map_point(kind, &x[..nn], q.xi);
            let eps = corr.apply(&p, q.xi, strain(&p, nn, &ue));
            let s = d * nalgebra::Vector3::from(eps);
            [s[0], s[1], s[2], mat.sigma_zz(eps[0], eps[1])]
        })
        .collect()
}

/// Matrix E (nodes x integration points): nodal value = E * point values, from the
/// polynomial that interpolates the integration points (bilinear for 2x2, biquadratic for
/// 3x3, linear for 3-point triangles, constant for 1 point).
pub fn extrapolation_matrix(kind: ElementKind) -> &'static DMatrix<f64> {
    static CACHE: [OnceLock<DMatrix<f64>>; 5] =
        [OnceLock::new(), OnceLock::new(), OnceLock::new(), OnceLock::new(), OnceLock::new()];
    let i = ElementKind::ALL.iter().position(|&k| k == kind).unwrap();
    CACHE[i].get_or_init(|| {
        let pts = stiffness_rule(kind);
        let basis = |p: [f64; 2]| -> Vec<f64> {
            let [x, y] = p;
            match pts.len() {
                1 => vec![1.0],
                3 => vec![1.0, x, y],
                4 => vec![1.0, x, y, x * y],
                9 => (0..3).flat_map(|i| (0..3).map(move |j| x.powi(i) * y.powi(j))).collect(),
                n => unreachable!("{n}-point rule"),
            }
        };
        let m = pts.len();
        let a = DMatrix::from_fn(m, m, |q, k| basis(pts[q].xi)[k]);
        let a_inv = a.try_inverse().expect("integration points are unisolvent");
        let nodes = kind.reference_nodes();
        let p = DMatrix::from_fn(nodes.len(), m, |n, k| basis(nodes[n])[k]);
        p * a_inv
    })
}

/// Nodal stresses: integration-point stresses extrapolated to each element's nodes, then
/// averaged over the elements sharing the node.
pub fn nodal_stresses(model: &Model, u: &[f64]) -> Vec<Stress> {
    let all: Vec<usize> = (0..model.mesh.n_elements()).collect();
    nodal_stresses_from(model, u, &all)
}

/// [`nodal_stresses`] from the given elements only: exact at nodes all of whose elements are
/// given (e.g. the interface nodes and [`elements_touching`] them), zero at nodes none touches.
pub fn nodal_stresses_from(model: &Model, u: &[f64], elements: &[usize]) -> Vec<Stress> {
    let mesh = model.mesh;
    let per_elem: Vec<Vec<Stress>> = elements
        .par_iter()
        .map(|&e| {
            let g = gauss_stresses(model, e, u);
            let ex = extrapolation_matrix(mesh.kind(e));
            (0..ex.nrows())
                .map(|a| {
                    let mut s = [0.0; 4];
                    for (q, gq) in g.iter().enumerate() {
                        for c in 0..4 {
                            s[c] += ex[(a, q)] * gq[c];
                        }
                    }
                    s
                })
                .collect()
        })
        .collect();
    let mut sum = vec![[0.0; 4]; mesh.n_nodes()];
    let mut count = vec![0u32; mesh.n_nodes()];
    for (&e, vals) in elements.iter().zip(&per_elem) {
        for (&n, s) in mesh.element_nodes(e).iter().zip(vals) {
            for c in 0..4 {
                sum[n][c] += s[c];
            }
            count[n] += 1;
        }
    }
    // Averaged in place: a new array would be 16 MB more fresh memory per call at 1e6 DOFs.
    sum.iter_mut().zip(&count).filter(|(_, &c)| c > 0).for_each(|(s, &c)| *s = s.map(|v| v / c as f64));
    sum
}

/// Internal forces K u (length 2 n_nodes) from the given elements only: the consistent
/// reaction at a constrained DOF is (K u - f) there, and only elements touching it matter.
pub fn internal_forces(model: &Model, u: &[f64], elements: &[usize]) -> crate::Result<Vec<f64>> {
    let mut out = vec![0.0; 2 * model.mesh.n_nodes()];
    let mut ke = [0.0; MAX_DOFS * MAX_DOFS];
    for &e in elements {
        model.element_stiffness(e, &mut ke)?;
        let (_, ue) = element_dofs(model, e, u);
        let nodes = model.mesh.element_nodes(e);
        let nd = 2 * nodes.len();
        for a in 0..nd {
            let fa: f64 = (0..nd).map(|b| ke[a * nd + b] * ue[b]).sum();
            out[2 * nodes[a / 2] + a % 2] += fa;
        }
    }
    Ok(out)
}

/// Elements having at least one node in `nodes`.
pub fn elements_touching(model: &Model, nodes: &[usize]) -> Vec<usize> {
    let mut mark = vec![false; model.mesh.n_nodes()];
    nodes.iter().for_each(|&n| mark[n] = true);
    (0..model.mesh.n_elements()).filter(|&e| model.mesh.element_nodes(e).iter().any(|&n| mark[n])).collect()
}

/// L2 norm of (u_h - u) and energy norm of the error, sqrt(int (eps_h - eps)^T D (eps_h - eps)),
/// with an accurate quadrature; `exact` returns (u, eps) at a point. eps_h is the strain the
/// element uses (B-bar, or with the incompatible modes); u_h is the compatible nodal
/// interpolation only (for IM the modes are element-internal, not part of the field).
pub fn error_norms(
    model: &Model,
    u: &[f64],
    exact: &(dyn Fn([f64; 2]) -> ([f64; 2], [f64; 3]) + Sync),
) -> (f64, f64) {
    let mesh = model.mesh;
    let (l2, en) = (0..mesh.n_elements())
        .into_par_iter()
        .map(|e| {
            let kind = mesh.kind(e);
            let nn = kind.n_nodes();
            let (x, ue) = element_dofs(model, e, u);
            let d = model.material(e).d_matrix();
            let corr = StrainCorrection::new(model.technology(e), &x[..nn], &d, &ue);
            let (mut l2, mut en) = (0.0, 0.0);
            for q in accurate_rule(kind) {
                let p = map_point(kind, &x[..nn], q.xi);
                let (uex, eex) = exact(p.x);
                let uh: [f64; 2] = std::array::from_fn(|c| (0..nn).map(|a| p.n[a] * ue[2 * a + c]).sum());
                let eh = corr.apply(&p, q.xi, strain(&p, nn, &ue));
                let de = nalgebra::Vector3::new(eh[0] - eex[0], eh[1] - eex[1], eh[2] - eex[2]);
                let w = q.w * p.det_j;
                l2 += w * ((uh[0] - uex[0]).powi(2) + (uh[1] - uex[1]).powi(2));
                en += w * de.dot(&(d * de));
            }
            (l2, en)
        })
        .reduce(|| (0.0, 0.0), |a, b| (a.0 + b.0, a.1 + b.1));
    (l2.sqrt(), en.sqrt())
}
