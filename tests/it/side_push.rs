//! Issue 49, phase 1: the side-pushed rig in `tribofe check` (bonded interface). A rigid pusher
//! on the trailing face x = -L/2 at push_height, push_width wide, carries F; the top carries N
//! as a uniform pressure or through a rigid plate free to slide and rotate.

use tribofe::linalg::solve::SolverOptions;
use tribofe::scene::{Overrides, Rig, Scene, Top};
use tribofe::studies::check::run;

/// A block thick enough to push on its side: L = 0.1 m, t = 0.02 m, h = t / 10; the pusher
/// 6 mm wide at 5 mm (three element edges on the coarsest mesh).
fn side(top: Top, h: f64) -> Scene {
    Scene::default()
        .apply(&Overrides {
            length: Some(0.1),
            thickness: Some(0.02),
            h: Some(h),
            rig: Some(Rig::SidePush),
            push_height: Some(0.005),
            push_width: Some(0.006),
            top: Some(top),
            fn_ratios: Some(vec![0.0, 0.3, 0.7]),
            ..Default::default()
        })
        .unwrap()
}

#[test]
fn side_push_balances_force_and_moment() {
    for top in [Top::UniformPressure, Top::SlidingPlate] {
        let r = run(&side(top, 0.002), &SolverOptions::default()).unwrap().0;
        for c in &r.cases {
            let m = &c.metrics;
            // Every balance is exact for any displacement but for the solve's residual and the
            // summation's round-off (~1e-14 here): 1e-10 relative to the load, as the issue asks.
            assert!(
                m.balance_n < 1e-10 && m.balance_f < 1e-10 && m.balance_moment < 1e-10,
                "{top:?} F/N = {}: {m:?}",
                c.fn_ratio
            );
            assert!((c.f / c.n - c.fn_ratio).abs() < 1e-12);
            // The model column is the torque balance with the push's arm h.
            assert!((m.slope_model - 12.0 * c.fn_ratio * 0.005 / 0.1).abs() < 1e-15);
            // The mean of p is N/L, and of tau F/L.
            let w = &r.unit.w_over_l;
            let mean_p: f64 = c.p.iter().zip(w).map(|(p, w)| p * w).sum();
            let mean_tau: f64 = c.tau.iter().zip(w).map(|(t, w)| t * w).sum();
            assert!(
                (mean_p - 1.0).abs() < 1e-10 && (mean_tau - c.fn_ratio).abs() < 1e-10,
                "{mean_p} {mean_tau}"
            );
        }
        r.self_check().unwrap();
    }
}

#[test]
fn the_pushed_corner_concentrates_shear_under_refinement() {
    // The trailing corner (x = -L/2, y = 0) joins the free face below the pusher to the bonded
    // interface: its stress is singular, so the corner node's shear grows without bound as h
    // shrinks (h, h/2, h/4).
    let peaks: Vec<f64> = [0.002, 0.001, 0.0005]
        .iter()
        .map(|&h| {
            let r = run(&side(Top::UniformPressure, h), &SolverOptions::default()).unwrap().0;
            let c = &r.cases[2];
            // The peak over the first t of the trailing end (the corner node by far).
            c.x_over_l
                .iter()
                .zip(&c.tau)
                .filter(|(x, _)| **x < -0.5 + 0.2)
                .map(|(_, t)| *t)
                .fold(f64::MIN, f64::max)
        })
        .collect();
    assert!(peaks[0] < peaks[1] && peaks[1] < peaks[2], "peak tau/(N/L) at the pushed corner: {peaks:?}");
    // And far above the mean shear F/N = 0.7.
    assert!(peaks[0] > 0.7, "{peaks:?}");
}

