//! Bad inputs run as a user runs them: the built binary, its exit status, its message, and an
//! output folder left untouched because the refusal comes before any solve.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use tribofe::fem::element::ElementKind;
use tribofe::fem::mesh::Mesh;
use tribofe::fem::mesher::Rectangle;

fn tribofe(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_tribofe")).args(args).output().unwrap()
}

/// A structured block x in [x0, x0 + l], y in [0, t] with the groups interface, top, block.
fn block(kind: ElementKind, x0: f64, l: f64, t: f64, nx: usize) -> Mesh {
    let mut m = Rectangle::new(x0, x0 + l, 0.0, t, nx, 2).kind(kind).build().unwrap();
    let bottom = m.edge_sets.remove("bottom").unwrap();
    m.edge_sets.insert("interface".into(), bottom);
    let all = m.element_sets.remove("all").unwrap();
    m.element_sets.insert("block".into(), all);
    m
}

fn write(dir: &Path, name: &str, m: &Mesh) -> PathBuf {
    let p = dir.join(name);
    tribofe::io::gmsh_post::write_msh(&p, m, &[], &[]).unwrap();
    p
}

/// Runs `check` into a fresh folder and returns (exit status, stderr, whether the folder exists).
fn check(dir: &Path, args: &[&str]) -> (i32, String, bool) {
    let out = dir.join("out");
    let mut a = vec!["check", "--no-fields", "--no-converged", "--out", out.to_str().unwrap()];
    a.extend_from_slice(args);
    let o = tribofe(&a);
    (o.status.code().unwrap(), String::from_utf8_lossy(&o.stderr).into_owned(), out.exists())
}

/// Refused with the input status, naming each of `words`, the folder never created.
fn refused(dir: &Path, args: &[&str], words: &[&str]) {
    let (code, err, written) = check(dir, args);
    assert_eq!(code, 2, "{args:?}: {err}");
    for w in words {
        assert!(err.contains(w), "{args:?}: '{w}' not in: {err}");
    }
    assert!(!written, "{args:?}: output folder written");
}

#[test]
fn qua8_gmsh_mesh_of_another_geometry_runs_without_element_flag() {
    let dir = tempfile::tempdir().unwrap();
    let (l, t) = (0.1, 0.002);
    let m = write(dir.path(), "q8.msh", &block(ElementKind::Qua8, -l / 2.0, l, t, 50));
    let (code, err, written) = check(dir.path(), &["--mesh", m.to_str().unwrap(), "--length", "0.1"]);
    assert_eq!(code, 0, "{err}");
    assert!(written && dir.path().join("out/summary.csv").exists());
    // A technology the file's elements lack is still refused, naming the option.
    let other = tempfile::tempdir().unwrap();
    refused(
        other.path(),
        &["--mesh", m.to_str().unwrap(), "--length", "0.1", "--element", "qua4-im"],
        &["mesh.element", "qua8"],
    );
}

#[test]
fn mesh_contradicting_the_scene_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let (l, t) = (0.1, 0.002);
    let good = block(ElementKind::Qua4, -l / 2.0, l, t, 50);
    let ok = write(d, "ok.msh", &good);
    // The default scene has L = 0.4 m: normalising by it would be silently wrong.
    refused(d, &["--mesh", ok.to_str().unwrap()], &["ok.msh", "length", "0.4"]);
    refused(d, &["--mesh", ok.to_str().unwrap(), "--length", "0.1", "--thickness", "0.003"], &["thickness"]);
    // Shifted in x.
    let shifted = write(d, "shifted.msh", &block(ElementKind::Qua4, -l / 2.0 + 0.01, l, t, 50));
    refused(d, &["--mesh", shifted.to_str().unwrap(), "--length", "0.1"], &["shifted.msh", "x in"]);
    // An interface covering half the base.
    let mut half = good.clone();
    let iface = half.edge_sets.get_mut("interface").unwrap();
    iface.truncate(iface.len() / 2);
    let half = write(d, "half.msh", &half);
    refused(d, &["--mesh", half.to_str().unwrap(), "--length", "0.1"], &["'interface'", "cover"]);
    // interface and top swapped through the scene's group names.
    let scene = d.join("swap.toml");
    std::fs::write(&scene, "[mesh]\ninterface = \"top\"\ntop = \"interface\"\n").unwrap();
    refused(
        d,
        &["--scene", scene.to_str().unwrap(), "--mesh", ok.to_str().unwrap(), "--length", "0.1"],
        &["'top'", "y = 0"],
    );
    // A mesher flag cannot act on a mesh file.
    refused(d, &["--mesh", ok.to_str().unwrap(), "--length", "0.1", "--h", "0.0005"], &["--h", "ok.msh"]);
    // QUA8 elements with 2-node boundary lines.
    let mut q8 = block(ElementKind::Qua8, -l / 2.0, l, t, 50);
    for edges in q8.edge_sets.values_mut() {
        edges.iter_mut().for_each(|e| e.mid = None);
    }
    let q8 = write(d, "q8_line2.msh", &q8);
    refused(d, &["--mesh", q8.to_str().unwrap(), "--length", "0.1"], &["2-node", "line3"]);
}

