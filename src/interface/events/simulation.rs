//! The simulation: the normal phase (N ramped at X = 0), then the drive phase (X increased with
//! N held), each advancing from event to event, and the [`Recorder`] that writes the run.

use super::active::Solver;
use super::handoff::{Found, Onset, Resolved, Resolver};
use super::operator::{Affine, Dense, Operator};
use super::relax::Rules;
use super::search::{Fix, Hit};
use super::{
    tolerances, weakening, BorderRole, Event, EventKind, NodeState, OperatorRef, Phase, Problem, Run, State,
};
use crate::error::{Error, Result};
use crate::law::Law;

/// Runs the loading history on the condensed S (at the drive height, see
/// [`crate::interface::condense::Condensed::at_height`]); `progress` gets a fraction in [0, 1].
pub fn run(s: &[f64], n: usize, pb: &Problem, progress: &dyn Fn(f64)) -> Result<Run> {
    run_rig(s, &super::TOP_PLATE, n, pb, progress)
}

/// [`run`] on the condensed S of any rig: the interface's 2n DOFs then `border`.
fn run_rig(s: &[f64], border: &[BorderRole], n: usize, pb: &Problem, progress: &dyn Fn(f64)) -> Result<Run> {
    let nd = 2 * n + border.len();
    let drives = border.iter().filter(|&&r| r == BorderRole::Drive).count();
    if s.len() != nd * nd || drives != 1 || border.first() != Some(&BorderRole::Drive) {
        return Err(Error::input("condensed system", "sizes do not match the interface"));
    }
    run_on(Box::new(Dense::with_border(s, border)), n, pb, progress)
}

/// [`run`] on either operator ([`Problem::operator`] is the caller's choice of which to build).
pub fn run_with(op: OperatorRef, n: usize, pb: &Problem, progress: &dyn Fn(f64)) -> Result<Run> {
    match op {
        OperatorRef::Dense(s, border) => run_rig(s, border, n, pb, progress),
        OperatorRef::Banded(b) => {
            if b.n != n {
                return Err(Error::input("banded operator", "sizes do not match the interface"));
            }
            run_on(Box::new(crate::interface::banded::Solving::new(b)), n, pb, progress)
        }
    }
}

/// [`run`] on any representation of the condensed operator (n interface nodes).
pub(super) fn run_on(
    op: Box<dyn Operator + '_>,
    n: usize,
    pb: &Problem,
    progress: &dyn Fn(f64),
) -> Result<Run> {
    check(pb)?;
    let (mut sv, rec) = start_drive(op, n, pb)?;
    if let Law::SlipWeakening { dc, .. } = pb.law {
        let mut resolver = weakening::Runaway { dc, end_at_crossing: pb.end_at_crossing };
        return weakening::drive(&mut sv, rec, dc, &mut resolver, progress);
    }
    drive_phase(&mut sv, rec, &mut Rules::default(), progress)
}

/// The start of every drive on `op` (n interface nodes), quasi-static or dynamic: the
/// active set ([`start`]), the normal phase, then the drive phase's start at X = 0 with N
/// held. The one re-stick rule: under a law that weakens (static-kinetic, slip weakening)
/// the normal loading stops, so every pre-slipped node sticks where it is and re-arms
/// (keeping the slip it made); under Coulomb a pre-slipped node slips on.
pub(crate) fn start_drive<'a, 'p>(
    op: Box<dyn Operator + 'a>,
    n: usize,
    pb: &'p Problem,
) -> Result<(Solver<'a>, Recorder<'p>)> {
    let (mut sv, mut rec) = start(op, n, pb)?;
    normal_phase(&mut sv, &mut rec)?;
    sv.set_phase(Phase::Drive);
    if pb.law.weakens() {
        for i in 0..n {
            if let NodeState::Slip(_) = sv.states()[i] {
                sv.set_state(i, NodeState::Stick, rec.prev_u[i])?;
            }
        }
    }
    Ok((sv, rec))
}

/// The problem's own inputs, refused before any work (also by
/// [`crate::studies::slide::check_options`], which every frictional run calls up front).
pub(crate) fn check(pb: &Problem) -> Result<()> {
    pb.law.rate_free("--law")?;
    if !(pb.n_force.is_finite() && pb.n_force > 0.0) {
        return Err(Error::input("N", format!("{} N/m must be a positive number", pb.n_force)));
    }
    if let Some(x) = pb.x_max {
        if !(x.is_finite() && x > 0.0) {
            return Err(Error::input("x-max", format!("{x} m must be a positive number")));
        }
    }
    if !(pb.creep_fraction.is_finite() && pb.creep_fraction >= 0.0 && pb.creep_fraction < 1.0) {
        return Err(Error::input("creep fraction", "must be in [0, 1)"));
    }
    Ok(())
}

