//! One dynamic event of the plate-driven block (issue 33, part 3): explicit central
//! differences on the whole mesh, the rigid plate as a rigid body, the base on the rigid flat
//! with unilateral contact and slip-weakening friction imposed per node and step in total
//! forces (the traction-at-split-node rule of [`super::rupture`], here without a background).
//!
//! The plate: U_H (the drive point at height H) held, or moved at a constant velocity; its
//! other two DOFs q = (V, theta) are free under -N and no moment. The top nodes follow it,
//! u = U_H + theta (H - t), v = V + theta x, so its mass matrix is G^T M_top G from their
//! lumped masses plus the plate's own: a rigid body of mass m_p (kg/m) and rotational
//! inertia I_c (kg m^2/m) about its centre of mass, taken at the block top's mid-point
//! (x_c, t), whose velocity is (U_H' + (H - t) theta', V' + x_c theta'):
//!
//! ```text
//! M_q = G^T M_top G + [[m_p, m_p x_c], [m_p x_c, m_p (x_c^2 + (H - t)^2) + I_c]]
//! F   = (sum m_top + m_p) (H - t) theta'' - sum_top f_x        (the drive's reaction)
//! ```
//!
//! Default m_p = I_c = 0, the massless-plate limit (see [`Layout::with_plate`]).
//!
//! Each base node i at step n, with f = -K (u^n + eta v^{n-1/2}) and v = v^{n-1/2}:
//!
//! ```text
//! P* = -f_y - m v_y / dt - m u_y / dt^2      force keeping u_y^{n+1} = 0; P* <= 0: open (P = T = 0)
//! T* = -f_x - m v_x / dt                     force that would stop the node
//! T  = T* if |T*| <= mu(d) P*, else mu(d) P* sign(T*);   d += dt |v_x^{n+1/2}|
//! ```
//!
//! The energy ledger is the scheme's exact one (see [`super::explicit::Ledger`]): shadow
//! energy + friction + damping - work of N - contact work - drive work is constant to
//! round-off over an event.

use super::explicit::{Boundary, BoundaryStep, Elastodynamic, Explicit};
use crate::error::{Error, Result};
use crate::law::{Law, Normal, Trial};

/// The mesh's parts as the event loop reads them.
#[derive(Debug, Clone)]
pub struct Layout {
    /// Base (interface) nodes sorted by x, and their x, m.
    pub base: Vec<usize>,
    pub x: Vec<f64>,
    /// Top nodes and their x, m.
    pub top: Vec<usize>,
    pub top_x: Vec<f64>,
    /// H - t, m: the arm from the block top to the drive point.
    pub arm: f64,
    /// The plate's own mass (kg/m) and rotational inertia about its centre of mass
    /// (kg m^2/m), and the centre's x (the block top's mid-point), m.
    pub plate_mass: f64,
    pub plate_inertia: f64,
    pub x_c: f64,
    /// The base nodes, then the top nodes: the nodes the stepper's boundary updates.
    hooked: Vec<usize>,
    /// sum m, sum m x, sum m (x^2 + arm^2) over the top nodes.
    top_moments: [f64; 3],
    /// Inverse of the plate's 2x2 mass matrix over (V, theta).
    mp_inv: [[f64; 2]; 2],
    m_top: f64,
    /// The side-pushed rig's boundary in place of the top plate's (None: the top plate).
    pub side: Option<SideLayout>,
}

/// The side push's boundary (issue 49; docs/check.md, "The side-pushed rig"): the pusher's
/// face nodes share U_p (their v free); the top is either under the uniform pressure (free
/// nodes, each loaded by its consistent share of N) or the sliding plate (u = U, v = V +
/// theta x: the top plate's (V, theta) with a zero arm, and U free, not driven).
#[derive(Debug, Clone)]
pub struct SideLayout {
    /// The pusher's face nodes; whether the pusher moves each one's v (false: a top node
    /// under the pressure, moved with the top).
    pub pusher: Vec<usize>,
    pusher_v: Vec<bool>,
    /// The spring's stiffness, N/m per m: the drive X is its far end and U_p is free
    /// ([`DynState::free`]); None: U_p is the drive.
    pub stiffness: Option<f64>,
    /// Under the uniform pressure, each top node's nodal force per N/m of N (y, N/m; the
    /// consistent share, negative); empty: the sliding plate.
    pub pressure: Vec<f64>,
    /// Top nodes whose u is the pusher's (the pressure's top corner when the pusher reaches it).
    pushed_top: Vec<bool>,
    /// The pusher nodes' lumped mass, kg/m (the sprung U_p's inertia).
    m_pusher: f64,
}