#[test]
fn a_side_pushed_scene_round_trips_without_height() {
    let s = side(Top::SlidingPlate, 0.002);
    let text = s.to_toml().unwrap();
    assert!(text.contains("rig = \"side-push\"") && !text.contains("height = 0.04"), "{text}");
    let dir = tempfile::tempdir().unwrap();
    let f = dir.path().join("s.toml");
    std::fs::write(&f, &text).unwrap();
    assert_eq!(Scene::from_file(&f).unwrap(), s);
    // The top-plate scene writes none of the new keys (its files are unchanged).
    let t = Scene::default().to_toml().unwrap();
    assert!(!t.contains("rig = ") && !t.contains("push_") && !t.contains("uniform-pressure"), "{t}");
    // A library caller cannot run a side-pushed scene through the top plate's model.
    assert!(s.build().err().unwrap().to_string().contains("loading.rig"));
}

fn tribofe(args: &[&str], out: &std::path::Path) -> (Option<i32>, String) {
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_tribofe"))
        .args(args)
        .arg("--out")
        .arg(out)
        .output()
        .unwrap();
    (o.status.code(), String::from_utf8_lossy(&o.stderr).into_owned())
}

#[test]
fn bad_side_push_input_is_refused_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let block = ["--length", "0.1", "--thickness", "0.02", "--h", "0.002", "--rig", "side-push"];
    let cases: &[(&[&str], &str)] = &[
        // above the block: 0.018 + 0.003 > t
        (&["--push-height", "0.018", "--push-width", "0.006"], "--push-height"),
        // wider than the face
        (&["--push-height", "0.01", "--push-width", "0.03"], "--push-width"),
        // at a negative height: 0.002 - 0.003 < 0
        (&["--push-height", "0.002", "--push-width", "0.006"], "--push-height"),
        (&["--push-height=-0.005", "--push-width", "0.006"], "--push-height"),
        // the spring
        (&["--push-height", "0.005", "--push-width", "0.006", "--push-stiffness", "0"], "--push-stiffness"),
        (&["--push-height", "0.005", "--push-width", "0.006", "--push-stiffness=-4e6"], "--push-stiffness"),
        // the top plate's H
        (&["--push-height", "0.005", "--push-width", "0.006", "--height", "0.01"], "--height"),
        // a contact of 1.5 element edges
        (&["--push-height", "0.005", "--push-width", "0.003"], "--h"),
        // a missing key
        (&["--push-width", "0.006"], "--push-height"),
        // a wrong name lists the accepted ones
        (&["--push-height", "0.005", "--push-width", "0.006", "--top", "plate"], "sliding-plate"),
    ];
    for (extra, named) in cases {
        let mut args = vec!["check"];
        args.extend(block);
        args.extend(*extra);
        let (code, err) = tribofe(&args, &out);
        assert_eq!(code, Some(2), "{args:?}: {err}");
        assert!(err.contains(named), "{args:?} should name {named}: {err}");
        assert!(!out.exists(), "{args:?} wrote {out:?}");
    }
    let (code, err) = tribofe(&["check", "--rig", "side-pushed"], &out);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("top-plate") && err.contains("side-push"), "{err}");
    // The side push's keys need the side push.
    let (code, err) = tribofe(&["check", "--push-height", "0.001"], &out);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("--push-height") && err.contains("side-push"), "{err}");
    // Commands that cannot run it yet name what can.
    for cmd in [&["precursors", "fe"][..], &["converge"], &["sweep"], &["stability"]] {
        let mut args = cmd.to_vec();
        args.extend(["--length", "0.1", "--thickness", "0.02", "--rig", "side-push"]);
        args.extend(["--push-height", "0.005", "--push-width", "0.006"]);
        let (code, err) = tribofe(&args, &out);
        assert_eq!(code, Some(2), "{args:?}: {err}");
        assert!(err.contains("--rig") && err.contains("tribofe check"), "{args:?}: {err}");
        assert!(!out.exists(), "{args:?} wrote {out:?}");
    }
    // In a scene file: the key, with its line.
    let scene = dir.path().join("s.toml");
    std::fs::write(
        &scene,
        "[block]\nlength = 0.1\nthickness = 0.02\n[mesh]\nh = 0.002\n[loading]\nrig = \"side-push\"\npush_height = 0.005\npush_width = 0.006\nheight = 0.01\n",
    )
    .unwrap();
    let msg = Scene::from_file(&scene).unwrap_err().to_string();
    assert!(msg.contains("line 10") && msg.contains("height"), "{msg}");
    // A top-plate file's height and the flag --rig side-push.
    std::fs::write(
        &scene,
        "[block]\nlength = 0.1\nthickness = 0.02\n[mesh]\nh = 0.002\n[loading]\nheight = 0.01\n",
    )
    .unwrap();
    let s = scene.to_str().unwrap();
    let (code, err) = tribofe(
        &["check", "--scene", s, "--rig", "side-push", "--push-height", "0.005", "--push-width", "0.006"],
        &out,
    );
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("loading.height"), "{err}");
    for (text, named) in [
        ("push_stiffness = 0.0\n", "push_stiffness"),
        ("push_width = 0.03\n", "push_width"),
        ("rig = \"sidepush\"\n", "side-push"),
    ] {
        let base = "[block]\nlength = 0.1\nthickness = 0.02\n[mesh]\nh = 0.002\n[loading]\nrig = \"side-push\"\npush_height = 0.005\n";
        let body = if text.starts_with("push_width") {
            format!("{base}{text}")
        } else {
            format!("{base}push_width = 0.006\n{text}")
        };
        let body = if text.starts_with("rig") { body.replace("rig = \"side-push\"\n", "") } else { body };
        std::fs::write(&scene, body).unwrap();
        let (code, err) = tribofe(&["check", "--scene", s], &out);
        assert_eq!(code, Some(2), "{text}: {err}");
        assert!(err.contains(named), "{text}: {err}");
    }
}

