//! Numerical stability of the paper's check (issue 7), five studies:
//! `plate` (stiff elastic plate vs the exact rigid one: modelling error against round-off),
//! `nu` (near-incompressibility: locking per element), `shape` (elongated and distorted
//! elements), `thin` (t/L -> 0 at a fixed number of elements through the thickness) and
//! `corners` (singular end nodes vs converging integrated quantities).

use crate::error::{Error, Result};
use crate::fem::material::Material;
use crate::linalg::solve::SolverOptions;
use crate::scene::{PlateModel, Scene};
use crate::studies::check::interpolate;
use crate::studies::check::{self, CheckResult};
use crate::studies::convergence::{self, zone_errors, Family, StudyOptions, ZoneErrors};
use std::collections::HashMap;
use std::time::Instant;

pub const STUDIES: [&str; 5] = ["plate", "nu", "shape", "thin", "corners"];

/// Progress callback: called once per solved run with a short description.
pub type Progress<'a> = &'a (dyn Fn(&str) + Sync);

#[derive(Debug, Clone)]
pub struct Options {
    /// plate: E_plate / E_block values, and meshes (elements through the thickness; 2 = paper).
    pub plate_ratios: Vec<f64>,
    pub plate_n_thick: Vec<usize>,
    /// plate: also run forced iterative refinement (3 steps) at each point.
    pub plate_refine: bool,
    pub nus: Vec<f64>,
    pub elements: Vec<String>,
    /// Elements through the thickness of the nu and shape runs (h = t / n).
    pub n_thick: usize,
    /// Reference: qua9 with this many elements through the thickness.
    pub n_ref: usize,
    pub aspects: Vec<f64>,
    /// Growth ratio of the graded family of the shape study.
    pub grading_ratio: f64,
    /// Distortion amplitudes, fractions of h, and the seed of the perturbation.
    pub distortions: Vec<f64>,
    pub seed: u64,
    /// Unstructured Gmsh mesh of the block for the shape study (skipped if the file is absent).
    pub unstructured_mesh: Option<std::path::PathBuf>,
    pub thin_ratios: Vec<f64>,
    /// thin: elements through the thickness; meshes above `max_dofs` are graded instead.
    pub thin_n_thick: usize,
    pub max_dofs: usize,
    pub corner_n_thick: Vec<usize>,
    /// The load case compared (F/N) where one is needed.
    pub fn_ratio: f64,
}

impl Default for Options {
    fn default() -> Self {
        Self {
            plate_ratios: (0..=16).map(|k| 10f64.powi(k)).collect(),
            plate_n_thick: vec![2, 4],
            plate_refine: true,
            nus: vec![0.3, 0.4, 0.45, 0.49, 0.499, 0.4999],
            elements: ["qua4", "qua4-sri", "qua4-im", "qua8", "qua9"].map(String::from).to_vec(),
            n_thick: 4,
            n_ref: 16,
            aspects: vec![1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0],
            grading_ratio: 1.1,
            distortions: vec![0.0, 0.1, 0.2, 0.3],
            seed: 7,
            // The shipped mesh, found from the source tree, not the current directory.
            unstructured_mesh: Some(
                concat!(env!("CARGO_MANIFEST_DIR"), "/meshes/block_unstructured_v41_bin.msh").into(),
            ),
            thin_ratios: vec![1e-1, 1e-2, 1e-3, 1e-4],
            thin_n_thick: 4,
            max_dofs: 600_000,
            corner_n_thick: vec![1, 2, 4, 8, 16, 32],
            fn_ratio: 0.82,
        }
    }
}

/// Largest |a - b| over two equally long profiles.
fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max)
}

/// Largest |p - p_ref|, |tau - tau_ref| (units of N/L) at distances t .. 10 t from either end:
/// the edge zones without the corners' immediate neighbourhood, where every mesh is wrong.
fn edge_far(r: &CheckResult, reference: &CheckResult) -> f64 {
    let (c, rc) = (r.cases.last().unwrap(), reference.cases.last().unwrap());
    let tl = r.scene.block.thickness / r.scene.block.length;
    (0..=40)
        .map(|i| tl * 10f64.powf(i as f64 / 40.0))
        .flat_map(|d| [-0.5 + d, 0.5 - d])
        .map(|s| {
            let dp = (interpolate(&c.x_over_l, &c.p, s) - interpolate(&rc.x_over_l, &rc.p, s)).abs();
            dp.max((interpolate(&c.x_over_l, &c.tau, s) - interpolate(&rc.x_over_l, &rc.tau, s)).abs())
        })
        .fold(0.0, f64::max)
}

