//! Stopping a long run from outside it: a host (a Python interrupt key, a GUI's stop button, a
//! time limit) holds a clone of the [`Cancel`] token it passed in the run's options and calls
//! [`Cancel::cancel`]; the run checks the token at each progress point and returns
//! [`Error::Interrupted`] without writing anything. No process-wide state: each run has its own.

use crate::error::{Error, Result};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// A cancellation flag shared between a host and the runs it started (cheap to clone).
#[derive(Debug, Clone, Default)]
pub struct Cancel(Arc<AtomicBool>);

impl Cancel {
    pub fn new() -> Cancel {
        Cancel::default()
    }

    /// Asks every run holding this token to stop at its next progress point.
    pub fn cancel(&self) {
        self.0.store(true, Ordering::Relaxed);
    }

    pub fn is_cancelled(&self) -> bool {
        self.0.load(Ordering::Relaxed)
    }

    /// `Err(Error::Interrupted)` once cancelled.
    pub fn check(&self) -> Result<()> {
        if self.is_cancelled() {
            Err(Error::Interrupted)
        } else {
            Ok(())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_clone_sees_the_cancel() {
        let host = Cancel::new();
        let run = host.clone();
        assert!(run.check().is_ok());
        host.cancel();
        assert!(matches!(run.check(), Err(Error::Interrupted)));
    }
}
