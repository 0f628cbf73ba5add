//! The drive phase at a fixed slip step per node: `slide --dynamics`' static loading (held
//! drive). X advances to the next exact threshold (stick, slip, open, close), or under slip
//! weakening to where a slipping node has made D_c / N more slip since its coefficient was
//! last brought to its slip; there the coefficients are brought to their slips by fixed point
//! ([`relax`]). A fixed point that runs away is an instability, handed to the [`Resolver`].
//! Coulomb never runs away: its run is the exact static loading, the same events as
//! [`super::run`]'s.
//!
//! It differs from the quasi-static slip-weakening drive (`weakening`), which steps every
//! D_c/20 of the fastest node's slip and relaxes to convergence (Newton where it can): the two
//! loadings are validated separately, and merging them would move both sets of outputs.

use super::active::Solver;
use super::handoff::{Found, Onset, Resolved, Resolver};
use super::operator::Affine;
use super::search::Hit;
use super::simulation::{apply_hit, hit_kind, settle_continuous, settle_within, stuck_err, Recorder};
use super::{tolerances, EventKind, NodeState, Weakening};
use crate::error::{Error, Result};
use crate::law::Law;

/// How a stepped drive ended (the run so far is the recorder's either way).
#[derive(Debug)]
pub(crate) enum Ended {
    /// At the end of the loading (an `end` event) or after the cycles asked for.
    Done,
    /// Steady sliding at mu_d reached stably at this X (no instability): nothing sticks again.
    Steady(f64),
    /// The resolver stopped the run.
    Stopped,
    /// The event cap ([`Error::EventCap`]): the run ends with what it recorded.
    Cap(Error),
}

/// Fixed-point iterates of one relaxation before it counts as unstable.
const FIXED_POINT_ITERATES: usize = 30;

/// The drive phase from X = 0 ([`super::handoff::start_drive`] done) with `steps_per_dc`
/// coefficient updates per D_c of slip; each instability goes to `resolver`. `progress`: the
/// fraction of the run done.
pub(crate) fn drive(
    sv: &mut Solver,
    rec: &mut Recorder,
    resolver: &mut dyn Resolver,
    steps_per_dc: f64,
    progress: &dyn Fn(f64),
) -> Result<Ended> {
    // The cap ends the run with what it recorded, not with an error that would discard it.
    match stepped(sv, rec, resolver, steps_per_dc, progress) {
        Err(e @ Error::EventCap { .. }) => Ok(Ended::Cap(e)),
        r => r,
    }
}

