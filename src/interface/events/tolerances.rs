//! The event solver's tolerances and caps, each with its reason, in one place (they were bare
//! numbers repeated where they are used).

/// Relative tolerance of a state check (equilibrium, p >= 0, gap >= 0, friction bounds), in
/// units of the mean nodal force (forces) or the displacement scale N t/(E* L) (gaps, slips):
/// three orders above the round-off of the dense solve (~1e-12 measured), far below any
/// physical event.
pub const STATE: f64 = 1e-9;

/// A rate (dF/dX, du/dX) counts as zero below this fraction of the largest rate of its kind:
/// rates are differences of affine coefficients, so their round-off scales with the largest.
pub const RATE: f64 = 1e-10;

/// A bordering update whose pivot is below this fraction of the diagonal it came from would
/// amplify round-off: the inverse is refactorised instead.
pub const PIVOT: f64 = 1e-10;

/// A full LU whose smallest pivot is below this fraction of its largest is singular (the
/// interface leaves the block a rigid motion): the round-off of an invertible free system of
/// a few thousand DOFs stays orders above it.
pub const SINGULAR: f64 = 1e-13;

/// Residual of the bordered inverse, relative to the largest coefficient, above which it is
/// refactorised once and the step retried.
pub const RESIDUAL: f64 = 1e-10;

/// Below this many node changes at once, bordering updates (O(m^2) each) beat one full LU
/// (O(m^3)) on every mesh measured; above it the full LU or the spare inverse is considered.
pub const BATCH: usize = 32;

/// Slip weakening: a slipping node's coefficient has converged when it moves by less than
/// this fraction of mu_s in an iterate (fixed point or Newton): four orders above the
/// round-off of the solve, and a slip error of this times mu_s P/k for a node held by k.
pub const COEFFICIENT: f64 = 1e-12;

/// The constrained values' forces g = S b_c are updated change by change and rebuilt in one
/// pass after this many updates, before their round-off accumulates (each update is an axpy
/// of one row of S).
pub const REBUILD: usize = 256;

/// State changes allowed at one load parameter before the run is declared stuck (a cycle):
/// each node may change a few times in a legitimate settle, plus slack for tiny interfaces.
pub fn max_changes(n: usize) -> usize {
    20 * n + 100
}
