//! tribofe: a 2D plane-strain finite-element verifier for frictional interfaces.
//!
//! **Embedding tribofe? Start with [`api`]**: the curated items (scene, check, slide, sweep,
//! converge, the precursor studies, the rupture scene, cancel, progress, errors, output
//! folders), each documented with its units. The layers below stay public.
//!
//! The layers, each depending only on those before it:
//! - [`linalg`]: sparse Cholesky (faer, our multifrontal factorisation, two domains);
//! - [`fem`]: mesh, elements, assembly, constraints, the linear pipeline, recovery;
//! - [`io`]: Gmsh reader, VTU and Gmsh field writers;
//! - [`scene`]: the paper's block and plate, and a general rectangle;
//! - [`interface`]: contact and friction laws on the block's base, event-driven (condensed
//!   from the scene's block and plate);
//! - [`dynamics`]: explicit elastodynamics of the block with friction on its base
//!   (docs/dynamics.md);
//! - [`studies`]: the paper's check, convergence, stability, benchmarks;
//! - [`report`]: CSV and SVG output of the studies.
//!
//! Beside them: [`analytical`] (closed forms the results are judged against), [`precursors`]
//! (the paper's 1D friction model), [`numeric`] (helpers on sampled profiles), [`cancel`] (a
//! host's token to stop a long run) and [`progress`] (the one progress callback of every long
//! run). `tests/it/layering.rs` checks that no module imports a layer above its own.
//!
//! # Examples
//!
//! The paper's bonded check (L = 40 cm, t = 2 mm, H = 4 cm, F/N = 0, 0.41, 0.82): the
//! interior pressure slope is within 2 % of the model's 12 (F/N)(H/L) (1.8 % low: the
//! block's own shear couple shortens the arm to H - t/2, see [`analytical::thin_layer`]).
//! ```
//! use tribofe::{linalg::solve::SolverOptions, scene::Scene, studies::check};
//!
//! let (result, _model) = check::run(&Scene::default(), &SolverOptions::default())?;
//! for case in &result.cases {
//!     let m = &case.metrics;
//!     assert!((m.slope_interior - m.slope_model).abs() <= 0.02 * m.slope_model + 1e-6);
//! }
//! # Ok::<(), tribofe::Error>(())
//! ```
//!
//! The same block on a Coulomb interface (mu = 0.5) under N = 1 N/m, driven until it
//! slides: the friction force reaches mu N.
//! ```
//! use tribofe::{law::Law, scene::Scene, studies::slide};
//!
//! let opts = slide::SlideOptions { law: Law::coulomb(0.5)?, ..Default::default() };
//! let r = slide::run(&Scene::default(), &opts, tribofe::Progress::none())?;
//! let f_max = r.run.states.iter().map(|s| s.f).fold(0.0, f64::max);
//! assert!((f_max - 0.5).abs() < 1e-9);
//! # Ok::<(), tribofe::Error>(())
//! ```

pub mod analytical;
pub mod api;
pub mod cancel;
pub mod dynamics;
pub mod error;
pub mod fem;
pub mod interface;
pub mod io;
pub mod law;
pub mod linalg;
pub mod memory;
pub mod numeric;
pub mod precursors;
pub mod progress;
pub mod report;
pub mod scene;
pub mod studies;

pub use cancel::Cancel;
pub use error::{Error, Result};
pub use progress::{Progress, Tick};
