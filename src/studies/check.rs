//! The paper's check: solve the scene's two unit load cases (normal, tangential) with one
//! factorisation, combine them to hit each requested F/N exactly, recover the interface
//! tractions, and measure how far they are from the model's assumptions
//! p/(N/L) = 1 + 12 (F/N)(H/L)(x/L) and tau/(N/L) = F/N.

use crate::error::{Error, Result};
use crate::fem::assembly::Model;
use crate::fem::problem::{solve, LoadCase, Prepared, Solution, SolverStats, Timings};
use crate::fem::recovery::{elements_touching, nodal_stresses_from};
use crate::linalg::solve::SolverOptions;
use crate::numeric::{interpolate, line_fit};
use crate::precursors::fe::UnitFields;
use crate::scene::{PlateModel, Rig, Scene, SceneModel, SidePushDofs};
use std::time::Instant;

/// Figures of one load case (all stresses divided by the mean pressure N/L).
#[derive(Debug, Clone)]
pub struct CaseResult {
    pub fn_ratio: f64,
    /// Normal and tangential force per unit width, N/m.
    pub n: f64,
    pub f: f64,
    /// Plate tilt, rad (positive counter-clockwise).
    pub tilt: f64,
    /// The prescribed plate displacements that produce this case: U (tangential, at height H)
    /// and V (normal), m.
    pub plate_u: f64,
    pub plate_v: f64,
    pub x_over_l: Vec<f64>,
    /// From the consistent nodal reactions (default).
    pub p: Vec<f64>,
    pub tau: Vec<f64>,
    /// From integration-point stresses extrapolated to the nodes and averaged.
    pub p_extrap: Vec<f64>,
    pub tau_extrap: Vec<f64>,
    pub p_model: Vec<f64>,
    pub tau_model: Vec<f64>,
    /// The corrected model's pressure (`analytical::thin_layer`), valid away from the end zones.
    pub p_corrected: Vec<f64>,
    pub metrics: Metrics,
}

#[derive(Debug, Clone)]
pub struct Metrics {
    /// Least-squares slope of p/(N/L) against x/L over the interior |x| < L/2 - [`interior_margin`],
    /// and the model's 12 (F/N)(H/L). Interior figures are NaN (reported `-`, undefined) when
    /// the interior holds fewer than two nodes (one for the deviations).
    pub slope_interior: f64,
    pub slope_model: f64,
    /// Largest |deviation from the model| over the interior, in units of N/L.
    pub interior_dev_p: f64,
    pub interior_dev_tau: f64,
    pub tau_center: f64,
    /// Values at the two end nodes (mesh-dependent: the corners are singular).
    pub p_ends: [f64; 2],
    pub tau_ends: [f64; 2],
    /// Edge-zone widths in units of t (left, right); None where the model value is zero.
    pub edge_p_t: [Option<f64>; 2],
    pub edge_tau_t: [Option<f64>; 2],
    /// Errors of the global balances relative to the load size: |sum of interface normal
    /// forces - N| and |sum of shear forces + F| over |N| + |F|, |moment - F H| over
    /// |N| L/2 + |F| H (the largest moment the loads make), so a large F/N does not inflate them.
    pub balance_n: f64,
    pub balance_f: f64,
    pub balance_moment: f64,
    /// The corrected model (`analytical::thin_layer`): its least-squares slope over the same
    /// interior, and the largest |p - p_corrected| there, in units of N/L.
    pub slope_corrected: f64,
    pub interior_dev_p_corrected: f64,
}

#[derive(Debug, Clone)]
pub struct CheckResult {
    pub scene: Scene,
    pub cases: Vec<CaseResult>,
    /// Interface fields per unit N and per unit F (input of the FE-fed precursor model).
    pub unit: UnitFields,
    pub n_nodes: usize,
    pub n_elements: usize,
    /// The solve's sizes, accuracy and phase times (mesh and recovery included).
    pub stats: SolverStats,
    /// Full displacements of each combined case (for field output) and the model used.
    pub displacements: Vec<Vec<f64>>,
    /// With `mesh.geometry = file`: what every verdict against the paper's model must say,
    /// with the share of L t the elements cover.
    pub geometry_note: Option<String>,
}

