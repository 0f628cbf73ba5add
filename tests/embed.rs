//! A host stopping the library's long runs through its [`tribofe::Cancel`] token: the run
//! returns `Error::Interrupted` at its next progress point, whatever thread cancels.

use std::sync::atomic::{AtomicUsize, Ordering};
use tribofe::interface::law::{Law, Rule};
use tribofe::scene::Scene;
use tribofe::studies::slide::{self, SlideOptions};
use tribofe::{Cancel, Error};

#[test]
fn a_slide_cancelled_from_its_progress_stops_at_the_next_event() {
    // The paper's law and scene run 31 events to the first whole slip (cycles = 1); cancelling
    // at the 5th progress point stops it there with Interrupted, not with a result.
    let cancel = Cancel::new();
    let o = SlideOptions {
        law: Law::static_kinetic(0.648, 0.583, Rule::Paper).unwrap(),
        cycles: 1,
        cancel: cancel.clone(),
        ..Default::default()
    };
    let calls = AtomicUsize::new(0);
    let tick = |_: &tribofe::Tick| {
        if calls.fetch_add(1, Ordering::Relaxed) + 1 == 5 {
            cancel.cancel();
        }
    };
    let r = slide::run(&Scene::default(), &o, tribofe::Progress::new(&tick));
    assert!(matches!(r, Err(Error::Interrupted)), "{r:?}");
    assert_eq!(calls.load(Ordering::Relaxed), 5, "no progress point after the cancel");
    // The same options without a cancel run to the end.
    let o = SlideOptions { cancel: Cancel::new(), ..o };
    assert!(slide::run(&Scene::default(), &o, tribofe::Progress::none()).is_ok());
}

#[test]
fn a_sweep_cancelled_from_another_thread_stops() {
    use tribofe::studies::sweep::{self, Axis, Param, SweepOptions};
    let cancel = Cancel::new();
    cancel.cancel();
    let o = SweepOptions { cancel: cancel.clone(), converged: false, ..Default::default() };
    let axes = [Axis { param: Param::Thickness, values: vec![0.002, 0.004] }];
    let r = std::thread::scope(|s| {
        s.spawn(|| sweep::run(&Scene::default(), &axes, &o, tribofe::Progress::none())).join().unwrap()
    });
    assert!(matches!(r, Err(Error::Interrupted)));
}
