//! `slide --dynamics --drive-velocity`: the constant-velocity drive against the exact
//! quasi-static loading and the held-drive mode, its refusals, and the rigid plate's mass and
//! rotational inertia (issue 33). Small scenes: a few seconds in release mode.

use tribofe::dynamics::driven::{Contact, Driven, DynState, EventEnergy, Layout};
use tribofe::dynamics::explicit::Elastodynamic;
use tribofe::fem::material::Material;
use tribofe::interface::condense::{boundary_model, condense};
use tribofe::interface::events::{EventKind, NodeState, Operator, Phase};
use tribofe::law::{Law, Normal};
use tribofe::linalg::solve::SolverOptions;
use tribofe::scene::Scene;
use tribofe::studies::dynamic_slide::{self as ds, DynamicOptions};
use tribofe::studies::slide::{self, SlideOptions, SlideResult};

/// The paper's block (t = 2 mm, H = 4 cm) with `l` and `h` changed.
fn block(l: f64, h: f64) -> Scene {
    crate::dynamics::block(l, h, None)
}

fn at_velocity(v: f64) -> DynamicOptions {
    DynamicOptions { drive_velocity: Some(v), ..Default::default() }
}

fn slipping(s: &tribofe::interface::events::State) -> usize {
    s.states.iter().filter(|n| matches!(n, NodeState::Slip(_))).count()
}

/// Largest |F_V(X) - F_qs(X)| / (mu N) over the drive samples of `dy`, with F_qs linear
/// between the event solver's states (exact: between two events the static path is affine
/// in X), and the largest difference of slipping-node counts against the static state that
/// holds at the sample's X.
pub(crate) fn against_static(qs: &SlideResult, dy: &SlideResult, mu_n: f64) -> (f64, usize, usize) {
    let drive: Vec<_> = qs.run.states.iter().filter(|s| s.phase == Phase::Drive).collect();
    let (mut err, mut worst_nodes, mut samples) = (0.0f64, 0usize, 0usize);
    for (e, s) in dy.run.events.iter().zip(&dy.run.states) {
        if e.kind != EventKind::Sample || s.x <= drive[0].x || s.x >= drive.last().unwrap().x {
            continue;
        }
        let k = drive.partition_point(|q| q.x <= s.x) - 1;
        let (a, b) = (drive[k], drive[k + 1]);
        let f = if b.x > a.x { a.f + (b.f - a.f) * (s.x - a.x) / (b.x - a.x) } else { a.f };
        err = err.max((s.f - f).abs() / mu_n);
        worst_nodes = worst_nodes.max(slipping(s).abs_diff(slipping(a)));
        samples += 1;
    }
    (err, worst_nodes, samples)
}