#[test]
fn h_giving_one_element_through_the_thickness_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    // t = 2 mm: round(t / h) = 1 for h in (1.33, 2] mm.
    refused(dir.path(), &["--h", "0.0018"], &["--h", "t / 2", "--n-thick"]);
    refused(dir.path(), &["--h", "0.003"], &["mesh.h", "t / 2"]);
}

/// Runs `check` on a short block and returns (stdout, summary.csv).
fn short_block(dir: &Path, args: &[&str]) -> (String, String) {
    let out = dir.join("out");
    let mut a = vec!["check", "--no-fields", "--out", out.to_str().unwrap()];
    a.extend_from_slice(args);
    let o = tribofe(&a);
    assert!(o.status.success(), "{args:?}: {}", String::from_utf8_lossy(&o.stderr));
    let summary = std::fs::read_to_string(out.join("summary.csv")).unwrap();
    (String::from_utf8_lossy(&o.stdout).into_owned(), summary)
}

#[test]
fn short_thick_block_uses_its_middle_half() {
    // L = 20 t: no node lies 10 t from both ends; the interior is |x| < L/4 and says so.
    let dir = tempfile::tempdir().unwrap();
    let (stdout, summary) = short_block(dir.path(), &["--length", "0.1", "--thickness", "0.005"]);
    assert!(stdout.contains("middle half") && stdout.contains("2.5000e-2 m"), "{stdout}");
    assert!(!summary.to_lowercase().contains("nan"));
    // Every figure defined; the slope at F/N = 0.82 near the model's 12 (F/N)(H/L) = 3.936
    // (measured 4.02: the short block's shear couple shifts it by a few percent).
    let row: Vec<&str> = summary.lines().nth(3).unwrap().split(',').collect();
    let slope: f64 = row[3].parse().unwrap();
    assert!((slope / 3.936 - 1.0).abs() < 0.05, "{slope}");
    assert!(row.iter().skip(10).all(|c| !c.is_empty()), "{row:?}");
}

#[test]
fn undefined_interior_figures_are_dashes_and_empty_cells() {
    // L = 2 t on 1 mm elements: the middle half holds one node, no slope can be fitted.
    let dir = tempfile::tempdir().unwrap();
    let (stdout, summary) = short_block(
        dir.path(),
        &["--length", "0.004", "--thickness", "0.002", "--h", "0.001", "--no-converged"],
    );
    assert!(stdout.contains("fewer than two interface nodes"), "{stdout}");
    assert!(!summary.to_lowercase().contains("nan"));
    for line in summary.lines().skip(1) {
        let row: Vec<&str> = line.split(',').collect();
        assert!(row[3].is_empty() && row[20].is_empty(), "{row:?}");
        // One node: the deviation is defined; the balance is exact to round-off.
        assert!(row[10].parse::<f64>().is_ok() && row[17].parse::<f64>().unwrap() < 1e-9, "{row:?}");
    }
}

