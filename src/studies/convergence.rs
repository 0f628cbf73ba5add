//! Mesh convergence of the paper's check: the scene solved over families of meshes and
//! elements, errors against the most accurate run in three zones that converge differently
//! (the smooth interior, the edge zones, the singular end nodes), observed orders, converged
//! edge-zone widths, and the cost of each run for the accuracy-versus-time chart.

use crate::error::{Error, Result};
use crate::fem::problem::Timings;
use crate::linalg::solve::SolverOptions;
use crate::numeric::{interpolate, line_fit};
use crate::progress::Progress;
use crate::scene::Scene;
use crate::studies::check::{self, CheckResult};
use rayon::prelude::*;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

/// How a family spaces its elements along x (through the thickness both are uniform).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Family {
    /// Square elements of size h everywhere.
    Uniform,
    /// Size h at both ends, growing geometrically towards the middle up to `h_max`: elongated
    /// elements where the fields are smooth.
    Graded,
}

impl Family {
    pub fn name(self) -> &'static str {
        match self {
            Family::Uniform => "uniform",
            Family::Graded => "graded",
        }
    }
}

impl std::str::FromStr for Family {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        match s {
            "uniform" => Ok(Family::Uniform),
            "graded" => Ok(Family::Graded),
            _ => Err(Error::input("mesh family", format!("'{s}' is not known; choose uniform or graded"))),
        }
    }
}

#[derive(Debug, Clone)]
pub struct StudyOptions {
    pub elements: Vec<String>,
    pub families: Vec<Family>,
    /// Elements through the thickness of each run: h = t / n.
    pub n_thick: Vec<usize>,
    /// The load case (F/N) whose profiles are compared.
    pub fn_ratio: f64,
    /// Growth ratio and largest element length (in units of t) of the graded family.
    pub grading_ratio: f64,
    pub graded_h_max_over_t: f64,
    /// Run the meshes concurrently (faster overall; per-run times then share the cores).
    pub parallel: bool,
    /// Checked before each run.
    pub cancel: crate::Cancel,
}

/// The load case (F/N) compared by default (`converge --case`).
pub const DEFAULT_FN_RATIO: f64 = 0.82;

impl Default for StudyOptions {
    fn default() -> Self {
        Self {
            elements: vec!["qua4".into()],
            families: vec![Family::Uniform, Family::Graded],
            n_thick: vec![1, 2, 4, 8, 16, 32, 64],
            fn_ratio: DEFAULT_FN_RATIO,
            grading_ratio: 1.15,
            graded_h_max_over_t: 4.0,
            parallel: true,
            cancel: crate::Cancel::new(),
        }
    }
}

/// Largest |error| in units of N/L, per zone, for pressure and shear.
#[derive(Debug, Clone, Copy, Default)]
pub struct ZoneErrors {
    pub interior: [f64; 2],
    pub edge: [f64; 2],
    pub end: [f64; 2],
}

#[derive(Debug, Clone)]
pub struct Run {
    pub family: Family,
    pub element: String,
    pub n_thick: usize,
    pub dofs: usize,
    pub n_elements: usize,
    pub timings: Timings,
    /// Whole run in the process (mesh, solve, recovery), s.
    pub wall: f64,
    /// Memory of the Cholesky factor, MiB.
    pub factor_mib: f64,
    /// Peak heap of the run above what was in use before it, MiB (serial studies only: runs in
    /// parallel share the heap).
    pub peak_mib: Option<f64>,
    pub x: Vec<f64>,
    pub p: Vec<f64>,
    pub tau: Vec<f64>,
    pub slope: f64,
    pub tau_center: f64,
    pub p_end: [f64; 2],
    pub tau_end: [f64; 2],
    /// Edge widths in units of t: pressure left/right, shear left/right.
    pub widths: [Option<f64>; 4],
    /// Worst relative error of the global balances (N, F, moment F H).
    pub balance: f64,
    pub errors: ZoneErrors,
}

#[derive(Debug, Clone)]
pub struct Study {
    /// Poisson ratio and t/L of the scene (for the theory the study is compared with).
    pub nu: f64,
    pub t_over_l: f64,
    pub runs: Vec<Run>,
    /// Index of the reference run (most accurate), against which errors are measured.
    pub reference: usize,
    pub skipped: Vec<String>,
    pub theory: Theory,
}

