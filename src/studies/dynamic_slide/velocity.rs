//! `slide --dynamics --drive-velocity V`: the drive phase run explicitly at a constant drive
//! velocity, U_H = V t, for comparison with the held-drive mode (issue 33).
//!
//! 1. The normal phase is the held mode's: N ramped quasi-statically and exactly at U_H = 0
//!    (the event solver's start-up, `interface::events`' `handoff`); under a weakening law
//!    slipping nodes stick where they are as the drive starts, under Coulomb they slip on
//!    (the event solver's one rule). Every event goes through the event solver's recorder.
//! 2. From that equilibrium the whole drive phase is one explicit run
//!    ([`crate::dynamics::driven::Driven::step`]) to --x-max, started on the quasi-static
//!    path (u from the static field, v = V du/dU_H of the static path with the states of the
//!    start), so the start launches no wave of order rho c V.
//! 3. Events are read off the slip rates: one starts when some base node's |v_x| exceeds
//!    the event threshold ([`event_threshold`]) and ends when every node has stayed below it
//!    for one period of the block's thickness-shear mode. Under a weakening law the threshold
//!    is the law's own, independent of V ([`super::physics::event_rate`]), and V is refused
//!    above 1/[`RATE_FACTOR`] of it: a quasi-static slip runs at about V (a node cannot slip
//!    faster than the plate drags it, the tilt aside), so a faster drive cannot be told
//!    from an instability. Without weakening (Coulomb: no rate scale) it is [`RATE_FACTOR`]
//!    V. Onset X and F are those of the last step before
//!    the threshold was crossed; the slipped region is the run of nodes that crossed it
//!    around the first one; the relaxed F is the one at the event's end. After an event in
//!    which some node weakened fully (slip >= D_c) every node heals to mu_s (slip memory 0),
//!    as in the held mode and the quasi-static solver.
//!
//! Outputs are the held mode's: loading.csv is a sample of the drive every
//! X_max / [`LOADING_ROWS`] (kind `sample` in events.csv) plus the events; dyn_events.csv's
//! f_gap and u_gap (distance to a static equilibrium after an event) are 0 here: no static
//! equilibrium is solved.

use super::setup::{Setup, StaticOperator};
use super::steps::{arrest, crossing, kind_of};
use super::{check as check_held, DynEvent, DynamicOptions, DynamicResult};
use crate::dynamics::driven::{tip, Contact, DynState, EventEnergy, EventRecord};
use crate::error::{Error, Result};
use crate::interface::events::handoff::{settle_continuous, start_drive, Recorder};
use crate::interface::events::{tolerances, Event, EventKind, NodeState, Phase, State, Violations};
use crate::progress::Progress;
use crate::scene::Scene;
use crate::studies::slide::SlideOptions;
use std::time::Instant;

/// Without weakening (Coulomb: no rate scale of its own) a base node is in an event while
/// its slip rate exceeds this multiple of V. Under a weakening law the threshold is the
/// law's own ([`super::physics::event_rate`]) and V must stay below 1 / this of it.
pub const RATE_FACTOR: f64 = 10.0;
/// The drive phase is sampled into about this many rows of loading.csv.
pub const LOADING_ROWS: u64 = 2000;
/// Largest drive velocity, in units of the shear-wave speed c_s: the drive must be
/// quasi-static against the waves that carry it through the block (its shear wave has strain
/// V/c_s), and its event threshold [`RATE_FACTOR`] V well below the slip rates of an
/// instability, (tau/G) c_s.
pub const MAX_DRIVE_OVER_C_S: f64 = 0.01;
/// Default cap on the explicit steps of one run (X_max / V / dt): 1e7 steps of the paper's
/// block (2.4e3 DOFs at h = 1 mm) are about 2.4e10 DOF-updates, minutes on this machine.
pub const MAX_STEPS: u64 = 10_000_000;
/// Samples of one event's slip rates kept at most (the stride doubles beyond).
const EVENT_SAMPLES: usize = 4096;

