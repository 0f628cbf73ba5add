//! Explicit elastodynamics of the block and its frictional base (issue 33, first part).
//!
//! - [`waves`]: the body-wave and Rayleigh speeds the solver is judged against;
//! - [`explicit`]: lumped-mass central differences (Newmark beta = 0, gamma = 1/2) on QUA4
//!   meshes, Kelvin-Voigt damping, the stable time step, energies: the crate's one time loop,
//!   with boundary conditions as [`explicit::Boundary`] hooks;
//! - the friction laws and the split-node rule are the law layer's ([`crate::law`]);
//! - [`driven`]: one dynamic event of the plate-driven block (the plate and base as a hook);
//! - [`rupture`]: the base on a rigid flat with friction imposed per node per step (the
//!   traction-at-split-node rule of Day et al. 2005) and the shared cross-check scene
//!   "rupture" (arrival times, force drop, front speed).
//!
//! Units SI throughout. The formulation, tolerances and measured numbers are in
//! docs/dynamics.md.

pub mod driven;
pub mod explicit;
pub mod rupture;
pub mod waves;
