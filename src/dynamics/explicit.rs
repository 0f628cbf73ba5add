//! Explicit elastodynamics: central differences (Newmark beta = 0, gamma = 1/2) with a lumped
//! row-sum mass, on QUA4 meshes with full 2x2 integration (the static solver's element).
//!
//! ```text
//! M (v^{n+1/2} - v^{n-1/2}) / dt = f_ext^n - K (u^n + eta v^{n-1/2}),   u^{n+1} = u^n + dt v^{n+1/2}
//! ```
//!
//! `eta` (s) is stiffness-proportional Kelvin-Voigt damping (sigma = D (eps + eta d eps/dt)),
//! taken at the lagging half step so the update stays explicit, as SEM2DPACK does. A mode of
//! frequency omega is damped at the ratio xi = eta omega / 2: the highest mesh modes most.
//!
//! Internal forces come from element matrices (no assembled matrix); elements equal up to a
//! translation share one. On a regular grid (one matrix, row-by-row numbering: every mesh
//! `Rectangle` builds) K u is a node-wise stencil (`stencil`), optionally on several threads
//! with the same bits, and `Explicit::step` makes one fused pass over the node rows; other
//! meshes go element by element. Throughput and where the time goes: docs/dynamics-verification.md.
//!
//! The stable step is bounded rigorously by the element eigenvalues (Irons: the largest
//! eigenvalue of M^-1 K is at most the largest of the elements' Me^-1 Ke with their own lumped
//! masses); [`Elastodynamic::power_iteration`] estimates the true one to show the margin.

use crate::error::{Error, Result};
use crate::fem::element::stiffness::{map_point, stiffness, stiffness_rule};
use crate::fem::element::ElementKind;
use crate::fem::material::Material;
use crate::fem::mesh::Mesh;
use nalgebra::SMatrix;
use std::collections::HashMap;

mod stencil;
use stencil::Grid;

/// The block's mass and stiffness in the form the explicit update reads.
#[derive(Debug, Clone)]
pub struct Elastodynamic {
    n_nodes: usize,
    conn: Vec<[u32; 4]>,
    kmats: Vec<[f64; 64]>,
    kidx: Vec<u32>,
    /// Lumped mass of each node, kg per metre of width (the same for both of its DOFs).
    pub mass: Vec<f64>,
    /// Upper bound on the largest eigenvalue of M^-1 K, 1/s^2 (element bound).
    pub lambda_bound: f64,
    pub material: Material,
    /// kg/m^3.
    pub density: f64,
    /// Set when the mesh is a regular grid (see [`Grid`]): K u then reads no connectivity.
    grid: Option<Grid>,
    /// Threads K u may use (bands of node rows; the result does not depend on it).
    threads: usize,
}

impl Elastodynamic {
    /// Mass and element matrices of `mesh` (QUA4 only) with `material` at `density`.
    pub fn new(mesh: &Mesh, material: Material, density: f64) -> Result<Self> {
        if !(density.is_finite() && density > 0.0) {
            return Err(Error::input(
                "block.density (kg/m^3, --density)",
                format!("{density} must be a positive number"),
            ));
        }
        if let Some(k) = mesh.kinds_present().into_iter().find(|&k| k != ElementKind::Qua4) {
            return Err(Error::input(
                "mesh.element (--element)",
                format!(
                    "the dynamic solver takes qua4 elements (full 2x2 integration) only for now; this mesh has {} \
                     elements: use --element qua4 or a Gmsh mesh of 4-node quadrangles",
                    k.name()
                ),
            ));
        }
        let d = material.d_matrix();
        let rule = stiffness_rule(ElementKind::Qua4);
        let ne = mesh.n_elements();
        let (mut conn, mut kmats, mut kidx) = (Vec::with_capacity(ne), Vec::new(), Vec::with_capacity(ne));
        let mut emass: Vec<[f64; 4]> = Vec::new();
        let mut mass = vec![0.0; mesh.n_nodes()];
        let mut seen: HashMap<[i64; 6], u32> = HashMap::new();
        for e in 0..ne {
            let nodes = mesh.element_nodes(e);
            let x: Vec<[f64; 2]> = nodes.iter().map(|&n| mesh.nodes[n]).collect();
            // Row-sum mass: m_a = rho int N_a dA (the rows of the consistent mass summed).
            let mut me = [0.0; 4];
            for q in rule {
                let p = map_point(ElementKind::Qua4, &x, q.xi);
                for a in 0..4 {
                    me[a] += density * q.w * p.det_j * p.n[a];
                }
            }
            // Elements equal up to a translation share one matrix (to 1e-12 of their size).
            let scale = (x[2][0] - x[0][0]).abs().max((x[2][1] - x[0][1]).abs());
            let key: [i64; 6] = std::array::from_fn(|i| {
                let (a, c) = (1 + i / 2, i % 2);
                ((x[a][c] - x[0][c]) / scale * 1e12).round() as i64
            });
            let id = match seen.get(&key) {
                Some(&id) => id,
                None => {
                    let mut k = [0.0; 64];
                    let min_det = stiffness(ElementKind::Qua4, &x, &d, &mut k);
                    if !(min_det > 0.0) {
                        return Err(Error::Mesh(format!(
                            "{} has a Jacobian determinant {min_det:.3e} <= 0",
                            mesh.describe_element(e)
                        )));
                    }
                    // Exactly symmetric, so apply_k may read rows as columns.
                    for i in 0..8 {
                        for j in 0..i {
                            let m = 0.5 * (k[8 * i + j] + k[8 * j + i]);
                            k[8 * i + j] = m;
                            k[8 * j + i] = m;
                        }
                    }
                    kmats.push(k);
                    emass.push(me);
                    let id = (kmats.len() - 1) as u32;
                    seen.insert(key, id);
                    id
                }
            };
            for a in 0..4 {
                mass[nodes[a]] += me[a];
            }
            conn.push(std::array::from_fn(|a| nodes[a] as u32));
            kidx.push(id);
        }
        if let Some(n) = mass.iter().position(|&m| !(m > 0.0)) {
            return Err(Error::Mesh(format!("node {} belongs to no element (zero mass)", mesh.node_tag(n))));
        }
        let lambda_bound =
            kmats.iter().zip(&emass).map(|(k, m)| element_lambda_max(k, m)).fold(0.0, f64::max);
        let grid = Grid::detect(&conn, mesh.n_nodes(), &kmats);
        // The rayon pool's size (RAYON_NUM_THREADS, or a host's pool): one thread setting.
        let threads = rayon::current_num_threads();
        Ok(Self {
            n_nodes: mesh.n_nodes(),
            conn,
            kmats,
            kidx,
            mass,
            lambda_bound,
            material,
            density,
            grid,
            threads,
        })
    }