/// Refusals of the constant-velocity mode that need no mesh: V > 0 and slow against the
/// waves, --x-max given.
pub fn check(scene: &Scene, o: &SlideOptions, d: &DynamicOptions) -> Result<f64> {
    // The quasi-static normal phase takes a rate-free law (rate-and-state's stand-in).
    check_held(scene, &SlideOptions { law: o.law.rate_free_stand_in(), ..o.clone() }, d)?;
    if let Some(r) = o.law.rate_state() {
        super::physics::check_rate_state_resolved(scene, r, o.n_force)?;
    }
    let v = d.drive_velocity.unwrap_or(f64::NAN);
    if !(v.is_finite() && v > 0.0) {
        return Err(Error::input(
            "--drive-velocity",
            format!("{v}: give the drive velocity dU_H/dt in m/s, > 0 (without the flag the drive is held during each event)"),
        ));
    }
    let c_s = super::shear_speed(scene)?;
    if v > MAX_DRIVE_OVER_C_S * c_s {
        return Err(Error::input(
            "--drive-velocity",
            format!(
                "{v:e} m/s is not slow against the waves: give V <= {MAX_DRIVE_OVER_C_S} c_s = {:.4e} m/s (c_s = {c_s:.4e} m/s). A faster plate launches a shear wave of strain V/c_s above 1 %, outside the small-strain model, and the event threshold {RATE_FACTOR} V would pass the slip rates (tau/G) c_s of the instabilities it is to detect",
                MAX_DRIVE_OVER_C_S * c_s
            ),
        ));
    }
    if o.law.weakens() {
        let thr = event_threshold(scene, o, v)?;
        if RATE_FACTOR * v > thr {
            return Err(Error::input(
                "--drive-velocity",
                format!(
                    "{v:e} m/s is too fast to tell instabilities from the creep the drive imposes: events are read off the slip rates at the law's threshold {thr:.3e} m/s (the front arrival rate, {} of the strength drop's shear-wave particle velocity (mu_s - mu_d) (N/L) / (rho c_s), whatever V), and slipping nodes creep at about V; give --drive-velocity <= {:.3e} m/s ({RATE_FACTOR} times below it; the run costs X_max / V / dt steps), or leave it out for the held mode, this mode's V -> 0 limit",
                    super::physics::ARRIVAL_FRACTION,
                    thr / RATE_FACTOR
                ),
            ));
        }
    }
    if o.x_max.is_none() {
        return Err(Error::input(
            "--x-max",
            "required with --drive-velocity: the run is X_max / V / dt explicit steps, bounded before it starts",
        ));
    }
    Ok(v)
}

/// The slip rate above which a base node is in an event, m/s: the law's own
/// ([`super::physics::event_rate`], independent of V) under a weakening law, [`RATE_FACTOR`]
/// V without one.
pub fn event_threshold(scene: &Scene, o: &SlideOptions, v: f64) -> Result<f64> {
    if o.law.weakens() {
        super::physics::event_rate(scene, o.law.mu_s(), o.law.mu_d(), o.n_force)
    } else {
        Ok(RATE_FACTOR * v)
    }
}

/// Explicit steps the run takes to X_max at V with step dt.
pub fn steps_needed(x_max: f64, v: f64, dt: f64) -> f64 {
    (x_max / (v * dt)).ceil()
}

/// A time level of the drive: X (m) and the plate's (V, theta).
#[derive(Clone, Copy)]
struct Level {
    x: f64,
    q: [f64; 2],
}

/// An event while it runs.
struct Open {
    x0: f64,
    f0: f64,
    d0: Vec<f64>,
    went: Vec<bool>,
    e0: EventEnergy,
    balance0: f64,
    quiet: usize,
    stride: usize,
    rec: EventRecord,
}

