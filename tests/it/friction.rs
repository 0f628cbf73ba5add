//! The frictional interface (issue 17): condensation, coulomb and static-kinetic laws solved
//! event by event. Tolerances come from the theory: round-off for the limits (bonded, mu = 0,
//! whole sliding), complementarity to round-off for every state, the thin-layer closed form
//! for the coulomb slip front (offset O(t), shrinking in units of L with t).

use tribofe::analytical::partial_slip;
use tribofe::interface::condense::condense;
use tribofe::interface::events::EventKind;
use tribofe::interface::events::Phase;
use tribofe::law::{Law, Rule};
use tribofe::linalg::solve::SolverOptions;
use tribofe::scene::Scene;
use tribofe::studies::slide::{coefficients_from_rg, run, trailing_front, SlideOptions, SlideResult};

/// The paper's block on a coarser mesh (t = 2 mm, h = 2 mm along x, 2 elements through).
fn coarse() -> Scene {
    let mut s = Scene::default();
    s.mesh.h = 0.002;
    s.mesh.n_thick = Some(2);
    s
}

/// A block of thickness t with h = t and 2 elements through the thickness.
fn thin(t: f64) -> Scene {
    let mut s = Scene::default();
    s.block.thickness = t;
    s.mesh.h = t;
    s.mesh.n_thick = Some(2);
    s
}

fn slide(scene: &Scene, law: Law, x_max: Option<f64>) -> SlideResult {
    let o = SlideOptions { law, x_max, ..Default::default() };
    run(scene, &o, tribofe::Progress::none()).unwrap()
}

fn worst_violation(r: &SlideResult) -> f64 {
    r.run.max_violation
}

#[test]
fn condensed_stiffness_is_symmetric_and_free_of_rigid_motions() {
    let c = condense(&coarse(), &SolverOptions::default()).unwrap();
    assert_eq!(c.n, 201);
    assert!(c.asymmetry < 1e-12, "asymmetry {:e}", c.asymmetry);
    assert!(c.rigid_residual < 1e-12, "rigid residual {:e}", c.rigid_residual);
    let w: f64 = c.w.iter().sum();
    assert!((w - 0.4).abs() < 1e-14, "tributary widths sum to {w}");
}

/// mu = 1e6 (the largest accepted): nothing slips, so the state at any X is the bonded one of `check` (superposition
/// of the N and X states gives any F/N); both come from the same FE model, so they agree to
/// round-off.
#[test]
fn large_mu_reproduces_the_bonded_check() {
    let scene = coarse();
    let r = slide(&scene, Law::coulomb(1e6).unwrap(), Some(1e-6));
    assert!(r.run.events.iter().all(|e| matches!(e.kind, EventKind::NormalLoad | EventKind::End)));
    let (s0, s1) = (&r.run.states[0], r.run.states.last().unwrap());
    let mut sc = scene.clone();
    sc.loading.fn_ratios = vec![0.0, 0.41, 0.82];
    let chk = tribofe::studies::check::run(&sc, &SolverOptions::default()).unwrap().0;
    let c = &r.condensed;
    let pm = 1.0 / c.l;
    let tilt_max = chk.cases.iter().fold(0.0f64, |m, c| m.max(c.tilt.abs()));
    for case in &chk.cases {
        // X such that F = ratio N (F is affine in X between the two states).
        let a = (case.fn_ratio - s0.f) / (s1.f - s0.f);
        let mut dev = 0.0f64;
        for i in 0..c.n {
            let p = (s0.p_force[i] + a * (s1.p_force[i] - s0.p_force[i])) / c.w[i] / pm;
            let tau = -(s0.t_force[i] + a * (s1.t_force[i] - s0.t_force[i])) / c.w[i] / pm;
            dev = dev.max((p - case.p[i]).abs()).max((tau - case.tau[i]).abs());
        }
        assert!(dev < 1e-9, "F/N = {}: |p, tau - check| up to {dev:e} of N/L", case.fn_ratio);
        let tilt = s0.tilt + a * (s1.tilt - s0.tilt);
        // check's N is that of its unit case, ours is 1 N/m: compare the tilt per unit N.
        let tc = case.tilt / case.n;
        assert!((tilt - tc).abs() < 1e-9 * tilt_max / case.n, "tilt {tilt} vs {tc}");
    }
    assert!(worst_violation(&r) < 1e-9);
}

