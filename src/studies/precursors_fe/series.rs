//! The one-parameter series of FE fig. 4 runs (rule `paper`) that test the model's limits:
//! thin layer ([`thin_layer`]), height of the drive ([`heights`]) and event rule against D_c
//! ([`dc_series`]), with the extrapolation of their limits ([`richardson`],
//! [`thin_layer_limits`]).

use super::{fig4_on, sk, Fig4};
use crate::error::Result;
use crate::interface::condense::condense;
use crate::law::{Law, Rule};
use crate::linalg::solve::SolverOptions;
use crate::progress::Progress;
use crate::scene::Scene;
use crate::studies::slide::{coefficients_from_rg, PaperComparison, SlideOptions};
/// One run of a one-parameter series of FE fig. 4 runs (rule `paper`): the parameter's value,
/// the run (or why it was refused) and its wall time (condensation and events), s.
pub struct SeriesRow {
    pub value: f64,
    pub fig4: Result<Fig4>,
    pub seconds: f64,
}

/// A row's run refused by the host's cancel ends the whole series (other refusals are the
/// row's result).
pub(super) fn interrupted(fig4: &Result<Fig4>) -> Result<()> {
    match fig4 {
        Err(crate::Error::Interrupted) => Err(crate::Error::Interrupted),
        _ => Ok(()),
    }
}

/// Largest t/L of a thin-layer series: the block is then still a layer whose end zones
/// (about 2 t at each end, which the model leaves out) cover at most 40 % of its length.
pub const MAX_T_OVER_L: f64 = 0.1;

/// The thin-layer limit (issue 18): the `paper` rule at (r, g) on blocks of thickness
/// t = (t/L) L at the scene's L and H/L, a regular mesh with h = t and 2 elements through t
/// (the meshes of validation/friction; a scene's mesh file is refused), one cycle each,
/// thickest first; `progress` gets the fraction done after each; `cancel` stops it at the next
/// event.
pub fn thin_layer(
    scene: &Scene,
    r: f64,
    g: f64,
    t_over_l: &[f64],
    cancel: &crate::Cancel,
    progress: Progress,
) -> Result<Vec<SeriesRow>> {
    if let Some(file) = &scene.mesh.file {
        return Err(crate::Error::input(
            "--t-over-l",
            format!("meshes its own blocks, one per t/L; drop the mesh file {}", file.display()),
        ));
    }
    let mut ts = t_over_l.to_vec();
    ts.sort_by(|a, b| b.total_cmp(a));
    let mut scenes = Vec::with_capacity(ts.len());
    for &tl in &ts {
        if !(tl.is_finite() && tl > 0.0 && tl <= MAX_T_OVER_L) {
            return Err(crate::Error::input(
                "--t-over-l",
                format!(
                    "t/L = {tl}: need 0 < t/L <= {MAX_T_OVER_L}, where the block is a thin layer: the model leaves out the end zones (about 2 t at each end, src/analytical/thin_layer.rs), which then cover at most 40 % of L; the series extrapolates to t/L -> 0 (validated at t/L = 0.02 .. 0.000625)"
                ),
            ));
        }
        let mut s = scene.clone();
        s.block.thickness = tl * scene.block.length;
        s.mesh.h = s.block.thickness;
        s.mesh.n_thick = Some(2);
        (s.mesh.grading, s.mesh.h_max) = (None, None);
        s.validate().map_err(|e| crate::Error::input("--t-over-l", format!("t/L = {tl}: {e}")))?;
        crate::scene::limits::check_interface((s.block.length / s.mesh.h).round() as usize + 1)?;
        scenes.push(s);
    }
    let mut rows = Vec::with_capacity(ts.len());
    let total = ts.len();
    for (tl, s) in ts.into_iter().zip(&scenes) {
        let clock = std::time::Instant::now();
        let c = condense(s, &SolverOptions::default())?;
        let fig4 = fig4_on(
            s,
            &c,
            r,
            g,
            SlideOptions {
                law: sk(s, r, g, Rule::Paper)?,
                cycles: 1,
                cancel: cancel.clone(),
                ..Default::default()
            },
            Progress::none(),
        );
        interrupted(&fig4)?;
        rows.push(SeriesRow { value: tl, fig4, seconds: clock.elapsed().as_secs_f64() });
        progress.fraction(rows.len() as f64 / total as f64);
    }
    Ok(rows)
}