fn stepped(
    sv: &mut Solver,
    rec: &mut Recorder,
    resolver: &mut dyn Resolver,
    steps_per_dc: f64,
    progress: &dyn Fn(f64),
) -> Result<Ended> {
    let (n, pb) = (sv.n(), rec.pb);
    let law = sv.law();
    let weakens = law.weakens();
    let dc = match law {
        Law::SlipWeakening { dc, .. } => dc,
        _ => f64::INFINITY,
    };
    let exact = weakens && pb.weakening == Weakening::Exact;
    let cap = tolerances::max_changes(n);
    let x_end = pb.x_max.unwrap_or(f64::INFINITY);
    let mut x_stop = x_end;
    let mut sliding_seen = false;
    let mut lam = 0.0;
    let mut idle = 0;
    let mut done = vec![0.0f64; n]; // slip since each coefficient was frozen
    let mut slipped = vec![false; n]; // by instabilities since the last cycle end
    let mut path = Path::default();
    sv.tangent = exact;
    loop {
        pb.cancel.check()?;
        let a = if exact {
            let pre = sv.states().to_vec();
            match on_path(sv, lam, cap, dc, &mut path)? {
                Ok(t) => {
                    // The path's state changes are events as the stepped drive's hits are.
                    if let Some((i, kind)) = super::weakening::stable_change(sv.states(), &pre) {
                        rec.simple(sv, &t, lam, kind, i)?;
                    }
                    t
                }
                Err(a) => {
                    // No stable equilibrium continues the branch past this X.
                    let fold = (lam, a.f(sv.iu(), lam));
                    let (lam_on, go) =
                        onset(sv, rec, resolver, &mut path, &a, lam, &mut slipped, 0.0, dc, fold)?;
                    if go == Resolved::Stop {
                        return Ok(Ended::Stopped);
                    }
                    lam = lam_on;
                    if rec.out.sliding_events >= pb.cycles {
                        return Ok(Ended::Done);
                    }
                    continue;
                }
            }
        } else {
            settle_continuous(sv, lam, true, cap, "drive")?
        };
        let frac = if x_end.is_finite() { lam / x_end } else { 0.0 };
        // Cycles done, and of the current one the share of the interface its instabilities
        // have slipped (the crossing ends it at 1).
        let share = slipped.iter().filter(|&&s| s).count() as f64 / n as f64;
        let shown = frac.max((rec.out.sliding_events as f64 + share) / pb.cycles.max(1) as f64).min(1.0);
        progress(shown);
        if !weakens && !sliding_seen && lam > 0.0 && sv.all_contact_slipping() {
            // Coulomb's first whole-interface slip; by default the run ends 5 % further (`slide`).
            sliding_seen = true;
            rec.out.sliding_events += 1;
            rec.simple(sv, &a, lam, EventKind::Sliding, 0)?;
            if pb.x_max.is_none() {
                x_stop = lam + 0.05 * lam.max(pb.n_force / rec.out.k_bonded);
            }
        }
        if weakens && x_end.is_infinite() && sv.all_contact_slipping() {
            let weak =
                (0..n).all(|k| sv.states()[k] == NodeState::Open || sv.slip_memory(k, a.b(k, lam)) >= dc);
            if weak {
                // Steady sliding at mu_d, reached stably: nothing sticks again with the drive
                // advancing; the run ends here.
                rec.out.sliding_events += 1;
                rec.simple(sv, &a, lam, EventKind::Sliding, 0)?;
                return Ok(Ended::Steady(lam));
            }
        }
        if exact {
            path.track(sv, &a, lam);
            if path.at_fold(sv, &a, lam, pb.n_force) {
                let fold = path.fold_at(sv, &a, lam);
                let (lam_on, go) =
                    onset(sv, rec, resolver, &mut path, &a, lam, &mut slipped, shown, dc, fold)?;
                if go == Resolved::Stop {
                    return Ok(Ended::Stopped);
                }
                lam = lam_on;
                if rec.out.sliding_events >= pb.cycles {
                    return Ok(Ended::Done);
                }
                continue;
            }
        }
        // Next X: the next threshold, or a slipping node's next D_c / steps_per_dc of slip
        // (exact path: the predictor's step, see [`Path::step`]).
        let mut next: Option<(f64, Option<(usize, Hit)>)> =
            sv.next_event(&a, lam).map(|(dl, i, h)| (dl, Some((i, h))));
        if exact {
            if let Some(dl) = path.step(sv, &a, lam, dc) {
                if next.is_none_or(|b| dl < b.0) {
                    next = Some((dl, None));
                }
            }
        } else if weakens {
            for k in 0..n {
                let rate = a.b1[k].abs();
                if matches!(sv.states()[k], NodeState::Slip(_))
                    && rate > 0.0
                    && sv.slip_memory(k, a.b(k, lam)) < dc
                {
                    let dl = (dc / steps_per_dc - done[k]).max(0.0) / rate;
                    if next.is_none_or(|b| dl < b.0) {
                        next = Some((dl, None));
                    }
                }
            }
        }
        if exact
            && x_stop.is_finite()
            && next.is_none_or(|b| lam + b.0 >= x_stop)
            && x_stop - lam > path.tol(lam)
        {
            // The exact path reaches the end by its corrector, not along a tangent.
            next = Some((x_stop - lam, None));
        }
        let Some((dl, hit)) = next.filter(|b| {
            lam + b.0 < x_stop || (exact && b.1.is_none() && lam + b.0 <= x_stop && b.0 > path.tol(lam))
        }) else {
            if !x_stop.is_finite() {
                return Err(Error::Untrustworthy {
                    detail: format!("the static loading has no further event at X = {lam:e} m"),
                    hint: "give --x-max".into(),
                });
            }
            rec.simple(sv, &a, x_stop, EventKind::End, 0)?;
            return Ok(Ended::Done);
        };
        idle = if dl == 0.0 { idle + 1 } else { 0 };
        if idle > cap {
            return Err(stuck_err("dynamic slide's drive", lam));
        }
        if exact && !(hit.is_some() && dl <= path.tol(lam)) {
            // The exact path moves by its corrector; a threshold is crossed where the tangent
            // from a corrected point puts it within the path's tolerance (below).
            lam = path.advance(sv, &a, lam, dl, dc)?;
            continue;
        }
        for k in 0..n {
            if matches!(sv.states()[k], NodeState::Slip(_)) {
                done[k] += a.b1[k].abs() * dl;
            }
        }
        lam += dl;
        if let Some((i, h)) = hit {
            apply_hit(sv, &a, lam, i, h)?;
            if let Hit::Friction(_) = h {
                done[i] = 0.0;
            }
            let a = settle_continuous(sv, lam, true, cap, "drive")?;
            rec.simple(sv, &a, lam, hit_kind(h), i)?;
            continue;
        }
        // Slip weakening: bring the slipping coefficients to their slips at fixed X.
        let states_pre = sv.states().to_vec();
        let mu_pre: Vec<f64> = (0..n).map(|k| sv.mu_slip(k)).collect();
        let mut touched = vec![false; n];
        let Some(a_cur) = relax(sv, &a, lam, dc, cap, &mut done, &mut touched)? else {
            continue;
        };
        let u_pre: Vec<f64> = (0..n).map(|k| a.b(k, lam)).collect();
        let at = Onset {
            lam,
            a: &a_cur,
            states_pre: &states_pre,
            f_pre: a.f(sv.iu(), lam),
            found: Found::Runaway { u_pre: &u_pre, mu_pre: &mu_pre, touched: &touched },
            slipped: &mut slipped,
            shown,
        };
        // A creep (static-kinetic's) cannot follow a runaway: loading goes on.
        if resolver.resolve(sv, rec, at)? == Resolved::Stop {
            return Ok(Ended::Stopped);
        }
        // The resolver left a static state: every coefficient starts afresh.
        done.iter_mut().for_each(|v| *v = 0.0);
        if rec.out.sliding_events >= pb.cycles {
            return Ok(Ended::Done);
        }
    }
}