    pub fn n_nodes(&self) -> usize {
        self.n_nodes
    }
    pub fn n_dofs(&self) -> usize {
        2 * self.n_nodes
    }
    /// Distinct element matrices held (1 on a regular mesh).
    pub fn n_element_matrices(&self) -> usize {
        self.kmats.len()
    }

    /// Whether K u runs as a stencil on a regular grid (no connectivity read) rather than
    /// element by element.
    pub fn is_grid(&self) -> bool {
        self.grid.is_some()
    }

    /// Threads K u may use (default: the current rayon pool's, i.e. RAYON_NUM_THREADS or the
    /// machine's; the results are the same bits for any).
    pub fn threads(&self) -> usize {
        self.threads
    }

    /// Sets the threads K u may use (at least 1). Only the grid path uses more than one, and
    /// only on meshes big enough to pay for them; every node's sum is the same expression for
    /// any count, so results do not depend on it.
    pub fn set_threads(&mut self, threads: usize) {
        self.threads = threads.max(1);
    }

    /// out = K u (out overwritten; DOF order u0, v0, u1, v1, ...).
    pub fn apply_k(&self, u: &[f64], out: &mut [f64]) {
        assert!(u.len() == self.n_dofs() && out.len() == self.n_dofs(), "one value per DOF");
        match &self.grid {
            Some(g) => g.apply(u, out, self.threads),
            None => self.apply_k_by_elements(u, out),
        }
    }

    /// out = K u element by element (gather, 8x8 product, scatter), whatever the mesh: the
    /// general path, and the reference the grid stencil is tested against.
    pub fn apply_k_by_elements(&self, u: &[f64], out: &mut [f64]) {
        // Node-wise views: one bounds check per node instead of per DOF.
        let (u2, _) = u.as_chunks::<2>();
        let (o2, _) = out.as_chunks_mut::<2>();
        o2.fill([0.0; 2]);
        for (c, &id) in self.conn.iter().zip(&self.kidx) {
            let k = &self.kmats[id as usize];
            let n = [c[0] as usize, c[1] as usize, c[2] as usize, c[3] as usize];
            let mut ue = [0.0; 8];
            for a in 0..4 {
                let p = u2[n[a]];
                ue[2 * a] = p[0];
                ue[2 * a + 1] = p[1];
            }
            // K symmetric: column j of K is row j, so f = sum_j K[j, :] ue[j] vectorises.
            let mut fe = [0.0; 8];
            for j in 0..8 {
                let row: &[f64; 8] = k[8 * j..8 * j + 8].try_into().expect("8 columns");
                for i in 0..8 {
                    fe[i] += row[i] * ue[j];
                }
            }
            for a in 0..4 {
                let o = &mut o2[n[a]];
                o[0] += fe[2 * a];
                o[1] += fe[2 * a + 1];
            }
        }
    }

    /// Strain energy 0.5 u^T K u, J per metre of width.
    pub fn strain_energy(&self, u: &[f64]) -> f64 {
        let mut ku = vec![0.0; u.len()];
        self.apply_k(u, &mut ku);
        0.5 * dot(u, &ku)
    }

