//! The paper's check (issue 3): Scheibert & Dysthe, EPL 2010, the paragraph before fig. 2.
//!
//! Block 0.4 m x 2 mm, E = 2 kPa, nu = 0.4, bonded at y = 0, plate on top loaded at H = 4 cm;
//! regular 1 mm QUA4 mesh (400 x 2). Checks: exact global balances, symmetry at F/N = 0,
//! superposition equal to direct solves, rigid vs elastic plate, refusal of an
//! ill-conditioned elastic plate.

use tribofe::fem::constraints::dof;
use tribofe::fem::problem::{solve, LoadCase};
use tribofe::fem::recovery::elements_touching;
use tribofe::linalg::solve::SolverOptions;
use tribofe::scene::{PlateModel, Scene};
use tribofe::studies::check::{converged_scene, run, CheckResult};

fn paper() -> CheckResult {
    run(&Scene::default(), &SolverOptions::default()).unwrap().0
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max)
}

#[test]
fn global_balances_hold_to_round_off() {
    let r = paper();
    assert_eq!(r.cases.len(), 3);
    for c in &r.cases {
        let m = &c.metrics;
        // Each balance sums the n interface reactions (relative to N + |F|): recursive
        // summation errs by at most (n - 1) eps sum|r_i| (Higham, ch. 4), sum|r_i| is a few
        // (N + |F|) here, and each reaction K u adds a few eps: 16 n eps bounds it (1.4e-12
        // at n = 401; about 6e-15 is achieved).
        let tol = 16.0 * c.p.len() as f64 * f64::EPSILON;
        assert!(
            m.balance_n < tol && m.balance_f < tol && m.balance_moment < tol,
            "F/N = {}: {m:?} (tol {tol:e})",
            c.fn_ratio
        );
        // The requested ratio is hit exactly and N is the same for every case.
        assert!((c.f / c.n - c.fn_ratio).abs() < 1e-12);
        assert!((c.n - r.cases[0].n).abs() < 1e-12 * c.n);
        // The tractions, integrated with the tributary widths, give back N/L on average.
        let mean: f64 = c.p.iter().zip(&r.unit.w_over_l).map(|(p, w)| p * w).sum();
        assert!((mean - 1.0).abs() < 1e-12, "mean p/(N/L) = {mean}");
    }
}

#[test]
fn normal_load_is_symmetric() {
    let r = paper();
    let c = &r.cases[0];
    assert_eq!(c.fn_ratio, 0.0);
    let n = c.p.len();
    for i in 0..n {
        let j = n - 1 - i;
        assert!((c.x_over_l[i] + c.x_over_l[j]).abs() < 1e-14);
        assert!((c.p[i] - c.p[j]).abs() < 1e-10, "p not symmetric at node {i}");
        assert!((c.tau[i] + c.tau[j]).abs() < 1e-10, "tau not antisymmetric at node {i}");
    }
    assert!(c.tilt.abs() < 1e-15, "no tilt without tangential load");
}

#[test]
fn model_is_close_in_the_interior_and_deviates_at_the_ends() {
    // The paper: linear pressure and uniform shear to a very good approximation, deviations over
    // ~t (pressure) and ~3 t (shear) at the ends. Bounds here are what the 1 mm mesh gives, with
    // a margin: interior slope within 3 % of 12 (F/N)(H/L), tau(0) within 0.5 %.
    let r = paper();
    // Edge-zone widths against the converged mesh's (tests/convergence.rs checks that one
    // against a 4x finer mesh to 0.02 t): the width is a crossing located by linear
    // interpolation between nodes, so the paper's mesh places it to within one element,
    // h/t = 0.5, of the converged value.
    let scene = Scene::default();
    let reference = run(&converged_scene(&scene), &SolverOptions::default()).unwrap().0;
    let h_over_t = scene.mesh.h / scene.block.thickness;
    for (c, cr) in r.cases[1..].iter().zip(&reference.cases[1..]) {
        let m = &c.metrics;
        assert!((m.slope_interior / m.slope_model - 1.0).abs() < 0.03, "{m:?}");
        assert!((m.tau_center / c.fn_ratio - 1.0).abs() < 0.005, "{m:?}");
        let mr = &cr.metrics;
        for (w, wr) in m.edge_p_t.iter().zip(&mr.edge_p_t).chain(m.edge_tau_t.iter().zip(&mr.edge_tau_t)) {
            let (w, wr) = (w.unwrap(), wr.unwrap());
            assert!(wr > 0.0 && (w - wr).abs() <= h_over_t, "edge zone {w} t vs converged {wr} t");
        }
    }
}