/// Slip (fraction of D_c) per predictor step of the exact path: the corrector makes the path
/// exact whatever the step; this only keeps Newton's start close (the rows are bilinear, so
/// the tangent's error is quadratic in the step).
const PATH_SLIP_STEP: f64 = 0.1;

/// Fraction of the estimated distance to the fold taken per step: the fold is approached
/// geometrically (an overshoot, which has no equilibrium, halves the step).
const FOLD_APPROACH: f64 = 0.75;

/// The fold is extrapolated from a point whose extrapolation step 2 (X_fold - X) dF/dX is
/// below this fraction of mu_s N ([`Path::fold_at`]): the extrapolation's error is about the
/// step's square, 1e-8 mu_s N, near the round-off of solves that close to a singular system.
const FOLD_F_TOL: f64 = 1e-4;

/// Slip past the fold (fraction of D_c, along the last stable tangent, near a fold the
/// unstable direction) from which a dynamic event starts: at the fold itself the runaway is
/// only quadratic and the damped event creeps. At 5e-3 the paper's scene to X = 3.8e-6 m took
/// 9.6x the stepped path's CPU, most of it explicit steps; 5e-2 starts the events where they
/// run away as fast as the stepped path's (docs/speed.md, issue 48). The fold's X and F are
/// recorded before the kick, so the onset found does not depend on it.
const KICK: f64 = 5e-2;

