//! The linear static pipeline in order: reduce the constraints, build the pattern, assemble,
//! analyse, factorise, solve all load cases at once, expand to full displacements.
//! Each phase is timed so benchmarks and convergence runs can report where time goes.

use crate::error::{Error, Result};
use crate::fem::assembly::{Assembler, Model};
use crate::fem::constraints::{Constraints, Reduction};
use crate::fem::ordering::{bisection, nested_dissection};
use crate::fem::recovery::internal_forces;
use crate::linalg::solve::{Ordering, SolveReport, Solver, SolverOptions};
use std::sync::Arc;
use std::time::Instant;

/// One load case: the prescribed values (one per fixed DOF, in `Constraints::fix` order) and
/// external nodal forces (full length, or empty for none), N.
#[derive(Debug, Clone, Default)]
pub struct LoadCase {
    pub prescribed: Vec<f64>,
    pub forces: Vec<f64>,
}

/// Unknowns from which `Ordering::Auto` solves grids as two domains instead of with AMD: from
/// ~1e4 on it is faster (1.3x at 3.6e4, 2x at 9.6e4, validation/bench); below, equal.
pub const TWO_DOMAINS_FROM: usize = 10_000;

/// Wall time of each phase, s.
#[derive(Debug, Clone, Copy, Default)]
pub struct Timings {
    /// Mesh and constraints construction (set by callers that build them, e.g. `check::run`).
    pub mesh: f64,
    /// Constraint reduction, sparsity pattern and element colouring.
    pub pattern: f64,
    pub assembly: f64,
    pub symbolic: f64,
    pub numeric: f64,
    /// All load cases, the condition probe and the residual check with refinement.
    pub solve: f64,
    /// Post-processing (e.g. interface tractions; set by callers).
    pub recovery: f64,
    /// The rest of the run's wall time, outside the phases above (e.g. freeing memory).
    pub other: f64,
}

impl Timings {
    /// The run's wall time.
    pub fn total(&self) -> f64 {
        self.phases() + self.other
    }

    fn phases(&self) -> f64 {
        self.mesh + self.pattern + self.assembly + self.symbolic + self.numeric + self.solve + self.recovery
    }

    /// Sets `other` so that the total is `wall` (s).
    pub fn set_wall(&mut self, wall: f64) {
        self.other = (wall - self.phases()).max(0.0);
    }
}

#[derive(Debug, Clone)]
pub struct Solution {
    /// Shared with the [`Prepared`] it came from (a copy would be 40 MB at 1e6 DOFs).
    pub reduction: Arc<Reduction>,
    /// Full displacement per case (node DOFs then extra DOFs), m (rad for rotations).
    pub u: Vec<Vec<f64>>,
    /// Sizes, accuracy and timings of the solve (shared by every result that reports them).
    pub stats: SolverStats,
}

/// What a solve cost and how accurate it was: sizes, accuracy report and phase times.
#[derive(Debug, Clone)]
pub struct SolverStats {
    pub report: SolveReport,
    pub timings: Timings,
    pub n_unknowns: usize,
    pub matrix_nnz: usize,
    pub factor_nnz: usize,
    pub factor_flops: f64,
    /// Core-seconds of the numeric factorisation spent in dense kernels, when known.
    pub dense_seconds: Option<f64>,
    pub supernodal: bool,
}

/// Solves every load case with one factorisation. `hint` is appended to the error when
/// the residual check rejects the answer (e.g. suggest a better-conditioned model).
pub fn solve(
    model: &Model,
    constraints: &Constraints,
    cases: &[LoadCase],
    opts: &SolverOptions,
    hint: &str,
) -> Result<Solution> {
    let clock = Instant::now();
    let prepared = Prepared::new(model.mesh, constraints, opts)?;
    let mut sol = prepared.solve(model, constraints, cases, opts, hint)?;
    sol.stats.timings.pattern = prepared.pattern_time;
    sol.stats.timings.symbolic = prepared.symbolic_time;
    let bytes = prepared.asm.pattern.nnz() * std::mem::size_of::<usize>();
    crate::memory::drop_in_background(prepared, bytes);
    sol.stats.timings.set_wall(clock.elapsed().as_secs_f64());
    Ok(sol)
}

/// What a solve needs that depends only on the mesh and the structure of the constraints: the
/// reduction, the sparsity pattern with its element colouring, and the symbolic Cholesky
/// analysis (ordering included). Built once, it serves any materials, prescribed values and
/// loads on that mesh (parameter sweeps): [`Prepared::solve`] only assembles, factorises and
/// solves, and reports zero pattern and symbolic time.
pub struct Prepared {
    red: Arc<Reduction>,
    asm: Assembler,
    solver: Solver,
    /// Time spent building the pattern and in the ordering + symbolic analysis, s.
    pub pattern_time: f64,
    pub symbolic_time: f64,
}

