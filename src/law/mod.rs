//! Friction laws of the interface. Each is named in the outputs by [`Law::name`].

pub mod rate_state;

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

#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Law {
    /// mu_s = mu_d = mu.
    Coulomb { mu: f64 },
    /// Amontons with mu_s > mu_d and an explicit event rule.
    /// `paper`: the rule's conventions (ignored by `overdamped`; [`Law::with_paper_options`]
    /// refuses them there).
    StaticKinetic { mu_s: f64, mu_d: f64, rule: Rule, paper: PaperOptions },
    /// Linear slip weakening: a slipping node's coefficient falls from mu_s to mu_d over the
    /// slip distance dc (m) accumulated since it last stuck; a node heals to mu_s when it
    /// sticks again.
    SlipWeakening { mu_s: f64, mu_d: f64, dc: f64 },
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
        !matches!(self, Law::Coulomb { .. })
    }

    /// Static threshold (stuck nodes).
    pub fn mu_s(&self) -> f64 {
        match *self {
            Law::Coulomb { mu } => mu,
            Law::StaticKinetic { mu_s, .. } | Law::SlipWeakening { mu_s, .. } => mu_s,
        }
    }

    /// Kinetic coefficient (slipping nodes).
    pub fn mu_d(&self) -> f64 {
        match *self {
            Law::Coulomb { mu } => mu,
            Law::StaticKinetic { mu_d, .. } | Law::SlipWeakening { mu_d, .. } => mu_d,
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
        }
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