/// The exact weakening path's state between its points: the last stable tangent (the onset's
/// starting line) and the fold estimate.
#[derive(Default)]
struct Path {
    /// X and the stable tangent at the last point on the path.
    last: Option<(f64, Affine)>,
    /// The last point's X, 1 / (largest weakening slip rate)^2 and its states (the fold's
    /// test function: linear in X near a fold, zero at it).
    prev: Option<(f64, f64, Vec<NodeState>)>,
    /// Estimated X of the fold ahead.
    fold: Option<f64>,
    /// Steps toward the same fold.
    approach: usize,
    /// Where the last onset's event left the drive, and its kick (fraction of D_c).
    resumed: Option<f64>,
    kick: f64,
    /// The corrector's stable tangent at the X it returned: the next point's first Newton
    /// pass and stability test would repeat it.
    corrected: Option<(f64, Affine)>,
}

impl Path {
    /// Smallest X step the path resolves: below it a threshold counts as reached.
    fn tol(&self, lam: f64) -> f64 {
        1e-12 * lam.abs().max(f64::MIN_POSITIVE)
    }

    /// Records the stable tangent `a` at lam and updates the fold estimate: g = 1/r^2 (r the
    /// largest slip rate of a weakening node) falls linearly to 0 at a fold, where
    /// r ~ (X_fold - X)^(-1/2); two points of one state set extrapolate it.
    fn track(&mut self, sv: &Solver, a: &Affine, lam: f64) {
        let r = weakening_rate(sv, a);
        let states = sv.states().to_vec();
        self.fold = None;
        if r > 0.0 {
            let g = 1.0 / (r * r);
            if let Some((l0, g0, s0)) = &self.prev {
                if *s0 == states && g < *g0 && lam > *l0 {
                    self.fold = Some(lam + g * (lam - l0) / (g0 - g));
                }
            }
            self.prev = Some((lam, g, states));
        } else {
            self.prev = None;
        }
        if self.fold.is_none() {
            self.approach = 0;
        }
        self.last = Some((lam, a.clone()));
    }

    /// Whether lam is close enough to the fold ahead to extrapolate it ([`Self::fold_at`]):
    /// the extrapolation's step 2 (X_f - X) |dF/dX| below [`FOLD_F_TOL`] mu_s N, or the
    /// distance below the path's resolution, or the approach long.
    fn at_fold(&mut self, sv: &Solver, a: &Affine, lam: f64, n_force: f64) -> bool {
        let Some(lf) = self.fold else { return false };
        let gap = lf - lam;
        let df = a.f1[sv.iu()].abs();
        2.0 * gap * df <= FOLD_F_TOL * sv.law().mu_s() * n_force
            || gap <= self.tol(lam)
            || self.approach > 200
    }

    /// The fold's X and F from the point (lam, `a`) before it: X_f the estimate, and, as near
    /// a fold F = F_f + C (X_f - X)^(1/2) + D (X_f - X), F_f = F + 2 (X_f - X) dF/dX up to
    /// -D (X_f - X), the square of the step over the force scale (the test in `tests`).
    fn fold_at(&self, sv: &Solver, a: &Affine, lam: f64) -> (f64, f64) {
        let iu = sv.iu();
        match self.fold {
            Some(lf) if lf >= lam => (lf, a.f(iu, lam) + 2.0 * (lf - lam) * a.f1[iu]),
            _ => (lam, a.f(iu, lam)),
        }
    }