#[test]
fn size_guard_refuses_before_meshing() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // 1.6e9 unknowns: once a 25.6 GB allocation abort; metres for millimetres: 1.6e6 unknowns;
    // 1e300 m: once a capacity-overflow panic.
    refused(d, &["--h", "1e-6"], &["too large", "1.601e9", "--max-dofs", "--h"]);
    refused(d, &["--thickness", "2"], &["too large", "block.thickness = 2e0 m"]);
    refused(d, &["--thickness", "1e300"], &["--thickness", "1.0000e300", "units"]);
    // Scales double precision cannot hold: once "free to move" or "degenerate" after meshing.
    refused(d, &["--length", "1e-300"], &["--length", "units"]);
    refused(d, &["--young", "1e300"], &["--young", "units"]);
    refused(d, &["--height", "1e300"], &["--height"]);
    refused(d, &["--height", "1000"], &["--height", "L"]);
    refused(d, &["--length", "0.001"], &["--h", "two elements along x"]);
    // The default scene has 2 x 401 x 3 = 2406 unknowns: the limit acts on both sides of it.
    refused(d, &["--max-dofs", "2000"], &["about 2.406e3 unknowns", "2000"]);
    refused(d, &["--max-dofs", "0"], &["--max-dofs"]);
    let (code, err, written) = check(d, &["--max-dofs", "3000"]);
    assert!(code == 0 && written, "{code} {written} {err}");
    // Every subcommand: sweep checks each point, converge its own limit.
    let o =
        tribofe(&["sweep", "--as-meshed", "--thickness", "0.002,2", "--out", d.join("sw").to_str().unwrap()]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        o.status.code() == Some(2) && err.contains("sweep point 2") && err.contains("too large"),
        "{err}"
    );
    assert!(!d.join("sw").exists());
    let o = tribofe(&["converge", "--max-dofs", "0", "--out", d.join("cv").to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(!d.join("cv").exists());
    // A frictional interface of 2e5 nodes: 1.2e6 FE unknowns pass, the dense condensed system
    // (4 x (4e5)^2 doubles, 5 TB) does not.
    let sl = d.join("sl");
    let o =
        tribofe(&["slide", "--length", "20", "--h", "1e-4", "--n-thick", "2", "--out", sl.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.code() == Some(2) && err.contains("200001 nodes") && err.contains("--h"), "{err}");
    assert!(!sl.exists());
}

#[test]
fn bench_refuses_sizes_and_thread_counts_it_cannot_run() {
    // Once an unwrap on a 80 GB allocation error (exit 101).
    for (args, word) in
        [(&["bench", "--dgemm", "100000"][..], "--dgemm"), (&["bench", "--threads", "0"][..], "--threads")]
    {
        let o = tribofe(args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(o.status.code() == Some(2) && err.contains(word), "{args:?}: {err}");
    }
}

#[test]
fn max_dofs_acts_on_every_meshing_subcommand_and_is_scene_data() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let out = d.join("out");
    let o = out.to_str().unwrap();
    // The default scene has 2406 unknowns, the default rectangle of `solve` 410.
    let cases: [&[&str]; 6] = [
        &["check", "--max-dofs", "2000"],
        &["slide", "--max-dofs", "2000"],
        &["stability", "--study", "plate", "--max-dofs", "2000"],
        &["sweep", "--as-meshed", "--max-dofs", "2000"],
        &["precursors", "--fe", "--max-dofs", "2000"],
        &["solve", "--max-dofs", "400"],
    ];
    for args in cases {
        let mut a = args.to_vec();
        a.extend(["--out", o]);
        let r = tribofe(&a);
        let err = String::from_utf8_lossy(&r.stderr);
        assert!(
            r.status.code() == Some(2) && err.contains("too large") && err.contains("--max-dofs"),
            "{a:?}: {err}"
        );
        assert!(!out.exists(), "{a:?}: output written");
    }
    // A scene file carries the limit (mesh.max_dofs), and --write-scene keeps it.
    let scene = d.join("s.toml");
    std::fs::write(&scene, "[mesh]\nmax_dofs = 2000\n").unwrap();
    refused(d, &["--scene", scene.to_str().unwrap()], &["too large", "2000"]);
    // A refused run writes no scene; an accepted one writes the limit it ran under.
    let written = d.join("w.toml");
    refused(d, &["--max-dofs", "2000", "--write-scene", written.to_str().unwrap()], &["too large"]);
    assert!(!written.exists(), "a refused run wrote its --write-scene file");
    let (code, err, _) = check(d, &["--max-dofs", "1000000", "--write-scene", written.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(std::fs::read_to_string(&written).unwrap().contains("max_dofs = 1000000"));
    // No process-wide state: two scenes with different limits in one process.
    let base = tribofe::scene::Scene::default();
    let mut small = base.clone();
    small.mesh.max_dofs = Some(2000);
    assert!(small.check_size().is_err());
    assert!(base.check_size().is_ok());
    assert!(small.check_size().is_err());
}

#[test]
fn self_check_and_load_ratios() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // Absurd and duplicated F/N, refused before solving.
    refused(d, &["--fn-ratios", "1e20"], &["--fn-ratios", "1e20", "friction coefficient"]);
    refused(d, &["--fn-ratios", "0,0.4,0.4"], &["--fn-ratios", "0.4", "twice"]);
    // The README's elastic plate at 2e9 Pa passes its self-check (the error relative to the
    // load, 8e-9, against 100 eps kappa with kappa ~ 9e6).
    let (code, err, written) = check(d, &["--plate", "elastic", "--plate-modulus", "2e9"]);
    assert!(code == 0 && written, "{err}");
    // A balance worse than the solve can explain is a numerical refusal (status 3).
    let (mut res, _) = tribofe::studies::check::run(
        &tribofe::scene::Scene::default(),
        &tribofe::linalg::solve::SolverOptions::default(),
    )
    .unwrap();
    let limit = res.balance_limit();
    assert!(res.balance_error() <= limit && limit < 1e-11, "{} {limit}", res.balance_error());
    assert!(res.self_check().is_ok());
    res.cases[1].metrics.balance_moment = 2.0 * limit;
    assert_eq!(res.self_check().unwrap_err().exit_status(), 3);
    // Locking pairs run with a warning naming the better element.
    let (code, err, _) = check(&d.join("nu"), &["--poisson", "0.4995"]);
    assert!(code == 0 && err.contains("warning") && err.contains("qua8"), "{err}");
}

#[test]
fn options_that_cannot_act_or_make_no_sense_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    refused(d, &["--grading", "1.2", "--h-max", "nan"], &["mesh.h_max", "--h-max", "NaN"]);
    refused(d, &["--grading", "1.2", "--h-max", "-1"], &["--h-max"]);
    refused(d, &["--h-max", "0.004"], &["--h-max", "--grading"]);
    refused(d, &["--plate-modulus", "-5"], &["--plate-modulus", "-5"]);
    refused(d, &["--plate-modulus", "2e9"], &["--plate-modulus", "rigid", "--plate elastic"]);
    refused(d, &["--tol", "2"], &["--tol", "(0, 1)"]);
    refused(d, &["--young", "-1"], &["block.young", "--young"]);
    refused(d, &["--n-thick", "2.5"], &["--n-thick", "whole"]);
    let scene = d.join("s.toml");
    std::fs::write(&scene, "[plate]\nyoung = nan\n").unwrap();
    refused(d, &["--scene", scene.to_str().unwrap()], &["plate.young"]);
    // converge: the flags its runs set are refused with the one that acts instead; an empty
    // study names the size limit; its --n-thick list acts.
    let cv = d.join("cv");
    let cvs = cv.to_str().unwrap();
    for (flag, value, instead) in [
        ("--element", "qua8", "--elements"),
        ("--fn-ratios", "0.4", "--case"),
        ("--h", "0.0005", "--n-thick"),
        ("--grading", "1.2", "grading"),
        ("--mesh", "m.msh", "meshes the block"),
    ] {
        let o = tribofe(&["converge", flag, value, "--out", cvs]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(o.status.code() == Some(2) && err.contains(flag) && err.contains(instead), "{flag}: {err}");
    }
    let o = tribofe(&["converge", "--max-dofs", "100", "--out", cvs]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.code() == Some(2) && err.contains("every run is above"), "{err}");
    assert!(!cv.exists());
    let o =
        tribofe(&["converge", "--n-thick", "1,2", "--families", "uniform", "--case", "0.41", "--out", cvs]);
    assert_eq!(o.status.code(), Some(0), "{}", String::from_utf8_lossy(&o.stderr));
    let csv = std::fs::read_to_string(cv.join("convergence.csv")).unwrap();
    assert_eq!(csv.lines().count(), 3, "{csv}");
    // stability's corner study needs three meshes within the limit.
    let o = tribofe(&[
        "stability",
        "--study",
        "corners",
        "--corner-max",
        "2",
        "--out",
        d.join("st").to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.code() == Some(2) && err.contains("--corner-max"), "{err}");
    assert!(!d.join("st").exists());
}

/// Every file under `dir`, relative, sorted.
fn tree(dir: &Path) -> Vec<String> {
    let mut v = Vec::new();
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        let name = p.file_name().unwrap().to_string_lossy().into_owned();
        if p.is_dir() {
            v.extend(tree(&p).into_iter().map(|s| format!("{name}/{s}")));
        } else {
            v.push(name);
        }
    }
    v.sort();
    v
}

#[test]
fn output_folder_is_replaced_by_record_or_not_at_all() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let out = d.join("out");
    let o = out.to_str().unwrap();
    let args = ["check", "--h", "2e-4", "--fn-ratios", "0.3,0.6", "--out", o];
    assert!(tribofe(&args).status.success());
    let full = tree(&out);
    assert!(full.contains(&"run.toml".to_string()) && full.contains(&"fields_FN0.6.vtu".to_string()));
    let run = std::fs::read_to_string(out.join("run.toml")).unwrap();
    assert!(
        run.contains("\n[tribofe]\n") && run.contains("n_force_n_per_m") && run.contains("[scene.block]")
    );
    // A rerun with other ratios replaces the files the first run listed (no stale ones) and
    // keeps a file the user put there.
    std::fs::write(out.join("old"), "").unwrap();
    let other = ["check", "--h", "2e-4", "--out", o];
    assert!(tribofe(&other).status.success());
    let new = tree(&out);
    assert!(new.contains(&"old".to_string()) && !new.contains(&"fields_FN0.3.vtu".to_string()), "{new:?}");
    // Interrupted at points spread over a run (~0.4 s): the folder is the previous one or the
    // new one, never a mix, and no temporary is left.
    for (i, ms) in [5u64, 40, 80, 130, 200, 300, 450].into_iter().enumerate() {
        std::fs::write(out.join("old"), "").unwrap();
        let before = tree(&out);
        // Each commit renames a new run.toml into place: a new inode.
        use std::os::unix::fs::MetadataExt;
        let record = || std::fs::metadata(out.join("run.toml")).unwrap().ino();
        let record_before = record();
        let mut child = Command::new(env!("CARGO_BIN_EXE_tribofe"))
            .args(other)
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .spawn()
            .unwrap();
        std::thread::sleep(std::time::Duration::from_millis(ms));
        let sig = if i % 2 == 0 { libc::SIGINT } else { libc::SIGTERM };
        unsafe { libc::kill(child.id() as i32, sig) };
        let status = child.wait().unwrap();
        let after = tree(&out);
        assert!(after == before || after == new, "killed at {ms} ms ({status:?}): {after:?}");
        // Exit 130 from the handler; or, killed within the first milliseconds of start-up
        // before the handler is installed (a loaded machine, or other tests of this binary
        // running alongside), ended by the signal itself, having written nothing.
        use std::os::unix::process::ExitStatusExt;
        assert!(status.success() || status.code() == Some(130) || status.signal() == Some(sig), "{status:?}");
        // 130 only with the folder as before; after the commit point the run's own status.
        if status.code() == Some(130) || status.signal() == Some(sig) {
            assert_eq!(
                record(),
                record_before,
                "interrupted at {ms} ms ({status:?}) but the folder holds the new run"
            );
        }
        let left: Vec<_> = std::fs::read_dir(d).unwrap().map(|e| e.unwrap().file_name()).collect();
        assert_eq!(left, vec![std::ffi::OsString::from("out")], "killed at {ms} ms");
    }
    // A refused run leaves the folder as it was; --out naming a file or a dangling link is
    // refused before any work.
    let before = tree(&out);
    let (code, _, _) = check(d, &["--tol", "2"]);
    assert_eq!((code, tree(&out)), (2, before));
    let file = d.join("file");
    std::fs::write(&file, "keep").unwrap();
    let link = d.join("link");
    std::os::unix::fs::symlink(d.join("nowhere"), &link).unwrap();
    for (target, word) in [(&file, "existing file"), (&link, "symbolic link")] {
        for cmd in ["check", "converge", "slide", "stability", "solve"] {
            let t0 = std::time::Instant::now();
            let r = tribofe(&[cmd, "--out", target.to_str().unwrap()]);
            let err = String::from_utf8_lossy(&r.stderr);
            assert!(r.status.code() == Some(2) && err.contains(word), "{cmd}: {err}");
            assert!(t0.elapsed().as_secs_f64() < 1.0, "{cmd}: refused late");
        }
    }
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "keep");
}

#[test]
fn converge_target_names_the_run_with_fewest_unknowns() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("cv");
    let args = [
        "converge",
        "--n-thick",
        "1,2,4",
        "--case",
        "0.41",
        "--target",
        "10",
        "--out",
        out.to_str().unwrap(),
    ];
    // Every run reaches 10 N/L: the winner is the graded t/1 mesh (fewest unknowns), every time.
    for _ in 0..2 {
        let o = tribofe(&args);
        let text = String::from_utf8_lossy(&o.stdout);
        let line = text.lines().find(|l| l.starts_with("cheapest run")).unwrap_or_default().to_string();
        assert!(line.contains("graded qua4 h = t/1 ("), "{line}\n{}", String::from_utf8_lossy(&o.stderr));
    }
}

