//! One progress channel for every long run (slide, the precursor figures and series, sweep,
//! converge, edges, stability, the rupture scene): a borrowed callback receiving a [`Tick`]
//! (the fraction done when the run can tell, a short message, and for studies made of finished
//! points the point itself, typed). `Sync`, so a parallel sweep can call it from any thread.
//!
//! Cancellation stays apart, in the run's options ([`crate::Cancel`]): a token is owned data
//! that a run clones into its workers and a host keeps after the call, while a callback is
//! borrowed for the call only. A host that wants to stop from inside its callback captures a
//! clone of the token there and cancels it; the run stops at its next progress point.

/// One progress report.
#[derive(Debug)]
pub struct Tick<'a, T: ?Sized = ()> {
    /// Fraction of the run done, in [0, 1] (dimensionless); `None` when the run cannot tell
    /// (a study whose steps differ widely in cost).
    pub fraction: Option<f64>,
    /// What was just done, for a log line ("" when nothing to say).
    pub message: &'a str,
    /// The finished point of a study made of points (a sweep's point, a convergence run).
    pub item: Option<&'a T>,
}

/// What a host passes to [`Progress::new`]: called with each tick, from any thread.
pub type Callback<'a, T = ()> = dyn Fn(&Tick<'_, T>) + Sync + 'a;

/// The progress callback of a long run, or none ([`Progress::none`]). Cheap to copy.
pub struct Progress<'a, T: ?Sized = ()> {
    f: Option<&'a Callback<'a, T>>,
}

impl<T: ?Sized> Clone for Progress<'_, T> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<T: ?Sized> Copy for Progress<'_, T> {}

impl<T: ?Sized> Default for Progress<'_, T> {
    fn default() -> Self {
        Progress { f: None }
    }
}

impl<T: ?Sized> std::fmt::Debug for Progress<'_, T> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(if self.f.is_some() { "Progress(callback)" } else { "Progress(none)" })
    }
}

impl<'a, T: ?Sized> Progress<'a, T> {
    /// No callback: the run reports nothing.
    pub fn none() -> Self {
        Progress { f: None }
    }

    /// Calls `f` at each progress point.
    pub fn new(f: &'a Callback<'a, T>) -> Self {
        Progress { f: Some(f) }
    }

    /// Reports a tick.
    pub fn tick(&self, t: &Tick<'_, T>) {
        if let Some(f) = self.f {
            f(t)
        }
    }

    /// Reports the fraction done, in [0, 1] (clamped; a NaN is reported as `None`).
    pub fn fraction(&self, x: f64) {
        self.tick(&Tick { fraction: clamp(x), message: "", item: None })
    }

    /// Reports a message (the fraction unknown).
    pub fn message(&self, m: &str) {
        self.tick(&Tick { fraction: None, message: m, item: None })
    }

    /// Reports a finished point and the fraction done.
    pub fn item(&self, item: &T, fraction: f64) {
        self.tick(&Tick { fraction: clamp(fraction), message: "", item: Some(item) })
    }

    /// A callback of another payload that forwards the fraction and message of each tick
    /// here (its item dropped), for a study that runs another as one of its steps.
    pub fn forward<'s, U: ?Sized>(&'s self) -> impl Fn(&Tick<'_, U>) + Sync + 's
    where
        'a: 's,
    {
        move |t: &Tick<'_, U>| self.tick(&Tick { fraction: t.fraction, message: t.message, item: None })
    }
}

fn clamp(x: f64) -> Option<f64> {
    (!x.is_nan()).then(|| x.clamp(0.0, 1.0))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Mutex;

    #[test]
    fn ticks_reach_the_callback_clamped_and_typed() {
        let seen = Mutex::new(Vec::new());
        let f = |t: &Tick<'_, usize>| {
            seen.lock().unwrap().push((t.fraction, t.message.to_string(), t.item.copied()))
        };
        let p = Progress::new(&f);
        p.fraction(1.5);
        p.fraction(f64::NAN);
        p.message("half");
        p.item(&7, 0.25);
        Progress::<usize>::none().fraction(0.5); // reaches nobody
        let seen = seen.into_inner().unwrap();
        assert_eq!(
            seen,
            vec![
                (Some(1.0), String::new(), None),
                (None, String::new(), None),
                (None, "half".to_string(), None),
                (Some(0.25), String::new(), Some(7)),
            ]
        );
    }

    #[test]
    fn forward_keeps_fraction_and_message() {
        let seen = Mutex::new(Vec::new());
        let f = |t: &Tick<'_>| seen.lock().unwrap().push((t.fraction, t.message.to_string()));
        {
            let outer = Progress::new(&f);
            let g = outer.forward::<str>();
            Progress::<str>::new(&g).item("a point", 0.5);
        }
        assert_eq!(seen.into_inner().unwrap(), vec![(Some(0.5), String::new())]);
    }
}
