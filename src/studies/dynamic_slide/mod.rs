//! `slide --dynamics`: the paper's plate-driven block, loaded quasi-statically and exactly
//! between events, each instability run dynamically with the drive held (issue 33, part 3).
//!
//! 1. Loading ([`crate::dynamics::statics`]): N at U_H = 0, then U_H, on the condensed block
//!    and plate; nodes stick, slip (Coulomb at a frozen coefficient) or open, and every change
//!    is found exactly. Under slip weakening a slipping node's coefficient is brought to its
//!    slip every D_c/20 (a fixed point at fixed U_H, as the quasi-static solver does); when
//!    that fixed point diverges (a change above D_c/2 in one iterate, or 30 iterates
//!    without settling to 1e-3 D_c) the patch is unstable and the event is run dynamically.
//! 2. The event ([`crate::dynamics::driven`]): from the static field (v = 0), U_H held, until
//!    no node slips and the kinetic energy is below 1e-6 of what the event dissipated, both
//!    for one period of the block's thickness mode.
//! 3. The static equilibrium with every contact node anchored where the event left it; an
//!    event in which some node weakened fully (slip >= D_c) is an instability: every node
//!    heals to mu_s (slip memory 0), as in the quasi-static solver; otherwise nodes keep
//!    their slip. Loading continues from there.
//!
//! Coulomb friction never becomes unstable, so a Coulomb run is the static loading alone:
//! the cross-check against the event solver (tests/dynamics.rs).

use crate::dynamics::driven::{Driven, DynState, EventLimits, EventRecord, Layout};
use crate::dynamics::explicit::Elastodynamic;
use crate::dynamics::friction::SlipWeakening;
use crate::dynamics::statics::{Load, Node, Statics};
use crate::dynamics::waves::WaveSpeeds;
use crate::error::{Error, Result};
use crate::fem::assembly::Assembler;
use crate::interface::condense::{boundary_model, condense};
use crate::interface::events::{Event, EventKind, Phase, Run, State};
use crate::interface::law::Law;
use crate::linalg::solve::{Solver, SolverOptions};
use crate::progress::Progress;
use crate::scene::Scene;
use crate::studies::slide::{SlideOptions, SlideResult};
use std::time::Instant;

mod steps;
pub mod velocity;
use steps::{add_slip, add_slip_done, arrest, change_kind, settle, to_state};

/// The dynamic options beside the slide options.
#[derive(Debug, Clone)]
pub struct DynamicOptions {
    /// Kelvin-Voigt eta, s; None: [`DEFAULT_DAMPING_RATIO`] of critical at the thickness mode.
    pub damping: Option<f64>,
    /// Time step as a fraction of the stable one.
    pub courant: f64,
    /// End of an event: kinetic energy below this fraction of the event's dissipation.
    pub ke_fraction: f64,
    /// Cap on the steps of one event, in thickness-mode periods.
    pub max_periods: f64,
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
}

impl Default for DynamicOptions {
    fn default() -> Self {
        Self {
            damping: None,
            courant: 0.9,
            ke_fraction: 1e-6,
            max_periods: 20_000.0,
            drive_velocity: None,
            max_velocity_steps: velocity::MAX_STEPS,
            plate_mass: 0.0,
            plate_inertia: 0.0,
        }
    }
}

/// Default damping: this fraction of critical at the block's fundamental thickness-shear
/// mode omega_t = pi c_s / (2 t) (base stuck, top held by the plate).
pub const DEFAULT_DAMPING_RATIO: f64 = 0.1;

/// Slip-weakening step of the static loading: D_c / this of slip (as the quasi-static solver).
const STEPS_PER_DC: f64 = 20.0;

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
    /// (F_onset - F(t_arrest)) / (F_onset - F_after): the share of the drop made while the
    /// front still moved (the paper's assumption 5 says 0).
    pub drop_while_moving: Option<f64>,
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
}

