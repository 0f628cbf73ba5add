//! The instability of a static-kinetic node at fixed X: the event rules ([`Rule`]: the paper's
//! region relaxed at once, or the overdamped cascade), each ending with every node in contact
//! stuck again; [`Rules`], the quasi-static drive's resolver that applies them.

use super::active::Solver;
use super::classify::classify;
use super::handoff::{Found, Onset, Resolved, Resolver};
use super::operator::Affine;
use super::simulation::{stuck_err, Recorder};
use super::{tolerances, Event, NodeState};
use crate::error::Result;
use crate::law::{Residual, Rule};

/// The quasi-static rules as the drive's [`Resolver`]: the law's rule ([`instability`]), then
/// the event classified and recorded. Keeps the last region for the Zeno guard.
#[derive(Default)]
pub(super) struct Rules {
    last_region: Option<(usize, usize)>,
}

impl Resolver for Rules {
    fn resolve(&mut self, sv: &mut Solver, rec: &mut Recorder, at: Onset) -> Result<Resolved> {
        let lam = at.lam;
        // A runaway has no single node past its threshold: the largest jump nucleates.
        let i0 = match at.found {
            Found::Threshold { node } => node,
            Found::Runaway { u_pre, .. } => {
                (0..sv.n())
                    .map(|i| (i, (at.a.b(i, lam) - u_pre[i]).abs()))
                    .fold((0, 0.0), |b, (i, m)| if m > b.1 { (i, m) } else { b })
                    .0
            }
        };
        let (region, backslip, all_slip) = instability(sv, at.a, lam, i0)?;
        // Zeno guard: a node that relaxes alone twice in a row (the trailing corner as
        // p -> 0) slides on continuously at mu_d (creep) until its slip rate reverses or it
        // opens. It is recorded once the contact around it is consistent again (its pressure
        // may fall below zero as it slides).
        if region == (i0, i0) && self.last_region == Some((i0, i0)) {
            let b = sv.solve()?;
            let sg = if b.f(i0, lam) > 0.0 { -1.0 } else { 1.0 };
            sv.set_state(i0, NodeState::Slip(sg), 0.0)?;
            return Ok(Resolved::Creep(i0));
        }
        let a2 = sv.solve()?;
        let kind = classify(at.states_pre, sv.states(), region, at.slipped, rec.pb.end_at_crossing);
        if kind.ends_cycle() {
            rec.out.sliding_events += 1;
        }
        self.last_region = Some(region);
        rec.record(sv, &a2, lam, |st| Event {
            kind,
            f: at.f_pre,
            x: lam,
            node: i0,
            region: Some(region),
            f_relaxed: st.f,
            backslip,
            all_slipping: all_slip,
        })?;
        Ok(Resolved::Go)
    }
}

/// Static-kinetic instability nucleated at i0 at fixed X = lam: applies the rule, relaxes,
/// re-sticks everything in contact. Returns the slipped region (first, last node), the
/// number of region nodes that slipped backwards, and whether every contact node was slipping
/// at the end of the relaxation (whole-interface slip).
pub(super) fn instability(
    sv: &mut Solver,
    a: &Affine,
    lam: f64,
    i0: usize,
) -> Result<((usize, usize), usize, bool)> {
    let n = sv.n();
    let u_start: Vec<f64> = (0..n).map(|i| a.b(i, lam)).collect();
    // Every contact node sticks at its current position to start with.
    for i in 0..n {
        if sv.set.states[i] != NodeState::Open && sv.set.states[i] != NodeState::Stick {
            sv.set_state(i, NodeState::Stick, u_start[i])?;
        } else if sv.set.states[i] == NodeState::Stick && sv.set.anchor[i] != u_start[i] {
            sv.move_anchor(i, u_start[i]);
        }
    }
    let rule = sv.law().rule();
    let in_region = match rule {
        Rule::Paper => paper(sv, a, lam, i0, &u_start)?,
        Rule::Overdamped => overdamped(sv, a, lam, i0, &u_start)?,
    };
    // Every node still slipping sticks where it stopped.
    let td = tolerances::STATE * sv.dscale;
    let b = sv.solve()?;
    let all_slip = sv.all_contact_slipping();
    let mut backslip = 0;
    let mut ch = Vec::new();
    for i in 0..n {
        if let NodeState::Slip(s) = sv.set.states[i] {
            let u = b.b(i, lam);
            if s * (u - u_start[i]) < -td {
                backslip += 1;
            }
            ch.push((i, NodeState::Stick, u));
        }
    }
    sv.set_many(&ch)?;
    let first = (0..n).find(|&i| in_region[i]).unwrap_or(i0);
    let last = (0..n).rev().find(|&i| in_region[i]).unwrap_or(i0);
    Ok(((first, last), backslip, all_slip))
}

