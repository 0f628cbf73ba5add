//! `tribofe sweep`: the paper's check over a grid of scene parameters, each point on the model
//! the convergence study proves adequate ([`super::check::converged_scene`]), with validity
//! verdicts. Points are independent: they run in parallel (rayon) and split into contiguous
//! shards whose tables concatenate into the unsharded one.

use super::check::{converged_scene, CheckResult};
use crate::error::{Error, Result};
use crate::fem::problem::Prepared;
use crate::linalg::solve::SolverOptions;
use crate::progress::Progress;
use crate::scene::{Overrides, Scene};
use rayon::prelude::*;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

/// A sweepable scene parameter; its CSV column is named after its flag with its unit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Param {
    Length,
    Thickness,
    Height,
    Young,
    Poisson,
}

impl Param {
    pub const ALL: [Param; 5] =
        [Param::Length, Param::Thickness, Param::Height, Param::Young, Param::Poisson];
    pub fn flag(self) -> &'static str {
        match self {
            Param::Length => "length",
            Param::Thickness => "thickness",
            Param::Height => "height",
            Param::Young => "young",
            Param::Poisson => "poisson",
        }
    }
    pub fn column(self) -> &'static str {
        match self {
            Param::Length => "length_m",
            Param::Thickness => "thickness_m",
            Param::Height => "height_m",
            Param::Young => "young_Pa",
            Param::Poisson => "poisson",
        }
    }
    /// The unit of [`Self::column`].
    pub fn unit(self) -> &'static str {
        match self {
            Param::Length | Param::Thickness | Param::Height => "m",
            Param::Young => "Pa",
            Param::Poisson => "1",
        }
    }
    pub fn get(self, s: &Scene) -> f64 {
        match self {
            Param::Length => s.block.length,
            Param::Thickness => s.block.thickness,
            Param::Height => s.loading.height,
            Param::Young => s.block.young,
            Param::Poisson => s.block.poisson,
        }
    }
    fn set(self, o: &mut Overrides, v: f64) {
        let slot = match self {
            Param::Length => &mut o.length,
            Param::Thickness => &mut o.thickness,
            Param::Height => &mut o.height,
            Param::Young => &mut o.young,
            Param::Poisson => &mut o.poisson,
        };
        *slot = Some(v);
    }
}

/// One swept parameter and its values, in order.
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    pub param: Param,
    pub values: Vec<f64>,
}

/// Parses `a`, a list `a,b,c`, or a range `a:b:n` (n points, ends included, linearly spaced)
/// or `a:b:ng` (geometrically spaced; a and b of the same sign, nonzero).
pub fn parse_values(s: &str) -> Result<Vec<f64>> {
    let bad = |msg: String| Error::input(format!("value list '{s}'"), msg);
    let num = |x: &str| -> Result<f64> {
        x.trim()
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| bad(format!("'{x}' is not a finite number")))
    };
    if s.contains(':') {
        let parts: Vec<&str> = s.split(':').collect();
        if parts.len() != 3 {
            return Err(bad("a range is START:END:N (linear) or START:END:Ng (geometric)".into()));
        }
        let (a, b) = (num(parts[0])?, num(parts[1])?);
        let last = parts[2].trim();
        let (count, geometric) = match last.strip_suffix('g') {
            Some(c) => (c, true),
            None => (last, false),
        };
        let n: usize =
            count.parse().map_err(|_| bad(format!("'{last}' is not a point count like 8 or 8g")))?;
        if n < 2 {
            return Err(bad("a range needs at least 2 points".into()));
        }
        if n > MAX_POINTS {
            return Err(bad(format!("{n} points: at most {MAX_POINTS} (each point is a solve)")));
        }
        if geometric && !(a * b > 0.0) {
            return Err(bad("a geometric range needs nonzero ends of the same sign".into()));
        }
        return Ok((0..n)
            .map(|i| {
                let f = i as f64 / (n - 1) as f64;
                if i == n - 1 {
                    b
                } else if geometric {
                    a * (b / a).powf(f)
                } else {
                    a + (b - a) * f
                }
            })
            .collect());
    }
    s.split(',').map(num).collect()
}

