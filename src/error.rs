//! One error type for the whole library. Every variant names what was wrong and where
//! (file and line, element and nodes, DOF and node) so the CLI can print it as is.

use std::path::PathBuf;

#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A parameter outside its physical or numerical range.
    #[error("invalid {what}: {why}")]
    Input { what: String, why: String },

    /// A file that could not be parsed; `at` is "line N" (text) or "byte N" (binary).
    #[error("{}: {at}: {msg}", file.display())]
    Parse { file: PathBuf, at: String, msg: String },

    /// A mesh that cannot be used (degenerate element, unknown set, empty mesh...).
    #[error("mesh: {0}")]
    Mesh(String),

    /// The reduced stiffness matrix is not positive definite.
    #[error("the boundary conditions leave the body free to move: {detail}")]
    Singular { detail: String },

    /// The solve went through but its residual says the answer cannot be trusted.
    #[error("untrustworthy solution: {detail}; {hint}")]
    Untrustworthy { detail: String, hint: String },

    #[error("{}: {source}", path.display())]
    Io { path: PathBuf, source: std::io::Error },
}

impl Error {
    pub fn input(what: impl Into<String>, why: impl Into<String>) -> Self {
        Error::Input { what: what.into(), why: why.into() }
    }
    pub fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        Error::Io { path: path.into(), source }
    }
}

pub type Result<T> = std::result::Result<T, Error>;
