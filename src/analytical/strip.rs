//! Decay of end disturbances into a plane-strain strip clamped on both faces.
//!
//! References: the traction-free analogue is the Papkovich–Fadle eigenfunction problem
//! (P. F. Papkovich 1940; J. Fadle 1941; e.g. M. W. Johnson & R. W. Little 1965,
//! Q. Appl. Math. 22:335; R. D. Gregory & I. Gladwell 1982, J. Elasticity 12:317). The
//! incompressible limit matches the lubrication theory of bonded rubber layers
//! (A. N. Gent & P. B. Lindley 1959, Proc. Inst. Mech. Eng. 173:111).
//!
//! # Derivation
//! Strip 0 <= y <= t, mid-plane coordinate η = y − t/2, half-thickness h = t/2. Seek
//! displacements ~ e^(−s x) with Re s > 0 (decaying away from an end at x = 0). Any solution
//! of Navier's equations can be written (2D Papkovich–Neuber, κ = 3 − 4ν)
//!
//! 2μ u_x = ∂_x (φ + η ψ),   2μ u_η = ∂_η (φ + η ψ) − κ ψ,   ∇²φ = ∇²ψ = 0,
//!
//! and harmonic functions ~ e^(−s x) are e^(−s x){cos sη, sin sη}. With z = s h = s t / 2 the
//! modes split by parity about the mid-plane:
//!
//! * **Compression class**, u_x even, u_η odd: φ = A cos sη, ψ = B sin sη. Clamping at η = ±h:
//!   A cos z + B h sin z = 0 and −A z sin z + B h (z cos z − κ sin z) = 0, whose determinant
//!   z − (κ/2) sin 2z must vanish: **κ sin 2z − 2z = 0**.
//! * **Shear class**, u_x odd, u_η even: φ = A sin sη, ψ = B cos sη, giving
//!   **κ sin 2z + 2z = 0**.
//!
//! Which load excites which: uniform compression of the layer (plate pressed down) gives a
//! far field with σ_xx = λ ε_yy uniform across the thickness and σ_xy = 0; the free end must
//! cancel an even σ_xx with no shear, and σ_xx even / σ_xy odd in η is exactly u_x even /
//! u_η odd. Uniform shear (plate displaced along x) gives σ_xy = μγ uniform, σ_xx = 0: an even
//! σ_xy, i.e. u_x odd / u_η even. (Both far fields carry a net end load; unlike a free strip,
//! the clamped strip has no s = 0 mode, so these need not be self-equilibrated to decay.)
//!
//! For ν < 1/2 (κ > 1) the slowest compression root is *real*: s t = w with κ sin w = w,
//! i.e. a monotone, non-oscillating decay. As ν → 1/2, w² → 6(κ−1)/κ → 12μ/λ_Lamé → 0:
//! an incompressible layer squeezed between rigid plates carries a pressure that never decays
//! from the ends (Gent & Lindley). The shear roots are complex (oscillating decay) for
//! ν > −0.40 (real ones need κ > 4.60).
//!
//! With traction-free faces the same parities give Papkovich–Fadle: sin 2z + 2z = 0
//! (compression/symmetric class, first root z = 2.1062 + 1.1254 i) and sin 2z − 2z = 0
//! (shear/antisymmetric class, z = 3.7488 + 1.3843 i), independent of ν. They are exposed
//! via [`Faces::TractionFree`] to check the solver against tabulated roots.
//!
//! [`navier_determinant`] re-derives all of this without the Papkovich–Neuber ansatz: it
//! integrates Navier's equations across the thickness as a first-order system and evaluates
//! the 4×4 boundary-condition determinant directly.

use super::roots::{find_roots, smallest_re_above, Region};
use super::{check_nu, det, kappa_plane_strain, Complex};
use crate::{Error, Result};

/// Mode families by parity about the mid-plane (see the module docs for which load excites
/// which).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Family {
    /// u_x even, u_y odd; excited by a uniform normal-pressure (compression) disturbance.
    Compression,
    /// u_x odd, u_y even; excited by a uniform shear disturbance.
    Shear,
}

/// Conditions on both faces y = 0 and y = t.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Faces {
    /// u = v = 0: the scene's bonded strip.
    Clamped,
    /// σ_xy = σ_yy = 0: the Papkovich–Fadle strip, used to check the solver.
    TractionFree,
}

