//! `slide --states none` keeps no per-event state (issue 33): the run keeps each event's
//! [`Summary`] instead, every output but states.csv is the same bytes as with the states
//! kept, and the memory check counts what is kept. Small scenes: well under a second each in
//! release mode.

use crate::common;

use common::process::run;
use std::path::{Path, PathBuf};
use std::time::Duration;
use tribofe::interface::events::{bytes_per_event, State, Summary};
use tribofe::law::Law;
use tribofe::scene::Scene;
use tribofe::studies::dynamic_slide::{self as ds, DynamicOptions};
use tribofe::studies::slide::{self, SlideOptions, SlideResult};

/// Far above these runs' cost (under 1 s each), far below a hang.
const LIMIT: Duration = Duration::from_secs(120);

/// The paper's block (t = 2 mm, H = 4 cm) with `l` and `h` changed.
fn block(l: f64, h: f64) -> Scene {
    crate::dynamics::block(l, h, None)
}

/// Runs `tribofe slide <args> --states <states> --out <dir>/<name>`; exit status and stderr.
fn slide_cli(dir: &Path, name: &str, args: &[&str], states: &str) -> (PathBuf, common::process::Ran) {
    let out = dir.join(name);
    let mut a = vec!["slide"];
    a.extend(args);
    a.extend(["--states", states, "--out", out.to_str().unwrap()]);
    (out.clone(), run(&a, LIMIT))
}