#[test]
fn zero_mu_is_refused_before_any_work() {
    // Every result of slide is in units of mu_s N, so mu = 0 is refused, with or without an
    // end X (it once ran to --x-max and returned F/(mu_s N) = inf to Python).
    for x_max in [None, Some(1e-6)] {
        let o = SlideOptions { law: Law::coulomb(0.0).unwrap(), x_max, ..Default::default() };
        let e = run(&coarse(), &o, tribofe::Progress::none()).unwrap_err();
        assert!(e.to_string().contains("--mu") && e.exit_status() == 2, "{e}");
    }
}

#[test]
fn coulomb_whole_sliding_is_at_mu_n_and_every_state_is_admissible() {
    let mu = 0.5;
    let r = slide(&coarse(), Law::coulomb(mu).unwrap(), None);
    let sliding: Vec<usize> = r
        .run
        .events
        .iter()
        .enumerate()
        .filter(|(_, e)| matches!(e.kind, EventKind::Sliding | EventKind::End))
        .map(|(k, _)| k)
        .collect();
    assert_eq!(sliding.len(), 2, "one sliding event, then the end 5 % further");
    for k in sliding {
        let f = r.run.states[k].f;
        assert!((f / (mu * 1.0) - 1.0).abs() < 1e-12, "F/(mu N) = {}", f / mu);
    }
    // The force grows monotonically under a monotonic X (coulomb is path-stable).
    for w in r.run.states.windows(2).filter(|w| w[0].phase == Phase::Drive) {
        assert!(w[1].f >= w[0].f - 1e-12);
    }
    let v = worst_violation(&r);
    assert!(v < 1e-9, "largest violation {v:e} of N/n");
}

/// Thin-layer closed form: F/(mu N) = 1/(1 + g (1/2 - x_s/L)^2). The FE front lags it by a
/// fixed number of thicknesses (the edge zone ~ t), so in units of L the offset halves with
/// t; measured (validation/friction/README.md): -2.51 t, -2.19 t, -2.15 t at t/L = 0.02,
/// 0.01, 0.005 (mean over fronts with |x_s| < 0.3 L).
#[test]
fn coulomb_front_converges_to_the_thin_layer_closed_form() {
    let mu = 0.5;
    let mut offsets = Vec::new();
    for t in [0.008, 0.004, 0.002] {
        let sc = thin(t);
        let g = 6.0 * mu * sc.loading.height / sc.block.length;
        let r = slide(&sc, Law::coulomb(mu).unwrap(), None);
        let mut d = Vec::new();
        for (k, st) in r.run.states.iter().enumerate() {
            if st.phase != Phase::Drive {
                continue;
            }
            if let (Some(xf), Some(xc)) = (trailing_front(&r, k), partial_slip::front(g, st.f / mu)) {
                if xc.abs() < 0.3 {
                    d.push((xf - xc) * sc.block.length / t);
                }
            }
        }
        assert!(d.len() > 10);
        let mean = d.iter().sum::<f64>() / d.len() as f64;
        assert!((-3.0..-1.5).contains(&mean), "t = {t}: mean offset {mean} t");
        offsets.push(mean * t / sc.block.length);
        assert!(worst_violation(&r) < 1e-9);
    }
    // In units of L the offset shrinks like t (ratio 1/2 per halving, to 15 %).
    for w in offsets.windows(2) {
        let ratio = w[1] / w[0];
        assert!((0.4..0.6).contains(&ratio), "offset ratio {ratio} ({offsets:?})");
    }
}