#[test]
fn check_runs_the_side_push_and_says_its_model() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_tribofe"))
        .args(["check", "--length", "0.1", "--thickness", "0.02", "--h", "0.002", "--rig", "side-push"])
        .args(["--push-height", "0.005", "--push-width", "0.006", "--top", "sliding-plate", "--no-fields"])
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(stdout.contains("side push") && stdout.contains("12 F h x / L^3"), "{stdout}");
    let run = std::fs::read_to_string(out.join("run.toml")).unwrap();
    assert!(run.contains("12 F h x / L^3") && run.contains("rig = \"side-push\""), "{run}");
    assert!(out.join("profile_FN0.82.csv").exists());
}

// Issue 49, phase 2: the side push in the quasi-static `slide` (the event solver on the
// condensed block with the rig's border: the pusher's U_p, or its spring's far end, driven).

use tribofe::interface::events::{EventKind, Phase};
use tribofe::law::{Law, Rule};
use tribofe::studies::slide::{run as slide, SlideOptions, SlideResult};

/// The frictional run of `side(top, 0.002)` under `law`, N = 1 N/m, with the driving spring
/// `k` (N/m per m) if given.
fn slid(top: Top, law: Law, k: Option<f64>) -> SlideResult {
    let mut scene = side(top, 0.002);
    scene.loading.push_stiffness = k;
    let o = SlideOptions { law, cycles: 1, ..Default::default() };
    slide(&scene, &o, tribofe::Progress::none()).unwrap()
}