/// The active set on `op`, all stuck, its bonded stiffness and displacement scale (|V| under
/// N) read off the all-stuck solution, set for the normal phase; and an empty recorder.
fn start<'a, 'p>(
    op: Box<dyn Operator + 'a>,
    n: usize,
    pb: &'p Problem,
) -> Result<(Solver<'a>, Recorder<'p>)> {
    let mut sv = Solver::new(op, n, pb)?;
    let a = sv.solve()?;
    let k_bonded = a.f1[sv.iu()];
    // |V| under N; without a plate (uniform pressure) N over the bonded stiffness, the
    // same order (both ~ N t/(E L)).
    let v_scale = match sv.set.iv() {
        Some(iv) => a.b0[iv].abs(),
        None => pb.n_force / k_bonded,
    };
    if !(k_bonded > 0.0 && v_scale > 0.0) {
        return Err(Error::input(
            "condensed system",
            "the bonded block has no tangential or normal stiffness",
        ));
    }
    sv.dscale = v_scale;
    sv.set_phase(Phase::Normal);
    Ok((sv, Recorder { out: Run::new(k_bonded), prev_u: vec![0.0; n], pb }))
}

/// N from 0 to its value (lambda = N reached / N); proportional loading, so the rate problem
/// at 0 decides and nodes slip continuously. Ends with the `normal-load` (or `edge-preslip`)
/// event.
fn normal_phase(sv: &mut Solver, rec: &mut Recorder) -> Result<()> {
    let max_fix = tolerances::max_changes(sv.n());
    let mut lam = 0.0;
    let mut pending: Option<(EventKind, usize)> = None;
    let mut idle = 0;
    let a = loop {
        let a = settle_continuous(sv, lam, true, max_fix, "normal loading")?;
        if let Some((kind, i)) = pending.take() {
            rec.simple(sv, &a, lam, kind, i)?;
        }
        match sv.next_event(&a, lam) {
            Some((d, i, h)) if lam + d < 1.0 => {
                idle = if d == 0.0 { idle + 1 } else { 0 };
                if idle > max_fix {
                    return Err(stuck_err("normal loading", lam));
                }
                lam += d;
                apply_hit(sv, &a, lam, i, h)?;
                pending = Some((hit_kind(h), i));
            }
            _ => break a,
        }
    };
    rec.record(sv, &a, 1.0, |st| {
        let pre = st.states.iter().position(|s| matches!(s, NodeState::Slip(_)));
        let kind = if pre.is_some() { EventKind::EdgePreslip } else { EventKind::NormalLoad };
        Event::simple(kind, st, pre.unwrap_or(0))
    })
}

/// What the drive phase carries from one X to the next.
struct Drive {
    /// Static-kinetic (instabilities) rather than coulomb (continuous slip).
    is_sk: bool,
    x_end: f64,
    max_fix: usize,
    /// A continuous event waiting for the settle at its X to be recorded.
    pending: Option<(EventKind, usize)>,
    /// Nodes slipped in an instability since the last whole-interface slip: an event nucleating
    /// next to this set's run from the trailing edge is the tip advance of an arrested front.
    slipped: Vec<bool>,
    sliding_seen: bool,
}

impl Drive {
    fn frac(&self, out: &Run, cycles: usize, lam: f64) -> f64 {
        let by_x = if self.x_end.is_finite() { lam / self.x_end } else { 0.0 };
        let by_c = if self.is_sk { out.sliding_events as f64 / cycles.max(1) as f64 } else { 0.0 };
        by_x.max(by_c).min(1.0)
    }
}