fn interior_max(e: &ZoneErrors) -> f64 {
    e.interior[0].max(e.interior[1])
}

// ---------------------------------------------------------------- plate

#[derive(Debug, Clone)]
pub struct PlatePoint {
    pub n_thick: usize,
    /// E_plate / E_block.
    pub ratio: f64,
    /// None when the solve itself failed (the message is in `failure`).
    pub raw: Option<PlateRaw>,
    pub failure: Option<String>,
    /// Error with forced iterative refinement (max |diff| of p and tau, N/L), and its steps.
    pub refined: Option<(f64, usize)>,
    /// tribofe's default check refuses the result (and why).
    pub refused: Option<String>,
}

#[derive(Debug, Clone)]
pub struct PlateRaw {
    /// Max |elastic - rigid| over every interface node and load case, units of N/L.
    pub err_p: f64,
    pub err_tau: f64,
    pub backward_error: f64,
    pub condition: f64,
    /// Tilt per unit normal force at the compared F/N, relative difference from the rigid plate.
    pub tilt_rel: f64,
    pub time: f64,
    pub symbolic_time: f64,
}

impl PlateRaw {
    pub fn err(&self) -> f64 {
        self.err_p.max(self.err_tau)
    }
}

/// Per mesh: where the error stops falling and where round-off takes over.
#[derive(Debug, Clone)]
pub struct PlateFinding {
    pub n_thick: usize,
    /// Ratio of the smallest error, and that error (N/L).
    pub best_ratio: f64,
    pub best_err: f64,
    /// First ratio above the best whose error is 10x the smallest.
    pub roundoff_ratio: Option<f64>,
    /// Smallest ratio the default check refuses.
    pub first_refused: Option<f64>,
    /// log10(condition) at the paper's ratio 1e12 (digits lost).
    pub digits_lost_1e12: Option<f64>,
}

#[derive(Debug, Clone)]
pub struct PlateStudy {
    pub points: Vec<PlatePoint>,
    pub findings: Vec<PlateFinding>,
    /// Share of a point's solve that the pattern + symbolic analysis (built once per mesh and
    /// reused along the sweep) would cost if redone.
    pub symbolic_share: f64,
}

/// Elastic plate at `ratio` against the rigid plate on the same block mesh.
pub fn plate(base: &Scene, o: &Options, progress: Progress) -> Result<PlateStudy> {
    let t = base.block.thickness;
    let raw_opts = SolverOptions {
        max_error_estimate: f64::INFINITY,
        residual_limit: f64::INFINITY,
        max_refinement: 0,
        ..Default::default()
    };
    let refine_opts = SolverOptions { max_refinement: 3, refine_above: 0.0, ..raw_opts.clone() };
    let mut points = Vec::new();
    let mut prepare_time = 0.0;
    for &n in &o.plate_n_thick {
        let mut s = base.clone();
        s.mesh.h = t / n as f64;
        s.mesh.n_thick = Some(n);
        s.plate.model = PlateModel::Rigid;
        let (rigid, _) = check::run(&s, &SolverOptions::default())?;
        progress(&format!("plate rigid t/{n}"));
        // Only the plate modulus changes along the sweep: one pattern and symbolic analysis.
        let mut e0 = s.clone();
        e0.plate.model = PlateModel::Elastic;
        let prepared = check::prepare(&e0, &SolverOptions::default())?;
        prepare_time += prepared.pattern_time + prepared.symbolic_time;
        let run =
            |e: &Scene, opts: &SolverOptions| check::run_model(e, e.build()?, 0.0, opts, Some(&prepared));
        for &ratio in &o.plate_ratios {
            let mut e = e0.clone();
            e.plate.young = ratio * base.block.young;
            let clock = Instant::now();
            let (raw, failure) = match run(&e, &raw_opts) {
                Ok((r, _)) => (Some(plate_raw(&r, &rigid, clock.elapsed().as_secs_f64(), o.fn_ratio)), None),
                Err(err) => (None, Some(err.to_string())),
            };
            let refined = if o.plate_refine && raw.is_some() {
                run(&e, &refine_opts).ok().map(|(r, _)| {
                    (plate_raw(&r, &rigid, 0.0, o.fn_ratio).err(), r.solve_report.refinement_steps)
                })
            } else {
                None
            };
            let refused = run(&e, &SolverOptions::default()).err().map(|e| e.to_string());
            progress(&format!("plate t/{n} ratio {ratio:.0e}"));
            points.push(PlatePoint { n_thick: n, ratio, raw, failure, refined, refused });
        }
    }
    let findings = o.plate_n_thick.iter().map(|&n| plate_finding(n, &points)).collect();
    // Share of each point's solve that the reused pattern + symbolic analysis would have cost.
    let times: Vec<f64> = points.iter().filter_map(|p| p.raw.as_ref()).map(|r| r.time).collect();
    let per_mesh = prepare_time / o.plate_n_thick.len().max(1) as f64;
    let mean = times.iter().sum::<f64>() / times.len().max(1) as f64;
    Ok(PlateStudy {
        points,
        findings,
        symbolic_share: if per_mesh + mean > 0.0 { per_mesh / (per_mesh + mean) } else { 0.0 },
    })
}

