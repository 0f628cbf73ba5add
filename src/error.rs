//! One error type for the whole library. Every variant names what was wrong and where
//! (parameter, file and line, node and component) so the CLI can print it as is, and maps to
//! one documented exit status ([`Error::exit_status`]). Its text (`Display`) has every control
//! byte of an input (a scene string, a file name) escaped ([`quote_lines`]), for the terminal
//! and for the Python layer alike.

use std::path::PathBuf;

/// Exit statuses of the `tribofe` command (README, "Inputs and failures").
pub mod exit {
    /// Success.
    pub const OK: i32 = 0;
    /// Bad input: a parameter, scene key, mesh or option refused, an unreadable input file,
    /// a problem above the size limit, an output folder that cannot be used.
    pub const INPUT: i32 = 2;
    /// Numerical refusal: a singular or ill-conditioned system, a failed self-check.
    pub const NUMERICAL: i32 = 3;
    /// An I/O failure while writing results (disk full, permissions...), or a resource the
    /// system refused (threads).
    pub const OUTPUT: i32 = 4;
    /// Incomplete: the run met a cap (events, an event's steps) after it started; what it had
    /// computed up to there is written, and the cap is named on stderr and in run.toml
    /// (`[results] incomplete`).
    pub const INCOMPLETE: i32 = 5;
    /// Interrupted by SIGINT or SIGTERM (128 + SIGINT, as shells report it).
    pub const INTERRUPTED: i32 = 130;
    /// Standard output closed before everything was printed (`tribofe check | head -1`);
    /// 128 + SIGPIPE, as shells report a process ended by a closed pipe. The results were
    /// written to disk before anything was printed.
    pub const BROKEN_PIPE: i32 = 141;
}

#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A parameter outside its physical or numerical range; `what` is the name the user gave
    /// (`--h`, `block.thickness`...).
    #[error("invalid {}: {}", quote_lines(.what), quote_lines(.why))]
    Input { what: String, why: String },

    /// A file that could not be parsed; `at` is "line N" (text) or "byte N" (binary).
    #[error("{}: {}: {}", path_text(.file), quote_lines(.at), quote_lines(.msg))]
    Parse { file: PathBuf, at: String, msg: String },

    /// A mesh that cannot be used (degenerate element, unknown set, a geometry that
    /// contradicts the scene...).
    #[error("mesh: {}", quote_lines(.0))]
    Mesh(String),

    /// The problem would not fit: estimated unknowns and memory against the limit.
    #[error("problem too large: about {dofs:.3e} unknowns and {} estimated, above the limit of {limit} unknowns (--max-dofs); {}", bytes_text(*gib * (1u64 << 30) as f64), quote_lines(.suggestion))]
    TooLarge { dofs: f64, gib: f64, limit: usize, suggestion: String },

    /// The reduced stiffness matrix is not positive definite; `node` (tag) and `component`
    /// (0 = u, 1 = v) name the first bad pivot when it is a node's DOF.
    #[error("the boundary conditions leave the body free to move: {}", quote_lines(.detail))]
    Singular { detail: String, node: Option<u64>, component: Option<usize> },

    /// The solve went through but its residual says the answer cannot be trusted.
    #[error("untrustworthy solution: {}; {}", quote_lines(.detail), quote_lines(.hint))]
    Untrustworthy { detail: String, hint: String },

    /// A frictional run needed more events than its cap before reaching its end.
    /// `f_peak_over_n`: the largest F/N reached up to the cap. No precursor count: that is the
    /// one definition's ([`crate::precursors::definition`]), which a caller applies to the
    /// events an [`crate::interface::events::Observer`] saw (the fig. 5 study does).
    #[error("the run needs more than {cap} events (stopped at X = {x:.6e} m, F/N = {f_over_n:.6}, after a peak F/N = {f_peak_over_n:.6}); raise --max-events or lower --x-max/--cycles")]
    EventCap { cap: usize, x: f64, f_over_n: f64, f_peak_over_n: f64 },

    /// A self-check of the results (global balance...) failed beyond its threshold.
    #[error("self-check failed: {} = {value:.2e} exceeds {limit:.1e}; {}", quote_lines(.what), quote_lines(.hint))]
    SelfCheck { what: String, value: f64, limit: f64, hint: String },

    /// A chart that could not be drawn.
    #[error("{}: cannot draw the chart: {}", quote_lines(.file), quote_lines(.msg))]
    Plot { file: String, msg: String },

    /// An input file that cannot be read.
    #[error("cannot read {}: {source}", path_text(.path))]
    Read { path: PathBuf, source: std::io::Error },

    /// An output folder that cannot be used (a file of that name, another run's lock...).
    #[error("output folder {}: {}", path_text(.path), quote_lines(.why))]
    Output { path: PathBuf, why: String },

    /// Writing results failed.
    #[error("{}: {source}", path_text(.path))]
    Io { path: PathBuf, source: std::io::Error },

    /// The system refused a resource (a thread pool...).
    #[error("the system refused {}: {}", quote_lines(.what), quote_lines(.why))]
    Resource { what: String, why: String },

    /// A run met a cap after it started; its partial results were written (exit status 5).
    #[error("incomplete: {}; the results up to there are written and run.toml names the cap", quote_lines(.what))]
    Incomplete { what: String },

    /// SIGINT or SIGTERM arrived; temporaries were removed.
    #[error("interrupted; temporaries removed, the output folder is as before (or complete, if the run had finished)")]
    Interrupted,
}

