//! Slip-weakening friction for the dynamic interface, and the cohesive-zone size it implies.
//!
//! mu(d) = mu_s - (mu_s - mu_d) min(d / D_c, 1), d the slip path length of the node (Ida 1972,
//! Andrews 1976); mu_s = mu_d is Coulomb friction (D_c then plays no part).

use crate::error::{Error, Result};


#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SlipWeakening {
    pub mu_s: f64,
    pub mu_d: f64,
    /// m.
    pub d_c: f64,
}

impl SlipWeakening {
    /// Checks 0 <= mu_d <= mu_s (finite) and D_c > 0; `flag` prefixes the names in messages.
    pub fn new(mu_s: f64, mu_d: f64, d_c: f64) -> Result<Self> {
        if !(mu_s.is_finite() && mu_d.is_finite() && 0.0 <= mu_d && mu_d <= mu_s) {
            return Err(Error::input(
                "friction coefficients (--mu-s, --mu-d)",
                format!("mu_s = {mu_s}, mu_d = {mu_d}: need 0 <= mu_d <= mu_s (mu_d = mu_s is Coulomb)"),
            ));
        }
        if !(d_c.is_finite() && d_c > 0.0) {
            return Err(Error::input("D_c (m, --dc)", format!("{d_c} must be a positive slip distance")));
        }
        Ok(Self { mu_s, mu_d, d_c })
    }

    pub fn coulomb(mu: f64) -> Result<Self> {
        Self::new(mu, mu, 1.0)
    }

    /// Friction coefficient after a slip path length `d`.
    #[inline]
    pub fn mu(&self, d: f64) -> f64 {
        self.mu_s - (self.mu_s - self.mu_d) * (d / self.d_c).min(1.0)
    }

    /// Cohesive-zone size of a slowly moving mode-II crack (Day et al. 2005, BSSA 95, eq. 5;
    /// Palmer & Rice 1973): Lambda_0 = (9 pi / 32) G D_c / ((1 - nu)(tau_p - tau_r)), with
    /// tau_p = mu_s sigma and tau_r = mu_d sigma. Infinite for Coulomb friction.
    pub fn cohesive_zone(&self, shear_modulus: f64, poisson: f64, sigma: f64) -> f64 {
        let drop = (self.mu_s - self.mu_d) * sigma;
        9.0 * std::f64::consts::PI / 32.0 * shear_modulus * self.d_c / ((1.0 - poisson) * drop)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weakening_and_zone() {
        let f = SlipWeakening::new(0.648, 0.583, 7.7e-7).unwrap();
        assert_eq!(f.mu(0.0), 0.648);
        assert!((f.mu(0.5 * 7.7e-7) - 0.6155).abs() < 1e-15);
        assert_eq!(f.mu(1.0), 0.583);
        // The spec scene: G = 714.2857 Pa, nu = 0.4, sigma0 = 2.5 Pa -> 4.984 mm.
        let l = f.cohesive_zone(2e3 / 2.8, 0.4, 2.5);
        assert!(
            (l - 9.0 * std::f64::consts::PI / 32.0 * (2e3 / 2.8) * 7.7e-7 / (0.6 * 0.1625)).abs() < 1e-15
        );
        assert!((l - 4.9843e-3).abs() < 1e-7, "{l}");
        assert!(SlipWeakening::new(0.5, 0.6, 1e-6).is_err());
        assert!(SlipWeakening::new(0.6, 0.5, 0.0).is_err());
        assert!(SlipWeakening::coulomb(0.5).unwrap().cohesive_zone(1.0, 0.3, 1.0).is_infinite());
    }
}
