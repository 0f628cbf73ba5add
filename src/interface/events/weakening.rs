//! The drive phase under linear slip weakening.
//!
//! Between state changes the response is no longer linear in X (a slipping node's coefficient
//! depends on its slip), so X advances in steps: to the next threshold of a stuck node, open
//! or close (exact, as for the other laws), and by at most the X that the current slip rates
//! turn into D_c/20 of slip. At each X the coefficients are brought to their slips by fixed
//! point (each iterate a linear solve with the coefficients frozen; an overdamped relaxation
//! at fixed X). A stable slip patch converges in a few iterates; past its critical length the
//! iterates run away until the nodes reach mu_d or the front arrests: a step whose relaxation
//! moves some node by more than D_c/2 at fixed X (ten times what the step control allows a
//! stable step) is an instability. It is classified like a static-kinetic event, and when it
//! ends every node sticks and heals to mu_s, as in the paper's model. Between instabilities a
//! node keeps the slip it has accumulated since the last one, slipping or stuck: a node that
//! stops in a stable process zone resumes at the coefficient it had reached. A slipping node
//! whose relaxation would move it backwards within a step sticks where the step started.

use super::active::Solver;
use super::classify::classify;
use super::handoff::{Found, Onset, Resolved, Resolver};
use super::operator::Affine;
use super::search::Fix;
use super::simulation::{stuck_err, Recorder};
use super::{tolerances, Event, EventKind, NodeState, Run};
use crate::error::Result;

/// Steps per D_c of slip of the fastest slipping node (step control).
const STEPS_PER_DC: f64 = 20.0;

pub(super) fn drive(
    sv: &mut Solver,
    mut rec: Recorder,
    dc: f64,
    resolver: &mut dyn Resolver,
    progress: &dyn Fn(f64),
) -> Result<Run> {
    let (n, pb) = (sv.n(), rec.pb);
    let x_end = pb.x_max.unwrap_or(f64::INFINITY);
    let mut lam = 0.0;
    let mut slipped = vec![false; n];
    let cap = tolerances::max_changes(n);
    let frac = |out: &Run, lam: f64| -> f64 {
        let by_x = if x_end.is_finite() { lam / x_end } else { 0.0 };
        by_x.max(out.sliding_events as f64 / pb.cycles.max(1) as f64).min(1.0)
    };
    let mut idle = 0;
    sv.heal_memory();
    loop {
        // Also here: a drive step without a state change reuses the last solve.
        rec.pb.cancel.check()?;
        let a0 = sv.solve()?;
        let u_pre: Vec<f64> = (0..n).map(|i| a0.b(i, lam)).collect();
        let f_pre = a0.f(sv.iu(), lam);
        let states_pre = sv.states().to_vec();
        let mu_pre = (0..n).map(|i| sv.mu_slip(i)).collect::<Vec<_>>();
        let (a, touched) = settle(sv, lam, cap, &u_pre, dc, pb.newton)?;
        let jump = (0..n).map(|i| (a.b(i, lam) - u_pre[i]).abs()).fold(0.0, f64::max);
        if jump > 0.5 * dc {
            let at = Onset {
                lam,
                a: &a,
                states_pre: &states_pre,
                f_pre,
                found: Found::Runaway { u_pre: &u_pre, mu_pre: &mu_pre, touched: &touched },
                slipped: &mut slipped,
                shown: frac(&rec.out, lam),
            };
            let go = resolver.resolve(sv, &mut rec, at)?;
            progress(frac(&rec.out, lam));
            if go == Resolved::Stop || rec.out.sliding_events >= pb.cycles {
                return Ok(rec.finish(sv));
            }
            continue;
        }
        if let Some((i, kind)) = stable_change(sv.states(), &states_pre) {
            rec.simple(sv, &a, lam, kind, i)?;
        }
        // Steady sliding: every contact node slipping at mu_d; nothing re-sticks any more.
        let steady = sv.all_contact_slipping()
            && (0..n).all(|i| sv.states()[i] == NodeState::Open || sv.mu_slip(i) <= sv.law().mu_d());
        if steady {
            rec.out.sliding_events += 1;
            rec.simple(sv, &a, lam, EventKind::Sliding, 0)?;
            progress(1.0);
            return Ok(rec.finish(sv));
        }
        // Next X: the next exact threshold, or the slip-rate step.
        let rate = (0..n)
            .filter(|&i| matches!(sv.states()[i], NodeState::Slip(_)))
            .map(|i| a.b1[i].abs())
            .fold(0.0, f64::max);
        let by_slip = if rate > 0.0 { dc / STEPS_PER_DC / rate } else { f64::INFINITY };
        let by_event = sv.next_event(&a, lam).map_or(f64::INFINITY, |e| e.0);
        let d = by_slip.min(by_event);
        if lam + d >= x_end {
            if !x_end.is_finite() {
                return Err(crate::error::Error::input(
                    "x-max",
                    "the loading reaches no further event and no end was given; give --x-max",
                ));
            }
            rec.simple(sv, &a, x_end, EventKind::End, 0)?;
            progress(1.0);
            return Ok(rec.finish(sv));
        }
        idle = if d == 0.0 { idle + 1 } else { 0 };
        if idle > cap {
            return Err(stuck_err("slip-weakening drive", lam));
        }
        // An exact threshold hit is applied by the next settle's rate problem.
        lam += d;
        progress(frac(&rec.out, lam));
    }
}

