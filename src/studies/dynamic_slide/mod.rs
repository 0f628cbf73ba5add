//! `slide --dynamics`: the paper's plate-driven block, loaded quasi-statically and exactly
//! between events, each instability run dynamically with the drive held (issue 33, part 3).
//!
//! 1. Loading: the event solver's own active set ([`crate::interface::events`]'s `Solver` on
//!    the dense condensed S or, with `--operator banded`, the banded block: O(n) a solve):
//!    its normal phase, then U_H with nodes sticking, slipping (at a frozen coefficient) or
//!    opening, every change found exactly. Under slip weakening a slipping node's coefficient
//!    is brought to its slip every D_c/20 of slip (`DynamicOptions::weakening_steps`; a fixed
//!    point at fixed U_H, each iterate one solve); when that fixed point diverges (a change
//!    above D_c/2 in one iterate, or 30 iterates without settling to 1e-3 D_c) the patch is
//!    unstable and the event is run dynamically (`steps.rs`).
//! 2. The event ([`crate::dynamics::driven`]): from the static field (v = 0), U_H held, until
//!    no node slips and the kinetic energy is below 1e-6 of what the event dissipated, both
//!    for one period of the block's thickness mode.
//! 3. The static equilibrium with every contact node anchored where the event left it; an
//!    event in which some node weakened fully (slip >= D_c) is an instability: every node
//!    heals to mu_s (slip memory 0), as in the quasi-static solver; otherwise nodes keep
//!    their slip. Loading continues from there.
//!
//! Coulomb friction never becomes unstable, so a Coulomb run is the static loading alone:
//! the same events as `slide` (tests/it/dynamics.rs).

use crate::dynamics::driven::{DynState, EventLimits, EventRecord};
use crate::dynamics::waves::WaveSpeeds;
use crate::error::{Error, Result};
use crate::interface::banded::{BandedOperator, Solving};
use crate::interface::condense::{condense, Condensed};
use crate::interface::events::{self, tolerances, Event, EventKind, NodeState, Operator, Phase};
use crate::interface::law::Law;
use crate::linalg::solve::SolverOptions;
use crate::progress::Progress;
use crate::scene::Scene;
use crate::studies::slide::{SlideOptions, SlideResult};
use events::operator::Affine;
use events::search::Hit;
use events::simulation::{apply_hit, hit_kind, normal_phase, settle_continuous, start, stuck_err};
use std::time::Instant;

pub mod assumption5;
pub mod fronts;
pub mod physics;
pub mod refine;
mod setup;
mod steps;
pub mod summary;
pub use physics::{default_dc, smallest_resolved_dc};
pub mod velocity;
use setup::Setup;
use steps::{anchor_after, arrest, classify_event, crossing, relax};

/// The dynamic options beside the slide options.
#[derive(Debug, Clone)]
pub struct DynamicOptions {
    /// Kelvin-Voigt eta, s; None: [`DEFAULT_DAMPING_RATIO`] of critical at the thickness mode.
    pub damping: Option<f64>,
    /// Time step as a fraction of the stable one.
    pub courant: f64,
    /// End of an event: kinetic energy below this fraction of the event's dissipation.
    pub ke_fraction: f64,
    /// Cap on the steps of one event, in thickness-mode periods; None: [`event_cap_periods`]
    /// (what a front crossing the interface and the decay to `ke_fraction` need, times 4).
    pub max_periods: Option<f64>,
    /// Constant drive velocity dU_H/dt, m/s (None: the drive held during each event and the
    /// loading quasi-static; see [`velocity`]).
    pub drive_velocity: Option<f64>,
    /// Cap on the explicit steps of a constant-velocity run (X_max / V / dt).
    pub max_velocity_steps: u64,
    /// The rigid plate's own mass (kg/m) and rotational inertia about its centre of mass at
    /// the block top's mid-point (kg m^2/m); 0: the massless limit
    /// ([`crate::dynamics::driven::Layout::with_plate`]).
    pub plate_mass: f64,
    pub plate_inertia: f64,
    /// After an instability heal only the nodes that slipped in it (event slip above
    /// D_c/100), the others keeping their slip; false: every node heals (the model's rule).
    pub heal_slipped_only: bool,
    /// The held mode's static loading updates a slipping node's slip-weakening coefficient
    /// every D_c / this of its slip; between updates the coefficient lags by up to
    /// (mu_s - mu_d) / this (validation/dynamics/converge/README.md, "The static loading's
    /// weakening step"). The constant-velocity drive updates it every explicit step instead.
    pub weakening_steps: f64,
}