impl Prepared {
    pub fn new(
        mesh: &crate::fem::mesh::Mesh,
        constraints: &Constraints,
        opts: &SolverOptions,
    ) -> Result<Self> {
        let clock = Instant::now();
        let red = constraints.reduce()?;
        let mut options = opts.clone();
        // Nested dissection's first cut solved as two domains uses both cores. The grid
        // bisection needs only the mesh, so it runs alongside the pattern build (and is
        // timed with it).
        let two_domains = options.ordering == Ordering::Auto && red.n_free() >= TWO_DOMAINS_FROM;
        let (asm, split) = rayon::join(
            || Assembler::new(mesh, &red),
            || if two_domains { bisection(mesh, &red) } else { None },
        );
        let asm = asm?;
        let pattern_time = clock.elapsed().as_secs_f64();
        let clock = Instant::now();
        if let Some(split) = split {
            options.ordering = Ordering::TwoDomain(split);
        } else if options.ordering == Ordering::NestedDissection {
            if let Some(p) = nested_dissection(mesh, &red) {
                options.ordering = Ordering::Custom(p);
            }
        }
        let solver = Solver::analyse(&asm.pattern, options)?;
        Ok(Self {
            red: Arc::new(red),
            asm,
            solver,
            pattern_time,
            symbolic_time: clock.elapsed().as_secs_f64(),
        })
    }

    /// Assembles `model` (same mesh and constraint structure as at [`Prepared::new`]),
    /// factorises, and solves every load case, with the checks of [`solve`]; the accuracy
    /// limits come from `opts`.
    pub fn solve(
        &self,
        model: &Model,
        constraints: &Constraints,
        cases: &[LoadCase],
        opts: &SolverOptions,
        hint: &str,
    ) -> Result<Solution> {
        let (red, asm, solver) = (&*self.red, &self.asm, &self.solver);
        let mut t = Timings::default();
        let clock = Instant::now();
        let prescribed: Vec<Vec<f64>> = cases.iter().map(|c| c.prescribed.clone()).collect();
        let loads: Vec<Vec<f64>> = cases.iter().map(|c| c.forces.clone()).collect();
        if let Some(bad) = loads.iter().find(|f| !f.is_empty() && f.len() != red.n_full) {
            return Err(Error::input(
                "load case",
                format!("force vector has {} entries, the model has {} DOFs", bad.len(), red.n_full),
            ));
        }
        let (values, rhs) = asm.assemble(model, red, &loads, &prescribed)?;
        t.assembly = clock.elapsed().as_secs_f64();

        let clock = Instant::now();
        let factor = solver
            .factorize(&asm.pattern, &values)
            .map_err(|e| singular(model, constraints, red, e.unknown))?;
        t.numeric = clock.elapsed().as_secs_f64();

        let clock = Instant::now();
        let n = red.n_free();
        let nc = cases.len();
        // One extra column, a fixed pseudo-random probe b, rides along in the same solve: the
        // size of K^-1 b bounds the condition number from below, and for a singular K it is
        // dominated by the free rigid-body motion, which we can then name.
        let mut x = Vec::with_capacity((nc + 1) * n);
        x.extend_from_slice(&rhs);
        x.extend(probe_vector(n));
        factor.solve_in_place(&mut x, nc + 1);
        let condition =
            norm_1_sym(&asm.pattern, &values) * x[nc * n..].iter().fold(0.0f64, |m, v| m.max(v.abs()));
        if !(condition < 1e15) {
            let g0 = vec![0.0; red.n_fixed()];
            let mode = red.expand(&x[nc * n..], &g0);
            if let Some(what) = rigid_mode(model, &mode) {
                return Err(Error::Singular { detail: format!("the solution contains an unresisted {what} (condition estimate {condition:.1e}); prescribe enough displacements to stop both translations and the rotation of every separate body"), node: None, component: None });
            }
        }
        let expected = condition * f64::EPSILON;
        if !(expected <= opts.max_error_estimate) {
            let detail = format!(
                "the stiffness matrix is ill-conditioned (condition estimate {condition:.1e}): about {:.0} of 16 digits are lost, so results can be wrong by {expected:.1e} relative (limit {:.1e})",
                condition.log10(),
                opts.max_error_estimate
            );
            return Err(Error::Untrustworthy { detail, hint: hint.to_string() });
        }
        x.truncate(nc * n);
        let (x, mut report) = factor.check_and_refine(&asm.pattern, &values, &rhs, x, nc, opts, hint)?;
        report.condition_estimate = condition;
        let u = cases
            .iter()
            .enumerate()
            .map(|(c, case)| red.expand(&x[c * n..(c + 1) * n], &case.prescribed))
            .collect();
        t.solve = clock.elapsed().as_secs_f64();
        let bytes = values.len() * std::mem::size_of::<f64>();
        crate::memory::drop_in_background(values, bytes);
        Ok(Solution {
            reduction: Arc::clone(&self.red),
            u,
            stats: SolverStats {
                report,
                timings: t,
                n_unknowns: n,
                matrix_nnz: asm.pattern.nnz(),
                factor_nnz: solver.factor_nnz(),
                factor_flops: solver.factor_flops(),
                dense_seconds: factor.dense_seconds(),
                supernodal: solver.is_supernodal(),
            },
        })
    }
}