impl Layout {
    /// The massless plate (m_p = I_c = 0): its inertia is the top nodes' lumped masses.
    pub fn new(
        model: &Elastodynamic,
        base: Vec<usize>,
        x: Vec<f64>,
        top: Vec<usize>,
        top_x: Vec<f64>,
        arm: f64,
    ) -> Self {
        let hooked = base.iter().chain(&top).copied().collect();
        let (mut a, mut b, mut c) = (0.0, 0.0, 0.0);
        for (&k, &xk) in top.iter().zip(&top_x) {
            let m = model.mass[k];
            a += m;
            b += m * xk;
            c += m * (xk * xk + arm * arm);
        }
        let (lo, hi) =
            top_x.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &v| (l.min(v), h.max(v)));
        let mut lay = Self {
            base,
            x,
            top,
            top_x,
            arm,
            plate_mass: 0.0,
            plate_inertia: 0.0,
            x_c: 0.5 * (lo + hi),
            hooked,
            top_moments: [a, b, c],
            mp_inv: [[0.0; 2]; 2],
            m_top: a,
            side: None,
        };
        lay.mp_inv = inverse(lay.plate_matrix());
        lay
    }

    /// The side-pushed rig: the pusher's face nodes `pusher`, the spring `stiffness` (N/m per
    /// m; None: U_p driven), the top's `pressure` shares (per top node; empty: the sliding
    /// plate, whose (V, theta) are the top plate's with a zero arm).
    pub fn side_push(
        model: &Elastodynamic,
        (base, x): (Vec<usize>, Vec<f64>),
        (top, top_x): (Vec<usize>, Vec<f64>),
        pusher: Vec<usize>,
        stiffness: Option<f64>,
        pressure: Vec<f64>,
    ) -> Self {
        let mut lay = Self::new(model, base, x, top, top_x, 0.0);
        let on_top = |k: &usize| lay.top.contains(k);
        let pusher_v = pusher.iter().map(|k| !on_top(k)).collect();
        let pushed_top =
            if pressure.is_empty() { vec![] } else { lay.top.iter().map(|k| pusher.contains(k)).collect() };
        lay.hooked.extend(pusher.iter().filter(|k| !on_top(k)));
        let m_pusher = pusher.iter().map(|&k| model.mass[k]).sum();
        lay.side = Some(SideLayout { pusher, pusher_v, stiffness, pressure, pushed_top, m_pusher });
        lay
    }

    /// The plate as a rigid body of mass `mass` (kg/m) and rotational inertia `inertia`
    /// (kg m^2/m) about its centre of mass at the block top's mid-point. Both 0 is the
    /// massless limit: the paper's plate is loaded quasi-statically and has no stated mass,
    /// and with the drive held or slow the plate only moves with the block, so its mass is
    /// a free input of the dynamic events (the top nodes' lumped masses, rho h^2 / 2 each,
    /// already give the plate DOFs a non-singular mass).
    pub fn with_plate(mut self, mass: f64, inertia: f64) -> Result<Self> {
        check_plate(mass, inertia)?;
        self.plate_mass = mass;
        self.plate_inertia = inertia;
        self.mp_inv = inverse(self.plate_matrix());
        Ok(self)
    }

    /// The plate's 2x2 mass matrix over (V, theta): the top nodes' and the plate's own.
    pub fn plate_matrix(&self) -> [[f64; 2]; 2] {
        let [a, b, c] = self.top_moments;
        let (mp, xc) = (self.plate_mass, self.x_c);
        [[a + mp, b + mp * xc], [b + mp * xc, c + mp * (xc * xc + self.arm * self.arm) + self.plate_inertia]]
    }

    /// The plate's own kinetic energy (without the top nodes'), J/m, at rates (V', theta')
    /// with the drive point moving at `u_h_dot`.
    pub fn plate_kinetic(&self, u_h_dot: f64, qdot: [f64; 2]) -> f64 {
        let (vx, vy) = (u_h_dot + self.arm * qdot[1], qdot[0] + self.x_c * qdot[1]);
        0.5 * self.plate_mass * (vx * vx + vy * vy) + 0.5 * self.plate_inertia * qdot[1] * qdot[1]
    }
}

/// Refuses a plate mass or inertia that is negative or not finite.
pub fn check_plate(mass: f64, inertia: f64) -> Result<()> {
    for (flag, v, unit) in [("--plate-mass", mass, "kg/m"), ("--plate-inertia", inertia, "kg m^2/m")] {
        // Above 1e100 the plate's 2x2 matrix (products of two) overflows: a plate that heavy
        // is the rigid, unmoving one anyway.
        if !(v.is_finite() && (0.0..=1e100).contains(&v)) {
            return Err(Error::input(
                flag,
                format!(
                    "{}: give a value in [0, 1e100] {unit} (0: the massless plate)",
                    crate::error::num(v)
                ),
            ));
        }
    }
    Ok(())
}

fn inverse(m: [[f64; 2]; 2]) -> [[f64; 2]; 2] {
    let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    [[m[1][1] / det, -m[0][1] / det], [-m[1][0] / det, m[0][0] / det]]
}

