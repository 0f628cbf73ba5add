//! The block's ends on the frictional interface: how far they pre-slip under N alone (which
//! must converge under refinement, unlike the bonded end values), and whether the trailing
//! end opens under the drive before the first precursor, over t/L and H/L.

use crate::cancel::Cancel;
use crate::error::{Error, Result};
use crate::interface::condense::condense;
use crate::interface::events::EventKind;
use crate::interface::events::{NodeState, Phase};
use crate::law::{Law, Rule};
use crate::linalg::solve::SolverOptions;
use crate::progress::Progress;
use crate::scene::Scene;
use crate::studies::slide::{compare_paper, run_condensed, SlideOptions, SlideResult};
use rayon::prelude::*;
use std::sync::atomic::{AtomicUsize, Ordering};

/// Pre-slip under N alone, on one mesh.
#[derive(Debug, Clone)]
pub struct Preslip {
    pub mu: f64,
    /// Elements through the thickness (t/h) and interface nodes.
    pub t_over_h: f64,
    pub nodes: usize,
    /// Slipping length from the left and right end, in units of t: from the end to midway
    /// between the last slipping and the first stuck node (0 when the end node sticks).
    pub extent_t: [f64; 2],
}

/// The meshes of both studies: uniform with h = t/k (`grading` None or 1), or graded from
/// h = t/k at both ends by `grading` per element up to [`H_MAX_OVER_T`] t in the middle. Both
/// studies look at the ends, so the grading resolves them for a fraction of the unknowns: a
/// uniform t/h = 16 on the paper's 0.4 m block condenses 3201 interface nodes out of 1e5
/// unknowns (10 GB); graded, about 500.
pub const H_MAX_OVER_T: f64 = 0.5;

/// `scene` with k elements through its thickness and the end mesh of [`H_MAX_OVER_T`].
fn meshed(scene: &Scene, k: usize, grading: Option<f64>) -> Scene {
    let t = scene.block.thickness;
    let mut sc = scene.clone();
    sc.mesh.h = t / k as f64;
    sc.mesh.n_thick = Some(k);
    match grading {
        Some(r) if r > 1.0 && sc.mesh.h < H_MAX_OVER_T * t => {
            sc.mesh.grading = Some(r);
            sc.mesh.h_max = Some(H_MAX_OVER_T * t);
        }
        _ => {
            sc.mesh.grading = None;
            sc.mesh.h_max = None;
        }
    }
    sc
}

/// Pre-slip extents at both ends for each coulomb `mu` and each refinement t/h (the scene's
/// other values kept; the mesh uniform with h = t / (t/h)).
pub fn preslip(scene: &Scene, mus: &[f64], t_over_h: &[usize]) -> Result<Vec<Preslip>> {
    preslip_graded(scene, mus, t_over_h, None, &Cancel::new(), Progress::none())
}

/// [`preslip`] on the meshes of `meshed` (`grading` None: uniform); `progress` gets the
/// fraction of the meshes done after each; `cancel` stops it at the next mesh or event.
pub fn preslip_graded(
    scene: &Scene,
    mus: &[f64],
    t_over_h: &[usize],
    grading: Option<f64>,
    cancel: &Cancel,
    progress: Progress,
) -> Result<Vec<Preslip>> {
    let t = scene.block.thickness;
    let mut rows = Vec::new();
    for (i, &k) in t_over_h.iter().enumerate() {
        cancel.check()?;
        let sc = meshed(scene, k, grading);
        sc.validate()?;
        sc.check_size()?;
        let c = condense(&sc, &SolverOptions::default())?;
        let found: Vec<Preslip> =
            mus.par_iter()
                .map(|&mu| {
                    // Any X ends the normal phase; the state after N alone is the last normal one.
                    let o = SlideOptions {
                        law: Law::coulomb(mu)?,
                        x_max: Some(1e-9 * t),
                        cancel: cancel.clone(),
                        ..Default::default()
                    };
                    let r = run_condensed(&sc, c.clone(), 0.0, &o, Progress::none())?;
                    let st =
                        r.run.states.iter().rfind(|s| s.phase == Phase::Normal).ok_or_else(|| {
                            Error::input("edges", "the run recorded no state under N alone")
                        })?;
                    // From an end inwards: the distance to midway between the last slipping node
                    // and the first that does not slip.
                    let ext = |order: Vec<usize>| -> f64 {
                        let end = c.x[order[0]];
                        let k =
                            order.iter().take_while(|&&i| matches!(st.states[i], NodeState::Slip(_))).count();
                        match k {
                            0 => 0.0,
                            k if k == order.len() => c.l / t,
                            k => (0.5 * (c.x[order[k - 1]] + c.x[order[k]]) - end).abs() / t,
                        }
                    };
                    Ok(Preslip {
                        mu,
                        t_over_h: k as f64,
                        nodes: c.n,
                        extent_t: [ext((0..c.n).collect()), ext((0..c.n).rev().collect())],
                    })
                })
                .collect::<Result<_>>()?;
        rows.extend(found);
        progress.fraction((i + 1) as f64 / t_over_h.len() as f64);
    }
    Ok(rows)
}