    /// Kinetic energy 0.5 v^T M v, J per metre of width.
    pub fn kinetic_energy(&self, v: &[f64]) -> f64 {
        0.5 * (0..self.n_nodes)
            .map(|n| self.mass[n] * (v[2 * n] * v[2 * n] + v[2 * n + 1] * v[2 * n + 1]))
            .sum::<f64>()
    }

    /// Estimate of the largest eigenvalue of M^-1 K (free body) by `iters` power iterations
    /// from a fixed pseudo-random start; a lower bound that rises towards the true value.
    pub fn power_iteration(&self, iters: usize) -> f64 {
        let n = self.n_dofs();
        let mut seed = 0x9E37_79B9_7F4A_7C15u64;
        let mut x: Vec<f64> = (0..n)
            .map(|_| {
                seed ^= seed << 13;
                seed ^= seed >> 7;
                seed ^= seed << 17;
                (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
            })
            .collect();
        let mut kx = vec![0.0; n];
        let mut lambda = 0.0;
        for _ in 0..iters {
            self.apply_k(&x, &mut kx);
            let xmx: f64 = (0..n).map(|i| self.mass[i / 2] * x[i] * x[i]).sum();
            lambda = dot(&x, &kx) / xmx;
            let mut norm = 0.0;
            for i in 0..n {
                x[i] = kx[i] / self.mass[i / 2];
                norm += x[i] * x[i];
            }
            let s = 1.0 / norm.sqrt();
            x.iter_mut().for_each(|v| *v *= s);
        }
        lambda
    }

    /// Stable step of the scheme with damping `eta` (s) for the bound [`Self::lambda_bound`]:
    /// dt_c = (2 / omega) (sqrt(1 + xi^2) - xi), omega = sqrt(lambda), xi = eta omega / 2
    /// (from the characteristic equation of the lagged-damping recurrence; 2 / omega undamped).
    pub fn critical_dt(&self, eta: f64) -> f64 {
        critical_dt(self.lambda_bound, eta)
    }
}

/// See [`Elastodynamic::critical_dt`].
pub fn critical_dt(lambda_max: f64, eta: f64) -> f64 {
    let omega = lambda_max.sqrt();
    let xi = 0.5 * eta * omega;
    // sqrt(1 + xi^2) - xi written as 1 / (sqrt(1 + xi^2) + xi): the difference cancels to 0
    // above xi ~ 1e8 and xi^2 overflows to inf (dt_c = inf: an undamped run) above 1e154.
    2.0 / omega / (xi.hypot(1.0) + xi)
}

/// Smallest time step accepted, as a fraction of the stable one (`--courant`): below, the
/// steps grow as 1/courant and buy nothing, the time error (order dt^2) being already far
/// below the mesh's at the defaults.
pub const MIN_COURANT: f64 = 0.01;

/// The largest damping eta (s) whose stable step [`critical_dt`] is still `dt`, for the bound
/// `lambda_max`: dt_c(eta) = dt solved for eta, (1 - a^2) / (a omega) with a = dt omega / 2;
/// 0 when dt is above the undamped step.
pub fn largest_damping(lambda_max: f64, dt: f64) -> f64 {
    let omega = lambda_max.sqrt();
    let a = 0.5 * dt * omega;
    ((1.0 - a * a) / (a * omega)).max(0.0)
}

/// Largest eigenvalue of Me^-1 Ke (Me diagonal): of the symmetric Me^-1/2 Ke Me^-1/2.
fn element_lambda_max(k: &[f64; 64], m: &[f64; 4]) -> f64 {
    let s: [f64; 8] = std::array::from_fn(|i| 1.0 / m[i / 2].sqrt());
    let a = SMatrix::<f64, 8, 8>::from_fn(|i, j| s[i] * k[8 * i + j] * s[j]);
    a.symmetric_eigenvalues().max()
}

pub(crate) fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Energies of an explicit run, J per metre of width. The `*_half` fields are the scheme's
/// exactly conserved "shadow" energy and the work/dissipation that match it; the others are
/// the physical energies at the integer step, which differ from it by O(dt^2).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Ledger {
    /// E^{n-1/2} = 0.5 v^{n-1/2} M v^{n-1/2} + 0.5 u^{n-1} K u^n for the last step n (plus
    /// the kinetic energy a [`Boundary`] holds outside the mesh).
    pub shadow_half: f64,
    /// Its kinetic part (the rest is the strain part 0.5 u^{n-1} K u^n).
    pub kinetic_half: f64,
    /// Work of the external forces and damping dissipation through step n - 1 (the sums of
    /// dt vbar^k . f_ext^k and dt vbar^k . eta K v^{k-1/2}, vbar^k = (v^{k-1/2} + v^{k+1/2}) / 2):
    /// shadow_half + damping_half - work_half is the same at every step, to round-off.
    pub work_half: f64,
    pub damping_half: f64,
    /// Net work the boundary hooks put in through step n - 1 (their forces' work less what
    /// they dissipate, as each reports it).
    pub boundary_half: f64,
    /// The same sums through step n (to set against the physical energies at step n + 1/2).
    pub work: f64,
    pub damping: f64,
    pub boundary: f64,
    /// Physical energies at step n: 0.5 vbar M vbar and 0.5 u^n K u^n.
    pub kinetic: f64,
    pub strain: f64,
    /// (dt^2 / 8) a^n M a^n (a the step's acceleration): undamped and unforced,
    /// kinetic + strain - correction equals the shadow energy exactly.
    pub correction: f64,
}