/// The moving state: displacements at step n, velocities at n - 1/2, the plate, the slips.
#[derive(Debug, Clone, Default)]
pub struct DynState {
    pub u: Vec<f64>,
    pub v: Vec<f64>,
    /// Drive point, m; its velocity, m/s (0: held).
    pub u_h: f64,
    pub drive_velocity: f64,
    /// Plate V (m), theta (rad) at step n and their rates at n - 1/2.
    pub q: [f64; 2],
    pub qdot: [f64; 2],
    /// The side push's free coordinates (the sprung pusher's U_p, the sliding plate's U; m)
    /// at step n and their rates at n - 1/2 (unused by the top plate).
    pub free: [f64; 2],
    pub free_dot: [f64; 2],
    /// Slip path length of each base node since the last healing, m.
    pub d: Vec<f64>,
    /// Rate-and-state state of each base node, s (empty for the rate-free laws).
    pub theta: Vec<f64>,
    /// The normal force each base node's strength is taken on under a lagging normal response,
    /// N/m (empty: taken from the first step's contact force).
    pub p_lagged: Vec<f64>,
    /// Time, s.
    pub time: f64,
}

/// Which test ends an event (`slide --dynamics --event-end`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum EventEnd {
    /// The kinetic energy at most [`EventLimits::ke_fraction`] of the dissipation with no base
    /// node moving ([`EventLimits::quiet_steps`]): the ring-down to rest.
    #[default]
    Energy,
    /// What is handed back is frozen: once some node slipped past the event's threshold, over
    /// [`EventLimits::slip_window`] steps no base node's slip (path length) grew by more than
    /// [`EventLimits::slip_tol`] and none opened or closed. The energy test still ends the event
    /// if it comes first (an event in which no node passed the threshold).
    Slip,
}

impl EventEnd {
    /// The names a front end accepts, with their values.
    pub const NAMES: [(&'static str, EventEnd); 2] = [("energy", EventEnd::Energy), ("slip", EventEnd::Slip)];

    pub fn name(self) -> &'static str {
        Self::NAMES.iter().find(|(_, e)| *e == self).map_or("", |(n, _)| n)
    }
}

impl std::str::FromStr for EventEnd {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        Self::NAMES.iter().find(|(n, _)| *n == s).map(|&(_, e)| e).ok_or_else(|| {
            Error::input("--event-end", format!("'{s}': give energy (rest: the kinetic-energy test) or slip (the handed-back state frozen)"))
        })
    }
}

/// When an event stops.
#[derive(Debug, Clone, Copy)]
pub struct EventLimits {
    /// Which test ends the event.
    pub end: EventEnd,
    /// [`EventEnd::Energy`]: kinetic energy at most this fraction of what the event has
    /// dissipated (friction + damping)...
    pub ke_fraction: f64,
    /// ...and no base node slipping, both for this many consecutive steps.
    pub quiet_steps: usize,
    /// [`EventEnd::Slip`]: the largest slip growth of a base node over the window, m, and the
    /// window, steps.
    pub slip_tol: f64,
    pub slip_window: usize,
    /// A base node at its strength slipping slower than this (m/s) counts as stuck in that
    /// test: a node that comes to rest exactly at its strength (tau -> mu(d) p from above,
    /// e.g. a fully weakened node arresting at mu_d p) stays flagged as slipping at any
    /// speed, down to round-off (1e-17 m/s), so without it the event never ends by the quiet
    /// test. See [`rest_rate`].
    pub rest_rate: f64,
    /// Cap on the steps of one event.
    pub max_steps: usize,
    /// Record a sample (tip, force, slip rates) every this many steps.
    pub sample_every: usize,
    /// A base node's front arrival is the first step its |v_x| exceeds this, m/s
    /// ([`EventRecord::arrival`]).
    pub arrival_rate: f64,
}

/// Energies of one event, J/m (the scheme's exact ledger).
#[derive(Debug, Clone, Copy, Default)]
pub struct EventEnergy {
    pub kinetic: f64,
    pub strain: f64,
    pub friction: f64,
    pub damping: f64,
    pub work_n: f64,
    pub contact: f64,
    pub drive: f64,
    /// (kinetic + strain + friction + damping - work_n - contact - drive) minus its value at
    /// the start: zero to round-off.
    pub residual: f64,
    /// Strain energy at the start.
    pub strain_start: f64,
    /// Kinetic energy after the last step (what the end criterion reads).
    pub kinetic_end: f64,
}