/// The smallest D_c whose cohesive zone Lambda_0 at the mean pressure spans 3 elements.
pub fn default_dc(scene: &Scene, mu_s: f64, mu_d: f64, n_force: f64) -> Result<f64> {
    let b = &scene.block;
    let g = b.young / (2.0 * (1.0 + b.poisson));
    let p = n_force / b.length;
    let unit = SlipWeakening::new(mu_s, mu_d, 1.0)?.cohesive_zone(g, b.poisson, p);
    Ok(crate::dynamics::rupture::MIN_ZONE_ELEMENTS * scene.mesh.h / unit)
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
            "static-kinetic is refused with --dynamics: its abrupt drop mu_s -> mu_d has no length scale, so a dynamic front on it is set by the mesh (issue 33); use --law slip-weakening (with --dc, default the smallest D_c the mesh resolves)",
        ));
    }
    if let Some(eta) = d.damping {
        if !(eta.is_finite() && eta > 0.0) {
            return Err(Error::input(
                "--damping",
                format!("{eta}: events end only when the kinetic energy decays; give eta > 0 s (default: 10 % of critical at the thickness mode)"),
            ));
        }
    }
    if !(d.courant > 0.0 && d.courant <= 1.0) {
        return Err(Error::input(
            "--courant",
            format!("{}: give a fraction of the stable step in (0, 1]", d.courant),
        ));
    }
    if let Law::SlipWeakening { mu_s, mu_d, dc } = o.law {
        let b = &scene.block;
        let g = b.young / (2.0 * (1.0 + b.poisson));
        let l0 = SlipWeakening::new(mu_s, mu_d, dc)?.cohesive_zone(g, b.poisson, o.n_force / b.length);
        if l0 < crate::dynamics::rupture::MIN_ZONE_ELEMENTS * scene.mesh.h {
            return Err(Error::input(
                "--dc",
                format!(
                    "{dc:e} m: the cohesive zone Lambda_0 = {l0:.3e} m spans {:.2} elements of h = {} m, fewer than 3; the front would be mesh dependent: use --dc >= {:.3e} m or a smaller --h",
                    l0 / scene.mesh.h,
                    scene.mesh.h,
                    default_dc(scene, mu_s, mu_d, o.n_force)?
                ),
            ));
        }
    }
    Ok(())
}