#[test]
fn superposition_equals_direct_solves() {
    let scene = Scene::default();
    let (r, sm) = run(&scene, &SolverOptions::default()).unwrap();
    let model = sm.model();
    let (ju, jv) =
        (sm.constraints.fixed_slot(sm.dof_u).unwrap(), sm.constraints.fixed_slot(sm.dof_v).unwrap());
    let near = elements_touching(&model, &sm.interface);
    for c in &r.cases {
        let mut g = vec![0.0; sm.constraints.n_fixed()];
        g[ju] = c.plate_u;
        g[jv] = c.plate_v;
        let case = LoadCase { prescribed: g, forces: vec![] };
        let sol = solve(&model, &sm.constraints, std::slice::from_ref(&case), &SolverOptions::default(), "")
            .unwrap();
        let res = sol.residual_forces(&model, &case, 0, &near).unwrap();
        let sum_ry: f64 = sm.interface.iter().map(|&k| res[dof(k, 1)]).sum();
        assert!((sum_ry - c.n).abs() < 1e-10 * c.n, "N {sum_ry} vs {}", c.n);
        let pmean = c.n / scene.block.length;
        let p_direct: Vec<f64> = sm
            .interface
            .iter()
            .zip(&r.unit.w_over_l)
            .map(|(&k, w)| res[dof(k, 1)] / (w * scene.block.length) / pmean)
            .collect();
        assert!(max_diff(&p_direct, &c.p) < 1e-10, "F/N = {}", c.fn_ratio);
    }
}

#[test]
fn elastic_plate_agrees_with_rigid_when_well_conditioned_and_is_refused_otherwise() {
    let rigid = paper();
    let elastic = |e: f64, opts: &SolverOptions| {
        let mut s = Scene::default();
        s.plate.model = PlateModel::Elastic;
        s.plate.young = e;
        run(&s, opts).map(|x| x.0)
    };
    // E_plate = 2e9 (ratio 1e6): the plate's own bending changes the profiles by ~1 % of N/L
    // (measured: p 1.5e-2, tau 8.9e-3, interior slope 4.1e-4 at F/N = 0.82).
    let soft = elastic(2e9, &SolverOptions::default()).unwrap();
    for (a, b) in soft.cases.iter().zip(&rigid.cases) {
        assert!(max_diff(&a.p, &b.p) < 2e-2 && max_diff(&a.tau, &b.tau) < 1e-2);
        assert!((a.metrics.slope_interior - b.metrics.slope_interior).abs() < 1e-3);
    }
    // E_plate = 2e12 (ratio 1e9): rigid to 5e-5 of N/L (measured: p 4.6e-5, tau 3.2e-5), with
    // ~10 digits lost to the stiffness contrast and 6 left.
    let stiff = elastic(2e12, &SolverOptions::default()).unwrap();
    for (a, b) in stiff.cases.iter().zip(&rigid.cases) {
        assert!(
            max_diff(&a.p, &b.p) < 1e-4 && max_diff(&a.tau, &b.tau) < 1e-4,
            "{} {}",
            max_diff(&a.p, &b.p),
            max_diff(&a.tau, &b.tau)
        );
    }
    // E_plate = 2e15 (the paper's, ratio 1e12): ~13 digits are lost; tribofe refuses it...
    let err = elastic(2e15, &SolverOptions::default()).unwrap_err().to_string();
    assert!(err.contains("ill-conditioned") && err.contains("--plate rigid"), "{err}");
    // ...and rightly: forced through, the profiles are off by up to 4.4e-2 of N/L and the
    // interior slope by 2e-2 (measured), from round-off alone.
    let forced = elastic(2e15, &SolverOptions { max_error_estimate: 1.0, ..Default::default() }).unwrap();
    let worst = forced.cases.iter().zip(&rigid.cases).map(|(a, b)| max_diff(&a.p, &b.p)).fold(0.0, f64::max);
    assert!(worst > 1e-3, "the forced solution should visibly differ, got {worst}");
}

