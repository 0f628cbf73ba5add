//! The friction laws: one type, [`Law`], for the quasi-static event solver and the explicit
//! solver alike, named in the outputs by [`Law::name`]. The quasi-static solver is
//! rate-independent and takes the rate-free laws; the explicit solver takes every law but
//! static-kinetic (whose jump has no dynamic meaning) through one split-node rule,
//! [`Law::split_node`], with the normal response ([`Normal`]) as its own piece.

pub mod normal;
pub mod rate_state;

pub use normal::Normal;
pub use rate_state::{RateState, StateLaw};

use crate::error::{Error, Result};

/// What a static-kinetic instability does once a node reaches mu_s p.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rule {
    /// Scheibert & Dysthe's rule: the front runs over the connected region around the
    /// nucleation node where the pre-event |tau| >= mu_d p (fields frozen at the event's
    /// force); that region then relaxes to mu_d p with equilibrium restored (the plate held at
    /// X), and everything sticks again. Which p, and whether a node may end behind where it
    /// started: [`PaperOptions`].
    Paper,
    /// Quasi-static cascade at fixed X: slipping nodes carry mu_d p (p of the current
    /// iterate), the body re-equilibrates, any stuck node above its threshold joins. A node
    /// that has slipped once in the event keeps the kinetic threshold mu_d p for the rest of
    /// the event; if equilibrium asks it to slip backwards it sticks at its position from the
    /// start of the event (and may rejoin at mu_d p). When nothing moves, all nodes re-stick
    /// with mu_s.
    Overdamped,
}

impl Rule {
    /// The name `FromStr` reads.
    pub fn name(self) -> &'static str {
        match self {
            Rule::Paper => "paper",
            Rule::Overdamped => "overdamped",
        }
    }
}

/// Where the `paper` rule takes the slipped region's residual shear mu_d p (docs/precursors.md,
/// "What the `paper` rule does relative to the paper's equations").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Residual {
    /// mu_d P with P of the relaxed equilibrium (each slipping node's row T = -s mu_d P).
    #[default]
    Relaxed,
    /// mu_d P with P of the state before the event: the paper's mu_d p(x, F_i) (fixed point on
    /// the slipping rows' coefficients, mu_i = mu_d P_i(before) / P_i).
    PreEvent,
}

impl Residual {
    /// The name `FromStr` reads.
    pub fn name(self) -> &'static str {
        match self {
            Residual::Relaxed => "relaxed",
            Residual::PreEvent => "pre-event",
        }
    }
}

impl std::str::FromStr for Residual {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        match s {
            "relaxed" => Ok(Residual::Relaxed),
            "pre-event" => Ok(Residual::PreEvent),
            _ => Err(Error::input("residual", format!("'{s}': use relaxed or pre-event"))),
        }
    }
}

/// The `paper` rule's conventions where the paper's equations and a 2D relaxation part ways.
/// The default is the rule as it has always run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PaperOptions {
    pub residual: Residual,
    /// Whether a region node may end the relaxation behind where it started (counted in
    /// `Event::backslip`); false: such a node sticks where it started, the worst first, and
    /// the rest relax again (as slip weakening and the overdamped rule do).
    pub backslip: bool,
}

impl Default for PaperOptions {
    fn default() -> Self {
        Self { residual: Residual::Relaxed, backslip: true }
    }
}

impl std::str::FromStr for Rule {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        match s {
            "paper" => Ok(Rule::Paper),
            "overdamped" => Ok(Rule::Overdamped),
            _ => Err(Error::input("rule", format!("'{s}': use paper or overdamped"))),
        }
    }
}

