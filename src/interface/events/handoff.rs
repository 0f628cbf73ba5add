//! The quasi-static <-> dynamic handoff: the one door into the event solver for a drive that
//! is not its own (`slide --dynamics`, held or at constant velocity).
//!
//! - [`start_drive`]: the active set, the normal phase and the drive phase's start (the one
//!   re-stick rule), as [`super::run`] does them;
//! - [`Recorder`]: every recorded event goes through it, so [`super::Problem::observer`] is
//!   called and [`super::Problem::max_events`] caps alike in every mode;
//! - [`Resolver`]: what happens where a slip-weakening drive meets an instability. The
//!   quasi-static drive (`weakening`) resolves it by its fixed-point relaxation; the held
//!   dynamic mode by an explicit event (`studies::dynamic_slide`);
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
    /// The unstable solution: the last iterate of the relaxation that ran away.
    pub a: &'x Affine,
    /// At the start of the drive step: each node's u, state and coefficient, and F (N/m).
    pub u_pre: &'x [f64],
    pub states_pre: &'x [NodeState],
    pub mu_pre: &'x [f64],
    pub f_pre: f64,
    /// Nodes that slipped at some iterate of the relaxation.
    pub touched: &'x [bool],
    /// Nodes slipped by instabilities since the last cycle end (the resolver updates it).
    pub slipped: &'x mut [bool],
    /// The drive's progress fraction, for a resolver's heartbeat.
    pub shown: f64,
}

/// What the drive does after a resolved instability.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Resolved {
    /// Loading goes on from the static state the resolver left.
    Go,
    /// The run ends here with what is recorded (the resolver says why, to its caller).
    Stop,
}

/// Resolves an instability: leaves the active set static and consistent at the onset's X,
/// records the event through the recorder and counts a cycle end in `rec.out.sliding_events`.
pub(crate) trait Resolver {
    fn resolve(&mut self, sv: &mut Solver, rec: &mut Recorder, at: Onset) -> Result<Resolved>;
}