/// Deterministic values in [-1, 1] (a linear congruential sequence), the same every run.
fn probe_vector(n: usize) -> impl Iterator<Item = f64> {
    let mut s: u64 = 0x9E37_79B9_7F4A_7C15;
    (0..n).map(move |_| {
        s = s.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
        (s >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    })
}

/// max_j sum_i |K_ij| (= the infinity norm) of the symmetric matrix stored by its lower triangle.
fn norm_1_sym(p: &crate::fem::assembly::Pattern, values: &[f64]) -> f64 {
    let mut col = vec![0.0; p.n];
    for j in 0..p.n {
        for k in p.col(j) {
            let i = p.row_idx[k] as usize;
            col[j] += values[k].abs();
            if i != j {
                col[i] += values[k].abs();
            }
        }
    }
    col.into_iter().fold(0.0, f64::max)
}

/// If the nodal field is (to 1 %) a rigid motion u = a - w y, v = b + w x, names its
/// dominant part; otherwise None.
fn rigid_mode(model: &Model, u: &[f64]) -> Option<String> {
    let nodes = &model.mesh.nodes;
    let n = nodes.len() as f64;
    let c = nodes.iter().fold([0.0, 0.0], |a, p| [a[0] + p[0] / n, a[1] + p[1] / n]);
    // Least squares for (a, b, w) about the centroid: the three columns are orthogonal there.
    let (mut su, mut sv, mut sw, mut rr) = (0.0, 0.0, 0.0, 0.0);
    for (k, p) in nodes.iter().enumerate() {
        let (x, y) = (p[0] - c[0], p[1] - c[1]);
        su += u[2 * k];
        sv += u[2 * k + 1];
        sw += -y * u[2 * k] + x * u[2 * k + 1];
        rr += x * x + y * y;
    }
    let (a, b, w) = (su / n, sv / n, if rr > 0.0 { sw / rr } else { 0.0 });
    let (mut res, mut tot) = (0.0, 0.0);
    for (k, p) in nodes.iter().enumerate() {
        let (x, y) = (p[0] - c[0], p[1] - c[1]);
        res += (u[2 * k] - (a - w * y)).powi(2) + (u[2 * k + 1] - (b + w * x)).powi(2);
        tot += u[2 * k].powi(2) + u[2 * k + 1].powi(2);
    }
    if !(tot > 0.0) || res > 1e-4 * tot {
        return None;
    }
    let size = (rr / n).sqrt();
    let parts =
        [(a.abs(), "translation along x"), (b.abs(), "translation along y"), ((w * size).abs(), "rotation")];
    let names: Vec<&str> = parts
        .iter()
        .filter(|(m, _)| *m > 0.05 * parts.iter().fold(0.0f64, |x, p| x.max(p.0)))
        .map(|p| p.1)
        .collect();
    Some(format!("rigid-body motion ({})", names.join(" and ")))
}

fn singular(model: &Model, c: &Constraints, red: &Reduction, k: usize) -> Error {
    let full = red.free_to_full.get(k).copied();
    let which = full.map_or("an unknown".to_string(), |d| c.describe_dof(model.mesh, d));
    let at_node = full.filter(|&d| d < 2 * model.mesh.n_nodes());
    Error::Singular {
        node: at_node.map(|d| model.mesh.node_tag(d / 2)),
        component: at_node.map(|d| d % 2),
        detail: format!(
            "the stiffness matrix is not positive definite (first bad pivot at {which}); prescribe enough displacements to stop both translations and the rotation of every separate body"
        ),
    }
}

impl Solution {
    /// Consistent reactions (K u - f) at every full DOF for case `c`, computed from the given
    /// elements only (pass the elements touching the constrained DOFs of interest).
    pub fn residual_forces(
        &self,
        model: &Model,
        case: &LoadCase,
        c: usize,
        elements: &[usize],
    ) -> Result<Vec<f64>> {
        let mut r = internal_forces(model, &self.u[c], elements)?;
        r.resize(self.reduction.n_full, 0.0);
        if !case.forces.is_empty() {
            r.iter_mut().zip(&case.forces).for_each(|(a, f)| *a -= f);
        }
        Ok(r)
    }
}
