//! Sparse symmetric positive definite solvers: faer's Cholesky behind one interface
//! ([`solve`]), our multifrontal numeric factorisation on faer's symbolic structure
//! ([`multifrontal`]) and the two-domain solver that puts both cores on it ([`substructure`]);
//! a banded LU with partial pivoting for the event solver's unsymmetric systems ([`banded`]).
//! Knows matrices and orderings ([`pattern`]), not meshes: nothing here imports another layer.

pub mod banded;
pub mod multifrontal;
pub mod pattern;
pub mod solve;
pub mod substructure;

/// A numeric factorisation met a pivot that is not positive: the matrix is not positive
/// definite (a rigid mode left free, or a material that is not). `unknown` is the pivot's
/// unknown in the numbering of the matrix the caller gave, so the caller can name its node.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct NonPositivePivot {
    pub unknown: usize,
}

impl std::fmt::Display for NonPositivePivot {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "non-positive pivot at unknown {}", self.unknown)
    }
}

impl std::error::Error for NonPositivePivot {}