/// The trailing end under the drive (static-kinetic, one geometry).
#[derive(Debug, Clone)]
pub struct Opening {
    pub t_over_l: f64,
    /// Elements through the thickness.
    pub t_over_h: f64,
    pub h_over_l: f64,
    /// The paper's g = 6 mu_d H/L, and its first precursor force F_1/(mu_s N).
    pub g: f64,
    pub f1_model: f64,
    /// F/(mu_s N) when a node first opens (None: none opens before the first whole slip),
    /// and the open length from the trailing end then, in units of t.
    pub f_open: Option<f64>,
    pub open_length_t: Option<f64>,
    /// F/(mu_s N) of the first precursor longer than 5 t (None: none before the first whole slip).
    pub f1_fe: Option<f64>,
    /// Largest open length from the trailing end before the first whole slip, in units of t.
    pub max_open_t: f64,
    /// Length of the element at the trailing end, in units of t: an open length reported
    /// with a single open node lies below it (the midpoint rule gives half of it).
    pub end_element_t: f64,
    /// Open nodes when the end first opens, and at most before the first whole slip (1: the
    /// open length is below the end element, not resolved).
    pub open_nodes: Option<usize>,
    pub max_open_nodes: usize,
}

impl Opening {
    /// The trailing end opens before the first precursor (or opens with none at all).
    pub fn opens_first(&self) -> bool {
        match (self.f_open, self.f1_fe) {
            (Some(o), Some(f)) => o < f,
            (Some(_), None) => true,
            _ => false,
        }
    }
}

/// Open nodes from the trailing end of a state (reads the per-node states: the edge runs
/// keep them, [`SlideOptions::keep_states`] at its default).
fn open_nodes(r: &SlideResult, k: usize) -> usize {
    r.run.states[k].states.iter().take_while(|s| **s == NodeState::Open).count()
}

/// Open length from the trailing end of a state, in units of t.
fn open_length_t(r: &SlideResult, k: usize) -> f64 {
    let c = &r.condensed;
    let m = open_nodes(r, k);
    if m == 0 {
        0.0
    } else {
        (0.5 * (c.x[m - 1] + c.x[m.min(c.n - 1)]) - c.x[0]) / c.t
    }
}

/// For each t/L, refinement t/h (2: the paper's 1 mm on 2 mm) and H/L (one condensation per
/// mesh), static-kinetic with `mu_s`, `mu_d`, `rule`, driven to the first whole-interface slip.
pub fn opening(
    scene: &Scene,
    mu_s: f64,
    mu_d: f64,
    rule: Rule,
    t_over_l: &[f64],
    t_over_h: &[usize],
    h_over_l: &[f64],
) -> Result<Vec<Opening>> {
    opening_graded(
        scene,
        mu_s,
        mu_d,
        rule,
        t_over_l,
        t_over_h,
        h_over_l,
        None,
        &Cancel::new(),
        Progress::none(),
    )
}