/// X from 0 with N held (coulomb, static-kinetic): at each X the states are made consistent
/// (rate fixes, instabilities), then X advances to the next event.
fn drive_phase(
    sv: &mut Solver,
    mut rec: Recorder,
    resolver: &mut dyn Resolver,
    progress: &dyn Fn(f64),
) -> Result<Run> {
    let (n, pb) = (sv.n(), rec.pb);
    let mut dr = Drive {
        is_sk: pb.law.weakens(),
        x_end: pb.x_max.unwrap_or(f64::INFINITY),
        max_fix: tolerances::max_changes(n),
        pending: None,
        slipped: vec![false; n],
        sliding_seen: false,
    };
    let mut lam = 0.0;
    let mut idle = 0;
    loop {
        // Also here: a drive step without a state change reuses the last solve.
        rec.pb.cancel.check()?;
        let Some(a) = settle_drive(sv, &mut rec, &mut dr, resolver, lam, progress)? else {
            return Ok(rec.finish(sv));
        };
        if let Some((kind, i)) = dr.pending.take() {
            rec.simple(sv, &a, lam, kind, i)?;
        }
        // Coulomb: the first whole-interface slip; by default the run ends 5 % further.
        if !dr.is_sk && !dr.sliding_seen && sv.all_contact_slipping() {
            dr.sliding_seen = true;
            rec.out.sliding_events += 1;
            rec.simple(sv, &a, lam, EventKind::Sliding, 0)?;
            if pb.x_max.is_none() {
                dr.x_end = lam + 0.05 * lam.max(pb.n_force / rec.out.k_bonded);
            }
        }
        let next = sv.next_event(&a, lam);
        let Some((d, i, h)) = next.filter(|&(d, _, _)| lam + d < dr.x_end) else {
            // Static-kinetic: every contact node creeping at mu_d is a steady whole slip that
            // no further event can end.
            if dr.is_sk && next.is_none() && sv.all_contact_slipping() {
                rec.out.sliding_events += 1;
                rec.record(sv, &a, lam, |st| Event {
                    all_slipping: true,
                    ..Event::simple(EventKind::Sliding, st, 0)
                })?;
                progress(1.0);
                return Ok(rec.finish(sv));
            }
            if !dr.x_end.is_finite() {
                return Err(Error::input(
                    "x-max",
                    "the loading reaches no further event and no end was given; give --x-max",
                ));
            }
            rec.simple(sv, &a, dr.x_end, EventKind::End, 0)?;
            progress(1.0);
            return Ok(rec.finish(sv));
        };
        idle = if d == 0.0 { idle + 1 } else { 0 };
        if idle > dr.max_fix {
            return Err(stuck_err("drive", lam));
        }
        lam += d;
        progress(dr.frac(&rec.out, pb.cycles, lam));
        if dr.is_sk && matches!(h, Hit::Friction(_)) {
            // The settle at the new X starts the instability (or creep).
            continue;
        }
        apply_hit(sv, &a, lam, i, h)?;
        let kind = match h {
            Hit::Friction(_) => {
                let slipping = |k: usize| matches!(sv.states()[k], NodeState::Slip(_));
                if (i > 0 && slipping(i - 1)) || (i + 1 < n && slipping(i + 1)) {
                    EventKind::TipAdvance
                } else {
                    EventKind::Nucleation
                }
            }
            _ => hit_kind(h),
        };
        dr.pending = Some((kind, i));
    }
}

/// Makes the states consistent at this X: rate fixes, and (static-kinetic) instabilities,
/// each resolved by `resolver` and recorded as an event. Returns the consistent solution, or None when the cycles asked
/// for are done.
fn settle_drive(
    sv: &mut Solver,
    rec: &mut Recorder,
    dr: &mut Drive,
    resolver: &mut dyn Resolver,
    lam: f64,
    progress: &dyn Fn(f64),
) -> Result<Option<Affine>> {
    let pb = rec.pb;
    let mut fixes = 0;
    loop {
        let a = sv.solve()?;
        match sv.rate_fix(&a, lam, !dr.is_sk)? {
            Fix::None => return Ok(Some(a)),
            Fix::Changed(i, what) => {
                fixes += 1;
                if fixes > dr.max_fix {
                    return Err(stuck_err("drive", lam));
                }
                if what == EventKind::Creep {
                    dr.slipped[i] = true; // a creeping corner has slipped (front crossing)
                }
                if matches!(what, EventKind::Open | EventKind::Close | EventKind::Creep)
                    && dr.pending.is_none()
                {
                    dr.pending = Some((what, i));
                }
            }
            Fix::Instability(i0) => {
                fixes = 0;
                if let Some((kind, i)) = dr.pending.take() {
                    rec.simple(sv, &a, lam, kind, i)?;
                }
                let before = sv.states().to_vec();
                let shown = dr.frac(&rec.out, pb.cycles, lam);
                let at = Onset {
                    lam,
                    a: &a,
                    states_pre: &before,
                    f_pre: a.f(sv.iu(), lam),
                    found: Found::Threshold { node: i0 },
                    slipped: &mut dr.slipped,
                    shown,
                };
                match resolver.resolve(sv, rec, at)? {
                    Resolved::Creep(i) => {
                        dr.pending = Some((EventKind::Creep, i));
                        continue;
                    }
                    Resolved::Stop => return Ok(None),
                    Resolved::Go => {}
                }
                progress(dr.frac(&rec.out, pb.cycles, lam));
                if dr.is_sk && rec.out.sliding_events >= pb.cycles {
                    return Ok(None);
                }
            }
        }
    }
}