/// The run: quasi-static normal load, then the drive at V, explicitly, to X_max.
pub fn run(scene: &Scene, o: &SlideOptions, d: &DynamicOptions, progress: Progress) -> Result<DynamicResult> {
    let vel = check(scene, o, d)?;
    let x_max = o.x_max.expect("checked");
    let clock = Instant::now();
    // The set-up first (the step; no condensation), so a run over the step cap is refused
    // before the condensation.
    let su = Setup::new(scene, o, d)?;
    // The one damping rule of both modes: outside its range --damping is named here, not
    // --drive-velocity below (heavy damping shrinks dt, so no V could fit the step cap).
    su.check_event_work(scene, d)?;
    let (model, dt, dt_stable, eta) = (&su.model, su.dt, su.dt_stable, su.eta);
    let n_total = steps_needed(x_max, vel, dt);
    if n_total > d.max_velocity_steps as f64 {
        let v_min = x_max / (d.max_velocity_steps as f64 * dt);
        return Err(Error::input(
            "--drive-velocity",
            format!(
                "{vel:e} m/s needs {n_total:.3e} explicit steps of dt = {dt:.4e} s to --x-max {x_max:e} m, above the cap of {:.1e} steps: use --drive-velocity >= {v_min:.3e} m/s or a smaller --x-max",
                d.max_velocity_steps as f64
            ),
        ));
    }
    let so = StaticOperator::new(scene, o.operator)?;
    let c = &so.c;
    let layout = su.layout(c.x.clone(), d)?;
    let n = c.n;
    let (mu_s, law, weakens, lambda0) = (o.law.mu_s(), su.law, su.weakens, su.lambda0);
    // Full fields from boundary values (as the held mode): the block with its boundary held.
    let full = su.full_field()?;
    let full_field = |b: &[f64]| full.field(b);
    let driven = su.driven(&layout, o.n_force);
    let (quiet_steps, sample_every) = (su.quiet_steps, su.sample_every);
    let thr = event_threshold(scene, o, vel)?;
    progress.message(&format!(
        "dynamics, drive at V = {vel:e} m/s to X = {x_max:e} m: {n_total:.0} steps of dt = {dt:.4e} s ({} x the stable {dt_stable:.4e} s), {} DOFs, eta = {eta:.4e} s = {:.3} of critical at the thickness mode; event threshold |v_x| > {thr:.3e} m/s; plate mass {} kg/m, inertia {} kg m^2/m{}",
        d.courant,
        model.n_dofs(),
        su.xi(),
        d.plate_mass,
        d.plate_inertia,
        // Only a slip-weakening law has a cohesive zone at the mean pressure.
        if lambda0.is_finite() {
            format!("; Lambda_0 = {lambda0:.3e} m = {:.2} h", lambda0 / scene.mesh.h)
        } else {
            String::new()
        },
    ));
    let setup_s = clock.elapsed().as_secs_f64();

    // Normal phase, quasi-static and exact, and the drive's start: the event solver's (as the
    // held mode), and its recorder for every event (the observer, the cap).
    let o_qs = SlideOptions { law: o.law.rate_free_stand_in(), ..o.clone() };
    let (mut sv, mut rec) = start_drive(so.solver(), n, &o_qs)?;
    let cap = tolerances::max_changes(n);
    // The start on the quasi-static path: u of the static field at U_H = 0, v = V du/dU_H.
    let p = settle_continuous(&mut sv, 0.0, true, cap, "drive")?;
    let start = sv.record(&p, 0.0, None);
    let slip: Vec<f64> = (0..n).map(|k| sv.slip_memory(k, p.b(k, 0.0))).collect();
    let u0 = full_field(&p.b0);
    let du = full_field(&p.b1);
    let (q, free) = su.coordinates(n, |j| p.b(j, 0.0));
    let (qdot, free_dot) = su.coordinates(n, |j| vel * p.b1[j]);
    let mut ds = DynState {
        u: u0,
        v: du.iter().map(|g| vel * g).collect(),
        u_h: 0.0,
        drive_velocity: vel,
        q,
        qdot,
        free,
        free_dot,
        d: slip,
        theta: law.rate_state().map_or(vec![], |r| vec![r.theta0; n]),
        p_lagged: vec![],
        time: 0.0,
    };

    // The drive phase.
    let dclock = Instant::now();
    let row_every = (n_total as u64 / LOADING_ROWS).max(1);
    let mut w = driven.work(&ds);
    let mut contact = vec![Contact::default(); n];
    let mut window = vec![false; n]; // slipped at some step since the last row
    let mut e = EventEnergy::default();
    let mut balance_first = None;
    let mut f_prev = start.f;
    let mut steps = 0usize;
    let mut open: Option<Open> = None;
    let mut dyn_events: Vec<DynEvent> = Vec::new();
    // A cap met once the drive runs ends it with what it computed (the held mode's rule).
    let mut incomplete: Option<String> = None;
    let mut beat = o.cancel.beat();
    // Nodes slipped by instabilities since the last cycle end, and whether a crossing ends one.
    let mut slipped = (vec![false; layout.x.len()], o.end_at_crossing);
    let dc = su.slip_scale();
    // The state at level n after the step from n: X^n, u^n, the plate's q^n and the
    // forces at n (F^n, P, T), all of one time level (loading.csv's rows).
    let sample_state =
        |ds: &DynState, at: &Level, u: &[f64], contact: &[Contact], slipped: &[bool], f: f64| {
            let base = &layout.base;
            State {
                phase: Phase::Drive,
                x: at.x,
                n_force: o.n_force,
                f,
                tilt: at.q[1],
                v: at.q[0],
                t_force: contact.iter().map(|c| c.t).collect(),
                p_force: contact.iter().map(|c| c.p).collect(),
                u: base.iter().map(|&k| u[2 * k]).collect(),
                gap: base.iter().map(|&k| u[2 * k + 1]).collect(),
                states: (0..n)
                    .map(|b| {
                        if contact[b].open {
                            NodeState::Open
                        } else if slipped[b] {
                            NodeState::Slip(if ds.v[2 * base[b]] < 0.0 { -1.0 } else { 1.0 })
                        } else {
                            NodeState::Stick
                        }
                    })
                    .collect(),
                violations: Violations::default(),
            }
        };
    // The level the last step started from (X^0, q^0 before the first).
    let mut at = Level { x: ds.u_h, q: ds.q };
    loop {
        if ds.u_h >= x_max - 0.5 * vel * dt {
            break;
        }
        at = Level { x: ds.u_h, q: ds.q };
        let out = driven.step(&mut ds, &mut w, &mut e, &mut contact);
        steps += 1;
        let b0 = *balance_first.get_or_insert(out.balance);
        if !(out.f_drive.is_finite() && (out.balance - b0).is_finite()) {
            return Err(Error::Untrustworthy {
                detail: format!("the constant-velocity run produced non-finite values at X = {:e} m", ds.u_h),
                hint: "lower the time step (--courant) or check the scene".into(),
            });
        }
        let mut max_rate = 0.0f64;
        let mut fastest = 0;
        for (b, &k) in layout.base.iter().enumerate() {
            window[b] |= contact[b].slipping;
            let r = ds.v[2 * k].abs();
            if r > max_rate {
                max_rate = r;
                fastest = b;
            }
        }
        if open.is_none() && max_rate > thr {
            open = Some(Open {
                x0: at.x,
                f0: out.f_drive,
                d0: ds.d.clone(),
                went: vec![false; n],
                e0: e,
                balance0: out.balance,
                quiet: 0,
                stride: sample_every,
                rec: EventRecord {
                    slip: vec![0.0; n],
                    peak_rate: vec![0.0; n],
                    nucleation: Some(fastest),
                    open: vec![false; n],
                    // In an event every node's rate is measured against the event's own
                    // threshold too: below it the node creeps with the drive.
                    arrival: vec![f64::NAN; n],
                    arrival_rate: su.arrival_rate.max(thr),
                    // The nodes already slipped at the onset (fronts_t.csv's `preslip`).
                    d_pre: ds.d.clone(),
                    threshold: dc / 100.0,
                    ..Default::default()
                },
            });
        }
        f_prev = out.f_drive;
        let mut closed = false;
        if let Some(ev) = open.as_mut() {
            let rec = &mut ev.rec;
            rec.steps += 1;
            let now = rec.steps as f64 * dt;
            for (b, &k) in layout.base.iter().enumerate() {
                let r = ds.v[2 * k].abs();
                rec.note_rate(b, r, now);
                ev.went[b] |= r > thr;
                rec.slip[b] = ds.d[b] - ev.d0[b];
                rec.open[b] = contact[b].open;
                if ds.d[b] >= dc && ev.d0[b] < dc && law.weakens() {
                    rec.weakened = true;
                }
            }
            if (rec.steps - 1) % ev.stride == 0 {
                if rec.t.len() >= EVENT_SAMPLES {
                    // Keep every other sample and double the stride: the memory stays bounded.
                    for v in [&mut rec.t, &mut rec.force, &mut rec.tip] {
                        *v = v.iter().step_by(2).copied().collect();
                    }
                    rec.rates = rec.rates.iter().step_by(2).cloned().collect();
                    ev.stride *= 2;
                }
                rec.t.push(rec.steps as f64 * dt);
                rec.force.push(out.f_drive);
                rec.tip.push(tip(rec.nucleation, |i| ev.went[i], &layout.x));
                rec.rates.push(layout.base.iter().map(|&k| ds.v[2 * k].abs() as f32).collect());
            }
            ev.quiet = if max_rate > thr { 0 } else { ev.quiet + 1 };
            closed = ev.quiet >= quiet_steps;
        }
        let at_end = ds.u_h >= x_max - 0.5 * vel * dt;
        if closed || (at_end && open.is_some()) {
            let ev = open.take().expect("open event");
            let s = sample_state(&ds, &at, w.u_before(), &contact, &window, out.f_drive);
            let weakened = ev.rec.weakened;
            let kind =
                match close(&mut rec, ev, s, out, &e, closed, dt, &layout.x, &mut dyn_events, &mut slipped) {
                    Ok(kind) => kind,
                    Err(e) => {
                        incomplete = Some(super::cap_met(e)?);
                        break;
                    }
                };
            if weakened && closed {
                // An instability: every node heals to mu_s (slip memory 0), as the held mode.
                ds.d.iter_mut().for_each(|d| *d = 0.0);
            }
            if kind.ends_cycle() {
                rec.out.sliding_events += 1;
            }
            let last = dyn_events.last().expect("event");
            if last.record.weakened {
                progress.message(&format!(
                    "event {} ({kind}) at X = {:.5e} m: F/(mu_s N) {:.5} -> {:.5}, {} steps ({:.3} s), peak slip rate {:.3e} m/s",
                    last.event,
                    last.x,
                    last.f_onset / (mu_s * o.n_force),
                    last.f_after / (mu_s * o.n_force),
                    last.record.steps,
                    last.record.duration,
                    last.record.peak_rate.iter().cloned().fold(0.0, f64::max)
                ));
            }
            if weakens && rec.out.sliding_events >= o.cycles {
                break;
            }
        }
        if (steps as u64).is_multiple_of(row_every) && !at_end {
            let s = sample_state(&ds, &at, w.u_before(), &contact, &window, out.f_drive);
            if let Err(e) = rec.push(Event::simple(EventKind::Sample, &s, 0), s) {
                incomplete = Some(super::cap_met(e)?);
                break;
            }
            window.iter_mut().for_each(|v| *v = false);
        }
        if beat.due()? {
            progress.fraction((ds.u_h / x_max).min(1.0));
        }
    }
    if incomplete.is_none() {
        // The last level the drive reached (the start if it took no step).
        let u_end = if steps == 0 { &ds.u[..] } else { w.u_before() };
        let s = sample_state(&ds, &at, u_end, &contact, &window, f_prev);
        if let Err(e) = rec.push(Event::simple(EventKind::End, &s, 0), s) {
            incomplete = Some(super::cap_met(e)?);
        }
    }
    let dynamic_s = dclock.elapsed().as_secs_f64();
    let total = clock.elapsed().as_secs_f64();
    let run = rec.finish(&sv);
    drop(sv); // it borrows the operator, whose interface the result takes
    let mut res =
        su.result(scene, o, so.c, run, dyn_events, steps, [setup_s, total - setup_s - dynamic_s, dynamic_s]);
    res.incomplete = incomplete;
    Ok(res)
}

