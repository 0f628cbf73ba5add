//! `slide --dynamics`: the paper's plate-driven block, loaded quasi-statically and exactly
//! between events, each instability run dynamically with the drive held (issue 33, part 3).
//!
//! 1. Loading: the event solver's own start-up and stepped drive loop
//!    ([`crate::interface::events`]' `handoff`, on the dense condensed S or, with
//!    `--operator banded`, the banded block: O(n) a solve): its normal phase, then U_H with
//!    nodes sticking, slipping (at a frozen coefficient) or opening, every change found
//!    exactly. Under slip weakening a slipping node's coefficient is brought to its slip every
//!    D_c/20 of slip (`DynamicOptions::weakening_steps`; a fixed point at fixed U_H, each
//!    iterate one solve); when that fixed point diverges (a change above D_c/2 in one iterate,
//!    or 30 iterates without settling to 1e-3 D_c) the patch is unstable and the loop hands
//!    the event to this mode's resolver (`resolve.rs`), which runs it dynamically.
//! 2. The event ([`crate::dynamics::driven`]): from the static field (v = 0), U_H held, until
//!    no node slips and the kinetic energy is below 1e-6 of what the event dissipated, both
//!    for one period of the block's thickness mode; with `--event-end slip`, once no node's
//!    slip grew by D_c/1000 (nor a node opened or closed) over one such period.
//! 3. The static equilibrium with every contact node anchored where the event left it; an
//!    event in which some node weakened fully (slip >= D_c) is an instability: every node
//!    heals to mu_s (slip memory 0), as in the quasi-static solver; otherwise nodes keep
//!    their slip. Loading continues from there.
//!
//! Coulomb friction never becomes unstable, so a Coulomb run is the static loading alone:
//! the same events as `slide` (tests/it/dynamics.rs).

use crate::dynamics::driven::{EventEnd, EventLimits, EventRecord};
use crate::dynamics::waves::WaveSpeeds;
use crate::error::{Error, Result};
use crate::interface::events::handoff::{drive_stepped, start_drive, Affine, Ended};
use crate::interface::events::Weakening;
use crate::law::{Law, Normal};
use crate::progress::Progress;
use crate::scene::Scene;
use crate::studies::slide::{SlideOptions, SlideResult};
use std::time::Instant;

pub mod assumption5;
pub mod fracture;
pub mod fronts;
pub mod physics;
pub mod refine;
mod resolve;
mod setup;
mod steps;
pub mod summary;
pub use physics::{default_dc, smallest_resolved_dc};
pub mod velocity;
use setup::{Setup, StaticOperator};

/// The dynamic options beside the slide options.
#[derive(Debug, Clone)]
pub struct DynamicOptions {
    /// Kelvin-Voigt eta, s; None: [`DEFAULT_DAMPING_RATIO`] of critical at the thickness mode.
    pub damping: Option<f64>,
    /// Time step as a fraction of the stable one.
    pub courant: f64,
    /// Which test ends a held-mode event ([`EventEnd`]; docs/speed.md, "Event end").
    pub event_end: EventEnd,
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
    /// The normal response of the explicit solver's base ([`Normal`]; the quasi-static phase's
    /// normal force is its own equilibrium's).
    pub normal: Normal,
}

