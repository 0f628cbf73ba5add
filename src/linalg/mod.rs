//! Sparse symmetric positive definite solvers: faer's Cholesky behind one interface
//! ([`solve`]), our multifrontal numeric factorisation on faer's symbolic structure
//! ([`multifrontal`]) and the two-domain solver that puts both cores on it ([`substructure`]).
//! Knows matrices and orderings, not meshes.

pub mod multifrontal;
pub mod solve;
pub mod substructure;