/// What one event did.
#[derive(Debug, Clone, Default)]
pub struct EventRecord {
    pub steps: usize,
    pub duration: f64,
    /// Slip of each base node during the event (path length), m; its largest |v_x|, m/s.
    pub slip: Vec<f64>,
    pub peak_rate: Vec<f64>,
    /// First base node (index) whose event slip passed the threshold, the threshold (m).
    pub nucleation: Option<usize>,
    pub threshold: f64,
    /// Samples: time since the event began (s), the drive force F (N/m), the tip of the
    /// slipped run containing the nucleation node farthest from it (x, m; NaN before
    /// nucleation), and |v_x| of every base node (m/s).
    pub t: Vec<f64>,
    pub force: Vec<f64>,
    pub tip: Vec<f64>,
    pub rates: Vec<Vec<f32>>,
    /// The base nodes' contact forces before the event, N/m: the first step's P* and T*
    /// (before the friction cap), which start from the static field at rest and so are its
    /// reactions: the pre-event field (sum P = N, sum T = -F_onset). The nucleating patch
    /// starts above its strength there (its slip has outrun its coefficient: the
    /// instability), so T differs from T* on it from the first step on.
    pub p_pre: Vec<f64>,
    pub t_pre: Vec<f64>,
    /// Slip memory of each base node at the onset (slip since the last healing), m: the
    /// nucleating patch is the run of nodes past `threshold` around the nucleation node.
    pub d_pre: Vec<f64>,
    /// P and T (N/m) of every base node at the samples up to the front's arrest
    /// ([`arrest_sample`]; `p_samples[j]` is at `t[j]`): the later samples are dropped, only
    /// the propagation is read from them and they cost 2 x `rates`.
    pub p_samples: Vec<Vec<f32>>,
    pub t_samples: Vec<Vec<f32>>,
    /// Time since onset (s) of the first step at which each base node's |v_x| exceeded
    /// `arrival_rate` (m/s); NaN: never. Per step, not per sample: a front at c_s crosses a
    /// quarter of the thickness between samples, one step is ~1/12 of that.
    pub arrival: Vec<f64>,
    pub arrival_rate: f64,
    /// Some node reached D_c of slip since the last healing (weakened fully) in this event.
    pub weakened: bool,
    pub settled: bool,
    /// Base nodes that ended the event at their strength but slower than the rest rate
    /// (counted as stuck by the quiet test).
    pub at_strength: usize,
    pub energy: EventEnergy,
    /// Base nodes open at the end.
    pub open: Vec<bool>,
}

/// The dynamic problem: model, layout, friction law and normal response, N, step and damping.
pub struct Driven<'a> {
    pub model: &'a Elastodynamic,
    pub layout: &'a Layout,
    /// Coulomb, slip weakening or rate-and-state ([`Law::split_node`]).
    pub law: Law,
    pub normal: Normal,
    pub n_force: f64,
    pub dt: f64,
    pub eta: f64,
}

/// The run's stepper (the crate's one explicit integrator, [`Explicit`]) between steps.
pub struct Work<'a> {
    ex: Explicit<'a>,
}

/// A base node after a step: the flat's forces on it (T along x, P along y, N/m), the T*
/// that would have stopped it (N/m; 0 when open), whether it slipped (friction at its
/// strength) and whether it is open.
#[derive(Debug, Clone, Copy, Default)]
pub struct Contact {
    pub t: f64,
    pub p: f64,
    pub t_trial: f64,
    pub slipping: bool,
    pub open: bool,
}

/// What one step reports: the drive's reaction F (N/m) after it, whether some base node
/// slipped, and the ledger's balance before it (J/m; constant to round-off).
#[derive(Debug, Clone, Copy)]
pub struct StepOut {
    pub f_drive: f64,
    pub any_slip: bool,
    pub balance: f64,
}

impl EventRecord {
    /// Base node `b` moving at `rate` (|v_x|, m/s) at `t` s since onset: its peak rate and
    /// its arrival ([`Self::arrival`]).
    pub fn note_rate(&mut self, b: usize, rate: f64, t: f64) {
        self.peak_rate[b] = self.peak_rate[b].max(rate);
        if rate > self.arrival_rate && self.arrival[b].is_nan() {
            self.arrival[b] = t;
        }
    }
}

impl Work<'_> {
    /// After a [`Driven::step`] from level n: the displacements u^n it started from, m.
    pub fn u_before(&self) -> &[f64] {
        self.ex.u_before()
    }
}

/// The block's boundary in one step: the base on the flat and the plate (see the module
/// docs); the stepper updates every other node.
struct PlateAndBase<'s> {
    dr: &'s Driven<'s>,
    q: &'s mut [f64; 2],
    qdot: &'s mut [f64; 2],
    free: &'s mut [f64; 2],
    free_dot: &'s mut [f64; 2],
    u_h: &'s mut f64,
    drive_velocity: f64,
    d: &'s mut [f64],
    theta: &'s mut [f64],
    p_lagged: &'s mut [f64],
    contact: &'s mut [Contact],
    e: &'s mut EventEnergy,
    any_slip: bool,
    f_drive: f64,
}