impl CheckResult {
    /// Worst global-balance error of all load cases (relative to the load size).
    pub fn balance_error(&self) -> f64 {
        self.cases
            .iter()
            .map(|c| c.metrics.balance_n.max(c.metrics.balance_f).max(c.metrics.balance_moment))
            .fold(0.0, f64::max)
    }

    /// The balance error the solve can achieve: the balance is exact for any displacement
    /// except for the residuals left at the free unknowns, ~ eps kappa of the load (kappa: the
    /// solver's condition estimate); 100 eps kappa. Measured 0.3-8 eps kappa: rigid plate with
    /// H up to 1e3 L (`--height`), elastic plate from 2e4 to 2e12 Pa (`tribofe check --plate
    /// elastic --plate-modulus E` prints both figures).
    pub fn balance_limit(&self) -> f64 {
        100.0 * f64::EPSILON * self.stats.report.condition_estimate.max(1.0)
    }

    /// The check's self-check: refuses results whose global balance is worse than the solve
    /// can explain ([`CheckResult::balance_limit`]).
    pub fn self_check(&self) -> Result<()> {
        let (value, limit) = (self.balance_error(), self.balance_limit());
        if value > limit || value.is_nan() {
            return Err(Error::SelfCheck {
                what: "global balance (interface forces vs N, F and the moment F H, relative to the load)"
                    .into(),
                value,
                limit,
                hint: "the limit is 100 eps kappa from the solver's condition estimate kappa; \
                       a larger error means a defect in the model or the mesh: report it with the scene \
                       (--write-scene)"
                    .into(),
            });
        }
        Ok(())
    }
}

/// The cheapest model the convergence study (`validation/convergence/`) shows to match the
/// finest meshes: quadratic QUA8, t/16 at both ends, growing by 1.15 per element to 4 t in the
/// smooth middle. Used by `tribofe check` for the "converged" figures next to the paper's mesh.
pub fn converged_scene(scene: &Scene) -> Scene {
    let mut s = scene.clone();
    let t = s.block.thickness;
    s.mesh.element = "qua8".into();
    s.mesh.h = t / 16.0;
    s.mesh.n_thick = None;
    s.mesh.grading = Some(1.15);
    s.mesh.h_max = Some(4.0 * t);
    s.mesh.file = None;
    s.mesh.geometry = crate::scene::MeshGeometry::Block;
    s
}

/// The reusable part of the check's solve for `scene`: valid for every scene that differs
/// only in material values or loading (a sweep of the plate modulus, of nu, of F/N).
pub fn prepare(scene: &Scene, opts: &SolverOptions) -> Result<Prepared> {
    let sm = scene.build()?;
    Prepared::new(&sm.mesh, &sm.constraints, opts)
}

/// Runs the paper's check on a scene.
pub fn run(scene: &Scene, opts: &SolverOptions) -> Result<(CheckResult, SceneModel)> {
    if scene.loading.rig == Rig::SidePush {
        return run_side_push(scene, opts);
    }
    let clock = Instant::now();
    let sm = scene.build()?;
    let mesh_time = clock.elapsed().as_secs_f64();
    let (mut res, sm) = run_model(scene, sm, mesh_time, opts, None)?;
    res.stats.timings.set_wall(clock.elapsed().as_secs_f64());
    Ok((res, sm))
}

/// Runs the check on a model built from `scene` and then altered (e.g. interior nodes moved
/// by the stability study); the interface, top and loading DOFs must be those of the scene.
/// `mesh_time` (s) is reported as the mesh phase. With `prepared` (built on the same mesh and
/// constraint structure, see [`prepare`]) the pattern and symbolic analysis are reused.
pub fn run_model(
    scene: &Scene,
    sm: SceneModel,
    mesh_time: f64,
    opts: &SolverOptions,
    prepared: Option<&Prepared>,
) -> Result<(CheckResult, SceneModel)> {
    run_model_with_decay(scene, sm, mesh_time, opts, prepared, None)
}

