//! The paper's model corrected to first order in t/H and t/L for a thin bonded layer under a
//! rigid tilting plate (issue 19). Closed form; its one ingredient beyond algebra is the slowest
//! compression decay rate k(nu) of the clamped strip ([`super::strip`]).
//!
//! # Derivation (x along the interface, 0 < y < t, plate tilt theta, lambda, mu Lamé)
//! 1. Interior. With the top tied to the plate (u = u0, v = V + theta x) and the bottom
//!    clamped, the exact polynomial solution of Navier's equations is
//!    v = (V + theta x) y/t, u = u0 y/t + c y (t - y) with c = (lambda + mu) theta / (2 mu t).
//!    It gives sigma_yy = (lambda + 2 mu)(V + theta x)/t, the same on both faces (a linear
//!    pressure p_i(x) = P0 + s x), sigma_xx = -(nu/(1-nu)) p_i, and a vertical shear force on a
//!    section Q = int sigma_xy dy = t tau_b - lambda theta t / 2 = t F / L to this order.
//! 2. Shear couple. Q must vanish at both free ends: the end zones pass it to the faces as
//!    opposite pressure forces, +-Q/2 on the interface at each end (antisymmetric class). Their
//!    moment about the centre is Q L / 2 = F t / 2, so the smooth pressure carries only
//!    F (H - t/2): **the effective arm is H - t/2**.
//! 3. Poisson edge deficit (next term in t/L). Releasing sigma_xx at a free end while the clamps
//!    hold epsilon_yy lowers sigma_yy there by the factor a = (nu/(1-nu))^2 of the local interior
//!    pressure; the deficit decays as exp(-k d/t) with the slowest compression root k(nu)
//!    (symmetric class). Its force, a t p_end / k at each end, shifts the mean interior pressure
//!    to P0 = (N/L) / (1 - 2 a t/(k L)) and its moment raises the slope:
//!    slope = 12 (F/N)(H - t/2)/L / (1 - 6 (a/k)(t/L)(1 - 2 t/(k L))).
//!    As nu -> 1/2, a -> 1 and k -> sqrt(12 (1 - 2 nu)) -> 0: the deficit spreads over
//!    t/k >> t and the interior pressure becomes the dome of bonded rubber layers (Gent and
//!    Lindley 1959), which the profile below follows with the exact finite-length integrals.
//!
//! Not modelled: the end zones themselves (singular corners, |x| > L/2 - ~2 t), and the
//! shear's own O(t/L) edge forces (the interior shear stays F/L here; FE: -0.06 % at the paper's
//! t/L = 0.005, `tribofe check`).

use super::strip::{slowest_decay, Family};
use crate::{Error, Result};

/// The corrected interior fields of one load case, in units of N/L against x/L.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Corrected {
    /// t/L, H/L, F/N.
    pub t_over_l: f64,
    pub h_over_l: f64,
    pub fn_ratio: f64,
    /// Drop factor a = (nu/(1-nu))^2 and decay rate k (s t) of the Poisson edge deficit.
    pub a: f64,
    pub k: f64,
    /// Interior mean pressure P0 and slope S: p_i(xi) = P0 + S xi (xi = x/L).
    pub p0: f64,
    pub slope: f64,
}

impl Corrected {
    /// The corrected model for a block of thickness t, length l, loaded at height h (m), with
    /// Poisson ratio nu and the load ratio F/N.
    pub fn new(l: f64, t: f64, h: f64, nu: f64, fn_ratio: f64) -> Result<Self> {
        Self::with_decay(l, t, h, nu, fn_ratio, Self::decay(nu)?)
    }

    /// The decay rate k(nu) of [`Corrected::new`]: a complex root search (milliseconds), so
    /// callers with many load cases or geometries at one nu compute it once.
    pub fn decay(nu: f64) -> Result<f64> {
        if !(nu > -1.0 && nu < 0.5) {
            return Err(Error::input("corrected model", format!("nu = {nu} must lie in (-1, 0.5)")));
        }
        Ok(slowest_decay(nu, Family::Compression)?.re)
    }

