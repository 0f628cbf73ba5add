//! A host stopping the library's long runs through its [`tribofe::Cancel`] token: the run
//! returns `Error::Interrupted` at its next progress point, whatever thread cancels.

use std::sync::atomic::{AtomicUsize, Ordering};
use tribofe::law::{Law, Rule};
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

#[test]
fn a_slides_arrays_are_its_states_and_events_columns_its_csv() {
    use tribofe::studies::slide::StateField;
    let o = SlideOptions {
        law: Law::static_kinetic(0.648, 0.583, Rule::Paper).unwrap(),
        cycles: 1,
        ..Default::default()
    };
    let r = slide::run(&Scene::default(), &o, tribofe::Progress::none()).unwrap();
    let n = r.condensed.n;
    for f in StateField::ALL {
        let (v, shape) = r.field(f);
        assert_eq!(shape, [r.run.states.len(), n]);
        assert_eq!(v.len(), shape[0] * shape[1]);
        for (k, st) in r.run.states.iter().enumerate() {
            let row = &v[k * n..(k + 1) * n];
            let want: Vec<f64> = match f {
                StateField::Slip => st.u.clone(),
                StateField::Gap => st.gap.clone(),
                StateField::TangentialForce => st.t_force.clone(),
                StateField::NormalForce => st.p_force.clone(),
                StateField::Code => st
                    .states
                    .iter()
                    .map(|s| match s {
                        tribofe::interface::events::NodeState::Stick => 0.0,
                        tribofe::interface::events::NodeState::Slip(_) => 1.0,
                        tribofe::interface::events::NodeState::Open => 2.0,
                    })
                    .collect(),
                StateField::ContactAreaOverA0 => {
                    let n: f64 = st.p_force.iter().sum();
                    let p_mean = n / r.condensed.l;
                    st.p_force.iter().zip(&r.condensed.w).map(|(p, w)| p / w / p_mean).collect()
                }
            };
            assert_eq!(row, &want[..], "{f:?} state {k}");
        }
    }
    // The columns are the numbers events.csv prints (to its printed digits).
    let ev = r.event_columns();
    let csv = tribofe::report::slide::events_csv(&r).unwrap();
    let head: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let col = |name: &str| head.iter().position(|h| *h == name).unwrap();
    let rows: Vec<Vec<&str>> = csv.lines().skip(1).map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), ev.kind.len());
    assert!(ev.kind.len() > 2, "the paper's scene makes precursors before the first slide");
    for (k, row) in rows.iter().enumerate() {
        assert_eq!(row[col("kind")], ev.kind[k]);
        for (name, v) in [
            ("F_over_mu_s_N", ev.f_over_mu_s_n[k]),
            ("x_arrest_over_L", ev.x_arrest_over_l[k]),
            ("slipped_length_over_L", ev.slipped_length_over_l[k]),
            ("F_relaxed_over_mu_s_N", ev.f_relaxed_over_mu_s_n[k]),
        ] {
            let printed: f64 = row[col(name)].parse().unwrap();
            // The CSV prints enough digits to read back to round-off.
            assert!((printed - v).abs() <= 1e-12 * v.abs().max(1.0), "{name} event {k}: {printed} vs {v}");
        }
    }
}
