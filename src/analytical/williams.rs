//! Williams corner singularity where a clamped face meets a traction-free face.
//!
//! Reference: M. L. Williams (1952), "Stress singularities resulting from various boundary
//! conditions in angular corners of plates in extension", J. Appl. Mech. 19:526–528
//! (the clamped–free case); see also G. B. Sinclair (2004), "Stress singularities in
//! classical elasticity I/II", Appl. Mech. Rev. 57:251–297 and 385–439, and the
//! displacement fields of J. R. Barber, *Elasticity*, Table 8.1.
//!
//! # Derivation
//! Wedge 0 <= θ <= α with apex at r = 0; clamped at θ = 0, free at θ = α. The Airy function
//! φ = r^(λ+1) F(θ),
//!
//! F = a cos(λ+1)θ + b sin(λ+1)θ + c cos(λ−1)θ + d sin(λ−1)θ,
//!
//! gives σ_θθ = λ(λ+1) r^(λ−1) F, σ_rθ = −λ r^(λ−1) F', so stresses ~ r^(λ−1) and the strain
//! energy near the apex is finite for Re λ > 0. In plane strain (κ = 3 − 4ν)
//!
//! 2μ u_r = r^λ [ −(λ+1)(a cos(λ+1)θ + b sin(λ+1)θ) + (κ−λ)(c cos(λ−1)θ + d sin(λ−1)θ) ],
//! 2μ u_θ = r^λ [  (λ+1)(a sin(λ+1)θ − b cos(λ+1)θ) + (κ+λ)(c sin(λ−1)θ − d cos(λ−1)θ) ].
//!
//! Boundary conditions: u_r(0) = u_θ(0) = 0 and F(α) = F'(α) = 0 (λ ≠ 0, −1), i.e. the 4×4
//! system of [`clamped_free_determinant`]. Eliminating a and b through the clamp rows and
//! expanding the remaining 2×2 with cos(λ+1)α cos(λ−1)α ∓ sin(λ+1)α sin(λ−1)α = cos 2λα,
//! cos 2α gives
//!
//! det = 4 (λ+1) [ κ sin²(λα) + λ² sin²α − (1+κ)²/4 ],
//!
//! and since λ + 1 ≠ 0 for Re λ > 0 the eigen-equation is
//!
//! **κ sin²(λα) = (1+κ)²/4 − λ² sin²α.**
//!
//! (With the plane-stress κ = (3−ν)/(1+ν), (1+κ)²/4 = 4/(1+ν)², the form in which the
//! clamped–free result is usually quoted.) Note the sign: the right side is (1+κ)²/4 minus
//! λ² sin²α; the other sign has no root for α = π, where the correct form reproduces the
//! classical oscillatory exponent λ = 1/2 + iε, ε = ln κ / (2π), of a bonded (clamped–free)
//! half-plane edge (Muskhelishvili, *Some Basic Problems...*, the adhesive rigid punch).
//!
//! For the strip's corner, α = π/2: κ sin²(πλ/2) + λ² = (1+κ)²/4. Limits: ν = 0 (κ = 3)
//! gives λ = 1 exactly — uniaxial σ_yy with zero Poisson contraction fits the clamp, so there
//! is no singularity; ν = 1/2 (κ = 1) gives cos(πλ/2) = λ, λ = 0.594612; ν = 0.3 gives
//! λ = 0.711173, the commonly quoted 0.7112 for a 90° elastic corner bonded to a rigid base.

use super::roots::{find_roots, smallest_re_above, Region};
use super::{check_nu, det, kappa_plane_strain, Complex};
use crate::{Error, Result};
use std::f64::consts::PI;

/// Closed-form residual κ sin²(λα) + λ² sin²α − (1+κ)²/4 of the clamped–free eigen-equation.
pub fn clamped_free_residual(lambda: Complex, alpha: f64, nu: f64) -> Complex {
    let kappa = kappa_plane_strain(nu);
    let s = (lambda * alpha).sin();
    kappa * (s * s) + lambda * lambda * alpha.sin().powi(2) - 0.25 * (1.0 + kappa).powi(2)
}

/// Determinant of the 4×4 boundary-condition matrix acting on (a, b, c, d) of the Williams
/// stress function (rows: u_r(0), u_θ(0), F(α), F'(α)); equals 4(λ+1) ×
/// [`clamped_free_residual`].
/// Kept as the independent check of the closed form.
pub fn clamped_free_determinant(lambda: Complex, alpha: f64, nu: f64) -> Complex {
    let kappa = kappa_plane_strain(nu);
    let (p, m) = (lambda + 1.0, lambda - 1.0);
    let (cp, sp) = ((p * alpha).cos(), (p * alpha).sin());
    let (cm, sm) = ((m * alpha).cos(), (m * alpha).sin());
    let z = Complex::ZERO;
    det([
        [-p, z, -(lambda - kappa), z],
        [z, -p, z, -(lambda + kappa)],
        [cp, sp, cm, sm],
        [-(p * sp), p * cp, -(m * sm), m * cm],
    ])
}