#[test]
fn static_kinetic_slides_at_mu_d_n_and_cycles() {
    let sc = coarse();
    let (ms, md) = coefficients_from_rg(&sc, 0.9, 0.35).unwrap();
    for rule in [Rule::Paper, Rule::Overdamped] {
        let o =
            SlideOptions { law: Law::static_kinetic(ms, md, rule).unwrap(), cycles: 3, ..Default::default() };
        let r = run(&sc, &o, tribofe::Progress::none()).unwrap();
        assert_eq!(r.run.sliding_events, 3);
        for e in r.run.events.iter().filter(|e| e.kind == EventKind::Sliding) {
            // Paper rule: the whole interface relaxes to mu_d p, so F* = mu_d N to round-off.
            // Overdamped: nodes whose slip would reverse re-stick and may carry less than
            // mu_d p, so only |F*| <= mu_s N holds (friction bound summed over the nodes).
            if rule == Rule::Paper || e.all_slipping {
                assert!(e.all_slipping);
                assert!(
                    (e.f_relaxed / md - 1.0).abs() < 1e-12,
                    "{rule:?}: F* / (mu_d N) = {}",
                    e.f_relaxed / md
                );
            } else {
                assert!(e.f_relaxed.abs() <= ms * (1.0 + 1e-12), "{rule:?}: F* = {}", e.f_relaxed);
            }
            assert!(e.f > e.f_relaxed, "a whole-interface slip drops the force");
        }
        assert!(r.run.events.iter().any(|e| e.kind == EventKind::Precursor), "{rule:?}: no precursor");
        let v = worst_violation(&r);
        assert!(v < 1e-9, "{rule:?}: largest violation {v:e}");
    }
}

/// The paper rule's stick-slip peaks against the analytic iteration's F_max = 1/(1 + g(1-r)/r)
/// for (r, g) = (0.9, 0.35): the FE peak is lower by 5.5 % (t/L = 0.01) because the singular
/// trailing corner nucleates early (validation/friction/README.md).
#[test]
fn paper_rule_peak_force_near_the_analytic_f_max() {
    let sc = thin(0.004);
    let (ms, md) = coefficients_from_rg(&sc, 0.9, 0.35).unwrap();
    let o = SlideOptions { law: Law::static_kinetic(ms, md, Rule::Paper).unwrap(), ..Default::default() };
    let r = run(&sc, &o, tribofe::Progress::none()).unwrap();
    assert_eq!(r.run.sliding_events, 10);
    let f_max = tribofe::precursors::Params::new(0.9, 0.35).unwrap().f_max();
    let peak = r.run.events.iter().rfind(|e| e.kind == EventKind::Sliding).unwrap().f / ms;
    assert!((peak / f_max - 1.0).abs() < 0.07, "FE peak {peak} vs analytic {f_max}");
}

#[test]
fn one_and_two_threads_give_the_same_events() {
    let sc = coarse();
    let (ms, md) = coefficients_from_rg(&sc, 0.9, 0.35).unwrap();
    let o = SlideOptions {
        law: Law::static_kinetic(ms, md, Rule::Paper).unwrap(),
        cycles: 2,
        ..Default::default()
    };
    let go = |k: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(k)
            .build()
            .unwrap()
            .install(|| run(&sc, &o, tribofe::Progress::none()).unwrap())
    };
    let (a, b) = (go(1), go(2));
    assert_eq!(a.run.events.len(), b.run.events.len());
    for (x, y) in a.run.states.iter().zip(&b.run.states) {
        assert_eq!(x.f.to_bits(), y.f.to_bits());
        assert_eq!(x.x.to_bits(), y.x.to_bits());
    }
}