#[test]
fn side_push_nucleates_the_first_slip_at_the_pushed_edge() {
    // The push at h = t/4 < t/2, where the top plate's rule would put the lowest pressure at
    // the leading edge: under side push p = N/L + 12 F h x/L^3 is lowest at x = -L/2.
    for top in [Top::UniformPressure, Top::SlidingPlate] {
        let r = slid(top, Law::static_kinetic(0.5, 0.45, Rule::Paper).unwrap(), None);
        let (k, e) = r
            .run
            .events
            .iter()
            .enumerate()
            .find(|(k, e)| {
                r.run.summaries[*k].phase == Phase::Drive && (e.region.is_some() || e.kind == EventKind::Slip)
            })
            .expect("a slip in the drive");
        assert_eq!(e.node, 0, "{top:?}: first slip (event {k}, {:?}) at node {}", e.kind, e.node);
        assert_eq!(r.condensed.x[0], -0.05, "{top:?}: node 0 is the pushed edge x = -L/2");
        assert_eq!(tribofe::studies::slide::nucleating_edge(&r).name(), "trailing");
    }
}

#[test]
fn side_push_force_equals_the_interface_shear() {
    // Horizontal balance of the block: the pusher's force F and the interface's shear
    // sum(T_i) are its only horizontal forces (the top: a pressure, or a plate free to slide),
    // in every recorded state: before the first slip (asserted to exist) and after. F + sum T
    // is S's x translation applied to b: S annihilates it to its rigid residual (~1e-15 of
    // max |S|), and a sprung pusher's free row holds to the solver's 1e-10 of the largest
    // force (tolerances::RESIDUAL): 1e-9 of N covers both at N = 1 N/m and F <= N.
    for top in [Top::UniformPressure, Top::SlidingPlate] {
        for k in [None, Some(1e9)] {
            let r = slid(top, Law::static_kinetic(0.5, 0.45, Rule::Paper).unwrap(), k);
            let first_slip =
                r.run.events.iter().position(|e| e.region.is_some() || e.kind == EventKind::Slip);
            assert!(first_slip.is_some_and(|s| s >= 1), "{top:?} {k:?}");
            let mut worst = 0.0f64;
            for st in &r.run.states {
                let shear: f64 = st.t_force.iter().sum();
                worst = worst.max((st.f + shear).abs() / st.n_force);
                let normal: f64 = st.p_force.iter().sum();
                assert!((normal - st.n_force).abs() <= 1e-9 * st.n_force, "{top:?} {k:?}: sum P {normal:e}");
            }
            eprintln!("{top:?} {k:?}: |F + sum T|/N <= {worst:e}");
            assert!(worst <= 1e-9, "{top:?} {k:?}: |F + sum T|/N = {worst:e}");
            // The drive force is F: with the spring, k (X - U_p) > 0 and X > U_p.
            let last = r.run.states.last().unwrap();
            assert!(last.f > 0.0 && last.x > 0.0, "{top:?} {k:?}");
        }
    }
}

#[test]
fn side_push_coulomb_peak_is_mu_n_at_full_sliding() {
    // Coulomb: |sum T_i| <= mu sum P_i = mu N in every state, equal once every contact node
    // slips one way. The states satisfy friction and balance to the run's largest violation v
    // (in N/n per node): summed over the n nodes, |F/N - mu| at most 2 v (friction and
    // balance), plus round-off.
    let mu = 0.5;
    for top in [Top::UniformPressure, Top::SlidingPlate] {
        let r = slid(top, Law::coulomb(mu).unwrap(), None);
        let tol = 2.0 * r.run.max_violation + 1e-9;
        let peak = r.run.states.iter().map(|s| s.f / s.n_force).fold(f64::MIN, f64::max);
        eprintln!("{top:?}: F_max/N = {peak}, tol {tol:e}");
        assert!(peak <= mu + tol, "{top:?}: F_max/N = {peak} above mu = {mu}");
        let full =
            r.run.states.iter().find(|s| s.states.iter().all(|q| q.name() != "stick")).expect("full sliding");
        assert!(
            (full.f / full.n_force - mu).abs() <= tol,
            "{top:?}: F/N = {} at full sliding, mu = {mu}",
            full.f / full.n_force
        );
        // Before full sliding the push is below mu N: the drive loads the pushed edge first.
        let first = &r.run.states[1];
        assert!(first.f / first.n_force < mu * (1.0 - 1e-3), "{top:?}: {}", first.f / first.n_force);
    }
}