fn plate_raw(r: &CheckResult, rigid: &CheckResult, time: f64, fn_ratio: f64) -> PlateRaw {
    let (mut ep, mut et) = (0.0f64, 0.0f64);
    for (a, b) in r.cases.iter().zip(&rigid.cases) {
        ep = ep.max(max_diff(&a.p, &b.p));
        et = et.max(max_diff(&a.tau, &b.tau));
    }
    let pick = |c: &CheckResult| {
        c.cases.iter().find(|x| x.fn_ratio == fn_ratio).or(c.cases.last()).map_or(0.0, |x| x.tilt / x.n)
    };
    let (te, tr) = (pick(r), pick(rigid));
    PlateRaw {
        err_p: ep,
        err_tau: et,
        backward_error: r.solve_report.residual.iter().cloned().fold(0.0, f64::max),
        condition: r.solve_report.condition_estimate,
        tilt_rel: if tr != 0.0 { (te - tr).abs() / tr.abs() } else { (te - tr).abs() },
        time,
        symbolic_time: r.timings.symbolic,
    }
}

fn plate_finding(n: usize, points: &[PlatePoint]) -> PlateFinding {
    let pts: Vec<&PlatePoint> = points.iter().filter(|p| p.n_thick == n).collect();
    let ok: Vec<(f64, f64)> = pts.iter().filter_map(|p| p.raw.as_ref().map(|r| (p.ratio, r.err()))).collect();
    let (best_ratio, best_err) =
        ok.iter().cloned().min_by(|a, b| a.1.total_cmp(&b.1)).unwrap_or((f64::NAN, f64::NAN));
    // A failed solve above the best counts as round-off having taken over.
    let roundoff_ratio = pts
        .iter()
        .filter(|p| p.ratio > best_ratio)
        .find(|p| p.raw.as_ref().is_none_or(|r| r.err() > 10.0 * best_err))
        .map(|p| p.ratio);
    PlateFinding {
        n_thick: n,
        best_ratio,
        best_err,
        roundoff_ratio,
        first_refused: pts.iter().find(|p| p.refused.is_some()).map(|p| p.ratio),
        digits_lost_1e12: pts
            .iter()
            .find(|p| p.ratio == 1e12)
            .and_then(|p| p.raw.as_ref())
            .map(|r| r.condition.log10()),
    }
}

// ---------------------------------------------------------------- references

/// qua9 references at h = t / n_ref, one per Poisson's ratio (cached across studies).
pub struct References {
    base: Scene,
    n_ref: usize,
    cache: HashMap<u64, CheckResult>,
}

impl References {
    pub fn new(base: &Scene, n_ref: usize) -> Self {
        Self { base: base.clone(), n_ref, cache: HashMap::new() }
    }