#[derive(Debug, Clone)]
pub struct SweepOptions {
    /// Solve each point on the converged model (graded QUA8, t/16 at the ends); otherwise on
    /// the scene's own mesh settings.
    pub converged: bool,
    /// Run only shard `i` of `n` (1-based), a contiguous block of points.
    pub shard: Option<(usize, usize)>,
    pub verdict: VerdictOptions,
    pub solver: SolverOptions,
    /// Also run the frictional interface at each point (`None`: the check only).
    pub friction: Option<FrictionSweep>,
    /// Checked before each point (and at each event of a frictional point).
    pub cancel: crate::Cancel,
}

/// The frictional quantities of each point: the static-kinetic law with fixed coefficients
/// (a rig's materials: g = 6 mu_d H/L then follows the geometry), on the QUA4 mesh of the
/// thin-layer validation runs (h = t along x, 2 elements through t, rigid plate), against the
/// paper's iteration for the same (r, g) ([`super::slide::compare_paper`]).
#[derive(Debug, Clone, Copy)]
pub struct FrictionSweep {
    pub mu_s: f64,
    pub mu_d: f64,
    pub rule: crate::law::Rule,
    /// Whole-interface slips to run (the last one's peak is reported as F_max).
    pub cycles: usize,
}

/// Refuses a frictional run's setting given without the frictional run (`given`: each
/// setting as the front end spells it, `--rule`, `--cycles`, and whether it was given).
pub fn check_friction_settings(friction: bool, given: &[(&str, bool)]) -> crate::error::Result<()> {
    match given.iter().find(|(_, on)| *on) {
        Some((key, _)) if !friction => Err(crate::error::Error::input(
            *key,
            "cannot act without --friction (the static and kinetic coefficients of the frictional run it sets up)",
        )),
        _ => Ok(()),
    }
}

impl FrictionSweep {
    /// The frictional scene of a point: its geometry and material on the QUA4 interface mesh.
    pub fn scene(base: &Scene) -> Scene {
        let mut s = base.clone();
        s.mesh.element = "qua4".into();
        s.mesh.grading = None;
        s.mesh.h_max = None;
        s.mesh.h = s.block.thickness;
        s.mesh.n_thick = Some(2);
        s
    }
}

impl Default for SweepOptions {
    fn default() -> Self {
        Self {
            converged: true,
            shard: None,
            verdict: VerdictOptions::default(),
            solver: SolverOptions::default(),
            friction: None,
            cancel: crate::Cancel::new(),
        }
    }
}

/// When the paper's model is said to hold at a point.
#[derive(Debug, Clone)]
pub struct VerdictOptions {
    /// Largest interior |p - model| and |tau - model|, in units of N/L.
    pub interior_tol: f64,
    /// Largest edge zone (pressure or shear, either end) as a fraction of L.
    pub edge_fraction: f64,
    /// The trailing edge must stay in compression up to this F/N (default: the largest
    /// requested ratio).
    pub tension_fn: Option<f64>,
}

impl Default for VerdictOptions {
    fn default() -> Self {
        Self { interior_tol: 0.02, edge_fraction: 0.05, tension_fn: None }
    }
}

/// The verdicts of one point and load case.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Verdict {
    /// Largest edge zone / L.
    pub edge_zone_fraction: f64,
    /// F/N at which the FE pressure one t inside the trailing end reaches zero (None: never),
    /// and the model's L / (6 H).
    pub tension_onset_fn: Option<f64>,
    pub tension_onset_fn_model: f64,
    /// Linear elements (qua4, tri3) at nu >= 0.49 lock.
    pub locking_prone: bool,
    pub interior_ok: bool,
    pub edges_ok: bool,
    pub tension_ok: bool,
}

impl Verdict {
    pub fn holds(&self) -> bool {
        self.interior_ok && self.edges_ok && self.tension_ok && !self.locking_prone
    }
}

/// One solved point: its index in the full grid, its scene and check result.
#[derive(Debug, Clone)]
pub struct Point {
    pub index: usize,
    pub scene: Scene,
    pub result: CheckResult,
    pub verdicts: Vec<Verdict>,
    /// The frictional run against the paper's iteration (with [`SweepOptions::friction`]).
    pub friction: Option<super::slide::PaperComparison>,
    /// Wall time of the point, s.
    pub wall: f64,
}