/// The closed forms the study is read against.
#[derive(Debug, Clone)]
pub struct Theory {
    /// Williams' exponent of the clamped-free 90-degree corner (stress ~ r^(lambda - 1)),
    /// the stress singularity exponent 1 - lambda and the end values' growth per halving of h.
    pub lambda: crate::analytical::Complex,
    pub singularity: f64,
    pub growth_per_halving: f64,
    /// Decay rates k of |deviation from the far field| ~ exp(-k d/t) fitted on the reference
    /// (p left, p right, tau left, tau right).
    pub decay_fitted: [Option<f64>; 4],
    /// Slowest decay root s t of the strip clamped on both faces, and the distance (in t) over
    /// which it falls to 5 %: compression class, then shear class.
    pub strip: [(crate::analytical::Complex, f64); 2],
}

impl Theory {
    fn new(nu: f64, reference: &Run, t_over_l: f64) -> Result<Self> {
        use crate::analytical::{strip, williams};
        let lambda = williams::clamped_free_exponent(std::f64::consts::FRAC_PI_2, nu)?;
        let mode = |fam| -> Result<_> {
            Ok((strip::slowest_decay(nu, fam)?, strip::decay_distance_over_t(nu, fam, 0.05)?))
        };
        Ok(Theory {
            lambda,
            singularity: williams::singularity_exponent(lambda),
            growth_per_halving: williams::refinement_growth(lambda),
            decay_fitted: decay_rates(reference, t_over_l, 1e-4),
            strip: [mode(strip::Family::Compression)?, mode(strip::Family::Shear)?],
        })
    }
}

/// The scene variant of one run.
pub fn run_scene(base: &Scene, o: &StudyOptions, family: Family, element: &str, n: usize) -> Scene {
    let mut s = base.clone();
    let t = s.block.thickness;
    s.mesh.h = t / n as f64;
    s.mesh.n_thick = Some(n);
    s.mesh.element = element.to_string();
    s.loading.fn_ratios = vec![o.fn_ratio];
    (s.mesh.grading, s.mesh.h_max) = match family {
        Family::Graded => (Some(o.grading_ratio), Some(o.graded_h_max_over_t * t)),
        Family::Uniform => (None, None),
    };
    s
}

/// Runs the study; `progress` gets each finished run and the fraction of the runs done (from
/// any thread).
pub fn study(base: &Scene, o: &StudyOptions, progress: Progress<Run>) -> Result<Study> {
    if o.elements.is_empty() || o.families.is_empty() || o.n_thick.is_empty() {
        return Err(Error::input("convergence study", "need at least one element, family and mesh"));
    }
    if o.n_thick.contains(&0) {
        return Err(Error::input("n-thick", "elements through the thickness must be at least 1"));
    }
    if let Some(f) = &base.mesh.file {
        return Err(Error::input(
            "mesh.file (--mesh)",
            format!(
                "the study meshes the block itself at each size; one file {} cannot be refined by it",
                crate::error::quote(&f.display().to_string())
            ),
        ));
    }
    let limit = crate::scene::limits::effective(base.mesh.max_dofs)?;
    let mut specs = Vec::new();
    let mut skipped = Vec::new();
    for e in &o.elements {
        for &f in &o.families {
            for &n in &o.n_thick {
                let s = run_scene(base, o, f, e, n);
                s.validate()?;
                // Runs above the scene's size limit (mesh.max_dofs) are skipped and listed.
                let dofs = s.estimate_dofs()?;
                if dofs > limit as f64 {
                    skipped.push(format!("{} {e} h = t/{n} (~{dofs:.3e} DOFs > {limit})", f.name()));
                } else {
                    specs.push((f, e.clone(), n, s));
                }
            }
        }
    }
    if specs.is_empty() {
        return Err(Error::input(
            "--max-dofs (mesh.max_dofs)",
            format!("every run is above the limit of {limit} unknowns: {}", skipped.join("; ")),
        ));
    }
    // Largest first, so the long runs start early when running concurrently.
    specs.sort_by(|a, b| {
        (b.3.estimate_dofs().unwrap_or(0.0) + b.2 as f64)
            .total_cmp(&(a.3.estimate_dofs().unwrap_or(0.0) + a.2 as f64))
    });
    let (done, total) = (AtomicUsize::new(0), specs.len());
    let one = |(f, e, n, s): &(Family, String, usize, Scene)| -> Result<Run> {
        o.cancel.check()?;
        let base = crate::memory::in_use_bytes().unwrap_or(0);
        if !o.parallel {
            crate::memory::reset_peak();
        }
        let clock = Instant::now();
        let (r, _) = check::run(s, &SolverOptions::default())?;
        let mut run = to_run(*f, e, *n, &r, clock.elapsed().as_secs_f64());
        if !o.parallel {
            run.peak_mib =
                crate::memory::peak_bytes().map(|p| p.saturating_sub(base) as f64 / (1u64 << 20) as f64);
        }
        let k = done.fetch_add(1, Ordering::Relaxed) + 1;
        progress.item(&run, k as f64 / total as f64);
        Ok(run)
    };
    let mut runs: Vec<Run> = if o.parallel {
        specs.par_iter().map(one).collect::<Result<_>>()?
    } else {
        specs.iter().map(one).collect::<Result<_>>()?
    };
    runs.sort_by(|a, b| {
        (a.element.as_str(), a.family.name(), a.n_thick).cmp(&(
            b.element.as_str(),
            b.family.name(),
            b.n_thick,
        ))
    });
    let reference = pick_reference(&runs);
    let t_over_l = base.block.thickness / base.block.length;
    let samples = Samples::new(t_over_l);
    let (rx, rp, rt) = (runs[reference].x.clone(), runs[reference].p.clone(), runs[reference].tau.clone());
    for r in &mut runs {
        r.errors = samples.errors(&r.x, &r.p, &r.tau, &rx, &rp, &rt);
    }
    let theory = Theory::new(base.block.plane_strain_nu(), &runs[reference], t_over_l)?;
    Ok(Study { nu: base.block.poisson, t_over_l, runs, reference, skipped, theory })
}