    /// Reference for the base scene at Poisson's ratio `nu` (load cases F/N = 0 and `fn_ratio`).
    pub fn get(&mut self, nu: f64, fn_ratio: f64, progress: Progress) -> Result<&CheckResult> {
        if !self.cache.contains_key(&nu.to_bits()) {
            let mut s = self.base.clone();
            s.block.poisson = nu;
            s.mesh.h = s.block.thickness / self.n_ref as f64;
            s.mesh.element = "qua9".into();
            (s.mesh.grading, s.mesh.h_max) = (None, None);
            s.mesh.n_thick = None;
            s.loading.fn_ratios = vec![0.0, fn_ratio];
            let (r, _) = check::run(&s, &SolverOptions::default())?;
            progress(&format!("reference qua9 t/{} nu {nu}", self.n_ref));
            self.cache.insert(nu.to_bits(), r);
        }
        Ok(&self.cache[&nu.to_bits()])
    }
}

/// A run's interface-profile errors against a reference at the compared load case (the last).
fn errors_against(r: &CheckResult, reference: &CheckResult) -> ZoneErrors {
    let (c, rc) = (r.cases.last().unwrap(), reference.cases.last().unwrap());
    zone_errors(
        r.scene.block.thickness / r.scene.block.length,
        &c.x_over_l,
        &c.p,
        &c.tau,
        &rc.x_over_l,
        &rc.p,
        &rc.tau,
    )
}

// ---------------------------------------------------------------- nu

#[derive(Debug, Clone)]
pub struct NuPoint {
    pub nu: f64,
    pub element: String,
    pub errors: ZoneErrors,
    /// Largest interior error (p or tau), units of N/L: the edge zones' error is dominated by
    /// the singular corners for every element, the interior's shows locking.
    pub err: f64,
    /// See `edge_far`.
    pub err_edge_far: f64,
    /// Max |second difference| of p or tau between neighbouring nodes t/2 .. 10 t from the
    /// ends, in excess of the reference's sampled at those nodes (units of N/L): checkerboard.
    pub oscillation: f64,
    /// p(0) at F/N = 0 over the closed-form thin-layer value (dimensionless; 1 = exact).
    pub p0_closed: f64,
    /// N / (L strain) over the confined modulus lambda + 2G (dimensionless).
    pub modulus_ratio: f64,
}

#[derive(Debug, Clone)]
pub struct NuStudy {
    pub points: Vec<NuPoint>,
    /// The references' own closed-form p(0) ratios, per nu.
    pub reference_p0: Vec<(f64, f64)>,
}

/// Closed-form p(0) and N/(L strain) ratios of a run's F/N = 0 case (the first).
fn closed_form(r: &CheckResult) -> Result<(f64, f64)> {
    let s = &r.scene;
    let mat = Material::plane_strain(s.block.young, s.block.poisson)?;
    let c = &r.cases[0];
    let strain = c.plate_v.abs() / s.block.thickness;
    let pmean = c.n / s.block.length;
    let p0 = interpolate(&c.x_over_l, &c.p, 0.0) * pmean;
    let m = mat.lambda() + 2.0 * mat.shear_modulus();
    Ok((
        p0 / crate::analytical::thin_layer::bonded_layer_p0(&mat, strain, s.block.length, s.block.thickness),
        pmean / (m * strain),
    ))
}

fn oscillation(r: &CheckResult, reference: &CheckResult) -> f64 {
    let (c, rc) = (r.cases.last().unwrap(), reference.cases.last().unwrap());
    let tl = r.scene.block.thickness / r.scene.block.length;
    let x = &c.x_over_l;
    let mut worst = 0.0f64;
    for i in 1..x.len() - 1 {
        let d = 0.5 - x[i].abs();
        if d < 0.5 * tl || d > 10.0 * tl {
            continue;
        }
        let second = |v: &dyn Fn(usize) -> f64| v(i - 1) - 2.0 * v(i) + v(i + 1);
        for (own, rv) in [(&c.p, &rc.p), (&c.tau, &rc.tau)] {
            let a = second(&|k| own[k]);
            let b = second(&|k| interpolate(&rc.x_over_l, rv, x[k]));
            worst = worst.max((a.abs() - b.abs()).max(0.0));
        }
    }
    worst
}