#[test]
fn coulomb_slow_drive_reproduces_the_event_solver() {
    // Coulomb friction, mu = 0.5, L = 0.1 m, h = 1 mm, to X = 3.4e-5 m (whole slip at
    // 3.26e-5 m). With stiffness-proportional damping a linear system driven at constant V
    // settles on the static path shifted by the Kelvin-Voigt lag: F - F_qs = eta V k with k
    // at most the bonded stiffness k_bonded (slipping nodes only soften it). So the error is
    // bounded by eta V k_bonded / (mu N) and falls like V (measured: ratios 2.15, 1.90 per
    // halving, 0.57-0.61 of the bound). Slip extents: within one node of the event solver's
    // state at every sample of the drive (the tolerance; measured: exactly within one).
    let scene = block(0.1, 0.001);
    let o = SlideOptions { law: Law::coulomb(0.5).unwrap(), x_max: Some(3.4e-5), ..Default::default() };
    let qs = slide::run(&scene, &o, tribofe::Progress::none()).unwrap();
    let mut errs = vec![];
    for v in [1e-5, 5e-6, 2.5e-6] {
        let dy = ds::run(&scene, &o, &at_velocity(v), tribofe::Progress::none()).unwrap();
        let (err, nodes, samples) = against_static(&qs, &dy.slide, 0.5);
        // The steady Kelvin-Voigt lag is eta V k <= eta V k_bonded; where a node changes
        // state the lag moves between two such values, and a damped oscillator overshoots a
        // step by less than the step itself: at most twice the bonded lag. (Measured 1.08 x
        // at 10 um/s once loading.csv's rows pair X^n with F^n; the order-1 ratio below is
        // the sharp check.)
        let bound = 2.0 * dy.eta * v * qs.run.k_bonded / 0.5;
        eprintln!("V = {v:e}: max |dF| = {err:.3e} mu N (lag bound {bound:.3e}), slip count within {nodes} node(s) over {samples} samples");
        assert!(samples > 1000, "{samples} samples");
        assert!(err <= bound, "V = {v}: |dF| {err:e} above the Kelvin-Voigt lag {bound:e}");
        assert!(nodes <= 1, "V = {v}: slipping nodes differ by {nodes}");
        assert!(dy.events.is_empty(), "V = {v}: {} events in a Coulomb run", dy.events.len());
        errs.push(err);
        // loading.csv's rows are one time level each (X^n with F^n): on a static segment
        // (states unchanged between two events, slope k = dF/dX exact) the drive's F sits
        // at F_qs + eta V k once the start's transient has decayed (second half of segments
        // lasting 10 thickness periods or more); a row carrying F^(n-1) would sit at
        // (eta - dt) V k, 1 - dt / eta = 0.7 of it here.
        let period = 2.0 * std::f64::consts::PI / dy.omega_thickness;
        let drive: Vec<_> = qs.run.states.iter().filter(|s| s.phase == Phase::Drive).collect();
        let mut ratios = vec![];
        for (e, s) in dy.slide.run.events.iter().zip(&dy.slide.run.states) {
            let k = drive.partition_point(|q| q.x <= s.x);
            if e.kind != EventKind::Sample || k == 0 || k >= drive.len() {
                continue;
            }
            let (a, b) = (drive[k - 1], drive[k]);
            if (b.x - a.x) / v < 10.0 * period || s.x < 0.5 * (a.x + b.x) {
                continue;
            }
            let slope = (b.f - a.f) / (b.x - a.x);
            ratios.push((s.f - (a.f + slope * (s.x - a.x))) / (dy.eta * v * slope));
        }
        ratios.sort_by(f64::total_cmp);
        let med = ratios[ratios.len() / 2];
        eprintln!(
            "V = {v:e}: (F - F_qs) / (eta V k) median {med:.4} over {} rows, dt / eta = {:.3}",
            ratios.len(),
            dy.dt / dy.eta
        );
        assert!(ratios.len() > 100 && (med - 1.0).abs() < 0.02, "{med} over {} rows", ratios.len());
    }
    for w in errs.windows(2) {
        let ratio = w[0] / w[1];
        assert!((1.5..3.0).contains(&ratio), "error ratio per halving {ratio} (order 1 expected)");
    }
}

#[test]
fn slip_weakening_events_are_read_at_the_laws_rate_and_approach_the_held_limit() {
    // L = 0.1 m, h = 0.5 mm, (r, g) = (0.9, 0.35), D_c = 2.3107e-7 m. Events are read at the
    // law's own threshold (the front arrival rate, 1.917e-6 m/s here), whatever V, and V is
    // refused above a tenth of it, where creep at ~V cannot be told from an instability.
    let (scene, o) = crate::dynamics::short_weakening(Operator::Dense, 4.9e-6);
    let mu_s = o.law.mu_s();
    let thr = ds::physics::event_rate(&scene, mu_s, o.law.mu_d(), o.n_force).unwrap();
    assert!((thr - 1.917e-6).abs() < 1e-9, "{thr}");
    let e = ds::run(&scene, &o, &at_velocity(1e-6), tribofe::Progress::none()).unwrap_err();
    let m = e.to_string();
    assert!(m.contains("--drive-velocity <= 1.917e-7") && e.exit_status() == 2, "{m}");
    // The held mode's limit as its coefficient updates per D_c grow (0.771948, 0.771944 at
    // 80, 320; validation/dynamics/velocity): the V -> 0 limit of the drive.
    let held = DynamicOptions { weakening_steps: 320.0, ..Default::default() };
    let held = ds::run(&scene, &o, &held, tribofe::Progress::none()).unwrap();
    let first = |r: &ds::DynamicResult| -> (f64, f64, (usize, usize)) {
        let e = r.events.iter().find(|e| e.record.weakened).expect("an instability");
        (e.x, e.f_onset / mu_s, r.slide.run.events[e.event].region.expect("region"))
    };
    let (x_h, f_h, reg_h) = first(&held);
    // At the largest V accepted: a slow drive crosses the stability limit late by the time
    // the unstable patch takes to grow and F rises by about k_bonded V meanwhile: measured
    // order 1 in V, dF = 5.2e-4 mu_s N at 5e-7 m/s (the 10 V threshold's series), so
    // 2.0e-4 at 1.9e-7; asserted within twice that. The onset X within 0.5 % (dX = 9e-10 m
    // at 5e-7 m/s), the slipped region the held one's to one node, and the instability
    // healed (the drive's slip memory is back at 0 after it: no second weakening at mu_d).
    let v = 0.1 * thr;
    let r = ds::run(&scene, &o, &at_velocity(v), tribofe::Progress::none()).unwrap();
    let (x, f, reg) = first(&r);
    eprintln!("V = {v:e}: first instability X = {x:.6e} (held {x_h:.6e}), F = {f:.6} (held {f_h:.6}) mu_s N, nodes {reg:?} (held {reg_h:?})");
    assert!((x - x_h).abs() < 0.005 * x_h, "onset X {x:e} vs {x_h:e}");
    assert!((f - f_h).abs() < 4e-4, "onset F {f} vs the held limit {f_h}");
    assert!(reg.0.abs_diff(reg_h.0) <= 1 && reg.1.abs_diff(reg_h.1) <= 1, "{reg:?} vs {reg_h:?}");
    assert_eq!(r.events.iter().filter(|e| e.record.weakened).count(), 1);
}

