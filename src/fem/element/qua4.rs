//! QUA4 technologies beyond full 2x2 integration: mean-dilatation B-bar and incompatible
//! modes (QM6). Both integrate at the 2x2 Gauss points, pass the patch test on any convex
//! quadrilateral, and keep exactly three zero-energy modes.
//!
//! Strain columns: `col[j]` is the strain (eps_xx, eps_yy, gamma_xy) of unit DOF j, DOF
//! order u0, v0, u1, v1, ... as in [`super::stiffness::stiffness`].

use super::stiffness::{map_point, stiffness_rule, MappedPoint, Technology};
use super::ElementKind;
use nalgebra::{Matrix3, Matrix4, SMatrix, Vector3, Vector4};

const NN: usize = 4;
const ND: usize = 8;
type Cols<const N: usize> = [[f64; 3]; N];

/// The 2x2 points mapped, with w det J, and the smallest det J.
fn mapped_points(x: &[[f64; 2]]) -> ([MappedPoint; 4], [f64; 4], f64) {
    let rule = stiffness_rule(ElementKind::Qua4);
    let p: [MappedPoint; 4] = std::array::from_fn(|q| map_point(ElementKind::Qua4, x, rule[q].xi));
    let w: [f64; 4] = std::array::from_fn(|q| rule[q].w * p[q].det_j);
    let min_det = p.iter().fold(f64::INFINITY, |m, p| m.min(p.det_j));
    (p, w, min_det)
}

/// Compatible strain columns B at a point.
fn b_columns(p: &MappedPoint) -> Cols<ND> {
    let mut c = [[0.0; 3]; ND];
    for a in 0..NN {
        let [nx, ny] = p.dndx[a];
        c[2 * a] = [nx, 0.0, ny];
        c[2 * a + 1] = [0.0, ny, nx];
    }
    c
}

/// Adds w A^T D B into `k` (row-major R x C).
fn add_atdb<const R: usize, const C: usize>(
    k: &mut [f64],
    d: &Matrix3<f64>,
    w: f64,
    a: &Cols<R>,
    b: &Cols<C>,
) {
    for i in 0..R {
        let da = d * Vector3::from(a[i]);
        for j in 0..C {
            k[i * C + j] += w * (da[0] * b[j][0] + da[1] * b[j][1] + da[2] * b[j][2]);
        }
    }
}

/// Element averages of the shape-function gradients, b_a = (1/A) int grad N_a dA.
fn mean_gradients(p: &[MappedPoint; 4], w: &[f64; 4]) -> [[f64; 2]; NN] {
    let area: f64 = w.iter().sum();
    std::array::from_fn(|a| {
        std::array::from_fn(|c| (0..4).map(|q| w[q] * p[q].dndx[a][c]).sum::<f64>() / area)
    })
}

/// Mean-dilatation B-bar QUA4 (Hughes, "Generalization of selective integration procedures
/// to anisotropic and nonlinear media", IJNME 15, 1980; Hughes, *The Finite Element Method*,
/// 2000, sec. 4.5.2). At each 2x2 point the dilatational part of B is replaced by its
/// element average:
///
/// ```text
/// B̄_a = B_a + ½ m (b̄_a - ∇N_a)^T,   m = (1, 1, 0),   b̄_a = (1/A) ∫_e ∇N_a dA,
/// K   = Σ_q w_q det J_q B̄_q^T D B̄_q,
/// ```
///
/// so eps̄ = eps + ½ (θ̄ - θ) m with θ = div u and θ̄ its element average: the deviatoric
/// part keeps full 2x2 integration, the (λ + μ) θ̄² energy of isotropic plane strain is one
/// constraint per element, which cures volumetric locking. Constant strains give θ̄ = θ,
/// hence the patch test. The in-plane projector ½ m m^T is used (eps_zz stays 0, and
/// sigma_zz = λ θ̄ in recovery) rather than the 3D ⅓ projector with an eps_zz row; both
/// impose the same single constraint. Fills the 8x8 `k`; returns the smallest det J.
pub fn stiffness_bbar(x: &[[f64; 2]], d: &Matrix3<f64>, k: &mut [f64]) -> f64 {
    let (p, w, min_det) = mapped_points(x);
    let bbar = mean_gradients(&p, &w);
    k[..ND * ND].fill(0.0);
    for q in 0..4 {
        let mut c = b_columns(&p[q]);
        for a in 0..NN {
            let [dx, dy] = [0.5 * (bbar[a][0] - p[q].dndx[a][0]), 0.5 * (bbar[a][1] - p[q].dndx[a][1])];
            c[2 * a][0] += dx;
            c[2 * a][1] += dx;
            c[2 * a + 1][0] += dy;
            c[2 * a + 1][1] += dy;
        }
        add_atdb(k, d, w[q], &c, &c);
    }
    min_det
}