/// What the fused update of a node row reads besides its row slices.
struct RowCtx<'a> {
    row_len: usize,
    dt: f64,
    eta: f64,
    fixed: &'a [bool],
    mass: &'a [f64],
    u: &'a [f64],
    /// Per DOF: updated by the boundary (empty without one).
    owned: &'a [bool],
}

/// The update of node row j (see [`Explicit::step_grid`]): un holds u^{n-1} and receives
/// u^{n+1}, vout receives v^{n+1/2} (and holds v^{n-1/2} unless DAMPED, when that is read
/// from `vin`), fe is read and zeroed. Per DOF the arithmetic of the general path; the sums
/// run in two lanes (x and y DOFs) added at the row's end, so no sum waits on the one before.
/// Without FULL the physical energies at step n (strain, kinetic, correction) are not summed:
/// a run that reads only the conserved ledger saves three of the seven sums; without HALF
/// neither are the energies at the half step (kinetic, u^{n-1} K u^n). Without EXT there
/// are no external forces: fe is neither read nor zeroed (it stays zero). HOOKED: the row holds
/// boundary nodes; their DOFs add only their share of the sums over v^{n-1/2} and u^n (the
/// rest is added after the boundary ran), keep K u in `kus` and K v in `kvs`, and are left
/// for the boundary (v^{n-1/2} in `vout` unless DAMPED, their fe unread).
#[inline(always)]
fn update_row<const DAMPED: bool, const HALF: bool, const FULL: bool, const EXT: bool, const HOOKED: bool>(
    c: &RowCtx,
    j: usize,
    ku: &[f64],
    kv: &[f64],
    vin: &[f64],
    [un, fe, vout]: [&mut [f64]; 3],
    [kus, kvs]: [&mut [f64]; 2],
) -> RowSums {
    let (dt, eta, i0) = (c.dt, c.eta, j * c.row_len);
    let mut l = [[0.0f64; 2]; 7];
    for node in 0..c.row_len / 2 {
        let mi = c.mass[i0 / 2 + node];
        // One division per node, not two per DOF (divisions were most of the update's time).
        let inv = 1.0 / mi;
        for a in 0..2 {
            let (k, i) = (2 * node + a, i0 + 2 * node + a);
            let vm = if DAMPED { vin[i] } else { vout[k] };
            if HALF {
                l[0][a] += mi * vm * vm;
                l[1][a] += un[k] * ku[k];
            }
            if HOOKED && c.owned[i] {
                if FULL {
                    l[2][a] += c.u[i] * ku[k];
                }
                kus[k] = ku[k];
                if DAMPED {
                    kvs[k] = kv[k];
                }
                continue;
            }
            let fd = if DAMPED { eta * kv[k] } else { 0.0 };
            // Without external forces f = 0 - K u - fd: the same bits as with fe = 0.
            let f = if EXT { fe[k] } else { 0.0 } - ku[k] - fd;
            let fixed = c.fixed[i];
            let vp = if fixed { 0.0 } else { vm + dt * f * inv };
            let vbar = 0.5 * (vm + vp);
            if EXT {
                l[3][a] += dt * vbar * fe[k];
            }
            // Undamped, fd = 0 adds nothing; skipping it saves a multiply-add per DOF.
            if DAMPED {
                l[4][a] += dt * vbar * fd;
            }
            if FULL {
                l[2][a] += c.u[i] * ku[k];
                l[5][a] += 0.5 * mi * vbar * vbar;
                l[6][a] += if fixed { 0.0 } else { dt * dt / 8.0 * f * f * inv };
            }
            vout[k] = vp;
            un[k] = c.u[i] + dt * vp;
            if EXT {
                fe[k] = 0.0;
            }
        }
    }
    let s = l.map(|p| p[0] + p[1]);
    RowSums { kin_old: s[0], shadow: s[1], strain: s[2], work: s[3], damp: s[4], kin: s[5], corr: s[6] }
}

/// One node row's share of the ledger sums of a grid step.
#[derive(Debug, Clone, Copy, Default)]
struct RowSums {
    kin_old: f64,
    shadow: f64,
    strain: f64,
    work: f64,
    damp: f64,
    kin: f64,
    corr: f64,
}