impl Error {
    pub fn input(what: impl Into<String>, why: impl Into<String>) -> Self {
        Error::Input { what: what.into(), why: why.into() }
    }
    pub fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        Error::Io { path: path.into(), source }
    }
    pub fn read(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        Error::Read { path: path.into(), source }
    }
    pub fn plot(file: impl Into<String>, msg: impl std::fmt::Display) -> Self {
        Error::Plot { file: file.into(), msg: msg.to_string() }
    }

    /// The exit status documented in README ("Inputs and failures") and `tribofe --help`.
    pub fn exit_status(&self) -> i32 {
        match self {
            Error::Input { .. }
            | Error::Parse { .. }
            | Error::Mesh(_)
            | Error::TooLarge { .. }
            | Error::Read { .. }
            | Error::Output { .. }
            | Error::EventCap { .. } => exit::INPUT,
            Error::Singular { .. } | Error::Untrustworthy { .. } | Error::SelfCheck { .. } => exit::NUMERICAL,
            Error::Plot { .. } | Error::Io { .. } | Error::Resource { .. } => exit::OUTPUT,
            Error::Incomplete { .. } => exit::INCOMPLETE,
            Error::Interrupted => exit::INTERRUPTED,
        }
    }
}

/// `Ok` for a finite value above zero, else the refusal naming `what` (a parameter or flag).
pub fn positive(what: &str, v: f64) -> Result<()> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(Error::input(what, format!("{v} must be a positive number")))
    }
}

/// `Ok` for a positive value in [1e-100, 1e100] (`unit` its unit), else the refusal naming
/// `what`: lengths and moduli far outside it under- or overflow in the element products
/// (h^2, E h^2) before any check can see it; physical values are far inside.
pub fn scaled(what: &str, v: f64, unit: &str) -> Result<()> {
    positive(what, v)?;
    if (1e-100..=1e100).contains(&v) {
        Ok(())
    } else {
        Err(Error::input(
            what,
            format!("{} {unit} is outside [1e-100, 1e100] {unit}, where double precision holds the stiffness; check the units", num(v)),
        ))
    }
}

/// A value for a message: plain in [1e-4, 1e6), else in scientific notation.
pub fn num(v: f64) -> String {
    if v == 0.0 || (1e-4..1e6).contains(&v.abs()) {
        format!("{v}")
    } else {
        format!("{v:.4e}")
    }
}

/// Quotes text taken from an input file or argument for a message: control characters
/// (ESC, NUL...) are escaped so nothing read from input can drive the terminal.
pub fn quote(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    for c in s.chars() {
        if c.is_control() {
            // `\x1b` for the C0 controls and DEL, as a shell's $'...' writes them.
            if (c as u32) < 0x80 {
                out.push_str(&format!("\\x{:02x}", c as u32));
            } else {
                out.extend(c.escape_unicode());
            }
        } else {
            out.push(c);
        }
    }
    out
}

/// A path for a message, quoted ([`quote`]): a file name may hold any byte but `/` and NUL.
fn path_text(p: &std::path::Path) -> String {
    quote(&p.display().to_string())
}

/// Quotes a whole message for a terminal: as [`quote`], but line breaks and tabs kept. Every
/// message, warning and printed table goes through it on its way out.
pub fn quote_lines(s: &str) -> String {
    if !s.chars().any(|c| c.is_control() && c != '\n' && c != '\t') {
        return s.to_string();
    }
    s.split('\n')
        .map(|l| l.split('\t').map(quote).collect::<Vec<_>>().join("\t"))
        .collect::<Vec<_>>()
        .join("\n")
}

pub type Result<T> = std::result::Result<T, Error>;

/// `bytes` in the binary unit that fits (GiB, MiB, KiB), so that the small limits of a tight
/// `ulimit -v` do not read "0.0 GiB".
pub fn bytes_text(bytes: f64) -> String {
    const KIB: f64 = 1024.0;
    match bytes {
        b if b >= KIB * KIB * KIB => format!("{:.1} GiB", b / (KIB * KIB * KIB)),
        b if b >= KIB * KIB => format!("{:.1} MiB", b / (KIB * KIB)),
        b if b >= KIB => format!("{:.1} KiB", b / KIB),
        b => format!("{b:.0} bytes"),
    }
}