/// [`run_model`] with the corrected model's decay rate k(nu) given (a sweep computes it once
/// per Poisson ratio: the root search costs as much as a small solve).
pub fn run_model_with_decay(
    scene: &Scene,
    sm: SceneModel,
    mesh_time: f64,
    opts: &SolverOptions,
    prepared: Option<&Prepared>,
    decay: Option<f64>,
) -> Result<(CheckResult, SceneModel)> {
    let (sol, cases) = solve_units(scene, &sm, opts, prepared, false)?;
    let clock = Instant::now();
    let model = sm.model();
    let units = Units::from_solution(&sm, &model, &sol, &cases)?;
    let res = finish(scene, &sm, &sol, units, mesh_time, clock, decay, None)?;
    Ok((res, sm))
}

/// The check under side push (bonded interface): two force cases from one factorisation, a
/// unit normal load N0 on the top (uniform pressure N0/L, or N0 on the sliding plate's V) and
/// a force N0 on the pusher's U_p, combined to each requested F/N. N0 = 0.05 E L (a mean
/// pressure of 5 % of E); `--n-force` rescales. The model column is the paper's torque
/// balance with the push's arm h: p = N/L + 12 F h x / L^3, tau = F/L; the corrected model is
/// the top plate's only, so p_corrected repeats the model. The moment balance compares the
/// interface's moment with the one the pusher's own nodal forces and the top load make.
pub fn run_side_push(scene: &Scene, opts: &SolverOptions) -> Result<(CheckResult, SceneModel)> {
    let clock = Instant::now();
    let (sm, sp) = scene.build_side_push()?;
    let mesh_time = clock.elapsed().as_secs_f64();
    let model = sm.model();
    let (n_full, nf) = (sm.constraints.n_full(), sm.constraints.n_fixed());
    let l = scene.block.length;
    let n0 = 0.05 * scene.block.young * l;
    let mut fa = vec![0.0; n_full];
    match sp.plate {
        Some([_, pv, _]) => fa[pv] = -n0,
        None => crate::fem::loads::add_edge_traction(&sm.mesh, &sm.top_set, &|_| [0.0, -n0 / l], &mut fa)?,
    }
    let mut fb = vec![0.0; n_full];
    fb[sp.pusher] = n0;
    let cases = vec![
        LoadCase { prescribed: vec![0.0; nf], forces: fa },
        LoadCase { prescribed: vec![0.0; nf], forces: fb },
    ];
    let sol = solve(&model, &sm.constraints, &cases, opts, "check the mesh and the material values")?;
    let solved = Instant::now();
    let near = elements_touching(&model, &sm.interface);
    let push_elems = elements_touching(&model, &sp.pusher_nodes);
    let mut units = Vec::new();
    for (c, case) in cases.iter().enumerate() {
        let r_int = sol.residual_forces(&model, case, c, &near)?;
        let r_push = sol.residual_forces(&model, case, c, &push_elems)?;
        // The moment about (0, 0) the interface must carry: y F_i of each pusher node's force
        // (the tie's reaction), minus the top load's own moment (zero to round-off).
        let pushed: f64 = sp.pusher_nodes.iter().map(|&k| sm.mesh.nodes[k][1] * r_push[2 * k]).sum();
        let top: f64 = (0..sm.mesh.n_nodes()).map(|k| sm.mesh.nodes[k][0] * case.forces[2 * k + 1]).sum();
        units.push(Unit {
            u: sol.u[c].clone(),
            n: if c == 0 { n0 } else { 0.0 },
            f: if c == 1 { n0 } else { 0.0 },
            rx: sm.interface.iter().map(|&k| r_int[2 * k]).collect(),
            ry: sm.interface.iter().map(|&k| r_int[2 * k + 1]).collect(),
            plate_u: sol.u[c][sp.pusher],
            theta: 0.0,
            moment: pushed - top,
        });
    }
    let mut res = finish(scene, &sm, &sol, Units(units), mesh_time, solved, None, Some(&sp))?;
    res.stats.timings.set_wall(clock.elapsed().as_secs_f64());
    Ok((res, sm))
}

