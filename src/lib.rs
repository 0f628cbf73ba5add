//! tribofe: a 2D plane-strain finite-element verifier for frictional interfaces.
//!
//! The layers, each depending only on those before it:
//! - [`linalg`]: sparse Cholesky (faer, our multifrontal factorisation, two domains);
//! - [`fem`]: mesh, elements, assembly, constraints, the linear pipeline, recovery;
//! - [`io`]: Gmsh reader, VTU and Gmsh field writers;
//! - [`scene`]: the paper's block and plate, and a general rectangle;
//! - [`studies`]: the paper's check, convergence, stability, benchmarks;
//! - [`report`]: CSV and SVG output of the studies.
//!
//! Beside them: [`analytical`] (closed forms the results are judged against) and
//! [`precursors`] (the paper's 1D friction model).

// `!(x <= limit)` is how the checks treat NaN as a failure; index loops over several arrays
// read more plainly than zipped iterators in the numeric kernels.
#![allow(clippy::neg_cmp_op_on_partial_ord, clippy::needless_range_loop)]

pub mod analytical;
pub mod error;
pub mod fem;
pub mod interface;
pub mod io;
pub mod linalg;
pub mod memory;
pub mod precursors;
pub mod report;
pub mod scene;
pub mod studies;

pub use error::{Error, Result};