/// Residual of the eigen-equation in z = s t / 2 (ν does not enter the traction-free case):
/// clamped κ sin 2z ∓ 2z, traction-free sin 2z ± 2z (upper sign: compression class).
pub fn residual(faces: Faces, nu: f64, family: Family, z: Complex) -> Complex {
    let s2 = (z * 2.0).sin();
    match (faces, family) {
        (Faces::Clamped, Family::Compression) => kappa_plane_strain(nu) * s2 - z * 2.0,
        (Faces::Clamped, Family::Shear) => kappa_plane_strain(nu) * s2 + z * 2.0,
        (Faces::TractionFree, Family::Compression) => s2 + z * 2.0,
        (Faces::TractionFree, Family::Shear) => s2 - z * 2.0,
    }
}

/// The root s t (dimensionless, Im >= 0; its conjugate is also a root) with the smallest
/// positive real part. The trivial root z = 0 is divided out before searching (it is of order
/// 3 for traction-free shear, else simple), so the real compression root is still bracketed
/// when ν → 1/2 pushes it towards 0. The search covers 1e-3 <= Re z <= 6, 0 <= Im z <= 4;
/// the lower bound keeps the divided residual clear of cancellation near z = 0.
///
/// Clamped compression needs ν < 1/2: at ν = 1/2 the root reaches s t = 0 (no decay), and
/// within ~2e-7 of 1/2 it falls below s t = 2e-3 and is reported as not found.
pub fn slowest_root(faces: Faces, nu: f64, family: Family) -> Result<Complex> {
    check_nu(nu, !(faces == Faces::Clamped && family == Family::Compression))?;
    let order = if (faces, family) == (Faces::TractionFree, Family::Shear) { 3 } else { 1 };
    let g = |z: Complex| {
        let mut zn = Complex::ONE;
        for _ in 0..order {
            zn = zn * z;
        }
        residual(faces, nu, family, z) / zn
    };
    let roots = find_roots(&g, Region { re: (1e-3, 6.0), im_max: 4.0, n_re: 60, n_im: 40 });
    smallest_re_above(&roots, 0.0).map(|z| z * 2.0).ok_or_else(|| {
        Error::input("strip eigenvalue", format!("no {family:?} root with 1e-3 <= Re(z) <= 6 for nu = {nu}"))
    })
}

/// [`slowest_root`] for the clamped strip: the slowest-decaying s t of `family`.
pub fn slowest_decay(nu: f64, family: Family) -> Result<Complex> {
    slowest_root(Faces::Clamped, nu, family)
}

/// 1 / Re(s t): the distance from the end, in units of t, over which the slowest mode's
/// envelope falls by a factor e.
pub fn decay_length_over_t(nu: f64, family: Family) -> Result<f64> {
    Ok(1.0 / slowest_decay(nu, family)?.re)
}

/// ln(1/tol) / Re(s t): the distance, in units of t, for the slowest mode's envelope to fall
/// to the fraction `tol` (e.g. 0.05) of its end value. Higher modes decay faster, so this is
/// where a unit end disturbance of that class is down to ~tol, up to its modal amplitude.
pub fn decay_distance_over_t(nu: f64, family: Family, tol: f64) -> Result<f64> {
    if !(tol > 0.0 && tol < 1.0) {
        return Err(Error::input("decay tolerance", format!("tol = {tol} is outside (0, 1)")));
    }
    Ok((1.0 / tol).ln() * decay_length_over_t(nu, family)?)
}

/// λ/μ = 2ν/(1 − 2ν).
fn lame_over_mu(nu: f64) -> f64 {
    2.0 * nu / (1.0 - 2.0 * nu)
}

/// The 4×4 first-order system X' = M X, X = (U, U', V, V'), that Navier's plane-strain
/// equations become for u = U(y) e^(−w x/t), v = V(y) e^(−w x/t), y in units of t, μ = 1:
/// (λ+2) w² U + U'' − (λ+1) w V' = 0 and w² V + (λ+2) V'' − (λ+1) w U' = 0.
fn navier_system(w: Complex, nu: f64) -> [[Complex; 4]; 4] {
    let lam = lame_over_mu(nu);
    let z = Complex::ZERO;
    let one = Complex::ONE;
    let w2 = w * w;
    [
        [z, one, z, z],
        [-(lam + 2.0) * w2, z, z, (lam + 1.0) * w],
        [z, z, z, one],
        [z, (lam + 1.0) / (lam + 2.0) * w, -(w2 / (lam + 2.0)), z],
    ]
}

