//! Numerical stability of the paper's check (issue 7), five studies:
//! `plate` (stiff elastic plate vs the exact rigid one: modelling error against round-off),
//! `nu` (near-incompressibility: locking per element), `shape` (elongated and distorted
//! elements), `thin` (t/L -> 0 at a fixed number of elements through the thickness) and
//! `corners` (singular end nodes vs converging integrated quantities).

use crate::error::{Error, Result};
use crate::linalg::solve::SolverOptions;
use crate::numeric::interpolate;
use crate::scene::{PlateModel, Scene};
use crate::studies::check::{self, CheckResult};
use crate::studies::convergence::{self, zone_errors, Family, StudyOptions, ZoneErrors};
use std::collections::HashMap;
use std::time::Instant;

pub const STUDIES: [&str; 5] = ["plate", "nu", "shape", "thin", "corners"];

/// The studies' progress: a message (a short description) once per solved run.
pub use crate::progress::Progress;

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
    /// Stops the studies before and after each solve.
    pub cancel: crate::Cancel,
}

/// The finest corner mesh's elements through the thickness (`--corner-max`).
pub const DEFAULT_CORNER_MAX: usize = 32;
/// The qua9 reference's elements through the thickness (`--n-ref`).
pub const DEFAULT_N_REF: usize = 16;

/// The corner study's meshes: 1, 2, 4, .. elements through the thickness, up to `max`.
pub fn corner_meshes(max: usize) -> Vec<usize> {
    std::iter::successors(Some(1usize), |n| n.checked_mul(2)).take_while(|&n| n <= max).collect()
}

/// Refuses a sizing option given for a study that is not run (`given`: the option's name as
/// the caller typed it, when given): it could not act.
pub fn refuse_idle(studies: &[String], n_ref: Option<&str>, corner_max: Option<&str>) -> Result<()> {
    let runs = |names: &[&str]| studies.iter().any(|s| names.contains(&s.as_str()));
    for (given, needs) in [(n_ref, &["nu", "shape"][..]), (corner_max, &["corners"])] {
        if let Some(name) = given.filter(|_| !runs(needs)) {
            return Err(Error::input(
                name,
                format!("cannot act: it sizes the {} study, not run here (--study)", needs.join(" and ")),
            ));
        }
    }
    Ok(())
}

impl Options {
    /// Reports a finished solve and stops here once the run is cancelled.
    fn done(&self, progress: Progress, message: &str) -> Result<()> {
        progress.message(message);
        self.cancel.check()
    }
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
            n_ref: DEFAULT_N_REF,
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
            corner_n_thick: corner_meshes(DEFAULT_CORNER_MAX),
            fn_ratio: 0.82,
            cancel: crate::Cancel::new(),
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

mod corners;
mod nu;
mod plate;
mod shape;
mod thin;

pub use corners::*;
pub use nu::*;
pub use plate::*;
pub use shape::*;
pub use thin::*;

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

    /// Reference for the base scene at Poisson's ratio `nu` (load cases F/N = 0 and `o.fn_ratio`).
    pub fn get(&mut self, nu: f64, o: &Options, progress: Progress) -> Result<&CheckResult> {
        if !self.cache.contains_key(&nu.to_bits()) {
            o.cancel.check()?;
            let mut s = self.base.clone();
            s.block.poisson = nu;
            s.mesh.h = s.block.thickness / self.n_ref as f64;
            s.mesh.element = "qua9".into();
            (s.mesh.grading, s.mesh.h_max) = (None, None);
            s.mesh.n_thick = None;
            s.loading.fn_ratios = vec![0.0, o.fn_ratio];
            let (r, _) = check::run(&s, &SolverOptions::default())?;
            o.done(progress, &format!("reference qua9 t/{} nu {nu}", self.n_ref))?;
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
    o.cancel.check()?;
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
