//! tribofe: a 2D plane-strain finite-element verifier for frictional interfaces.
//!
//! The pipeline, one module per stage:
//! mesh ([`mesh`], [`mesher`], [`io`]) -> element ([`element`], [`material`])
//! -> assembly ([`assembly`]) -> constraints ([`constraints`]) -> solve ([`solve`])
//! -> recovery ([`recovery`]) -> report ([`report`]).

pub mod element;
pub mod error;
pub mod io;
pub mod material;
pub mod mesh;
pub mod mesher;

pub use error::{Error, Result};