#[test]
fn slide_runs_the_side_push_on_the_dense_operator_only() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let base = ["slide", "--length", "0.1", "--thickness", "0.02", "--h", "0.002", "--rig", "side-push"];
    let push = ["--push-height", "0.005", "--push-width", "0.006", "--push-stiffness", "1e9"];
    for (extra, named) in [(&["--operator", "banded"][..], "--operator"), (&["--fields", "2"], "--fields")] {
        let mut args = base.to_vec();
        args.extend(push);
        args.extend(extra);
        let (code, err) = tribofe(&args, &out);
        assert_eq!(code, Some(2), "{args:?}: {err}");
        assert!(err.contains(named), "{args:?} should name {named}: {err}");
        assert!(!out.exists(), "{args:?} wrote {out:?}");
    }
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_tribofe"))
        .args(base)
        .args(push)
        .args(["--law", "static-kinetic", "--cycles", "1", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let run = std::fs::read_to_string(out.join("run.toml")).unwrap();
    assert!(run.contains("far end of the pusher's spring") && run.contains("operator = \"dense\""), "{run}");
    assert!(out.join("events.csv").exists());
}

// Issue 49, phase 3: the side push in `slide --dynamics` (the explicit events on the rig's
// border: the pusher driven or sprung, the top under the pressure or the sliding plate).

use tribofe::studies::dynamic_slide::{self as ds, DynamicOptions, DynamicResult};

/// A thin side-pushed block with slip weakening the mesh resolves: L = 0.1 m, t = 4 mm,
/// h = 0.5 mm, the pusher 2 mm wide at 2 mm (4 element edges); mu_s = 0.6, mu_d = 0.2,
/// D_c = 6e-6 m (Lambda_0 = 3.16 h, thin-layer kappa = 0.27: precursors possible), N = 1 N/m,
/// drive held in each event, to `x_max`.
fn thin_dynamic(top: Top, k: Option<f64>, x_max: f64) -> DynamicResult {
    let scene = Scene::default()
        .apply(&Overrides {
            length: Some(0.1),
            thickness: Some(0.004),
            h: Some(0.0005),
            rig: Some(Rig::SidePush),
            push_height: Some(0.002),
            push_width: Some(0.002),
            push_stiffness: k,
            top: Some(top),
            ..Default::default()
        })
        .unwrap();
    let o = SlideOptions {
        law: Law::slip_weakening(0.6, 0.2, 6e-6).unwrap(),
        x_max: Some(x_max),
        operator: ds::default_operator(&scene),
        ..Default::default()
    };
    ds::run(&scene, &o, &DynamicOptions::default(), tribofe::Progress::none()).unwrap()
}

#[test]
fn dynamic_side_push_nucleates_its_first_instability_at_the_pushed_edge() {
    // The push's torque unloads the trailing edge (p = N/L + 12 F h x/L^3 lowest at
    // x = -L/2): the drive's first slip is there, and the first instability runs from it, a
    // precursor whose slipped run starts at the edge node and whose first node past D_c/100
    // of event slip lies within the cohesive zone Lambda_0 of the edge (the weakening zone
    // that goes unstable is the edge's). Fixed grips (U_p held in the event, the pressure
    // dead) are the fracture prediction's own assumptions: its arrest within 0.01 L of the
    // dynamic one (the tolerance; measured 0.005 L, one node).
    for (top, k, x_max) in [(Top::UniformPressure, None, 3e-5), (Top::SlidingPlate, Some(1e5), 5e-5)] {
        let r = thin_dynamic(top, k, x_max);
        let (c, run) = (&r.slide.condensed, &r.slide.run);
        assert_eq!(c.x[0], -0.05);
        // The first state with slipping nodes has the edge node slipping (N alone, with the
        // pusher held, pre-slips both ends outwards: the block's Poisson expansion).
        let first =
            run.states.iter().find(|st| st.states.iter().any(|q| q.name() == "slip")).expect("a slip");
        assert_eq!(first.states[0].name(), "slip", "{top:?}");
        let ev = r.events.iter().find(|e| e.record.weakened).expect("an instability");
        let kind = run.events[ev.event].kind;
        let node = ev.record.nucleation.expect("nucleated");
        let a5 = ev.assumption5.expect("assumption 5 measured");
        eprintln!(
            "{top:?} {k:?}: first instability (event {}) {kind} at F/(mu_s N) = {:.4}, nucleation x/L = {:.4} (Lambda_0/L = {:.4}), arrest {:.4}, predicted (fracture) {:.4}",
            ev.event,
            ev.f_onset / (0.6 * 1.0),
            c.x[node] / c.l,
            r.lambda0 / c.l,
            a5.arrest / c.l,
            a5.predicted_fracture / c.l
        );
        assert_eq!(kind, EventKind::Precursor, "{top:?}");
        assert_eq!(run.events[ev.event].region.unwrap().0, 0, "{top:?}: the slipped run starts at the edge");
        assert!(c.x[node] - c.x[0] <= r.lambda0, "{top:?}: nucleation at x = {}", c.x[node]);
        assert!(a5.predicted_fracture.is_finite() && a5.arrest.is_finite());
        if k.is_none() {
            assert!((a5.predicted_fracture - a5.arrest).abs() <= 0.01 * c.l, "{top:?}: {a5:?}");
        }
    }
}

#[test]
fn dynamic_side_push_static_states_balance_force() {
    // After each dynamic event the static equilibrium is solved with every contact node
    // anchored where the event left it: the states handed back balance the block as the
    // quasi-static ones do (F + sum T = 0 and sum P = N to 1e-9 of N: S's rigid residual and
    // the solver's 1e-10 of the largest force, as side_push_force_equals_the_interface_shear).
    for (top, k, x_max) in [(Top::UniformPressure, None, 3e-5), (Top::SlidingPlate, Some(1e5), 5e-5)] {
        let r = thin_dynamic(top, k, x_max);
        assert!(r.events.iter().any(|e| e.record.weakened), "{top:?}: no instability");
        let run = &r.slide.run;
        assert!(run.states.len() == run.events.len() && run.states.len() > 2);
        let mut worst = 0.0f64;
        for st in &run.states {
            let shear: f64 = st.t_force.iter().sum();
            let normal: f64 = st.p_force.iter().sum();
            worst =
                worst.max((st.f + shear).abs() / st.n_force).max((normal - st.n_force).abs() / st.n_force);
        }
        eprintln!("{top:?} {k:?}: {} states, |F + sum T|, |sum P - N| <= {worst:e} N", run.states.len());
        assert!(worst <= 1e-9, "{top:?} {k:?}: {worst:e}");
        // The dynamic events end near their static equilibrium (F within 1 % of mu_s N), and
        // the scheme's exact ledger (the pressure's, the plate's N and the spring's or the
        // driven pusher's work counted as the rig's) closes to round-off: 1e-9 of the dissipation.
        for e in &r.events {
            assert!(e.f_gap < 1e-2, "{top:?}: event {} f_gap {}", e.event, e.f_gap);
            let en = &e.record.energy;
            let rel = en.residual.abs() / (en.friction + en.damping);
            assert!(rel < 1e-9, "{top:?}: event {} ledger residual {rel:e}", e.event);
        }
    }
}

#[test]
fn coulomb_side_push_at_constant_velocity_follows_the_event_solver() {
    // Coulomb, mu = 0.5, on the thick block of `side` (t = L/5, h = 2 mm) to X = 2.5e-4 m,
    // past its whole slip: the explicit drive at V (pusher driven, or its spring's far end)
    // settles on the static path shifted by the Kelvin-Voigt lag eta V k, k at most the
    // bonded stiffness: |F - F_qs| <= 2 eta V k_bonded (the bound and the reasoning of
    // dynamics_velocity::coulomb_slow_drive_reproduces_the_event_solver), and the slipping
    // node count within one of the event solver's at every sample. Both tops.
    for (top, k) in [(Top::UniformPressure, None), (Top::SlidingPlate, Some(1e6))] {
        let mut scene = side(top, 0.002);
        scene.loading.push_stiffness = k;
        let o = SlideOptions {
            law: Law::coulomb(0.5).unwrap(),
            x_max: Some(2.5e-4),
            operator: ds::default_operator(&scene),
            ..Default::default()
        };
        let qs = slide(&scene, &o, tribofe::Progress::none()).unwrap();
        let v = 1e-5;
        let d = DynamicOptions { drive_velocity: Some(v), ..Default::default() };
        let dy = ds::run(&scene, &o, &d, tribofe::Progress::none()).unwrap();
        let (err, nodes, samples) = crate::dynamics_velocity::against_static(&qs, &dy.slide, 0.5);
        let bound = 2.0 * dy.eta * v * qs.run.k_bonded / 0.5;
        eprintln!("{top:?} {k:?}: max |dF| = {err:.3e} mu N (bound {bound:.3e}), slip count within {nodes} over {samples} samples");
        assert!(samples > 1000, "{samples}");
        assert!(err <= bound, "{top:?}: |dF| {err:e} above {bound:e}");
        assert!(nodes <= 1, "{top:?}: {nodes}");
    }
}

#[test]
fn dynamic_side_push_refuses_what_it_cannot_run() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let base = ["slide", "--dynamics", "--law", "coulomb", "--length", "0.1", "--thickness", "0.02"];
    let push = ["--h", "0.002", "--rig", "side-push", "--push-height", "0.005", "--push-width", "0.006"];
    for (extra, named) in [
        (&["--operator", "banded"][..], "--operator"),
        (&["--plate-mass", "0.1"], "--plate-mass"),
        (&["--plate-inertia", "1e-6"], "--plate-inertia"),
    ] {
        let args: Vec<&str> = [&base[..], &push, extra].concat();
        let (code, err) = tribofe(&args, &out);
        assert_eq!(code, Some(2), "{args:?}: {err}");
        assert!(err.contains(named), "{args:?} should name {named}: {err}");
        assert!(!out.exists(), "{args:?} wrote {out:?}");
    }
    // The default operator is dense, and run.toml says what X is.
    let args: Vec<&str> = [&base[..], &push, &["--x-max", "1e-5"]].concat();
    let (code, err) = tribofe(&args, &out);
    assert_eq!(code, Some(0), "{err}");
    let run = std::fs::read_to_string(out.join("run.toml")).unwrap();
    assert!(run.contains("operator = \"dense\"") && run.contains("the pusher's displacement U_p"), "{run}");
    assert!(run.contains("side push's default (dense)"), "{run}");
}

#[test]
fn side_push_defaults_to_the_papers_coefficients_whatever_the_push_height() {
    // g = 6 mu_d H/L is the top plate's: read through the push height it would set mu_d =
    // 0.35 L / (6 h), 2.9 under a pusher at 0.02 L. The side push keeps the paper's friction,
    // that of (r, g) = (0.9, 0.35) at H/L = 0.1: mu_d = 0.35 / 0.6, mu_s = mu_d / 0.9.
    for h in [0.002, 0.005, 0.015] {
        let mut s = side(Top::UniformPressure, 0.002);
        s.loading.push_height = Some(h);
        let (mu_s, mu_d) = tribofe::studies::slide::default_coefficients(&s).unwrap();
        assert!(
            (mu_d - 0.35 / 0.6).abs() < 1e-14 && (mu_s - 0.35 / 0.6 / 0.9).abs() < 1e-14,
            "{mu_s} {mu_d}"
        );
    }
}