impl Default for DynamicOptions {
    fn default() -> Self {
        Self {
            damping: None,
            courant: DEFAULT_COURANT,
            ke_fraction: 1e-6,
            max_periods: None,
            drive_velocity: None,
            max_velocity_steps: velocity::MAX_STEPS,
            plate_mass: 0.0,
            plate_inertia: 0.0,
            heal_slipped_only: false,
            weakening_steps: DEFAULT_WEAKENING_STEPS,
        }
    }
}

/// Default time step, as a fraction of the stable one (the command's `--courant`).
pub const DEFAULT_COURANT: f64 = 0.9;

/// Default damping: this fraction of critical at the block's fundamental thickness-shear
/// mode omega_t = pi c_s / (2 t) (base stuck, top held by the plate).
pub const DEFAULT_DAMPING_RATIO: f64 = 0.1;

/// The default cap on one event, in periods T = 2 pi / omega_t of the thickness mode:
/// [`EVENT_CAP_FACTOR`] x (a front crossing the length L at c_s, L / c_s = L / (4 t) periods,
/// plus the decay of the kinetic energy to `ke_fraction` of the dissipation in the thickness
/// mode, the least damped mode of the stuck block under Kelvin-Voigt damping: its amplitude
/// decays at s omega_t, s = xi (xi <= 1) or xi - sqrt(xi^2 - 1) (overdamped), so
/// ln(1 / ke_fraction) / (4 pi s) periods). The paper's block at the default damping
/// (xi = 0.1): 4 (50 + 11) = 244 periods; its events last 2 to 16.
pub fn event_cap_periods(length: f64, thickness: f64, xi: f64, ke_fraction: f64) -> f64 {
    let crossing = length / (4.0 * thickness);
    // xi - sqrt(xi^2 - 1) without the cancellation (0, not NaN, when xi^2 overflows).
    let s = if xi <= 1.0 { xi } else { 1.0 / (xi + (xi * xi - 1.0).sqrt()) };
    let decay = (1.0 / ke_fraction).ln() / (4.0 * std::f64::consts::PI * s);
    EVENT_CAP_FACTOR * (crossing + decay)
}

/// Most explicit steps one event of the held mode may be capped at: about 10 s on the paper's
/// mesh (2406 unknowns, 5e7 unknown-steps a second here), whose default events cap at 1.4e4
/// steps (twice that per halving of h). A damping whose cap is above it is refused up front,
/// in both drive modes, with the range this scene accepts (`Setup::check_event_work`, the one
/// range rule of --damping): on the paper's scene about
/// 1.9e-6 to 6.1e-3 s.
pub const MAX_EVENT_STEPS: u64 = 200_000;

/// Margin of [`event_cap_periods`] over the physics (slow fronts, a second rupture).
pub const EVENT_CAP_FACTOR: f64 = 4.0;

/// `slide --dynamics` runs the paper's first cycle by default: one cycle, ended by the first
/// front crossing (what F_1, x_1, the envelope and the peak are read on).
pub const DEFAULT_CYCLES: usize = 1;
pub const DEFAULT_END_AT_CROSSING: bool = true;

/// The operator of a dynamic slide's static loading by default: its runs have thousands of
/// events on fine meshes, where the banded solve's cost per event grows like n, not n^2.
pub const DEFAULT_OPERATOR: crate::interface::events::Operator = crate::interface::events::Operator::Banded;