impl RowSums {
    fn add(self, o: &RowSums) -> RowSums {
        RowSums {
            kin_old: self.kin_old + o.kin_old,
            shadow: self.shadow + o.shadow,
            strain: self.strain + o.strain,
            work: self.work + o.work,
            damp: self.damp + o.damp,
            kin: self.kin + o.kin,
            corr: self.corr + o.corr,
        }
    }
}

/// A boundary condition of the one explicit stepper ([`Explicit::step_with`]): called once
/// per step between the predictor (K u^n and K v^{n-1/2} known) and the update, it updates
/// its own nodes' DOFs (the stepper leaves them alone) and reports the net work it put in.
/// The frictional base (rigid flat or symmetric fault), the rigid plate with its drive, or
/// any edge condition is one; the ledger's boundary term is the sum of what they report.
pub trait Boundary {
    /// The nodes it updates, each once (fixed for the run).
    fn nodes(&self) -> &[usize];
    /// Kinetic energy it holds outside the mesh (a rigid plate's own mass) at the half step
    /// n - 1/2, J/m (read before [`Self::apply`]).
    fn own_kinetic(&self) -> f64 {
        0.0
    }
    /// Writes v^{n+1/2} into `s.v` (which holds v^{n-1/2} at its nodes) and u^{n+1} into
    /// `s.u_next` for its nodes; returns the net work it put in over the step (its forces'
    /// work less its dissipation), J/m.
    fn apply(&mut self, s: BoundaryStep<'_>) -> f64;
}

/// What a [`Boundary`] reads and writes in one step (whole-mesh DOF arrays, DOF order u0, v0,
/// u1, ...; only its own nodes' entries of `v` and `u_next` are its to write).
pub struct BoundaryStep<'s> {
    /// The step number n (time n dt), the step and the damping.
    pub n: usize,
    pub dt: f64,
    pub eta: f64,
    pub mass: &'s [f64],
    /// K u^n, and K v^{n-1/2} (read only when eta > 0), at its nodes.
    pub ku: &'s [f64],
    pub kv: &'s [f64],
    /// External forces at t = n dt.
    pub fe: &'s [f64],
    /// u^n.
    pub u: &'s [f64],
    pub v: &'s mut [f64],
    pub u_next: &'s mut [f64],
}

impl BoundaryStep<'_> {
    /// The mesh's force on DOF i at this step: f_ext - K (u^n + eta v^{n-1/2}).
    #[inline]
    pub fn force(&self, i: usize) -> f64 {
        self.fe[i] - self.ku[i] - if self.eta > 0.0 { self.eta * self.kv[i] } else { 0.0 }
    }
}

/// No boundary hook ([`Explicit::step`]).
struct Free;

impl Boundary for Free {
    fn nodes(&self) -> &[usize] {
        &[]
    }
    fn apply(&mut self, _: BoundaryStep<'_>) -> f64 {
        0.0
    }
}

/// A running explicit integration: displacements at step n, velocities at n - 1/2. The one
/// central-difference loop of the crate: every dynamic command steps through it, its
/// boundary conditions as [`Boundary`] hooks.
pub struct Explicit<'a> {
    pub model: &'a Elastodynamic,
    pub dt: f64,
    /// Kelvin-Voigt coefficient, s.
    pub eta: f64,
    /// DOFs held at zero displacement and velocity.
    pub fixed: Vec<bool>,
    pub u: Vec<f64>,
    /// v^{n-1/2}.
    pub v: Vec<f64>,
    /// Steps taken (the current time is `n dt`).
    pub n: usize,
    pub ledger: Ledger,
    u_prev: Vec<f64>,
    ku: Vec<f64>,
    kv: Vec<f64>,
    fe: Vec<f64>,
    /// The boundary's DOFs (sorted), a flag per DOF, and on a grid a flag per node row that
    /// holds one; empty without a boundary.
    hook_dofs: Vec<usize>,
    owned: Vec<bool>,
    hook_rows: Vec<bool>,
    /// K v at the boundary's DOFs on the grid path (whole-mesh array), and v^{n-1/2} there.
    kv_hook: Vec<f64>,
    v_hook: Vec<f64>,
    /// Which energy sums the grid pass makes (default all; see [`Sums`]).
    pub sums: Sums,
}

/// The energy sums a grid step makes: each is a multiply-add per DOF, so a run skips those it
/// never reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Sums {
    /// The running sums only (work, damping, the boundary's net work): a run that takes its
    /// energies from [`Explicit::level`] when it reports them (`rupture`). The ledger's
    /// half-step and step-n energies then mean nothing.
    Running,
    /// Those and the energies at the half step (`kinetic_half`, `shadow_half`): the conserved
    /// ledger every step (the plate-driven events' end test). `strain`, `kinetic` and
    /// `correction` then hold only the boundary's share and mean nothing.
    Ledger,
    /// Every sum, the physical energies at step n too.
    All,
}