#[test]
fn bad_inputs_are_refused_with_the_parameter_named() {
    let mut sc = coarse();
    sc.mesh.element = "qua8".into();
    let e = run(&sc, &SlideOptions::default(), tribofe::Progress::none()).unwrap_err().to_string();
    assert!(e.contains("mesh.element") && e.contains("linear elements"), "{e}");
    assert!(Law::coulomb(-0.1).unwrap_err().to_string().contains("mu"));
    assert!(Law::static_kinetic(0.5, 0.6, Rule::Paper).unwrap_err().to_string().contains("mu-d"));
    let o = SlideOptions { n_force: -1.0, ..Default::default() };
    assert!(run(&coarse(), &o, tribofe::Progress::none()).unwrap_err().to_string().contains("N"));
    let mut el = coarse();
    el.plate.model = tribofe::scene::PlateModel::Elastic;
    assert!(run(&el, &SlideOptions::default(), tribofe::Progress::none())
        .unwrap_err()
        .to_string()
        .contains("rigid"));
}

#[test]
fn slide_command_writes_the_named_files() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("s");
    let status = std::process::Command::new(env!("CARGO_BIN_EXE_tribofe"))
        .args([
            "slide",
            "--thickness",
            "0.004",
            "--h",
            "0.004",
            "--n-thick",
            "2",
            "--law",
            "static-kinetic",
            "--r",
            "0.9",
            "--g",
            "0.35",
        ])
        .args(["--cycles", "2", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(status.status.success(), "{}", String::from_utf8_lossy(&status.stderr));
    let read = |n: &str| std::fs::read_to_string(out.join(n)).unwrap();
    assert!(read("loading.csv").starts_with("event,phase,X_m,F_N_per_m,N_N_per_m,"));
    let ev = read("events.csv");
    assert!(ev.starts_with(
        "event,kind,X_m,F_N_per_m,F_over_mu_s_N,Fc_over_mu_s_N,x_nucleation_over_L,x_arrest_over_L,"
    ));
    assert_eq!(ev.lines().filter(|l| l.contains(",sliding,")).count(), 2);
    let st = read("states.csv");
    assert!(st
        .starts_with("event,x_over_L,p_over_pmean,tau_over_pmean,slip_m,gap_m,state,contact_area_over_A0\n"));
    assert!(read("fig4_fe.svg").contains("<svg") && read("fronts.svg").contains("<svg"));
    assert!(read("run.toml").contains("static-kinetic"));
    let bad = std::process::Command::new(env!("CARGO_BIN_EXE_tribofe"))
        .args(["slide", "--law", "static-kinetic", "--mu-s", "0.5"])
        .output()
        .unwrap();
    assert_eq!(bad.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&bad.stderr).contains("mu-s"));
}

/// Linear elasticity with Coulomb friction is homogeneous of degree one in (N, X): the same
/// events at X/N and F/N for any N (the tolerances are relative, so the event sequence too).
#[test]
fn results_per_unit_n_do_not_depend_on_n() {
    let sc = coarse();
    let go = |n_force: f64| {
        let o = SlideOptions { law: Law::coulomb(0.5).unwrap(), n_force, ..Default::default() };
        run(&sc, &o, tribofe::Progress::none()).unwrap()
    };
    let (a, b) = (go(1.0), go(7.5));
    assert_eq!(a.run.events.len(), b.run.events.len());
    for (x, y) in a.run.states.iter().zip(&b.run.states) {
        assert!((x.f - y.f / 7.5).abs() < 1e-12, "F/N {} vs {}", x.f, y.f / 7.5);
        let x_last = a.run.states.last().unwrap().x;
        assert!((x.x - y.x / 7.5).abs() < 1e-10 * x_last, "X/N {} vs {}", x.x, y.x / 7.5);
        assert_eq!(x.states, y.states);
    }
}