/// Slip direction opposing the shear force t.
fn dir(t: f64) -> f64 {
    if t > 0.0 {
        -1.0
    } else {
        1.0
    }
}

/// The paper's rule: the connected region around i0 where the pre-event |T| >= mu_d P slips at
/// once, then contact is made consistent. With [`crate::law::PaperOptions`] off
/// their defaults, by turns after contact: a region node that would end behind where it
/// started sticks there (the worst first), and the slipping rows' coefficients are moved
/// to mu_d P(before)/P so that T = -s mu_d P(before) (the paper's mu_d p(x, F_i)). Returns the
/// region's nodes.
fn paper(sv: &mut Solver, a: &Affine, lam: f64, i0: usize, u_start: &[f64]) -> Result<Vec<bool>> {
    let n = sv.n();
    let tf = tolerances::STATE * sv.fscale;
    let mu_d = sv.law().mu_d();
    let t_start: Vec<f64> = (0..n).map(|i| a.f(i, lam)).collect();
    let above =
        |i: usize| sv.set.states[i] != NodeState::Open && t_start[i].abs() >= mu_d * a.f(n + i, lam) - tf;
    let (lo, hi) = crate::numeric::run_around(i0, n, above);
    let ch: Vec<(usize, NodeState, f64)> =
        (lo..=hi).map(|i| (i, NodeState::Slip(dir(t_start[i])), 0.0)).collect();
    sv.set_many(&ch)?;
    let opts = sv.law().paper_options();
    let td = tolerances::STATE * sv.dscale;
    let p_start: Vec<f64> = (0..n).map(|i| a.f(n + i, lam)).collect();
    // Contact consistency of the relaxed state, then the coefficients' fixed point, relaxed
    // by Aitken's factor: most of the region contracts (P moves with F through the tilt, by
    // a fraction of the relaxation), but a corner's P follows its own T so strongly that the
    // plain iterate oscillates and diverges ((0.8, 0.5), t = 2 mm: ratio -1.4 per iterate).
    let mut aitken = Aitken::new();
    for _ in 0..tolerances::max_changes(n) {
        let b = sv.solve()?;
        if contact(sv, &b, lam)?.is_some() {
            aitken.reset();
            continue;
        }
        if !opts.backslip {
            let worst = (0..n)
                .filter_map(|i| match sv.set.states[i] {
                    NodeState::Slip(s) => Some((i, s * (b.b(i, lam) - u_start[i]))),
                    _ => None,
                })
                .filter(|&(_, d)| d < -td)
                .min_by(|x, y| x.1.total_cmp(&y.1));
            if let Some((i, _)) = worst {
                sv.set_state(i, NodeState::Stick, u_start[i])?;
                aitken.reset();
                continue;
            }
        }
        if opts.residual == Residual::PreEvent {
            let (nodes, r) = pre_event_residuals(sv, &b, lam, &p_start);
            let tol = tolerances::COEFFICIENT * sv.law().mu_s();
            if r.iter().any(|v| v.abs() > tol) {
                let w = aitken.factor(&nodes, &r);
                let change: Vec<(usize, f64, f64, f64)> = nodes
                    .iter()
                    .zip(&r)
                    .map(|(&i, &ri)| (i, (sv.mu_slip(i) + w * ri).max(0.0), 0.0, 0.0))
                    .collect();
                sv.set_coefficients(&change)?;
                continue;
            }
        }
        return Ok((0..n).map(|i| (lo..=hi).contains(&i)).collect());
    }
    Err(stuck_err("paper-rule relaxation (contact)", lam))
}

/// Per slipping node, the coefficient that gives T = -s mu_d P(before) at the pressures of
/// `b` minus the row's: mu_d P(before)/P - mu. A node whose pressure is within the state
/// tolerance of 0 counts 0 (mu_d P(before)/P has no finite value there; the contact check
/// opens it if it pulls).
fn pre_event_residuals(sv: &Solver, b: &Affine, lam: f64, p_start: &[f64]) -> (Vec<usize>, Vec<f64>) {
    let n = sv.n();
    let tf = tolerances::STATE * sv.fscale;
    let mu_d = sv.law().mu_d();
    (0..n)
        .filter(|&i| matches!(sv.set.states[i], NodeState::Slip(_)))
        .map(|i| {
            let p = b.f(n + i, lam);
            (i, if p > tf { mu_d * p_start[i] / p - sv.mu_slip(i) } else { 0.0 })
        })
        .unzip()
}

