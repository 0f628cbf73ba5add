//! What tribofe computes with the engine, each returning numbers for [`crate::report`] to
//! format: the paper's check ([`check`]), mesh and element convergence ([`convergence`]),
//! where methods fail ([`stability`]) and phase timings ([`bench`](mod@bench)).

pub mod bench;
pub mod check;
pub mod convergence;
pub mod dynamic_slide;
pub mod edges;
pub mod precursors_fe;
pub mod slide;
mod slide_arrays;
pub mod stability;
pub mod sweep;