    /// The predictor's step from the stable tangent `a` at lam: [`PATH_SLIP_STEP`] D_c of the
    /// fastest weakening node's slip, no weakening node past D_c (the law's kink), and
    /// [`FOLD_APPROACH`] of the way to an estimated fold.
    fn step(&self, sv: &Solver, a: &Affine, lam: f64, dc: f64) -> Option<f64> {
        let mut dl = None::<f64>;
        let mut take = |d: f64| dl = Some(dl.map_or(d, |b: f64| b.min(d)));
        let r = weakening_rate(sv, a);
        if r > 0.0 {
            take(PATH_SLIP_STEP * dc / r);
        }
        for k in 0..sv.n() {
            if let NodeState::Slip(s) = sv.states()[k] {
                let (rate, slip) = (s * a.b1[k], sv.slip_memory(k, a.b(k, lam)));
                // A node within 1e-9 D_c of the kink is at it: limiting the step there asks
                // for steps at the path's resolution, which the corrector never takes.
                if rate > 0.0 && slip < dc * (1.0 - 1e-9) {
                    take(((dc - slip) / rate).max(self.tol(lam)));
                }
            }
        }
        if let Some(lf) = self.fold {
            take(FOLD_APPROACH * (lf - lam));
        }
        dl
    }

    /// The corrector: Newton on the coefficients at lam + dl from the tangent at lam, the step
    /// halved while it finds no stable equilibrium (past a fold). Returns the new X (lam
    /// itself if the step falls below the path's resolution: the fold is here, and the next
    /// point's test finds it).
    fn advance(&mut self, sv: &mut Solver, a: &Affine, lam: f64, dl: f64, dc: f64) -> Result<f64> {
        let u: Vec<f64> = (0..sv.n()).map(|k| a.b(k, lam)).collect();
        let td = f64::INFINITY;
        let start = super::weakening::snapshot(sv);
        self.approach += usize::from(self.fold.is_some());
        let mut step = dl;
        while step > self.tol(lam) {
            match super::weakening::tangent(sv, lam + step, &u, dc, td)? {
                // Past a threshold of the current states: the step holds an event, which the
                // next point's tangent locates.
                Some(t) if sv.overshoots(&t, lam + step) => {}
                Some(t) if super::weakening::tangent_stable(sv)? => {
                    self.corrected = Some((lam + step, t));
                    return Ok(lam + step);
                }
                _ => {
                    // No stable equilibrium there: the fold lies within the step.
                    self.fold = Some(self.fold.map_or(lam + step, |f| f.min(lam + step)));
                }
            }
            sv.set_coefficients(&start)?;
            step *= 0.5;
        }
        // The fold is within the path's resolution of lam.
        self.fold = Some(lam);
        Ok(lam)
    }

    fn reset(&mut self) {
        *self = Path::default();
    }
}

/// Largest slip rate dU/dX of a slipping node still weakening (a spring on its row).
fn weakening_rate(sv: &Solver, a: &Affine) -> f64 {
    (0..sv.n())
        .filter(|&k| matches!(sv.states()[k], NodeState::Slip(_)) && sv.spring(k) != 0.0)
        .map(|k| a.b1[k].abs())
        .fold(0.0, f64::max)
}