/// Aitken's dynamic relaxation of a vector fixed point x <- x + w r (Irons & Tuck 1969;
/// Kuettler & Wall 2008): w_k = -w_{k-1} r_{k-1}.(r_k - r_{k-1}) / |r_k - r_{k-1}|^2, which
/// for a linear map is the secant along the last step. Restarts at w = 1 (the plain iterate)
/// when the slipping set changes.
struct Aitken {
    w: f64,
    prev: Option<(Vec<usize>, Vec<f64>)>,
}

impl Aitken {
    /// Bound on |w|: a step 10x the plain iterate's is far past any ratio measured.
    const W_MAX: f64 = 10.0;

    fn new() -> Aitken {
        Aitken { w: 1.0, prev: None }
    }
    fn reset(&mut self) {
        self.w = 1.0;
        self.prev = None;
    }
    fn factor(&mut self, nodes: &[usize], r: &[f64]) -> f64 {
        if let Some((pn, pr)) = &self.prev {
            if pn == nodes {
                let (mut num, mut den) = (0.0, 0.0);
                for (a, b) in pr.iter().zip(r) {
                    num += a * (b - a);
                    den += (b - a) * (b - a);
                }
                if den > 0.0 {
                    let w = -self.w * num / den;
                    if w.is_finite() && w != 0.0 {
                        self.w = w.clamp(-Self::W_MAX, Self::W_MAX);
                    }
                }
            }
        }
        self.prev = Some((nodes.to_vec(), r.to_vec()));
        self.w
    }
}

/// The overdamped cascade: i0 slips, then by turns contact is made consistent, the node
/// slipping backwards most re-sticks where it started slipping, and every stuck node above
/// its threshold (mu_d once it has slipped in this event) joins, until nothing changes.
/// Returns the nodes that slipped.
fn overdamped(sv: &mut Solver, a: &Affine, lam: f64, i0: usize, u_start: &[f64]) -> Result<Vec<bool>> {
    let n = sv.n();
    let tf = tolerances::STATE * sv.fscale;
    let td = tolerances::STATE * sv.dscale;
    let (mu_s, mu_d) = (sv.law().mu_s(), sv.law().mu_d());
    let mut in_region = vec![false; n];
    let mut awake = vec![false; n];
    // Where each node last started slipping: a node that closed in the relaxation starts from
    // where it landed, not from the event's start.
    let mut u_join = u_start.to_vec();
    in_region[i0] = true;
    awake[i0] = true;
    sv.set_state(i0, NodeState::Slip(dir(a.f(i0, lam))), 0.0)?;
    for _ in 0..tolerances::max_changes(n) {
        let b = sv.solve()?;
        // Contact first.
        match contact(sv, &b, lam)? {
            Some(Landed::Closed(i, u)) => {
                u_join[i] = u;
                continue;
            }
            Some(Landed::Opened) => continue,
            None => {}
        }
        // Backward slip: the worst re-sticks where it started slipping.
        let worst = (0..n)
            .filter_map(|i| match sv.set.states[i] {
                NodeState::Slip(s) => Some((i, s * (b.b(i, lam) - u_join[i]))),
                _ => None,
            })
            .filter(|&(_, d)| d < -td)
            .min_by(|x, y| x.1.total_cmp(&y.1));
        if let Some((i, _)) = worst {
            sv.set_state(i, NodeState::Stick, u_join[i])?;
            continue;
        }
        // Cascade: every stuck node above its threshold joins.
        let join: Vec<(usize, f64)> = (0..n)
            .filter(|&i| sv.set.states[i] == NodeState::Stick)
            .filter_map(|i| {
                let (t, p) = (b.f(i, lam), b.f(n + i, lam));
                let thr = if awake[i] { mu_d } else { mu_s };
                (t.abs() > thr * p + tf).then_some((i, dir(t)))
            })
            .collect();
        if join.is_empty() {
            return Ok(in_region);
        }
        let ch: Vec<(usize, NodeState, f64)> =
            join.iter().map(|&(i, s)| (i, NodeState::Slip(s), 0.0)).collect();
        for &(i, _) in &join {
            awake[i] = true;
            in_region[i] = true;
        }
        sv.set_many(&ch)?;
    }
    Err(stuck_err("overdamped relaxation", lam))
}

