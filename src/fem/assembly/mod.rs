//! Assembly of the reduced system T^T K T r = T^T (f - K G g) straight from element
//! matrices: the lower-triangular CSC pattern is built once from the mesh topology, then
//! element matrices are scattered into it in parallel (elements coloured so that no two
//! in one colour share a node unknown). The full matrix is never formed.

mod model;
mod pattern;
mod scatter;

pub use crate::linalg::pattern::Pattern;
pub use model::Model;

use crate::error::{Error, Result};
use crate::fem::constraints::{Reduction, Target};
use crate::fem::element::stiffness::{MAX_DOFS, MAX_NODES};
use crate::fem::mesh::Mesh;
use nalgebra::Matrix3;
use pattern::{by_nodes, by_unknowns};
use rayon::prelude::*;
use scatter::SyncPtr;

/// Pattern and element colouring for one mesh and one set of constraints; reused for any
/// material values and load cases.
#[derive(Debug, Clone)]
pub struct Assembler {
    pub pattern: Pattern,
    colors: Vec<Vec<usize>>,
    /// Elements that found no free colour among 64; assembled on one thread.
    serial: Vec<usize>,
    /// Reduced unknowns from here on are extra DOFs (shared by many elements).
    first_extra: usize,
    /// Per node, its x unknown k when its DOFs are exactly the unknowns k and k + 1 and no
    /// other DOF refers to them; usize::MAX otherwise. Elements of such nodes take the
    /// fast scatter.
    plain: Vec<usize>,
}

impl Assembler {
    pub fn new(mesh: &Mesh, red: &Reduction) -> Result<Self> {
        if red.n_free() == 0 {
            return Err(Error::input("boundary conditions", "every DOF is prescribed: nothing to solve"));
        }
        let fe = red.n_free_nodes;
        let (pattern, colors, serial, fast) = match by_nodes(mesh, red) {
            Some((p, c, s)) => (p, c, s, true),
            None => {
                let (p, c, s) = by_unknowns(mesh, red)?;
                (p, c, s, false)
            }
        };
        let plain = (0..mesh.n_nodes())
            .map(|m| match (red.terms(2 * m), red.terms(2 * m + 1)) {
                (&[(Target::Free(kx), cx)], &[(Target::Free(ky), cy)])
                    if fast && ky == kx + 1 && ky < fe && cx == 1.0 && cy == 1.0 =>
                {
                    kx
                }
                _ => usize::MAX,
            })
            .collect();
        Ok(Self { pattern, colors, serial, first_extra: fe, plain })
    }

    /// Pattern and colouring by the general construction, whatever the reduction (for tests
    /// of the node-level one).
    #[cfg(test)]
    fn new_general(mesh: &Mesh, red: &Reduction) -> Self {
        let (pattern, colors, serial) = by_unknowns(mesh, red).unwrap();
        Self {
            pattern,
            colors,
            serial,
            first_extra: red.n_free_nodes,
            plain: vec![usize::MAX; mesh.n_nodes()],
        }
    }

    /// Number of element colours (parallel passes).
    pub fn n_colors(&self) -> usize {
        self.colors.len() + usize::from(!self.serial.is_empty())
    }