/// Ends an event: its kind, its row of events.csv (onset X and F, region, relaxed F) and its
/// record.
#[allow(clippy::too_many_arguments)]
fn close(
    recorder: &mut Recorder,
    ev: Open,
    s: State,
    out: crate::dynamics::driven::StepOut,
    e: &EventEnergy,
    settled: bool,
    dt: f64,
    x: &[f64],
    dyn_events: &mut Vec<DynEvent>,
    slipped: &mut (Vec<bool>, bool),
) -> Result<EventKind> {
    let Open { x0, f0, went, e0, balance0, mut rec, .. } = ev;
    let (kind, node, (a, b)) = kind_of(&rec, &went);
    let kind = crossing(kind, (a, b), &rec.open[..went.len()], &mut slipped.0, slipped.1);
    rec.duration = rec.steps as f64 * dt;
    rec.settled = settled;
    rec.energy = EventEnergy {
        kinetic: e.kinetic,
        strain: e.strain,
        friction: e.friction - e0.friction,
        damping: e.damping - e0.damping,
        work_n: e.work_n - e0.work_n,
        contact: e.contact - e0.contact,
        drive: e.drive - e0.drive,
        residual: out.balance - balance0,
        strain_start: e0.strain,
        kinetic_end: e.kinetic,
    };
    rec.t.push(rec.duration);
    rec.force.push(out.f_drive);
    rec.tip.push(tip(rec.nucleation, |i| went[i], x));
    let f_after = s.f;
    recorder.push(
        Event {
            kind,
            f: f0,
            x: x0,
            node,
            region: Some((a, b)),
            f_relaxed: f_after,
            backslip: 0,
            all_slipping: kind == EventKind::Sliding,
        },
        s,
    )?;
    let (t_arrest, force_drop_at_arrest) =
        arrest(&rec, f0, f_after).map_or((None, None), |(t, f)| (Some(t), f));
    dyn_events.push(DynEvent {
        event: recorder.out.events.len() - 1,
        x: x0,
        f_onset: f0,
        f_pre: f0,
        f_after,
        record: rec,
        t_arrest,
        force_drop_at_arrest,
        assumption5: None,
        f_gap: 0.0,
        u_gap: 0.0,
    });
    Ok(kind)
}