impl Boundary for PlateAndBase<'_> {
    fn nodes(&self) -> &[usize] {
        &self.dr.layout.hooked
    }

    fn own_kinetic(&self) -> f64 {
        self.dr.layout.plate_kinetic(self.drive_velocity, *self.qdot)
    }

    fn apply(&mut self, mut s: BoundaryStep<'_>) -> f64 {
        let (lay, dt) = (self.dr.layout, s.dt);
        let (fr0, co0, wn0, dr0) = (self.e.friction, self.e.contact, self.e.work_n, self.e.drive);
        // Base nodes: contact and friction.
        for (b, &k) in lay.base.iter().enumerate() {
            let mk = s.mass[k];
            let (ix, iy) = (2 * k, 2 * k + 1);
            let (fx, fy) = (s.force(ix), s.force(iy));
            let (vxm, vym) = (s.v[ix], s.v[iy]);
            let p_star = -fy - mk * vym / dt - mk * s.u[iy] / (dt * dt);
            let mut slipping = false;
            let p_strength = if self.dr.normal.lags() {
                let lagged = if self.p_lagged[b].is_nan() { p_star } else { self.p_lagged[b] };
                self.p_lagged[b] = self.dr.normal.relax(lagged, p_star.max(0.0), dt, vxm);
                self.p_lagged[b]
            } else {
                p_star
            };
            let (t, p, t_trial) = if p_star > 0.0 {
                let t_star = -fx - mk * vxm / dt;
                let trial =
                    Trial { t_star, p: p_strength, z: mk / dt, dt, slip: self.d[b], v_old: vxm.abs() };
                let mut rate_free = 0.0;
                let theta = match self.theta.get_mut(b) {
                    Some(th) => th,
                    None => &mut rate_free,
                };
                let (t, slips) = self.dr.law.split_node(trial, theta);
                slipping = slips;
                (t, p_star, t_star)
            } else {
                (0.0, 0.0, 0.0)
            };
            self.any_slip |= slipping;
            self.contact[b] = Contact { t, p, t_trial, slipping, open: p_star <= 0.0 };
            let vx = vxm + dt * (fx + t) / mk;
            let vy = if p_star > 0.0 { -s.u[iy] / dt } else { vym + dt * (fy + p) / mk };
            let (vbx, vby) = (0.5 * (vxm + vx), 0.5 * (vym + vy));
            self.e.friction -= dt * vbx * t;
            self.e.contact += dt * vby * p;
            s.v[ix] = vx;
            s.v[iy] = vy;
            s.u_next[ix] = s.u[ix] + dt * vx;
            s.u_next[iy] = if p_star > 0.0 { 0.0 } else { s.u[iy] + dt * vy };
            self.d[b] += dt * vx.abs();
        }
        if let Some(side) = &lay.side {
            self.side_push(side, &mut s);
            return (self.e.work_n - wn0) + (self.e.contact - co0) + (self.e.drive - dr0)
                - (self.e.friction - fr0);
        }
        // The plate, and the drive's reaction F = (sum m + m_p) arm theta'' - sum f_x (U_H
        // has no acceleration).
        let (theta_acc, fx_sum) = self.plate_step(&s, lay.arm);
        self.f_drive = (lay.m_top + lay.plate_mass) * lay.arm * theta_acc - fx_sum;
        self.e.drive += dt * self.drive_velocity * self.f_drive;
        *self.u_h += dt * self.drive_velocity;
        for (&k, &xk) in lay.top.iter().zip(&lay.top_x) {
            let (ix, iy) = (2 * k, 2 * k + 1);
            s.v[ix] = self.drive_velocity + lay.arm * self.qdot[1];
            s.v[iy] = self.qdot[0] + xk * self.qdot[1];
            s.u_next[ix] = *self.u_h + lay.arm * self.q[1];
            s.u_next[iy] = self.q[0] + xk * self.q[1];
        }
        (self.e.work_n - wn0) + (self.e.contact - co0) + (self.e.drive - dr0) - (self.e.friction - fr0)
    }
}

/// v^{n+1/2} of DOF `i` moving freely under the mesh's force plus `ext` (N/m).
fn free_dof(s: &BoundaryStep<'_>, i: usize, ext: f64) -> f64 {
    s.v[i] + s.dt * (s.force(i) + ext) / s.mass[i / 2]
}