/// `--weakening-steps` belongs to the held mode's static loading under slip weakening.
#[test]
fn weakening_steps_act_only_on_the_held_slip_weakening_loading() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let o = out.to_str().unwrap();
    for (args, why) in [
        (&["slide", "--weakening-steps", "80"][..], "--dynamics"),
        (&["slide", "--dynamics", "--law", "coulomb", "--weakening-steps", "80"], "slip-weakening"),
        (
            &[
                "slide",
                "--dynamics",
                "--drive-velocity",
                "1e-5",
                "--x-max",
                "1e-6",
                "--weakening-steps",
                "80",
            ],
            "--drive-velocity",
        ),
        (&["slide", "--dynamics", "--law", "slip-weakening", "--weakening-steps", "0.5"], "[1, 1e4]"),
    ] {
        let mut a = args.to_vec();
        a.extend(["--out", o]);
        let r = tribofe(&a);
        let err = String::from_utf8_lossy(&r.stderr);
        assert!(
            r.status.code() == Some(2) && err.contains("--weakening-steps") && err.contains(why),
            "{a:?}: {err}"
        );
        assert!(!out.exists());
    }
}

#[test]
fn slide_and_stability_refuse_flags_that_cannot_act() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    for args in [
        &["slide", "--fn-ratios", "0.4"][..],
        &["slide", "--tol", "0.1"],
        &["slide", "--newton"],
        &["stability", "--h", "0.0005"],
        &["stability", "--n-thick", "4"],
        &["stability", "--fn-ratios", "0.4"],
        &["stability", "--mesh", "m.msh"],
    ] {
        let mut a = args.to_vec();
        a.extend(["--out", out.to_str().unwrap()]);
        let o = tribofe(&a);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            o.status.code() == Some(2) && err.contains(args[1]) && err.contains("cannot act"),
            "{a:?}: {err}"
        );
        assert!(!out.exists());
    }
}

