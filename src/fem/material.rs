//! Isotropic linear elasticity in plane strain or plane stress (per unit out-of-plane width,
//! SI units).

use crate::error::{Error, Result};
use nalgebra::Matrix3;
use serde::{Deserialize, Serialize};

/// The out-of-plane state of the 2D model: eps_zz = 0 (a long body, the default) or
/// sigma_zz = 0 (a thin plate, as the experiments' 5-6 mm plates).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum State {
    #[default]
    PlaneStrain,
    PlaneStress,
}

impl State {
    /// The name as the scene file writes it.
    pub fn name(self) -> &'static str {
        match self {
            State::PlaneStrain => "plane-strain",
            State::PlaneStress => "plane-stress",
        }
    }
}

impl std::str::FromStr for State {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        match s {
            "plane-strain" => Ok(State::PlaneStrain),
            "plane-stress" => Ok(State::PlaneStress),
            _ => Err(Error::input("block.state", format!("'{s}': use plane-strain or plane-stress"))),
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    /// Young's modulus, Pa.
    pub e: f64,
    /// Poisson's ratio, dimensionless.
    pub nu: f64,
    /// Plane strain or plane stress.
    pub state: State,
}

impl Material {
    /// Plane-strain material; rejects E <= 0 and nu outside (-1, 0.5).
    pub fn plane_strain(e: f64, nu: f64) -> Result<Self> {
        check_e(e)?;
        if !nu.is_finite() || nu <= -1.0 || nu >= 0.5 {
            let why = if nu == 0.5 {
                "nu = 0.5 is exactly incompressible: plane-strain displacement elements need a mixed (u-p) formulation for it; use nu <= 0.4999".to_string()
            } else {
                format!("nu = {nu}, must lie in (-1, 0.5) for a stable isotropic solid")
            };
            return Err(Error::input("Poisson's ratio", why));
        }
        Ok(Self { e, nu, state: State::PlaneStrain })
    }

    /// Plane-stress material; rejects E <= 0 and nu outside (-1, 0.5]: with sigma_zz = 0 the
    /// in-plane law stays finite at nu = 0.5 (the plate thickens freely).
    pub fn plane_stress(e: f64, nu: f64) -> Result<Self> {
        check_e(e)?;
        if !nu.is_finite() || nu <= -1.0 || nu > 0.5 {
            return Err(Error::input(
                "Poisson's ratio",
                format!("nu = {nu}, must lie in (-1, 0.5] for a stable isotropic solid"),
            ));
        }
        Ok(Self { e, nu, state: State::PlaneStress })
    }

    /// The material in `state`.
    pub fn new(e: f64, nu: f64, state: State) -> Result<Self> {
        match state {
            State::PlaneStrain => Self::plane_strain(e, nu),
            State::PlaneStress => Self::plane_stress(e, nu),
        }
    }

    /// Shear modulus G (Lame's mu), Pa; the same in both states.
    pub fn shear_modulus(&self) -> f64 {
        self.e / (2.0 * (1.0 + self.nu))
    }

    /// Lame's lambda of the in-plane law (D's off-diagonal), Pa: the 3D lambda in plane
    /// strain, E nu / (1 - nu^2) in plane stress.
    pub fn lambda(&self) -> f64 {
        match self.state {
            State::PlaneStrain => self.e * self.nu / ((1.0 + self.nu) * (1.0 - 2.0 * self.nu)),
            State::PlaneStress => self.e * self.nu / (1.0 - self.nu * self.nu),
        }
    }

    /// Bulk modulus of the in-plane law, lambda + G (the volumetric part of D), Pa:
    /// E / (2 (1 + nu) (1 - 2 nu)) in plane strain, E / (2 (1 - nu)) in plane stress.
    pub fn plane_bulk(&self) -> f64 {
        self.lambda() + self.shear_modulus()
    }