#[test]
fn constant_velocity_refuses_what_it_cannot_bound() {
    let scene = block(0.1, 0.001);
    let o = SlideOptions { law: Law::coulomb(0.5).unwrap(), x_max: Some(3.4e-5), ..Default::default() };
    for v in [0.0, -1e-5, f64::NAN, f64::INFINITY] {
        let e = ds::run(&scene, &o, &at_velocity(v), tribofe::Progress::none()).unwrap_err();
        assert!(e.to_string().contains("--drive-velocity") && e.exit_status() == 2, "{v}: {e}");
    }
    let no_x = SlideOptions { x_max: None, ..o.clone() };
    let e = ds::run(&scene, &no_x, &at_velocity(1e-5), tribofe::Progress::none()).unwrap_err();
    assert!(e.to_string().contains("--x-max") && e.exit_status() == 2, "{e}");
    // 3.4e-5 m at 1e-12 m/s is 2e11 steps: refused with the smallest V the cap allows.
    let e = ds::run(&scene, &o, &at_velocity(1e-12), tribofe::Progress::none()).unwrap_err();
    let m = e.to_string();
    assert!(m.contains("cap") && m.contains("--drive-velocity >=") && e.exit_status() == 2, "{m}");
    let neg = DynamicOptions { plate_mass: -1.0, ..at_velocity(1e-5) };
    let e = ds::run(&scene, &o, &neg, tribofe::Progress::none()).unwrap_err();
    assert!(e.to_string().contains("--plate-mass"), "{e}");
    let nan = DynamicOptions { plate_inertia: f64::NAN, ..Default::default() };
    let e = ds::run(&scene, &o, &nan, tribofe::Progress::none()).unwrap_err();
    assert!(e.to_string().contains("--plate-inertia"), "{e}");
}

/// Symmetric 2x2 generalized eigenproblem K phi = w^2 M phi: (w^2, phi) ascending.
fn eig2(k: [[f64; 2]; 2], m: [[f64; 2]; 2]) -> [(f64, [f64; 2]); 2] {
    // det(K - l M) = 0: a l^2 + b l + c = 0.
    let a = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    let b = -(k[0][0] * m[1][1] + k[1][1] * m[0][0] - k[0][1] * m[1][0] - k[1][0] * m[0][1]);
    let c = k[0][0] * k[1][1] - k[0][1] * k[1][0];
    let d = (b * b - 4.0 * a * c).sqrt();
    let ls = [(-b - d) / (2.0 * a), (-b + d) / (2.0 * a)];
    ls.map(|l| {
        // (K - l M) phi = 0 from its better-conditioned row.
        let r0 = [k[0][0] - l * m[0][0], k[0][1] - l * m[0][1]];
        let r1 = [k[1][0] - l * m[1][0], k[1][1] - l * m[1][1]];
        let r = if r0[0].hypot(r0[1]) >= r1[0].hypot(r1[1]) { r0 } else { r1 };
        let phi = [-r[1], r[0]];
        let s = phi[0].hypot(phi[1]);
        (l, [phi[0] / s, phi[1] / s])
    })
}