impl PlateAndBase<'_> {
    /// The rigid plate's (V, theta) over one step under the top nodes' forces and -N, f_x
    /// acting at `arm` above the block's top (0: the side push's sliding plate), with N's
    /// work; returns theta'' and sum f_x over the top.
    fn plate_step(&mut self, s: &BoundaryStep<'_>, arm: f64) -> (f64, f64) {
        let (lay, dt) = (self.dr.layout, s.dt);
        let (mut qv, mut qt, mut fx_sum) = (-self.dr.n_force, 0.0, 0.0);
        for (&k, &xk) in lay.top.iter().zip(&lay.top_x) {
            let (fx, fy) = (s.force(2 * k), s.force(2 * k + 1));
            qv += fy;
            qt += fx * arm + fy * xk;
            fx_sum += fx;
        }
        let acc =
            [lay.mp_inv[0][0] * qv + lay.mp_inv[0][1] * qt, lay.mp_inv[1][0] * qv + lay.mp_inv[1][1] * qt];
        let qd_old = *self.qdot;
        for j in 0..2 {
            self.qdot[j] += dt * acc[j];
            self.q[j] += dt * self.qdot[j];
        }
        self.e.work_n -= dt * 0.5 * (qd_old[0] + self.qdot[0]) * self.dr.n_force;
        (acc[1], fx_sum)
    }

    /// The side push's boundary in one step (the base done): the pusher (U_p driven at the
    /// drive velocity, or free under its spring k (X - U_p) and the face's forces), the top
    /// (free nodes under the pressure's nodal forces, or the sliding plate: U free, (V,
    /// theta) as the top plate's with a zero arm). F is the pusher's force on the block: the
    /// spring's, or -sum f_x over the face (U_p has no acceleration).
    fn side_push(&mut self, side: &SideLayout, s: &mut BoundaryStep<'_>) {
        let (lay, dt, n_force) = (self.dr.layout, s.dt, self.dr.n_force);
        let face_fx: f64 = side.pusher.iter().map(|&k| s.force(2 * k)).sum();
        let (up_next, up_dot) = match side.stiffness {
            Some(k) => {
                let spring = k * (*self.u_h - self.free[0]);
                let old = self.free_dot[0];
                self.free_dot[0] += dt * (face_fx + spring) / side.m_pusher;
                self.free[0] += dt * self.free_dot[0];
                self.f_drive = spring;
                // The ledger's drive work is the spring's on the pusher (its energy is outside the mesh).
                self.e.drive += dt * 0.5 * (old + self.free_dot[0]) * spring;
                (self.free[0], self.free_dot[0])
            }
            None => {
                self.f_drive = -face_fx;
                self.e.drive += dt * self.drive_velocity * self.f_drive;
                (*self.u_h + dt * self.drive_velocity, self.drive_velocity)
            }
        };
        *self.u_h += dt * self.drive_velocity;
        if side.pressure.is_empty() {
            // The sliding plate: U under the top's sum f_x, (V, theta) under -N and no moment.
            let (_, fx_sum) = self.plate_step(s, 0.0);
            self.free_dot[1] += dt * fx_sum / lay.m_top;
            self.free[1] += dt * self.free_dot[1];
            for (&k, &xk) in lay.top.iter().zip(&lay.top_x) {
                let (ix, iy) = (2 * k, 2 * k + 1);
                s.v[ix] = self.free_dot[1];
                s.v[iy] = self.qdot[0] + xk * self.qdot[1];
                s.u_next[ix] = self.free[1];
                s.u_next[iy] = self.q[0] + xk * self.q[1];
            }
        } else {
            for (j, &k) in lay.top.iter().enumerate() {
                let (ix, iy) = (2 * k, 2 * k + 1);
                let p = n_force * side.pressure[j];
                let vy = free_dof(s, iy, p);
                self.e.work_n += dt * 0.5 * (s.v[iy] + vy) * p;
                s.v[iy] = vy;
                s.u_next[iy] = s.u[iy] + dt * vy;
                if !side.pushed_top[j] {
                    s.v[ix] = free_dof(s, ix, 0.0);
                    s.u_next[ix] = s.u[ix] + dt * s.v[ix];
                }
            }
        }
        for (&k, &own_v) in side.pusher.iter().zip(&side.pusher_v) {
            let (ix, iy) = (2 * k, 2 * k + 1);
            s.v[ix] = up_dot;
            s.u_next[ix] = up_next;
            if own_v {
                s.v[iy] = free_dof(s, iy, 0.0);
                s.u_next[iy] = s.u[iy] + dt * s.v[iy];
            }
        }
    }
}

