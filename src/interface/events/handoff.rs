//! The quasi-static <-> dynamic handoff: the one door into the event solver for a drive that
//! is not its own (`slide --dynamics`, held or at constant velocity).
//!
//! - [`start_drive`]: the active set, the normal phase and the drive phase's start (the one
//!   re-stick rule), as [`super::run`] does them;
//! - [`Recorder`]: every recorded event goes through it, so [`super::Problem::observer`] is
//!   called and [`super::Problem::max_events`] caps alike in every mode;
//! - [`Resolver`]: what happens where a drive meets an instability. The quasi-static drives
//!   resolve it by the static-kinetic rules (`relax`: the paper's, overdamped) or the
//!   slip-weakening fixed-point relaxation (`weakening`); the held dynamic mode by an
//!   explicit event (`studies::dynamic_slide`);
//! - [`drive_stepped`]: the drive loop at a fixed slip step per node (D_c / N), the held
//!   mode's static loading, which calls a [`Resolver`] at each instability.

pub(crate) use super::active::Solver;
pub(crate) use super::classify::crossed;
pub(crate) use super::operator::Affine;
pub(crate) use super::simulation::{settle_continuous, start_drive, Recorder};
pub(crate) use super::stepped::{drive as drive_stepped, Ended};
use super::NodeState;
use crate::error::Result;

/// Where a drive found an instability, at fixed X.
pub(crate) struct Onset<'x> {
    /// X (m).
    pub lam: f64,
    /// The solution where it was found (see [`Found`]).
    pub a: &'x Affine,
    /// The states and F (N/m) before it: at the start of the drive step.
    pub states_pre: &'x [NodeState],
    pub f_pre: f64,
    pub found: Found<'x>,
    /// Nodes slipped by instabilities since the last cycle end (the resolver updates it).
    pub slipped: &'x mut [bool],
    /// The drive's progress fraction, for a resolver's heartbeat.
    pub shown: f64,
}

/// How the drive found the instability.
pub(crate) enum Found<'x> {
    /// A stuck node past its static threshold, `a` the consistent solution (static-kinetic).
    Threshold { node: usize },
    /// The slip-weakening fixed point ran away, `a` its last iterate; at the step's start each
    /// node's u and coefficient, and the nodes slipping at some iterate.
    Runaway { u_pre: &'x [f64], mu_pre: &'x [f64], touched: &'x [bool] },
}

/// What the drive does after a resolved instability.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Resolved {
    /// Loading goes on from the static state the resolver left.
    Go,
    /// The nucleating node slides on at mu_d instead (static-kinetic's Zeno guard): nothing
    /// recorded yet, the drive records the creep once the contact around it is consistent.
    Creep(usize),
    /// The run ends here with what is recorded (the resolver says why, to its caller).
    Stop,
}

/// Resolves an instability: leaves the active set static and consistent at the onset's X,
/// records the event through the recorder and counts a cycle end in `rec.out.sliding_events`.
pub(crate) trait Resolver {
    fn resolve(&mut self, sv: &mut Solver, rec: &mut Recorder, at: Onset) -> Result<Resolved>;
}