/// The run: quasi-static loading, dynamic instabilities.
pub fn run(scene: &Scene, o: &SlideOptions, d: &DynamicOptions, progress: Progress) -> Result<DynamicResult> {
    if d.drive_velocity.is_some() {
        return velocity::run(scene, o, d, progress);
    }
    check(scene, o, d)?;
    let clock = Instant::now();
    let c = condense(scene, &SolverOptions::default())?;
    let n = c.n;
    let (mu_s, mu_d) = (o.law.mu_s(), o.law.mu_d());
    let friction = match o.law {
        Law::SlipWeakening { dc, .. } => SlipWeakening::new(mu_s, mu_d, dc)?,
        _ => SlipWeakening::coulomb(mu_s)?,
    };
    let weakens = o.law.weakens();
    let dc = friction.d_c;
    let mut st = Statics::new(c.at_height(scene.loading.height), n, mu_s);
    st.n_force = o.n_force;
    // Full fields: the block with every boundary DOF prescribed, factorised once.
    let (sm, bdofs) = boundary_model(scene)?;
    let nf = sm.constraints.n_fixed();
    let slots: Vec<usize> =
        bdofs.iter().map(|&k| sm.constraints.fixed_slot(k).expect("boundary DOF fixed")).collect();
    let red = sm.constraints.reduce()?;
    let asm = Assembler::new(&sm.mesh, &red)?;
    let (values, _) = asm.assemble(&sm.model(), &red, &[vec![]], &[vec![0.0; nf]])?;
    let solver = Solver::analyse(&asm.pattern, SolverOptions::default())?;
    let factor = solver.factorize(&asm.pattern, &values).map_err(|e| Error::Singular {
        detail: format!("the block with its boundary held is not positive definite ({e})"),
        node: None,
        component: None,
    })?;
    let mat = crate::fem::material::Material::plane_strain(scene.block.young, scene.block.poisson)?;
    let model = Elastodynamic::new(&sm.mesh, mat, scene.block.density)?;
    let nn = sm.mesh.n_nodes();
    let (t, hgt) = (scene.block.thickness, scene.loading.height);
    let arm = hgt - t;
    let full_field = |b: &[f64]| -> Vec<f64> {
        // b in the statics' order (U_H at H); the model's U0 is at the block top.
        let mut g = vec![0.0; nf];
        for (j, &slot) in slots.iter().enumerate() {
            g[slot] = if j == 2 * n { b[j] + arm * b[2 * n + 2] } else { b[j] };
        }
        let up = red.expand(&vec![0.0; red.n_free()], &g);
        let mut ku = vec![0.0; 2 * nn];
        model.apply_k(&up[..2 * nn], &mut ku);
        let mut f = vec![0.0; red.n_full];
        for i in 0..2 * nn {
            f[i] = -ku[i];
        }
        let mut r = vec![0.0; red.n_free()];
        red.project_add(&f, &mut r);
        factor.solve_in_place(&mut r, 1);
        red.expand(&r, &g)[..2 * nn].to_vec()
    };
    let speeds = WaveSpeeds::new(&mat, scene.block.density);
    let omega_t = std::f64::consts::PI * speeds.c_s / (2.0 * t);
    let eta = d.damping.unwrap_or(2.0 * DEFAULT_DAMPING_RATIO / omega_t);
    let dt_stable = model.critical_dt(eta);
    let dt = d.courant * dt_stable;
    let period = 2.0 * std::f64::consts::PI / omega_t;
    let quiet_steps = ((period / dt).ceil() as usize).max(10);
    let lim = EventLimits {
        ke_fraction: d.ke_fraction,
        quiet_steps,
        max_steps: (d.max_periods * period / dt).ceil() as usize,
        sample_every: ((period / dt / 16.0).floor() as usize).max(1),
    };
    let top: Vec<usize> = sm.mesh.set_nodes(&sm.top_set)?;
    let top_x: Vec<f64> = top.iter().map(|&k| sm.mesh.nodes[k][0]).collect();
    let layout = Layout::new(&model, sm.interface.clone(), c.x.clone(), top, top_x, arm)
        .with_plate(d.plate_mass, d.plate_inertia)?;
    let driven = Driven { model: &model, layout: &layout, friction, n_force: o.n_force, dt, eta };
    let lambda0 = if weakens {
        friction.cohesive_zone(mat.shear_modulus(), mat.nu, o.n_force / c.l)
    } else {
        f64::INFINITY
    };
    progress.message(&format!(
        "dynamics: {} DOFs, dt = {dt:.4e} s ({} x the stable {dt_stable:.4e} s), eta = {eta:.4e} s = {:.3} of critical at the thickness mode omega = {omega_t:.4e} rad/s; c_s = {:.4} m/s; Lambda_0 = {:.3e} m = {:.2} h{}",
        model.n_dofs(),
        d.courant,
        0.5 * eta * omega_t,
        speeds.c_s,
        lambda0,
        lambda0 / scene.mesh.h,
        if weakens { format!(", D_c = {dc:.4e} m") } else { String::new() }
    ));
    let setup_s = clock.elapsed().as_secs_f64();
    let mut dynamic_s = 0.0;

    let scale_f = o.n_force / n as f64;
    let ftol = 1e-9 * scale_f;
    let gtol = 1e-12 * o.n_force * t / (c.e_star * c.l);
    let cap = crate::interface::events::tolerances::max_changes(n);
    let mut run = Run {
        events: vec![],
        states: vec![],
        max_violation: 0.0,
        k_bonded: st.k_bonded()?,
        sliding_events: 0,
        updates: 0,
        refreshes: 0,
    };
    let mut dyn_events: Vec<DynEvent> = Vec::new();
    let mut slip = vec![0.0f64; n]; // path length since healing
    let mut steps = 0usize;
    let push = |run: &mut Run, ev: Event, s: State| -> Result<()> {
        run.max_violation = run.max_violation.max(s.violations.max());
        run.events.push(ev);
        run.states.push(s);
        if run.events.len() > o.max_events {
            let last = run.states.last().expect("state");
            return Err(Error::EventCap {
                cap: o.max_events,
                x: last.x,
                f_over_n: last.f / o.n_force,
                precursors: run.events.iter().filter(|e| e.kind == EventKind::Precursor).count(),
                f_peak_over_n: run.states.iter().map(|s| s.f).fold(0.0, f64::max) / o.n_force,
            });
        }
        Ok(())
    };
    let simple = |kind: EventKind, s: &State, i: usize| Event {
        kind,
        f: s.f,
        x: s.x,
        node: i,
        region: None,
        f_relaxed: s.f,
        backslip: 0,
        all_slipping: false,
    };

    // Normal phase.
    let mut lam = 0.0;
    loop {
        o.cancel.check()?;
        let p = settle(&mut st, Load::Normal, lam, ftol, gtol, cap)?;
        match st.next_change(&p, lam, o.n_force, None) {
            Some((l, i, to)) => {
                add_slip(&st, &p, lam, l, &mut slip);
                lam = l;
                let from = st.nodes[i];
                st.nodes[i] =
                    if let Node::Stick { .. } = to { Node::Stick { anchor: p.b(i, l) } } else { to };
                let p = settle(&mut st, Load::Normal, lam, ftol, gtol, cap)?;
                let s = to_state(&st, &p, lam, Phase::Normal);
                push(&mut run, simple(change_kind(from, to), &s, i), s)?;
            }
            None => {
                add_slip(&st, &p, lam, o.n_force, &mut slip);
                lam = o.n_force;
                let s = to_state(&st, &p, lam, Phase::Normal);
                let kind = if st.nodes.iter().any(|s| matches!(s, Node::Slip { .. })) {
                    EventKind::EdgePreslip
                } else {
                    EventKind::NormalLoad
                };
                push(&mut run, simple(kind, &s, 0), s)?;
                break;
            }
        }
    }
    // Drive phase: every slipping node sticks where it is as the drive starts (U_H = 0).
    for i in 0..n {
        if let Node::Slip { .. } = st.nodes[i] {
            st.nodes[i] = Node::Stick { anchor: run.states.last().expect("state").u[i] };
        }
    }
    let x_end = o.x_max.unwrap_or(f64::INFINITY);
    let mut x_stop = x_end;
    let mut lam = 0.0;
    let mut done = vec![0.0f64; n]; // slip since each coefficient was frozen
    'drive: loop {
        o.cancel.check()?;
        let p = settle(&mut st, Load::Drive, lam, ftol, gtol, cap)?;
        let frac = if x_end.is_finite() { lam / x_end } else { 0.0 };
        progress.fraction(frac.max(run.sliding_events as f64 / o.cycles.max(1) as f64).min(1.0));
        if !weakens
            && !x_stop.is_finite()
            && lam > 0.0
            && st.nodes.iter().all(|s| !matches!(s, Node::Stick { .. }))
        {
            // Coulomb's default end: 5 % past the first whole-interface slip, as `slide`.
            x_stop = 1.05 * lam;
            run.sliding_events += 1;
            let s = to_state(&st, &p, lam, Phase::Drive);
            push(&mut run, simple(EventKind::Sliding, &s, 0), s)?;
        }
        // Slip left before each coefficient must be updated (none once fully weakened).
        let left: Vec<f64> =
            (0..n).map(|k| if slip[k] < dc { dc / STEPS_PER_DC - done[k] } else { f64::INFINITY }).collect();
        if weakens && x_end.is_infinite() {
            let contact: Vec<usize> = (0..n).filter(|&k| st.nodes[k] != Node::Open).collect();
            if contact.iter().all(|&k| matches!(st.nodes[k], Node::Slip { .. }) && slip[k] >= dc) {
                // Steady sliding at mu_d, reached stably: nothing sticks again with the drive
                // advancing; the run ends here.
                run.sliding_events += 1;
                let s = to_state(&st, &p, lam, Phase::Drive);
                push(&mut run, simple(EventKind::Sliding, &s, 0), s)?;
                progress.message(&format!(
                    "steady sliding at mu_d reached stably at X = {lam:.6e} m (no instability): the run ends"
                ));
                break 'drive;
            }
        }
        let weaken = weakens.then_some(left.as_slice());
        let Some((l, i, to)) = st.next_change(&p, lam, x_stop, weaken) else {
            // To the end X: coulomb's default end is 5 % past the first whole slip.
            if !x_stop.is_finite() {
                return Err(Error::Untrustworthy {
                    detail: format!("the static loading has no further event at X = {lam:e} m"),
                    hint: "give --x-max".into(),
                });
            }
            add_slip_done(&st, &p, lam, x_stop, &mut slip, &mut done);
            lam = x_stop;
            let s = to_state(&st, &p, lam, Phase::Drive);
            push(&mut run, simple(EventKind::End, &s, 0), s)?;
            break;
        };
        add_slip_done(&st, &p, lam, l, &mut slip, &mut done);
        lam = l;
        if to != st.nodes[i] {
            let from = st.nodes[i];
            st.nodes[i] = if let Node::Stick { .. } = to { Node::Stick { anchor: p.b(i, l) } } else { to };
            if let Node::Slip { .. } = to {
                done[i] = 0.0;
            }
            let p = settle(&mut st, Load::Drive, lam, ftol, gtol, cap)?;
            let s = to_state(&st, &p, lam, Phase::Drive);
            push(&mut run, simple(change_kind(from, to), &s, i), s)?;
            continue;
        }
        // Slip weakening: bring the slipping coefficients to their slips at fixed U_H.
        let mut stable = false;
        let mut p_cur = settle(&mut st, Load::Drive, lam, ftol, gtol, cap)?;
        for _ in 0..30 {
            for k in 0..n {
                if let Node::Slip { .. } = st.nodes[k] {
                    st.mu[k] = friction.mu(slip[k]);
                    done[k] = 0.0;
                }
            }
            let p_new = settle(&mut st, Load::Drive, lam, ftol, gtol, cap)?;
            let mut jump = 0.0f64;
            for k in 0..n {
                if let Node::Slip { .. } = st.nodes[k] {
                    let dk = (p_new.b(k, lam) - p_cur.b(k, lam)).abs();
                    slip[k] += dk;
                    jump = jump.max(dk);
                }
            }
            p_cur = p_new;
            if jump < 1e-3 * dc {
                stable = true;
                break;
            }
            if jump > 0.5 * dc {
                break;
            }
        }
        if stable {
            continue;
        }
        // The instability, dynamically, from this static equilibrium.
        let dclock = Instant::now();
        let before = to_state(&st, &p_cur, lam, Phase::Drive);
        let u0 = full_field(&p_cur.b0.iter().zip(&p_cur.b1).map(|(a, b)| a + lam * b).collect::<Vec<_>>());
        let mut ds = DynState {
            u: u0,
            v: vec![0.0; model.n_dofs()],
            u_h: lam,
            drive_velocity: 0.0,
            q: [before.v, before.tilt],
            qdot: [0.0; 2],
            d: slip.clone(),
            time: 0.0,
        };
        let rec = driven.run_event(&mut ds, &lim, dc / 100.0, &o.cancel)?;
        steps += rec.steps;
        if !rec.settled {
            return Err(Error::Untrustworthy {
                detail: format!(
                    "a dynamic event at X = {lam:.6e} m did not settle within {} steps ({} thickness-mode periods)",
                    lim.max_steps, d.max_periods
                ),
                hint: "raise --damping".into(),
            });
        }
        // Back to statics: every contact node anchored where the event left it.
        slip.clone_from(&ds.d);
        for (b, &k) in layout.base.iter().enumerate() {
            st.nodes[b] = if rec.open[b] { Node::Open } else { Node::Stick { anchor: ds.u[2 * k] } };
        }
        if rec.weakened {
            slip.iter_mut().for_each(|s| *s = 0.0);
        }
        for k in 0..n {
            st.mu[k] = friction.mu(slip[k]);
            done[k] = 0.0;
        }
        let p_after = settle(&mut st, Load::Drive, lam, ftol, gtol, cap)?;
        let after = to_state(&st, &p_after, lam, Phase::Drive);
        let u_static =
            full_field(&p_after.b0.iter().zip(&p_after.b1).map(|(a, b)| a + lam * b).collect::<Vec<_>>());
        let max_slip = rec.slip.iter().cloned().fold(0.0, f64::max).max(f64::MIN_POSITIVE);
        let u_gap = ds.u.iter().zip(&u_static).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max) / max_slip;
        let f_gap = (rec.force.last().copied().unwrap_or(after.f) - after.f).abs() / (mu_s * o.n_force);
        // The event's region and kind.
        let thr = dc / 100.0;
        let went: Vec<bool> = rec.slip.iter().map(|&s| s > thr).collect();
        let node = rec.nucleation.unwrap_or(0);
        let (mut a, mut b) = (node, node);
        while a > 0 && went[a - 1] {
            a -= 1;
        }
        while b + 1 < n && went[b + 1] {
            b += 1;
        }
        let first_contact = (0..n).find(|&k| !rec.open[k] || went[k]).unwrap_or(0);
        let last_contact = (0..n).rev().find(|&k| !rec.open[k] || went[k]).unwrap_or(n - 1);
        let kind = if !rec.weakened || rec.nucleation.is_none() {
            EventKind::Slip
        } else if a <= first_contact && b >= last_contact {
            EventKind::Sliding
        } else if a <= first_contact {
            EventKind::Precursor
        } else {
            EventKind::Nucleation
        };
        if kind.ends_cycle() {
            run.sliding_events += 1;
        }
        let ev = Event {
            kind,
            f: before.f,
            x: lam,
            node,
            region: rec.nucleation.map(|_| (a, b)),
            f_relaxed: after.f,
            backslip: 0,
            all_slipping: kind == EventKind::Sliding,
        };
        push(&mut run, ev, after)?;
        let (t_arrest, drop_while_moving) = arrest(&rec, before.f, run.states.last().expect("state").f)
            .map_or((None, None), |(t, f)| (Some(t), f));
        dyn_events.push(DynEvent {
            event: run.events.len() - 1,
            x: lam,
            f_onset: before.f,
            f_after: run.states.last().expect("state").f,
            record: rec,
            t_arrest,
            drop_while_moving,
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
                c.x[a] / c.l,
                c.x[b] / c.l,
                e.record.steps,
                e.record.duration,
                e.record.peak_rate.iter().cloned().fold(0.0, f64::max)
            ));
        }
        dynamic_s += dclock.elapsed().as_secs_f64();
        if run.sliding_events >= o.cycles {
            break 'drive;
        }
    }
    let total = clock.elapsed().as_secs_f64();
    let static_s = total - setup_s - dynamic_s;
    let events_s = total - setup_s;
    Ok(DynamicResult {
        slide: SlideResult {
            scene: scene.clone(),
            options: o.clone(),
            condensed: c,
            run,
            condense_s: setup_s,
            events_s,
        },
        events: dyn_events,
        dt,
        dt_stable,
        eta,
        xi_thickness: 0.5 * eta * omega_t,
        omega_thickness: omega_t,
        speeds,
        lambda0,
        steps,
        dofs: model.n_dofs(),
        setup_s,
        static_s,
        dynamic_s,
    })
}
