//! One dynamic event of the plate-driven block (issue 33, part 3): explicit central
//! differences on the whole mesh, the rigid plate as a rigid body, the base on the rigid flat
//! with unilateral contact and slip-weakening friction imposed per node and step in total
//! forces (the traction-at-split-node rule of [`super::rupture`], here without a background).
//!
//! The plate: U_H (the drive point at height H) held, or moved at a constant velocity; its
//! other two DOFs q = (V, theta) are free under -N and no moment. The top nodes follow it,
//! u = U_H + theta (H - t), v = V + theta x, so its mass matrix is G^T M_top G from their
//! lumped masses (the massless-plate limit: the plate itself adds no mass).
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

use super::explicit::{dot, Elastodynamic};
use super::friction::SlipWeakening;
use crate::error::{Error, Result};

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
    /// 0 interior, 1 base, 2 top, per node.
    role: Vec<u8>,
    /// Inverse of the plate's 2x2 mass matrix over (V, theta), and sum m, sum m x over the top.
    mp_inv: [[f64; 2]; 2],
    m_top: f64,
}

impl Layout {
    pub fn new(
        model: &Elastodynamic,
        base: Vec<usize>,
        x: Vec<f64>,
        top: Vec<usize>,
        top_x: Vec<f64>,
        arm: f64,
    ) -> Self {
        let mut role = vec![0u8; model.n_nodes()];
        base.iter().for_each(|&k| role[k] = 1);
        top.iter().for_each(|&k| role[k] = 2);
        let (mut a, mut b, mut c) = (0.0, 0.0, 0.0);
        for (&k, &xk) in top.iter().zip(&top_x) {
            let m = model.mass[k];
            a += m;
            b += m * xk;
            c += m * (xk * xk + arm * arm);
        }
        let det = a * c - b * b;
        let mp_inv = [[c / det, -b / det], [-b / det, a / det]];
        Self { base, x, top, top_x, arm, role, mp_inv, m_top: a }
    }
}

/// The moving state: displacements at step n, velocities at n - 1/2, the plate, the slips.
#[derive(Debug, Clone)]
pub struct DynState {
    pub u: Vec<f64>,
    pub v: Vec<f64>,
    /// Drive point, m; its velocity, m/s (0: held).
    pub u_h: f64,
    pub drive_velocity: f64,
    /// Plate V (m), theta (rad) at step n and their rates at n - 1/2.
    pub q: [f64; 2],
    pub qdot: [f64; 2],
    /// Slip path length of each base node since the last healing, m.
    pub d: Vec<f64>,
    /// Time, s.
    pub time: f64,
}

/// When an event stops.
#[derive(Debug, Clone, Copy)]
pub struct EventLimits {
    /// Kinetic energy at most this fraction of what the event has dissipated (friction +
    /// damping)...
    pub ke_fraction: f64,
    /// ...and no base node slipping, both for this many consecutive steps.
    pub quiet_steps: usize,
    /// Cap on the steps of one event.
    pub max_steps: usize,
    /// Record a sample (tip, force, slip rates) every this many steps.
    pub sample_every: usize,
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
    /// Some node reached D_c of slip since the last healing (weakened fully) in this event.
    pub weakened: bool,
    pub settled: bool,
    pub energy: EventEnergy,
    /// Base nodes open at the end.
    pub open: Vec<bool>,
}

/// The dynamic problem: model, layout, friction, N, step and damping.
pub struct Driven<'a> {
    pub model: &'a Elastodynamic,
    pub layout: &'a Layout,
    pub friction: SlipWeakening,
    pub n_force: f64,
    pub dt: f64,
    pub eta: f64,
}