/// The exact path at X = lam: the states consistent and every slipping coefficient at its
/// slip, the tangent springs on. Ok(tangent), or Err(the settled solution) where no stable
/// equilibrium continues the branch (a node that joined made it unstable, or Newton finds no
/// equilibrium): an onset. Each stable tangent found before a state change is kept in
/// `path.last` (the onset's line).
fn on_path(
    sv: &mut Solver,
    lam: f64,
    cap: usize,
    dc: f64,
    path: &mut Path,
) -> Result<std::result::Result<Affine, Affine>> {
    // No backward test (td infinite): a slipping node whose rate turns sticks by the rate
    // problem at the corrected point.
    let td = f64::INFINITY;
    sv.lost = false;
    let mut fresh = path.corrected.take().filter(|c| c.0 == lam);
    for _ in 0..cap {
        let states = sv.states().to_vec();
        if let Some((_, t)) = fresh.take() {
            // The corrector just found this stable tangent at lam, the states unchanged.
            path.last = Some((lam, t));
        } else {
            let a = sv.solve()?;
            let u: Vec<f64> = (0..sv.n()).map(|k| a.b(k, lam)).collect();
            match super::weakening::tangent(sv, lam, &u, dc, td)? {
                Some(t) if super::weakening::tangent_stable(sv)? => path.last = Some((lam, t)),
                _ => return Ok(Err(a)),
            }
        }
        // States that cycle with the weakening springs on: the rate problem has no unique
        // solution there, so no stable quasi-static branch goes on (an onset).
        let Some(t) = settle_within(sv, lam, true, cap)? else {
            sv.lost = false;
            return Ok(Err(sv.solve()?));
        };
        if std::mem::take(&mut sv.lost) {
            return Ok(Err(t));
        }
        if sv.states() == states {
            return Ok(Ok(t));
        }
    }
    Err(stuck_err("exact slip-weakening path", lam))
}

/// An instability's onset on the exact path at lam: the fold's X and F (`fold`) are kept in
/// [`super::Run::folds`], and the event is handed to the resolver from [`KICK`] D_c of slip
/// past the fold along the last stable tangent (at X + that slip / the tangent's rate; with
/// no stable tangent yet, from `a` itself). Returns the X loading resumes from and what the
/// resolver said.
#[allow(clippy::too_many_arguments)]
fn onset(
    sv: &mut Solver,
    rec: &mut Recorder,
    resolver: &mut dyn Resolver,
    path: &mut Path,
    a: &Affine,
    lam: f64,
    slipped: &mut [bool],
    shown: f64,
    dc: f64,
    fold: (f64, f64),
) -> Result<(f64, Resolved)> {
    let n = sv.n();
    // An onset right where the last event left the drive (its event moved nothing): a kick
    // ten times larger, so that the loading always moves on.
    path.kick = if path.resumed == Some(lam) { (10.0 * path.kick).min(0.5) } else { KICK };
    let kick = path.kick;
    let (lam_on, a_on) = match path.last.take() {
        Some((l, t)) => {
            // Along the tangent: the slipping set may have changed since (a node joined), so
            // the fastest node of the line itself sets the step.
            let r = (0..n).map(|k| t.b1[k].abs()).fold(0.0, f64::max);
            let eps = if r > 0.0 { kick * dc / r } else { kick * dc };
            (lam.max(l) + eps, t)
        }
        None => {
            // No stable tangent since the last event: along the solution's own line.
            let r = (0..n).map(|k| a.b1[k].abs()).fold(0.0, f64::max);
            (lam + if r > 0.0 { kick * dc / r } else { kick * dc }, a.clone())
        }
    };
    rec.out.folds.push(fold);
    let states_pre = sv.states().to_vec();
    let mu_pre: Vec<f64> = (0..n).map(|k| sv.mu_slip(k)).collect();
    let u_pre: Vec<f64> = (0..n).map(|k| a.b(k, lam)).collect();
    let touched: Vec<bool> = states_pre.iter().map(|s| matches!(s, NodeState::Slip(_))).collect();
    let at = Onset {
        lam: lam_on,
        a: &a_on,
        states_pre: &states_pre,
        f_pre: a.f(sv.iu(), lam),
        found: Found::Runaway { u_pre: &u_pre, mu_pre: &mu_pre, touched: &touched },
        slipped,
        shown,
    };
    let go = resolver.resolve(sv, rec, at)?;
    let kick = path.kick;
    path.reset();
    (path.resumed, path.kick) = (Some(lam_on), kick);
    Ok((lam_on, go))
}