/// One node's step in the split-node rule ([`Law::split_node`]), in consistent units: forces
/// per unit width (N/m) with nodal masses, or tractions (Pa) with masses per unit area.
#[derive(Debug, Clone, Copy)]
pub struct Trial {
    /// The tangential force that would stop the node.
    pub t_star: f64,
    /// The compressive normal force the strength is taken on (after the normal response).
    pub p: f64,
    /// The force per unit slip rate the step's inertia opposes: m / dt per unit slip rate
    /// (m / (2 dt) on a symmetric fault, whose slip is twice the node's displacement).
    pub z: f64,
    /// s.
    pub dt: f64,
    /// The node's slip since it last healed, m.
    pub slip: f64,
    /// Its slip rate at the half step before, m/s.
    pub v_old: f64,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Law {
    /// mu_s = mu_d = mu.
    Coulomb { mu: f64 },
    /// Amontons with mu_s > mu_d and an explicit event rule.
    /// `paper`: the rule's conventions (ignored by `overdamped`; [`Law::with_paper_options`]
    /// refuses them there).
    StaticKinetic { mu_s: f64, mu_d: f64, rule: Rule, paper: PaperOptions },
    /// Linear slip weakening (Ida 1972, Andrews 1976): a slipping node's coefficient falls
    /// from mu_s to mu_d over the slip distance dc (m) accumulated since it last healed. The
    /// healing rule is the solver's: the quasi-static solver heals a node when it sticks
    /// again, the dynamic commands every node after an event in which one weakened fully.
    SlipWeakening { mu_s: f64, mu_d: f64, dc: f64 },
    /// Rate-and-state friction (explicit solver only: the quasi-static solver is
    /// rate-independent).
    RateState(RateState),
}

impl Law {
    pub fn coulomb(mu: f64) -> Result<Law> {
        if !(mu.is_finite() && mu >= 0.0) {
            return Err(Error::input("mu", format!("{mu} must be a finite number >= 0")));
        }
        if mu > MU_MAX {
            return Err(too_high("mu", mu));
        }
        if mu != 0.0 && mu < MU_MIN {
            return Err(too_low("mu", mu));
        }
        Ok(Law::Coulomb { mu })
    }

    pub fn static_kinetic(mu_s: f64, mu_d: f64, rule: Rule) -> Result<Law> {
        if !(mu_s.is_finite() && mu_s > 0.0) {
            return Err(Error::input("mu-s", format!("{mu_s} must be a finite number > 0")));
        }
        if mu_s > MU_MAX {
            return Err(too_high("mu-s", mu_s));
        }
        if !(mu_d.is_finite() && mu_d > 0.0 && mu_d < mu_s) {
            return Err(Error::input(
                "mu-d",
                format!("{mu_d} must be > 0 and below mu_s = {mu_s} (use --law coulomb for mu_s = mu_d)"),
            ));
        }
        if mu_d < MU_MIN {
            return Err(too_low("mu-d", mu_d));
        }
        Ok(Law::StaticKinetic { mu_s, mu_d, rule, paper: PaperOptions::default() })
    }

    /// The same law with the `paper` rule's conventions `o`; refused (naming the flag) for any
    /// other law or rule unless `o` is the default.
    pub fn with_paper_options(self, o: PaperOptions) -> Result<Law> {
        match self {
            Law::StaticKinetic { mu_s, mu_d, rule: Rule::Paper, .. } => {
                Ok(Law::StaticKinetic { mu_s, mu_d, rule: Rule::Paper, paper: o })
            }
            _ if o == PaperOptions::default() => Ok(self),
            _ => Err(Error::input(
                if o.residual != Residual::Relaxed { "--residual" } else { "--backslip" },
                "belongs to --law static-kinetic --rule paper (the overdamped rule already re-sticks a node that would slip backwards, at the current pressure)",
            )),
        }
    }

    /// The `paper` rule's conventions (the default for every other law).
    pub fn paper_options(&self) -> PaperOptions {
        match *self {
            Law::StaticKinetic { paper, .. } => paper,
            _ => PaperOptions::default(),
        }
    }

    pub fn slip_weakening(mu_s: f64, mu_d: f64, dc: f64) -> Result<Law> {
        Law::static_kinetic(mu_s, mu_d, Rule::Paper)?; // the same bounds on mu_s, mu_d
        if !(dc.is_finite() && dc > 0.0) {
            return Err(Error::input("dc", format!("{dc} m must be a finite slip distance > 0")));
        }
        Ok(Law::SlipWeakening { mu_s, mu_d, dc })
    }

    /// Coefficient of a node that has slipped `slip` (m) since it last stuck.
    pub fn kinetic(&self, slip: f64) -> f64 {
        match *self {
            Law::SlipWeakening { mu_s, mu_d, dc } => mu_s - (mu_s - mu_d) * (slip / dc).clamp(0.0, 1.0),
            _ => self.mu_d(),
        }
    }

    /// d(kinetic)/d(slip) (1/m): the weakening rate while 0 <= slip < D_c, else 0.
    pub fn kinetic_slope(&self, slip: f64) -> f64 {
        match *self {
            Law::SlipWeakening { mu_s, mu_d, dc } if (0.0..dc).contains(&slip) => -(mu_s - mu_d) / dc,
            _ => 0.0,
        }
    }

