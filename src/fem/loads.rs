//! External loads as full nodal force vectors (length 2 n_nodes + extra DOFs): point
//! forces, edge tractions on named edge sets, body forces.

use crate::error::Result;
use crate::fem::element::stiffness::{body_force as elem_body, edge_traction as elem_edge, MAX_DOFS};
use crate::fem::mesh::Mesh;

/// Adds the consistent nodal forces of traction `t(x, y)` (Pa) on edge set `name`.
pub fn add_edge_traction(
    mesh: &Mesh,
    name: &str,
    t: &dyn Fn([f64; 2]) -> [f64; 2],
    f: &mut [f64],
) -> Result<()> {
    let mut fe = [0.0; 6];
    for edge in mesh.edges(name)? {
        let nodes: Vec<usize> = edge.nodes().collect();
        let x: Vec<[f64; 2]> = nodes.iter().map(|&n| mesh.nodes[n]).collect();
        elem_edge(&x, t, &mut fe);
        for (a, &n) in nodes.iter().enumerate() {
            f[2 * n] += fe[2 * a];
            f[2 * n + 1] += fe[2 * a + 1];
        }
    }
    Ok(())
}

/// Adds the consistent nodal forces of a body force `b(x, y)` (N/m^3) over all elements.
pub fn add_body_force(mesh: &Mesh, b: &dyn Fn([f64; 2]) -> [f64; 2], f: &mut [f64]) {
    let mut fe = [0.0; MAX_DOFS];
    for e in 0..mesh.n_elements() {
        let x = mesh.element_coords(e);
        elem_body(mesh.kind(e), &x, b, &mut fe);
        for (a, &n) in mesh.element_nodes(e).iter().enumerate() {
            f[2 * n] += fe[2 * a];
            f[2 * n + 1] += fe[2 * a + 1];
        }
    }
}