/// Brings the slipping coefficients to their slips at fixed X = lam by fixed point (each
/// iterate one solve with the coefficients frozen, the states made consistent after it).
/// None: it settled (an iterate moved no slipping node by 1e-3 D_c); Some(the last iterate):
/// it diverged (an iterate moved a node by more than D_c/2, or 30 iterates did not settle),
/// so the patch is unstable. `done`: slip since each coefficient was last brought to its slip
/// (reset for the slipping nodes); `touched`: the nodes slipping at some iterate.
fn relax(
    sv: &mut Solver,
    a: &super::operator::Affine,
    lam: f64,
    dc: f64,
    cap: usize,
    done: &mut [f64],
    touched: &mut [bool],
) -> Result<Option<super::operator::Affine>> {
    let n = sv.n();
    let mut a_cur = a.clone();
    for _ in 0..FIXED_POINT_ITERATES {
        // Exact (tolerance 0): the held mode's step size is what sets the coefficients' lag.
        let change = super::weakening::coefficients(sv, &a_cur, lam, false, 0.0);
        for k in 0..n {
            if let NodeState::Slip(_) = sv.states()[k] {
                done[k] = 0.0;
                touched[k] = true;
            }
        }
        sv.set_coefficients(&change)?;
        let a_new = settle_continuous(sv, lam, true, cap, "slip-weakening relaxation")?;
        let jump = (0..n)
            .filter(|&k| matches!(sv.states()[k], NodeState::Slip(_)))
            .map(|k| (a_new.b(k, lam) - a_cur.b(k, lam)).abs())
            .fold(0.0, f64::max);
        a_cur = a_new;
        if jump < 1e-3 * dc {
            return Ok(None);
        }
        if jump > 0.5 * dc {
            break;
        }
    }
    Ok(Some(a_cur))
}

#[cfg(test)]
mod tests {
    use super::super::handoff::start_drive;
    use super::super::operator::Dense;
    use super::super::{springs, Problem};
    use super::*;

    /// Keeps the first onset and stops the run.
    struct First(Option<(f64, f64)>);

    impl Resolver for First {
        fn resolve(&mut self, _: &mut Solver, _: &mut Recorder, at: Onset) -> Result<Resolved> {
            self.0 = Some((at.lam, at.f_pre));
            Ok(Resolved::Stop)
        }
    }

