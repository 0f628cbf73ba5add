//! Thin-layer closed form of partial slip under a tilting rigid plate (coulomb friction).
//!
//! For t/L -> 0 each interface point is a local spring: the stuck zone carries a uniform
//! shear tau_0 (the plate moves it rigidly) and the pressure is linear, p = (N/L)(1 + 2 g' x/L)
//! with 2 g' = 12 (F/N)(H/L) from the moment balance F H = int p x dx. The slip zone grows
//! from the trailing edge x = -L/2 up to x_s, where tau = mu p; continuity at the front gives
//! tau_0 = mu p(x_s). Integrating,
//!
//! F/(mu N) = int_{-1/2}^{xi_s} (1 + a xi) dxi + (1/2 - xi_s)(1 + a xi_s) = 1 - (a/2)(xi_s - 1/2)^2
//!
//! with a = 12 (F/N)(H/L) = 2 g F/(mu N) and g = 6 mu H/L, hence
//! F/(mu N) = 1/(1 + g (1/2 - x_s/L)^2): slip starts at F/(mu N) = 1/(1 + g) (x_s = -L/2)
//! and the whole interface slides at F = mu N (x_s = L/2).

/// F/(mu N) when the front is at x_s/L (in [-1/2, 1/2]); g = 6 mu H/L.
pub fn force_ratio(g: f64, xs_over_l: f64) -> f64 {
    1.0 / (1.0 + g * (0.5 - xs_over_l).powi(2))
}

/// Front position x_s/L at F/(mu N) = phi, for phi in [1/(1+g), 1]; None outside.
pub fn front(g: f64, phi: f64) -> Option<f64> {
    if !(phi >= force_ratio(g, -0.5) - 1e-15 && phi <= 1.0 && g > 0.0) {
        return None;
    }
    Some(0.5 - ((1.0 / phi - 1.0).max(0.0) / g).sqrt())
}

/// Onset of slip at the trailing edge, F/(mu N) = 1/(1 + g).
pub fn onset(g: f64) -> f64 {
    1.0 / (1.0 + g)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inverse_and_limits() {
        let g = 0.3;
        assert!((force_ratio(g, -0.5) - onset(g)).abs() < 1e-15);
        assert!((force_ratio(g, 0.5) - 1.0).abs() < 1e-15);
        for xs in [-0.5, -0.2, 0.0, 0.3, 0.5] {
            assert!((front(g, force_ratio(g, xs)).unwrap() - xs).abs() < 1e-12);
        }
        assert!(front(g, 0.5).is_none());
    }
}