impl<'a> Explicit<'a> {
    /// Starts at rest (u = 0, v^{-1/2} = 0) with step `dt`; refuses a step above the stable one.
    pub fn new(model: &'a Elastodynamic, dt: f64, eta: f64, fixed: Vec<bool>) -> Result<Self> {
        if !(eta.is_finite() && eta >= 0.0) {
            return Err(Error::input("damping (s, --damping)", format!("eta = {eta} must be >= 0")));
        }
        let dt_c = model.critical_dt(eta);
        if !(dt > 0.0 && dt <= dt_c) {
            return Err(Error::input(
                "time step (--courant)",
                format!(
                    "dt = {dt:.4e} s is not in (0, {dt_c:.4e}] s, the stable step of this mesh and damping"
                ),
            ));
        }
        Ok(Self::checked_by_caller(model, dt, eta, fixed))
    }

    /// [`Self::new`] for a caller that has checked dt and eta itself (with the flags to name).
    pub(crate) fn checked_by_caller(model: &'a Elastodynamic, dt: f64, eta: f64, fixed: Vec<bool>) -> Self {
        let n = model.n_dofs();
        assert_eq!(fixed.len(), n, "one flag per DOF");
        Self {
            model,
            dt,
            eta,
            fixed,
            u: vec![0.0; n],
            v: vec![0.0; n],
            n: 0,
            ledger: Ledger::default(),
            u_prev: vec![0.0; n],
            ku: vec![0.0; n],
            kv: vec![0.0; n],
            fe: vec![0.0; n],
            hook_dofs: vec![],
            owned: vec![],
            hook_rows: vec![],
            kv_hook: vec![],
            v_hook: vec![],
            sums: Sums::All,
        }
    }

    /// The same, with the nodes a [`Boundary`] will update (see [`Self::step_with`]).
    pub fn with_boundary(mut self, nodes: &[usize]) -> Self {
        let n = self.model.n_dofs();
        self.owned = vec![false; n];
        for &k in nodes {
            self.owned[2 * k] = true;
            self.owned[2 * k + 1] = true;
        }
        self.hook_dofs = (0..n).filter(|&i| self.owned[i]).collect();
        if let Some(g) = &self.model.grid {
            let rl = g.row_len();
            self.hook_rows = self.owned.chunks(rl).map(|r| r.iter().any(|&o| o)).collect();
            self.kv_hook = vec![0.0; n];
        }
        self.v_hook = vec![0.0; self.hook_dofs.len()];
        self
    }

    /// Sets the initial displacement (fixed DOFs must be zero) and keeps v^{-1/2}.
    pub fn set_displacement(&mut self, u: &[f64]) {
        self.u.copy_from_slice(u);
        for i in 0..u.len() {
            if self.fixed[i] {
                self.u[i] = 0.0;
            }
            self.u_prev[i] = self.u[i] - self.dt * self.v[i];
        }
    }

    /// Sets u^n and v^{n-1/2} together (u^{n-1} = u^n - dt v^{n-1/2}), e.g. a dynamic event
    /// starting from a static field.
    pub fn set_state(&mut self, u: &[f64], v: &[f64]) {
        self.v.copy_from_slice(v);
        self.set_displacement(u);
    }

    /// u^{n-1}: after a step from level n, the displacements it started from.
    pub fn u_before(&self) -> &[f64] {
        &self.u_prev
    }

    /// The current level n without a step (a run that reads its boundary at the level it ends
    /// on): K u^n and the mesh's shadow energy there, 0.5 v^{n-1/2} M v^{n-1/2} and
    /// 0.5 u^{n-1} K u^n (J/m).
    pub fn level(&mut self) -> (&[f64], f64, f64) {
        self.model.apply_k(&self.u, &mut self.ku);
        let kinetic = self.model.kinetic_energy(&self.v);
        (&self.ku, kinetic, 0.5 * dot(&self.u_prev, &self.ku))
    }

    /// One step; `f_ext(t, f)` adds the external nodal forces at t = n dt into `f` (zeroed).
    pub fn step(&mut self, f_ext: impl FnMut(f64, &mut [f64])) {
        self.step_with(&mut Free, f_ext)
    }

    /// One step with boundary hooks (built with [`Self::with_boundary`] on its nodes).
    pub fn step_with(&mut self, b: &mut dyn Boundary, f_ext: impl FnMut(f64, &mut [f64])) {
        self.step_inner(b, Some(f_ext))
    }

    /// One step with boundary hooks and no external forces (the grid pass then neither reads
    /// nor zeroes them: the commands' path).
    pub fn step_boundary(&mut self, b: &mut dyn Boundary) {
        self.step_inner(b, None::<fn(f64, &mut [f64])>)
    }