fn to_run(family: Family, element: &str, n: usize, r: &CheckResult, wall: f64) -> Run {
    let c = &r.cases[0];
    let m = &c.metrics;
    Run {
        family,
        element: element.to_string(),
        n_thick: n,
        dofs: 2 * r.n_nodes,
        n_elements: r.n_elements,
        timings: r.stats.timings,
        wall,
        factor_mib: r.stats.factor_nnz as f64 * 8.0 / (1u64 << 20) as f64,
        peak_mib: None,
        x: c.x_over_l.clone(),
        p: c.p.clone(),
        tau: c.tau.clone(),
        slope: m.slope_interior,
        tau_center: m.tau_center,
        p_end: m.p_ends,
        tau_end: m.tau_ends,
        widths: [m.edge_p_t[0], m.edge_p_t[1], m.edge_tau_t[0], m.edge_tau_t[1]],
        balance: m.balance_n.max(m.balance_f).max(m.balance_moment),
        errors: ZoneErrors::default(),
    }
}

/// The reference: the finest uniform run of the highest-order element present (quadratic
/// elements converge fastest in the smooth zones; among equals QUA9, then QUA8, then TRI6,
/// the most accurate per DOF in the study), else the run with the most DOFs.
fn pick_reference(runs: &[Run]) -> usize {
    let choice = |r: &Run| r.element.parse::<crate::fem::element::stiffness::ElementChoice>().ok();
    let order = |r: &Run| choice(r).map_or(1, |c| c.kind.order());
    let rank = |r: &Run| match choice(r).map(|c| c.kind) {
        Some(crate::fem::element::ElementKind::Qua9) => 3,
        Some(crate::fem::element::ElementKind::Qua8) => 2,
        _ => 1,
    };
    (0..runs.len())
        .max_by_key(|&i| (order(&runs[i]), runs[i].family == Family::Uniform, runs[i].dofs, rank(&runs[i])))
        .unwrap_or(0)
}

/// Sample positions (in units of L) of the three zones.
struct Samples {
    interior: Vec<f64>,
    edge: Vec<f64>,
}