#[test]
fn heavy_plate_rings_at_the_rigid_body_frequencies() {
    // The plate (m_p, I_c 1000 times the block's mass and its inertia about the drive
    // point) on the block, base stuck (mu = 100, pressed by N), drive held: its two modes
    // (V, theta) are those of the 2x2 problem K_p phi = w^2 M_p phi, K_p the block's static
    // stiffness on the plate DOFs (the condensed S with the base held), M_p the plate's mass
    // matrix (own + top nodes). Each mode is started alone (plate at its static position
    // under N, a velocity along phi) and its frequency read from the zero crossings of the
    // M_p-projection on phi over three periods. The block's remaining mass adds at most its
    // rigid-body inertia r M in the mode (r = that / phi^T M_p phi), so w falls by at most
    // r/2; central differences raise it by (w dt)^2/24; the crossings are interpolated
    // linearly (1e-4). Tolerance: r/2 + (w dt)^2/24 + 1e-4.
    let scene = block(0.1, 0.001);
    let (sm, _) = boundary_model(&scene).unwrap();
    let mat = Material::plane_strain(scene.block.young, scene.block.poisson).unwrap();
    let model = Elastodynamic::new(&sm.mesh, mat, scene.block.density).unwrap();
    let c = condense(&scene, &SolverOptions::default()).unwrap();
    let (t, hgt) = (scene.block.thickness, scene.loading.height);
    let arm = hgt - t;
    let top = sm.mesh.set_nodes(&sm.top_set).unwrap();
    let top_x: Vec<f64> = top.iter().map(|&k| sm.mesh.nodes[k][0]).collect();
    let m_block: f64 = model.mass.iter().sum();
    let i_block: f64 = (0..model.n_nodes())
        .map(|k| {
            let [x, y] = sm.mesh.nodes[k];
            model.mass[k] * (x * x + (hgt - y) * (hgt - y))
        })
        .sum();
    let (mp, ic) = (1000.0 * m_block, 1000.0 * i_block);
    let layout = Layout::new(&model, sm.interface.clone(), c.x.clone(), top.clone(), top_x.clone(), arm)
        .with_plate(mp, ic)
        .unwrap();
    assert!((layout.x_c).abs() < 1e-12 * scene.block.length, "x_c {}", layout.x_c);
    let omega_t =
        std::f64::consts::PI * tribofe::dynamics::waves::WaveSpeeds::new(&mat, 1000.0).c_s / (2.0 * t);
    let eta = 0.2 / omega_t;
    let dt = 0.9 * model.critical_dt(eta);
    let n_force = 1.0;
    let driven = Driven {
        model: &model,
        layout: &layout,
        law: Law::coulomb(100.0).unwrap(),
        normal: Normal::Instantaneous,
        n_force,
        dt,
        eta,
    };
    // K_p: S at height H on (V, theta) with the interface held.
    let s = c.at_height(hgt);
    let nd = c.dim();
    let (iv, it) = (2 * c.n + 1, 2 * c.n + 2);
    let kp = [[s[iv * nd + iv], s[iv * nd + it]], [s[it * nd + iv], s[it * nd + it]]];
    let mpm = layout.plate_matrix();
    // Static position under N: K_p q = (-N, 0).
    let det = kp[0][0] * kp[1][1] - kp[0][1] * kp[1][0];
    let qs = [-n_force * kp[1][1] / det, n_force * kp[1][0] / det];
    let modes = eig2(kp, mpm);
    for (l, phi) in modes {
        let w = l.sqrt();
        let modal_mass = phi[0] * (mpm[0][0] * phi[0] + mpm[0][1] * phi[1])
            + phi[1] * (mpm[1][0] * phi[0] + mpm[1][1] * phi[1]);
        // Rigid-body inertia of the non-top nodes in the mode (an upper bound of what they add).
        let extra: f64 = (0..model.n_nodes())
            .filter(|k| !top.contains(k))
            .map(|k| {
                let [x, y] = sm.mesh.nodes[k];
                let (ux, uy) = ((hgt - y) * phi[1], phi[0] + x * phi[1]);
                model.mass[k] * (ux * ux + uy * uy)
            })
            .sum();
        let r = extra / modal_mass;
        // Amplitude 20 % of the static compression: contact stays closed.
        let amp = 0.2 * qs[0].abs() / (phi[0].abs() + 0.5 * scene.block.length * phi[1].abs());
        let qdot = [amp * w * phi[0], amp * w * phi[1]];
        let mut u = vec![0.0; model.n_dofs()];
        let mut v = vec![0.0; model.n_dofs()];
        for (&k, &x) in top.iter().zip(&top_x) {
            u[2 * k] = arm * qs[1];
            u[2 * k + 1] = qs[0] + x * qs[1];
            v[2 * k] = arm * qdot[1];
            v[2 * k + 1] = qdot[0] + x * qdot[1];
        }
        let mut st = DynState {
            u,
            v,
            u_h: 0.0,
            drive_velocity: 0.0,
            q: qs,
            qdot,
            d: vec![0.0; c.n],
            ..Default::default()
        };
        let mut wk = driven.work(&st);
        let mut e = EventEnergy::default();
        let mut contact = vec![Contact::default(); c.n];
        let proj = |q: [f64; 2]| {
            let dq = [q[0] - qs[0], q[1] - qs[1]];
            phi[0] * (mpm[0][0] * dq[0] + mpm[0][1] * dq[1])
                + phi[1] * (mpm[1][0] * dq[0] + mpm[1][1] * dq[1])
        };
        let steps = (3.2 * 2.0 * std::f64::consts::PI / w / dt).ceil() as usize;
        let (mut prev, mut crossings) = (proj(st.q), Vec::new());
        let mut opened = 0usize;
        for _ in 0..steps {
            driven.step(&mut st, &mut wk, &mut e, &mut contact);
            opened += contact.iter().filter(|c| c.open).count();
            let now = proj(st.q);
            if prev != 0.0 && (prev < 0.0) != (now < 0.0) {
                crossings.push(st.time - dt * now / (now - prev));
            }
            prev = now;
        }
        let n = crossings.len();
        assert!(n >= 6, "{n} crossings");
        let w_meas = std::f64::consts::PI * (n - 1) as f64 / (crossings[n - 1] - crossings[0]);
        let tol = 0.5 * r + (w * dt).powi(2) / 24.0 + 1e-4;
        eprintln!(
            "mode phi = ({:.4}, {:.4}): w = {w:.6} rad/s, measured {w_meas:.6} ({:+.2e}), tolerance {tol:.2e} (r = {r:.2e}); open node-steps {opened}",
            phi[0],
            phi[1],
            w_meas / w - 1.0
        );
        assert!((w_meas / w - 1.0).abs() <= tol, "w {w_meas} vs {w}");
        assert!(w_meas <= w * (1.0 + (w * dt).powi(2) / 24.0 + 1e-4), "w {w_meas} above {w}");
    }
    // The plate's own mass matters: the vertical mode of the massless plate is ~30x faster.
    let light = Layout::new(&model, sm.interface.clone(), c.x.clone(), top, top_x, arm).plate_matrix();
    assert!(light[0][0] < 1e-2 * mpm[0][0]);
}