    fn step_inner(&mut self, b: &mut dyn Boundary, f_ext: Option<impl FnMut(f64, &mut [f64])>) {
        debug_assert_eq!(b.nodes().len() * 2, self.hook_dofs.len(), "the boundary's nodes");
        let own_kinetic = b.own_kinetic();
        let ext = f_ext.is_some();
        if let Some(g) = &self.model.grid {
            // fe is zero here: new() makes it so and every grid step leaves it so.
            if let Some(mut f) = f_ext {
                f(self.n as f64 * self.dt, &mut self.fe);
            }
            return self.step_grid(g, b, own_kinetic, ext);
        }
        let mut f_ext = f_ext;
        let (m, dt, eta) = (self.model, self.dt, self.eta);
        m.apply_k(&self.u, &mut self.ku);
        if eta > 0.0 {
            m.apply_k(&self.v, &mut self.kv);
        }
        self.fe.fill(0.0);
        if let Some(f) = f_ext.as_mut() {
            f(self.n as f64 * dt, &mut self.fe);
        }
        let (kinetic_half, shadow_half) = if self.sums == Sums::Running {
            (0.0, 0.0)
        } else {
            let kinetic_half = m.kinetic_energy(&self.v) + own_kinetic;
            (kinetic_half, kinetic_half + 0.5 * dot(&self.u_prev, &self.ku))
        };
        let mut s = RowSums::default();
        let hooked = !self.owned.is_empty();
        for i in 0..self.u.len() {
            if hooked && self.owned[i] {
                continue;
            }
            let vm = self.v[i];
            let fd = if eta > 0.0 { eta * self.kv[i] } else { 0.0 };
            let f = self.fe[i] - self.ku[i] - fd;
            let mi = m.mass[i / 2];
            // As the grid path: the inverse mass, then products (the same bits).
            let inv = 1.0 / mi;
            let vp = if self.fixed[i] { 0.0 } else { vm + dt * f * inv };
            let vbar = 0.5 * (vm + vp);
            s.work += dt * vbar * self.fe[i];
            s.damp += dt * vbar * fd;
            s.kin += 0.5 * mi * vbar * vbar;
            if !self.fixed[i] {
                s.corr += dt * dt / 8.0 * f * f * inv;
            }
            self.v[i] = vp;
            self.u_prev[i] = self.u[i] + dt * vp;
        }
        let strain = 0.5 * dot(&self.u, &self.ku);
        let boundary = self.apply_boundary(b, &mut s, false);
        std::mem::swap(&mut self.u, &mut self.u_prev);
        self.close_step(s, shadow_half, kinetic_half, strain, boundary);
    }

    /// The boundary's update (after every other DOF's) and its DOFs' ledger terms; on the
    /// grid path K v there was kept in `kv_hook`.
    fn apply_boundary(&mut self, b: &mut dyn Boundary, s: &mut RowSums, grid: bool) -> f64 {
        if self.hook_dofs.is_empty() {
            return 0.0;
        }
        let (m, dt, eta) = (self.model, self.dt, self.eta);
        let damped = eta > 0.0;
        // v^{n+1/2} lands where the step keeps it: in place, or kv's array on a damped grid.
        let into_kv = grid && damped;
        for (j, &i) in self.hook_dofs.iter().enumerate() {
            self.v_hook[j] = self.v[i];
            if into_kv {
                self.kv[i] = self.v[i];
            }
        }
        let Self { kv: kv_all, kv_hook, v: v_all, ku, fe, u, u_prev, n, .. } = self;
        let (kv, v): (&[f64], &mut [f64]) = match (grid, into_kv) {
            (true, true) => (kv_hook, kv_all),
            (true, false) => (kv_hook, v_all),
            _ => (kv_all, v_all),
        };
        let net = b.apply(BoundaryStep { n: *n, dt, eta, mass: &m.mass, ku, kv, fe, u, v, u_next: u_prev });
        let kv: &[f64] = if grid { &self.kv_hook } else { &self.kv };
        let vnew: &[f64] = if into_kv { &self.kv } else { &self.v };
        for (j, &i) in self.hook_dofs.iter().enumerate() {
            let (vm, vp, mi) = (self.v_hook[j], vnew[i], m.mass[i / 2]);
            let fd = if damped { eta * kv[i] } else { 0.0 };
            let vbar = 0.5 * (vm + vp);
            s.work += dt * vbar * self.fe[i];
            s.damp += dt * vbar * fd;
            s.kin += 0.5 * mi * vbar * vbar;
            s.corr += 0.125 * mi * (vp - vm) * (vp - vm);
            self.fe[i] = 0.0;
        }
        net
    }

    /// The ledger after a step with sums `s` (work, damping, kinetic, correction).
    fn close_step(&mut self, s: RowSums, shadow_half: f64, kinetic_half: f64, strain: f64, boundary: f64) {
        let l = &mut self.ledger;
        l.shadow_half = shadow_half;
        l.kinetic_half = kinetic_half;
        l.strain = strain;
        l.kinetic = s.kin;
        l.correction = s.corr;
        // shadow_half is E^{n-1/2}: it matches the sums through step n - 1.
        l.work_half = l.work;
        l.damping_half = l.damping;
        l.boundary_half = l.boundary;
        l.work += s.work;
        l.damping += s.damp;
        l.boundary += boundary;
        self.n += 1;
    }