/// [`opening`] on the meshes of `meshed` (`grading` None: uniform); `progress` gets the
/// fraction of the runs done after each (from any thread); `cancel` stops it at the next
/// mesh or event.
#[allow(clippy::too_many_arguments)]
pub fn opening_graded(
    scene: &Scene,
    mu_s: f64,
    mu_d: f64,
    rule: Rule,
    t_over_l: &[f64],
    t_over_h: &[usize],
    h_over_l: &[f64],
    grading: Option<f64>,
    cancel: &Cancel,
    progress: Progress,
) -> Result<Vec<Opening>> {
    let law = Law::static_kinetic(mu_s, mu_d, rule)?;
    let l = scene.block.length;
    let mut rows = Vec::new();
    let (done, total) = (AtomicUsize::new(0), t_over_l.len() * t_over_h.len() * h_over_l.len());
    for (&tl, &k) in t_over_l.iter().flat_map(|tl| t_over_h.iter().map(move |k| (tl, k))) {
        cancel.check()?;
        let mut sc = scene.clone();
        sc.block.thickness = tl * l;
        let sc = meshed(&sc, k, grading);
        sc.validate()?;
        sc.check_size()?;
        let c = condense(&sc, &SolverOptions::default())?;
        let found: Vec<Opening> = h_over_l
            .par_iter()
            .map(|&hl| {
                let mut s = sc.clone();
                s.loading.height = hl * l;
                s.validate()?;
                let o = SlideOptions { law, cycles: 1, cancel: cancel.clone(), ..Default::default() };
                let r = run_condensed(&s, c.clone(), 0.0, &o, Progress::none())?;
                let cmp = compare_paper(&r).ok_or_else(|| Error::input("edges", "no paper comparison"))?;
                let first_slide = r
                    .run
                    .events
                    .iter()
                    .position(|e| e.kind == EventKind::Sliding)
                    .unwrap_or(r.run.events.len());
                let k_open = (0..first_slide).find(|&k| r.run.states[k].states[0] == NodeState::Open);
                let row = Ok(Opening {
                    t_over_l: tl,
                    t_over_h: k as f64,
                    h_over_l: hl,
                    g: cmp.g,
                    f1_model: cmp.f1,
                    f_open: k_open.map(|k| r.run.states[k].f / (mu_s * o.n_force)),
                    open_length_t: k_open.map(|k| open_length_t(&r, k)),
                    f1_fe: cmp.f1_fe,
                    max_open_t: (0..first_slide).map(|k| open_length_t(&r, k)).fold(0.0, f64::max),
                    end_element_t: (c.x[1] - c.x[0]) / c.t,
                    open_nodes: k_open.map(|k| open_nodes(&r, k)),
                    max_open_nodes: (0..first_slide).map(|k| open_nodes(&r, k)).max().unwrap_or(0),
                });
                let i = done.fetch_add(1, Ordering::Relaxed) + 1;
                progress.fraction(i as f64 / total as f64);
                row
            })
            .collect::<Result<_>>()?;
        rows.extend(found);
    }
    Ok(rows)
}

/// The `edges` command's defaults (`tribofe edges`, `tribofe.edges`): the pre-slip study's
/// coulomb coefficients and elements through t; the opening study's coefficients (the
/// paper's r = 0.9, g = 0.35 at H/L = 0.1: mu_s = 0.6481, mu_d = 0.5833), rule, t/L, elements
/// through t and H/L; the end grading of both.
pub const DEFAULT_MU: [f64; 2] = [0.3, 0.65];
pub const DEFAULT_REFINE: [usize; 4] = [2, 4, 8, 16];
pub const DEFAULT_MU_S: f64 = 0.35 / 0.6 / 0.9;
pub const DEFAULT_MU_D: f64 = 0.35 / 0.6;
pub const DEFAULT_RULE: Rule = Rule::Paper;
pub const DEFAULT_T_OVER_L: [f64; 4] = [0.02, 0.01, 0.005, 0.0025];
pub const DEFAULT_OPEN_REFINE: [usize; 1] = [8];
pub const DEFAULT_END_GRADING: f64 = 1.05;
pub const DEFAULT_H_OVER_L: [f64; 4] = [0.025, 0.05, 0.1, 0.2];

/// Most values of a list (or opening runs): each is a mesh or a run of seconds.
pub const MAX_LIST: usize = 1000;

