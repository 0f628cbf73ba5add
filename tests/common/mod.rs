//! Set-up shared by the verification tests.

use tribofe::fem::assembly::Model;
use tribofe::fem::constraints::{dof, Constraints};
use tribofe::fem::mesh::Mesh;
use tribofe::fem::problem::{solve, LoadCase};
use tribofe::fem::recovery::gauss_stresses;
use tribofe::linalg::solve::SolverOptions;

/// Boundary nodes of a rectangle mesh (all four named edges).
pub fn boundary(m: &Mesh) -> Vec<usize> {
    m.nodes_of_sets(&["bottom", "right", "top", "left"]).unwrap()
}

/// Patch test (Irons & Razzaque 1972): the linear field u = (a + b x + c y, d + e x + f y),
/// prescribed on the boundary of `model`'s mesh (a rectangle mesh of the unit square), is a
/// constant-strain state every conforming element represents exactly. Asserts that the solve
/// reproduces it at every node and its stress at every Gauss point to 1e-10 relative.
pub fn assert_patch_test(model: &Model, what: &str) {
    let lin = |p: [f64; 2]| [1e-3 + 2e-3 * p[0] - 1e-3 * p[1], -2e-3 + 0.5e-3 * p[0] + 3e-3 * p[1]];
    let (u_scale, eps) = (3e-3, [2e-3, 3e-3, -0.5e-3]);
    let mat = model.material(0);
    let s_exact = mat.d_matrix() * nalgebra::Vector3::from(eps);
    let scale = s_exact.amax();
    let mesh = model.mesh;
    let mut c = Constraints::new(mesh.n_nodes());
    let mut g = Vec::new();
    for n in boundary(mesh) {
        let u = lin(mesh.nodes[n]);
        for k in 0..2 {
            c.fix(dof(n, k));
            g.push(u[k]);
        }
    }
    let sol = solve(model, &c, &[LoadCase { prescribed: g, forces: vec![] }], &SolverOptions::default(), "")
        .unwrap();
    let u = &sol.u[0];
    for n in 0..mesh.n_nodes() {
        let ex = lin(mesh.nodes[n]);
        for k in 0..2 {
            assert!(
                (u[2 * n + k] - ex[k]).abs() < 1e-10 * u_scale,
                "{what} node {n}: {} vs {}",
                u[2 * n + k],
                ex[k]
            );
        }
    }
    for e in 0..mesh.n_elements() {
        for s in gauss_stresses(model, e, u) {
            for k in 0..3 {
                assert!((s[k] - s_exact[k]).abs() < 1e-10 * scale, "{what} element {e} stress {k}: {}", s[k]);
            }
            assert!(
                (s[3] - mat.lambda() * (eps[0] + eps[1])).abs() < 1e-10 * scale,
                "{what} element {e}: sigma_zz"
            );
        }
    }
}
pub mod commands;
pub mod process;