/// run.toml without the lines of the command line (the command, its arguments and the
/// --states and --out options: where the two runs differ) and the time it was written.
fn toml_body(dir: &Path) -> String {
    let text = std::fs::read_to_string(dir.join("run.toml")).unwrap();
    // The manifest lists states.csv in one run only; its other entries are the files compared.
    let text = text.split("\n[manifest]\n").next().unwrap_or_default().to_string();
    text.lines()
        .filter(|l| {
            !["command =", "arguments =", "out =", "states =", "date_utc ="].iter().any(|p| l.starts_with(p))
                // The phase times of a dynamic run (wall s) are measurements.
                && !l.contains("_wall_s =")
        })
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn states_none_writes_every_other_file_byte_identical() {
    // The reports read each event's summary, kept whether or not the states are, so the
    // bytes cannot depend on --states: equality is exact, file by file (every file the
    // `--states all` run wrote but states.csv), for the three paths that record events: the
    // quasi-static event solver (static-kinetic: precursors, creep runs in fronts.svg), the
    // held-drive dynamics (slip weakening, dynamic events: dyn_events.csv, cycle.svg)
    // and the constant-velocity drive (its samples).
    let dir = tempfile::tempdir().unwrap();
    let cases: [(&str, &[&str]); 3] = [
        ("sk", &["--law", "static-kinetic", "--length", "0.1", "--h", "0.001", "--cycles", "1"]),
        (
            "dyn",
            &["--dynamics", "--law", "slip-weakening", "--length", "0.1", "--h", "0.0005", "--x-max", "6e-6"],
        ),
        (
            "vel",
            &[
                "--dynamics",
                "--drive-velocity",
                "1e-5",
                "--law",
                "coulomb",
                "--length",
                "0.1",
                "--h",
                "0.001",
                "--x-max",
                "3.4e-5",
            ],
        ),
    ];
    for (name, args) in cases {
        let (all, ra) = slide_cli(dir.path(), &format!("{name}_all"), args, "all");
        let (none, rn) = slide_cli(dir.path(), &format!("{name}_none"), args, "none");
        assert_eq!((ra.code, rn.code), (0, 0), "{name}: {} / {}", ra.stderr, rn.stderr);
        let mut files: Vec<String> = std::fs::read_dir(&all)
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .filter(|f| f != "states.csv" && f != "run.toml")
            .collect();
        files.sort();
        let mut written: Vec<String> = std::fs::read_dir(&none)
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect();
        written.sort();
        assert!(all.join("states.csv").exists(), "{name}: the `all` run wrote no states.csv");
        let mut expected = files.clone();
        expected.push("run.toml".into());
        expected.sort();
        assert_eq!(written, expected, "{name}: files written without states");
        for must in ["loading.csv", "events.csv", "fronts.svg"] {
            assert!(files.iter().any(|f| f == must), "{name}: no {must}");
        }
        if name == "dyn" {
            assert!(files.iter().any(|f| f == "cycle.svg"), "{name}: no cycle.svg");
        }
        for f in &files {
            assert!(
                std::fs::read(all.join(f)).unwrap() == std::fs::read(none.join(f)).unwrap(),
                "{name}: {f} differs between --states all and none"
            );
        }
        assert_eq!(toml_body(&all), toml_body(&none), "{name}: run.toml");
    }
}

fn same_state(a: &State, b: &State) -> bool {
    (a.phase, a.x, a.f, a.n_force, a.tilt, a.v) == (b.phase, b.x, b.f, b.n_force, b.tilt, b.v)
        && (&a.t_force, &a.p_force, &a.u, &a.gap, &a.states)
            == (&b.t_force, &b.p_force, &b.u, &b.gap, &b.states)
}

/// The run with states kept and the same without: same events, one state (the last), and
/// the summaries those of the kept states.
fn check_pair(what: &str, kept: &SlideResult, lean: &SlideResult) {
    let (k, l) = (&kept.run, &lean.run);
    assert!(k.states.len() > 10 && k.has_all_states(), "{what}: {} states kept", k.states.len());
    assert_eq!(k.events.len(), l.events.len(), "{what}: events");
    assert_eq!(l.states.len(), 1, "{what}: keep_states false kept {} states", l.states.len());
    assert!(!l.has_all_states());
    assert!(same_state(l.states.last().unwrap(), k.states.last().unwrap()), "{what}: last state");
    assert_eq!(k.summaries.len(), k.states.len(), "{what}");
    for (j, st) in k.states.iter().enumerate() {
        assert_eq!(k.summaries[j], Summary::of(st), "{what}: summary {j} of the kept run");
    }
    assert_eq!(k.summaries, l.summaries, "{what}: summaries with and without states");
    assert_eq!(k.max_violation, l.max_violation, "{what}");
    // The summaries hold what fronts.svg draws: some state has slipping nodes, and the runs
    // cover exactly the slipping count.
    assert!(k.summaries.iter().any(|s| !s.slip_runs.is_empty()), "{what}: no slipping node");
    for s in &k.summaries {
        let in_runs: u32 = s.slip_runs.iter().map(|&(a, b)| b - a + 1).sum();
        assert_eq!(in_runs, s.counts[1], "{what}: runs vs count at X = {}", s.x);
    }
    // The readers of every state refuse the lean run instead of reading the wrong one.
    assert!(tribofe::report::slide::states_csv(lean).is_err(), "{what}: states.csv of a lean run");
    assert!(slide::state_displacements(lean, &[0], &Default::default()).is_err(), "{what}: fields");
}

#[test]
fn keep_states_false_holds_one_state_and_the_same_summaries() {
    // The run is the same computation with or without the states (they are only stored), so
    // the equalities are exact.
    let scene = block(0.1, 0.001);
    let sk = SlideOptions {
        law: Law::static_kinetic(0.648, 0.583, tribofe::law::Rule::Paper).unwrap(),
        cycles: 1,
        ..Default::default()
    };
    let coulomb = SlideOptions { law: Law::coulomb(0.5).unwrap(), ..Default::default() };
    for (what, o) in [("static-kinetic", &sk), ("coulomb", &coulomb)] {
        let kept = slide::run(&scene, o, tribofe::Progress::none()).unwrap();
        let lean =
            slide::run(&scene, &SlideOptions { keep_states: false, ..o.clone() }, tribofe::Progress::none())
                .unwrap();
        check_pair(what, &kept, &lean);
        // The slip front read off the summaries (coulomb only) is the same.
        let (a, b) = (slide::front_offset(&kept), slide::front_offset(&lean));
        assert_eq!(format!("{a:?}"), format!("{b:?}"), "{what}: front offset");
        if what == "coulomb" {
            assert!(a.is_some_and(|f| f.samples > 10), "coulomb: front offset {a:?}");
        }
    }
    // The held-drive and the constant-velocity dynamics.
    let (scene, sw) = crate::dynamics::short_weakening(tribofe::interface::events::Operator::Dense, 6e-6);
    let vel_scene = block(0.1, 0.001);
    let cl = SlideOptions { law: Law::coulomb(0.5).unwrap(), x_max: Some(3.4e-5), ..Default::default() };
    let vel = DynamicOptions { drive_velocity: Some(1e-5), ..Default::default() };
    for (what, sc, o, d) in
        [("held", &scene, &sw, &DynamicOptions::default()), ("velocity", &vel_scene, &cl, &vel)]
    {
        let kept = ds::run(sc, o, d, tribofe::Progress::none()).unwrap();
        let lean =
            ds::run(sc, &SlideOptions { keep_states: false, ..o.clone() }, d, tribofe::Progress::none())
                .unwrap();
        assert_eq!(kept.events.len(), lean.events.len(), "{what}: dynamic events");
        if what == "held" {
            assert!(kept.events.len() >= 3, "held: {} dynamic events", kept.events.len());
        }
        check_pair(what, &kept.slide, &lean.slide);
    }
}

#[test]
fn the_event_cap_check_counts_only_what_is_kept() {
    // A cap whose states need twice half the memory the process may use, while the summaries
    // alone need a quarter of it (their bytes per event at 101 nodes are ~10x fewer): refused
    // with the states kept (exit 2, naming --max-events and the way out), accepted without
    // (the run, a short coulomb one, then ends by itself long before the cap).
    let (mem, _) = tribofe::scene::limits::memory_bytes();
    let n = 101; // L = 0.1 m, h = 1 mm
    let (with, without) = (bytes_per_event(n, true), bytes_per_event(n, false));
    assert!(with > 8.0 * without, "bytes per event {with} with states, {without} without");
    let cap = (0.25 * 0.5 * mem / without) as u64;
    assert!(cap as f64 * with > 2.0 * 0.5 * mem);
    let cap = cap.to_string();
    let dir = tempfile::tempdir().unwrap();
    let args = ["--law", "coulomb", "--length", "0.1", "--h", "0.001", "--max-events", &cap];
    let (out, r) = slide_cli(dir.path(), "kept", &args, "all");
    assert_eq!(r.code, 2, "states kept: exit {}, {}", r.code, r.stderr);
    for s in ["--max-events", "GiB", "--states none"] {
        assert!(r.stderr.contains(s), "the refusal must say {s:?}: {}", r.stderr);
    }
    assert!(!out.exists(), "the refusal left {}", out.display());
    let (out, r) = slide_cli(dir.path(), "lean", &args, "none");
    assert_eq!(r.code, 0, "no states: exit {}, {}", r.code, r.stderr);
    assert!(out.join("loading.csv").exists() && !out.join("states.csv").exists());
}

#[test]
fn fields_need_the_states() {
    // --fields writes the block in picked states: with `--states none` there are none to
    // pick, so the pair is refused before any work, naming both flags.
    let dir = tempfile::tempdir().unwrap();
    let (out, r) = slide_cli(
        dir.path(),
        "f",
        &["--law", "coulomb", "--length", "0.1", "--h", "0.001", "--fields", "3"],
        "none",
    );
    assert_eq!(r.code, 2, "exit {}, {}", r.code, r.stderr);
    assert!(r.stderr.contains("--fields") && r.stderr.contains("--states none"), "{}", r.stderr);
    assert!(!r.stderr.contains("panicked"), "{}", r.stderr);
    assert!(!out.exists());
}