    /// Whether the law has a static peak above the kinetic level (stick-slip instabilities).
    pub fn weakens(&self) -> bool {
        !matches!(self, Law::Coulomb { .. } | Law::RateState(_))
    }

    /// The quasi-static event rule: static-kinetic's own, else the `paper` rule (the others
    /// have no jump to resolve).
    pub fn rule(&self) -> Rule {
        match *self {
            Law::StaticKinetic { rule, .. } => rule,
            _ => Rule::Paper,
        }
    }

    /// Refuses rate-and-state for the quasi-static event solver, which is rate-independent;
    /// `key` names the law as the user gave it.
    pub fn rate_free(&self, key: &str) -> Result<()> {
        match self {
            Law::RateState(_) => Err(Error::input(
                key,
                "rate-and-state has no rate-free limit for the quasi-static event solver (it creeps at any load): run the dynamic slide under a constant drive velocity, --drive-velocity V",
            )),
            _ => Ok(()),
        }
    }

    /// The rate-free law the quasi-static event solver takes in this law's place for what it
    /// does before an explicit run (the normal load): Coulomb at f_0 for rate-and-state (at
    /// rest under the normal load a node holds up to about f_0 p), else the law itself.
    pub fn rate_free_stand_in(&self) -> Law {
        match *self {
            Law::RateState(r) => Law::Coulomb { mu: r.f0.max(0.0) },
            l => l,
        }
    }

    /// The rate-and-state parameters, if the law is one.
    pub fn rate_state(&self) -> Option<&RateState> {
        match self {
            Law::RateState(r) => Some(r),
            _ => None,
        }
    }

    /// Cohesive-zone size of a slowly moving mode-II crack under slip weakening (Day et al.
    /// 2005, BSSA 95, eq. 5; Palmer & Rice 1973), m: Lambda_0 = (9 pi / 32) G D_c /
    /// ((1 - nu)(tau_p - tau_r)), tau_p = mu_s sigma, tau_r = mu_d sigma, for shear modulus G
    /// (Pa), Poisson's ratio nu and normal stress sigma (Pa). Infinite without weakening.
    pub fn cohesive_zone(&self, shear_modulus: f64, poisson: f64, sigma: f64) -> f64 {
        match *self {
            Law::SlipWeakening { mu_s, mu_d, dc } => {
                9.0 * std::f64::consts::PI / 32.0 * shear_modulus * dc
                    / ((1.0 - poisson) * (mu_s - mu_d) * sigma)
            }
            _ => f64::INFINITY,
        }
    }

    /// The length the mesh must resolve, m: slip weakening's [`Self::cohesive_zone`];
    /// rate-and-state's L_b = G L / ((1 - nu) b sigma) (Dieterich 1992; Rubin & Ampuero
    /// 2005), the process zone of its fronts; infinite for the rate-free laws without
    /// weakening.
    pub fn process_zone(&self, shear_modulus: f64, poisson: f64, sigma: f64) -> f64 {
        match self {
            Law::RateState(r) if r.b > 0.0 => shear_modulus * r.l / ((1.0 - poisson) * r.b * sigma),
            _ => self.cohesive_zone(shear_modulus, poisson, sigma),
        }
    }

    /// The traction-at-split-node rule (Day et al. 2005, BSSA 95) for one node in one explicit
    /// step ([`Trial`]), with the node's rate-and-state state `theta` (s; the other laws leave
    /// it). Returns the friction force T, of the sign of `t_star` (the node's new slip rate is
    /// (|t_star| - |T|) / z), and whether the node slips.
    ///
    /// Rate-free laws: stick if |t_star| <= mu(slip) p, else T = mu(slip) p sign(t_star).
    /// Rate-and-state: |t_star| - z V = p mu(V, theta) solved for V, the state advanced
    /// exactly at constant V over the step, V the mean of the old rate and a predicted one
    /// (the two-pass update of SEM2DPACK and SeisSol); it never sticks.
    #[inline]
    pub fn split_node(&self, s: Trial, theta: &mut f64) -> (f64, bool) {
        if let Law::RateState(r) = self {
            let tau = s.t_star.abs();
            if !(s.p > 0.0) || tau == 0.0 {
                return (0.0, false);
            }
            // z > 0 and p > 0: the solve is bracketed and cannot fail.
            let v_pred = r.solve_rate(tau, s.z, s.p, r.evolve(*theta, s.v_old, s.dt)).unwrap_or(0.0);
            *theta = r.evolve(*theta, 0.5 * (s.v_old + v_pred), s.dt);
            let v = r.solve_rate(tau, s.z, s.p, *theta).unwrap_or(0.0);
            return (sign(s.t_star) * (tau - s.z * v), v > 0.0);
        }
        let strength = self.kinetic(s.slip) * s.p;
        if s.t_star.abs() <= strength {
            (s.t_star, false)
        } else {
            (strength * sign(s.t_star), true)
        }
    }