/// The points of the grid (first axis slowest), as override sets.
/// Largest number of points of a sweep (all axes together, before sharding): each point is a
/// check of several load cases, ~0.05-1 s, so the cap is days of computing and ~100 MB of
/// points, not an allocator abort.
pub const MAX_POINTS: usize = 100_000;

/// Whole-interface slips of a sweep's frictional run by default (`sweep --cycles`).
pub const DEFAULT_FRICTION_CYCLES: usize = 3;

/// What makes two runs one sweep, for its shards' run files (`[results.sweep]`): the grid
/// (each axis's parameter and values, in order) and every option that changes a row; the
/// shard itself, the cancel token and the solver's defaults aside. `sweep --merge` joins only
/// shards whose tables are equal (and whose scenes are).
pub fn identity(axes: &[Axis], o: &SweepOptions) -> toml::Table {
    use toml::Value;
    let mut t = toml::Table::new();
    let grid: Vec<Value> = axes
        .iter()
        .map(|a| {
            let mut ax = toml::Table::new();
            ax.insert("param".into(), Value::from(a.param.flag()));
            ax.insert("values".into(), Value::Array(a.values.iter().map(|&v| Value::from(v)).collect()));
            Value::Table(ax)
        })
        .collect();
    t.insert("grid".into(), Value::Array(grid));
    t.insert("converged".into(), Value::from(o.converged));
    t.insert("interior_tol".into(), Value::from(o.verdict.interior_tol));
    t.insert("edge_fraction".into(), Value::from(o.verdict.edge_fraction));
    if let Some(v) = o.verdict.tension_fn {
        t.insert("tension_fn".into(), Value::from(v));
    }
    if let Some(f) = &o.friction {
        let mut ft = toml::Table::new();
        ft.insert("mu_s".into(), Value::from(f.mu_s));
        ft.insert("mu_d".into(), Value::from(f.mu_d));
        ft.insert("rule".into(), Value::from(f.rule.name()));
        ft.insert("cycles".into(), Value::from(f.cycles as i64));
        t.insert("friction".into(), Value::Table(ft));
    }
    t
}

/// Number of grid points of `axes`, refused above [`MAX_POINTS`] before any allocation.
pub fn grid_size(axes: &[Axis]) -> Result<usize> {
    axes.iter()
        .try_fold(1usize, |acc, a| acc.checked_mul(a.values.len()).filter(|&t| t <= MAX_POINTS))
        .ok_or_else(|| {
            let dims: Vec<String> =
                axes.iter().map(|a| format!("{} --{}", a.values.len(), a.param.flag())).collect();
            Error::input(
                format!("--{}", axes.last().map_or("", |a| a.param.flag())),
                format!("a sweep of {} values is above {MAX_POINTS} points; sweep fewer values or shard it into several sweeps", dims.join(" x ")),
            )
        })
}

pub fn grid(axes: &[Axis]) -> Vec<Vec<(Param, f64)>> {
    let mut pts: Vec<Vec<(Param, f64)>> = vec![vec![]];
    for a in axes {
        pts = pts
            .into_iter()
            .flat_map(|p| {
                a.values.iter().map(move |&v| {
                    let mut q = p.clone();
                    q.push((a.param, v));
                    q
                })
            })
            .collect();
    }
    pts
}

/// The contiguous range of point indices of shard i of n (1-based) out of `total`.
pub fn shard_range(total: usize, shard: Option<(usize, usize)>) -> Result<std::ops::Range<usize>> {
    match shard {
        None => Ok(0..total),
        Some((i, n)) if n >= 1 && (1..=n).contains(&i) => Ok(total * (i - 1) / n..total * i / n),
        Some((i, n)) => Err(Error::input("--shard", format!("{i}/{n}: need 1 <= I <= N"))),
    }
}