pub fn nu(base: &Scene, o: &Options, refs: &mut References, progress: Progress) -> Result<NuStudy> {
    let mut points = Vec::new();
    let mut reference_p0 = Vec::new();
    for &nu in &o.nus {
        let rf = refs.get(nu, o.fn_ratio, progress)?.clone();
        reference_p0.push((nu, closed_form(&rf)?.0));
        for e in &o.elements {
            let mut s = base.clone();
            s.block.poisson = nu;
            s.mesh.h = s.block.thickness / o.n_thick as f64;
            s.mesh.n_thick = Some(o.n_thick);
            s.mesh.element = e.clone();
            s.loading.fn_ratios = vec![0.0, o.fn_ratio];
            let (r, _) = check::run(&s, &SolverOptions::default())?;
            let errors = errors_against(&r, &rf);
            let (p0_closed, modulus_ratio) = closed_form(&r)?;
            progress(&format!("nu {nu} {e}"));
            points.push(NuPoint {
                nu,
                element: e.clone(),
                err: interior_max(&errors),
                err_edge_far: edge_far(&r, &rf),
                errors,
                oscillation: oscillation(&r, &rf),
                p0_closed,
                modulus_ratio,
            });
        }
    }
    Ok(NuStudy { points, reference_p0 })
}

// ---------------------------------------------------------------- shape

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ShapeCase {
    /// Square elements at the ends, growing to `aspect` x h in the smooth interior.
    Graded,
    /// Uniformly elongated elements everywhere, ends included.
    Uniform,
    /// Square structured mesh with interior nodes moved at random (`aspect` = amplitude / h).
    Distorted,
    /// The unstructured quad-dominant Gmsh mesh of the block (`meshes/`), QUA4-family
    /// elements only (the file holds QUA4 and TRI3).
    Unstructured,
}

impl ShapeCase {
    pub fn name(self) -> &'static str {
        match self {
            ShapeCase::Graded => "graded",
            ShapeCase::Uniform => "uniform",
            ShapeCase::Distorted => "distorted",
            ShapeCase::Unstructured => "unstructured",
        }
    }
}

#[derive(Debug, Clone)]
pub struct ShapePoint {
    pub case: ShapeCase,
    pub element: String,
    /// Largest element aspect ratio (length / height), or the distortion amplitude / h.
    pub param: f64,
    pub n_elements: usize,
    pub errors: ZoneErrors,
    /// Largest interior error and edge error t .. 10 t from the ends (p or tau), units of N/L.
    pub err: f64,
    pub err_edge_far: f64,
    /// Smallest Jacobian determinant over elements relative to the undistorted one (distorted only).
    pub min_jacobian_rel: f64,
}

pub fn shape(
    base: &Scene,
    o: &Options,
    refs: &mut References,
    progress: Progress,
) -> Result<Vec<ShapePoint>> {
    let rf = refs.get(base.block.poisson, o.fn_ratio, progress)?.clone();
    let t = base.block.thickness;
    let h = t / o.n_thick as f64;
    let mut out = Vec::new();
    for e in &o.elements {
        let mut s = base.clone();
        s.mesh.element = e.clone();
        s.mesh.h = h;
        s.mesh.n_thick = Some(o.n_thick);
        s.loading.fn_ratios = vec![o.fn_ratio];
        for &a in &o.aspects {
            for case in [ShapeCase::Graded, ShapeCase::Uniform] {
                let mut v = s.clone();
                match case {
                    ShapeCase::Graded => {
                        v.mesh.grading = Some(o.grading_ratio);
                        v.mesh.h_max = Some(a * h);
                    }
                    _ => {
                        v.mesh.h = a * h;
                        v.mesh.n_thick = Some(o.n_thick);
                    }
                }
                let (r, _) = check::run(&v, &SolverOptions::default())?;
                let errors = errors_against(&r, &rf);
                progress(&format!("shape {} {e} 1:{a}", case.name()));
                out.push(ShapePoint {
                    case,
                    element: e.clone(),
                    param: a,
                    n_elements: r.n_elements,
                    err: interior_max(&errors),
                    err_edge_far: edge_far(&r, &rf),
                    errors,
                    min_jacobian_rel: 1.0,
                });
            }
        }
        for &amp in &o.distortions {
            let mut sm = s.build()?;
            let j0 = (0..sm.mesh.n_elements()).map(|k| sm.mesh.min_jacobian(k)).fold(f64::INFINITY, f64::min);
            sm.mesh.distort(amp * h, o.seed)?;
            let j1 = (0..sm.mesh.n_elements()).map(|k| sm.mesh.min_jacobian(k)).fold(f64::INFINITY, f64::min);
            let (r, _) = check::run_model(&s, sm, 0.0, &SolverOptions::default(), None)?;
            let errors = errors_against(&r, &rf);
            progress(&format!("shape distorted {e} {amp}"));
            out.push(ShapePoint {
                case: ShapeCase::Distorted,
                element: e.clone(),
                param: amp,
                n_elements: r.n_elements,
                err: interior_max(&errors),
                err_edge_far: edge_far(&r, &rf),
                errors,
                min_jacobian_rel: j1 / j0,
            });
        }
        let qua4_family = s.element()?.kind == crate::fem::element::ElementKind::Qua4;
        if let (Some(path), true) = (o.unstructured_mesh.as_ref().filter(|p| p.exists()), qua4_family) {
            let mut v = s.clone();
            v.mesh.file = Some(path.clone());
            let sm = v.build()?;
            let quality =
                (0..sm.mesh.n_elements()).map(|k| sm.mesh.jacobian_quality(k)).fold(f64::INFINITY, f64::min);
            let (r, _) = check::run_model(&v, sm, 0.0, &SolverOptions::default(), None)?;
            let errors = errors_against(&r, &rf);
            progress(&format!("shape unstructured {e}"));
            out.push(ShapePoint {
                case: ShapeCase::Unstructured,
                element: e.clone(),
                param: 0.0,
                n_elements: r.n_elements,
                err: interior_max(&errors),
                err_edge_far: edge_far(&r, &rf),
                errors,
                min_jacobian_rel: quality,
            });
        }
    }
    Ok(out)
}