/// The check at every height of `scenes` (scenes equal to `reference` but for
/// loading.height, rigid plate) from one factorisation: the unit cases at the reference's
/// height plus a unit moment on the plate, combined per height (H enters the rigid plate's
/// ties only as the reference point of its rotation).
pub fn run_heights(
    reference: &Scene,
    scenes: &[Scene],
    opts: &SolverOptions,
    prepared: Option<&Prepared>,
    decay: Option<f64>,
) -> Result<Vec<CheckResult>> {
    let clock = Instant::now();
    let sm = reference.build()?;
    let mesh_time = clock.elapsed().as_secs_f64();
    if sm.dof_theta.is_none() {
        return Err(Error::input("plate.model", "the check over heights needs the rigid plate"));
    }
    let (sol, cases) = solve_units(reference, &sm, opts, prepared, true)?;
    let model = sm.model();
    let base = Units::from_solution(&sm, &model, &sol, &cases)?;
    scenes
        .iter()
        .map(|s| {
            let mut same = s.clone();
            same.loading.height = reference.loading.height;
            if format!("{same:?}") != format!("{reference:?}") {
                return Err(Error::input(
                    "check over heights",
                    "the scenes differ in more than loading.height",
                ));
            }
            let clock = Instant::now();
            let units = base.at_height(s.loading.height - reference.loading.height)?;
            finish(s, &sm, &sol, units, mesh_time, clock, decay, None)
        })
        .collect()
}

/// Solves the unit cases: A presses the plate down by d, B moves it sideways by d at height H
/// (the problem is linear; d = 5 % of t keeps N at the scale of the peer scripts in
/// validation/peers); with `moment`, C: U = V = 0 and a unit moment on the rigid plate.
fn solve_units(
    scene: &Scene,
    sm: &SceneModel,
    opts: &SolverOptions,
    prepared: Option<&Prepared>,
    moment: bool,
) -> Result<(Solution, Vec<LoadCase>)> {
    let model = sm.model();
    let d = 0.05 * scene.block.thickness;
    let nf = sm.constraints.n_fixed();
    let slot = |dof: usize| {
        sm.constraints
            .fixed_slot(dof)
            .ok_or_else(|| Error::input("scene", "the plate's loading DOFs are not prescribed"))
    };
    let (ju, jv) = (slot(sm.dof_u)?, slot(sm.dof_v)?);
    let mut ga = vec![0.0; nf];
    ga[jv] = -d;
    let mut gb = vec![0.0; nf];
    gb[ju] = d;
    let mut cases =
        vec![LoadCase { prescribed: ga, forces: vec![] }, LoadCase { prescribed: gb, forces: vec![] }];
    if let (true, Some(th)) = (moment, sm.dof_theta) {
        let mut f = vec![0.0; sm.constraints.n_full()];
        f[th] = 1.0;
        cases.push(LoadCase { prescribed: vec![0.0; nf], forces: f });
    }
    let hint = match scene.plate.model {
        PlateModel::Elastic => format!(
            "the elastic plate (E_plate / E_block = {:.1e}) makes the system too ill-conditioned for double precision; use the exact rigid plate (--plate rigid)",
            scene.plate.young / scene.block.young
        ),
        PlateModel::Rigid => "check the mesh and the material values".to_string(),
    };
    let sol = match prepared {
        Some(p) => p.solve(&model, &sm.constraints, &cases, opts, &hint)?,
        None => solve(&model, &sm.constraints, &cases, opts, &hint)?,
    };
    Ok((sol, cases))
}

/// Per unit case: displacements, the generalised reactions N and F at the plate, the
/// interface nodal reactions (x, y), and (rigid plate) the plate's U, rotation and applied
/// moment; all linear in the case, so cases combine.
#[derive(Clone)]
struct Unit {
    u: Vec<f64>,
    n: f64,
    f: f64,
    rx: Vec<f64>,
    ry: Vec<f64>,
    plate_u: f64,
    theta: f64,
    moment: f64,
}