/// Runs the sweep (or its shard) on `base` with every point's scene validated before any
/// solve; `progress` gets each finished point and the fraction of the points done (from any
/// thread).
pub fn run(base: &Scene, axes: &[Axis], o: &SweepOptions, progress: Progress<Point>) -> Result<Vec<Point>> {
    let mut seen = Vec::new();
    for a in axes {
        if seen.contains(&a.param) {
            return Err(Error::input(format!("--{}", a.param.flag()), "swept twice"));
        }
        if a.values.is_empty() {
            return Err(Error::input(format!("--{}", a.param.flag()), "no values"));
        }
        seen.push(a.param);
    }
    grid_size(axes)?;
    let all = grid(axes);
    let range = shard_range(all.len(), o.shard)?;
    // Validate every point first: a bad value is refused before any work.
    let scenes: Vec<(usize, Scene)> = range
        .map(|i| {
            let mut ov = Overrides::default();
            for &(p, v) in &all[i] {
                p.set(&mut ov, v);
            }
            let s =
                base.apply(&ov).map_err(|e| Error::input(format!("sweep point {}", i + 1), e.to_string()))?;
            let s = if o.converged { converged_scene(&s) } else { s };
            if s.mesh.file.is_none() {
                s.check_size().map_err(|e| Error::input(format!("sweep point {}", i + 1), e.to_string()))?;
            }
            Ok((i, s))
        })
        .collect::<Result<_>>()?;
    let law = match &o.friction {
        Some(f) => {
            if base.mesh.file.is_some() || base.plate.model != crate::scene::PlateModel::Rigid {
                return Err(Error::input(
                    "--friction",
                    "the frictional sweep meshes each point itself with a rigid plate: drop --mesh and --plate elastic",
                ));
            }
            if f.cycles == 0 {
                return Err(Error::input(
                    "--cycles",
                    "0: at least one whole-interface slip is needed for F_max",
                ));
            }
            Some(crate::law::Law::static_kinetic(f.mu_s, f.mu_d, f.rule)?)
        }
        None => None,
    };
    // The corrected model's inputs, its root search once per Poisson ratio.
    let mut decays: Vec<(f64, f64)> = Vec::new();
    let (done, total) = (AtomicUsize::new(0), scenes.len().max(1));
    for (_, s) in &scenes {
        let nu = s.block.plane_strain_nu();
        let k = match decays.iter().find(|d| d.0 == nu) {
            Some(d) => d.1,
            None => {
                let k = crate::analytical::thin_layer::Corrected::decay(nu)?;
                decays.push((nu, k));
                k
            }
        };
        crate::analytical::thin_layer::Corrected::with_decay(
            s.block.length,
            s.block.thickness,
            s.loading.height,
            nu,
            0.0,
            k,
        )?;
    }
    // Points that differ only in the block's material share the mesh, the constraint ties
    // pattern and so the symbolic analysis (`problem::Prepared`): one per group. Within a
    // group, points that differ only in H (rigid plate) share one factorisation: the unit
    // cases at a reference height plus a unit moment, combined per H
    // ([`super::check::run_heights`]). The reference is the first swept H (or the scene's), so
    // a shard computes its rows exactly as the whole sweep does.
    let h_ref = axes.iter().find(|a| a.param == Param::Height).map_or(base.loading.height, |a| a.values[0]);
    let rigid = |s: &Scene| s.plate.model == crate::scene::PlateModel::Rigid;
    let key = |s: &Scene, material: bool| {
        let mut k = s.clone();
        if !material {
            k.block.young = 0.0;
            k.block.poisson = 0.0;
        }
        if rigid(s) {
            k.loading.height = h_ref;
        }
        format!("{k:?}")
    };
    let mut groups: Vec<Vec<Vec<(usize, Scene)>>> = Vec::new();
    let mut keys: std::collections::HashMap<String, (usize, usize)> = std::collections::HashMap::new();
    let mut sub_keys: std::collections::HashMap<String, (usize, usize)> = std::collections::HashMap::new();
    for (i, s) in scenes {
        let (g, _) = *keys.entry(key(&s, false)).or_insert_with(|| {
            groups.push(Vec::new());
            (groups.len() - 1, 0)
        });
        let (_, j) = *sub_keys.entry(key(&s, true)).or_insert_with(|| {
            groups[g].push(Vec::new());
            (g, groups[g].len() - 1)
        });
        groups[g][j].push((i, s));
    }
    let prepared: Vec<Prepared> = groups
        .par_iter()
        .map(|g| {
            let mut s = g[0][0].1.clone();
            if rigid(&s) {
                s.loading.height = h_ref;
            }
            super::check::prepare(&s, &o.solver)
        })
        .collect::<Result<_>>()?;
    let subgroups: Vec<(usize, Vec<(usize, Scene)>)> =
        groups.into_iter().enumerate().flat_map(|(g, subs)| subs.into_iter().map(move |s| (g, s))).collect();
    let solved: Vec<Vec<Point>> = subgroups
        .into_par_iter()
        .map(|(g, sub)| {
            o.cancel.check()?;
            let clock = Instant::now();
            let first = &sub[0].1;
            let k = decays.iter().find(|d| d.0 == first.block.plane_strain_nu()).map(|d| d.1);
            let results = if rigid(first) {
                let mut reference = first.clone();
                reference.loading.height = h_ref;
                let scenes: Vec<Scene> = sub.iter().map(|p| p.1.clone()).collect();
                super::check::run_heights(&reference, &scenes, &o.solver, Some(&prepared[g]), k)?
            } else {
                sub.iter()
                    .map(|(_, scene)| {
                        let sm = scene.build()?;
                        let r = super::check::run_model_with_decay(
                            scene,
                            sm,
                            0.0,
                            &o.solver,
                            Some(&prepared[g]),
                            k,
                        );
                        Ok(r?.0)
                    })
                    .collect::<Result<Vec<_>>>()?
            };
            // The shared solve's time is split evenly over the subgroup's points.
            let shared = clock.elapsed().as_secs_f64() / sub.len() as f64;
            sub.into_iter()
                .zip(results)
                .map(|((index, scene), mut result)| {
                    o.cancel.check()?;
                    let clock = Instant::now();
                    result.displacements.clear();
                    let verdicts = result.cases.iter().map(|c| verdict(&result, c, &o.verdict)).collect();
                    let friction = match (&o.friction, law) {
                        (Some(f), Some(law)) => {
                            let so = super::slide::SlideOptions {
                                law,
                                cycles: f.cycles,
                                cancel: o.cancel.clone(),
                                ..Default::default()
                            };
                            let r = super::slide::run(&FrictionSweep::scene(&scene), &so, Progress::none())?;
                            super::slide::compare_paper(&r)
                        }
                        _ => None,
                    };
                    let wall = shared + clock.elapsed().as_secs_f64();
                    let p = Point { index, scene, result, verdicts, friction, wall };
                    let k = done.fetch_add(1, Ordering::Relaxed) + 1;
                    progress.item(&p, k as f64 / total as f64);
                    Ok(p)
                })
                .collect::<Result<Vec<Point>>>()
        })
        .collect::<Result<_>>()?;
    let mut points: Vec<Point> = solved.into_iter().flatten().collect();
    points.sort_by_key(|p| p.index);
    Ok(points)
}