/// What one contact fix did.
enum Landed {
    Opened,
    /// Node i closed and sticks at u.
    Closed(usize, f64),
}

/// The first node (in order) whose contact is inconsistent in b: a node in contact pulled
/// (P < 0) opens, an open node penetrating (gap < 0) sticks where it is.
fn contact(sv: &mut Solver, b: &Affine, lam: f64) -> Result<Option<Landed>> {
    let n = sv.n();
    let tf = tolerances::STATE * sv.fscale;
    let td = tolerances::STATE * sv.dscale;
    for i in 0..n {
        let (p, g) = (b.f(n + i, lam), b.b(n + i, lam));
        if sv.set.states[i] != NodeState::Open && p < -tf {
            sv.set_state(i, NodeState::Open, 0.0)?;
            return Ok(Some(Landed::Opened));
        }
        if sv.set.states[i] == NodeState::Open && g < -td {
            // It lands where it is now: sticking it at its position from before the
            // relaxation would drag it back, pull it off again, and cycle.
            let u = b.b(i, lam);
            sv.set_state(i, NodeState::Stick, u)?;
            return Ok(Some(Landed::Closed(i, u)));
        }
    }
    Ok(None)
}

#[cfg(test)]
mod tests {
    use super::super::{springs, NodeState, Problem};
    use super::*;
    use crate::law::Law;

    /// Two identical nodes with the drive at the interface (h = 0, no tilt): both stuck at 0
    /// carry T = -kt lam, P = N/2 and reach mu_s P together at lam* = mu_s N/(2 kt).
    fn uniform(rule: Rule) -> (Vec<f64>, Problem, f64) {
        let (kt, n_force, mu_s) = (1.0, 1.0, 0.6);
        let s = springs::operator(&[-1.0, 1.0], &[kt, kt], 2.0, 0.0);
        let pb =
            Problem { n_force, law: Law::static_kinetic(mu_s, 0.3, rule).unwrap(), ..Default::default() };
        (s, pb, mu_s * n_force / (2.0 * kt))
    }

    /// The paper's rule at lam*: the region is both nodes (each at |T| >= mu_d P), it relaxes
    /// to T_i = -mu_d P_i, a whole slip, and everything re-sticks where it stopped:
    /// u_i = lam* - mu_d N/(2 kt), F = mu_d N.
    #[test]
    fn the_paper_rule_relaxes_a_uniform_interface_to_mu_d() {
        let (s, pb, lam) = uniform(Rule::Paper);
        let mut sv = springs::solver(&s, 2, &pb);
        let a = sv.solve().unwrap();
        let (region, backslip, all_slip) = instability(&mut sv, &a, lam, 0).unwrap();
        assert_eq!((region, backslip, all_slip), ((0, 1), 0, true));
        assert_eq!(sv.states(), &[NodeState::Stick; 2]);
        let b = sv.solve().unwrap();
        let st = sv.record(&b, lam, None);
        for i in 0..2 {
            assert!((st.t_force[i] + 0.3 * st.p_force[i]).abs() < 1e-14, "node {i}: T {}", st.t_force[i]);
            assert!((st.u[i] - (lam - 0.3 * 0.5)).abs() < 1e-14, "node {i}: u {}", st.u[i]);
        }
        assert!((st.f - 0.3).abs() < 1e-14, "F {} vs mu_d N = 0.3", st.f);
    }

    /// The overdamped cascade on the same interface: node 0 relaxes alone (nothing couples the
    /// nodes' shear at h = 0, and node 1 sits exactly at, not above, mu_s P), so the region is
    /// node 0 and node 1 keeps T = -mu_s P.
    #[test]
    fn the_overdamped_cascade_stops_where_no_threshold_is_exceeded() {
        let (s, pb, lam) = uniform(Rule::Overdamped);
        let mut sv = springs::solver(&s, 2, &pb);
        let a = sv.solve().unwrap();
        let (region, backslip, all_slip) = instability(&mut sv, &a, lam, 0).unwrap();
        assert_eq!((region, backslip, all_slip), ((0, 0), 0, false));
        let b = sv.solve().unwrap();
        let st = sv.record(&b, lam, None);
        assert!((st.t_force[0] + 0.3 * 0.5).abs() < 1e-14, "T_0 {}", st.t_force[0]);
        assert!((st.t_force[1] + 0.6 * 0.5).abs() < 1e-14, "T_1 {}", st.t_force[1]);
        assert!((st.f - 0.45).abs() < 1e-14, "F {}", st.f);
    }
}