struct Units(Vec<Unit>);

impl Units {
    fn from_solution(sm: &SceneModel, model: &Model, sol: &Solution, cases: &[LoadCase]) -> Result<Self> {
        // Interface reactions of each unit case, and the generalised reactions at U and V.
        let near = elements_touching(model, &sm.interface);
        let plate_elems: Vec<usize> = match sm.dof_theta {
            Some(_) => elements_touching(model, &sm.mesh.set_nodes(&sm.top_set)?),
            None => elements_touching(model, &[sm.dof_u / 2, sm.dof_v / 2]),
        };
        let (ju, jv) = (sm.constraints.fixed_slot(sm.dof_u), sm.constraints.fixed_slot(sm.dof_v));
        let (Some(ju), Some(jv)) = (ju, jv) else {
            return Err(Error::input("scene", "the plate's loading DOFs are not prescribed"));
        };
        let mut units = Vec::new();
        for (c, case) in cases.iter().enumerate() {
            let r_int = sol.residual_forces(model, case, c, &near)?;
            let r_plate = sol.residual_forces(model, case, c, &plate_elems)?;
            let fixed = sol.reduction.fixed_reactions(&r_plate);
            let th = sm.dof_theta;
            units.push(Unit {
                u: sol.u[c].clone(),
                n: -fixed[jv],
                f: fixed[ju],
                rx: sm.interface.iter().map(|&k| r_int[2 * k]).collect(),
                ry: sm.interface.iter().map(|&k| r_int[2 * k + 1]).collect(),
                plate_u: case.prescribed[ju],
                theta: th.map_or(0.0, |th| sol.u[c][th]),
                moment: th.map_or(0.0, |th| case.forces.get(th).copied().unwrap_or(0.0)),
            });
        }
        Ok(Self(units))
    }

    /// The cases A and B for the drive at height H0 + dh from A, B and the moment case C at
    /// H0: U(H) = U - theta dh (the tie u = U - theta (y - H0)), and a force F at H is F at H0
    /// with the moment -dh F (virtual work F du(H)), so C's share makes the moment -dh F.
    fn at_height(&self, dh: f64) -> Result<Self> {
        let [a, b, c] = &self.0[..] else {
            return Err(Error::input("check over heights", "needs the three unit cases"));
        };
        let d = b.plate_u;
        // beta B + gamma C added to alpha A: U(H) = target, moment = -dh F.
        let m = [[d - dh * b.theta, -dh * c.theta], [dh * b.f, c.moment + dh * c.f]];
        let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
        if !(det.abs() > 0.0) {
            return Err(Error::input("check over heights", "the height shift is degenerate"));
        }
        let pick = |alpha: f64, u_target: f64| -> Unit {
            let r = [u_target + dh * alpha * a.theta, -dh * alpha * a.f];
            let beta = (r[0] * m[1][1] - m[0][1] * r[1]) / det;
            let gamma = (m[0][0] * r[1] - r[0] * m[1][0]) / det;
            let mix = |x: &[f64], y: &[f64], z: &[f64]| -> Vec<f64> {
                x.iter().zip(y).zip(z).map(|((x, y), z)| alpha * x + beta * y + gamma * z).collect()
            };
            let theta = alpha * a.theta + beta * b.theta + gamma * c.theta;
            Unit {
                u: mix(&a.u, &b.u, &c.u),
                n: alpha * a.n + beta * b.n + gamma * c.n,
                f: alpha * a.f + beta * b.f + gamma * c.f,
                rx: mix(&a.rx, &b.rx, &c.rx),
                ry: mix(&a.ry, &b.ry, &c.ry),
                plate_u: u_target,
                theta,
                moment: 0.0,
            }
        };
        Ok(Self(vec![pick(1.0, 0.0), pick(0.0, d)]))
    }
}

