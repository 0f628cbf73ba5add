//! One summary per dynamic run (summary.csv and `[results]` in run.toml): what the paper asks
//! of a first cycle, with the physics and the resolution that produced it. Which quantities
//! converge under refinement is stated beside them (validation/dynamics/converge): F_1, x_1,
//! the front envelope and the largest force do; the two counts do not.

use super::{physics, DynamicResult};
use crate::law::Law;
use crate::precursors::definition::Edge;

/// Forces (units of mu_s N) at which the front envelope is read.
pub const ENVELOPE_F: [f64; 4] = [0.75, 0.80, 0.85, 0.90];

/// The summary's columns, in order, with what each means (one schema: the CSV header, the
/// run.toml keys and the docs are these names).
pub const COLUMNS: &[(&str, &str)] = &[
    ("first_advance_F_over_mu_s_N", "F_1: drive force at the first front advance (converges)"),
    ("first_advance_front_over_L", "x_1: the front after it (converges)"),
    (
        "largest_F_before_crossing_over_mu_s_N",
        "the largest force up to and including the cycle's end (converges)",
    ),
    (
        "crossing_F_over_mu_s_N",
        "the force at the cycle's end, the front crossing (not converged: round-off moves it)",
    ),
    ("crossing_X_m", "the drive displacement at the cycle's end"),
    ("front_advances", "count of front advances (not converged)"),
    ("edge_precursors", "count of the one definition's advancing precursors (not converged)"),
    (
        "nucleation_at_leading_edge",
        "0: slip nucleates at the trailing edge and the counts run from there; 1: at the leading edge",
    ),
    (
        "envelope_front_over_L_at_F_0.75",
        "front x on the curve through the advances at F = 0.75 mu_s N (converges)",
    ),
    ("envelope_front_over_L_at_F_0.80", "the same at 0.80"),
    ("envelope_front_over_L_at_F_0.85", "the same at 0.85"),
    ("envelope_front_over_L_at_F_0.90", "the same at 0.90"),
    ("kappa", "thin-layer stability number G D_c / ((mu_s - mu_d) (N/L) t)"),
    ("lambda0_m", "cohesive zone at the mean pressure"),
    ("lambda0_over_h", "its elements"),
    ("dc_m", "slip-weakening distance"),
    ("h_m", "element size"),
    ("damping_eta_s", "Kelvin-Voigt eta"),
    ("damping_ratio_thickness_mode", "eta as a fraction of critical at the thickness mode"),
    (
        "weakening_steps",
        "the static loading's coefficient updates per D_c (0: followed exactly, --exact-weakening)",
    ),
    ("complete", "1: the run reached its end; 0: it met a cap (run.toml names it)"),
];

/// The values of [`COLUMNS`], in order; NaN where a quantity does not exist in the run (no
/// advance, no crossing, a force the advances do not bracket).
pub fn values(r: &DynamicResult) -> Vec<f64> {
    let res = &r.slide;
    let (c, law) = (&res.condensed, res.options.law);
    let k = law.mu_s() * res.options.n_force;
    let adv = crate::studies::slide::front_advances(res);
    let pre = crate::studies::slide::precursors(res);
    let events = &res.run.events;
    let cross = events.iter().position(|e| e.ends_cycle());
    let upto = &events[..cross.map_or(events.len(), |i| i + 1)];
    let nan = f64::NAN;
    let curve: Vec<(f64, f64)> = adv.iter().map(|a| (a.f / k, c.x[a.front] / c.l)).collect();
    let (kappa, dc) = match law {
        Law::SlipWeakening { mu_s, mu_d, dc } => {
            (physics::kappa(&res.scene, mu_s, mu_d, dc, res.options.n_force), dc)
        }
        _ => (nan, nan),
    };
    let mut v = vec![
        curve.first().map_or(nan, |p| p.0),
        curve.first().map_or(nan, |p| p.1),
        upto.iter().map(|e| e.f / k).fold(nan, f64::max),
        cross.map_or(nan, |i| events[i].f / k),
        cross.map_or(nan, |i| events[i].x),
        adv.len() as f64,
        pre.n() as f64,
        f64::from(u8::from(crate::studies::slide::nucleating_edge(res) == Edge::Leading)),
    ];
    v.extend(ENVELOPE_F.iter().map(|&f| envelope(&curve, f)));
    v.extend([
        kappa,
        r.lambda0,
        r.lambda0 / res.scene.mesh.h,
        dc,
        res.scene.mesh.h,
        r.eta,
        r.xi_thickness,
        r.weakening_steps,
        if r.incomplete.is_some() { 0.0 } else { 1.0 },
    ]);
    v
}

/// The front x/L at force `f` on the curve through the advances' points (F, front), linear
/// between the first consecutive pair that brackets f (validation/dynamics/converge/table.py's
/// `tip_curve`); NaN outside. Unlike the front after the last advance below f, it does not
/// jump by a whole step when a mesh moves a step across f.
pub fn envelope(curve: &[(f64, f64)], f: f64) -> f64 {
    curve
        .windows(2)
        .find(|w| w[0].0 <= f && f <= w[1].0 && w[1].0 > w[0].0)
        .map_or(f64::NAN, |w| w[0].1 + (f - w[0].0) / (w[1].0 - w[0].0) * (w[1].1 - w[0].1))
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_envelope_is_linear_between_the_bracketing_advances() {
        let c = [(0.7, -0.4), (0.8, -0.2), (0.9, 0.1)];
        assert!((super::envelope(&c, 0.75) + 0.3).abs() < 1e-15);
        assert!((super::envelope(&c, 0.85) + 0.05).abs() < 1e-15);
        assert!(super::envelope(&c, 0.95).is_nan() && super::envelope(&c, 0.6).is_nan());
        assert_eq!(super::COLUMNS.len(), 21);
    }
}
