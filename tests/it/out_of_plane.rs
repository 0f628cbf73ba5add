//! Plane stress (issue 49): the constitutive law sigma_zz = 0 checked against plane strain
//! with the mapped moduli E' = E (1 + 2 nu)/(1 + nu)^2, nu' = nu/(1 + nu) (the same in-plane
//! law, so the same 2D solution); the width b it requires; its wave speeds.

use tribofe::dynamics::waves::{rayleigh_ratio, WaveSpeeds};
use tribofe::fem::material::Material;
use tribofe::linalg::solve::SolverOptions;
use tribofe::scene::{Overrides, PlateModel, Scene, State};
use tribofe::studies::check::run;

fn mapped(e: f64, nu: f64) -> (f64, f64) {
    (e * (1.0 + 2.0 * nu) / (1.0 + nu).powi(2), nu / (1.0 + nu))
}

/// max |a - b| over max |a| (or 1e-300).
fn rel(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    let scale = a.iter().fold(0.0f64, |m, v| m.max(v.abs())).max(1e-300);
    a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max) / scale
}

fn compare(stress: &Scene, strain: &Scene) {
    let (a, b) = (
        run(stress, &SolverOptions::default()).unwrap().0,
        run(strain, &SolverOptions::default()).unwrap().0,
    );
    assert_eq!(a.cases.len(), b.cases.len());
    for (x, y) in a.cases.iter().zip(&b.cases) {
        let what = format!("F/N = {}", x.fn_ratio);
        assert!((x.n - y.n).abs() <= 1e-10 * y.n.abs(), "{what}: N {} vs {}", x.n, y.n);
        assert!((x.f - y.f).abs() <= 1e-10 * y.n.abs(), "{what}: F {} vs {}", x.f, y.f);
        for (name, u, v) in [
            ("p", &x.p, &y.p),
            ("tau", &x.tau, &y.tau),
            ("p_extrap", &x.p_extrap, &y.p_extrap),
            ("tau_extrap", &x.tau_extrap, &y.tau_extrap),
            ("p_corrected", &x.p_corrected, &y.p_corrected),
        ] {
            // Relative to the field's largest value; tau at F/N = 0 is round-off around 0:
            // there in units of the mean pressure (the profiles' unit).
            let e = if x.fn_ratio == 0.0 && name.starts_with("tau") {
                u.iter().zip(v.iter()).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max)
            } else {
                rel(v, u)
            };
            assert!(e <= 1e-10, "{what}: {name} differs by {e:e} (relative)");
        }
        assert_eq!(x.x_over_l, y.x_over_l);
    }
}

#[test]
fn bonded_check_in_plane_stress_is_plane_strain_with_mapped_moduli() {
    let (e, nu) = (2e3, 0.4);
    let stress = Scene::default()
        .apply(&Overrides { state: Some(State::PlaneStress), width: Some(0.006), ..Default::default() })
        .unwrap();
    let (e2, nu2) = mapped(e, nu);
    let strain = Scene::default()
        .apply(&Overrides { young: Some(e2), poisson: Some(nu2), ..Default::default() })
        .unwrap();
    compare(&stress, &strain);
    // nu = 0.5 is a plate in plane stress (nu' = 1/3), on an elastic plate of its own modulus,
    // qua8 elements.
    let o = Overrides {
        poisson: Some(0.5),
        plate: Some(PlateModel::Elastic),
        plate_young: Some(2e6),
        plate_poisson: Some(0.3),
        element: Some("qua8".into()),
        length: Some(0.1),
        h: Some(0.001),
        ..Default::default()
    };
    let stress = Scene::default()
        .apply(&Overrides { state: Some(State::PlaneStress), width: Some(0.005), ..o.clone() })
        .unwrap();
    let ((e2, nu2), (ep, nup)) = (mapped(e, 0.5), mapped(2e6, 0.3));
    let strain = Scene::default()
        .apply(&Overrides {
            young: Some(e2),
            poisson: Some(nu2),
            plate_young: Some(ep),
            plate_poisson: Some(nup),
            ..o
        })
        .unwrap();
    compare(&stress, &strain);
}