/// Default slip-weakening step of the static loading: D_c / this of slip (as the quasi-static
/// solver).
pub const DEFAULT_WEAKENING_STEPS: f64 = 20.0;

/// One dynamic event, as measured.
#[derive(Debug, Clone)]
pub struct DynEvent {
    /// Row of events.csv.
    pub event: usize,
    pub x: f64,
    pub f_onset: f64,
    pub f_after: f64,
    pub record: EventRecord,
    /// Time at which the tip reached its final position (front arrest), s since onset.
    pub t_arrest: Option<f64>,
    /// (F_onset - F(t_arrest)) / (F_onset - F_after): the force drop made by the front's
    /// arrest over the event's. Not a share: above 1 the force undershoots its final value at
    /// the arrest and recovers after; with slip weakening the friction force falls behind the
    /// tip as it passes, so it is near 1 by construction and says nothing about assumption 5.
    pub force_drop_at_arrest: Option<f64>,
    /// Assumption 5 as the model needs it: the field ahead of the running tip and the arrest
    /// predicted from the pre-event field (held drive only; None in `--drive-velocity`).
    pub assumption5: Option<assumption5::Assumption5>,
    /// |F_dynamic at the end - F of the static equilibrium| / (mu_s N), and the largest
    /// difference of a displacement over the block / the event's largest slip.
    pub f_gap: f64,
    pub u_gap: f64,
}

#[derive(Debug, Clone)]
pub struct DynamicResult {
    pub slide: SlideResult,
    pub events: Vec<DynEvent>,
    pub dt: f64,
    pub dt_stable: f64,
    pub eta: f64,
    /// Damping ratio at the thickness mode, and that mode's omega (rad/s).
    pub xi_thickness: f64,
    pub omega_thickness: f64,
    pub speeds: WaveSpeeds,
    /// Lambda_0 at the mean pressure, m (infinite for Coulomb).
    pub lambda0: f64,
    pub steps: usize,
    pub dofs: usize,
    /// Wall times, s: condensation and factorisation, static loading, dynamic events.
    pub setup_s: f64,
    pub static_s: f64,
    pub dynamic_s: f64,
    /// The cap the run met before its end (events, an event's steps), if any: the tables
    /// hold what was computed up to there.
    pub incomplete: Option<String>,
    /// The held mode's static-loading coefficient updates per D_c (NaN under the
    /// constant-velocity drive, which updates every step).
    pub weakening_steps: f64,
}

/// The block's shear-wave speed c_s, m/s.
pub fn shear_speed(scene: &Scene) -> Result<f64> {
    let b = &scene.block;
    Ok(WaveSpeeds::new(&crate::fem::material::Material::plane_strain(b.young, b.poisson)?, b.density).c_s)
}