/// Rate-consistency changes at lam until none is needed (continuous slip allowed).
pub(crate) fn settle_continuous(
    sv: &mut Solver,
    lam: f64,
    cont: bool,
    cap: usize,
    what: &str,
) -> Result<Affine> {
    settle_within(sv, lam, cont, cap)?.ok_or_else(|| stuck_err(what, lam))
}

/// [`settle_continuous`], with None where `cap` changes did not settle the states.
pub(crate) fn settle_within(sv: &mut Solver, lam: f64, cont: bool, cap: usize) -> Result<Option<Affine>> {
    for _ in 0..cap {
        let a = sv.solve()?;
        match sv.rate_fix(&a, lam, cont)? {
            Fix::None => return Ok(Some(a)),
            Fix::Changed(i, _) if sv.tangent => {
                // The exact weakening path: a node that starts slipping takes its row's
                // linearisation at once, so that the rates are the branch's; if that makes
                // the linearised system unstable, no stable branch goes on (its onset).
                if matches!(sv.states()[i], NodeState::Slip(_)) && sv.law().weakens() {
                    let k = sv.law().kinetic_slope(sv.slip_memory(i, a.b(i, lam))) * a.f(sv.n() + i, lam);
                    sv.set_coefficients(&[(i, sv.mu_slip(i), k, a.b(i, lam))])?;
                    if !super::weakening::tangent_stable(sv)? {
                        sv.lost = true;
                        return sv.solve().map(Some);
                    }
                }
            }
            Fix::Changed(..) => {}
            Fix::Instability(_) => return Ok(None),
        }
    }
    Ok(None)
}

pub(super) fn hit_kind(h: Hit) -> EventKind {
    match h {
        Hit::Open => EventKind::Open,
        Hit::Close => EventKind::Close,
        Hit::Friction(_) => EventKind::Slip,
    }
}

pub(super) fn stuck_err(phase: &str, lam: f64) -> Error {
    Error::Untrustworthy {
        detail: format!("the state update at {phase} parameter {lam:.6e} cycles without settling"),
        hint: "report this case; try another mesh or friction coefficient".into(),
    }
}

/// Applies the transition that reached equality at lam.
pub(super) fn apply_hit(sv: &mut Solver, a: &Affine, lam: f64, i: usize, h: Hit) -> Result<()> {
    let u = a.b(i, lam);
    match h {
        Hit::Open => sv.set_state(i, NodeState::Open, 0.0),
        Hit::Close => sv.set_state(i, NodeState::Stick, u),
        Hit::Friction(s) => sv.set_state(i, NodeState::Slip(s), 0.0),
    }
}

/// The run being written: its events and states so far, and u at the last recorded state
/// (the slip-direction check of the next one).
pub(crate) struct Recorder<'p> {
    pub(crate) out: Run,
    pub(crate) prev_u: Vec<f64>,
    pub(super) pb: &'p Problem,
}

impl Recorder<'_> {
    /// Records the state of `a` at lam and the event `ev` builds from it.
    pub(crate) fn record(
        &mut self,
        sv: &Solver,
        a: &Affine,
        lam: f64,
        ev: impl FnOnce(&State) -> Event,
    ) -> Result<()> {
        let st = sv.record(a, lam, Some(&self.prev_u));
        self.prev_u.clone_from(&st.u);
        let ev = ev(&st);
        self.push(ev, st)
    }

    /// Records a continuous event (no relaxation) of `kind` at `node`.
    pub(crate) fn simple(
        &mut self,
        sv: &Solver,
        a: &Affine,
        lam: f64,
        kind: EventKind,
        node: usize,
    ) -> Result<()> {
        self.record(sv, a, lam, |st| Event::simple(kind, st, node))
    }

    /// Records an event and the state after it, built by the caller (the constant-velocity
    /// drive's samples and events): the cancel check, the cap and the observer's call.
    pub(crate) fn push(&mut self, ev: Event, st: State) -> Result<()> {
        let (out, pb) = (&mut self.out, self.pb);
        pb.cancel.check()?;
        if out.events.len() >= pb.max_events {
            // No precursor count here: the solver does not know the node positions and block
            // thickness the one definition reads; a study counts through `Problem::observer`.
            return Err(Error::EventCap {
                cap: pb.max_events,
                x: st.x,
                f_over_n: st.f / pb.n_force,
                f_peak_over_n: out.events.iter().map(|e| e.f).fold(st.f, f64::max) / pb.n_force,
            });
        }
        // The one call per recorded event.
        if let Some(obs) = &pb.observer {
            obs.call(out.events.len(), &ev, &st);
        }
        out.push(ev, st, pb.keep_states);
        Ok(())
    }

    /// The finished run with the operator's counts.
    pub(crate) fn finish(mut self, sv: &Solver) -> Run {
        (self.out.updates, self.out.refreshes) = sv.counts();
        self.out
    }
}