/// A stable change of the states from `pre` (nodes starting or stopping to slip, opening or
/// closing), as the event its first changed node makes; None if nothing changed.
pub(super) fn stable_change(states: &[NodeState], pre: &[NodeState]) -> Option<(usize, EventKind)> {
    let n = states.len();
    let i = (0..n).find(|&i| states[i] != pre[i])?;
    let kind = match (pre[i], states[i]) {
        (NodeState::Stick, NodeState::Slip(_)) => {
            let next_to = |k: Option<usize>| k.is_some_and(|k| matches!(states[k], NodeState::Slip(_)));
            if next_to(i.checked_sub(1)) || next_to((i + 1 < n).then_some(i + 1)) {
                EventKind::TipAdvance
            } else {
                EventKind::Nucleation
            }
        }
        (NodeState::Slip(_), NodeState::Stick) => EventKind::Stick,
        (_, NodeState::Open) => EventKind::Open,
        _ => EventKind::Close,
    };
    Some((i, kind))
}

/// The quasi-static resolution of a slip-weakening instability: the fixed-point relaxation
/// has run away to where the nodes reach mu_d or the front arrests (in [`settle`]); the
/// event is classified like a static-kinetic one and every node sticks and heals to mu_s.
pub(super) struct Runaway {
    pub(super) dc: f64,
    pub(super) end_at_crossing: bool,
}

impl Resolver for Runaway {
    fn resolve(&mut self, sv: &mut Solver, rec: &mut Recorder, at: Onset) -> Result<Resolved> {
        let (n, lam, dc) = (sv.n(), at.lam, self.dc);
        let Found::Runaway { u_pre, mu_pre, touched } = at.found else {
            // A node past its threshold: the paper's rule, as the other laws.
            return super::relax::Rules::default().resolve(sv, rec, at);
        };
        let moved: Vec<f64> = (0..n).map(|i| (at.a.b(i, lam) - u_pre[i]).abs()).collect();
        let i0 = moved.iter().enumerate().fold((0, 0.0), |b, (i, &m)| if m > b.1 { (i, m) } else { b }).0;
        // The region is the connected run around the largest jump of nodes that slipped in
        // the relaxation by more than 1 % of D_c (a corner that crept a little at the other
        // end is not part of it).
        let went = |i: usize| touched[i] && moved[i] > 0.01 * dc;
        let (first, last) = crate::numeric::run_around(i0, n, went);
        let all_slipping = sv.all_contact_slipping();
        // Nucleation: the most weakened node slipping when the step began.
        let node = (first..=last)
            .filter(|&i| matches!(at.states_pre[i], NodeState::Slip(_)))
            .min_by(|&i, &j| mu_pre[i].total_cmp(&mu_pre[j]))
            .unwrap_or(i0);
        let kind = classify(at.states_pre, sv.states(), (first, last), at.slipped, self.end_at_crossing);
        heal(sv, at.a, lam)?;
        let b = sv.solve()?;
        if kind.ends_cycle() {
            rec.out.sliding_events += 1;
        }
        rec.record(sv, &b, lam, |st| Event {
            kind,
            f: at.f_pre,
            x: lam,
            node,
            region: Some((first, last)),
            f_relaxed: st.f,
            backslip: 0,
            all_slipping,
        })?;
        Ok(Resolved::Go)
    }
}