impl<'a> Driven<'a> {
    /// The stepper for [`Self::step`] from the state's u and v (u^{n-1} = u^n - dt v^{n-1/2}).
    pub fn work(&self, st: &DynState) -> Work<'a> {
        let nd = self.model.n_dofs();
        // dt and eta were checked against the stable step with the user's flags (Setup).
        let mut ex = Explicit::checked_by_caller(self.model, self.dt, self.eta, vec![false; nd])
            .with_boundary(&self.layout.hooked);
        ex.set_state(&st.u, &st.v);
        // The event reads the conserved ledger only (EventEnergy).
        ex.sums = crate::dynamics::explicit::Sums::Ledger;
        Work { ex }
    }

    /// One explicit step of the block, its base and the plate; the energies of `e` (kinetic
    /// and strain at its start, the work and dissipation sums) are updated, the base nodes'
    /// forces written to `contact`.
    pub fn step(
        &self,
        st: &mut DynState,
        w: &mut Work,
        e: &mut EventEnergy,
        contact: &mut [Contact],
    ) -> StepOut {
        let nb = self.layout.base.len();
        if self.normal.lags() && st.p_lagged.len() != nb {
            // NaN: the first step takes its contact force (the state at rest is at equilibrium).
            st.p_lagged = vec![f64::NAN; nb];
        }
        let ex = &mut w.ex;
        // The state's arrays are the stepper's for the step (a swap of pointers).
        std::mem::swap(&mut ex.u, &mut st.u);
        std::mem::swap(&mut ex.v, &mut st.v);
        let mut b = PlateAndBase {
            dr: self,
            q: &mut st.q,
            qdot: &mut st.qdot,
            free: &mut st.free,
            free_dot: &mut st.free_dot,
            u_h: &mut st.u_h,
            drive_velocity: st.drive_velocity,
            d: &mut st.d,
            theta: &mut st.theta,
            p_lagged: &mut st.p_lagged,
            contact,
            e,
            any_slip: false,
            f_drive: 0.0,
        };
        ex.step_boundary(&mut b);
        let (any_slip, f_drive) = (b.any_slip, b.f_drive);
        std::mem::swap(&mut ex.u, &mut st.u);
        std::mem::swap(&mut ex.v, &mut st.v);
        let l = &ex.ledger;
        e.kinetic = l.kinetic_half;
        e.strain = l.shadow_half - l.kinetic_half;
        e.damping += l.damping - l.damping_half;
        st.time += self.dt;
        StepOut { f_drive, any_slip, balance: ex.shadow_balance() }
    }

    /// Runs until the event settles (or the step cap); `slip_threshold` (m) marks a node as
    /// slipped for the tip and the nucleation node. Every [`crate::cancel::BEAT`] of wall time
    /// `cancel` is checked and `tick` called (a host's progress report).
    pub fn run_event(
        &self,
        st: &mut DynState,
        lim: &EventLimits,
        slip_threshold: f64,
        cancel: &crate::Cancel,
        tick: &dyn Fn(),
    ) -> Result<EventRecord> {
        let (m, lay, dt) = (self.model, self.layout, self.dt);
        let nb = lay.base.len();
        let mut w = self.work(st);
        let mut contact = vec![Contact::default(); nb];
        let d0 = st.d.clone();
        let mut rec = EventRecord {
            d_pre: d0.clone(),
            slip: vec![0.0; nb],
            peak_rate: vec![0.0; nb],
            threshold: slip_threshold,
            open: vec![false; nb],
            arrival: vec![f64::NAN; nb],
            arrival_rate: lim.arrival_rate,
            ..Default::default()
        };
        let mut e = EventEnergy::default();
        let mut start_balance = None;
        let mut quiet = 0usize;
        // The slip test's window: its first step, and the slips and contact at its start.
        let (mut since, mut d_ref, mut open_ref) = (0usize, d0.clone(), vec![false; nb]);
        let mut f_drive = 0.0;
        let mut beat = cancel.beat();
        for step in 0..lim.max_steps {
            let out = self.step(st, &mut w, &mut e, &mut contact);
            let b0 = *start_balance.get_or_insert(out.balance);
            e.residual = out.balance - b0;
            if step == 0 {
                e.strain_start = e.strain;
                rec.p_pre = contact.iter().map(|c| c.p).collect();
                rec.t_pre = contact.iter().map(|c| c.t_trial).collect();
            }
            f_drive = out.f_drive;
            let now = (step + 1) as f64 * dt;
            for (b, &k) in lay.base.iter().enumerate() {
                rec.open[b] = contact[b].open;
                rec.note_rate(b, st.v[2 * k].abs(), now);
            }
            // The event's slip, the nucleation node, the tip.
            for b in 0..nb {
                rec.slip[b] = st.d[b] - d0[b];
                if rec.nucleation.is_none() && rec.slip[b] > slip_threshold {
                    rec.nucleation = Some(b);
                }
                if let Law::SlipWeakening { mu_s, mu_d, dc } = self.law {
                    if st.d[b] >= dc && d0[b] < dc && mu_s > mu_d {
                        rec.weakened = true;
                    }
                }
            }
            rec.steps = step + 1;
            if step % lim.sample_every == 0 {
                rec.t.push(rec.steps as f64 * dt);
                rec.force.push(f_drive);
                rec.tip.push(tip_of(&rec, &lay.x));
                rec.rates.push(lay.base.iter().map(|&k| st.v[2 * k].abs() as f32).collect());
                rec.p_samples.push(contact.iter().map(|c| c.p as f32).collect());
                rec.t_samples.push(contact.iter().map(|c| c.t as f32).collect());
            }
            // Slipping means at the strength and moving: a node at its strength at a
            // negligible rate is at rest (EventLimits::rest_rate).
            let mut resting = 0;
            let mut moving = false;
            if out.any_slip {
                for (b, &k) in lay.base.iter().enumerate() {
                    if contact[b].slipping {
                        if st.v[2 * k].abs() > lim.rest_rate {
                            moving = true;
                            break;
                        }
                        resting += 1;
                    }
                }
            }
            rec.at_strength = if moving { 0 } else { resting };
            quiet = if moving { 0 } else { quiet + 1 };
            if lim.end == EventEnd::Slip {
                // The handoff anchors each node where it is and keeps its slip (or heals it):
                // a window in which neither moved past the tolerance ends the event. Only once
                // some node slipped past the threshold: a slow start (an onset just past its
                // fold) must not end before it runs away; such a non-event rings down as before.
                let changed = step == 0
                    || (0..nb).any(|b| st.d[b] - d_ref[b] > lim.slip_tol || contact[b].open != open_ref[b]);
                if changed {
                    d_ref.copy_from_slice(&st.d);
                    open_ref.iter_mut().zip(&contact).for_each(|(o, c)| *o = c.open);
                    since = step;
                } else if step - since >= lim.slip_window && rec.nucleation.is_some() {
                    rec.settled = true;
                    break;
                }
            }
            let dissipated = e.friction + e.damping;
            // The kinetic energy only once quiet (a pass over every node, 10 % of a step).
            let ke = || m.kinetic_energy(&st.v) + lay.plate_kinetic(st.drive_velocity, st.qdot);
            if quiet >= lim.quiet_steps && ke() <= lim.ke_fraction * dissipated.max(f64::MIN_POSITIVE) {
                rec.settled = true;
                break;
            }
            if quiet >= lim.quiet_steps && dissipated == 0.0 {
                // Nothing ever moved: an empty event.
                rec.settled = true;
                break;
            }
            if beat.due()? {
                tick();
            }
        }
        rec.duration = rec.steps as f64 * dt;
        if !(e.residual.is_finite() && st.u.iter().all(|v| v.is_finite())) {
            return Err(Error::Untrustworthy {
                detail: "the dynamic event produced non-finite values".into(),
                hint: "lower the time step (--courant) or check the scene".into(),
            });
        }
        e.kinetic_end = m.kinetic_energy(&st.v) + lay.plate_kinetic(st.drive_velocity, st.qdot);
        rec.energy = e;
        rec.t.push(rec.duration);
        rec.force.push(f_drive);
        rec.tip.push(tip_of(&rec, &lay.x));
        let keep = arrest_sample(&rec.tip).map_or(0, |k| k + 1);
        rec.p_samples.truncate(keep);
        rec.t_samples.truncate(keep);
        Ok(rec)
    }
}