    /// [`Corrected::new`] with k = [`Corrected::decay`]`(nu)` given.
    pub fn with_decay(l: f64, t: f64, h: f64, nu: f64, fn_ratio: f64, k: f64) -> Result<Self> {
        if !(l > 0.0 && t > 0.0 && h > 0.0 && l.is_finite() && t.is_finite() && h.is_finite()) {
            return Err(Error::input(
                "corrected model",
                format!("L = {l}, t = {t}, H = {h} m must be positive"),
            ));
        }
        if !(nu > -1.0 && nu < 0.5) {
            return Err(Error::input("corrected model", format!("nu = {nu} must lie in (-1, 0.5)")));
        }
        let a = (nu / (1.0 - nu)).powi(2);
        let tau = t / l;
        let c = k / tau;
        let e = (-c).exp();
        // i0 = int exp(-c (1/2 - xi)) dxi, i1 = int xi exp(-c (1/2 - xi)) dxi over [-1/2, 1/2].
        let i0 = (1.0 - e) / c;
        let i1 = 0.5 * i0 - (1.0 / (c * c) - e * (1.0 / c + 1.0 / (c * c)));
        let p0 = 1.0 / (1.0 - 2.0 * a * i0);
        let moment = fn_ratio * (h - 0.5 * t) / l;
        let slope = moment / (1.0 / 12.0 - a * i1);
        Ok(Self { t_over_l: tau, h_over_l: h / l, fn_ratio, a, k, p0, slope })
    }

    /// p/(N/L) at xi = x/L (interior: valid for |x| < L/2 - ~2 t).
    pub fn pressure(&self, xi: f64) -> f64 {
        let c = self.k / self.t_over_l;
        let (pr, pl) = (self.p0 + 0.5 * self.slope, self.p0 - 0.5 * self.slope);
        self.p0 + self.slope * xi - self.a * (pr * (-c * (0.5 - xi)).exp() + pl * (-c * (0.5 + xi)).exp())
    }

    /// tau/(N/L): the model's F/N (see the module notes).
    pub fn shear(&self) -> f64 {
        self.fn_ratio
    }

    /// Asymptotic slope for k L / t >> 1 (the formula of the module notes).
    pub fn slope_asymptotic(&self) -> f64 {
        let g = self.a / self.k;
        12.0 * self.fn_ratio * (self.h_over_l - 0.5 * self.t_over_l)
            / (1.0 - 6.0 * g * self.t_over_l * (1.0 - 2.0 * self.t_over_l / self.k))
    }
}

/// Closed-form p(0) of a thin bonded layer compressed by strain e (parabolic lateral
/// displacement across the thickness): p = e [M - lambda^2/M cosh(x/l)/cosh(L/2l)],
/// M = lambda + 2G, l = t sqrt(M / 12 G). In the interior p -> M e (laterally confined).
pub fn bonded_layer_p0(mat: &crate::fem::material::Material, strain: f64, length: f64, t: f64) -> f64 {
    let (lam, g) = (mat.lambda(), mat.shear_modulus());
    let m = lam + 2.0 * g;
    let ell = t * (m / (12.0 * g)).sqrt();
    strain * (m - lam * lam / m / (length / (2.0 * ell)).cosh())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn balances_hold_and_limits_are_right() {
        let c = Corrected::new(0.4, 0.002, 0.04, 0.4, 0.82).unwrap();
        // Exact integrals: int p = 1 and int xi p = (F/N)(H - t/2)/L (Simpson, 20001 points).
        let n = 20000;
        let (mut s0, mut s1) = (0.0, 0.0);
        for i in 0..=n {
            let xi = -0.5 + i as f64 / n as f64;
            let w = if i == 0 || i == n {
                1.0
            } else if i % 2 == 1 {
                4.0
            } else {
                2.0
            } / (3.0 * n as f64);
            s0 += w * c.pressure(xi);
            s1 += w * xi * c.pressure(xi);
        }
        assert!((s0 - 1.0).abs() < 1e-9, "{s0}");
        assert!((s1 - 0.82 * 0.039 / 0.4).abs() < 1e-9, "{s1}");
        assert!((c.slope - c.slope_asymptotic()).abs() < 1e-6 * c.slope);
        // t -> 0 recovers the paper's model.
        let c0 = Corrected::new(0.4, 1e-9, 0.04, 0.4, 0.82).unwrap();
        assert!((c0.slope - 12.0 * 0.82 * 0.1).abs() < 1e-6);
        assert!((c0.p0 - 1.0).abs() < 1e-6);
        // nu = 0: no Poisson deficit.
        let z = Corrected::new(0.4, 0.002, 0.04, 0.0, 0.82).unwrap();
        assert!((z.slope - 12.0 * 0.82 * 0.039 / 0.4).abs() < 1e-12 && z.p0 == 1.0);
    }
}