/// Equilibrium at fixed X with every slipping node's coefficient at its slip: state changes
/// first (one at a time, as for the other laws), then the coefficients. Returns the solution
/// and the nodes that slipped at some iterate.
fn settle(
    sv: &mut Solver,
    lam: f64,
    cap: usize,
    u_pre: &[f64],
    dc: f64,
    newton: bool,
) -> Result<(Affine, Vec<bool>)> {
    let n = sv.n();
    // Looser than the state tolerances ([`tolerances::STATE`]): a node set slipping at its threshold by its
    // rate may settle a force tolerance's worth behind where it stood.
    let td = 1e-6 * sv.dscale();
    let mut touched = vec![false; n];
    // Newton from the start; after it fails (a runaway), again once fixed point has
    // contracted for 3 iterates in a row (the runaway has arrested and is settling). Without
    // `newton`, from SLOW_FP iterates on: a patch near its critical length contracts by
    // 1 - 1e-4 an iterate and would need ~1e5 of them.
    let (mut trying, mut last, mut shrinking) = (newton, f64::INFINITY, 0);
    let allowed = |it: usize| newton || it >= SLOW_FP;
    let mut stuck_at = vec![None; n];
    // A relaxation may run through every node and its coefficients converge geometrically.
    for it in 0..50 * cap {
        let a = sv.solve()?;
        if let Fix::Changed(i, what) = sv.rate_fix(&a, lam, true)? {
            // A node stuck (closed) again where it was stuck (closed) before in this settle is
            // a cycle: from now on the sticks go by speed (a stick), or the node stays open
            // until it penetrates without separating (a close).
            if what == EventKind::Stick || what == EventKind::Close {
                let u = sv.anchor(i);
                if stuck_at[i].is_some_and(|v: f64| (u - v).abs() <= 1e-12 * sv.dscale()) {
                    if what == EventKind::Stick {
                        sv.hold(true, None);
                    } else {
                        sv.set_state(i, NodeState::Open, 0.0)?;
                        sv.hold(false, Some(i));
                    }
                }
                stuck_at[i] = Some(u);
            }
            continue;
        }
        let mut back = None;
        for i in 0..n {
            if let NodeState::Slip(s) = sv.states()[i] {
                touched[i] = true;
                if s * (a.b(i, lam) - u_pre[i]) < -td {
                    back = Some(i);
                    break;
                }
            }
        }
        if let Some(i) = back {
            sv.set_state(i, NodeState::Stick, u_pre[i])?;
            continue;
        }
        let change = coefficients(sv, &a, lam, false, tolerances::COEFFICIENT * sv.law().mu_s());
        if change.is_empty() {
            sv.release();
            return Ok((a, touched));
        }
        let step = change.iter().map(|c| (c.1 - sv.mu_slip(c.0)).abs()).fold(0.0, f64::max);
        shrinking = if step < last { shrinking + 1 } else { 0 };
        last = step;
        sv.set_coefficients(&change)?;
        if trying || (allowed(it) && shrinking >= 3) {
            trying = newton_coefficients(sv, lam, u_pre, dc, td)?;
            shrinking = 0;
        }
    }
    Err(stuck_err("slip-weakening relaxation", lam))
}