/// Refusals before any work: the element, the law, damping and step.
pub fn check(scene: &Scene, o: &SlideOptions, d: &DynamicOptions) -> Result<()> {
    crate::studies::slide::check_options(scene, o)?;
    if scene.mesh.element != "qua4" {
        return Err(Error::input(
            "mesh.element (--element)",
            format!(
                "'{}': --dynamics runs qua4 (full 2x2 integration) only, so that the static and the explicit stiffness are the same; use --element qua4",
                scene.mesh.element
            ),
        ));
    }
    if let Law::StaticKinetic { .. } = o.law {
        return Err(Error::input(
            "--law",
            "static-kinetic is refused with --dynamics: its abrupt drop mu_s -> mu_d has no length scale, so a dynamic front on it is set by the mesh (issue 33); use --law slip-weakening (with --dc; default: the D_c giving kappa = 0.509, the paper scene's 2.3107e-7 m)",
        ));
    }
    if let Some(eta) = d.damping {
        if !(eta.is_finite() && eta > 0.0) {
            return Err(Error::input(
                "--damping",
                format!("{eta}: events end only when the kinetic energy decays; give eta > 0 s (default: 10 % of critical at the thickness mode)"),
            ));
        }
        // Its range is the one of the event's step cap, which needs the mesh
        // (`Setup::check_event_work`, before the condensation, in both drive modes).
    }
    crate::dynamics::driven::check_plate(d.plate_mass, d.plate_inertia)?;
    if !(d.weakening_steps >= 1.0 && d.weakening_steps <= 1e4) {
        return Err(Error::input(
            "--weakening-steps",
            format!(
                "{}: give the coefficient updates per D_c of slip in [1, 1e4] (default {DEFAULT_WEAKENING_STEPS})",
                crate::error::num(d.weakening_steps)
            ),
        ));
    }
    let min_courant = crate::dynamics::explicit::MIN_COURANT;
    if !(d.courant >= min_courant && d.courant <= 1.0) {
        return Err(Error::input(
            "--courant",
            format!(
                "{}: give a fraction of the stable step in [{min_courant}, 1] (below {min_courant} the steps grow as 1/courant and buy no accuracy)",
                crate::error::num(d.courant)
            ),
        ));
    }
    if let Law::SlipWeakening { mu_s, mu_d, dc } = o.law {
        physics::check_resolved(scene, mu_s, mu_d, dc, o.n_force, "--h")?;
    }
    Ok(())
}

/// [`DynamicOptions::weakening_steps`] from the value a front end was given (None: the
/// default), refused where it cannot act: under the constant-velocity drive (which updates the
/// coefficient every explicit step) or without a weakening law.
pub fn weakening_steps(given: Option<f64>, o: &SlideOptions, drive_velocity: Option<f64>) -> Result<f64> {
    match given {
        Some(_) if drive_velocity.is_some() || !o.law.weakens() => Err(Error::input(
            "--weakening-steps",
            "acts only on the held mode's static loading under --law slip-weakening: --drive-velocity updates the coefficient every explicit step",
        )),
        Some(n) => Ok(n),
        None => Ok(DEFAULT_WEAKENING_STEPS),
    }
}