/// The check's figures from the two unit cases (with `side`, the side-pushed rig's: each
/// unit's `moment` is the moment the interface must carry, `plate_u` the pusher's U_p).
#[allow(clippy::too_many_arguments)]
fn finish(
    scene: &Scene,
    sm: &SceneModel,
    sol: &Solution,
    units: Units,
    mesh_time: f64,
    clock: Instant,
    decay: Option<f64>,
    side: Option<&SidePushDofs>,
) -> Result<CheckResult> {
    let model = sm.model();
    let (l, t, hgt) = (scene.block.length, scene.block.thickness, scene.arm());
    let d = 0.05 * t;
    let near = elements_touching(&model, &sm.interface);
    let unit: Vec<(f64, f64, Vec<f64>, Vec<f64>)> =
        units.0.iter().take(2).map(|u| (u.n, u.f, u.rx.clone(), u.ry.clone())).collect();
    let (na, fa) = (unit[0].0, unit[0].1);
    let (nb, fb) = (unit[1].0, unit[1].1);
    let det = na * fb - nb * fa;
    if !(det.abs() > 0.0) || !(na > 0.0) {
        return Err(Error::input(
            "scene",
            "the unit load cases are degenerate (no normal force from pressing the plate)",
        ));
    }
    let widths = sm.tributary_widths();
    let xs: Vec<f64> = sm.interface.iter().map(|&k| sm.mesh.nodes[k][0]).collect();
    let x_over_l: Vec<f64> = xs.iter().map(|x| x / l).collect();
    // Unit fields: combination giving (N, F) = (1, 0) and (0, 1).
    let combo =
        |n_t: f64, f_t: f64| -> (f64, f64) { ((n_t * fb - f_t * nb) / det, (na * f_t - fa * n_t) / det) };
    let profile = |a: f64, b: f64| -> (Vec<f64>, Vec<f64>) {
        let p = (0..xs.len()).map(|i| (a * unit[0].3[i] + b * unit[1].3[i]) / widths[i]).collect();
        let tau = (0..xs.len()).map(|i| -(a * unit[0].2[i] + b * unit[1].2[i]) / widths[i]).collect();
        (p, tau)
    };
    let (a1, b1) = combo(1.0, 0.0);
    let (a2, b2) = combo(0.0, 1.0);
    let (pn, tn) = profile(a1, b1);
    let (pf, tf) = profile(a2, b2);
    let unit_profiles = UnitFields {
        h_over_l: hgt / l,
        t_over_l: t / l,
        x_over_l: x_over_l.clone(),
        w_over_l: widths.iter().map(|w| w / l).collect(),
        p_per_n: pn.iter().map(|v| v * l).collect(),
        tau_per_n: tn.iter().map(|v| v * l).collect(),
        p_per_f: pf.iter().map(|v| v * l).collect(),
        tau_per_f: tf.iter().map(|v| v * l).collect(),
    };

    let mut results = Vec::new();
    let mut displacements = Vec::new();
    let decay = match decay {
        Some(k) => k,
        None => crate::analytical::thin_layer::Corrected::decay(scene.block.plane_strain_nu())?,
    };
    for &ratio in &scene.loading.fn_ratios {
        // N = N_A (the normal force of case A alone), F = ratio N.
        let (a, b) = combo(na, ratio * na);
        let (n, f) = (a * na + b * nb, a * fa + b * fb);
        let pmean = n / l;
        let (p, tau) = profile(a, b);
        let u: Vec<f64> = units.0[0].u.iter().zip(&units.0[1].u).map(|(x, y)| a * x + b * y).collect();
        let s = nodal_stresses_from(&model, &u, &near);
        let p_extrap: Vec<f64> = sm.interface.iter().map(|&k| -s[k][1] / pmean).collect();
        let tau_extrap: Vec<f64> = sm.interface.iter().map(|&k| s[k][2] / pmean).collect();
        let p: Vec<f64> = p.iter().map(|v| v / pmean).collect();
        let tau: Vec<f64> = tau.iter().map(|v| v / pmean).collect();
        // The model from the requested ratio (F/N equals it to round-off, and exactly 0 stays 0).
        let slope_model = 12.0 * ratio * (hgt / l);
        let p_model: Vec<f64> = x_over_l.iter().map(|x| 1.0 + slope_model * x).collect();
        let tau_model = vec![ratio; xs.len()];
        // Global balances from the interface forces.
        let sum_ry: f64 = (0..xs.len()).map(|i| a * unit[0].3[i] + b * unit[1].3[i]).sum();
        let sum_rx: f64 = (0..xs.len()).map(|i| a * unit[0].2[i] + b * unit[1].2[i]).sum();
        let moment: f64 = (0..xs.len()).map(|i| xs[i] * (a * unit[0].3[i] + b * unit[1].3[i])).sum();
        let tilt = match sm.dof_theta {
            Some(th) => u[th],
            None => plate_tilt(sm, &u),
        };
        let p_corrected: Vec<f64> = match side {
            Some(_) => p_model.clone(),
            None => {
                let corr = crate::analytical::thin_layer::Corrected::with_decay(
                    l,
                    t,
                    hgt,
                    scene.block.plane_strain_nu(),
                    ratio,
                    decay,
                )?;
                x_over_l.iter().map(|&x| corr.pressure(x)).collect()
            }
        };
        let interior = interior_nodes(&x_over_l, l, t);
        let slope_corrected =
            line_fit(interior.iter().map(|&i| (x_over_l[i], p_corrected[i]))).map_or(f64::NAN, |l| l.1);
        let interior_dev_p_corrected = max_dev(&interior, &p, &p_corrected);
        let metrics = Metrics {
            slope_corrected,
            interior_dev_p_corrected,
            balance_n: (sum_ry - n).abs() / (n.abs() + f.abs()),
            balance_f: (sum_rx + f).abs() / (n.abs() + f.abs()),
            balance_moment: match side {
                None => (moment - f * hgt).abs() / (n.abs() * l / 2.0 + f.abs() * hgt),
                Some(_) => {
                    let applied = a * units.0[0].moment + b * units.0[1].moment;
                    (moment - applied).abs() / (n.abs() * l / 2.0 + f.abs() * hgt)
                }
            },
            ..metrics(&x_over_l, &p, &tau, &p_model, &tau_model, slope_model, l, t, scene.report.tol)
        };
        results.push(CaseResult {
            fn_ratio: ratio,
            n,
            f,
            tilt,
            plate_u: side.map_or(b * d, |s| u[s.pusher]),
            plate_v: match side {
                None => -a * d,
                Some(s) => match s.plate {
                    Some([_, pv, _]) => u[pv],
                    None => {
                        let top = sm.mesh.set_nodes(&sm.top_set)?;
                        top.iter().map(|&k| u[2 * k + 1]).sum::<f64>() / top.len() as f64
                    }
                },
            },
            x_over_l: x_over_l.clone(),
            p,
            tau,
            p_extrap,
            tau_extrap,
            p_model,
            tau_model,
            p_corrected,
            metrics,
        });
        displacements.push(u);
    }
    let timings = Timings { mesh: mesh_time, recovery: clock.elapsed().as_secs_f64(), ..sol.stats.timings };
    let res = CheckResult {
        scene: scene.clone(),
        cases: results,
        unit: unit_profiles,
        n_nodes: sm.mesh.n_nodes(),
        n_elements: sm.mesh.n_elements(),
        stats: SolverStats { timings, ..sol.stats.clone() },
        displacements,
        geometry_note: (scene.mesh.geometry == crate::scene::MeshGeometry::File).then(|| {
            let full = scene.block.length * scene.block.thickness;
            format!(
                "{} (its elements cover {:.6} of L t)",
                crate::scene::FILE_GEOMETRY_NOTE,
                sm.mesh.total_area() / full
            )
        }),
    };
    Ok(res)
}

