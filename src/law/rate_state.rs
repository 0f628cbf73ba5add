//! Rate-and-state friction (Dieterich 1979, Ruina 1983), in the regularised form the
//! dynamic-rupture codes use near V = 0 (Lapusta et al. 2000; SEM2DPACK, SeisSol):
//!
//! ```text
//! mu(V, theta) = a asinh( V / (2 V_0) exp(psi / a) ),   psi = f_0 + b ln(V_0 theta / L)
//! ```
//!
//! with the aging law d(theta)/dt = 1 - V theta / L or the slip law
//! d(theta)/dt = -(V theta / L) ln(V theta / L). For V >> V_0 exp(-psi / a) it is the classic
//! mu = f_0 + a ln(V / V_0) + b ln(V_0 theta / L); steady state theta_ss = L / V.
//!
//! This is the law layer's rate-and-state piece (issue 46): the law, its exact state update at
//! a constant slip rate over a step, and the per-node solve of the split-node rule
//! tau_lock - Z V = sigma mu(V, theta). Wiring it into the explicit solver is the
//! one-integrator refactor's work.

use crate::error::{Error, Result};

/// How the state variable evolves.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StateLaw {
    /// d(theta)/dt = 1 - V theta / L (Dieterich): the state heals at rest.
    Aging,
    /// d(theta)/dt = -(V theta / L) ln(V theta / L) (Ruina): no healing at rest.
    Slip,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RateState {
    /// Direct effect (dimensionless).
    pub a: f64,
    /// Evolution effect (dimensionless); b > a is rate weakening at steady state.
    pub b: f64,
    /// State-evolution distance L, m.
    pub l: f64,
    /// Reference slip rate V_0, m/s.
    pub v0: f64,
    /// Steady-state coefficient at V_0 (dimensionless).
    pub f0: f64,
    pub law: StateLaw,
    /// The state every node starts from, s (default L / V_0: steady sliding at V_0; after a
    /// hold of t_h at rest from there, about t_h under the aging law).
    pub theta0: f64,
}

impl RateState {
    /// Checks 0 < a, 0 <= b, |f_0| (friction coefficients, at most [`super::MU_MAX`]) and L,
    /// V_0 in [1e-100, 1e100] (so that theta_0 = L / V_0 and every state stays finite),
    /// naming the flags.
    pub fn new(a: f64, b: f64, l: f64, v0: f64, f0: f64, law: StateLaw) -> Result<Self> {
        let bad = |key: &str, v: f64, need: &str| Err(Error::input(key, format!("{v}: {need}")));
        let max = super::MU_MAX;
        if !(a.is_finite() && a > 0.0 && a <= max) {
            return bad("--a", a, &format!("give the direct effect 0 < a <= {max:e}"));
        }
        if !(b.is_finite() && b >= 0.0 && b <= max) {
            return bad("--b", b, &format!("give the evolution effect 0 <= b <= {max:e}"));
        }
        crate::error::scaled("--l-rs", l, "m")?;
        crate::error::scaled("--v0", v0, "m/s")?;
        if !(f0.is_finite() && f0.abs() <= max) {
            return bad("--f0", f0, &format!("give a reference coefficient |f_0| <= {max:e}"));
        }
        Ok(Self { a, b, l, v0, f0, law, theta0: l / v0 })
    }

    /// The same law started from state `theta0` (s, in [1e-100, 1e100]).
    pub fn with_theta0(self, theta0: f64) -> Result<Self> {
        crate::error::scaled("--theta0", theta0, "s")?;
        Ok(Self { theta0, ..self })
    }

    /// How the outputs name it.
    pub fn name(&self) -> String {
        let kind = match self.law {
            StateLaw::Aging => "aging",
            StateLaw::Slip => "slip",
        };
        format!(
            "rate-and-state ({kind} law, a = {}, b = {}, L = {:e} m, V_0 = {:e} m/s, f_0 = {}, theta_0 = {:e} s)",
            self.a, self.b, self.l, self.v0, self.f0, self.theta0
        )
    }

    /// psi = f_0 + b ln(V_0 theta / L).
    fn psi(&self, theta: f64) -> f64 {
        self.f0 + self.b * (self.v0 * theta / self.l).ln()
    }

    /// ln of the asinh argument, ln(V / (2 V_0)) + psi / a (-inf at V = 0).
    fn log_arg(&self, v: f64, theta: f64) -> f64 {
        (v / (2.0 * self.v0)).ln() + self.psi(theta) / self.a
    }