    /// Assembles the reduced matrix values (lower triangle) and the reduced right-hand sides
    /// for each load case: `loads[c]` is the full nodal force vector (may be empty) and
    /// `prescribed[c]` the prescribed values g. Returns (values, rhs column-major n x cases).
    pub fn assemble(
        &self,
        model: &Model,
        red: &Reduction,
        loads: &[Vec<f64>],
        prescribed: &[Vec<f64>],
    ) -> Result<(Vec<f64>, Vec<f64>)> {
        let n = self.pattern.n;
        let nc = prescribed.len();
        if loads.len() != nc || prescribed.iter().any(|g| g.len() != red.n_fixed()) {
            return Err(Error::input(
                "load cases",
                format!("need {} prescribed values and one load vector per case", red.n_fixed()),
            ));
        }
        let mut values = vec![0.0; self.pattern.nnz()];
        crate::memory::advise_huge_pages(&values);
        let mut rhs = vec![0.0; n * nc];
        let nx = n - self.first_extra;
        let (vptr, rptr) = (SyncPtr(values.as_mut_ptr()), SyncPtr(rhs.as_mut_ptr()));
        let d: Vec<Matrix3<f64>> = model.materials.iter().map(|m| m.d_matrix()).collect();
        let mesh = model.mesh;
        // Entries between extra DOFs, and their rhs rows, are summed per chunk of elements.
        let new_extra = || Extra { k: vec![0.0; nx * nx], f: vec![0.0; nx * nc] };
        let run = |elems: &[usize], acc: &mut Extra| -> Result<()> {
            let (mut ke, mut ks) = ([0.0; MAX_DOFS * MAX_DOFS], [0usize; MAX_NODES]);
            for &e in elems {
                model.element_stiffness_with(
                    e,
                    &d[model.element_material.get(e).map_or(0, |&m| m as usize)],
                    &mut ke,
                )?;
                let nodes = mesh.element_nodes(e);
                nodes.iter().zip(&mut ks).for_each(|(&m, k)| *k = self.plain[m]);
                // SAFETY: elements processed concurrently share no node unknown (colouring), so
                // the columns and rhs rows they write are disjoint.
                unsafe {
                    if ks[..nodes.len()].iter().all(|&k| k != usize::MAX) {
                        self.scatter_plain(&ks[..nodes.len()], &ke, &vptr);
                    } else {
                        self.scatter(mesh, red, e, &ke, prescribed, &vptr, &rptr, &mut acc.k, &mut acc.f);
                    }
                }
            }
            Ok(())
        };
        // Extra-DOF sums over fixed chunks merged in order: bitwise the same for any thread count.
        let mut total = new_extra();
        for color in &self.colors {
            let parts = color.par_chunks(EXTRA_CHUNK).map(|c| {
                let mut acc = new_extra();
                run(c, &mut acc).map(|_| acc)
            });
            for b in parts.collect::<Result<Vec<_>>>()? {
                total.k.iter_mut().zip(&b.k).for_each(|(x, y)| *x += y);
                total.f.iter_mut().zip(&b.f).for_each(|(x, y)| *x += y);
            }
        }
        run(&self.serial, &mut total)?;
        for i in 0..nx {
            for j in 0..=i {
                let v = total.k[i * nx + j];
                if v != 0.0 {
                    values[self.pattern.position(self.first_extra + i, self.first_extra + j)] += v;
                }
            }
            for c in 0..nc {
                rhs[c * n + self.first_extra + i] += total.f[i * nc + c];
            }
        }
        for (c, f) in loads.iter().enumerate() {
            if !f.is_empty() {
                red.project_add(f, &mut rhs[c * n..(c + 1) * n]);
            }
        }
        Ok((values, rhs))
    }
}

/// Elements per chunk of the per-chunk extra-DOF accumulators.
const EXTRA_CHUNK: usize = 2048;

struct Extra {
    k: Vec<f64>,
    f: Vec<f64>,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{PlateModel, Scene};

    /// The paper's strip with h = t / ny, interior nodes moved so elements are not rectangles.
    fn strip(ny: usize, element: &str, plate: PlateModel) -> crate::scene::SceneModel {
        let mut s = Scene::default();
        s.mesh.h = s.block.thickness / ny as f64;
        s.mesh.n_thick = Some(ny);
        s.mesh.element = element.into();
        s.plate.model = plate;
        let mut sm = s.build().unwrap();
        let (h, t) = (s.mesh.h, s.block.thickness);
        for (k, p) in sm.mesh.nodes.iter_mut().enumerate() {
            if p[1] > 0.0 && p[1] < t {
                p[0] += 0.1 * h * (((k * 7) % 11) as f64 / 11.0 - 0.5);
                p[1] += 0.1 * h * (((k * 5) % 13) as f64 / 13.0 - 0.5);
            }
        }
        sm
    }