/// The front's arrest: the first sample at which the tip is at its final position (None:
/// the event never nucleated).
pub fn arrest_sample(tip: &[f64]) -> Option<usize> {
    let last = tip.iter().rev().find(|x| x.is_finite())?;
    tip.iter().position(|x| x == last)
}

/// The slip rate below which a base node at its strength counts as at rest, m/s:
/// `REST_SLIP` of the interface's slip scale per period of the block's thickness mode.
/// The scale is D_c (a slip of s changes the coefficient by (mu_s - mu_d) s / D_c) or, if
/// smaller, the elastic slip mu_s p t / G that relaxes the layer's whole shear (Coulomb:
/// D_c plays no part). A node at that rate moves 1e-6 of the scale in a period, changing
/// its friction force by 1e-6 of the weakening drop: the same fraction as the kinetic-energy
/// test (1e-6 of the dissipation). Round-off rates of a node at rest are ~1e-17 m/s, a
/// slipping node's at the end of an event (kinetic energy 1e-6 of the dissipation) 1e-9 to
/// 1e-7 m/s, against 4.9e-11 m/s on the paper's scene (D_c = 4.6e-7 m, period 9.5 ms).
/// Rate-and-state: its state distance L in place of D_c.
pub fn rest_rate(law: &Law, elastic_slip: f64, period: f64) -> f64 {
    let scale = match *law {
        Law::SlipWeakening { mu_s, mu_d, dc } if mu_s > mu_d => dc.min(elastic_slip),
        Law::RateState(r) => r.l.min(elastic_slip),
        _ => elastic_slip,
    };
    REST_SLIP * scale / period
}

/// Slip per thickness period, as a fraction of the slip scale, of a node at rest.
pub const REST_SLIP: f64 = 1e-6;

/// x of the end of the slipped run around the nucleation node farther from it; NaN before one.
fn tip_of(rec: &EventRecord, x: &[f64]) -> f64 {
    tip(rec.nucleation, |i| rec.slip[i] > rec.threshold, x)
}

/// x of the end of the run of nodes that `went` around the nucleation node, the end farther
/// from it; NaN before one. Both drive modes' front tip.
pub(crate) fn tip(nucleation: Option<usize>, went: impl Fn(usize) -> bool, x: &[f64]) -> f64 {
    let Some(c) = nucleation else { return f64::NAN };
    let (a, b) = crate::numeric::run_around(c, x.len(), went);
    if (x[b] - x[c]).abs() >= (x[c] - x[a]).abs() {
        x[b]
    } else {
        x[a]
    }
}