/// The slipping nodes' coefficients at their slips in `a` where they differ by more than
/// [`tolerances::COEFFICIENT`] mu_s from their rows', with Newton springs (d mu/d slip) p centred there if asked.
pub(super) fn coefficients(
    sv: &Solver,
    a: &Affine,
    lam: f64,
    springs: bool,
    tol: f64,
) -> Vec<(usize, f64, f64, f64)> {
    let mut change = Vec::new();
    for i in 0..sv.n() {
        if let NodeState::Slip(s) = sv.states()[i] {
            let u = a.b(i, lam);
            let slip = sv.slip_at(i, s, u);
            let mu = sv.law().kinetic(slip);
            let k = if springs { sv.law().kinetic_slope(slip) * a.f(sv.n() + i, lam) } else { 0.0 };
            if (mu - sv.mu_slip(i)).abs() > tol || k != sv.spring(i) {
                change.push((i, mu, k, u));
            }
        }
    }
    change
}

/// Whether the frozen system A stays stable under the weakening springs K: det(I + A^-1 K) > 0
/// over the springs' rows (A^-1 K has real eigenvalues >= 0 for a symmetric A, and the first
/// one past 1 is where fixed point starts to run away and the tangent A + K turns indefinite).
fn stable(sv: &mut Solver, springs: &[(usize, f64)]) -> Result<bool> {
    let m = springs.len();
    if m == 0 {
        return Ok(true);
    }
    let dofs: Vec<usize> = springs.iter().map(|&(i, _)| i).collect();
    let inv = sv.inverse_block(&dofs)?;
    let mat =
        nalgebra::DMatrix::from_fn(m, m, |r, c| f64::from(u8::from(r == c)) + springs[r].1 * inv[r * m + c]);
    Ok(mat.lu().determinant() > 0.0)
}

/// Fixed-point iterates of one relaxation after which Newton is tried even without
/// `Problem::newton`.
const SLOW_FP: usize = 10000;

/// Newton iterates allowed on the coefficients.
const NEWTON_MAX: usize = 30;

/// The coefficients by Newton at fixed states, each slipping row linearised in its own slip:
/// a few iterates where fixed point (each iterate a solve with the coefficients frozen) needs
/// hundreds near a patch's critical length, and to the same equilibrium (checked against
/// fixed point to 1e-4 D_c on validation/friction's sw_nt4). Returns false, with the
/// coefficients back where Newton started, when [`newton`] fails or converges to an unstable
/// equilibrium: past the critical length there is no stable equilibrium nearby and the
/// relaxation must run away by fixed point. Leaves no spring.
fn newton_coefficients(sv: &mut Solver, lam: f64, u_pre: &[f64], dc: f64, td: f64) -> Result<bool> {
    let start = snapshot(sv);
    let Some(change) = newton(sv, lam, u_pre, dc, td)? else { return Ok(false) };
    // Converged: the spring-free rows at these coefficients, if the equilibrium is one that
    // fixed point would reach (stable).
    let keep: Vec<_> = change.iter().map(|&(i, mu, _, _)| (i, mu, 0.0, 0.0)).collect();
    let springs: Vec<(usize, f64)> = change.iter().filter(|c| c.2 != 0.0).map(|c| (c.0, c.2)).collect();
    sv.set_coefficients(&keep)?;
    if stable(sv, &springs)? {
        return Ok(true);
    }
    sv.set_coefficients(&start)?;
    Ok(false)
}

/// The exact weakening path's corrector at X = lam (`stepped`): the slipping coefficients at
/// their slips by [`newton`], then the rows left linearised at that equilibrium (springs
/// (d mu/d slip) p centred on it), so that the solve returned is the path's tangent line:
/// b(lam) the equilibrium, b1 = db/dX along the branch. None: no equilibrium near (see
/// [`newton`]), the rows back where it started.
pub(super) fn tangent(sv: &mut Solver, lam: f64, u_pre: &[f64], dc: f64, td: f64) -> Result<Option<Affine>> {
    let Some(change) = newton(sv, lam, u_pre, dc, td)? else { return Ok(None) };
    sv.set_coefficients(&change)?;
    Ok(Some(sv.solve()?))
}