fn matmul(a: &[[Complex; 4]; 4], b: &[[Complex; 4]; 4]) -> [[Complex; 4]; 4] {
    let mut c = [[Complex::ZERO; 4]; 4];
    for i in 0..4 {
        for j in 0..4 {
            for k in 0..4 {
                c[i][j] = c[i][j] + a[i][k] * b[k][j];
            }
        }
    }
    c
}

/// exp(M y) by scaling and squaring with a Taylor series: the transfer matrix taking
/// (U, U', V, V') from 0 to y.
fn transfer(w: Complex, nu: f64, y: f64) -> [[Complex; 4]; 4] {
    let mut m = navier_system(w, nu);
    let norm = m.iter().flatten().map(|c| c.abs()).sum::<f64>() * y;
    let squarings = norm.max(1.0).log2().ceil() as i32 + 1;
    let scale = y / 2f64.powi(squarings);
    for row in m.iter_mut() {
        for c in row.iter_mut() {
            *c = *c * scale;
        }
    }
    let mut e = [[Complex::ZERO; 4]; 4];
    let mut term = e;
    for i in 0..4 {
        e[i][i] = Complex::ONE;
        term[i][i] = Complex::ONE;
    }
    for k in 1..=20 {
        term = matmul(&term, &m);
        for row in term.iter_mut() {
            for c in row.iter_mut() {
                *c = *c / k as f64;
            }
        }
        for i in 0..4 {
            for j in 0..4 {
                e[i][j] = e[i][j] + term[i][j];
            }
        }
    }
    for _ in 0..squarings {
        e = matmul(&e, &e);
    }
    e
}

/// The two boundary quantities of state X = (U, U', V, V') on a face: (U, V) if clamped,
/// (σ_xy, σ_yy)/μ = (U' − wV, (λ+2)V' − λwU) if traction-free.
fn face_rows(faces: Faces, w: Complex, nu: f64, x: [Complex; 4]) -> [Complex; 2] {
    let lam = lame_over_mu(nu);
    match faces {
        Faces::Clamped => [x[0], x[2]],
        Faces::TractionFree => [x[1] - w * x[2], (lam + 2.0) * x[3] - lam * w * x[0]],
    }
}