// ---------------------------------------------------------------- thin

#[derive(Debug, Clone)]
pub struct ThinPoint {
    pub t_over_l: f64,
    pub nx: usize,
    pub dofs: usize,
    /// Graded along x because the uniform mesh was over the DOF budget.
    pub graded: bool,
    pub condition: f64,
    pub backward_error: f64,
    /// nnz(L) / nnz(K).
    pub fill: f64,
    pub time: f64,
    /// Least-squares slope of p/(N/L) over |x| < L/4, and its relative error from 12 (F/N)(H/L).
    pub slope: f64,
    pub slope_rel_err: f64,
    /// Max |tau/(N/L) - F/N| over |x| < L/4.
    pub tau_dev: f64,
    /// Edge widths in units of t: p left/right, tau left/right.
    pub widths: [Option<f64>; 4],
}

pub fn thin(base: &Scene, o: &Options, progress: Progress) -> Result<Vec<ThinPoint>> {
    let l = base.block.length;
    let mut out = Vec::new();
    for &tl in &o.thin_ratios {
        let mut s = base.clone();
        s.block.thickness = tl * l;
        s.mesh.h = s.block.thickness / o.thin_n_thick as f64;
        s.mesh.element = "qua4".into();
        s.loading.fn_ratios = vec![o.fn_ratio];
        let nx = (l / s.mesh.h).round() as usize;
        let graded = 2 * (nx + 1) * (o.thin_n_thick + 1) > o.max_dofs;
        if graded {
            // Square elements over 20 t at the ends, growing by 10 % to at most 10 t.
            s.mesh.grading = Some(1.1);
            s.mesh.h_max = Some(10.0 * s.block.thickness);
        }
        let clock = Instant::now();
        let (r, _) = check::run(&s, &SolverOptions::default())?;
        let time = clock.elapsed().as_secs_f64();
        let c = &r.cases[0];
        let mid: Vec<usize> = (0..c.x_over_l.len()).filter(|&i| c.x_over_l[i].abs() < 0.25).collect();
        let slope = check::line_fit(mid.iter().map(|&i| (c.x_over_l[i], c.p[i]))).map_or(f64::NAN, |l| l.1);
        let model = c.metrics.slope_model;
        let mt = &c.metrics;
        progress(&format!("thin t/L {tl:.0e}"));
        out.push(ThinPoint {
            t_over_l: tl,
            nx: c.x_over_l.len() - 1,
            dofs: 2 * r.n_nodes,
            graded,
            condition: r.solve_report.condition_estimate,
            backward_error: r.solve_report.residual.iter().cloned().fold(0.0, f64::max),
            fill: r.factor_nnz as f64 / r.matrix_nnz as f64,
            time,
            slope,
            slope_rel_err: (slope - model).abs() / model.abs(),
            tau_dev: mid.iter().map(|&i| (c.tau[i] - c.fn_ratio).abs()).fold(0.0, f64::max),
            widths: [mt.edge_p_t[0], mt.edge_p_t[1], mt.edge_tau_t[0], mt.edge_tau_t[1]],
        });
    }
    Ok(out)
}

