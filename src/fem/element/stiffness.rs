//! Element kernels: shape functions mapped to physical coordinates, the stiffness
//! integral K_e = int B^T D B dA, consistent body-force and edge-traction loads, and the
//! strain at a point. Kernels fill caller buffers and never touch global data.

use super::quadrature::{gauss_1d, gauss_quad, gauss_tri, QPoint};
use super::{shape, ElementKind};
use nalgebra::Matrix3;
use std::sync::LazyLock;

/// Largest element (QUA9): 9 nodes, 18 DOFs.
pub const MAX_NODES: usize = 9;
pub const MAX_DOFS: usize = 2 * MAX_NODES;

/// How a QUA4 element integrates its stiffness; other kinds are always `Full`. Chosen by
/// name with [`ElementChoice`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Technology {
    /// Full Gauss integration: 2x2 on QUA4, 3x3 on QUA8/QUA9, 1 point on TRI3, 3 on TRI6.
    #[default]
    Full,
    /// Mean-dilatation B-bar (`qua4-sri`), see [`super::qua4::stiffness_bbar`].
    SelectiveReduced,
    /// Incompatible modes QM6 (`qua4-im`), see [`super::qua4::stiffness_im`].
    IncompatibleModes,
}

impl Technology {
    pub const ALL: [Technology; 3] = [Self::Full, Self::SelectiveReduced, Self::IncompatibleModes];

    /// Name suffix after the kind (`qua4-sri`).
    pub const fn suffix(self) -> &'static str {
        match self {
            Self::Full => "",
            Self::SelectiveReduced => "-sri",
            Self::IncompatibleModes => "-im",
        }
    }
}

/// An element formulation as users name it, see [`ElementChoice::NAMES`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ElementChoice {
    pub kind: ElementKind,
    pub tech: Technology,
}

impl ElementChoice {
    pub const NAMES: [&'static str; 7] = ["qua4", "qua4-sri", "qua4-im", "qua8", "qua9", "tri3", "tri6"];

    pub fn name(&self) -> String {
        format!("{}{}", self.kind.name(), self.tech.suffix())
    }
}

impl std::str::FromStr for ElementChoice {
    type Err = crate::Error;
    fn from_str(s: &str) -> crate::Result<Self> {
        let lower = s.to_ascii_lowercase();
        let (kind_name, suffix) = lower.split_at(lower.find('-').unwrap_or(lower.len()));
        let unknown = || {
            crate::Error::input(
                "element",
                format!("'{s}' is not known; choose one of {}", Self::NAMES.join(", ")),
            )
        };
        let kind = ElementKind::ALL.into_iter().find(|k| k.name() == kind_name).ok_or_else(unknown)?;
        let tech = Technology::ALL.into_iter().find(|t| t.suffix() == suffix).ok_or_else(unknown)?;
        if tech != Technology::Full && kind != ElementKind::Qua4 {
            return Err(crate::Error::input(
                "element",
                format!(
                    "'{s}': '{}' is only available for qua4 (try qua4{suffix}, or {} with full integration)",
                    &suffix[1..],
                    kind.name()
                ),
            ));
        }
        Ok(Self { kind, tech })
    }
}

/// Quadrature rule used for the stiffness of a kind (full integration), built once.
pub fn stiffness_rule(kind: ElementKind) -> &'static [QPoint] {
    static RULES: LazyLock<[Vec<QPoint>; 4]> =
        LazyLock::new(|| [gauss_quad(2), gauss_quad(3), gauss_tri(1), gauss_tri(2)]);
    &RULES[match kind {
        ElementKind::Qua4 => 0,
        ElementKind::Qua8 | ElementKind::Qua9 => 1,
        ElementKind::Tri3 => 2,
        ElementKind::Tri6 => 3,
    }]
}

/// A rule exact enough for error norms and body forces on each kind, built once.
pub fn accurate_rule(kind: ElementKind) -> &'static [QPoint] {
    static RULES: LazyLock<[Vec<QPoint>; 2]> = LazyLock::new(|| [gauss_quad(4), gauss_tri(4)]);
    &RULES[usize::from(!kind.is_quad())]
}