    /// The coefficient at slip rate `v` >= 0 (m/s) and state `theta` (s).
    pub fn mu(&self, v: f64, theta: f64) -> f64 {
        self.a * asinh_exp(self.log_arg(v, theta))
    }

    /// d mu / d V at (v, theta), 1/(m/s): a / sqrt(V^2 + (2 V_0 exp(-psi/a))^2).
    pub fn dmu_dv(&self, v: f64, theta: f64) -> f64 {
        let q = self.log_arg(v, theta);
        // a c / sqrt(1 + (V c)^2) with V c = e^q, written so that neither factor overflows.
        if q > 0.0 {
            self.a / (v * (1.0 + (-2.0 * q).exp()).sqrt())
        } else {
            let c = q.exp() / v;
            self.a * c / (1.0 + q.exp().powi(2)).sqrt()
        }
    }

    /// Steady-state coefficient at slip rate v > 0 (theta = L / V).
    pub fn mu_steady(&self, v: f64) -> f64 {
        self.mu(v, self.l / v)
    }

    /// The state after `dt` (s) at constant slip rate `v` >= 0, exactly: aging,
    /// theta = L/V + (theta_0 - L/V) exp(-V dt / L) (theta_0 + dt at rest); slip,
    /// ln(V theta / L) decays as exp(-V dt / L) (unchanged at rest). Written without L/V, which
    /// overflows at the subnormal slip rates of deep creep (V < L / 1.8e308; a small a puts
    /// stuck nodes there: V ~ exp(-(tau_pk - tau) / (sigma a))): aging theta e^-x + dt (1 -
    /// e^-x) / x, slip ln theta e^-x + (1 - e^-x) ln(L / V), x = V dt / L. Until 2026-11-29
    /// L/V + (theta - L/V) e^-x made theta NaN there, and the node's friction 0 from then on.
    pub fn evolve(&self, theta: f64, v: f64, dt: f64) -> f64 {
        if v <= 0.0 {
            return match self.law {
                StateLaw::Aging => theta + dt,
                StateLaw::Slip => theta,
            };
        }
        let x = v * dt / self.l;
        let decay = (-x).exp();
        let gone = -(-x).exp_m1();
        match self.law {
            StateLaw::Aging => theta * decay + dt * if x > 0.0 { gone / x } else { 1.0 },
            StateLaw::Slip => (theta.ln() * decay + gone * (self.l.ln() - v.ln())).exp(),
        }
    }

    /// Critical stiffness of a spring-slider at steady sliding V_ss under normal stress sigma
    /// with radiation damping eta (Pa s/m), per unit area (Pa/m): below it steady sliding is
    /// unstable. Linearising both state laws gives the Hopf point
    /// k_c = (sigma (b - a) - eta V_ss) / L (Rice & Ruina 1983 at eta = 0).
    pub fn critical_stiffness(&self, sigma: f64, eta: f64, v_ss: f64) -> f64 {
        (sigma * (self.b - self.a) - eta * v_ss) / self.l
    }

    /// The split-node rule's per-node solve: the slip rate V >= 0 with
    /// tau_lock - z V = sigma mu(V, theta), for a locking traction magnitude tau_lock >= 0
    /// (Pa), an impedance z >= 0 (Pa s/m) and a compressive sigma > 0 (Pa). g(V) = sigma mu + z V
    /// - tau_lock increases in V; the root is bracketed and found by Newton steps in ln V kept
    ///   inside the bracket (bisection when a step leaves it), to the round-off of g's terms.
    pub fn solve_rate(&self, tau_lock: f64, z: f64, sigma: f64, theta: f64) -> Result<f64> {
        self.solve_rate_steps(tau_lock, z, sigma, theta).map(|(v, _)| v)
    }