/// The run: quasi-static loading, dynamic instabilities.
pub fn run(scene: &Scene, o: &SlideOptions, d: &DynamicOptions, progress: Progress) -> Result<DynamicResult> {
    if d.drive_velocity.is_some() {
        return velocity::run(scene, o, d, progress);
    }
    check(scene, o, d)?;
    let clock = Instant::now();
    // The set-up both modes share (first: a damping above the event cap is refused before the
    // condensation); full fields: the block with its boundary held, factorised once.
    let su = Setup::new(scene, o, d)?;
    su.check_event_work(scene, d)?;
    // The static phase's operator: the dense condensed S, or the banded block (O(n) a solve).
    let (c, banded) = if o.operator == Operator::Banded {
        let op = BandedOperator::new(scene, scene.loading.height)?;
        let b = &scene.block;
        let c = Condensed {
            n: op.n,
            x: op.x.clone(),
            w: op.w.clone(),
            l: b.length,
            t: b.thickness,
            e_star: b.young / (1.0 - b.poisson.powi(2)),
            s: vec![],
            asymmetry: op.asymmetry,
            rigid_residual: op.rigid_residual,
        };
        (c, Some(op))
    } else {
        (condense(scene, &SolverOptions::default())?, None)
    };
    let s_h = if banded.is_none() { c.at_height(scene.loading.height) } else { vec![] };
    let n = c.n;
    let op: Box<dyn events::operator::Operator + '_> = match &banded {
        Some(b) => Box::new(Solving::new(b)),
        None => Box::new(events::operator::Dense::new(&s_h, 2 * n + 3)),
    };
    let (mu_s, mu_d) = (o.law.mu_s(), o.law.mu_d());
    let full = su.full_field()?;
    let full_field =
        |a: &Affine, lam: f64| full.field(&(0..2 * n + 3).map(|j| a.b(j, lam)).collect::<Vec<_>>());
    let (model, mat, friction, weakens) = (&su.model, su.mat, su.friction, su.weakens);
    let (dt, dt_stable, eta, omega_t, period, lambda0) =
        (su.dt, su.dt_stable, su.eta, su.omega_t, su.period, su.lambda0);
    let dc = friction.d_c;
    let t = scene.block.thickness;
    let max_periods = d.max_periods.unwrap_or_else(|| event_cap_periods(c.l, t, su.xi(), d.ke_fraction));
    let elastic_slip = mu_s * (o.n_force / c.l) * t / mat.shear_modulus();
    let lim = EventLimits {
        ke_fraction: d.ke_fraction,
        quiet_steps: su.quiet_steps,
        rest_rate: crate::dynamics::driven::rest_rate(&friction, elastic_slip, period),
        max_steps: (max_periods * period / dt).ceil() as usize,
        sample_every: su.sample_every,
        arrival_rate: su.arrival_rate,
    };
    let layout = su.layout(c.x.clone(), d)?;
    let driven = su.driven(&layout, o.n_force);
    progress.message(&format!(
        "dynamics: {} DOFs, dt = {dt:.4e} s ({} x the stable {dt_stable:.4e} s), eta = {eta:.4e} s = {:.3} of critical at the thickness mode omega = {omega_t:.4e} rad/s; c_s = {:.4} m/s; Lambda_0 = {:.3e} m = {:.2} h{}; static phase on the {} operator",
        model.n_dofs(),
        d.courant,
        su.xi(),
        su.speeds.c_s,
        lambda0,
        lambda0 / scene.mesh.h,
        if weakens {
            let kappa = physics::kappa(scene, mu_s, mu_d, dc, o.n_force);
            format!(
                ", D_c = {dc:.4e} m, thin-layer kappa = G D_c / ((mu_s - mu_d) (N/L) t) = {kappa:.3}: {}",
                physics::regime(kappa)
            )
        } else {
            String::new()
        },
        o.operator.name()
    ));

    // The event solver's active set on that operator; the normal phase is the event solver's.
    let (mut sv, mut rec) = start(op, n, o)?;
    let setup_s = clock.elapsed().as_secs_f64();
    let mut dynamic_s = 0.0;
    normal_phase(&mut sv, &mut rec)?;
    // Drive phase: under slip weakening every pre-slipped node sticks where it is as the
    // drive starts (the event solver's rule), keeping the slip it made.
    sv.set_phase(Phase::Drive);
    if weakens {
        for i in 0..n {
            if let NodeState::Slip(_) = sv.states()[i] {
                sv.set_state(i, NodeState::Stick, rec.prev_u[i])?;
            }
        }
    }
    let cap = tolerances::max_changes(n);
    let x_end = o.x_max.unwrap_or(f64::INFINITY);
    let mut x_stop = x_end;
    let mut sliding_seen = false;
    let mut lam = 0.0;
    let mut idle = 0;
    let mut done = vec![0.0f64; n]; // slip since each coefficient was frozen
    let mut slipped = vec![false; n]; // by instabilities since the last cycle end
    let mut dyn_events: Vec<DynEvent> = Vec::new();
    let mut steps = 0usize;
    let mut incomplete = None;
    // A cap met after the run started ends it with what it computed (exit status 5 in the
    // command), not with an error that would discard the work.
    macro_rules! capped {
        ($e:expr, $drive:lifetime) => {
            match $e {
                Err(Error::EventCap { cap, x, f_over_n, .. }) => {
                    incomplete = Some(format!(
                        "--max-events = {cap} met at X = {x:.6e} m, F/N = {f_over_n:.6}; raise --max-events or lower --cycles/--x-max"
                    ));
                    break $drive;
                }
                r => r?,
            }
        };
    }
    'drive: loop {
        o.cancel.check()?;
        let a = settle_continuous(&mut sv, lam, true, cap, "drive")?;
        let frac = if x_end.is_finite() { lam / x_end } else { 0.0 };
        // Cycles done, and of the current one the share of the interface its instabilities
        // have slipped (the crossing ends it at 1).
        let share = slipped.iter().filter(|&&s| s).count() as f64 / n as f64;
        let shown = frac.max((rec.out.sliding_events as f64 + share) / o.cycles.max(1) as f64).min(1.0);
        progress.fraction(shown);
        if !weakens && !sliding_seen && lam > 0.0 && sv.all_contact_slipping() {
            // Coulomb's first whole-interface slip; by default the run ends 5 % further (`slide`).
            sliding_seen = true;
            rec.out.sliding_events += 1;
            capped!(rec.simple(&sv, &a, lam, EventKind::Sliding, 0), 'drive);
            if o.x_max.is_none() {
                x_stop = lam + 0.05 * lam.max(o.n_force / rec.out.k_bonded);
            }
        }
        if weakens && x_end.is_infinite() && sv.all_contact_slipping() {
            let weak =
                (0..n).all(|k| sv.states()[k] == NodeState::Open || sv.slip_memory(k, a.b(k, lam)) >= dc);
            if weak {
                // Steady sliding at mu_d, reached stably: nothing sticks again with the drive
                // advancing; the run ends here.
                rec.out.sliding_events += 1;
                capped!(rec.simple(&sv, &a, lam, EventKind::Sliding, 0), 'drive);
                progress.message(&format!(
                    "steady sliding at mu_d reached stably at X = {lam:.6e} m (no instability): the run ends"
                ));
                break 'drive;
            }
        }
        // Next X: the next threshold, or a slipping node's next D_c / weakening_steps of slip.
        let mut next: Option<(f64, Option<(usize, Hit)>)> =
            sv.next_event(&a, lam).map(|(dl, i, h)| (dl, Some((i, h))));
        if weakens {
            for k in 0..n {
                let rate = a.b1[k].abs();
                if matches!(sv.states()[k], NodeState::Slip(_))
                    && rate > 0.0
                    && sv.slip_memory(k, a.b(k, lam)) < dc
                {
                    let dl = (dc / d.weakening_steps - done[k]).max(0.0) / rate;
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
            capped!(rec.simple(&sv, &a, x_stop, EventKind::End, 0), 'drive);
            break;
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
            apply_hit(&mut sv, &a, lam, i, h)?;
            if let Hit::Friction(_) = h {
                done[i] = 0.0;
            }
            let a = settle_continuous(&mut sv, lam, true, cap, "drive")?;
            capped!(rec.simple(&sv, &a, lam, hit_kind(h), i), 'drive);
            continue;
        }
        // Slip weakening: bring the slipping coefficients to their slips at fixed U_H.
        let Some(a_cur) = relax(&mut sv, &a, lam, dc, cap, &mut done)? else {
            continue;
        };
        // The instability, dynamically, from this static equilibrium.
        let dclock = Instant::now();
        let before = sv.record(&a_cur, lam, Some(&rec.prev_u));
        let mut ds = DynState {
            u: full_field(&a_cur, lam),
            v: vec![0.0; model.n_dofs()],
            u_h: lam,
            drive_velocity: 0.0,
            q: [before.v, before.tilt],
            qdot: [0.0; 2],
            d: (0..n).map(|k| sv.slip_memory(k, a_cur.b(k, lam))).collect(),
            time: 0.0,
        };
        let ev = driven.run_event(&mut ds, &lim, dc / 100.0, &o.cancel, &|| progress.fraction(shown))?;
        steps += ev.steps;
        if !ev.settled {
            // Where it still moves: the fastest base node of the last sample, and how many move.
            let last = ev.rates.last().cloned().unwrap_or_default();
            let (kmax, vmax) =
                last.iter().enumerate().fold((0, 0.0f32), |b, (k, &v)| if v > b.1 { (k, v) } else { b });
            let moving = last.iter().filter(|&&v| v > 1e-3 * vmax).count();
            let en = &ev.energy;
            incomplete = Some(format!(
                "a dynamic event at X = {lam:.6e} m did not settle within its cap of {} steps ({max_periods:.0} thickness-mode periods): at the end the base node at x/L = {:.4} moves at {vmax:.3e} m/s ({moving} nodes above 1e-3 of that, {} open), kinetic energy {:.3e} of the dissipated {:.3e} J/m; the tables end before it; raise --damping",
                lim.max_steps,
                c.x.get(kmax).copied().unwrap_or(0.0) / c.l,
                ev.open.iter().filter(|&&o| o).count(),
                en.kinetic_end / (en.friction + en.damping).max(f64::MIN_POSITIVE),
                en.friction + en.damping
            ));
            break 'drive;
        }
        // Back to statics: every contact node anchored where the event left it.
        let a_after =
            anchor_after(&mut sv, &layout.base, &ds, &ev, d.heal_slipped_only, lam, cap, &mut done)?;
        let u_static = full_field(&a_after, lam);
        let max_slip = ev.slip.iter().cloned().fold(0.0, f64::max).max(f64::MIN_POSITIVE);
        let u_gap = ds.u.iter().zip(&u_static).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max) / max_slip;
        let f_after = a_after.f(sv.iu(), lam);
        let f_gap = (ev.force.last().copied().unwrap_or(f_after) - f_after).abs() / (mu_s * o.n_force);
        let (kind, node, region) = classify_event(&ev, dc, n);
        let kind = crossing(kind, region, &ev.open[..n], &mut slipped, o.end_at_crossing);
        if kind.ends_cycle() {
            rec.out.sliding_events += 1;
        }
        capped!(rec.record(&sv, &a_after, lam, |st| Event {
            kind,
            f: before.f,
            x: lam,
            node,
            region: ev.nucleation.map(|_| region),
            f_relaxed: st.f,
            backslip: 0,
            all_slipping: kind == EventKind::Sliding,
        }), 'drive);
        let (t_arrest, force_drop_at_arrest) =
            arrest(&ev, before.f, f_after).map_or((None, None), |(t, f)| (Some(t), f));
        let assumption5 = assumption5::measure(&ev, &c.x, &c.w, &friction, mat.shear_modulus(), t);
        dyn_events.push(DynEvent {
            event: rec.out.events.len() - 1,
            x: lam,
            f_onset: before.f,
            f_after,
            record: ev,
            t_arrest,
            force_drop_at_arrest,
            assumption5,
            f_gap,
            u_gap,
        });
        let e = dyn_events.last().expect("event");
        if e.record.weakened {
            progress.message(&format!(
                "event {} ({kind}) at X = {lam:.5e} m: F/(mu_s N) {:.5} -> {:.5}, slipped {:.4}..{:.4} L, {} steps ({:.3} s), peak slip rate {:.3e} m/s",
                e.event,
                e.f_onset / (mu_s * o.n_force),
                e.f_after / (mu_s * o.n_force),
                c.x[region.0] / c.l,
                c.x[region.1] / c.l,
                e.record.steps,
                e.record.duration,
                e.record.peak_rate.iter().cloned().fold(0.0, f64::max)
            ));
        }
        dynamic_s += dclock.elapsed().as_secs_f64();
        if rec.out.sliding_events >= o.cycles {
            break 'drive;
        }
    }
    let run = rec.finish(&sv);
    let resting = dyn_events.iter().filter(|e| e.record.at_strength > 0).count();
    if resting > 0 {
        progress.message(&format!(
            "{resting} dynamic events ended with base nodes at rest exactly at their strength (slower than {:.2e} m/s, counted as stuck)",
            lim.rest_rate
        ));
    }
    let total = clock.elapsed().as_secs_f64();
    let static_s = total - setup_s - dynamic_s;
    let mut res = su.result(scene, o, c, run, dyn_events, steps, [setup_s, static_s, dynamic_s]);
    res.incomplete = incomplete;
    res.weakening_steps = d.weakening_steps;
    Ok(res)
}