/// The slip-weakening scene of the tests: L = 10 cm, t = 4 mm, (r, g) = (0.9, 0.35), one cycle.
/// Its thin-layer stability number kappa = G D_c / ((mu_s - mu_d) p t), p = N/L, is 1 at
/// D_c* = 0.91 um: below, slip patches go unstable once longer than the nucleation length
/// L_c ~ kappa t; above, every point is held by its own layer stiffness G/t and slip grows
/// stably until the whole interface slides at mu_d N.
fn weakening(h: f64, n_thick: usize, dc: f64) -> SlideResult {
    weakening_with(h, n_thick, (0.9, 0.35), dc, |law| SlideOptions { law, cycles: 1, ..Default::default() })
}

/// The same scene at (r, g) with the options `o` gives for the law.
fn weakening_with(
    h: f64,
    n_thick: usize,
    (r, g): (f64, f64),
    dc: f64,
    o: impl Fn(Law) -> SlideOptions,
) -> SlideResult {
    let sc = weakening_scene(h, n_thick);
    let (ms, md) = coefficients_from_rg(&sc, r, g).unwrap();
    run(&sc, &o(Law::slip_weakening(ms, md, dc).unwrap()), tribofe::Progress::none()).unwrap()
}

/// The slip-weakening scene's block and mesh: L = 10 cm, t = 4 mm, element size h.
fn weakening_scene(h: f64, n_thick: usize) -> Scene {
    let mut sc = thin(0.004);
    sc.block.length = 0.1;
    sc.mesh.h = h;
    sc.mesh.n_thick = Some(n_thick);
    sc
}

fn peak(r: &SlideResult) -> f64 {
    r.run.events.iter().rfind(|e| e.kind == EventKind::Sliding).unwrap().f / r.options.law.mu_s()
}

/// kappa = 0.33 (D_c = 0.3 um, L_c ~ 1.3 mm): the stick-slip peak on h = 2 mm and 1 mm agrees
/// to 1 % (0.6 % measured; 0.2 % between 1 mm and 0.5 mm, validation/friction/README.md).
/// States are admissible to the back-slip tolerance of the relaxation (1e-6 of the
/// displacement scale, so ~1e-6 of N/n).
#[test]
fn slip_weakening_peak_converges_under_refinement() {
    let (a, b) = (weakening(0.002, 4, 3e-7), weakening(0.001, 8, 3e-7));
    let (pa, pb) = (peak(&a), peak(&b));
    assert!((pa / pb - 1.0).abs() < 0.01, "peaks {pa} (h = 2 mm), {pb} (h = 1 mm)");
    assert!(pb > 0.9 && pb < 1.0, "peak {pb} outside (mu_d/mu_s, 1)");
    for r in [&a, &b] {
        assert!(r.run.events.iter().any(|e| e.kind == EventKind::Precursor));
        let v = worst_violation(r);
        assert!(v < 2e-6, "largest violation {v:e}");
    }
}

/// kappa = 11: no instability at all (no event with a relaxation region); the run ends in
/// steady sliding at F = mu_d N.
#[test]
fn slip_weakening_above_the_critical_distance_is_stable() {
    let r = weakening(0.002, 4, 1e-5);
    assert!(r.run.events.iter().all(|e| e.region.is_none()), "an instability at kappa = 11");
    let md = r.options.law.mu_d();
    let last = r.run.states.last().unwrap();
    assert!((last.f / md - 1.0).abs() < 1e-9, "final F/(mu_d N) = {}", last.f / md);
}

/// D_c -> 0 tends to the abrupt drop: the peak at D_c = 1e-10 m against the overdamped rule.
/// Not to round-off: a slip-weakening node re-sticks when its slip would reverse within a
/// relaxation, the overdamped rule's nodes stay at mu_d; the peaks differ by 0.8 %.
#[test]
fn slip_weakening_tends_to_the_abrupt_drop() {
    let r = weakening(0.001, 8, 1e-10);
    let sc = weakening_scene(0.001, 8);
    let (ms, md) = coefficients_from_rg(&sc, 0.9, 0.35).unwrap();
    let o = SlideOptions {
        law: Law::static_kinetic(ms, md, Rule::Overdamped).unwrap(),
        cycles: 1,
        ..Default::default()
    };
    let s = run(&sc, &o, tribofe::Progress::none()).unwrap();
    let (pw, ps) = (peak(&r), peak(&s));
    assert!((pw / ps - 1.0).abs() < 0.015, "peaks {pw} (D_c -> 0), {ps} (overdamped)");
    assert!(worst_violation(&r) < 1e-9);
}

