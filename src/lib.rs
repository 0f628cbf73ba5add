//! tribofe: a 2D plane-strain finite-element verifier for frictional interfaces.
//!
//! The pipeline, one module per stage:
//! mesh ([`mesh`], [`mesher`], [`io`]) -> element ([`element`], [`material`])
//! -> assembly ([`assembly`]) -> constraints ([`constraints`]) -> solve ([`solve`])
//! -> recovery ([`recovery`]) -> report ([`report`]).
//! Closed-form corner and end-decay theory to judge the results against: [`analytical`].

// `!(x <= limit)` is how the checks treat NaN as a failure; index loops over several arrays
// read more plainly than zipped iterators in the numeric kernels.
#![allow(clippy::neg_cmp_op_on_partial_ord, clippy::needless_range_loop)]

pub mod analytical;
pub mod assembly;
pub mod bench;
pub mod check;
pub mod constraints;
pub mod convergence;
pub mod element;
pub mod error;
pub mod io;
pub mod loads;
pub mod material;
pub mod memory;
pub mod mesh;
pub mod mesher;
pub mod multifrontal;
pub mod ordering;
pub mod precursors;
pub mod problem;
pub mod recovery;
pub mod rectangle;
pub mod report;
pub mod scene;
pub mod solve;
pub mod stability;
pub mod substructure;

pub use error::{Error, Result};