/// Shape functions at one point, mapped to physical space.
#[derive(Debug, Clone, Copy)]
pub struct MappedPoint {
    pub n: [f64; MAX_NODES],
    /// dN_a/dx, dN_a/dy.
    pub dndx: [[f64; 2]; MAX_NODES],
    pub det_j: f64,
    /// Physical coordinates of the point.
    pub x: [f64; 2],
}

/// Maps the shape functions at reference point `xi`; `det_j <= 0` flags a bad element.
pub fn map_point(kind: ElementKind, coords: &[[f64; 2]], xi: [f64; 2]) -> MappedPoint {
    let nn = kind.n_nodes();
    let mut n = [0.0; MAX_NODES];
    let mut dn = [[0.0; 2]; MAX_NODES];
    shape::eval(kind, xi, &mut n[..nn], &mut dn[..nn]);
    let mut x = [0.0; 2];
    for a in 0..nn {
        for r in 0..2 {
            x[r] += n[a] * coords[a][r];
        }
    }
    let mut dndx = [[0.0; 2]; MAX_NODES];
    let det_j = physical_derivatives(&coords[..nn], &dn[..nn], &mut dndx[..nn]);
    MappedPoint { n, dndx, det_j, x }
}

/// dN/dx from the reference derivatives `dn` at one point of the element with nodes
/// `coords`; returns det J. Shared by [`map_point`] and the stiffness kernel, which must agree
/// bitwise.
#[inline(always)]
#[allow(clippy::needless_range_loop)] // unrolled when the node count is a constant
fn physical_derivatives(coords: &[[f64; 2]], dn: &[[f64; 2]], dndx: &mut [[f64; 2]]) -> f64 {
    let mut j = [[0.0; 2]; 2];
    for a in 0..coords.len() {
        for r in 0..2 {
            for c in 0..2 {
                j[r][c] += coords[a][r] * dn[a][c];
            }
        }
    }
    let det_j = j[0][0] * j[1][1] - j[0][1] * j[1][0];
    let inv = [[j[1][1] / det_j, -j[0][1] / det_j], [-j[1][0] / det_j, j[0][0] / det_j]];
    for (d, g) in dndx.iter_mut().zip(dn) {
        // dN/dx_c = sum_k dN/dxi_k dxi_k/dx_c, with dxi/dx = J^-1
        for c in 0..2 {
            d[c] = g[0] * inv[0][c] + g[1] * inv[1][c];
        }
    }
    det_j
}

/// Full-integration stiffness into `k` (row-major, DOF order u0, v0, u1, v1, ...).
/// Returns the smallest Jacobian determinant met, so callers can reject bad elements.
pub fn stiffness(kind: ElementKind, coords: &[[f64; 2]], d: &Matrix3<f64>, k: &mut [f64]) -> f64 {
    // A fixed node count lets the compiler unroll: 3x faster on QUA4, same arithmetic.
    match kind {
        ElementKind::Tri3 => stiffness_n::<3>(kind, coords, d, k),
        ElementKind::Tri6 => stiffness_n::<6>(kind, coords, d, k),
        ElementKind::Qua4 => stiffness_n::<4>(kind, coords, d, k),
        ElementKind::Qua8 => stiffness_n::<8>(kind, coords, d, k),
        ElementKind::Qua9 => stiffness_n::<9>(kind, coords, d, k),
    }
}

/// Weight and reference shape derivatives at each point of a kind's stiffness rule, built
/// once (they do not depend on the element).
fn stiffness_table(kind: ElementKind) -> &'static [(f64, [[f64; 2]; MAX_NODES])] {
    type Table = Vec<(f64, [[f64; 2]; MAX_NODES])>;
    static TABLES: LazyLock<Vec<Table>> = LazyLock::new(|| {
        ElementKind::ALL
            .iter()
            .map(|&kind| {
                let nn = kind.n_nodes();
                stiffness_rule(kind)
                    .iter()
                    .map(|q| {
                        let (mut n, mut dn) = ([0.0; MAX_NODES], [[0.0; 2]; MAX_NODES]);
                        shape::eval(kind, q.xi, &mut n[..nn], &mut dn[..nn]);
                        (q.w, dn)
                    })
                    .collect()
            })
            .collect()
    });
    &TABLES[ElementKind::ALL.iter().position(|&k| k == kind).expect("listed kind")]
}

