//! Closed-form theory for the bonded strip, used to judge FE interface fields near the ends.
//!
//! The scene: an elastic strip of thickness `t` (plane strain, Poisson ratio `nu`), clamped
//! (u = v = 0) on y = 0 and y = t, traction-free at x = ±L/2. Two results describe how the
//! interface stresses depart from the uniform-strain model near the ends:
//!
//! * [`williams`]: the stress singularity r^(λ-1) at the 90° corner where a clamped face
//!   meets the free end (Williams 1952), and how end-node values grow under refinement;
//! * [`strip`]: the rate exp(-s x) at which end disturbances decay into the strip away from
//!   the corners (the clamped-face analogue of the Papkovich–Fadle eigenfunctions).
//!
//! Both reduce to roots of entire functions, found by [`roots`]. Only `std` is used: the
//! small [`Complex`] type below is all the complex arithmetic needed.
//!
//! Throughout, κ = 3 − 4ν (plane strain) and μ is the shear modulus.

pub mod manufactured;
pub mod partial_slip;
pub mod roots;
pub mod strip;
pub mod thin_layer;
pub mod williams;

use crate::{Error, Result};
use std::ops::{Add, Div, Mul, Neg, Sub};

/// A complex number; just the operations the eigen-equations need.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Complex {
    pub re: f64,
    pub im: f64,
}

impl Complex {
    pub const ZERO: Complex = Complex { re: 0.0, im: 0.0 };
    pub const ONE: Complex = Complex { re: 1.0, im: 0.0 };

    pub const fn new(re: f64, im: f64) -> Self {
        Complex { re, im }
    }
    pub fn abs(self) -> f64 {
        self.re.hypot(self.im)
    }
    pub fn arg(self) -> f64 {
        self.im.atan2(self.re)
    }
    pub fn conj(self) -> Self {
        Complex::new(self.re, -self.im)
    }
    pub fn is_finite(self) -> bool {
        self.re.is_finite() && self.im.is_finite()
    }
    /// sin(a + ib) = sin a cosh b + i cos a sinh b.
    pub fn sin(self) -> Self {
        Complex::new(self.re.sin() * self.im.cosh(), self.re.cos() * self.im.sinh())
    }
    /// cos(a + ib) = cos a cosh b − i sin a sinh b.
    pub fn cos(self) -> Self {
        Complex::new(self.re.cos() * self.im.cosh(), -self.re.sin() * self.im.sinh())
    }
}

impl From<f64> for Complex {
    fn from(re: f64) -> Self {
        Complex::new(re, 0.0)
    }
}

impl Add for Complex {
    type Output = Complex;
    fn add(self, o: Complex) -> Complex {
        Complex::new(self.re + o.re, self.im + o.im)
    }
}
impl Sub for Complex {
    type Output = Complex;
    fn sub(self, o: Complex) -> Complex {
        Complex::new(self.re - o.re, self.im - o.im)
    }
}
impl Mul for Complex {
    type Output = Complex;
    fn mul(self, o: Complex) -> Complex {
        Complex::new(self.re * o.re - self.im * o.im, self.re * o.im + self.im * o.re)
    }
}
impl Div for Complex {
    type Output = Complex;
    fn div(self, o: Complex) -> Complex {
        // Smith's algorithm: avoids overflow in |o|^2 when sin/cos of large Im are involved.
        if o.re.abs() >= o.im.abs() {
            let r = o.im / o.re;
            let d = o.re + o.im * r;
            Complex::new((self.re + self.im * r) / d, (self.im - self.re * r) / d)
        } else {
            let r = o.re / o.im;
            let d = o.re * r + o.im;
            Complex::new((self.re * r + self.im) / d, (self.im * r - self.re) / d)
        }
    }
}
impl Neg for Complex {
    type Output = Complex;
    fn neg(self) -> Complex {
        Complex::new(-self.re, -self.im)
    }
}
impl Mul<f64> for Complex {
    type Output = Complex;
    fn mul(self, k: f64) -> Complex {
        Complex::new(self.re * k, self.im * k)
    }
}
impl Mul<Complex> for f64 {
    type Output = Complex;
    fn mul(self, z: Complex) -> Complex {
        z * self
    }
}
impl Add<f64> for Complex {
    type Output = Complex;
    fn add(self, k: f64) -> Complex {
        Complex::new(self.re + k, self.im)
    }
}
impl Sub<f64> for Complex {
    type Output = Complex;
    fn sub(self, k: f64) -> Complex {
        Complex::new(self.re - k, self.im)
    }
}
impl Div<f64> for Complex {
    type Output = Complex;
    fn div(self, k: f64) -> Complex {
        Complex::new(self.re / k, self.im / k)
    }
}

/// κ = 3 − 4ν, the plane-strain Kolosov constant.
pub fn kappa_plane_strain(nu: f64) -> f64 {
    3.0 - 4.0 * nu
}

/// Accepts ν in (−1, 1/2], or (−1, 1/2) when `incompressible_ok` is false.
pub(crate) fn check_nu(nu: f64, incompressible_ok: bool) -> Result<()> {
    let ok = nu > -1.0 && (nu < 0.5 || (incompressible_ok && nu == 0.5));
    if ok {
        Ok(())
    } else {
        let range = if incompressible_ok { "(-1, 0.5]" } else { "(-1, 0.5)" };
        Err(Error::input("Poisson ratio", format!("nu = {nu} is outside {range}")))
    }
}

/// Determinant of a small complex matrix by Gaussian elimination with partial pivoting.
/// Used for the boundary-condition determinants that check the closed forms.
pub fn det<const N: usize>(mut a: [[Complex; N]; N]) -> Complex {
    let mut d = Complex::ONE;
    for k in 0..N {
        let p = (k..N).max_by(|&i, &j| a[i][k].abs().total_cmp(&a[j][k].abs())).unwrap();
        if a[p][k].abs() == 0.0 {
            return Complex::ZERO;
        }
        if p != k {
            a.swap(p, k);
            d = -d;
        }
        d = d * a[k][k];
        for i in k + 1..N {
            let m = a[i][k] / a[k][k];
            for j in k..N {
                a[i][j] = a[i][j] - m * a[k][j];
            }
        }
    }
    d
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn complex_arithmetic() {
        let z = Complex::new(0.3, -1.2);
        let w = Complex::new(-2.0, 0.5);
        let q = z / w * w;
        assert!((q - z).abs() < 1e-15);
        // sin^2 + cos^2 = 1 off the real axis.
        let one = z.sin() * z.sin() + z.cos() * z.cos();
        assert!((one - Complex::ONE).abs() < 1e-14);
        // det of [[1, i], [2, 3]] = 3 - 2i.
        let d = det([[Complex::ONE, Complex::new(0.0, 1.0)], [2.0.into(), 3.0.into()]]);
        assert!((d - Complex::new(3.0, -2.0)).abs() < 1e-15);
    }

    #[test]
    fn nu_range() {
        assert!(check_nu(0.4, false).is_ok());
        assert!(check_nu(0.5, true).is_ok());
        assert!(check_nu(0.5, false).is_err());
        assert!(check_nu(-1.0, true).is_err());
        assert!(check_nu(f64::NAN, true).is_err());
    }
}