impl Default for DynamicOptions {
    fn default() -> Self {
        Self {
            damping: None,
            courant: DEFAULT_COURANT,
            event_end: EventEnd::Energy,
            ke_fraction: 1e-6,
            max_periods: None,
            drive_velocity: None,
            max_velocity_steps: velocity::MAX_STEPS,
            plate_mass: 0.0,
            plate_inertia: 0.0,
            heal_slipped_only: false,
            weakening_steps: DEFAULT_WEAKENING_STEPS,
            normal: Normal::Instantaneous,
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

/// The operator of a dynamic slide's static loading by default: [`DEFAULT_OPERATOR`], except
/// under side push, whose border only the dense operator holds ([`crate::interface::events::Operator::for_scene`]).
pub fn default_operator(scene: &Scene) -> crate::interface::events::Operator {
    if scene.loading.rig.is_top_plate() {
        DEFAULT_OPERATOR
    } else {
        crate::interface::events::Operator::for_scene(scene)
    }
}

/// [`EventEnd::Slip`]'s tolerance: a base node's slip may grow by at most this fraction of
/// D_c over the window, a tenth of the D_c/100 at which the handoff counts a node as slipped
/// (the tip, the slipped region, `--heal slipped`); anchors moved by that much move the static
/// F after the event by at most k_bonded D_c / 1000 (5e-5 mu_s N on the paper's scene).
pub const SLIP_END_TOL: f64 = 1e-3;

/// [`EventEnd::Slip`]'s window, in periods of the thickness mode: the stuck block's slowest
/// mode (the quiet test's window, [`event_cap_periods`]), so every mode that could push a node
/// past its strength again has peaked in it, and with the drive held and the damping its
/// next peaks are lower. Two periods end no event earlier than the energy test on the small
/// scene (docs/speed.md, "Event end").
pub const SLIP_END_PERIODS: f64 = 1.0;

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
    /// Drive force on the static branch just before the onset (the onset's `f_pre`): on the
    /// exact path the last stable point before the fold (f_onset is the start just past it),
    /// on the stepped path the step's start before the relaxation that ran away; in the
    /// constant-velocity drive f_onset.
    pub f_pre: f64,
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
    Ok(WaveSpeeds::new(&b.material()?, b.density).c_s)
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
    if !scene.loading.rig.is_top_plate() {
        for (flag, v) in [("--plate-mass", d.plate_mass), ("--plate-inertia", d.plate_inertia)] {
            if v != 0.0 {
                return Err(Error::input(
                    flag,
                    "the top plate's own inertia: the side push has no driven plate (the sliding plate moves with the top nodes' masses); drop it",
                ));
            }
        }
    }
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

/// [`DynamicOptions::event_end`] from what a front end was given (None: the default), refused
/// under the constant-velocity drive, whose events are read off the slip rates.
pub fn event_end(given: Option<EventEnd>, drive_velocity: Option<f64>) -> Result<EventEnd> {
    match given {
        Some(_) if drive_velocity.is_some() => Err(Error::input(
            "--event-end",
            "acts only on the held mode's dynamic events: --drive-velocity runs one explicit drive without events to end",
        )),
        Some(end) => Ok(end),
        None => Ok(DynamicOptions::default().event_end),
    }
}

/// Which path the held mode's static loading follows slip weakening by (None: no weakening
/// law, or the constant-velocity drive, which has no static loading).
pub fn held_weakening(o: &SlideOptions, d: &DynamicOptions) -> Option<Weakening> {
    (o.law.weakens() && d.drive_velocity.is_none()).then_some(o.weakening)
}

/// [`SlideOptions::weakening`] from what a front end was given: `exact` (`--exact-weakening`)
/// or the stepped default, refused where the exact path cannot act (as
/// [`weakening_steps`]) and beside a given step count (`steps_given`), which is the other path.
pub fn weakening(
    exact: bool,
    steps_given: bool,
    o: &SlideOptions,
    drive_velocity: Option<f64>,
) -> Result<Weakening> {
    if !exact {
        return Ok(Weakening::Steps);
    }
    if steps_given {
        return Err(Error::input(
            "--exact-weakening",
            "follows the weakening exactly, without steps: drop --weakening-steps (the stepped path's N) or --exact-weakening",
        ));
    }
    if drive_velocity.is_some() {
        return Err(Error::input(
            "--exact-weakening",
            "acts only on the held mode's static loading: --drive-velocity has none (it updates the coefficient every explicit step); drop one of the two",
        ));
    }
    if !o.law.weakens() {
        return Err(Error::input("--exact-weakening", "acts only under --law slip-weakening: drop it"));
    }
    Ok(Weakening::Exact)
}

/// The event cap met after the run started, as the run's `incomplete` note (the run then ends
/// with what it computed, exit status 5 in the command); any other error stays one.
pub(crate) fn cap_met(e: Error) -> Result<String> {
    match e {
        Error::EventCap { cap, x, f_over_n, .. } => Ok(format!(
            "--max-events = {cap} met at X = {x:.6e} m, F/N = {f_over_n:.6}; raise --max-events or lower --cycles/--x-max"
        )),
        e => Err(e),
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
    let so = StaticOperator::new(scene, o.operator)?;
    let (c, op) = (&so.c, so.solver());
    let n = c.n;
    let (mu_s, mu_d) = (o.law.mu_s(), o.law.mu_d());
    let full = su.full_field()?;
    let full_field =
        |a: &Affine, lam: f64| full.field(&(0..c.dim()).map(|j| a.b(j, lam)).collect::<Vec<_>>());
    let coordinates = |a: &Affine, lam: f64| su.coordinates(n, |j| a.b(j, lam));
    let (model, mat, law, weakens) = (&su.model, su.mat, su.law, su.weakens);
    let (dt, dt_stable, eta, omega_t, period, lambda0) =
        (su.dt, su.dt_stable, su.eta, su.omega_t, su.period, su.lambda0);
    let dc = su.slip_scale();
    let t = scene.block.thickness;
    let max_periods = d.max_periods.unwrap_or_else(|| event_cap_periods(c.l, t, su.xi(), d.ke_fraction));
    let elastic_slip = mu_s * (o.n_force / c.l) * t / mat.shear_modulus();
    let lim = EventLimits {
        end: d.event_end,
        ke_fraction: d.ke_fraction,
        quiet_steps: su.quiet_steps,
        slip_tol: SLIP_END_TOL * dc,
        slip_window: (SLIP_END_PERIODS * period / dt).ceil() as usize,
        rest_rate: crate::dynamics::driven::rest_rate(&law, elastic_slip, period),
        max_steps: (max_periods * period / dt).ceil() as usize,
        sample_every: su.sample_every,
        arrival_rate: su.arrival_rate,
    };
    let layout = su.layout(c.x.clone(), d)?;
    let driven = su.driven(&layout, o.n_force);
    progress.message(&format!(
        "dynamics: {} DOFs, dt = {dt:.4e} s ({} x the stable {dt_stable:.4e} s), eta = {eta:.4e} s = {:.3} of critical at the thickness mode omega = {omega_t:.4e} rad/s; c_s = {:.4} m/s; Lambda_0 = {:.3e} m = {:.2} h{}; static phase on the {} operator{}; {}",
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
        o.operator.name(),
        match held_weakening(o, d) {
            Some(Weakening::Exact) => ", slip weakening followed exactly (--exact-weakening)".to_string(),
            Some(Weakening::Steps) => format!(", slip weakening in steps of D_c/{}", d.weakening_steps),
            None => String::new(),
        },
        match d.event_end {
            EventEnd::Energy => format!(
                "an event ends at rest (kinetic energy {:e} of its dissipation, --event-end energy)",
                d.ke_fraction
            ),
            EventEnd::Slip => format!(
                "an event ends when no node's slip grows by {SLIP_END_TOL:e} D_c, nor a node opens or closes, in {SLIP_END_PERIODS} x the thickness period (--event-end slip)"
            ),
        }
    ));

    // The event solver's start-up and its drive loop, each instability run dynamically.
    let (mut sv, mut rec) = start_drive(op, n, o)?;
    let setup_s = clock.elapsed().as_secs_f64();
    // The fracture prediction's stiffness (slip weakening only): the dense S, or the banded
    // block factored once with its boundary held.
    let held = match law {
        Law::SlipWeakening { .. } => Some(so.held()?),
        _ => None,
    };
    let mut resolver = resolve::Held {
        full_field: &full_field,
        coordinates: &coordinates,
        held: held.as_ref(),
        driven: &driven,
        lim: &lim,
        base: &layout.base,
        x: &c.x,
        w: &c.w,
        law: &law,
        shear_modulus: mat.shear_modulus(),
        thickness: t,
        length: c.l,
        max_periods,
        heal_slipped_only: d.heal_slipped_only,
        o,
        progress: &progress,
        events: Vec::new(),
        steps: 0,
        dynamic_s: 0.0,
        incomplete: None,
    };
    let ended =
        drive_stepped(&mut sv, &mut rec, &mut resolver, d.weakening_steps, &|f| progress.fraction(f))?;
    let (dyn_events, steps, dynamic_s) = (resolver.events, resolver.steps, resolver.dynamic_s);
    let mut incomplete = resolver.incomplete;
    match ended {
        Ended::Cap(e) => incomplete = Some(cap_met(e)?),
        Ended::Steady(x) => progress.message(&format!(
            "steady sliding at mu_d reached stably at X = {x:.6e} m (no instability): the run ends"
        )),
        Ended::Done | Ended::Stopped => {}
    }
    let run = rec.finish(&sv);
    drop(sv); // it borrows the operator, whose interface the result takes
    let resting = dyn_events.iter().filter(|e| e.record.at_strength > 0).count();
    if resting > 0 {
        progress.message(&format!(
            "{resting} dynamic events ended with base nodes at rest exactly at their strength (slower than {:.2e} m/s, counted as stuck)",
            lim.rest_rate
        ));
    }
    let total = clock.elapsed().as_secs_f64();
    let static_s = total - setup_s - dynamic_s;
    let mut res = su.result(scene, o, so.c, run, dyn_events, steps, [setup_s, static_s, dynamic_s]);
    res.incomplete = incomplete;
    // 0: the exact path has no step.
    res.weakening_steps = match held_weakening(o, d) {
        Some(Weakening::Exact) => 0.0,
        _ => d.weakening_steps,
    };
    Ok(res)
}