/// [`stiffness`] for `NN`-node kinds; the same operations in the same order as
/// [`map_point`] followed by the B^T D B sum, so results are bitwise those of the generic form.
#[inline(always)]
fn stiffness_n<const NN: usize>(
    kind: ElementKind,
    coords: &[[f64; 2]],
    d: &Matrix3<f64>,
    k: &mut [f64],
) -> f64 {
    let x: &[[f64; 2]; NN] = coords[..NN].try_into().expect("one coordinate pair per node");
    let nd = 2 * NN;
    let k = &mut k[..nd * nd];
    k.fill(0.0);
    let mut min_det = f64::INFINITY;
    for (qw, dn) in stiffness_table(kind) {
        let mut dndx = [[0.0; 2]; NN];
        let det_j = physical_derivatives(x, &dn[..NN], &mut dndx);
        min_det = min_det.min(det_j);
        add_btdb(k, &dndx, qw * det_j, d);
    }
    min_det
}

/// k += w B^T D B at one integration point, B from the shape derivatives `dndx`. D has no
/// normal-shear coupling (isotropic material), so only its four non-zero entries are used.
#[inline(always)]
fn add_btdb(k: &mut [f64], dndx: &[[f64; 2]], w: f64, d: &Matrix3<f64>) {
    let nd = 2 * dndx.len();
    let (d11, d12, d22, d33) = (d[(0, 0)], d[(0, 1)], d[(1, 1)], d[(2, 2)]);
    for (a, &[ax, ay]) in dndx.iter().enumerate() {
        for (b, &[bx, by]) in dndx.iter().enumerate() {
            let r0 = 2 * a * nd + 2 * b;
            let r1 = r0 + nd;
            k[r0] += w * (ax * d11 * bx + ay * d33 * by);
            k[r0 + 1] += w * (ax * d12 * by + ay * d33 * bx);
            k[r1] += w * (ay * d12 * bx + ax * d33 * by);
            k[r1 + 1] += w * (ay * d22 * by + ax * d33 * bx);
        }
    }
}

/// The generic form [`stiffness`] specialises, kept to check it against.
#[cfg(test)]
fn stiffness_generic(kind: ElementKind, coords: &[[f64; 2]], d: &Matrix3<f64>, k: &mut [f64]) -> f64 {
    let nn = kind.n_nodes();
    let nd = 2 * nn;
    k[..nd * nd].iter_mut().for_each(|v| *v = 0.0);
    let mut min_det = f64::INFINITY;
    for q in stiffness_rule(kind) {
        let p = map_point(kind, coords, q.xi);
        min_det = min_det.min(p.det_j);
        add_btdb(k, &p.dndx[..nn], q.w * p.det_j, d);
    }
    min_det
}

/// Strain (eps_xx, eps_yy, gamma_xy) at a mapped point from element nodal displacements.
pub fn strain(p: &MappedPoint, nn: usize, u: &[f64]) -> [f64; 3] {
    let mut e = [0.0; 3];
    for a in 0..nn {
        let [dx, dy] = p.dndx[a];
        let (ua, va) = (u[2 * a], u[2 * a + 1]);
        e[0] += dx * ua;
        e[1] += dy * va;
        e[2] += dy * ua + dx * va;
    }
    e
}

/// Consistent nodal forces of a body force b(x, y) (N/m^3) into `f` (length 2 n_nodes).
pub fn body_force(kind: ElementKind, coords: &[[f64; 2]], b: &dyn Fn([f64; 2]) -> [f64; 2], f: &mut [f64]) {
    let nn = kind.n_nodes();
    f[..2 * nn].iter_mut().for_each(|v| *v = 0.0);
    for q in accurate_rule(kind) {
        let p = map_point(kind, coords, q.xi);
        let bx = b(p.x);
        let w = q.w * p.det_j;
        for a in 0..nn {
            f[2 * a] += w * p.n[a] * bx[0];
            f[2 * a + 1] += w * p.n[a] * bx[1];
        }
    }
}