/// The height of the drive (issue 18): the `paper` rule with the coefficients of (r, g) at
/// the scene's H kept fixed while H/L takes the given values (so g = 6 mu_d H/L moves with
/// it; each must stay in (0, 1)); one condensation, one cycle per height; `progress` and
/// `cancel` as in [`thin_layer`].
pub fn heights(
    scene: &Scene,
    r: f64,
    g: f64,
    h_over_l: &[f64],
    cancel: &crate::Cancel,
    progress: Progress,
) -> Result<Vec<SeriesRow>> {
    let (_, mu_d) = coefficients_from_rg(scene, r, g)?;
    let l = scene.block.length;
    let mut hs = h_over_l.to_vec();
    hs.sort_by(f64::total_cmp);
    let mut scenes = Vec::with_capacity(hs.len());
    for &hl in &hs {
        let gh = 6.0 * mu_d * hl;
        if !(hl > 0.0 && gh < 1.0) {
            return Err(crate::Error::input(
                "--h-over-l",
                format!(
                    "H/L = {hl} gives g = 6 mu_d H/L = {gh:.4} with mu_d = {mu_d:.4}; need 0 < H/L < {:.4}",
                    1.0 / (6.0 * mu_d)
                ),
            ));
        }
        let mut s = scene.clone();
        s.loading.height = hl * l;
        s.validate().map_err(|e| crate::Error::input("--h-over-l", format!("H/L = {hl}: {e}")))?;
        scenes.push(s);
    }
    let c = condense(scene, &SolverOptions::default())?;
    let (mut rows, total) = (Vec::with_capacity(hs.len()), hs.len());
    for (hl, s) in hs.into_iter().zip(scenes) {
        let clock = std::time::Instant::now();
        let gh = 6.0 * mu_d * hl;
        let fig4 = fig4_on(
            &s,
            &c,
            r,
            gh,
            SlideOptions {
                law: sk(&s, r, gh, Rule::Paper)?,
                cycles: 1,
                cancel: cancel.clone(),
                ..Default::default()
            },
            Progress::none(),
        );
        interrupted(&fig4)?;
        rows.push(SeriesRow { value: hl, fig4, seconds: clock.elapsed().as_secs_f64() });
        progress.fraction(rows.len() as f64 / total as f64);
    }
    Ok(rows)
}

/// Observed convergence order and extrapolated limit of a quantity from its last three values
/// at refinement parameters x (e.g. t/L) sorted from coarse to fine: with differences
/// d1 = v1 - v2, d2 = v2 - v3, the order p = ln(d1/d2)/ln(x1/x2) (assuming x1/x2 = x2/x3) and
/// the limit v3 - d2/((x2/x3)^p - 1). None when the differences do not shrink at an order
/// above 1/4 (no asymptotic range: the last value is then the best estimate).
pub fn richardson(points: &[(f64, f64)]) -> Option<(f64, f64)> {
    let [(x1, v1), (x2, v2), (x3, v3)] = points.get(points.len().checked_sub(3)?..)? else {
        return None;
    };
    let (d1, d2) = (v1 - v2, v2 - v3);
    if d1 == 0.0 || d2 == 0.0 || d1.signum() != d2.signum() || d2.abs() >= d1.abs() {
        return None;
    }
    let p = (d1 / d2).ln() / (x1 / x2).ln();
    let q = (x2 / x3).powf(p);
    // Below order 1/4 the extrapolation amplifies round-off and node-spacing jumps.
    (p.is_finite() && p > 0.25).then(|| (p, v3 - d2 / (q - 1.0)))
}

