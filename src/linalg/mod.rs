//! Sparse symmetric positive definite solvers: faer's Cholesky behind one interface
//! ([`solve`]), our multifrontal numeric factorisation on faer's symbolic structure
//! ([`multifrontal`]) and the two-domain solver that puts both cores on it ([`substructure`]).
//! Knows matrices and orderings ([`pattern`]), not meshes: nothing here imports another layer.

pub mod multifrontal;
pub mod pattern;
pub mod solve;
pub mod substructure;