/// Rotation of an elastic plate from the vertical displacements of its top corners, rad.
fn plate_tilt(sm: &SceneModel, u: &[f64]) -> f64 {
    let top = sm.mesh.nodes.iter().fold(f64::MIN, |m, p| m.max(p[1]));
    let corners: Vec<usize> = (0..sm.mesh.n_nodes()).filter(|&k| sm.mesh.nodes[k][1] == top).collect();
    let (l, r) = corners.iter().fold((corners[0], corners[0]), |(l, r), &k| {
        (
            if sm.mesh.nodes[k][0] < sm.mesh.nodes[l][0] { k } else { l },
            if sm.mesh.nodes[k][0] > sm.mesh.nodes[r][0] { k } else { r },
        )
    });
    (u[2 * r + 1] - u[2 * l + 1]) / (sm.mesh.nodes[r][0] - sm.mesh.nodes[l][0])
}

#[allow(clippy::too_many_arguments)]
fn metrics(
    x: &[f64],
    p: &[f64],
    tau: &[f64],
    pm: &[f64],
    tm: &[f64],
    slope_model: f64,
    l: f64,
    t: f64,
    tol: f64,
) -> Metrics {
    let interior = interior_nodes(x, l, t);
    let slope = line_fit(interior.iter().map(|&i| (x[i], p[i]))).map_or(f64::NAN, |l| l.1);
    let dev = |v: &[f64], model: &[f64]| max_dev(&interior, v, model);
    let tau_center = interpolate(x, tau, 0.0);
    let n = x.len();
    // Edge-zone width: from the end to where the excess |v - model| - tol |model| last changes
    // sign, located by linear interpolation between the two nodes around that crossing.
    let width = |v: &[f64], model: &[f64], left: bool| -> Option<f64> {
        let order: Vec<usize> = if left {
            (0..n).filter(|&i| x[i] <= 0.0).collect()
        } else {
            (0..n).rev().filter(|&i| x[i] >= 0.0).collect()
        };
        if order.iter().any(|&i| model[i] == 0.0) {
            return None;
        }
        let dist = |i: usize| (x[i] - x[order[0]]).abs();
        let excess = |i: usize| (v[i] - model[i]).abs() - tol * model[i].abs();
        let w = match order.iter().rposition(|&i| excess(i) > 0.0) {
            None => 0.0,
            Some(k) if k + 1 == order.len() => dist(order[k]),
            Some(k) => {
                let (i, j) = (order[k], order[k + 1]);
                let (ei, ej) = (excess(i), excess(j));
                dist(i) + (dist(j) - dist(i)) * ei / (ei - ej)
            }
        };
        Some(w * l / t)
    };
    Metrics {
        slope_interior: slope,
        slope_model,
        interior_dev_p: dev(p, pm),
        interior_dev_tau: dev(tau, tm),
        tau_center,
        p_ends: [p[0], p[n - 1]],
        tau_ends: [tau[0], tau[n - 1]],
        edge_p_t: [width(p, pm, true), width(p, pm, false)],
        edge_tau_t: [width(tau, tm, true), width(tau, tm, false)],
        balance_n: 0.0,
        balance_f: 0.0,
        balance_moment: 0.0,
        slope_corrected: f64::NAN,
        interior_dev_p_corrected: f64::NAN,
    }
}

/// Distance from each end excluded from the interior, m: 10 t (the end zones are a few t
/// wide), or L/4 for a block shorter than 40 t, whose interior is then its middle half.
pub fn interior_margin(l: f64, t: f64) -> f64 {
    (10.0 * t).min(l / 4.0)
}

/// Interface nodes (by index into x = x/L) of the interior |x| < L/2 - [`interior_margin`].
fn interior_nodes(x_over_l: &[f64], l: f64, t: f64) -> Vec<usize> {
    let half = l / 2.0 - interior_margin(l, t);
    (0..x_over_l.len()).filter(|&i| x_over_l[i].abs() * l < half).collect()
}

/// Largest |v - model| over the nodes; NaN (undefined, reported as `-`) when there are none.
fn max_dev(nodes: &[usize], v: &[f64], model: &[f64]) -> f64 {
    nodes.iter().map(|&i| (v[i] - model[i]).abs()).reduce(f64::max).unwrap_or(f64::NAN)
}
