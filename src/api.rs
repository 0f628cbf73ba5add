//! The items an embedding program needs, in one place; start here. Everything else stays
//! reachable through its layer (see the crate docs), but a host that sticks to these gets the
//! whole workflow: describe a scene, run a study with progress and a cancel token, read the
//! numbers as arrays, write the command's output files, map errors to exit statuses.
//!
//! Units: SI throughout (lengths m, moduli and stresses Pa, forces per unit depth N/m,
//! displacements m, times s); dimensionless quantities say so in their names (`_over_l`,
//! `_over_mu_s_n`, `fn_ratio`).
//!
//! ```
//! use tribofe::api::*;
//!
//! // The paper's block on a Coulomb interface (mu = 0.5) under N = 1 N/m, driven to sliding.
//! let o = SlideOptions { law: Law::coulomb(0.5)?, ..Default::default() };
//! let r = slide(&Scene::default(), &o, Progress::none())?;
//! let (slip, [states, nodes]) = r.field(StateField::Slip);
//! assert_eq!(slip.len(), states * nodes);
//! # Ok::<(), tribofe::Error>(())
//! ```

/// The scene: block (L, t, H in m; E in Pa; nu), plate (rigid or elastic), loading (N in
/// N/m, F/N ratios) and mesh (h in m, element). `Scene::default()` is the paper's;
/// [`Scene::from_file`] reads a TOML scene (unknown keys refused, naming the line);
/// [`Overrides`] applies command-line style changes; [`Scene::validate`] refuses bad values
/// before any work.
pub use crate::scene::{MeshGeometry, Overrides, PlateModel, Scene};

/// Solver options (ordering, threads) for [`check`]; `Default` is what the command uses.
pub use crate::linalg::solve::SolverOptions;
/// The paper's bonded check: pressure and shear profiles along the base (Pa), the interior
/// slope against the model's 12 (F/N)(H/L) and its corrected form, per load case.
pub use crate::studies::check::{run as check, CheckResult};

/// What an event was (precursor, sliding, crossing...) and its CSV name.
pub use crate::interface::events::EventKind;
/// The friction laws (rate-and-state among them), the normal response and the static-kinetic
/// relaxation rules.
pub use crate::law::{Law, Normal, RateState, Rule, StateLaw};
/// The frictional run: the scene condensed onto its base, then N, then the drive X at height
/// H, event by event. [`SlideOptions`] holds the law (coulomb mu; static-kinetic mu_s, mu_d and
/// the relaxation [`Rule`]; slip-weakening with D_c in m), N in N/m, the end (cycles or X_max
/// in m), the event cap and the [`Cancel`] token. [`LawChoice`] builds a law from a user's
/// names (or the paper's (r, g)). [`SlideResult`] holds the events and states; its arrays:
/// [`SlideResult::field`] (states x nodes, [`StateField`]) and [`SlideResult::event_columns`]
/// ([`EventColumns`]); [`compare_paper`] sets its counts against the paper's model.
pub use crate::studies::slide::{
    compare_paper, run as slide, EventColumns, LawChoice, PaperComparison, SlideOptions, SlideResult,
    StateField,
};

/// The bonded check over a grid of scene parameters (rayon in parallel; shards), each point
/// with its verdicts; `progress` gets each finished [`SweepPoint`].
pub use crate::studies::sweep::{run as sweep, Axis, Param, Point as SweepPoint, SweepOptions};

/// Mesh and element convergence of the check; `progress` gets each finished
/// [`ConvergenceRun`].
pub use crate::studies::convergence::{
    study as converge, Run as ConvergenceRun, StudyOptions as ConvergeOptions,
};

/// The paper's 1D precursor model: parameters (r, g) (dimensionless), the event iteration
/// (forces in units of mu_s N, positions in units of L), n(r, g) and the fig. 5 map.
pub use crate::precursors::{n_map, n_precursors, simulate, Params as PrecursorParams};
/// The paper's figs. 4 and 5 from the frictional FE (both rules; one cell per (r, g)) and the
/// series (thin layer t/L, drive height H/L, slip-weakening D_c), each with progress and
/// cancel.
pub use crate::studies::precursors_fe::{dc_series, fig4, fig5, heights, thin_layer, Cell, Fig4, SeriesRow};

/// Explicit elastodynamics of a block on a rigid flat with slip-weakening friction: the
/// rupture scene (m, Pa, kg/m^3, s) and its result (arrival times in s, slip in m, energies
/// in J/m).
pub use crate::dynamics::rupture::{run as rupture, RuptureResult, RuptureSpec};

/// Stopping a long run from another thread or from its progress callback, and the one
/// progress callback type every long run takes.
pub use crate::cancel::Cancel;
pub use crate::progress::{Progress, Tick};

/// One error type (every message names the parameter, file or line to change) and the exit
/// statuses a command maps it to (`Error::exit_status`: 2 input, 3 numerical, 4 output, 130
/// interrupted).
pub use crate::error::{exit, Error, Result};

/// Output folders written whole or not at all ([`OutDir::begin`], [`OutDir::commit`]; a
/// [`Cleanup`] handle removes one from an interrupt handler), and the writers of each study's
/// files: [`crate::report`] (`report::check::write`, `report::slide::write`,
/// `report::sweep::csv`, `report::convergence::write`, `report::rupture::write`, the
/// precursor reports), each writing CSV and SVG into a folder.
pub use crate::io::outdir::{Cleanup, OutDir};
