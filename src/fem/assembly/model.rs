//! What is assembled: mesh, materials per element, QUA4 technology, and the element
//! stiffness dispatch.

use crate::error::{Error, Result};
use crate::fem::element::qua4::{stiffness_bbar, stiffness_im};
use crate::fem::element::stiffness::{stiffness, Technology};
use crate::fem::element::ElementKind;
use crate::fem::material::Material;
use crate::fem::mesh::Mesh;
use nalgebra::Matrix3;

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
    pub(super) fn element_stiffness_with(&self, e: usize, d: &Matrix3<f64>, k: &mut [f64]) -> Result<()> {
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