/// Whether the system linearised at the current equilibrium (the tangent springs on) is
/// stable: det > 0 of its free system (the banded factor keeps the sign; the frozen system's
/// is positive, as for any friction small enough for the frozen problem to be well posed),
/// or else [`stable`] on the springs' rows with the springs lifted for the test.
pub(super) fn tangent_stable(sv: &mut Solver) -> Result<bool> {
    if let Some(sign) = sv.det_sign()? {
        return Ok(sign > 0.0);
    }
    let on = snapshot(sv);
    let springs: Vec<(usize, f64)> = on.iter().filter(|c| c.2 != 0.0).map(|c| (c.0, c.2)).collect();
    if springs.is_empty() {
        return Ok(true);
    }
    let off: Vec<_> = on.iter().map(|&(i, mu, _, _)| (i, mu, 0.0, 0.0)).collect();
    sv.set_coefficients(&off)?;
    let ok = stable(sv, &springs)?;
    sv.set_coefficients(&on)?;
    Ok(ok)
}

/// Slipping rows: (node, coefficient, spring, its centre).
pub(super) type Rows = Vec<(usize, f64, f64, f64)>;

/// The slipping rows as they are.
pub(super) fn snapshot(sv: &Solver) -> Rows {
    (0..sv.n())
        .filter(|&i| matches!(sv.states()[i], NodeState::Slip(_)))
        .map(|i| (i, sv.mu_slip(i), sv.spring(i), sv.set.spring_u[i]))
        .collect()
}

/// Newton on the slipping coefficients at fixed states and X = lam, from the rows as they
/// are: the converged change (coefficients within [`tolerances::COEFFICIENT`] mu_s of their
/// slips, with the springs centred there), not yet applied. None, with the rows back where it
/// started, when an iterate moves a node by more than D_c/2 from where Newton started or back
/// past `u_pre` by more than `td`, or it does not converge in [`NEWTON_MAX`] iterates.
fn newton(sv: &mut Solver, lam: f64, u_pre: &[f64], dc: f64, td: f64) -> Result<Option<Rows>> {
    let start = snapshot(sv);
    let mut a = sv.solve()?;
    let u0: Vec<f64> = (0..sv.n()).map(|i| a.b(i, lam)).collect();
    for _ in 0..NEWTON_MAX {
        let change = coefficients(sv, &a, lam, true, tolerances::COEFFICIENT * sv.law().mu_s());
        if change.iter().all(|c| (c.1 - sv.mu_slip(c.0)).abs() <= tolerances::COEFFICIENT * sv.law().mu_s()) {
            return Ok(Some(change));
        }
        sv.set_coefficients(&change)?;
        a = sv.solve()?;
        let wild = start.iter().any(|&(i, ..)| {
            let NodeState::Slip(s) = sv.states()[i] else { return false };
            let u = a.b(i, lam);
            (u - u0[i]).abs() > 0.5 * dc || s * (u - u_pre[i]) < -td
        });
        if wild {
            break;
        }
    }
    sv.set_coefficients(&start)?;
    Ok(None)
}

