//! The held mode's instability resolver: where the event solver's stepped drive finds the
//! slip-weakening fixed point running away, the event is run dynamically from that static
//! equilibrium (v = 0, U_H held), then statics resumes with every contact node anchored where
//! the event left it.

use super::fracture::HeldStiffness;
use super::steps::{anchor_after, arrest, classify_event, crossing};
use super::{assumption5, DynEvent};
use crate::dynamics::driven::{DynState, EventLimits};
use crate::error::Result;
use crate::interface::events::handoff::{Affine, Onset, Recorder, Resolved, Resolver, Solver};
use crate::interface::events::{tolerances, Event, EventKind};
use crate::law::Law;
use crate::progress::Progress;
use crate::studies::slide::SlideOptions;
use std::time::Instant;

/// A plate's (V, theta) and the side push's free (U_p, U) ([`super::setup::Setup::coordinates`]).
pub(super) type Coordinates = ([f64; 2], [f64; 2]);

/// What a dynamic event needs of the run, and what the run reads back after the drive.
pub(super) struct Held<'r, 'a> {
    /// The whole block's displacement from the event solver's boundary values at X.
    pub full_field: &'r dyn Fn(&Affine, f64) -> Vec<f64>,
    /// The rig's moving coordinates at X: a plate's (V, theta), the side push's free (U_p, U).
    pub coordinates: &'r dyn Fn(&Affine, f64) -> Coordinates,
    /// The interface's stiffness with its boundary held, for the fracture arrest (None: none).
    pub held: Option<&'r HeldStiffness<'r>>,
    pub driven: &'r crate::dynamics::driven::Driven<'a>,
    pub lim: &'r EventLimits,
    /// Base node of each interface node; interface x and weights (m).
    pub base: &'r [usize],
    pub x: &'r [f64],
    pub w: &'r [f64],
    pub law: &'r Law,
    pub shear_modulus: f64,
    pub thickness: f64,
    pub length: f64,
    /// One event's cap, in thickness-mode periods (for the message of one that met it).
    pub max_periods: f64,
    pub heal_slipped_only: bool,
    pub o: &'r SlideOptions,
    pub progress: &'r Progress<'a>,
    /// The dynamic events, the explicit steps and the wall time they took.
    pub events: Vec<DynEvent>,
    pub steps: usize,
    pub dynamic_s: f64,
    /// Set when an event did not settle within its cap: the run ends before it.
    pub incomplete: Option<String>,
}

impl Resolver for Held<'_, '_> {
    fn resolve(&mut self, sv: &mut Solver, rec: &mut Recorder, at: Onset) -> Result<Resolved> {
        let (o, lim, law) = (self.o, self.lim, self.law);
        let (n, lam, a_cur, dc) = (sv.n(), at.lam, at.a, law.dc().unwrap_or(1.0));
        let mu_s = o.law.mu_s();
        let dclock = Instant::now();
        let before = sv.record(a_cur, lam, Some(&rec.prev_u));
        let (q, free) = (self.coordinates)(a_cur, lam);
        let mut ds = DynState {
            u: (self.full_field)(a_cur, lam),
            v: vec![0.0; self.driven.model.n_dofs()],
            u_h: lam,
            drive_velocity: 0.0,
            q,
            qdot: [0.0; 2],
            free,
            free_dot: [0.0; 2],
            d: (0..n).map(|k| sv.slip_memory(k, a_cur.b(k, lam))).collect(),
            theta: vec![],
            p_lagged: vec![],
            time: 0.0,
        };
        let shown = at.shown;
        let progress = self.progress;
        let ev = self.driven.run_event(&mut ds, lim, dc / 100.0, &o.cancel, &|| progress.fraction(shown))?;
        self.steps += ev.steps;
        if !ev.settled {
            // Where it still moves: the fastest base node of the last sample, and how many move.
            let last = ev.rates.last().cloned().unwrap_or_default();
            let (kmax, vmax) =
                last.iter().enumerate().fold((0, 0.0f32), |b, (k, &v)| if v > b.1 { (k, v) } else { b });
            let moving = last.iter().filter(|&&v| v > 1e-3 * vmax).count();
            let en = &ev.energy;
            self.incomplete = Some(format!(
                "a dynamic event at X = {lam:.6e} m did not settle within its cap of {} steps ({:.0} thickness-mode periods): at the end the base node at x/L = {:.4} moves at {vmax:.3e} m/s ({moving} nodes above 1e-3 of that, {} open), kinetic energy {:.3e} of the dissipated {:.3e} J/m; the tables end before it; raise --damping",
                lim.max_steps,
                self.max_periods,
                self.x.get(kmax).copied().unwrap_or(0.0) / self.length,
                ev.open.iter().filter(|&&o| o).count(),
                en.kinetic_end / (en.friction + en.damping).max(f64::MIN_POSITIVE),
                en.friction + en.damping
            ));
            return Ok(Resolved::Stop);
        }
        // Back to statics: every contact node anchored where the event left it.
        let cap = tolerances::max_changes(n);
        let a_after = anchor_after(sv, self.base, &ds, &ev, self.heal_slipped_only, lam, cap)?;
        let u_static = (self.full_field)(&a_after, lam);
        let max_slip = ev.slip.iter().cloned().fold(0.0, f64::max).max(f64::MIN_POSITIVE);
        let u_gap = ds.u.iter().zip(&u_static).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max) / max_slip;
        let f_after = a_after.f(sv.iu(), lam);
        let f_gap = (ev.force.last().copied().unwrap_or(f_after) - f_after).abs() / (mu_s * o.n_force);
        let (kind, node, region) = classify_event(&ev, dc, n);
        let kind = crossing(kind, region, &ev.open[..n], at.slipped, o.end_at_crossing);
        if kind.ends_cycle() {
            rec.out.sliding_events += 1;
        }
        rec.record(sv, &a_after, lam, |st| Event {
            kind,
            f: before.f,
            x: lam,
            node,
            region: ev.nucleation.map(|_| region),
            f_relaxed: st.f,
            backslip: 0,
            all_slipping: kind == EventKind::Sliding,
        })?;
        let (t_arrest, force_drop_at_arrest) =
            arrest(&ev, before.f, f_after).map_or((None, None), |(t, f)| (Some(t), f));
        let assumption5 =
            assumption5::measure(&ev, (self.x, self.w), law, (self.shear_modulus, self.thickness), self.held);
        self.events.push(DynEvent {
            event: rec.out.events.len() - 1,
            x: lam,
            f_onset: before.f,
            f_pre: at.f_pre,
            f_after,
            record: ev,
            t_arrest,
            force_drop_at_arrest,
            assumption5,
            f_gap,
            u_gap,
        });
        let e = self.events.last().expect("event");
        if e.record.weakened {
            progress.message(&format!(
                "event {} ({kind}) at X = {lam:.5e} m: F/(mu_s N) {:.5} -> {:.5}, slipped {:.4}..{:.4} L, {} steps ({:.3} s), peak slip rate {:.3e} m/s",
                e.event,
                e.f_onset / (mu_s * o.n_force),
                e.f_after / (mu_s * o.n_force),
                self.x[region.0] / self.length,
                self.x[region.1] / self.length,
                e.record.steps,
                e.record.duration,
                e.record.peak_rate.iter().cloned().fold(0.0, f64::max)
            ));
        }
        self.dynamic_s += dclock.elapsed().as_secs_f64();
        Ok(Resolved::Go)
    }
}