    /// [`Self::solve_rate`] with the count of Newton or bisection steps it took.
    fn solve_rate_steps(&self, tau_lock: f64, z: f64, sigma: f64, theta: f64) -> Result<(f64, usize)> {
        if !(tau_lock >= 0.0 && z >= 0.0 && sigma > 0.0 && tau_lock.is_finite() && z.is_finite()) {
            return Err(Error::input(
                "rate-and-state solve",
                format!("tau_lock = {tau_lock}, z = {z}, sigma = {sigma}: need tau_lock >= 0, z >= 0, sigma > 0, finite"),
            ));
        }
        if tau_lock == 0.0 {
            return Ok((0.0, 0));
        }
        // Without z the root is closed-form: sigma mu(V*) = tau_lock, ln V* = ln(2 V_0) - psi/a
        // + ln sinh(tau_lock / (sigma a)). With z > 0 the root lies below V* and below tau_lock/z.
        let r = tau_lock / (sigma * self.a);
        let ln_sinh = if r > 20.0 { r - std::f64::consts::LN_2 } else { r.sinh().ln() };
        let ln_vstar = (2.0 * self.v0).ln() - self.psi(theta) / self.a + ln_sinh;
        if z == 0.0 {
            let v = ln_vstar.exp();
            return if v.is_finite() {
                Ok((v, 0))
            } else {
                Err(Error::Untrustworthy {
                    detail: format!("rate-and-state: slip rate e^{ln_vstar:.1} m/s overflows"),
                    hint: "the locking traction exceeds what the law can hold at any finite rate".into(),
                })
            };
        }
        let g = |w: f64| -> (f64, f64) {
            let v = w.exp();
            (sigma * self.mu(v, theta) + z * v - tau_lock, v * (sigma * self.dmu_dv(v, theta) + z))
        };
        let mut hi = ln_vstar.min((tau_lock / z).ln());
        let mut lo = hi - 7.0;
        let mut tries = 0;
        while g(lo).0 >= 0.0 {
            hi = lo;
            lo -= 7.0;
            tries += 1;
            if tries > 200 {
                return Ok((0.0, 0));
            }
        }
        // g is increasing and convex in w = ln V (sigma a asinh(e^(w + c)) and z e^w are), and
        // g(hi) >= 0: Newton from hi falls monotonically onto the root, in a few steps where the
        // inertial term is small (creep: the root is then ln V* itself). The bracket's middle,
        // the start until 2026-11-29, is up to 3.5 in w off, which Newton on an exponential
        // walks back one unit a step.
        let mut w = hi;
        for k in 0..200 {
            let (gw, dg) = g(w);
            // The root to the round-off of the equation's own terms (sigma mu and z V are each
            // at most tau_lock there). Below it a step in w is noise, and for |w| > 8 (one ulp
            // of w above 1e-15) the step test below is met only by a step that rounds to 0.
            if gw.abs() <= 4.0 * f64::EPSILON * tau_lock {
                return Ok((w.exp(), k));
            }
            if gw > 0.0 {
                hi = w;
            } else {
                lo = w;
            }
            let step = gw / dg;
            let mut next = w - step;
            if !(next > lo && next < hi && step.is_finite()) {
                next = 0.5 * (lo + hi);
            }
            if (next - w).abs() < 1e-15 || hi - lo < 1e-15 {
                return Ok((next.exp(), k + 1));
            }
            w = next;
        }
        Ok((w.exp(), 200))
    }
}