    /// Static threshold (stuck nodes). Rate-and-state: f_0, its steady-state coefficient at
    /// V_0 (the scale F / (mu_s N) is read on).
    pub fn mu_s(&self) -> f64 {
        match *self {
            Law::Coulomb { mu } => mu,
            Law::StaticKinetic { mu_s, .. } | Law::SlipWeakening { mu_s, .. } => mu_s,
            Law::RateState(r) => r.f0,
        }
    }

    /// Kinetic coefficient (slipping nodes). Rate-and-state: f_0.
    pub fn mu_d(&self) -> f64 {
        match *self {
            Law::Coulomb { mu } => mu,
            Law::StaticKinetic { mu_d, .. } | Law::SlipWeakening { mu_d, .. } => mu_d,
            Law::RateState(r) => r.f0,
        }
    }

    /// The weakening slip D_c, m (slip weakening only).
    pub fn dc(&self) -> Option<f64> {
        match *self {
            Law::SlipWeakening { dc, .. } => Some(dc),
            _ => None,
        }
    }

    pub fn name(&self) -> String {
        match self {
            Law::Coulomb { .. } => "coulomb".into(),
            Law::StaticKinetic { rule: Rule::Paper, paper, .. } => {
                let mut what = String::from("static-kinetic (rule paper");
                if paper.residual != Residual::Relaxed {
                    what += &format!(", residual {}", paper.residual.name());
                }
                if !paper.backslip {
                    what += ", back-slip forbidden";
                }
                what + ")"
            }
            Law::StaticKinetic { rule: Rule::Overdamped, .. } => "static-kinetic (rule overdamped)".into(),
            Law::SlipWeakening { dc, .. } => format!("slip-weakening (D_c = {dc:e} m)"),
            Law::RateState(r) => r.name(),
        }
    }
}

/// sign as numpy's: 0 at 0 (the split-node rule's T at t_star = 0 under a negative strength,
/// possible under the rupture scene's bilateral contact, is 0).
#[inline]
pub fn sign(x: f64) -> f64 {
    if x > 0.0 {
        1.0
    } else if x < 0.0 {
        -1.0
    } else {
        0.0
    }
}

/// Largest friction coefficient accepted: measured ones stay below ~10, and 1e6 is the
/// bonded limit (nothing slips; tests/it/friction.rs); far above, the tangential thresholds
/// dwarf N by so much that the contact updates lose every digit (mu = 2^64 cycled without
/// settling for 8 s, issue 31).
pub const MU_MAX: f64 = 1e6;

fn too_high(what: &str, mu: f64) -> Error {
    Error::input(what, format!("{mu:e} is above {MU_MAX}, far beyond any measured friction coefficient"))
}

/// Smallest nonzero friction coefficient accepted: below, the thresholds mu p are subnormal
/// numbers, 0 to every digit kept and a hundred times slower to compute with.
pub const MU_MIN: f64 = 1e-100;

fn too_low(what: &str, mu: f64) -> Error {
    Error::input(what, format!("{mu:e} is below {MU_MIN:e}, 0 to every digit kept"))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A slider of mass m on the split-node rule, pulled through a stiff spring k whose far end
    /// moves at V1 and then at V2 = 10 V1: the rate-and-state velocity step (Dieterich 1979)
    /// through [`Law::split_node`] as the explicit solvers call it. Returns (slip since the
    /// step / L, mu) after the step.
    fn velocity_step(kind: StateLaw) -> (RateState, Vec<(f64, f64)>) {
        // a sigma / k = 1e-4 L: the spring's stretch changes V by 1e-4 of itself over the
        // decay, so the slider moves at the drive's rate (the stiff-drive limit). The friction's
        // viscosity a sigma / V2 = 1e9 N s/m is 5x the critical 2 sqrt(k m): no ringing.
        let r = RateState::new(0.01, 0.015, 1e-5, 1e-6, 0.6, kind).unwrap();
        let law = Law::RateState(r);
        let (sigma, k, m): (f64, f64, f64) = (1e6, 1e13, 1e3);
        let (v1, v2) = (1e-6, 1e-5);
        let dt = 0.5 * (m / k).sqrt();
        // Steady sliding at V1: theta = L / V1, the spring stretched to mu_ss(V1) sigma / k.
        let mut theta = r.l / v1;
        let (mut x, mut v) = (0.0, v1);
        let mut drive = r.mu_steady(v1) * sigma / k;
        let mut out = vec![];
        let steps = (6.0 * r.l / v2 / dt) as usize;
        for _ in 0..steps {
            drive += v2 * dt;
            let fx = k * (drive - x);
            let trial =
                Trial { t_star: -fx - m * v / dt, p: sigma, z: m / dt, dt, slip: 0.0, v_old: v.abs() };
            let (t, slips) = law.split_node(trial, &mut theta);
            assert!(slips);
            v += dt * (fx + t) / m;
            x += dt * v;
            out.push((x / r.l, -t / sigma));
        }
        (r, out)
    }

    #[test]
    fn the_split_node_rule_gives_the_velocity_step_of_rate_and_state() {
        // Closed forms at slip delta after the step (constant V2): slip law mu - mu_ss(V2) =
        // b ln(V2/V1) e^(-delta/L); aging law b ln(1 + (V2/V1 - 1) e^(-delta/L)). The direct
        // effect: mu jumps by a ln(V2/V1) at once. Deviations: the spring's stretch (1e-4 of
        // V, a 1e-4 change of mu's direct part: 1e-6) and the step's state update, exact at
        // constant V and second order in dt V2 / L = 1.6e-6: far below the 1e-5 allowed.
        for kind in [StateLaw::Aging, StateLaw::Slip] {
            let (r, out) = velocity_step(kind);
            let ratio: f64 = 10.0;
            let (at, peak) = out.iter().copied().fold((0.0, f64::MIN), |m, p| if p.1 > m.1 { p } else { m });
            let before = r.mu_steady(1e-6);
            let direct = peak - before;
            // The slider reaches V2 over a few a sigma / (k V2) = 1e-4 s: by the peak it has
            // slipped `at` L, over which the state part can fall by at most b ln(V2/V1) `at`.
            let bound = r.b * ratio.ln() * at + 1e-6;
            assert!(
                at < 0.01 && (direct - r.a * ratio.ln()).abs() < bound,
                "{kind:?}: direct effect {direct} at {at} L"
            );
            for &(delta, mu) in out.iter().filter(|p| p.0 > 0.05) {
                let want = r.mu_steady(1e-5)
                    + match kind {
                        StateLaw::Slip => r.b * ratio.ln() * (-delta).exp(),
                        StateLaw::Aging => r.b * (1.0 + 9.0 * (-delta).exp()).ln(),
                    };
                assert!((mu - want).abs() < 1e-5, "{kind:?} at slip {delta} L: mu {mu} vs {want}");
            }
            // The new steady state, (a - b) ln(V2/V1) from the old, reached over a few L.
            let last = out.last().unwrap().1;
            assert!((last - before - (r.a - r.b) * ratio.ln()).abs() < 0.01 * r.b * ratio.ln(), "{kind:?}");
        }
    }

    #[test]
    fn the_split_node_rule_is_the_stick_slip_rule_for_the_rate_free_laws() {
        let sw = Law::slip_weakening(0.6, 0.5, 1e-6).unwrap();
        let mut theta = 7.0;
        let trial = |t_star: f64, slip: f64| Trial { t_star, p: 2.0, z: 1.0, dt: 1e-3, slip, v_old: 0.0 };
        assert_eq!(sw.split_node(trial(1.1, 0.0), &mut theta), (1.1, false));
        assert_eq!(sw.split_node(trial(-1.3, 0.0), &mut theta), (-1.2, true));
        assert_eq!(sw.split_node(trial(1.3, 5e-7), &mut theta), (1.1, true));
        assert_eq!(sw.split_node(trial(1.3, 2e-6), &mut theta), (1.0, true));
        assert_eq!(theta, 7.0, "the rate-free laws leave the state alone");
        // A negative strength (a tensile bilateral contact) at t_star = 0: T = 0.
        assert_eq!(sw.split_node(Trial { p: -1.0, ..trial(0.0, 0.0) }, &mut theta), (0.0, true));
    }
}