/// Consistent nodal forces of a traction t(x, y) (Pa) on a straight or curved edge with
/// nodes [start, end] or [start, end, mid]; `f` gets 2 entries per edge node in that order.
pub fn edge_traction(coords: &[[f64; 2]], t: &dyn Fn([f64; 2]) -> [f64; 2], f: &mut [f64]) {
    let nn = coords.len();
    f[..2 * nn].iter_mut().for_each(|v| *v = 0.0);
    for &(s, w) in gauss_1d(4) {
        // 1D Lagrange shapes on [-1, 1] with nodes at -1, 1 (and 0 for the mid node).
        let (n, dn): (Vec<f64>, Vec<f64>) = if nn == 2 {
            (vec![0.5 * (1.0 - s), 0.5 * (1.0 + s)], vec![-0.5, 0.5])
        } else {
            (vec![0.5 * s * (s - 1.0), 0.5 * s * (s + 1.0), 1.0 - s * s], vec![s - 0.5, s + 0.5, -2.0 * s])
        };
        let (mut x, mut dx) = ([0.0; 2], [0.0; 2]);
        for a in 0..nn {
            for c in 0..2 {
                x[c] += n[a] * coords[a][c];
                dx[c] += dn[a] * coords[a][c];
            }
        }
        let jac = (dx[0] * dx[0] + dx[1] * dx[1]).sqrt();
        let tv = t(x);
        for a in 0..nn {
            f[2 * a] += w * jac * n[a] * tv[0];
            f[2 * a + 1] += w * jac * n[a] * tv[1];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::material::Material;

    fn distorted(kind: ElementKind) -> Vec<[f64; 2]> {
        // Map the reference nodes through a smooth, invertible affine-plus-bilinear map.
        kind.reference_nodes()
            .iter()
            .map(|&[a, b]| [1.0 + 0.9 * a + 0.2 * b + 0.05 * a * b, 0.5 + 0.1 * a + 0.7 * b])
            .collect()
    }

    #[test]
    fn symmetric_with_three_rigid_modes() {
        let d = Material::plane_strain(210e9, 0.3).unwrap().d_matrix();
        for kind in ElementKind::ALL {
            let x = distorted(kind);
            let nd = 2 * kind.n_nodes();
            let mut k = vec![0.0; nd * nd];
            assert!(stiffness(kind, &x, &d, &mut k) > 0.0);
            let scale = k.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            for i in 0..nd {
                for j in 0..nd {
                    assert!((k[i * nd + j] - k[j * nd + i]).abs() <= 1e-13 * scale, "{kind:?} not symmetric");
                }
            }
            // Translations and the infinitesimal rotation store no energy: K r = 0.
            type Mode = Box<dyn Fn([f64; 2]) -> [f64; 2]>;
            let modes: [Mode; 3] =
                [Box::new(|_| [1.0, 0.0]), Box::new(|_| [0.0, 1.0]), Box::new(|p| [-p[1], p[0]])];
            for m in &modes {
                let r: Vec<f64> = x.iter().flat_map(|&p| m(p)).collect();
                for i in 0..nd {
                    let ki: f64 = (0..nd).map(|j| k[i * nd + j] * r[j]).sum();
                    assert!(ki.abs() <= 1e-12 * scale, "{kind:?} rigid mode has force {ki}");
                }
            }
        }
    }

    #[test]
    fn specialised_stiffness_is_bitwise_the_generic_one() {
        let d = Material::plane_strain(210e9, 0.3).unwrap().d_matrix();
        for kind in ElementKind::ALL {
            let x = distorted(kind);
            let nd = 2 * kind.n_nodes();
            let (mut a, mut b) = (vec![1.0; nd * nd], vec![2.0; nd * nd]);
            let (da, db) = (stiffness(kind, &x, &d, &mut a), stiffness_generic(kind, &x, &d, &mut b));
            assert_eq!(da.to_bits(), db.to_bits(), "{kind:?}");
            assert!(a.iter().zip(&b).all(|(p, q)| p.to_bits() == q.to_bits()), "{kind:?}");
        }
    }

    #[test]
    fn edge_traction_integrates_exactly() {
        // Uniform traction on a straight edge of length 5: total force = 5 t, split 1/6-1/6-2/3 for line3.
        let mut f = [0.0; 6];
        edge_traction(&[[0.0, 0.0], [3.0, 4.0], [1.5, 2.0]], &|_| [2.0, -1.0], &mut f);
        assert!((f[0] - 10.0 / 6.0).abs() < 1e-13 && (f[4] - 40.0 / 6.0).abs() < 1e-13);
        assert!((f[1] + f[3] + f[5] + 5.0).abs() < 1e-13);
    }
}