impl Driven<'_> {
    /// Runs until the event settles (or the step cap); `slip_threshold` (m) marks a node as
    /// slipped for the tip and the nucleation node.
    pub fn run_event(
        &self,
        st: &mut DynState,
        lim: &EventLimits,
        slip_threshold: f64,
        cancel: &crate::Cancel,
    ) -> Result<EventRecord> {
        let (m, lay, dt, eta) = (self.model, self.layout, self.dt, self.eta);
        let nd = m.n_dofs();
        let nb = lay.base.len();
        let (mut ku, mut kv, mut u_prev) = (vec![0.0; nd], vec![0.0; nd], st.u.clone());
        for i in 0..nd {
            u_prev[i] = st.u[i] - dt * st.v[i];
        }
        let d0 = st.d.clone();
        let mut rec = EventRecord {
            slip: vec![0.0; nb],
            peak_rate: vec![0.0; nb],
            threshold: slip_threshold,
            open: vec![false; nb],
            ..Default::default()
        };
        let mut e = EventEnergy::default();
        let mut start_balance = None;
        let mut quiet = 0usize;
        let mut f_drive = 0.0;
        for step in 0..lim.max_steps {
            m.apply_k(&st.u, &mut ku);
            if eta > 0.0 {
                m.apply_k(&st.v, &mut kv);
            }
            let shadow = m.kinetic_energy(&st.v) + 0.5 * dot(&u_prev, &ku);
            let balance = shadow + e.friction + e.damping - e.work_n - e.contact - e.drive;
            let b0 = *start_balance.get_or_insert(balance);
            e.kinetic = m.kinetic_energy(&st.v);
            e.strain = 0.5 * dot(&u_prev, &ku);
            e.residual = balance - b0;
            if step == 0 {
                e.strain_start = e.strain;
            }
            let force = |i: usize| -ku[i] - if eta > 0.0 { eta * kv[i] } else { 0.0 };
            // Damping dissipation of this step over every DOF: sum dt vbar eta K v (vbar after
            // the update, accumulated below per node).
            let mut damp = 0.0;
            // Interior nodes.
            for k in 0..m.n_nodes() {
                if lay.role[k] != 0 {
                    continue;
                }
                let mk = m.mass[k];
                for c in 0..2 {
                    let i = 2 * k + c;
                    let vm = st.v[i];
                    let vp = vm + dt * force(i) / mk;
                    if eta > 0.0 {
                        damp += dt * 0.5 * (vm + vp) * eta * kv[i];
                    }
                    st.v[i] = vp;
                    u_prev[i] = st.u[i];
                    st.u[i] += dt * vp;
                }
            }
            // Base nodes: contact and friction.
            let mut any_slip = false;
            for (b, &k) in lay.base.iter().enumerate() {
                let mk = m.mass[k];
                let (ix, iy) = (2 * k, 2 * k + 1);
                let (fx, fy) = (force(ix), force(iy));
                let (vxm, vym) = (st.v[ix], st.v[iy]);
                let p_star = -fy - mk * vym / dt - mk * st.u[iy] / (dt * dt);
                let (t, p) = if p_star > 0.0 {
                    let strength = self.friction.mu(st.d[b]) * p_star;
                    let t_star = -fx - mk * vxm / dt;
                    if t_star.abs() <= strength {
                        (t_star, p_star)
                    } else {
                        any_slip = true;
                        (strength * t_star.signum(), p_star)
                    }
                } else {
                    (0.0, 0.0)
                };
                rec.open[b] = p_star <= 0.0;
                let vx = vxm + dt * (fx + t) / mk;
                let vy = if p_star > 0.0 { -st.u[iy] / dt } else { vym + dt * (fy + p) / mk };
                let (vbx, vby) = (0.5 * (vxm + vx), 0.5 * (vym + vy));
                e.friction -= dt * vbx * t;
                e.contact += dt * vby * p;
                if eta > 0.0 {
                    damp += dt * (vbx * eta * kv[ix] + vby * eta * kv[iy]);
                }
                st.v[ix] = vx;
                st.v[iy] = vy;
                u_prev[ix] = st.u[ix];
                u_prev[iy] = st.u[iy];
                st.u[ix] += dt * vx;
                st.u[iy] = if p_star > 0.0 { 0.0 } else { st.u[iy] + dt * vy };
                st.d[b] += dt * vx.abs();
                rec.peak_rate[b] = rec.peak_rate[b].max(vx.abs());
            }
            // The plate: generalized forces on (V, theta) from the top nodes, and the drive's
            // reaction F = sum m arm theta'' - sum f_x (U_H has no acceleration).
            let (mut qv, mut qt, mut fx_sum) = (-self.n_force, 0.0, 0.0);
            for (&k, &xk) in lay.top.iter().zip(&lay.top_x) {
                let (fx, fy) = (force(2 * k), force(2 * k + 1));
                qv += fy;
                qt += fx * lay.arm + fy * xk;
                fx_sum += fx;
            }
            let acc = [
                lay.mp_inv[0][0] * qv + lay.mp_inv[0][1] * qt,
                lay.mp_inv[1][0] * qv + lay.mp_inv[1][1] * qt,
            ];
            let qd_old = st.qdot;
            for j in 0..2 {
                st.qdot[j] += dt * acc[j];
                st.q[j] += dt * st.qdot[j];
            }
            f_drive = lay.m_top * lay.arm * acc[1] - fx_sum;
            e.work_n -= dt * 0.5 * (qd_old[0] + st.qdot[0]) * self.n_force;
            e.drive += dt * st.drive_velocity * f_drive;
            st.u_h += dt * st.drive_velocity;
            for (&k, &xk) in lay.top.iter().zip(&lay.top_x) {
                let (ix, iy) = (2 * k, 2 * k + 1);
                let (vx, vy) = (st.drive_velocity + lay.arm * st.qdot[1], st.qdot[0] + xk * st.qdot[1]);
                if eta > 0.0 {
                    damp +=
                        dt * (0.5 * (st.v[ix] + vx) * eta * kv[ix] + 0.5 * (st.v[iy] + vy) * eta * kv[iy]);
                }
                st.v[ix] = vx;
                st.v[iy] = vy;
                u_prev[ix] = st.u[ix];
                u_prev[iy] = st.u[iy];
                st.u[ix] = st.u_h + lay.arm * st.q[1];
                st.u[iy] = st.q[0] + xk * st.q[1];
            }
            e.damping += damp;
            st.time += dt;
            // The event's slip, the nucleation node, the tip.
            for b in 0..nb {
                rec.slip[b] = st.d[b] - d0[b];
                if rec.nucleation.is_none() && rec.slip[b] > slip_threshold {
                    rec.nucleation = Some(b);
                }
                if st.d[b] >= self.friction.d_c
                    && d0[b] < self.friction.d_c
                    && self.friction.mu_s > self.friction.mu_d
                {
                    rec.weakened = true;
                }
            }
            rec.steps = step + 1;
            if step % lim.sample_every == 0 {
                rec.t.push(rec.steps as f64 * dt);
                rec.force.push(f_drive);
                rec.tip.push(tip(&rec, &lay.x));
                rec.rates.push(lay.base.iter().map(|&k| st.v[2 * k].abs() as f32).collect());
            }
            quiet = if any_slip { 0 } else { quiet + 1 };
            let ke = m.kinetic_energy(&st.v);
            let dissipated = e.friction + e.damping;
            if quiet >= lim.quiet_steps && ke <= lim.ke_fraction * dissipated.max(f64::MIN_POSITIVE) {
                rec.settled = true;
                break;
            }
            if quiet >= lim.quiet_steps && dissipated == 0.0 {
                // Nothing ever moved: an empty event.
                rec.settled = true;
                break;
            }
            if step % 256 == 0 {
                cancel.check()?;
            }
        }
        rec.duration = rec.steps as f64 * dt;
        if !(e.residual.is_finite() && st.u.iter().all(|v| v.is_finite())) {
            return Err(Error::Untrustworthy {
                detail: "the dynamic event produced non-finite values".into(),
                hint: "lower the time step (--courant) or check the scene".into(),
            });
        }
        e.kinetic_end = m.kinetic_energy(&st.v);
        rec.energy = e;
        rec.t.push(rec.duration);
        rec.force.push(f_drive);
        rec.tip.push(tip(&rec, &lay.x));
        Ok(rec)
    }
}

/// x of the end of the slipped run around the nucleation node farther from it; NaN before one.
fn tip(rec: &EventRecord, x: &[f64]) -> f64 {
    let Some(c) = rec.nucleation else { return f64::NAN };
    let went = |i: usize| rec.slip[i] > rec.threshold;
    let (mut a, mut b) = (c, c);
    while a > 0 && went(a - 1) {
        a -= 1;
    }
    while b + 1 < x.len() && went(b + 1) {
        b += 1;
    }
    if (x[b] - x[c]).abs() >= (x[c] - x[a]).abs() {
        x[b]
    } else {
        x[a]
    }
}