impl Samples {
    fn new(t_over_l: f64) -> Self {
        let a = 0.5 - 10.0 * t_over_l;
        let interior = (0..=200).map(|i| -a + 2.0 * a * i as f64 / 200.0).collect();
        // Distances t/4 .. 10 t from each end, geometrically spaced.
        let d: Vec<f64> = (0..=60).map(|i| 0.25 * t_over_l * 40f64.powf(i as f64 / 60.0)).collect();
        let edge = d.iter().map(|d| -0.5 + d).chain(d.iter().map(|d| 0.5 - d)).collect();
        Self { interior, edge }
    }

    fn errors(&self, x: &[f64], p: &[f64], tau: &[f64], rx: &[f64], rp: &[f64], rt: &[f64]) -> ZoneErrors {
        let max_err = |pts: &[f64], v: &[f64], rv: &[f64]| {
            pts.iter().map(|&s| (interpolate(x, v, s) - interpolate(rx, rv, s)).abs()).fold(0.0, f64::max)
        };
        let n = x.len();
        let rn = rx.len();
        let end = |v: &[f64], rv: &[f64]| (v[0] - rv[0]).abs().max((v[n - 1] - rv[rn - 1]).abs());
        ZoneErrors {
            interior: [max_err(&self.interior, p, rp), max_err(&self.interior, tau, rt)],
            edge: [max_err(&self.edge, p, rp), max_err(&self.edge, tau, rt)],
            end: [end(p, rp), end(tau, rt)],
        }
    }
}

/// Zone errors (interior, edge zones, end nodes) of profiles (x/L, p, tau) against a
/// reference on another mesh, in units of N/L.
pub fn zone_errors(
    t_over_l: f64,
    x: &[f64],
    p: &[f64],
    tau: &[f64],
    rx: &[f64],
    rp: &[f64],
    rt: &[f64],
) -> ZoneErrors {
    Samples::new(t_over_l).errors(x, p, tau, rx, rp, rt)
}

/// Observed order of convergence between two runs: log(e1/e2) / log(h1/h2).
pub fn observed_order(e1: f64, h1: f64, e2: f64, h2: f64) -> f64 {
    (e1 / e2).ln() / (h1 / h2).ln()
}

/// Indices of the runs on the Pareto front of (wall time, error): no other run is both
/// faster and more accurate. Sorted by time.
pub fn pareto_front(points: &[(f64, f64)]) -> Vec<usize> {
    let mut idx: Vec<usize> = (0..points.len()).filter(|&i| points[i].0 > 0.0 && points[i].1 > 0.0).collect();
    idx.sort_by(|&a, &b| points[a].0.total_cmp(&points[b].0).then(points[a].1.total_cmp(&points[b].1)));
    let mut front = Vec::new();
    let mut best = f64::INFINITY;
    for i in idx {
        if points[i].1 < best {
            best = points[i].1;
            front.push(i);
        }
    }
    front
}

/// Runs of one (element, family) series, sorted from coarse to fine.
pub fn series(study: &Study) -> Vec<Vec<usize>> {
    let mut keys: Vec<(String, Family)> = study.runs.iter().map(|r| (r.element.clone(), r.family)).collect();
    keys.dedup();
    keys.iter()
        .map(|(e, f)| {
            let mut v: Vec<usize> = (0..study.runs.len())
                .filter(|&i| &study.runs[i].element == e && study.runs[i].family == *f)
                .collect();
            v.sort_by_key(|&i| study.runs[i].n_thick);
            v
        })
        .collect()
}

/// Observed orders of a series by self-convergence, independent of the reference: with
/// d_k = max |f_k - f_(k+1)| between successive meshes (zones as for the errors), the order
/// from the last three meshes is log(d_(k-1)/d_k) / log(h_(k-1)/h_k), per zone
/// [interior p, interior tau, edge p, edge tau]; None with fewer than three meshes.
pub fn orders(study: &Study, s: &[usize]) -> Option<[f64; 4]> {
    if s.len() < 3 {
        return None;
    }
    let samples = Samples::new(study.t_over_l);
    let diff = |a: &Run, b: &Run| samples.errors(&a.x, &a.p, &a.tau, &b.x, &b.p, &b.tau);
    let r: Vec<&Run> = s[s.len() - 3..].iter().map(|&i| &study.runs[i]).collect();
    let (d1, d2) = (diff(r[0], r[1]), diff(r[1], r[2]));
    let ratio = r[1].n_thick as f64 / r[0].n_thick as f64;
    let o = |a: f64, b: f64| (a / b).ln() / ratio.ln();
    Some([
        o(d1.interior[0], d2.interior[0]),
        o(d1.interior[1], d2.interior[1]),
        o(d1.edge[0], d2.edge[0]),
        o(d1.edge[1], d2.edge[1]),
    ])
}