    /// The fold of a two-node interface, by hand. Nodes at x = -a, +a (a = 1) tied to the
    /// plate by tangential springs kt0 = 2, kt1 = 1 and normal springs kn = 100, the drive
    /// at h = 0.5 (the springs fixture), N = 1, mu_s = 0.6, mu_d = 0.3, D_c = 0.058. Node 0
    /// (trailing, unloaded by the drive's moment) slips first and weakens; node 1 stays stuck
    /// at u1 = 0. With S = T0 + T1, the moment balance gives P0 = N/2 + c S (c = h/(2a)),
    /// the normal springs theta = e S (e = h/(2 a^2 kn)), and with L = X + h theta:
    /// T1 = -kt1 L, T0 = kt0 (u - L), S = kt0 u - K L (K = kt0 + kt1). Node 0's slip row
    /// T0 = -(mu_s - w u) P0 (w = (mu_s - mu_d)/D_c) is linear in L for a given slip u:
    ///   L(u) = (A0 + A1 u + A2 u^2)/(B0 + B1 u),  A0 = mu_s N/2, A1 = kt0 + mu_s c kt0 - w N/2,
    ///   A2 = -w c kt0, B0 = kt0 + c K mu_s, B1 = -c K w,
    /// and X(u) = g L(u) - d u (g = 1 + h e K, d = h e kt0). The fold is where dX/du = 0:
    ///   g [(A1 B0 - A0 B1) + 2 A2 B0 u + A2 B1 u^2] = d (B0 + B1 u)^2,
    /// a quadratic whose root in (0, D_c) is u_f = 0.6295 D_c: X_f = X(u_f) = 0.124315,
    /// F_f = -S(u_f) = 0.298803 (node 1 at 0.36 of its threshold there). The path stops
    /// where the fold's extrapolation step is FOLD_F_TOL = 1e-4 mu_s N or less; the
    /// extrapolation's error is about that step's square over the force scale, 2e-8 mu_s N
    /// (measured along this approach: 1.3e-7 at a step of 2.7e-4, 9e-9 at 6.7e-5), so F is
    /// asserted to 1e-7 mu_s N. X_f is the secant's zero of 1/(slip rate)^2, linear in X to
    /// O((X_f - X)^(3/2)): 1e-10 relative.
    #[test]
    fn the_exact_path_finds_the_hand_derived_fold_of_two_nodes() {
        let (a, n_force, mu_s, mu_d, kt0, kt1, kn, h, dc): (f64, f64, f64, f64, f64, f64, f64, f64, f64) =
            (1.0, 1.0, 0.6, 0.3, 2.0, 1.0, 100.0, 0.5, 0.058);
        let (k, c, e, w) = (kt0 + kt1, h / (2.0 * a), h / (2.0 * a * a * kn), (mu_s - mu_d) / dc);
        let (a0, a1, a2) = (mu_s * n_force / 2.0, kt0 + mu_s * c * kt0 - w * n_force / 2.0, -w * c * kt0);
        let (b0, b1) = (kt0 + c * k * mu_s, -c * k * w);
        let (g, d) = (1.0 + h * e * k, h * e * kt0);
        let (q2, q1, q0) = (
            g * a2 * b1 - d * b1 * b1,
            2.0 * g * a2 * b0 - 2.0 * d * b0 * b1,
            g * (a1 * b0 - a0 * b1) - d * b0 * b0,
        );
        let disc = (q1 * q1 - 4.0 * q2 * q0).sqrt();
        let u = [(-q1 - disc) / (2.0 * q2), (-q1 + disc) / (2.0 * q2)]
            .into_iter()
            .find(|&u| u > 0.0 && u < dc)
            .expect("a fold inside the weakening range");
        let l = (a0 + a1 * u + a2 * u * u) / (b0 + b1 * u);
        let (x_f, f_f) = (g * l - d * u, -(kt0 * u - k * l));
        assert!((u / dc - 0.6295).abs() < 1e-4 && (x_f - 0.124315).abs() < 1e-6, "u_f {u}, X_f {x_f}");

        let s = springs::operator(&[-a, a], &[kt0, kt1], kn, h);
        let law = Law::slip_weakening(mu_s, mu_d, dc).unwrap();
        let pb = Problem {
            n_force,
            law,
            x_max: Some(0.2),
            cycles: 1,
            weakening: Weakening::Exact,
            ..Default::default()
        };
        let (mut sv, mut rec) = start_drive(Box::new(Dense::new(&s, 7)), 2, &pb).unwrap();
        let mut first = First(None);
        let ended = drive(&mut sv, &mut rec, &mut first, 20.0, &|_| {}).unwrap();
        assert!(matches!(ended, Ended::Stopped), "{ended:?}");
        let (x, f) = rec.out.folds[0];
        assert!((f - f_f).abs() <= 1e-7 * mu_s * n_force, "F {f} vs {f_f}: {:e}", f - f_f);
        assert!((x - x_f).abs() <= 1e-10 * x_f, "X {x} vs {x_f}: {:e}", x - x_f);
        // The event is handed over just past the fold, KICK D_c of slip along the tangent:
        // X moves by KICK D_c / (slip rate), the rate large near the fold (under 1e-6 x_f at
        // a kick of 5e-3, so under KICK/5e-3 of that).
        let (x_on, _) = first.0.expect("an onset");
        assert!(x_on > x && x_on - x < KICK / 5e-3 * 1e-6 * x_f, "onset at {x_on}, fold at {x}");
    }
}