#[test]
fn ledger_closes_with_a_heavy_plate_and_a_moving_drive() {
    // Slip weakening at the largest V it accepts (1.9e-7 m/s) with a plate of 10x the
    // block's mass and inertia, through the first instability: over each dynamic event,
    // shadow kinetic (block + plate) + strain + friction + damping = work of N + contact work
    // + drive work, to round-off (tolerance 1e-8 of the event's dissipation, as for the held
    // drive).
    let (scene, o) = crate::dynamics::short_weakening(Operator::Dense, 4.9e-6);
    let m_block = 1000.0 * 0.1 * scene.block.thickness;
    let d = DynamicOptions {
        plate_mass: 10.0 * m_block,
        plate_inertia: 10.0 * m_block * 0.04 * 0.04,
        ..at_velocity(1.9e-7)
    };
    let r = ds::run(&scene, &o, &d, tribofe::Progress::none()).unwrap();
    assert!(r.events.iter().any(|e| e.record.weakened), "no instability");
    for e in &r.events {
        let en = &e.record.energy;
        let diss = en.friction + en.damping;
        assert!(en.drive != 0.0 && diss > 0.0, "event {}: {en:?}", e.event);
        assert!(
            en.residual.abs() <= 1e-8 * diss,
            "event {}: residual {:e} of {diss:e}",
            e.event,
            en.residual
        );
    }
}