/// Every slipping node sticks where it is and heals to mu_s (end of an instability).
fn heal(sv: &mut Solver, a: &Affine, lam: f64) -> Result<()> {
    let ch: Vec<(usize, NodeState, f64)> = (0..sv.n())
        .filter(|&i| matches!(sv.states()[i], NodeState::Slip(_)))
        .map(|i| (i, NodeState::Stick, a.b(i, lam)))
        .collect();
    sv.set_many(&ch)?;
    sv.heal_memory();
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::super::{springs, NodeState, Problem};
    use super::*;
    use crate::law::Law;

    /// A slow relaxation settles, at a cost set by the iterate caps, not by round-off. Six
    /// nodes, drive at the interface (no tilt, P = N/6 each); node 0's shear spring k0 = 2 is
    /// twice the others', so it slips first, at lam_0 = mu_s P/k0. Slipping u from its anchor 0
    /// under linear weakening, its equilibrium k0 (lam - u) = (mu_s - w u/P) P, w = (mu_s -
    /// mu_d) P/D_c, is u* = (k0 lam - mu_s P)/(k0 - w). With w = (1 - 1e-4) k0 the fixed point
    /// contracts by w/k0 = 1 - 1e-4 an iterate (2.7e5 iterates to 1e-12): Newton must take over
    /// after SLOW_FP of them and stop on the coefficient test 1e-12 mu_s, which bounds
    /// |u - u*| by 1e-12 mu_s P/(k0 - w).
    /// The six-node scene below, node 0 set slipping from its anchor 0 at the drive `lam`
    /// where u* = D_c/2: (S, problem, lam, u*, D_c, the bound on |u - u*|).
    struct NearCritical {
        s: Vec<f64>,
        pb: Problem,
        lam: f64,
        want: f64,
        dc: f64,
        tol: f64,
    }

    const N6: usize = 6;

    fn near_critical(cancel: crate::Cancel) -> NearCritical {
        let x: Vec<f64> = (0..N6).map(|i| i as f64 - 2.5).collect();
        let mut kt = vec![1.0; N6];
        kt[0] = 2.0;
        let (k0, n_force, mu_s, mu_d) = (2.0, 1.0, 0.6, 0.3);
        let p = n_force / N6 as f64;
        let w = (1.0 - 1e-4) * k0;
        let dc = (mu_s - mu_d) * p / w;
        let law = Law::slip_weakening(mu_s, mu_d, dc).unwrap();
        let lam = (mu_s * p + 0.5 * dc * (k0 - w)) / k0;
        NearCritical {
            s: springs::operator(&x, &kt, 2.0, 0.0),
            pb: Problem { n_force, law, cancel, ..Default::default() },
            lam,
            want: (k0 * lam - mu_s * p) / (k0 - w),
            dc,
            tol: 1e-12 * mu_s * p / (k0 - w),
        }
    }

    /// Node 0 slipping; the displacements before the relaxation.
    fn start(sv: &mut Solver, lam: f64) -> Vec<f64> {
        sv.set_state(0, NodeState::Slip(1.0), 0.0).unwrap();
        let a0 = sv.solve().unwrap();
        (0..N6).map(|i| a0.b(i, lam)).collect()
    }

    #[test]
    fn a_near_critical_relaxation_settles_by_newton_after_the_fixed_point_cap() {
        let sc = near_critical(crate::Cancel::new());
        let mut sv = springs::solver(&sc.s, N6, &sc.pb);
        let u_pre = start(&mut sv, sc.lam);
        let before = sv.counts().0;
        let (a, touched) =
            settle(&mut sv, sc.lam, tolerances::max_changes(N6), &u_pre, sc.dc, false).unwrap();
        let u = a.b(0, sc.lam);
        assert!(
            (u - sc.want).abs() < sc.tol,
            "u {u} vs u* {} (D_c {}): off by {:e}",
            sc.want,
            sc.dc,
            (u - sc.want).abs()
        );
        assert!(touched[0] && !touched[1..].iter().any(|&t| t));
        assert_eq!(sv.states()[1..], [NodeState::Stick; 5]);
        // Each fixed-point iterate is one coefficient change (a remove and an add of the row):
        // SLOW_FP of them, then a few for Newton.
        let updates = sv.counts().0 - before;
        assert!((2 * SLOW_FP..2 * SLOW_FP + 100).contains(&updates), "{updates} bordering updates");
    }

    /// The same relaxation (2e4 iterates, no event, no progress point) stops at its first
    /// fresh solve once the host cancels: one coefficient change (2 updates) at most.
    #[test]
    fn a_cancel_stops_a_relaxation_between_events() {
        let host = crate::Cancel::new();
        let sc = near_critical(host.clone());
        let mut sv = springs::solver(&sc.s, N6, &sc.pb);
        let u_pre = start(&mut sv, sc.lam);
        host.cancel();
        let before = sv.counts().0;
        let r = settle(&mut sv, sc.lam, tolerances::max_changes(N6), &u_pre, sc.dc, false);
        assert!(matches!(r, Err(crate::Error::Interrupted)), "{:?}", r.map(|_| ()));
        assert!(sv.counts().0 - before <= 2, "{} updates after the cancel", sv.counts().0 - before);
    }
}
