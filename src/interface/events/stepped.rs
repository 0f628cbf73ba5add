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
use super::search::Hit;
use super::simulation::{apply_hit, hit_kind, settle_continuous, stuck_err, Recorder};
use super::{tolerances, EventKind, NodeState};
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
    let cap = tolerances::max_changes(n);
    let x_end = pb.x_max.unwrap_or(f64::INFINITY);
    let mut x_stop = x_end;
    let mut sliding_seen = false;
    let mut lam = 0.0;
    let mut idle = 0;
    let mut done = vec![0.0f64; n]; // slip since each coefficient was frozen
    let mut slipped = vec![false; n]; // by instabilities since the last cycle end
    loop {
        pb.cancel.check()?;
        let a = settle_continuous(sv, lam, true, cap, "drive")?;
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
        // Next X: the next threshold, or a slipping node's next D_c / steps_per_dc of slip.
        let mut next: Option<(f64, Option<(usize, Hit)>)> =
            sv.next_event(&a, lam).map(|(dl, i, h)| (dl, Some((i, h))));
        if weakens {
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
        let Some((dl, hit)) = next.filter(|b| lam + b.0 < x_stop) else {
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