    fn cases() -> Vec<crate::scene::SceneModel> {
        vec![
            strip(4, "qua4", PlateModel::Rigid),
            strip(3, "qua8", PlateModel::Rigid),
            strip(2, "tri6", PlateModel::Rigid),
            strip(3, "qua4-im", PlateModel::Rigid),
            strip(2, "qua4", PlateModel::Elastic),
        ]
    }

    #[test]
    fn node_pattern_and_colouring_match_the_general_ones() {
        for sm in cases() {
            let red = sm.constraints.reduce().unwrap();
            assert!(by_nodes(&sm.mesh, &red).is_some());
            let (a, b) = (Assembler::new(&sm.mesh, &red).unwrap(), Assembler::new_general(&sm.mesh, &red));
            assert_eq!((&a.pattern.col_ptr, &a.pattern.row_idx), (&b.pattern.col_ptr, &b.pattern.row_idx));
            assert_eq!((&a.colors, &a.serial), (&b.colors, &b.serial));
            assert!(a.plain.iter().any(|&k| k != usize::MAX));
        }
    }

    #[test]
    fn ties_between_nodes_take_the_general_construction() {
        let sm = strip(2, "qua4", PlateModel::Rigid);
        let mut c = sm.constraints.clone();
        // An interior node's u follows its right neighbour's (row 1 of the 400 x 2 grid).
        c.tie(crate::fem::constraints::dof(406, 0), &[(crate::fem::constraints::dof(407, 0), 0.5)]);
        let red = c.reduce().unwrap();
        assert!(by_nodes(&sm.mesh, &red).is_none());
        let a = Assembler::new(&sm.mesh, &red).unwrap();
        assert!(a.plain.iter().all(|&k| k == usize::MAX));
    }

    #[test]
    fn fast_scatter_is_bitwise_the_general_one_and_matches_a_matrix_free_product() {
        for sm in cases() {
            let model = sm.model();
            let red = sm.constraints.reduce().unwrap();
            let g: Vec<Vec<f64>> = (0..2)
                .map(|c| (0..red.n_fixed()).map(|j| ((j * 7 + c * 3) % 5) as f64 - 2.0).collect())
                .collect();
            let f: Vec<Vec<f64>> = vec![(0..red.n_full).map(|d| (d % 7) as f64).collect(), vec![]];
            let (a, b) = (Assembler::new(&sm.mesh, &red).unwrap(), Assembler::new_general(&sm.mesh, &red));
            let (va, ra) = a.assemble(&model, &red, &f, &g).unwrap();
            let (vb, rb) = b.assemble(&model, &red, &f, &g).unwrap();
            assert!(va.iter().zip(&vb).all(|(x, y)| x.to_bits() == y.to_bits()), "matrix values differ");
            assert!(ra.iter().zip(&rb).all(|(x, y)| x.to_bits() == y.to_bits()), "right-hand sides differ");
            // K x from the stored lower triangle against T^T (sum_e K_e (T x)_e).
            let p = &a.pattern;
            let x: Vec<f64> = (0..p.n).map(|i| ((i * 13) % 17) as f64 / 17.0 - 0.4).collect();
            let mut kx = vec![0.0; p.n];
            for j in 0..p.n {
                for k in p.col(j) {
                    let i = p.row_idx[k] as usize;
                    kx[i] += va[k] * x[j];
                    if i != j {
                        kx[j] += va[k] * x[i];
                    }
                }
            }
            let u = red.expand(&x, &vec![0.0; red.n_fixed()]);
            let all: Vec<usize> = (0..sm.mesh.n_elements()).collect();
            let mut fu = crate::fem::recovery::internal_forces(&model, &u, &all).unwrap();
            fu.resize(red.n_full, 0.0);
            let mut want = vec![0.0; p.n];
            red.project_add(&fu, &mut want);
            let scale = want.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let err = kx.iter().zip(&want).fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
            assert!(err <= 1e-12 * scale, "K x off by {:.2e} relative", err / scale);
        }
    }
}