/// Largest edge-zone error of a run (pressure or shear, either end), units of N/L.
pub fn edge_error(r: &Run) -> f64 {
    r.errors.edge[0].max(r.errors.edge[1])
}

/// The cheapest run (fewest unknowns; other than the reference) whose edge-zone error is at
/// most `tol`.
pub fn cheapest(study: &Study, tol: f64) -> Option<&Run> {
    // Ranked by a deterministic cost (unknowns, then the factor's size), never by a noisy
    // wall time: identical studies name the same run.
    (0..study.runs.len())
        .filter(|&i| i != study.reference && edge_error(&study.runs[i]) <= tol)
        .map(|i| &study.runs[i])
        .min_by(|a, b| a.dofs.cmp(&b.dofs).then(a.factor_mib.total_cmp(&b.factor_mib)))
}

/// Rounds to two significant digits.
pub fn two_digits(v: f64) -> f64 {
    if v == 0.0 {
        return 0.0;
    }
    let m = 10f64.powf(v.abs().log10().floor() - 1.0);
    (v / m).round() * m
}

/// For each of the four widths: the coarsest run of the series from which on every finer run
/// agrees with the finest to two significant digits.
pub fn first_converged_width(study: &Study, s: &[usize]) -> [Option<usize>; 4] {
    std::array::from_fn(|k| {
        let finest = study.runs[*s.last()?].widths[k]?;
        let target = two_digits(finest);
        let mut first = None;
        for &i in s.iter().rev() {
            match study.runs[i].widths[k] {
                Some(w) if two_digits(w) == target => first = Some(i),
                _ => break,
            }
        }
        first
    })
}

/// Decay rates k (in units of 1/t) of the end disturbances, fitted as |dev| ~ exp(-k d / t) over
/// distances d from each end where the disturbance is above `floor` (units of N/L), for
/// [p left, p right, tau left, tau right]. The disturbance is measured from the run's own far
/// field (least-squares line of p, mean of tau over the interior), not from the model.
pub fn decay_rates(r: &Run, t_over_l: f64, floor: f64) -> [Option<f64>; 4] {
    let n = r.x.len();
    let interior: Vec<usize> = (0..n).filter(|&i| r.x[i].abs() < 0.5 - 10.0 * t_over_l).collect();
    let Some((a, b)) = line_fit(interior.iter().map(|&i| (r.x[i], r.p[i]))) else { return [None; 4] };
    let tau_far = interior.iter().map(|&i| r.tau[i]).sum::<f64>() / interior.len() as f64;
    let fit = |v: &dyn Fn(usize) -> f64, left: bool| -> Option<f64> {
        // Points from d = t/2 inwards while the disturbance stays above the floor.
        let order: Vec<usize> = if left { (0..n).collect() } else { (0..n).rev().collect() };
        let end = r.x[order[0]];
        let pts: Vec<(f64, f64)> = order
            .iter()
            .map(|&i| ((r.x[i] - end).abs() / t_over_l, v(i).abs()))
            .skip_while(|&(d, _)| d < 0.5)
            .take_while(|&(d, dev)| dev > floor && d < 10.0)
            .map(|(d, dev)| (d, dev.ln()))
            .collect();
        if pts.len() < 4 {
            return None;
        }
        line_fit(pts).map(|(_, slope)| -slope)
    };
    let dp = |i: usize| r.p[i] - (a + b * r.x[i]);
    let dt = |i: usize| r.tau[i] - tau_far;
    [fit(&dp, true), fit(&dp, false), fit(&dt, true), fit(&dt, false)]
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn pareto_keeps_only_non_dominated_points() {
        let pts = [(1.0, 1.0), (2.0, 0.5), (1.5, 2.0), (3.0, 0.5), (4.0, 0.1)];
        assert_eq!(pareto_front(&pts), vec![0, 1, 4]);
        assert!((observed_order(4.0, 2.0, 1.0, 1.0) - 2.0).abs() < 1e-15);
    }
}
