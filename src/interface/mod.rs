//! The frictional interface between the block's base and a rigid flat: unilateral contact
//! and friction laws acting on the interface DOFs only. The block and plate are condensed
//! once onto those DOFs ([`condense`]); the laws ([`crate::law`]) and the event-driven quasi-static
//! solver ([`events`]) then work on that small dense system. This layer knows nothing of
//! the CLI, reports or files.

pub mod banded;
pub mod condense;
pub mod events;
