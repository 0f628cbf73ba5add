//! Stopping a long run from outside it: a host (a Python interrupt key, a GUI's stop button, a
//! time limit) holds a clone of the [`Cancel`] token it passed in the run's options and calls
//! [`Cancel::cancel`]; the run checks the token at each progress point and returns
//! [`Error::Interrupted`] without writing anything. No process-wide state: each run has its own.

use crate::error::{Error, Result};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

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

/// How often a long loop looks at its token and reports progress, in wall time, whatever one
/// iteration costs: a host's interrupt lands within about this (plus one iteration).
pub const BEAT: Duration = Duration::from_millis(100);

/// The cadence of a long loop of cheap iterations (explicit steps): [`Beat::due`] is called
/// every iteration and costs a counter increment; every `stride` calls it reads the clock,
/// and once [`BEAT`] has passed it checks the token and says so, for the loop to report its
/// progress. The stride adapts so that the clock is read about every [`BEAT`]/8: a check
/// every N steps, fixed, was 40 s apart on a large mesh and a millisecond on a small one.
#[derive(Debug)]
pub struct Beat<'a> {
    cancel: &'a Cancel,
    count: u32,
    stride: u32,
    read: Instant,
    beat: Instant,
}

impl<'a> Beat<'a> {
    pub fn new(cancel: &'a Cancel) -> Beat<'a> {
        let now = Instant::now();
        // The first call is a beat: a token cancelled before the loop stops it at once.
        Beat { cancel, count: 0, stride: 1, read: now, beat: now.checked_sub(BEAT).unwrap_or(now) }
    }

    /// `Err(Error::Interrupted)` once cancelled (seen within about [`BEAT`]); `Ok(true)` when a
    /// beat has passed (report progress now), `Ok(false)` otherwise.
    #[inline]
    pub fn due(&mut self) -> Result<bool> {
        self.count += 1;
        if self.count < self.stride {
            return Ok(false);
        }
        self.count = 0;
        let now = Instant::now();
        let since = now - self.read;
        self.read = now;
        // Aim at BEAT/8 between clock reads: double the stride below BEAT/16, halve above BEAT/4.
        if since < BEAT / 16 {
            self.stride = self.stride.saturating_mul(2).min(1 << 20);
        } else if since > BEAT / 4 {
            self.stride = (self.stride / 2).max(1);
        }
        if now - self.beat < BEAT {
            return Ok(false);
        }
        self.beat = now;
        self.cancel.check()?;
        Ok(true)
    }
}

impl Cancel {
    /// The wall-clock cadence of a loop holding this token ([`Beat`]).
    pub fn beat(&self) -> Beat<'_> {
        Beat::new(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Iterations of very different costs all see a cancel within a few beats.
    #[test]
    fn a_beat_sees_a_cancel_within_its_period_whatever_an_iteration_costs() {
        for work in [Duration::ZERO, Duration::from_micros(50), Duration::from_millis(7)] {
            let c = Cancel::new();
            let mut b = c.beat();
            let t0 = Instant::now();
            let mut cancelled_at = None;
            let end = loop {
                if t0.elapsed() > Duration::from_millis(300) && cancelled_at.is_none() {
                    c.cancel();
                    cancelled_at = Some(Instant::now());
                }
                let until = Instant::now() + work;
                while Instant::now() < until {}
                if b.due().is_err() {
                    break Instant::now();
                }
                assert!(t0.elapsed() < Duration::from_secs(3), "no interrupt seen ({work:?} a step)");
            };
            let late = end - cancelled_at.unwrap();
            assert!(late < 2 * BEAT, "{work:?} a step: seen {late:?} after the cancel");
        }
    }

    #[test]
    fn a_clone_sees_the_cancel() {
        let host = Cancel::new();
        let run = host.clone();
        assert!(run.check().is_ok());
        host.cancel();
        assert!(matches!(run.check(), Err(Error::Interrupted)));
    }
}