    /// The step on a regular grid in one pass over the node rows (see [`Grid::sweep`]): each
    /// row's K u (and K v) is computed into a row buffer and used at once, u^{n+1} is written
    /// into u_prev's array after u^{n-1} is read from it (then the two swap), v^{n+1/2} in
    /// place (into kv's array when damped, as K v reads v^{n-1/2} of the next row), f_ext
    /// zeroed as it is read. Same arithmetic per DOF as the general path; the energy sums are
    /// per row, added in row order, so the result is the same for any thread count. A row
    /// holding boundary nodes keeps their K u (in ku's array) and K v for the boundary, which
    /// runs after the pass.
    fn step_grid(&mut self, g: &Grid, b: &mut dyn Boundary, own_kinetic: f64, ext: bool) {
        let eta = self.eta;
        let rows = match (self.sums, ext) {
            (Sums::All, true) => self.sweep::<true, true, true>(g),
            (Sums::All, false) => self.sweep::<true, true, false>(g),
            (Sums::Ledger, true) => self.sweep::<true, false, true>(g),
            (Sums::Ledger, false) => self.sweep::<true, false, false>(g),
            (Sums::Running, true) => self.sweep::<false, false, true>(g),
            (Sums::Running, false) => self.sweep::<false, false, false>(g),
        };
        let mut s = rows.iter().fold(RowSums::default(), |a, b| a.add(b));
        let boundary = self.apply_boundary(b, &mut s, true);
        std::mem::swap(&mut self.u, &mut self.u_prev);
        if eta > 0.0 {
            std::mem::swap(&mut self.v, &mut self.kv);
        }
        let kinetic_half = 0.5 * s.kin_old + own_kinetic;
        self.close_step(s, kinetic_half + 0.5 * s.shadow, kinetic_half, 0.5 * s.strain, boundary);
    }

    /// The pass of [`Self::step_grid`] over the node rows; HALF, FULL: see [`update_row`].
    fn sweep<const HALF: bool, const FULL: bool, const EXT: bool>(&mut self, g: &Grid) -> Vec<RowSums> {
        let (m, dt, eta) = (self.model, self.dt, self.eta);
        let row_len = g.row_len();
        let (fixed, mass, u) = (&self.fixed, &m.mass, &self.u);
        let ctx = RowCtx { row_len, dt, eta, fixed, mass, u, owned: &self.owned };
        match (self.hook_dofs.is_empty(), eta > 0.0) {
            (true, true) => {
                let v = &self.v;
                g.sweep(
                    u,
                    Some(v),
                    [&mut self.u_prev, &mut self.fe, &mut self.kv],
                    m.threads,
                    |j, ku, kv, o| {
                        update_row::<true, HALF, FULL, EXT, false>(&ctx, j, ku, kv, v, o, [&mut [], &mut []])
                    },
                )
            }
            (true, false) => {
                g.sweep(u, None, [&mut self.u_prev, &mut self.fe, &mut self.v], m.threads, |j, ku, kv, o| {
                    update_row::<false, HALF, FULL, EXT, false>(&ctx, j, ku, kv, &[], o, [&mut [], &mut []])
                })
            }
            (false, damped) => {
                let hook_rows = &self.hook_rows;
                let v = &self.v;
                let (vout, vin): (&mut [f64], &[f64]) =
                    if damped { (&mut self.kv, v) } else { (&mut self.v, &[]) };
                let outs = [&mut self.u_prev[..], &mut self.fe, vout, &mut self.ku, &mut self.kv_hook];
                g.sweep(u, damped.then_some(vin), outs, m.threads, |j, ku, kv, [un, fe, vo, kus, kvs]| {
                    let (o, st) = ([un, fe, vo], [kus, kvs]);
                    match (hook_rows[j], damped) {
                        (false, true) => {
                            update_row::<true, HALF, FULL, EXT, false>(&ctx, j, ku, kv, vin, o, st)
                        }
                        (false, false) => {
                            update_row::<false, HALF, FULL, EXT, false>(&ctx, j, ku, kv, &[], o, st)
                        }
                        (true, true) => {
                            update_row::<true, HALF, FULL, EXT, true>(&ctx, j, ku, kv, vin, o, st)
                        }
                        (true, false) => {
                            update_row::<false, HALF, FULL, EXT, true>(&ctx, j, ku, kv, &[], o, st)
                        }
                    }
                })
            }
        }
    }

    /// E^{n-1/2} + D - W - B (sums through step n - 1) as of the last step: constant to
    /// round-off.
    pub fn shadow_balance(&self) -> f64 {
        let l = &self.ledger;
        l.shadow_half + l.damping_half - l.work_half - l.boundary_half
    }
}

#[cfg(test)]
mod tests;
