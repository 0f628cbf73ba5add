//! A refinement series at fixed physics: the same scene, law and options on h, h/2, h/4...,
//! each quantity of the summary with its spread and a converged verdict by a stated rule.
//! D_c is part of the law, so it stays fixed as h halves: the cohesive zone spans 3, 6, 12
//! elements (the convergence study's design, validation/dynamics/converge).

use super::{run, summary, DynamicOptions};
use crate::error::{Error, Result};
use crate::progress::Progress;
use crate::scene::Scene;
use crate::studies::slide::SlideOptions;

/// The rule: a force (units of mu_s N) is converged when the two finest meshes agree within
/// [`FORCE_TOL`], a position (units of L) within [`POSITION_TOL`]; a count when they are
/// equal. The tolerances are the round-off bands measured on the paper's scene (the largest
/// force moves by up to 0.006 mu_s N and the front by a few elements between replicates that
/// differ only in round-off, validation/dynamics/converge/README.md).
pub const FORCE_TOL: f64 = 0.01;
pub const POSITION_TOL: f64 = 0.02;

/// The quantities judged (summary columns); the others describe the run.
pub const JUDGED: &[&str] = &[
    "first_advance_F_over_mu_s_N",
    "first_advance_front_over_L",
    "largest_F_before_crossing_over_mu_s_N",
    "crossing_F_over_mu_s_N",
    "front_advances",
    "edge_precursors",
    "envelope_front_over_L_at_F_0.75",
    "envelope_front_over_L_at_F_0.80",
    "envelope_front_over_L_at_F_0.85",
    "envelope_front_over_L_at_F_0.90",
];

/// One series: the element sizes, and each level's summary values ([`summary::COLUMNS`]).
#[derive(Debug, Clone)]
pub struct Refinement {
    pub h: Vec<f64>,
    pub values: Vec<Vec<f64>>,
    /// Wall time of each level, s.
    pub seconds: Vec<f64>,
    /// The cap a level met (the series stops there, the levels before it kept).
    pub incomplete: Option<String>,
}

/// The tolerance of a judged quantity: forces, positions, counts (exact).
pub fn tolerance(name: &str) -> f64 {
    if name.contains("_over_L") {
        POSITION_TOL
    } else if name.contains("_F_") {
        FORCE_TOL
    } else {
        0.0
    }
}

/// A judged quantity over the series.
#[derive(Debug, Clone, PartialEq)]
pub struct Verdict {
    pub name: &'static str,
    pub values: Vec<f64>,
    /// Largest minus smallest over the meshes (NaN where a mesh lacks the quantity).
    pub spread: f64,
    /// |finest - second finest|.
    pub last_change: f64,
    /// None where the two finest meshes do not both have it.
    pub converged: Option<bool>,
}

impl Refinement {
    pub fn verdicts(&self) -> Vec<Verdict> {
        JUDGED
            .iter()
            .map(|&name| {
                let col = summary::COLUMNS.iter().position(|c| c.0 == name).expect("a summary column");
                let values: Vec<f64> = self.values.iter().map(|v| v[col]).collect();
                let spread = values.iter().cloned().fold(f64::NEG_INFINITY, f64::max)
                    - values.iter().cloned().fold(f64::INFINITY, f64::min);
                let n = values.len();
                let last_change = if n >= 2 { (values[n - 1] - values[n - 2]).abs() } else { f64::NAN };
                let converged = last_change.is_finite().then_some(last_change <= tolerance(name));
                let spread = if values.iter().all(|v| v.is_finite()) { spread } else { f64::NAN };
                Verdict { name, values, spread, last_change, converged }
            })
            .collect()
    }
}

/// Runs `levels` meshes from the scene's h, halving it each time; D_c and every other input
/// fixed. The coarsest must resolve the cohesive zone (checked by [`super::check`]).
pub fn refine(
    scene: &Scene,
    o: &SlideOptions,
    d: &DynamicOptions,
    levels: usize,
    progress: Progress,
) -> Result<Refinement> {
    if !(2..=4).contains(&levels) {
        return Err(Error::input(
            "--refine",
            format!("{levels}: give 2 to 4 meshes (each halving costs ~10x the CPU of the one before)"),
        ));
    }
    if scene.mesh.file.is_some() || scene.mesh.n_thick.is_some() {
        return Err(Error::input("--refine", "halves the built-in mesh's h: not with --mesh or --n-thick"));
    }
    super::check(scene, o, d)?;
    let mut out = Refinement { h: vec![], values: vec![], seconds: vec![], incomplete: None };
    for k in 0..levels {
        let mut s = scene.clone();
        s.mesh.h = scene.mesh.h / f64::powi(2.0, k as i32);
        s.validate()?;
        progress.message(&format!("refinement level {} of {levels}: h = {:.4e} m", k + 1, s.mesh.h));
        let clock = std::time::Instant::now();
        let r = run(&s, o, d, progress)?;
        if let Some(why) = &r.incomplete {
            out.incomplete = Some(format!("the level h = {:.4e} m: {why}", s.mesh.h));
            break;
        }
        out.h.push(s.mesh.h);
        out.values.push(summary::values(&r));
        out.seconds.push(clock.elapsed().as_secs_f64());
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_quantity_is_judged_by_its_kind() {
        assert_eq!(tolerance("first_advance_F_over_mu_s_N"), FORCE_TOL);
        assert_eq!(tolerance("first_advance_front_over_L"), POSITION_TOL);
        assert_eq!(tolerance("envelope_front_over_L_at_F_0.85"), POSITION_TOL);
        assert_eq!(tolerance("front_advances"), 0.0);
        let col = |n: &str| summary::COLUMNS.iter().position(|c| c.0 == n).unwrap();
        let mut a = vec![f64::NAN; summary::COLUMNS.len()];
        let mut b = a.clone();
        (a[col("envelope_front_over_L_at_F_0.85")], b[col("envelope_front_over_L_at_F_0.85")]) =
            (-0.127, -0.1373);
        (a[col("front_advances")], b[col("front_advances")]) = (14.0, 19.0);
        (a[col("largest_F_before_crossing_over_mu_s_N")], b[col("largest_F_before_crossing_over_mu_s_N")]) =
            (0.9519, 0.9675);
        let r = Refinement {
            h: vec![5e-4, 2.5e-4],
            values: vec![a, b],
            seconds: vec![1.0, 2.0],
            incomplete: None,
        };
        let v = r.verdicts();
        let get = |n: &str| v.iter().find(|x| x.name == n).unwrap().clone();
        assert_eq!(get("envelope_front_over_L_at_F_0.85").converged, Some(true));
        assert_eq!(get("front_advances").converged, Some(false));
        assert_eq!(get("largest_F_before_crossing_over_mu_s_N").converged, Some(false));
        assert!((get("front_advances").spread - 5.0).abs() < 1e-12);
        assert_eq!(get("first_advance_F_over_mu_s_N").converged, None);
    }
}