/// Direct boundary-condition determinant for Navier's equations with e^(−w x/t) dependence,
/// w = s t: columns are the four fundamental solutions (unit initial states at y = 0), rows
/// the face conditions at y = 0 and y = t. Vanishes at the roots of both families; the
/// independent check of [`residual`]. Needs ν < 1/2.
pub fn navier_determinant(faces: Faces, nu: f64, w: Complex) -> Complex {
    let phi = transfer(w, nu, 1.0);
    let mut a = [[Complex::ZERO; 4]; 4];
    for j in 0..4 {
        let mut e = [Complex::ZERO; 4];
        e[j] = Complex::ONE;
        let end = [phi[0][j], phi[1][j], phi[2][j], phi[3][j]];
        let [r0, r1] = face_rows(faces, w, nu, e);
        let [r2, r3] = face_rows(faces, w, nu, end);
        a[0][j] = r0;
        a[1][j] = r1;
        a[2][j] = r2;
        a[3][j] = r3;
    }
    det(a)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analytical::roots::{count_zeros, newton};
    use Family::{Compression, Shear};

    fn close(a: Complex, b: Complex, tol: f64) -> bool {
        (a - b).abs() <= tol
    }

    #[test]
    fn papkovich_fadle_tabulated_roots() {
        // Traction-free first roots in z = s t / 2 as usually tabulated to 4 decimals
        // (e.g. Johnson & Little 1965): 2.1061 + 1.1254 i (truncated; 2.106196 + 1.125364 i)
        // and 3.7488 + 1.3843 i.
        let z = slowest_root(Faces::TractionFree, 0.3, Compression).unwrap() * 0.5;
        assert!(close(z, Complex::new(2.1061, 1.1254), 1.5e-4), "{z:?}");
        assert!(close(z, Complex::new(2.106_196_115_245_330, 1.125_364_305_800_930), 1e-12), "{z:?}");
        let z = slowest_root(Faces::TractionFree, 0.3, Shear).unwrap() * 0.5;
        assert!(close(z, Complex::new(3.7488, 1.3843), 1e-4), "{z:?}");
    }

    #[test]
    fn roots_satisfy_the_closed_form() {
        for faces in [Faces::Clamped, Faces::TractionFree] {
            for nu in [-0.5, 0.0, 0.3, 0.4, 0.49] {
                for family in [Compression, Shear] {
                    let w = slowest_root(faces, nu, family).unwrap();
                    let r = residual(faces, nu, family, w * 0.5);
                    assert!(r.abs() < 1e-12, "{faces:?} {nu} {family:?}: {w:?} -> {r:?}");
                }
            }
        }
    }

    #[test]
    fn closed_form_agrees_with_the_navier_determinant() {
        // Newton on the direct determinant, seeded 1e-3 off the closed-form root, must come
        // back to it; both the clamped equations and Papkovich–Fadle.
        for faces in [Faces::Clamped, Faces::TractionFree] {
            for nu in [0.0, 0.3, 0.4] {
                for family in [Compression, Shear] {
                    let w = slowest_root(faces, nu, family).unwrap();
                    let d = |s: Complex| navier_determinant(faces, nu, s);
                    let back = newton(&d, w * Complex::new(1.001, 0.001)).unwrap();
                    assert!(close(back, w, 1e-9 * w.abs()), "{faces:?} {nu} {family:?}: {w:?} vs {back:?}");
                }
            }
        }
    }

    #[test]
    fn family_parity_from_the_navier_mode_shape() {
        // Integrate the clamped mode across the thickness and compare y = t/4 with y = 3t/4:
        // compression has U even, V odd about the mid-plane; shear the opposite.
        let nu = 0.4;
        for (family, su, sv) in [(Compression, 1.0, -1.0), (Shear, -1.0, 1.0)] {
            let w = slowest_decay(nu, family).unwrap();
            let phi = transfer(w, nu, 1.0);
            // (U', V') at y = 0 spanning the null space of the 2×2 clamp at y = t.
            let slopes = [phi[0][3], -phi[0][1]];
            let at = |y: f64| {
                let p = transfer(w, nu, y);
                let u = p[0][1] * slopes[0] + p[0][3] * slopes[1];
                let v = p[2][1] * slopes[0] + p[2][3] * slopes[1];
                (u, v)
            };
            let ((u1, v1), (u3, v3)) = (at(0.25), at(0.75));
            let scale = u1.abs() + v1.abs();
            assert!(close(u3, u1 * su, 1e-9 * scale), "{family:?}: U {u1:?} {u3:?}");
            assert!(close(v3, v1 * sv, 1e-9 * scale), "{family:?}: V {v1:?} {v3:?}");
        }
    }

    #[test]
    fn no_slower_root_is_missed() {
        // Argument principle: no zero of the closed form with 0.005 <= Re z < Re z1, |Im z| <= 6.
        for nu in [0.0, 0.3, 0.4, 0.49] {
            for family in [Compression, Shear] {
                let z1 = slowest_decay(nu, family).unwrap() * 0.5;
                let f = |z: Complex| residual(Faces::Clamped, nu, family, z);
                let n = count_zeros(&f, (0.005, z1.re - 0.005), (-6.0, 6.0), 4000);
                assert_eq!(n, 0, "{nu} {family:?}");
            }
        }
    }

    #[test]
    fn incompressible_limit_of_the_compression_root() {
        // κ sin w = w near w = 0: w² ≈ 6(κ−1)/κ = 12 μ/λ as ν → 1/2 (Gent & Lindley's
        // pressure decay); relative error O(w²/20).
        for nu in [0.499, 0.4999] {
            let kappa = kappa_plane_strain(nu);
            let w = slowest_decay(nu, Compression).unwrap();
            let approx = (6.0 * (kappa - 1.0) / kappa).sqrt();
            assert!(w.im == 0.0 && (w.re / approx - 1.0).abs() < 2e-3, "{nu}: {w:?} vs {approx}");
        }
        assert!(slowest_decay(0.5, Compression).is_err());
        assert!(slowest_decay(0.5, Shear).is_ok());
    }

    #[test]
    fn bad_input_is_rejected() {
        assert!(slowest_decay(-1.0, Shear).is_err());
        assert!(decay_distance_over_t(0.4, Shear, 1.5).is_err());
    }
}