#[test]
/// `precursors --fe` studies (--map, --thin-layer, --heights, --dc): bad grid, cap, rule, t/L, H/L or D_c refused,
/// and mesh flags or a mesh file with --thin-layer (it meshes each thickness itself) with the input status and the flag
/// named, nothing written.
fn fe_fig5_refuses_bad_options() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let o = out.to_str().unwrap();
    let cases: [(&[&str], &str); 12] = [
        (&["--map", "--resolution", "1"], "resolution"),
        (&["--map", "--max-events", "0"], "--max-events"),
        (&["--map", "--rules", "paper,fast"], "fast"),
        (&["--map", "--cycles", "3"], "--cycles"),
        (&["--thin-layer", "0.01,0"], "--t-over-l"),
        (&["--thin-layer", "0.01", "--map"], "--map"),
        (&["--heights", "0.1,0.3"], "--h-over-l"),
        (&["--heights", "-0.1"], "--h-over-l"),
        (&["--dc", "1e-6,0"], "dc"),
        (&["--dc", "1e-6", "--heights", "0.1"], "--heights"),
        (&["--thin-layer", "0.01", "--h", "0.001"], "--h"),
        (
            &[
                "--thin-layer",
                "0.01",
                "--mesh",
                concat!(env!("CARGO_MANIFEST_DIR"), "/meshes/block_regular_v41_ascii.msh"),
            ],
            "mesh file",
        ),
    ];
    for (args, word) in cases {
        let mut a = vec!["precursors", "--fe", "--out", o];
        a.extend_from_slice(args);
        let r = tribofe(&a);
        let err = String::from_utf8_lossy(&r.stderr);
        assert!(r.status.code() == Some(2) && err.contains(word), "{a:?}: {err}");
        assert!(!out.exists(), "{a:?}: output written");
    }
}