/// Newton on the slip-weakening coefficients reaches the fixed point's equilibria: the first
/// 110 events (to X = 11 um) agree in kind and in X to 1e-8 (2.4e-9 measured: the coefficients
/// converge to 1e-12 mu_s, amplified near a patch's critical length; later the event sequence
/// amplifies any difference, to 3e-5 by event 200), with under a third of the bordering
/// updates (4.4x fewer measured).
#[test]
fn slip_weakening_newton_reaches_the_fixed_point_equilibria() {
    let go = |newton: bool| {
        let o = |law| SlideOptions { law, cycles: 1, x_max: Some(1.1e-5), newton, ..Default::default() };
        weakening_with(0.001, 8, (0.9, 0.35), 3e-7, o).run
    };
    let (a, b) = (go(true), go(false));
    assert!(
        a.events.len() > 90 && a.events.len() == b.events.len(),
        "{} vs {} events",
        a.events.len(),
        b.events.len()
    );
    for (x, y) in a.events.iter().zip(&b.events) {
        assert_eq!(x.kind, y.kind);
        assert!(
            (x.x - y.x).abs() <= 1e-8 * y.x.abs().max(1e-9),
            "X {} (Newton) vs {} (fixed point)",
            x.x,
            y.x
        );
    }
    assert!(
        3 * a.updates < b.updates,
        "bordering updates {} (Newton) vs {} (fixed point)",
        a.updates,
        b.updates
    );
}

/// On h = t = 4 mm with Newton the relaxation meets a node at its threshold next to a slipping
/// node where sticking by node order cycles (the node slips, both run back, the node sticks,
/// slips again); sticking the node running back fastest settles it. The run finishes with
/// admissible states.
#[test]
fn slip_weakening_rate_cycles_in_node_order_are_broken() {
    let o = |law| SlideOptions { law, cycles: 1, newton: true, ..Default::default() };
    let r = weakening_with(0.004, 2, (0.9, 0.35), 3e-7, o);
    let p = peak(&r);
    assert!(p > 0.9 && p < 1.0, "peak {p} outside (mu_d/mu_s, 1)");
    let v = worst_violation(&r);
    assert!(v < 2e-6, "largest violation {v:e}");
}

/// At (r, g) = (0.8, 0.5) on h = 1 mm the trailing corner reaches zero pressure and cycles
/// stick, slip, open (its pressure falls), close (it penetrates by round-off while separating);
/// a corner closed again where it closed before now stays open until it penetrates without
/// separating. The run finishes with admissible states.
#[test]
fn slip_weakening_corner_open_close_cycles_are_broken() {
    let o = |law| SlideOptions { law, cycles: 1, ..Default::default() };
    let r = weakening_with(0.001, 8, (0.8, 0.5), 3e-7, o);
    let p = peak(&r);
    assert!(p > 0.8 && p < 1.0, "peak {p} outside (mu_d/mu_s, 1)");
    let v = worst_violation(&r);
    assert!(v < 2e-6, "largest violation {v:e}");
}

// A slip patch near its critical length makes the fixed point contract by about 1 - 1e-4 an
// iterate; Newton takes over after 10^4 fixed-point iterates. That fallback is tested at a
// fixed cost on a hand-solvable system (interface::events::weakening's unit test
// a_near_critical_relaxation_settles_by_newton_after_the_fixed_point_cap), not by runs of
// this scene with L perturbed by 1e-11, whose cost and outcome were set by round-off.