/// Event rule and D_c (issue 18, assumption 4): at (r, g) on `scene`, the `paper` rule (row
/// value 0) and then slip-weakening with each D_c (m, largest first), one condensation, one
/// cycle each; a run over `max_events` is refused on its own row (every row refused: the
/// first refusal); every D_c and the cap are checked before any work; `progress` and
/// `cancel` as in [`thin_layer`].
#[allow(clippy::too_many_arguments)]
pub fn dc_series(
    scene: &Scene,
    r: f64,
    g: f64,
    dcs: &[f64],
    max_events: usize,
    cancel: &crate::Cancel,
    progress: Progress,
) -> Result<Vec<SeriesRow>> {
    let (ms, md) = coefficients_from_rg(scene, r, g)?;
    // Every D_c and the cap checked before the condensation, as the runs will see them.
    for &d in dcs {
        let o = SlideOptions {
            law: Law::slip_weakening(ms, md, d)?,
            cycles: 1,
            max_events,
            ..Default::default()
        };
        crate::studies::slide::check_options(scene, &o)?;
    }
    if max_events == 0 {
        return Err(crate::Error::input("--max-events", "0: need at least one event per run"));
    }
    let mut ds = dcs.to_vec();
    ds.sort_by(|a, b| b.total_cmp(a));
    let laws = std::iter::once(Ok((0.0, sk(scene, r, g, Rule::Paper)?)))
        .chain(ds.iter().map(|&d| Law::slip_weakening(ms, md, d).map(|l| (d, l))))
        .collect::<Result<Vec<_>>>()?;
    let c = condense(scene, &SolverOptions::default())?;
    let (mut rows, total) = (Vec::with_capacity(laws.len()), laws.len());
    for (d, law) in laws {
        let clock = std::time::Instant::now();
        let o = SlideOptions { law, cycles: 1, max_events, cancel: cancel.clone(), ..Default::default() };
        let fig4 = fig4_on(scene, &c, r, g, o, Progress::none());
        interrupted(&fig4)?;
        rows.push(SeriesRow { value: d, fig4, seconds: clock.elapsed().as_secs_f64() });
        progress.fraction(rows.len() as f64 / total as f64);
    }
    if rows.iter().all(|r| r.fig4.is_err()) {
        // Nothing to tabulate or draw: the first refusal says why.
        return rows.into_iter().find_map(|r| r.fig4.err()).map_or(Ok(Vec::new()), Err);
    }
    Ok(rows)
}

/// The length scales of slip-weakening with D_c on `scene` (N = n_force, p = N/L,
/// G = E/(2(1 + nu))): kappa = G D_c/((mu_s - mu_d) p t), the thin-layer stability number
/// (stable above 1); the nucleation length L_c = kappa t over the element size h; and the
/// Appendix's threshold (E/p)(D_c/t)(mu_s - mu_d)/(2 mu_d), the excess mu(x) - mu_d below
/// which its Griffith argument lets a front arrest.
pub fn dc_scales(scene: &Scene, mu_s: f64, mu_d: f64, n_force: f64, dc: f64) -> (f64, f64, f64) {
    let b = &scene.block;
    let p = n_force / b.length;
    let lc = b.young / (2.0 * (1.0 + b.poisson)) * dc / ((mu_s - mu_d) * p);
    (lc / b.thickness, lc / scene.mesh.h, b.young / p * dc / b.thickness * (mu_s - mu_d) / (2.0 * mu_d))
}

/// A thin-layer series' F_1, x_1 and F_max against t/L: the model's value, the observed order
/// and Richardson limit of the last three thicknesses ([`richardson`], None without an
/// asymptotic range) and the finest run's value.
pub struct Limit {
    pub name: &'static str,
    pub model: f64,
    pub order_limit: Option<(f64, f64)>,
    pub finest: Option<f64>,
}

/// [`Limit`]s of F_1, x_1 and F_max over the finished rows of [`thin_layer`].
pub fn thin_layer_limits(rows: &[SeriesRow]) -> Vec<Limit> {
    type Get = fn(&PaperComparison) -> (f64, Option<f64>);
    let quantities: [(&str, Get); 3] =
        [("F_1", |c| (c.f1, c.f1_fe)), ("x_1", |c| (c.x1, c.x1_fe)), ("F_max", |c| (c.f_max, c.f_max_fe))];
    quantities
        .into_iter()
        .map(|(name, get)| {
            let mut model = f64::NAN;
            let pts: Vec<(f64, f64)> = rows
                .iter()
                .filter_map(|r| r.fig4.as_ref().ok())
                .filter_map(|f| {
                    let (m, v) = get(&f.cmp);
                    model = m;
                    v.map(|v| (f.run.condensed.t / f.run.condensed.l, v))
                })
                .collect();
            Limit { name, model, order_limit: richardson(&pts), finest: pts.last().map(|q| q.1) }
        })
        .collect()
}
