//! A manufactured solution for convergence tests (Roache 2002): on the unit square,
//! u = v = sin(pi x) sin(pi y), zero on the boundary, loaded by the body force
//! b = -div sigma = -[(lambda + mu) grad(div u) + mu laplace(u)].

use crate::fem::material::Material;
use std::f64::consts::PI;

#[derive(Debug, Clone, Copy)]
pub struct SineSolution {
    lambda: f64,
    mu: f64,
}

impl SineSolution {
    pub fn new(m: &Material) -> Self {
        Self { lambda: m.lambda(), mu: m.shear_modulus() }
    }

    /// Body force b(x, y), N/m^3 (per unit displacement amplitude).
    pub fn body_force(&self, p: [f64; 2]) -> [f64; 2] {
        let (phi, psi) = ((PI * p[0]).sin() * (PI * p[1]).sin(), (PI * p[0]).cos() * (PI * p[1]).cos());
        let div = (self.lambda + self.mu) * PI * PI * (psi - phi) - 2.0 * self.mu * PI * PI * phi;
        [-div, -div]
    }

    /// Exact displacement and strain (eps_xx, eps_yy, gamma_xy) at a point.
    pub fn exact(&self, p: [f64; 2]) -> ([f64; 2], [f64; 3]) {
        let phi = (PI * p[0]).sin() * (PI * p[1]).sin();
        let (px, py) =
            (PI * (PI * p[0]).cos() * (PI * p[1]).sin(), PI * (PI * p[0]).sin() * (PI * p[1]).cos());
        ([phi, phi], [px, py, px + py])
    }
}
