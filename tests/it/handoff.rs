//! The quasi-static <-> dynamic handoff (issue 46): `slide --dynamics`, held or at constant
//! velocity, records through the event solver's recorder, so a host's `Problem::observer`
//! sees every recorded event once, in order, and `--max-events` stops every mode at the same
//! event index (the cap refuses event `max_events`, the observer has seen the ones before).

use std::sync::{Arc, Mutex};
use tribofe::interface::events::{EventKind, Observer, Operator};
use tribofe::law::Law;
use tribofe::scene::Scene;
use tribofe::studies::dynamic_slide::{self as ds, DynamicOptions};
use tribofe::studies::slide::{self, SlideOptions};
use tribofe::Progress;

/// (index, kind, X, F) of each call.
type Seen = Arc<Mutex<Vec<(usize, EventKind, f64, f64)>>>;

fn observed(o: &SlideOptions) -> (SlideOptions, Seen) {
    let seen: Seen = Arc::default();
    let log = seen.clone();
    let o = SlideOptions {
        observer: Some(Observer::new(move |k, e, _| log.lock().unwrap().push((k, e.kind, e.x, e.f)))),
        ..o.clone()
    };
    (o, seen)
}

/// The calls are 0, 1, ... in order and match `events` one for one.
fn matches(seen: &Seen, events: &[tribofe::interface::events::Event]) {
    let seen = seen.lock().unwrap();
    assert_eq!(seen.len(), events.len(), "observer calls vs recorded events");
    for (k, (i, kind, x, f)) in seen.iter().enumerate() {
        assert_eq!(*i, k);
        assert_eq!((*kind, *x, *f), (events[k].kind, events[k].x, events[k].f), "event {k}");
    }
}

/// Coulomb on the velocity tests' small block: L = 0.1 m, h = 1 mm, to X = 3.4e-5 m.
fn coulomb() -> (Scene, SlideOptions) {
    let scene = crate::dynamics::block(0.1, 0.001, None);
    let o = SlideOptions { law: Law::coulomb(0.5).unwrap(), x_max: Some(3.4e-5), ..Default::default() };
    (scene, o)
}

fn at_velocity(v: f64) -> DynamicOptions {
    DynamicOptions { drive_velocity: Some(v), ..Default::default() }
}

#[test]
/// The held mode (slip weakening: dynamic events among the static ones) and the
/// constant-velocity drive call the observer once per row of events.csv (`run.events`).
fn the_observer_sees_every_event_of_both_dynamic_modes() {
    let (scene, o) = crate::dynamics::short_weakening(Operator::Banded, 5.2e-6);
    let (o, seen) = observed(&o);
    let held = ds::run(&scene, &o, &DynamicOptions::default(), Progress::none()).unwrap();
    assert!(!held.events.is_empty(), "no dynamic event");
    assert!(held.slide.run.events.len() > 20, "{} events", held.slide.run.events.len());
    matches(&seen, &held.slide.run.events);

    let (scene, o) = coulomb();
    let (o, seen) = observed(&o);
    let vel = ds::run(&scene, &o, &at_velocity(2e-5), Progress::none()).unwrap();
    assert!(vel.slide.run.events.len() > 1000, "{} events", vel.slide.run.events.len());
    matches(&seen, &vel.slide.run.events);
}

#[test]
/// With --max-events k every mode records the first k events of the uncapped run and stops
/// at event k, as the quasi-static solver's recorder does: the held mode with what it
/// computed (incomplete), the quasi-static and the constant-velocity runs with the cap error
/// at event k's X; the observer has seen exactly k events.
fn the_event_cap_stops_every_mode_at_the_same_index() {
    let cap = 12;
    let capped = |o: &SlideOptions| SlideOptions { max_events: cap, ..o.clone() };
    let x_of = |e: tribofe::Error| match e {
        tribofe::Error::EventCap { cap: c, x, .. } => {
            assert_eq!(c, cap);
            x
        }
        e => panic!("not the cap: {e}"),
    };

    // Quasi-static (the reference) and held, on the short slip-weakening scene.
    let (scene, o) = crate::dynamics::short_weakening(Operator::Banded, 5.2e-6);
    let full_qs = slide::run(&scene, &o, Progress::none()).unwrap();
    let (oc, seen) = observed(&capped(&o));
    let x = x_of(slide::run(&scene, &oc, Progress::none()).unwrap_err());
    assert_eq!(seen.lock().unwrap().len(), cap);
    assert_eq!(x, full_qs.run.events[cap].x);

    let full = ds::run(&scene, &o, &DynamicOptions::default(), Progress::none()).unwrap();
    assert!(full.slide.run.events.len() > cap);
    let (oc, seen) = observed(&capped(&o));
    let held = ds::run(&scene, &oc, &DynamicOptions::default(), Progress::none()).unwrap();
    assert!(held.incomplete.as_deref().is_some_and(|m| m.contains("--max-events")), "{:?}", held.incomplete);
    assert_eq!(held.slide.run.events.len(), cap);
    matches(&seen, &full.slide.run.events[..cap]);

    // Constant velocity: as the held mode, the run ends at the cap with what it computed
    // (k events, the cap named at event k's X), and the observer has seen those k.
    let (scene, o) = coulomb();
    let full = ds::run(&scene, &o, &at_velocity(2e-5), Progress::none()).unwrap();
    let (oc, seen) = observed(&capped(&o));
    let vel = ds::run(&scene, &oc, &at_velocity(2e-5), Progress::none()).unwrap();
    let note = vel.incomplete.clone().unwrap_or_default();
    assert!(
        note.contains("--max-events = 12")
            && note.contains(&format!("X = {:.6e} m", full.slide.run.events[cap].x)),
        "{note}"
    );
    assert_eq!(vel.slide.run.events.len(), cap);
    matches(&seen, &full.slide.run.events[..cap]);
}