// ---------------------------------------------------------------- corners

#[derive(Debug, Clone)]
pub struct CornerStudy {
    pub study: convergence::Study,
    /// p(+L/2) per mesh (coarse to fine) and the ratios of successive increments.
    pub p_end: Vec<f64>,
    pub increment_ratios: Vec<f64>,
    /// Mean of the last two increment ratios, and the exponent it implies: lambda = 1 - log2(factor).
    pub factor: f64,
    pub lambda_measured: f64,
    /// Williams' exponent of the clamped-free right-angle corner (plane strain) and 2^(1 - lambda).
    pub lambda_williams: f64,
    pub factor_williams: f64,
    pub nu: f64,
}

pub fn corners(base: &Scene, o: &Options, progress: Progress) -> Result<CornerStudy> {
    let so = StudyOptions {
        elements: vec!["qua4".into()],
        families: vec![Family::Uniform],
        n_thick: o.corner_n_thick.clone(),
        fn_ratio: o.fn_ratio,
        parallel: false,
        ..Default::default()
    };
    let study = convergence::study(base, &so, &|r| progress(&format!("corners qua4 t/{}", r.n_thick)))?;
    // Two successive increments make one ratio: at least three meshes.
    if study.runs.len() < 3 {
        return Err(Error::input(
            "--corner-max",
            format!(
                "the corner study needs at least three meshes (t/1, t/2, t/4) within the size limit; got {}{}",
                study.runs.len(),
                if study.skipped.is_empty() { String::new() } else { format!(", skipped: {}", study.skipped.join("; ")) }
            ),
        ));
    }
    let p_end: Vec<f64> = study.runs.iter().map(|r| r.p_end[1]).collect();
    let increment_ratios: Vec<f64> = p_end.windows(3).map(|w| (w[2] - w[1]) / (w[1] - w[0])).collect();
    let tail = &increment_ratios[increment_ratios.len().saturating_sub(2)..];
    let factor = tail.iter().sum::<f64>() / tail.len().max(1) as f64;
    let lw =
        crate::analytical::williams::clamped_free_exponent(std::f64::consts::FRAC_PI_2, base.block.poisson)?
            .re;
    Ok(CornerStudy {
        study,
        p_end,
        increment_ratios,
        factor,
        lambda_measured: 1.0 - factor.log2(),
        lambda_williams: lw,
        factor_williams: 2f64.powf(1.0 - lw),
        nu: base.block.poisson,
    })
}

/// All selected studies.
#[derive(Default)]
pub struct Results {
    pub plate: Option<PlateStudy>,
    pub nu: Option<NuStudy>,
    pub shape: Option<Vec<ShapePoint>>,
    pub thin: Option<Vec<ThinPoint>>,
    pub corners: Option<CornerStudy>,
}

pub fn run(base: &Scene, studies: &[String], o: &Options, progress: Progress) -> Result<Results> {
    if let Some(bad) = studies.iter().find(|s| !STUDIES.contains(&s.as_str())) {
        return Err(Error::input(
            "study",
            format!("'{bad}' is not known; choose from {}", STUDIES.join(", ")),
        ));
    }
    let on = |name: &str| studies.iter().any(|s| s == name);
    let mut refs = References::new(base, o.n_ref);
    let mut res = Results::default();
    if on("plate") {
        res.plate = Some(plate(base, o, progress)?);
    }
    if on("nu") {
        res.nu = Some(nu(base, o, &mut refs, progress)?);
    }
    if on("shape") {
        res.shape = Some(shape(base, o, &mut refs, progress)?);
    }
    if on("thin") {
        res.thin = Some(thin(base, o, progress)?);
    }
    if on("corners") {
        res.corners = Some(corners(base, o, progress)?);
    }
    Ok(res)
}