    /// P-wave (uniaxial-strain) modulus of the in-plane law, D_xx,xx, Pa: lambda + 2 G in
    /// plane strain, E / (1 - nu^2) in plane stress.
    pub fn p_wave_modulus(&self) -> f64 {
        self.lambda() + 2.0 * self.shear_modulus()
    }

    /// The in-plane modulus of crack and contact formulas, E* Pa: E / (1 - nu^2) in plane
    /// strain, E in plane stress.
    pub fn e_star(&self) -> f64 {
        match self.state {
            State::PlaneStrain => self.e / (1.0 - self.nu.powi(2)),
            State::PlaneStress => self.e,
        }
    }

    /// The Poisson ratio of the plane-strain solid with this in-plane law (same G): nu in plane
    /// strain, nu / (1 + nu) in plane stress. Closed forms written for plane strain in (G, nu)
    /// (Kolosov's 3 - 4 nu, corner exponents, strip decay, cohesive zones) hold for plane
    /// stress with it: the 2D equations depend on the in-plane law only.
    pub fn plane_strain_nu(&self) -> f64 {
        match self.state {
            State::PlaneStrain => self.nu,
            State::PlaneStress => self.nu / (1.0 + self.nu),
        }
    }

    /// D in sigma = D eps with Voigt order (xx, yy, xy) and engineering shear strain.
    pub fn d_matrix(&self) -> Matrix3<f64> {
        match self.state {
            State::PlaneStrain => {
                let (l, g) = (self.lambda(), self.shear_modulus());
                Matrix3::new(l + 2.0 * g, l, 0.0, l, l + 2.0 * g, 0.0, 0.0, 0.0, g)
            }
            // sigma_zz = 0 eliminates eps_zz: D = E/(1-nu^2) [[1, nu, 0], [nu, 1, 0], [0, 0, (1-nu)/2]].
            State::PlaneStress => {
                let (c, nu) = (self.e / (1.0 - self.nu * self.nu), self.nu);
                Matrix3::new(c, c * nu, 0.0, c * nu, c, 0.0, 0.0, 0.0, c * (1.0 - nu) / 2.0)
            }
        }
    }

    /// Out-of-plane stress: lambda (eps_xx + eps_yy) in plane strain, 0 in plane stress.
    pub fn sigma_zz(&self, eps_xx: f64, eps_yy: f64) -> f64 {
        match self.state {
            State::PlaneStrain => self.lambda() * (eps_xx + eps_yy),
            State::PlaneStress => 0.0,
        }
    }
}

fn check_e(e: f64) -> Result<()> {
    if !(e.is_finite() && e > 0.0) {
        return Err(Error::input("Young's modulus", format!("E = {e} Pa, must be a finite positive number")));
    }
    Ok(())
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
        assert!(Material::plane_stress(1.0, 0.5).is_ok());
        assert!(Material::plane_stress(1.0, 0.5001).is_err());
        assert!(Material::plane_stress(f64::INFINITY, 0.3).is_err());
    }

    #[test]
    fn plane_stress_matrix_is_the_mapped_plane_strain_one() {
        let (e, nu) = (3e9, 0.35);
        let ps = Material::plane_stress(e, nu).unwrap();
        let mapped =
            Material::plane_strain(e * (1.0 + 2.0 * nu) / (1.0 + nu).powi(2), nu / (1.0 + nu)).unwrap();
        let (a, b) = (ps.d_matrix(), mapped.d_matrix());
        assert!((a - b).abs().max() <= 1e-12 * a.abs().max(), "{a} vs {b}");
        assert!((ps.lambda() - mapped.lambda()).abs() <= 1e-12 * ps.lambda());
        assert!((ps.e_star() - mapped.e_star()).abs() <= 1e-12 * e);
        assert!((ps.plane_strain_nu() - mapped.nu).abs() <= 1e-15);
        assert_eq!(ps.sigma_zz(1e-3, 2e-3), 0.0);
        // In plane stress, D_xx,xx is E / (1 - nu^2).
        assert!((ps.p_wave_modulus() - e / (1.0 - nu * nu)).abs() <= 1e-12 * e);
    }
}