fn verdict(res: &CheckResult, c: &super::check::CaseResult, o: &VerdictOptions) -> Verdict {
    let s = &res.scene;
    let (l, t, h) = (s.block.length, s.block.thickness, s.loading.height);
    let m = &c.metrics;
    let widest = m.edge_p_t.iter().chain(&m.edge_tau_t).flatten().fold(0.0f64, |a, &b| a.max(b));
    let edge_zone_fraction = widest * t / l;
    let u = &res.unit;
    let x0 = -0.5 + t / l;
    let pn = crate::numeric::interpolate(&u.x_over_l, &u.p_per_n, x0);
    let pf = crate::numeric::interpolate(&u.x_over_l, &u.p_per_f, x0);
    let tension_onset_fn = if pf < 0.0 { Some(-pn / pf) } else { None };
    let fn_check = o.tension_fn.unwrap_or_else(|| s.loading.fn_ratios.iter().cloned().fold(0.0, f64::max));
    let el = s.mesh.element.as_str();
    Verdict {
        edge_zone_fraction,
        tension_onset_fn,
        tension_onset_fn_model: l / (6.0 * h),
        locking_prone: matches!(el, "qua4" | "tri3") && s.block.poisson >= 0.49,
        interior_ok: m.interior_dev_p <= o.interior_tol && m.interior_dev_tau <= o.interior_tol,
        edges_ok: edge_zone_fraction <= o.edge_fraction,
        tension_ok: tension_onset_fn.is_none_or(|r| r > fn_check),
    }
}