#[test]
fn bad_scene_values_are_clear_errors() {
    let mut s = Scene::default();
    s.block.poisson = 0.5;
    assert!(run(&s, &SolverOptions::default()).err().unwrap().to_string().contains("incompressible"));
    let mut s = Scene::default();
    s.mesh.h = 0.01;
    assert!(s.validate().unwrap_err().to_string().contains("thickness"));
    let dir = std::env::temp_dir().join(format!("tribofe-scene-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let f = dir.join("bad.toml");
    std::fs::write(&f, "[block]\nlength = 0.4\nthicknes = 0.002\n").unwrap();
    let e = Scene::from_file(&f).unwrap_err().to_string();
    assert!(e.contains("bad.toml") && e.contains("line 3") && e.contains("thicknes"), "{e}");
    // A value that parses but fails validation is also located in the file.
    std::fs::write(&f, "# scene\n[block]\nthickness = 0.002\nlength = -1\n").unwrap();
    let e = Scene::from_file(&f).unwrap_err().to_string();
    assert!(e.contains("bad.toml: line 4: block.length"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn gmsh_regular_mesh_gives_the_structured_result_in_every_format() {
    let built = paper();
    for f in [
        "block_regular_v41_ascii",
        "block_regular_v41_bin",
        "block_regular_v22_ascii",
        "block_regular_v22_bin",
    ] {
        let mut s = Scene::default();
        s.mesh.file = Some(format!("{}/meshes/{f}.msh", env!("CARGO_MANIFEST_DIR")).into());
        let r = run(&s, &SolverOptions::default()).unwrap().0;
        for (a, b) in r.cases.iter().zip(&built.cases) {
            // Gmsh writes coordinates with ~5e-13 m round-off (1.3e-12 of L); profiles agree to that order.
            assert!(
                max_diff(&a.x_over_l, &b.x_over_l) < 1e-11,
                "{f}: x differs by {}",
                max_diff(&a.x_over_l, &b.x_over_l)
            );
            assert!(
                max_diff(&a.p, &b.p) < 1e-9 && max_diff(&a.tau, &b.tau) < 1e-9,
                "{f}: {} {}",
                max_diff(&a.p, &b.p),
                max_diff(&a.tau, &b.tau)
            );
        }
    }
    // A group the mesh lacks is named with the groups it has.
    let mut s = Scene::default();
    s.mesh.file = Some(format!("{}/meshes/block_regular_v41_ascii.msh", env!("CARGO_MANIFEST_DIR")).into());
    s.mesh.interface = "bottom".into();
    let e = run(&s, &SolverOptions::default()).err().unwrap().to_string();
    assert!(e.contains("'bottom'") && e.contains("interface") && e.contains("block_regular"), "{e}");
}

#[test]
fn reused_symbolic_analysis_gives_the_fresh_result() {
    // One pattern + symbolic analysis serves every plate modulus of a sweep.
    let mut s = Scene::default();
    s.plate.model = PlateModel::Elastic;
    let prepared = tribofe::studies::check::prepare(&s, &SolverOptions::default()).unwrap();
    for e in [2e9, 2e11] {
        s.plate.young = e;
        let fresh = run(&s, &SolverOptions::default()).unwrap().0;
        let reused = tribofe::studies::check::run_model(
            &s,
            s.build().unwrap(),
            0.0,
            &SolverOptions::default(),
            Some(&prepared),
        )
        .unwrap()
        .0;
        assert_eq!(reused.stats.timings.symbolic, 0.0);
        for (a, b) in fresh.cases.iter().zip(&reused.cases) {
            // Same pattern and ordering: the same arithmetic, so the same numbers.
            assert!(max_diff(&a.p, &b.p) < 1e-14 && max_diff(&a.tau, &b.tau) < 1e-14);
        }
    }
}

#[test]
fn unstructured_gmsh_mesh_agrees_with_the_converged_answer() {
    // Quad-dominant Gmsh mesh (QUA4 + TRI3, worst quad Jacobian half its mean), ~t/4.7 in size.
    // Measured against the converged graded QUA8 answer at F/N = 0.82: slope 4e-4, tau(0) 1e-3,
    // leading-edge pressure width 0.03 t.
    let conv = run(&tribofe::studies::check::converged_scene(&Scene::default()), &SolverOptions::default())
        .unwrap()
        .0;
    let c = conv.cases.last().unwrap();
    for el in ["qua4", "qua4-im"] {
        let mut s = Scene::default();
        s.mesh.file =
            Some(format!("{}/meshes/block_unstructured_v41_bin.msh", env!("CARGO_MANIFEST_DIR")).into());
        s.mesh.element = el.into();
        let r = run(&s, &SolverOptions::default()).unwrap().0;
        let u = r.cases.last().unwrap();
        assert!((u.metrics.slope_interior - c.metrics.slope_interior).abs() < 2e-3, "{el}");
        assert!((u.metrics.tau_center - c.metrics.tau_center).abs() < 2e-3, "{el}");
        assert!((u.metrics.edge_p_t[1].unwrap() - c.metrics.edge_p_t[1].unwrap()).abs() < 0.15, "{el}");
    }
}

/// One factorisation for every drive height (issue 19): the unit cases at the first H plus a
/// unit moment, combined per H, give each height's check to round-off of the fields' scale
/// (1e-10 of N/L: the combination coefficients grow with the shift, up to 10 cm here).
#[test]
fn heights_from_one_factorisation_equal_single_checks() {
    let mut s = Scene::default();
    s.mesh.h = 0.002;
    s.mesh.n_thick = Some(2);
    let heights = [0.04, 0.01, 0.14];
    let scenes: Vec<Scene> = heights
        .iter()
        .map(|&h| {
            let mut x = s.clone();
            x.loading.height = h;
            x
        })
        .collect();
    let shifted =
        tribofe::studies::check::run_heights(&scenes[0], &scenes, &SolverOptions::default(), None, None)
            .unwrap();
    for (sc, got) in scenes.iter().zip(&shifted) {
        let want = run(sc, &SolverOptions::default()).unwrap().0;
        for (a, b) in want.cases.iter().zip(&got.cases) {
            assert!(
                (a.n / b.n - 1.0).abs() < 1e-10 && (a.f - b.f).abs() < 1e-10 * a.n,
                "H {}",
                sc.loading.height
            );
            assert!(
                max_diff(&a.p, &b.p) < 1e-10 && max_diff(&a.tau, &b.tau) < 1e-10,
                "H {}: p {:e} tau {:e} tilt {} {} n {} {}",
                sc.loading.height,
                max_diff(&a.p, &b.p),
                max_diff(&a.tau, &b.tau),
                a.tilt,
                b.tilt,
                a.n,
                b.n
            );
            let scale = want.cases.iter().map(|c| c.tilt.abs()).fold(0.0, f64::max);
            assert!(
                (a.tilt - b.tilt).abs() < 1e-10 * scale,
                "H {}: tilt {} {}",
                sc.loading.height,
                a.tilt,
                b.tilt
            );
            assert!((a.metrics.slope_interior - b.metrics.slope_interior).abs() < 1e-10);
        }
    }
}

/// `check --fields` writes the formats asked for and nothing else; `--n-force` is checked
/// before any work and scales N and F in summary.csv (the profiles do not move).
#[test]
fn field_formats_and_normal_force() {
    let exe = env!("CARGO_BIN_EXE_tribofe");
    let dir = tempfile::tempdir().unwrap();
    let run = |args: &[&str], out: &str| {
        let o = std::process::Command::new(exe)
            .args(["check", "--h", "0.001", "--no-converged", "--out"])
            .arg(dir.path().join(out))
            .args(args)
            .output()
            .unwrap();
        let names: Vec<String> = std::fs::read_dir(dir.path().join(out))
            .map(|d| {
                let mut v: Vec<String> = d
                    .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
                    .filter(|n| n.starts_with("fields"))
                    .collect();
                v.sort();
                v
            })
            .unwrap_or_default();
        (o, names)
    };
    let vtu = ["fields.pvd", "fields_FN0.41.vtu", "fields_FN0.82.vtu", "fields_FN0.vtu"];
    let msh = ["fields_FN0.41.msh", "fields_FN0.82.msh", "fields_FN0.msh"];
    assert_eq!(run(&[], "a").1, vtu);
    assert_eq!(run(&["--fields", "msh"], "b").1, msh);
    assert_eq!(run(&["--fields", "none"], "c").1, Vec::<String>::new());
    assert_eq!(run(&["--no-fields"], "d").1, Vec::<String>::new());
    let mut both: Vec<&str> = vtu.iter().chain(&msh).copied().collect();
    both.sort();
    assert_eq!(run(&["--fields", "both"], "e").1, both);
    for bad in [
        &["--n-force", "-1"][..],
        &["--n-force", "nan"],
        &["--fields", "xml"],
        &["--fields", "vtu", "--no-fields"],
    ] {
        let (o, _) = run(bad, "bad");
        assert_eq!(o.status.code(), Some(2), "{bad:?}: {}", String::from_utf8_lossy(&o.stderr));
        assert!(!dir.path().join("bad").exists(), "{bad:?}");
    }
    let (o, _) = run(&["--n-force", "200", "--fields", "none"], "f");
    assert!(o.status.success());
    let summary = |d: &str| -> Vec<Vec<String>> {
        std::fs::read_to_string(dir.path().join(d).join("summary.csv"))
            .unwrap()
            .lines()
            .skip(1)
            .map(|l| l.split(',').map(String::from).collect())
            .collect()
    };
    for (a, f) in summary("a").iter().zip(summary("f")) {
        let num = |v: &str| v.parse::<f64>().unwrap();
        assert_eq!(num(&f[1]), 200.0, "N is the requested force");
        // F = (F/N) N to round-off; the shape columns (slopes, tau(0)) unchanged to round-off.
        assert!((num(&f[2]) - num(&f[0]) * 200.0).abs() <= 1e-12 * 200.0, "{f:?}");
        for col in [3, 4, 5] {
            let (x, y) = (num(&a[col]), num(&f[col]));
            assert!((x - y).abs() <= 1e-12 * x.abs().max(1.0), "column {col}: {x} vs {y}");
        }
    }
}