/// asinh(e^q) for any q, without overflow: q + ln(1 + sqrt(1 + e^(-2q))) above 0.
fn asinh_exp(q: f64) -> f64 {
    if q > 0.0 {
        q + (1.0 + (1.0 + (-2.0 * q).exp()).sqrt()).ln()
    } else {
        q.exp().asinh()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn law(kind: StateLaw) -> RateState {
        // Laboratory-scale values (Dieterich; Lapusta et al. 2000): a = 0.01, b = 0.015,
        // L = 10 um, V_0 = 1 um/s, f_0 = 0.6.
        RateState::new(0.01, 0.015, 1e-5, 1e-6, 0.6, kind).unwrap()
    }

    /// The state ODE integrated by classical RK4 in small steps: an independent reference
    /// for [`RateState::evolve`]'s closed forms.
    fn rk4(f: &RateState, mut theta: f64, v: f64, t: f64, n: usize) -> f64 {
        let rate = |th: f64| match f.law {
            StateLaw::Aging => 1.0 - v * th / f.l,
            StateLaw::Slip => -(v * th / f.l) * (v * th / f.l).ln(),
        };
        let h = t / n as f64;
        for _ in 0..n {
            let k1 = rate(theta);
            let k2 = rate(theta + 0.5 * h * k1);
            let k3 = rate(theta + 0.5 * h * k2);
            let k4 = rate(theta + h * k3);
            theta += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
        }
        theta
    }

    #[test]
    fn the_state_stays_finite_at_the_subnormal_rates_of_deep_creep() {
        // The study's law (validation/dynamics/rate_state, a = 4.8e-4): a stuck node's rate
        // falls as exp(-(tau_pk - tau) / (sigma a)) and passes through the subnormal floats on
        // its way to 0; there L/V overflowed and made the state NaN (friction 0 after it).
        let study =
            RateState::new(4.79753e-4, 4.79753e-3, 1.53842e-8, 5.79986e-11, 0.648, StateLaw::Aging).unwrap();
        let (sigma, z, dt) = (2.5, 5.2e3, 4.8e-5);
        let mut subnormal = 0;
        for k in 0..4000 {
            let tau = sigma * (0.25 + 0.35 * k as f64 / 4000.0);
            let v = study.solve_rate(tau, z, sigma, 100.0).unwrap();
            subnormal += usize::from(v > 0.0 && v < f64::MIN_POSITIVE);
            let th = study.evolve(100.0, v, dt);
            // At creep V dt / L << 1 the aging law is theta + dt (1 - V theta / L) to first order.
            let expect = 100.0 + dt * (1.0 - v * 100.0 / study.l);
            assert!((th - expect).abs() <= 1e-12 * expect, "tau {tau}: V {v:e}, theta {th} vs {expect}");
        }
        assert!(subnormal > 0, "the sweep crosses the subnormal rates");
        for kind in [StateLaw::Aging, StateLaw::Slip] {
            let f = law(kind);
            for v in [1e-300, 1e-310, 1e-317, 1e-320, 5e-324] {
                let th = f.evolve(3.0, v, dt);
                let expect = if kind == StateLaw::Aging { 3.0 + dt } else { 3.0 };
                assert!((th / expect - 1.0).abs() < 1e-15, "{kind:?} at V = {v:e}: {th}");
            }
            // At ordinary rates the closed form of before, to round-off.
            for (theta, v) in [(10.0, 1e-6), (0.1, 1e-4), (50.0, 1e-5), (1e-3, 1.0)] {
                let ss = f.l / v;
                let decay = (-v * 0.3 / f.l).exp();
                let before = match kind {
                    StateLaw::Aging => ss + (theta - ss) * decay,
                    StateLaw::Slip => ss * ((theta / ss).ln() * decay).exp(),
                };
                assert!((f.evolve(theta, v, 0.3) / before - 1.0).abs() < 1e-13, "{kind:?} {theta} {v}");
            }
        }
    }

    #[test]
    fn the_rate_solve_meets_its_equation_to_round_off_in_a_few_steps() {
        // g(w) = sigma mu(e^w, theta) + z e^w - tau_lock, w = ln V, increasing: the reference is
        // 400 bisections in w. The solve stops at |g| <= 4 eps tau_lock and g's own round-off
        // is a few eps tau_lock, so |w - w_ref| <= ~8 eps tau_lock / g'(w) (g' = V (sigma
        // dmu/dV + z)); asserted at 64 eps tau_lock / g'. Laws: the laboratory one and the
        // study's (validation/dynamics/rate_state: a = 4.8e-4, creep rates down to 1e-300 m/s);
        // z = rho h / (2 dt) at h = 0.5 mm (5.2e3 Pa s/m); tau_lock from creep to sliding.
        let study =
            RateState::new(4.79753e-4, 4.79753e-3, 1.53842e-8, 5.79986e-11, 0.648, StateLaw::Aging).unwrap();
        let (sigma, z) = (2.5, 5.2e3);
        for f in [law(StateLaw::Aging), study] {
            for theta in [100.0, 1.0, 1e-4] {
                for k in 1..=40 {
                    let tau = sigma * (0.3 + 0.02 * k as f64);
                    let (v, steps) = f.solve_rate_steps(tau, z, sigma, theta).unwrap();
                    let g = |w: f64| sigma * f.mu(w.exp(), theta) + z * w.exp() - tau;
                    let (mut lo, mut hi) = (-745.0_f64, (tau / z).ln());
                    for _ in 0..400 {
                        let mid = 0.5 * (lo + hi);
                        if g(mid) > 0.0 {
                            hi = mid;
                        } else {
                            lo = mid;
                        }
                    }
                    let w_ref = 0.5 * (lo + hi);
                    let v_ref = w_ref.exp();
                    if v_ref < 1e-300 {
                        continue;
                    }
                    let slope = v_ref * (sigma * f.dmu_dv(v_ref, theta) + z);
                    let tol = 64.0 * f64::EPSILON * tau / slope;
                    assert!(
                        (v.ln() - w_ref).abs() <= tol,
                        "a = {}, theta {theta}, tau {tau}: ln V {} vs {w_ref} (tol {tol:e})",
                        f.a,
                        v.ln()
                    );
                    // Creep (z V << tau_lock: the root is the closed-form V* of z = 0): Newton from
                    // V* in at most 3 steps; sliding in at most 30 (monotone, g convex in w).
                    let creep = z * v_ref < 1e-6 * tau;
                    assert!(
                        steps <= if creep { 3 } else { 30 },
                        "a = {}, theta {theta}, tau {tau}: {steps} steps (creep {creep})",
                        f.a
                    );
                }
            }
        }
    }

    #[test]
    fn steady_state_is_f0_plus_a_minus_b_ln_v_over_v0() {
        // Far above V_0 exp(-psi/a) (e^-60 V_0 here) the regularised law is the classic one to
        // e^-120: mu_ss(V) = f_0 + (a - b) ln(V / V_0).
        for kind in [StateLaw::Aging, StateLaw::Slip] {
            let f = law(kind);
            for v in [1e-9, 1e-6, 1e-3, 1.0] {
                let want = 0.6 + (0.01 - 0.015) * (v / 1e-6f64).ln();
                assert!((f.mu_steady(v) - want).abs() < 1e-14, "{v}: {} vs {want}", f.mu_steady(v));
            }
        }
        // At V = 0 the regularised law holds no shear.
        assert_eq!(law(StateLaw::Aging).mu(0.0, 10.0), 0.0);
    }

    #[test]
    fn evolve_is_the_state_ode_exactly() {
        for kind in [StateLaw::Aging, StateLaw::Slip] {
            let f = law(kind);
            for (theta0, v, t) in [(10.0, 1e-6, 30.0), (0.1, 1e-4, 0.5), (50.0, 1e-5, 3.0)] {
                let exact = f.evolve(theta0, v, t);
                let reference = rk4(&f, theta0, v, t, 200_000);
                assert!((exact / reference - 1.0).abs() < 1e-9, "{kind:?}: {exact} vs RK4 {reference}");
                // One step or many: the same state (the update is exact at constant V).
                let mut th = theta0;
                for _ in 0..100 {
                    th = f.evolve(th, v, t / 100.0);
                }
                assert!((th / exact - 1.0).abs() < 1e-12);
            }
        }
        // At rest the aging law heals (theta grows as t), the slip law does not.
        assert_eq!(law(StateLaw::Aging).evolve(2.0, 0.0, 3.0), 5.0);
        assert_eq!(law(StateLaw::Slip).evolve(2.0, 0.0, 3.0), 2.0);
    }

    #[test]
    fn velocity_step_direct_effect_and_decay_over_l() {
        // Steady sliding at V1, then V2 = 10 V1 imposed: mu jumps by a ln(V2/V1) at once, then
        // goes to the new steady state (a - b) ln(V2/V1) above the old. Slip law: mu - mu_ss(V2)
        // = b ln(V2/V1) exp(-delta/L) exactly (delta the slip since the step); aging law:
        // theta = L/V2 + (L/V1 - L/V2) exp(-delta/L), so mu - mu_ss(V2) = b ln(1 + 9 e^(-delta/L)).
        let (v1, v2): (f64, f64) = (1e-6, 1e-5);
        let r = (v2 / v1).ln();
        for kind in [StateLaw::Aging, StateLaw::Slip] {
            let f = law(kind);
            let theta1 = f.l / v1;
            let before = f.mu(v1, theta1);
            let jump = f.mu(v2, theta1) - before;
            assert!((jump - 0.01 * r).abs() < 1e-14, "{kind:?}: direct effect {jump}");
            let mut theta = theta1;
            let dt = 0.01 * f.l / v2;
            for k in 1..=1500 {
                theta = f.evolve(theta, v2, dt);
                let delta = k as f64 * dt * v2;
                let got = f.mu(v2, theta) - f.mu_steady(v2);
                let want = match kind {
                    StateLaw::Slip => 0.015 * r * (-delta / f.l).exp(),
                    StateLaw::Aging => 0.015 * (1.0 + 9.0 * (-delta / f.l).exp()).ln(),
                };
                assert!((got - want).abs() < 1e-12, "{kind:?} at delta/L = {}: {got} vs {want}", delta / f.l);
            }
            let settled = f.mu(v2, theta) - before;
            assert!((settled - (0.01 - 0.015) * r).abs() < 1e-4, "{kind:?}: steady change {settled}");
        }
    }

    #[test]
    fn split_node_solve_balances_the_traction() {
        let f = law(StateLaw::Aging);
        let sigma = 1e6;
        for (tau, z, theta) in [(6e5, 3e6, 10.0), (5.5e5, 1e3, 1e3), (6.5e5, 1e8, 1e-3), (7e5, 0.0, 10.0)] {
            let v = f.solve_rate(tau, z, sigma, theta).unwrap();
            let resid = tau - z * v - sigma * f.mu(v, theta);
            assert!(v > 0.0 && resid.abs() < 1e-8 * tau, "tau {tau}, z {z}: V = {v:e}, residual {resid:e}");
        }
        assert_eq!(f.solve_rate(0.0, 1.0, sigma, 1.0).unwrap(), 0.0);
        assert!(f.solve_rate(-1.0, 1.0, sigma, 1.0).is_err());
        assert!(RateState::new(0.0, 0.015, 1e-5, 1e-6, 0.6, StateLaw::Aging).is_err());
        assert!(RateState::new(0.01, 0.015, -1e-5, 1e-6, 0.6, StateLaw::Slip).is_err());
    }

    /// A spring-slider with radiation damping, loaded at V_ss, started 1 % off steady sliding:
    /// k (V_ss t - delta) - eta V = sigma mu(V, theta), V from the split-node solve, theta by
    /// the exact update, the spring by the trapezoid rule. Returns the ratio of the last
    /// swing of |ln(V/V_ss)| (the larger of its last two peaks, one each side) to the first,
    /// over about 28 periods of the linear oscillation.
    fn growth(kind: StateLaw, k_over_kc: f64) -> f64 {
        let f = law(kind);
        let (sigma, eta, v_ss) = (1e6, 1e6, 1e-6);
        let kc = f.critical_stiffness(sigma, eta, v_ss);
        let k = k_over_kc * kc;
        let mut theta = f.l / v_ss;
        // Force at steady sliding, minus 1 %: the spring starts slightly short.
        let tau_ss = sigma * f.mu_steady(v_ss) + eta * v_ss;
        let mut stretch = 0.99 * tau_ss / k;
        let t_osc = 2.0 * std::f64::consts::PI * f.l / v_ss; // a few of these per period
        let dt = t_osc / 2000.0;
        let mut v = f.solve_rate(k * stretch, eta, sigma, theta).unwrap();
        let mut peaks = vec![];
        let (mut prev, mut rising) = (0.0f64, false);
        for _ in 0..(40.0 * t_osc / dt) as usize {
            let th_next = f.evolve(theta, v, dt);
            let s_pred = stretch + (v_ss - v) * dt;
            let v_next = f.solve_rate(k * s_pred.max(0.0), eta, sigma, th_next).unwrap();
            stretch += (v_ss - 0.5 * (v + v_next)) * dt;
            theta = th_next;
            v = f.solve_rate(k * stretch.max(0.0), eta, sigma, theta).unwrap();
            let dev = (v / v_ss).ln().abs();
            if rising && dev < prev {
                peaks.push(prev);
            }
            rising = dev > prev;
            prev = dev;
        }
        assert!(peaks.len() > 6, "{kind:?} at k/k_c = {k_over_kc}: {} peaks", peaks.len());
        let n = peaks.len();
        peaks[n - 1].max(peaks[n - 2]) / peaks[0].max(peaks[1])
    }

    #[test]
    fn spring_slider_stability_boundary_is_k_c() {
        // Linear stability of steady sliding: k_c = (sigma (b - a) - eta V_ss) / L, the same
        // for both state laws (they agree to first order about steady state). 10 % either side
        // the perturbation must grow / decay over the run.
        for kind in [StateLaw::Aging, StateLaw::Slip] {
            let below = growth(kind, 0.97);
            let above = growth(kind, 1.03);
            assert!(below > 1.5, "{kind:?}: k = 0.97 k_c should be unstable, peak ratio {below}");
            assert!(above < 0.67, "{kind:?}: k = 1.03 k_c should be stable, peak ratio {above}");
        }
    }
}