/// Both studies' parameters (the command's flags, [`Default`] its defaults).
#[derive(Debug, Clone, PartialEq)]
pub struct EdgesOptions {
    /// Coulomb coefficients and elements through t (t/h) of the pre-slip study.
    pub mu: Vec<f64>,
    pub refine: Vec<usize>,
    /// Static-kinetic coefficients and rule, t/L, elements through t and H/L of the opening
    /// study.
    pub mu_s: f64,
    pub mu_d: f64,
    pub rule: Rule,
    pub t_over_l: Vec<f64>,
    pub open_refine: Vec<usize>,
    pub h_over_l: Vec<f64>,
    /// Growth ratio of the element length from the ends (1: uniform meshes).
    pub end_grading: f64,
}

impl Default for EdgesOptions {
    fn default() -> Self {
        EdgesOptions {
            mu: DEFAULT_MU.to_vec(),
            refine: DEFAULT_REFINE.to_vec(),
            mu_s: DEFAULT_MU_S,
            mu_d: DEFAULT_MU_D,
            rule: DEFAULT_RULE,
            t_over_l: DEFAULT_T_OVER_L.to_vec(),
            open_refine: DEFAULT_OPEN_REFINE.to_vec(),
            h_over_l: DEFAULT_H_OVER_L.to_vec(),
            end_grading: DEFAULT_END_GRADING,
        }
    }
}

impl EdgesOptions {
    /// The opening study's runs (t/L x t/h x H/L).
    pub fn runs(&self) -> usize {
        self.t_over_l.len().saturating_mul(self.open_refine.len()).saturating_mul(self.h_over_l.len())
    }

    /// Refuses what cannot run on `scene`, naming the flag, before any work.
    pub fn check(&self, scene: &Scene) -> Result<()> {
        if scene.mesh.file.is_some() {
            return Err(Error::input("--mesh", "`edges` builds its own meshes; a mesh file cannot act"));
        }
        for (flag, ks) in [("--refine", &self.refine), ("--open-refine", &self.open_refine)] {
            if let Some(k) = ks.iter().find(|&&k| k < 2) {
                return Err(Error::input(
                    flag,
                    format!("{k}: the condensation needs at least 2 elements through t"),
                ));
            }
        }
        if !(self.end_grading.is_finite() && (1.0..=2.0).contains(&self.end_grading)) {
            return Err(Error::input(
                "--end-grading",
                format!("{}: a growth ratio in [1, 2] (1: uniform meshes)", self.end_grading),
            ));
        }
        for (flag, n) in [("--mu", self.mu.len()), ("--refine", self.refine.len())] {
            if n > MAX_LIST {
                return Err(Error::input(flag, format!("{n} values: at most {MAX_LIST}")));
            }
        }
        let runs = self.runs();
        if runs > MAX_LIST {
            return Err(Error::input(
                "--t-over-l / --open-refine / --h-over-l",
                format!("{runs} opening runs: at most {MAX_LIST}"),
            ));
        }
        Ok(())
    }

    /// The end grading as the meshes take it (None: uniform).
    pub fn grading(&self) -> Option<f64> {
        (self.end_grading > 1.0).then_some(self.end_grading)
    }
}

/// Both studies on `scene` (its mesh keys do not act: each study meshes its own blocks; a
/// mesh file is refused): the pre-slip extents, then the openings; `progress` gets the
/// fraction of the meshes and runs done; `cancel` stops it at the next mesh or event.
pub fn run(
    scene: &Scene,
    o: &EdgesOptions,
    cancel: &Cancel,
    progress: Progress,
) -> Result<(Vec<Preslip>, Vec<Opening>)> {
    o.check(scene)?;
    let (pre_n, total) = (o.refine.len() as f64, (o.refine.len() + o.runs()).max(1) as f64);
    let pre = preslip_graded(
        scene,
        &o.mu,
        &o.refine,
        o.grading(),
        cancel,
        Progress::new(&|t| progress.fraction(t.fraction.unwrap_or(0.0) * pre_n / total)),
    )?;
    let open = opening_graded(
        scene,
        o.mu_s,
        o.mu_d,
        o.rule,
        &o.t_over_l,
        &o.open_refine,
        &o.h_over_l,
        o.grading(),
        cancel,
        Progress::new(&|t| progress.fraction((pre_n + t.fraction.unwrap_or(0.0) * (total - pre_n)) / total)),
    )?;
    Ok((pre, open))
}
