//! Wave speeds of an isotropic solid in plane strain or plane stress: P (of the in-plane
//! law: (lambda + 2 G) / rho in plane strain, E / ((1 - nu^2) rho) in plane stress), S, and the
//! Rayleigh speed (the root of
//! the Rayleigh equation between 0 and c_s).

use crate::fem::material::Material;

/// P, S and Rayleigh speeds (m/s) of `material` at density `rho` (kg/m^3).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WaveSpeeds {
    pub c_p: f64,
    pub c_s: f64,
    pub c_r: f64,
}

impl WaveSpeeds {
    pub fn new(material: &Material, rho: f64) -> Self {
        let (l, g) = (material.lambda(), material.shear_modulus());
        // lambda is the in-plane law's: E nu / (1 - nu^2) in plane stress.
        let c_p = ((l + 2.0 * g) / rho).sqrt();
        let c_s = (g / rho).sqrt();
        Self { c_p, c_s, c_r: c_s * rayleigh_ratio(c_s / c_p) }
    }
}

/// c_R / c_s for a ratio k = c_s / c_p: the root in (0, 1) of the Rayleigh function
/// R(x) = (2 - x^2)^2 - 4 sqrt(1 - x^2) sqrt(1 - k^2 x^2), x = c / c_s, by bisection.
/// R(x) = -2 (1 - k^2) x^2 + O(x^4) < 0 just above 0 and R(1) = 1 > 0, so the bracket holds.
pub fn rayleigh_ratio(k: f64) -> f64 {
    let r = |x: f64| {
        let x2 = x * x;
        (2.0 - x2).powi(2) - 4.0 * (1.0 - x2).sqrt() * (1.0 - k * k * x2).sqrt()
    };
    let (mut a, mut b) = (1e-3, 1.0);
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        if r(m) < 0.0 {
            a = m;
        } else {
            b = m;
        }
    }
    0.5 * (a + b)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rayleigh_speed_of_known_solids() {
        // nu = 0.25 (Poisson solid): c_R / c_s = sqrt(2 - 2/sqrt(3)) = 0.919402 (Achenbach 5.11).
        let m = Material::plane_strain(1.0, 0.25).unwrap();
        let w = WaveSpeeds::new(&m, 1.0);
        assert!((w.c_r / w.c_s - (2.0 - 2.0 / 3f64.sqrt()).sqrt()).abs() < 1e-12, "{w:?}");
        assert!((w.c_p / w.c_s - 3f64.sqrt()).abs() < 1e-12);
        // nu = 0.4: 0.942 c_s (the brief's value; Viktorov's fit (0.862 + 1.14 nu)/(1 + nu) = 0.9414).
        let w = WaveSpeeds::new(&Material::plane_strain(2e3, 0.4).unwrap(), 1e3);
        assert!((w.c_r / w.c_s - 0.942).abs() < 5e-4, "{}", w.c_r / w.c_s);
        assert!((w.c_s - 0.845154).abs() < 1e-6 && (w.c_p - 2.070197).abs() < 1e-6, "{w:?}");
    }
}