#[test]
fn plane_stress_needs_a_finite_positive_width() {
    let ps = |width: Option<f64>| {
        Scene::default().apply(&Overrides { state: Some(State::PlaneStress), width, ..Default::default() })
    };
    let msg = ps(None).unwrap_err().to_string();
    assert!(msg.contains("--width") && msg.contains("[block] width"), "{msg}");
    for b in [0.0, -0.005, f64::NAN, f64::INFINITY] {
        let msg = ps(Some(b)).unwrap_err().to_string();
        assert!(msg.contains("--width"), "width {b}: {msg}");
    }
    assert!(ps(Some(0.005)).is_ok());
    // A width alone is fine in plane strain (forces in newtons), a bad one is not.
    assert!(Scene::default().apply(&Overrides { width: Some(0.01), ..Default::default() }).is_ok());
    assert!(Scene::default().apply(&Overrides { width: Some(-1.0), ..Default::default() }).is_err());
    // Plane stress accepts nu = 0.5, plane strain does not.
    let half = Overrides { poisson: Some(0.5), ..Default::default() };
    assert!(Scene::default().apply(&half).is_err());
    assert!(Scene::default()
        .apply(&Overrides { state: Some(State::PlaneStress), width: Some(0.005), ..half })
        .is_ok());
}

#[test]
fn the_command_refuses_plane_stress_without_width_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    for (args, named) in [
        (vec!["--plane-stress"], "--width"),
        (vec!["--plane-stress", "--width", "0"], "--width"),
        (vec!["--plane-stress", "--width=-0.005"], "--width"),
        (vec!["--width", "nan"], "--width"),
    ] {
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_tribofe"))
            .arg("check")
            .args(&args)
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(named), "{args:?}: {err}");
        assert!(!out.exists(), "{args:?} wrote {out:?}");
    }
    // In a scene file: the key named with its line where it is in the file.
    let scene = dir.path().join("s.toml");
    std::fs::write(&scene, "[block]\nstate = \"plane-stress\"\n").unwrap();
    let msg = Scene::from_file(&scene).unwrap_err().to_string();
    assert!(msg.contains("[block] width"), "{msg}");
    std::fs::write(&scene, "[block]\nstate = \"plane-stress\"\nwidth = -1.0\n").unwrap();
    let msg = Scene::from_file(&scene).unwrap_err().to_string();
    assert!(msg.contains("line 3") && msg.contains("width"), "{msg}");
    std::fs::write(&scene, "[block]\nstate = \"plane-stres\"\nwidth = 0.005\n").unwrap();
    assert!(Scene::from_file(&scene).is_err());
}

#[test]
fn plane_stress_wave_speeds_are_the_closed_form() {
    let (e, nu, rho) = (3e9, 0.35, 1180.0);
    let w = WaveSpeeds::new(&Material::plane_stress(e, nu).unwrap(), rho);
    let c_p = (e / ((1.0 - nu * nu) * rho)).sqrt();
    let c_s = (e / (2.0 * (1.0 + nu) * rho)).sqrt();
    assert!((w.c_p - c_p).abs() <= 1e-12 * c_p, "{} vs {c_p}", w.c_p);
    assert!((w.c_s - c_s).abs() <= 1e-12 * c_s);
    assert!((w.c_r - c_s * rayleigh_ratio(c_s / c_p)).abs() <= 1e-12 * c_s);
    // Plane strain's P speed is faster: (lambda + 2 G) > E / (1 - nu^2).
    assert!(WaveSpeeds::new(&Material::plane_strain(e, nu).unwrap(), rho).c_p > 1.1 * c_p);
    // A scene given by its wave speeds in plane stress gives them back; a flag turning a
    // plane-strain file to plane stress turns its wave speeds again.
    let dir = tempfile::tempdir().unwrap();
    let f = dir.path().join("s.toml");
    let text = format!("[block]\ndensity = {rho}\nc_p = {c_p}\nc_s = {c_s}\n");
    std::fs::write(&f, format!("{text}state = \"plane-stress\"\nwidth = 0.005\n")).unwrap();
    let s = Scene::from_file(&f).unwrap();
    assert!((s.block.young - e).abs() <= 1e-9 * e && (s.block.poisson - nu).abs() <= 1e-9, "{:?}", s.block);
    std::fs::write(&f, &text).unwrap();
    let strain = Scene::from_file(&f).unwrap();
    assert!((strain.block.poisson - nu).abs() > 0.05, "plane strain reads the same speeds as another nu");
    let s = strain
        .apply(&Overrides { state: Some(State::PlaneStress), width: Some(0.005), ..Default::default() })
        .unwrap();
    assert!((s.block.young - e).abs() <= 1e-9 * e && (s.block.poisson - nu).abs() <= 1e-9, "{:?}", s.block);
    let m = s.block.material().unwrap();
    let back = WaveSpeeds::new(&m, rho);
    assert!((back.c_p - c_p).abs() <= 1e-9 * c_p && (back.c_s - c_s).abs() <= 1e-9 * c_s);
}
