//! Isotropic linear elasticity in plane strain (unit width, SI units).

use crate::error::{Error, Result};
use nalgebra::Matrix3;

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    /// Young's modulus, Pa.
    pub e: f64,
    /// Poisson's ratio, dimensionless.
    pub nu: f64,
}

impl Material {
    /// Plane-strain material; rejects E <= 0 and nu outside (-1, 0.5).
    pub fn plane_strain(e: f64, nu: f64) -> Result<Self> {
        if !(e.is_finite() && e > 0.0) {
            return Err(Error::input(
                "Young's modulus",
                format!("E = {e} Pa, must be a finite positive number"),
            ));
        }
        if !nu.is_finite() || nu <= -1.0 || nu >= 0.5 {
            let why = if nu == 0.5 {
                "nu = 0.5 is exactly incompressible: plane-strain displacement elements need a mixed (u-p) formulation for it; use nu <= 0.4999".to_string()
            } else {
                format!("nu = {nu}, must lie in (-1, 0.5) for a stable isotropic solid")
            };
            return Err(Error::input("Poisson's ratio", why));
        }
        Ok(Self { e, nu })
    }

    /// Shear modulus G (Lame's mu), Pa.
    pub fn shear_modulus(&self) -> f64 {
        self.e / (2.0 * (1.0 + self.nu))
    }

    /// Lame's lambda, Pa.
    pub fn lambda(&self) -> f64 {
        self.e * self.nu / ((1.0 + self.nu) * (1.0 - 2.0 * self.nu))
    }

    /// Bulk modulus of plane strain, lambda + G (the volumetric part of D), Pa.
    pub fn plane_bulk(&self) -> f64 {
        self.lambda() + self.shear_modulus()
    }

    /// D in sigma = D eps with Voigt order (xx, yy, xy) and engineering shear strain.
    pub fn d_matrix(&self) -> Matrix3<f64> {
        let (l, g) = (self.lambda(), self.shear_modulus());
        Matrix3::new(l + 2.0 * g, l, 0.0, l, l + 2.0 * g, 0.0, 0.0, 0.0, g)
    }

    /// Out-of-plane stress of plane strain, sigma_zz = lambda (eps_xx + eps_yy).
    pub fn sigma_zz(&self, eps_xx: f64, eps_yy: f64) -> f64 {
        self.lambda() * (eps_xx + eps_yy)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn rejects_bad_values() {
        assert!(Material::plane_strain(0.0, 0.3).is_err());
        assert!(Material::plane_strain(f64::NAN, 0.3).is_err());
        assert!(Material::plane_strain(1.0, -1.0).is_err());
        let msg = Material::plane_strain(1.0, 0.5).unwrap_err().to_string();
        assert!(msg.contains("incompressible"), "{msg}");
        assert!(Material::plane_strain(1.0, 0.4999).is_ok());
    }
}