/// (J^-1, det J) of the QUA4 map at reference point `xi`.
fn jacobian_inverse(x: &[[f64; 2]], xi: [f64; 2]) -> ([[f64; 2]; 2], f64) {
    let mut j = [[0.0; 2]; 2];
    for (a, &[r, s]) in ElementKind::Qua4.reference_nodes().iter().enumerate() {
        let dn = [0.25 * r * (1.0 + s * xi[1]), 0.25 * s * (1.0 + r * xi[0])];
        for c in 0..2 {
            j[c][0] += dn[0] * x[a][c];
            j[c][1] += dn[1] * x[a][c];
        }
    }
    let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
    ([[j[1][1] / det, -j[0][1] / det], [-j[1][0] / det, j[0][0] / det]], det)
}

/// Strain columns of the four incompatible modes (1 - xi^2, 1 - eta^2 on u, then on v) at
/// reference point `xi` where det J = `det_j`, with Taylor's centre-Jacobian gradients.
fn mode_columns(xi: [f64; 2], det_j: f64, j0inv: &[[f64; 2]; 2], det_j0: f64) -> Cols<4> {
    let s = det_j0 / det_j;
    // grad P = s J0^-T grad_xi P, grad_xi P1 = (-2 xi, 0), grad_xi P2 = (0, -2 eta).
    let g1 = [-2.0 * xi[0] * s * j0inv[0][0], -2.0 * xi[0] * s * j0inv[0][1]];
    let g2 = [-2.0 * xi[1] * s * j0inv[1][0], -2.0 * xi[1] * s * j0inv[1][1]];
    [[g1[0], 0.0, g1[1]], [g2[0], 0.0, g2[1]], [0.0, g1[1], g1[0]], [0.0, g2[1], g2[0]]]
}

/// K_uu (8x8), K_au (4x8) and K_aa (4x4) of QM6; `taylor = false` uses the local Jacobian for
/// the modes (the original Q6, which fails the patch test on distorted elements).
fn im_blocks(
    x: &[[f64; 2]],
    d: &Matrix3<f64>,
    taylor: bool,
    kuu: &mut [f64],
) -> (SMatrix<f64, 4, ND>, Matrix4<f64>, f64) {
    let (p, w, min_det) = mapped_points(x);
    let rule = stiffness_rule(ElementKind::Qua4);
    let (j0inv, det_j0) = jacobian_inverse(x, [0.0, 0.0]);
    let (mut kau, mut kaa) = ([0.0; 4 * ND], [0.0; 16]);
    kuu[..ND * ND].fill(0.0);
    for q in 0..4 {
        let b = b_columns(&p[q]);
        let g = if taylor {
            mode_columns(rule[q].xi, p[q].det_j, &j0inv, det_j0)
        } else {
            let (ji, _) = jacobian_inverse(x, rule[q].xi);
            mode_columns(rule[q].xi, 1.0, &ji, 1.0)
        };
        add_atdb(kuu, d, w[q], &b, &b);
        add_atdb(&mut kau, d, w[q], &g, &b);
        add_atdb(&mut kaa, d, w[q], &g, &g);
    }
    (SMatrix::from_row_slice(&kau), Matrix4::from_row_slice(&kaa), min_det)
}

/// Incompatible-mode QUA4, QM6 (Wilson, Taylor, Doherty & Ghaboussi 1973 for Q6; Taylor,
/// Beresford & Wilson, "A non-conforming element for stress analysis", IJNME 10, 1976):
///
/// ```text
/// u = Σ N_a u_a + (1 - ξ²) α1 + (1 - η²) α2,   v = Σ N_a v_a + (1 - ξ²) α3 + (1 - η²) α4,
/// ∇P = (det J0 / det J) J0^-T ∇_ξ P            (J0: Jacobian at the element centre),
/// K  = K_uu - K_αu^T K_αα^-1 K_αu,             α = -K_αα^-1 K_αu u_e.
/// ```
///
/// Taylor's correction makes ∫_e ∇P dA = det J0 J0^-T ∫ ∇_ξ P dξ dη = 0, so the modes do
/// no work on a constant stress and the element passes the patch test on any quadrilateral.
/// The modes represent pure bending exactly on rectangles, which removes shear locking.
/// Fills the 8x8 `k`; returns the smallest det J.
pub fn stiffness_im(x: &[[f64; 2]], d: &Matrix3<f64>, k: &mut [f64]) -> f64 {
    im_condensed(x, d, true, k)
}

fn im_condensed(x: &[[f64; 2]], d: &Matrix3<f64>, taylor: bool, k: &mut [f64]) -> f64 {
    let (kau, kaa, min_det) = im_blocks(x, d, taylor, k);
    if !(min_det > 0.0) {
        return min_det; // K_aa may be singular; the caller rejects the element anyway
    }
    // K_aa is SPD for a valid element (the modes are independent of the nodal field).
    let x_au = kaa.cholesky().expect("K_aa of a valid QUA4 is positive definite").solve(&kau);
    let corr = kau.transpose() * x_au;
    for i in 0..ND {
        for j in 0..ND {
            k[i * ND + j] -= corr[(i, j)];
        }
    }
    min_det
}

/// What a technology adds to the compatible strain B u of one element, from its nodal
/// displacements: nothing, the mean dilatation θ̄, or the condensed mode amplitudes α.
#[derive(Debug, Clone, Copy)]
pub enum StrainCorrection {
    None,
    MeanDilatation { theta_bar: f64 },
    Modes { alpha: [f64; 4], j0inv: [[f64; 2]; 2], det_j0: f64 },
}