/// The clamped–free eigenvalue λ with the smallest positive real part, Im λ >= 0 (its
/// conjugate is also a root). Stresses near the corner go like r^(Re λ − 1); Re λ in (0, 1)
/// means a singular corner, Re λ >= 1 (ν <= 0 at α = π/2) a bounded one.
///
/// `alpha` is the wedge angle in radians, in (0, 2π]; π/2 for the strip's corners. `nu` in
/// (−1, 1/2]. Roots are found in 0 < Re λ <= 1 + 2π/α, 0 <= Im λ <= 1 + 2π/α (the first root
/// scales like 1/α for small α) by [`find_roots`].
pub fn clamped_free_exponent(alpha: f64, nu: f64) -> Result<Complex> {
    check_nu(nu, true)?;
    if !(alpha > 0.0 && alpha <= 2.0 * PI) {
        return Err(Error::input("wedge angle", format!("alpha = {alpha} rad is outside (0, 2 pi]")));
    }
    let reach = 1.0 + 2.0 * PI / alpha;
    let f = |l: Complex| clamped_free_residual(l, alpha, nu);
    let roots = find_roots(&f, Region { re: (0.0, reach), im_max: reach, n_re: 60, n_im: 40 });
    smallest_re_above(&roots, 0.0).ok_or_else(|| {
        Error::input("clamped-free corner", format!("no eigenvalue with 0 < Re(lambda) <= {reach:.2}"))
    })
}

/// The stress singularity exponent 1 − Re λ: σ ~ r^−(1 − Re λ). Zero or negative means bounded.
pub fn singularity_exponent(lambda: Complex) -> f64 {
    1.0 - lambda.re
}

/// Growth of a corner nodal stress per halving of the element size h. A nodal value samples
/// the field at r ~ h, so it scales like h^(Re λ − 1) and halving h multiplies it by
/// 2^(1 − Re λ). For complex λ the factor r^(i Im λ) also turns the phase by Im λ · ln 2 per
/// halving, which can make single refinements look irregular; the modulus trend is this
/// factor. For Re λ >= 1 the corner value converges: growth 1.
pub fn refinement_growth(lambda: Complex) -> f64 {
    2f64.powf(singularity_exponent(lambda).max(0.0))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analytical::roots::count_zeros;

    const RIGHT: f64 = PI / 2.0;

    #[test]
    fn published_and_limiting_values_at_right_angle() {
        // ν = 0.3: 0.7112 as commonly quoted for a 90° corner bonded to a rigid base.
        let l = clamped_free_exponent(RIGHT, 0.3).unwrap();
        assert!((l.re - 0.7112).abs() < 5e-5 && l.im == 0.0, "{l:?}");
        assert!((l.re - 0.711_172_932_971_466).abs() < 1e-12, "{l:?}");
        // ν = 1/2: cos(πλ/2) = λ.
        let l = clamped_free_exponent(RIGHT, 0.5).unwrap();
        assert!(((RIGHT * l.re).cos() - l.re).abs() < 1e-14);
        assert!((l.re - 0.594_611_644_056_836).abs() < 1e-12, "{l:?}");
        // ν = 0: λ = 1, no singularity, no growth under refinement.
        let l = clamped_free_exponent(RIGHT, 0.0).unwrap();
        assert!((l.re - 1.0).abs() < 1e-12, "{l:?}");
        assert_eq!(refinement_growth(l), 1.0);
    }

    #[test]
    fn half_plane_gives_the_bonded_punch_exponent() {
        // α = π: λ = 1/2 + i ln κ / (2π).
        for nu in [0.0, 0.3, 0.4] {
            let l = clamped_free_exponent(PI, nu).unwrap();
            let eps = kappa_plane_strain(nu).ln() / (2.0 * PI);
            assert!((l - Complex::new(0.5, eps)).abs() < 1e-12, "nu {nu}: {l:?} vs eps {eps}");
        }
    }

    #[test]
    fn closed_form_equals_the_boundary_condition_determinant() {
        for nu in [-0.5, 0.0, 0.3, 0.4, 0.5] {
            for alpha in [0.7, RIGHT, 2.0, PI, 5.5] {
                for l in [Complex::new(0.3, 0.0), Complex::new(0.8, 0.4), Complex::new(2.5, -1.1)] {
                    let closed = clamped_free_residual(l, alpha, nu) * (l + 1.0) * 4.0;
                    let direct = clamped_free_determinant(l, alpha, nu);
                    assert!((closed - direct).abs() < 1e-12 * (1.0 + closed.abs()), "{nu} {alpha} {l:?}");
                }
                // And each returned root zeroes the determinant.
                let l = clamped_free_exponent(alpha, nu).unwrap();
                assert!(clamped_free_determinant(l, alpha, nu).abs() < 1e-10, "{nu} {alpha} {l:?}");
            }
        }
    }

    #[test]
    fn no_root_with_smaller_real_part_is_missed() {
        // Argument principle over 0.01 <= Re λ <= Re λ1 − 0.01, |Im λ| <= 6.
        for (alpha, nu) in [(RIGHT, 0.3), (RIGHT, 0.4), (RIGHT, 0.5), (PI, 0.4), (2.0, 0.2)] {
            let l = clamped_free_exponent(alpha, nu).unwrap();
            let f = |z: Complex| clamped_free_residual(z, alpha, nu);
            assert_eq!(count_zeros(&f, (0.01, l.re - 0.01), (-6.0, 6.0), 4000), 0, "{alpha} {nu}");
        }
    }

    #[test]
    fn refinement_growth_per_halving() {
        let l = clamped_free_exponent(RIGHT, 0.4).unwrap();
        assert!((singularity_exponent(l) - 0.350_089_999_050_640).abs() < 1e-12);
        assert!((refinement_growth(l) - 1.274_640_140_190_101).abs() < 1e-12);
    }

    #[test]
    fn bad_input_is_rejected() {
        assert!(clamped_free_exponent(RIGHT, 0.51).is_err());
        assert!(clamped_free_exponent(0.0, 0.3).is_err());
        assert!(clamped_free_exponent(7.0, 0.3).is_err());
    }
}