impl StrainCorrection {
    /// The correction of element `x` (QUA4 coordinates for SRI/IM) with displacements `u`.
    pub fn new(tech: Technology, x: &[[f64; 2]], d: &Matrix3<f64>, u: &[f64]) -> Self {
        match tech {
            Technology::Full => Self::None,
            Technology::SelectiveReduced => {
                let (p, w, _) = mapped_points(x);
                let b = mean_gradients(&p, &w);
                Self::MeanDilatation {
                    theta_bar: (0..NN).map(|a| b[a][0] * u[2 * a] + b[a][1] * u[2 * a + 1]).sum(),
                }
            }
            Technology::IncompatibleModes => {
                let mut kuu = [0.0; ND * ND];
                let (kau, kaa, _) = im_blocks(x, d, true, &mut kuu);
                let ue = SMatrix::<f64, ND, 1>::from_column_slice(&u[..ND]);
                let alpha: Vector4<f64> =
                    -kaa.cholesky().expect("K_aa of a valid QUA4 is positive definite").solve(&(kau * ue));
                let (j0inv, det_j0) = jacobian_inverse(x, [0.0, 0.0]);
                Self::Modes { alpha: alpha.into(), j0inv, det_j0 }
            }
        }
    }

    /// Element strain at mapped point `p` (reference point `xi`) from the compatible strain.
    pub fn apply(&self, p: &MappedPoint, xi: [f64; 2], mut eps: [f64; 3]) -> [f64; 3] {
        match self {
            Self::None => {}
            Self::MeanDilatation { theta_bar } => {
                let h = 0.5 * (theta_bar - eps[0] - eps[1]);
                eps[0] += h;
                eps[1] += h;
            }
            Self::Modes { alpha, j0inv, det_j0 } => {
                for (c, a) in mode_columns(xi, p.det_j, j0inv, *det_j0).iter().zip(alpha) {
                    (0..3).for_each(|i| eps[i] += c[i] * a);
                }
            }
        }
        eps
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::element::stiffness::strain;
    use crate::fem::material::Material;

    const X: [[f64; 2]; 4] = [[0.0, 0.0], [2.0, 0.3], [2.4, 1.9], [-0.2, 1.2]];

    /// Patch test of one element: for a linear field the element forces must equal the
    /// consistent forces of the constant stress, int B^T sigma dA.
    fn patch_residual(k: &[f64]) -> f64 {
        let d = Material::plane_strain(1.0, 0.3).unwrap().d_matrix();
        let lin = |p: [f64; 2]| [1e-3 * p[0] - 2e-3 * p[1], 0.5e-3 * p[0] + 3e-3 * p[1]];
        let u: Vec<f64> = X.iter().flat_map(|&p| lin(p)).collect();
        let sigma = d * Vector3::new(1e-3, 3e-3, -1.5e-3);
        let (p, w, _) = mapped_points(&X);
        let mut f = [0.0; ND];
        for q in 0..4 {
            for (j, c) in b_columns(&p[q]).iter().enumerate() {
                f[j] += w[q] * Vector3::from(*c).dot(&sigma);
            }
        }
        (0..ND).map(|i| ((0..ND).map(|j| k[i * ND + j] * u[j]).sum::<f64>() - f[i]).abs()).fold(0.0, f64::max)
            / sigma.amax()
    }

    #[test]
    fn taylor_correction_is_what_passes_the_patch_test() {
        let d = Material::plane_strain(1.0, 0.3).unwrap().d_matrix();
        let mut k = [0.0; ND * ND];
        im_condensed(&X, &d, true, &mut k);
        assert!(patch_residual(&k) < 1e-13, "QM6 residual {}", patch_residual(&k));
        im_condensed(&X, &d, false, &mut k);
        assert!(patch_residual(&k) > 1e-3, "Q6 (no correction) should fail: residual {}", patch_residual(&k));
    }

    #[test]
    fn recovered_modes_vanish_for_linear_fields() {
        let d = Material::plane_strain(1.0, 0.3).unwrap().d_matrix();
        let u: Vec<f64> =
            X.iter().flat_map(|&p| [1e-3 * p[0] - 2e-3 * p[1], 0.5e-3 * p[0] + 3e-3 * p[1]]).collect();
        match StrainCorrection::new(Technology::IncompatibleModes, &X, &d, &u) {
            StrainCorrection::Modes { alpha, .. } => {
                assert!(alpha.iter().all(|a| a.abs() < 1e-16), "{alpha:?}")
            }
            c => panic!("{c:?}"),
        }
        let c = StrainCorrection::new(Technology::SelectiveReduced, &X, &d, &u);
        let p = map_point(ElementKind::Qua4, &X, [0.3, -0.6]);
        let e = c.apply(&p, [0.3, -0.6], strain(&p, 4, &u));
        assert!(
            (e[0] - 1e-3).abs() < 1e-16 && (e[1] - 3e-3).abs() < 1e-16 && (e[2] + 1.5e-3).abs() < 1e-16,
            "{e:?}"
        );
    }
}
