//! Issue 31, what a user meets first (process tests of the `tribofe` command): `--out` never
//! deletes a file tribofe did not write, every folder holds a parseable run.toml, a closed pipe
//! is a non-zero exit with the results on disk, control bytes are quoted, negative values
//! reach the range checks, no `inf` in a results file, flags that cannot act are refused.

use crate::common;

use common::commands::{DC_QUICK, EDGES_QUICK};
use std::io::{BufRead, BufReader};
use std::path::Path;
use std::process::{Command, Output, Stdio};

pub(crate) fn tribofe(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_tribofe")).current_dir(dir).args(args).output().unwrap()
}

pub(crate) fn ok(dir: &Path, args: &[&str]) -> String {
    let o = tribofe(dir, args);
    assert_eq!(o.status.code(), Some(0), "{args:?}: {}", String::from_utf8_lossy(&o.stderr));
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// Asserts exit status 2 and a message holding every word of `words`; returns the message.
pub(crate) fn refused(dir: &Path, args: &[&str], words: &[&str]) -> String {
    let o = tribofe(dir, args);
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert_eq!(o.status.code(), Some(2), "{args:?} should be refused: {err}");
    for w in words {
        assert!(err.contains(w), "{args:?}: the message should name '{w}': {err}");
    }
    err
}

/// A quick check (short block, no converged run, no fields) into `out`.
fn check_args(out: &str) -> Vec<&str> {
    vec!["check", "--length", "0.05", "--no-converged", "--no-fields", "--out", out]
}

#[test]
fn a_foreign_file_in_out_survives_and_the_run_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::create_dir(d.join("proj")).unwrap();
    std::fs::write(d.join("proj/notes.txt"), "my notes").unwrap();
    refused(d, &check_args("proj"), &["proj", "notes.txt", "--force"]);
    assert_eq!(std::fs::read_to_string(d.join("proj/notes.txt")).unwrap(), "my notes");
    assert!(!d.join("proj/run.toml").exists(), "nothing written into the refused folder");
    // Every command that has --out refuses it the same way.
    for args in [
        &["solve", "--nx", "4", "--ny", "1", "--out", "proj"][..],
        &["precursors", "--out", "proj"],
        &["sweep", "--length", "0.05", "--thickness", "0.002,0.004", "--out", "proj"],
        &["bench", "--case", "square1", "--dgemm", "0", "--out", "proj"],
    ] {
        refused(d, args, &["proj", "--force"]);
        assert_eq!(std::fs::read_to_string(d.join("proj/notes.txt")).unwrap(), "my notes");
    }
    // --force writes into it; the user's file stays (only files of the run's names are replaced).
    let mut forced = check_args("proj");
    forced.push("--force");
    ok(d, &forced);
    assert!(d.join("proj/notes.txt").exists() && d.join("proj/run.toml").exists());
    // An empty existing folder is used as is.
    std::fs::create_dir(d.join("empty")).unwrap();
    ok(d, &check_args("empty"));
    assert!(d.join("empty/summary.csv").exists());
}

#[test]
fn a_second_run_replaces_the_files_the_first_one_listed() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    ok(d, &["check", "--length", "0.05", "--no-converged", "--out", "ck"]);
    assert!(d.join("ck/fields_FN0.vtu").exists());
    ok(d, &check_args("ck"));
    assert!(d.join("ck/summary.csv").exists());
    assert!(!d.join("ck/fields_FN0.vtu").exists(), "the first run's listed files it does not write go");
}

#[test]
fn orphaned_temporaries_of_a_killed_run_are_cleaned() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // A pid that has ended: a child reaped here.
    let mut child = Command::new("true").spawn().unwrap();
    let dead = child.id();
    child.wait().unwrap();
    let orphan = d.join(format!(".ck.tmp-{dead}"));
    std::fs::create_dir(&orphan).unwrap();
    std::fs::write(orphan.join("summary.csv"), "half").unwrap();
    // A live run's temporary (this test's own pid) is left alone.
    let live = d.join(format!(".ck.tmp-{}", std::process::id()));
    std::fs::create_dir(&live).unwrap();
    ok(d, &check_args("ck"));
    assert!(!orphan.exists(), "the orphan of pid {dead} should be removed");
    assert!(live.exists(), "a live run's temporary must stay");
}

/// The run.toml of `folder`, parsed, with the provenance every command records.
fn assert_run_file(folder: &Path, subcommand: &str, has_scene: bool) -> toml::Table {
    let path = folder.join("run.toml");
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert!(text.starts_with("# written by tribofe"), "{}: marker line", path.display());
    let t: toml::Table = text.parse().unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let p = t["tribofe"].as_table().unwrap();
    assert_eq!(p["version"].as_str(), Some(env!("CARGO_PKG_VERSION")));
    if let Some(rev) = option_env!("TRIBOFE_GIT_REVISION") {
        assert_eq!(p["revision"].as_str(), Some(rev), "{}", path.display());
        assert!(p["revision_dirty"].is_bool());
    }
    let date = p["date_utc"].as_str().unwrap();
    // YYYY-MM-DDTHH:MM:SSZ
    assert!(date.len() == 20 && &date[4..5] == "-" && &date[10..11] == "T" && date.ends_with('Z'), "{date}");
    assert!(p["host"].as_str().is_some_and(|h| !h.is_empty()));
    let args: Vec<&str> = p["arguments"].as_array().unwrap().iter().map(|a| a.as_str().unwrap()).collect();
    assert_eq!(args[1], subcommand);
    assert!(p["command"].as_str().unwrap().contains(subcommand));
    let o = t["options"].as_table().unwrap();
    assert_eq!(o["subcommand"].as_str(), Some(subcommand));
    assert!(o.contains_key("out") && o.contains_key("force"), "{}: every option", path.display());
    assert!(t.get("results").is_some_and(|r| r.is_table()), "{}: [results]", path.display());
    assert_eq!(t.get("scene").is_some_and(|s| s["block"].is_table()), has_scene, "{}", path.display());
    t
}

#[test]
fn every_command_writes_a_run_file_with_its_provenance() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let cases: &[(&[&str], &str, bool)] = &[
        (&["check", "--length", "0.05", "--no-fields", "--out", "ck"], "ck", true),
        (&["solve", "--nx", "8", "--ny", "2", "--out", "so"], "so", false),
        (
            &["converge", "--length", "0.05", "--families", "uniform", "--n-thick", "1,2", "--out", "cv"],
            "cv",
            true,
        ),
        (
            &["stability", "--study", "corners", "--corner-max", "4", "--length", "0.05", "--out", "st"],
            "st",
            true,
        ),
        (
            &["slide", "--length", "0.05", "--h", "0.001", "--law", "coulomb", "--mu", "0.5", "--out", "sl"],
            "sl",
            true,
        ),
        (EDGES_QUICK, "ed", true),
        (&["sweep", "--length", "0.05", "--thickness", "0.002,0.004", "--out", "sw"], "sw", true),
        (&["bench", "--case", "square1", "--dgemm", "0", "--out", "be"], "be", false),
        (&["precursors", "--out", "pr"], "pr", false),
        (&["precursors", "--map", "--resolution", "4", "--out", "pm"], "pm", false),
        (&["precursors", "--fe", "--length", "0.05", "--out", "pf"], "pf", true),
        (
            &["precursors", "--fe", "--map", "--resolution", "2", "--length", "0.05", "--out", "pfm"],
            "pfm",
            true,
        ),
        (&["precursors", "--fe", "--thin-layer", "0.04", "--length", "0.05", "--out", "pt"], "pt", true),
        (&["precursors", "--fe", "--heights", "0.1", "--length", "0.05", "--out", "ph"], "ph", true),
        (DC_QUICK, "pd", true),
        (&["precursors", "--bonded-fields", "--length", "0.05", "--out", "pb"], "pb", true),
    ];
    for (args, out, has_scene) in cases {
        ok(d, args);
        let t = assert_run_file(&d.join(out), args[0], *has_scene);
        assert_eq!(t["options"]["out"].as_str(), Some(*out));
    }
    // Figures a run records: the check's loads per case, N in N/m > 0.
    let ck = assert_run_file(&d.join("ck"), "check", true);
    let cases = ck["results"]["cases"].as_array().unwrap();
    assert_eq!(cases.len(), 3);
    assert!(cases.iter().all(|c| c["n_force_n_per_m"].as_float().unwrap() > 0.0));
    // A sweep shard records its own run file beside its table.
    ok(d, &["sweep", "--length", "0.05", "--thickness", "0.002,0.004", "--shard", "1/2", "--out", "sh"]);
    let text = std::fs::read_to_string(d.join("sh/run_1of2.toml")).unwrap();
    let t: toml::Table = text.parse().unwrap();
    assert_eq!(t["options"]["shard"].as_str(), Some("1/2"));
}

#[test]
fn quoting_in_the_recorded_command_line() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    ok(d, &["check", "--length", "0.05", "--no-converged", "--no-fields", "--out", "my run"]);
    let t = assert_run_file(&d.join("my run"), "check", true);
    assert!(t["tribofe"]["command"].as_str().unwrap().ends_with("--out 'my run'"));
}

/// Spawns `args` with a piped standard output, reads `lines` lines, closes the pipe, waits.
fn closed_after(dir: &Path, args: &[&str], lines: usize) -> Option<i32> {
    let mut child = Command::new(env!("CARGO_BIN_EXE_tribofe"))
        .current_dir(dir)
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let out = child.stdout.take().unwrap();
    if lines > 0 {
        let mut r = BufReader::new(out);
        let mut line = String::new();
        for _ in 0..lines {
            r.read_line(&mut line).unwrap();
        }
        drop(r);
    } else {
        drop(out);
    }
    child.wait().unwrap().code()
}

#[test]
fn a_closed_pipe_is_a_non_zero_exit_with_the_results_on_disk() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // `| head -1` on a long table: the pipe's buffer fills, the reader leaves after one line.
    assert_eq!(closed_after(d, &["precursors", "--events", "5000", "--out", "pr"], 1), Some(141));
    assert!(d.join("pr/events.csv").exists() && d.join("pr/run.toml").exists());
    // A reader gone before the first line (the end of `| head -1` on a short output).
    for (args, out, file) in [
        (&check_args("ck")[..], "ck", "summary.csv"),
        (&["precursors", "--out", "pq"], "pq", "events.csv"),
        (&["precursors", "--fe", "--length", "0.05", "--out", "pf"], "pf", "summary.csv"),
    ] {
        assert_eq!(closed_after(d, args, 0), Some(141), "{args:?}");
        assert!(d.join(out).join(file).exists(), "{args:?}: results before output");
    }
    let help = ok(d, &["--help"]);
    assert!(help.contains("141"), "the status is documented in --help");
}

/// Asserts `text` holds no raw control byte but line breaks, and holds the quoted ESC.
fn assert_quoted(text: &str, what: &str) {
    assert!(!text.chars().any(|c| c.is_control() && c != '\n'), "{what}: raw control byte in {text:?}");
    assert!(text.contains("\\x1b"), "{what}: ESC should be quoted as \\x1b: {text}");
}

#[test]
fn control_bytes_are_quoted_in_every_message() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // In an argument: clap's own error, and the library's.
    let e = refused(d, &["check", "--length", "0.0\u{1b}5"], &["--length"]);
    assert_quoted(&e, "clap value");
    let e = refused(d, &["check", "--bog\u{1b}us"], &["--bog"]);
    assert_quoted(&e, "clap flag");
    let e = refused(d, &["check", "--element", "qua\u{1b}[31m4", "--out", "x"], &["element"]);
    assert_quoted(&e, "element argument");
    // In a string value of a scene file.
    std::fs::write(d.join("s.toml"), "[mesh]\nelement = \"qua\\u001b4\"\n").unwrap();
    let e = refused(d, &["check", "--scene", "s.toml", "--out", "x"], &["element"]);
    assert_quoted(&e, "scene string");
    // In a physical name of a mesh.
    let mesh =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/meshes/block_regular_v22_ascii.msh"))
            .unwrap()
            .replace("\"interface\"", "\"inter\u{1b}face\"");
    std::fs::write(d.join("esc.msh"), mesh).unwrap();
    let e = refused(d, &["check", "--mesh", "esc.msh", "--out", "x"], &["interface"]);
    assert_quoted(&e, "physical name");
    // In an output path printed on standard output.
    let out = ok(d, &check_args("o\u{1b}ut"));
    assert_quoted(&out, "printed path");
}

#[test]
fn negative_values_reach_the_range_checks_in_both_forms() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for form in [&["--length", "-1"][..], &["--length=-1"]] {
        let mut args = vec!["check"];
        args.extend_from_slice(form);
        refused(d, &args, &["--length", "-1 must be a positive number"]);
    }
    // Lists and ranges starting with a negative number are values too.
    refused(d, &["sweep", "--poisson", "-2,0.3", "--out", "x"], &["--poisson"]);
    refused(d, &["sweep", "--poisson", "-2:0.3:3", "--out", "x"], &["--poisson"]);
    refused(d, &["slide", "--n-force", "-1", "--out", "x"], &["--n-force"]);
    // Accepted where it makes sense: F/N < 0 drives the block the other way.
    let out = ok(
        d,
        &[
            "check",
            "--length",
            "0.05",
            "--no-converged",
            "--no-fields",
            "--fn-ratios",
            "-0.41,0",
            "--out",
            "neg",
        ],
    );
    assert!(out.contains("wrote"));
    assert!(d.join("neg/profile_FN-0.41.csv").exists());
}

#[test]
fn messages_name_the_flag_typed() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    refused(d, &["solve", "--poisson", "0.7", "--out", "x"], &["--poisson"]);
    refused(d, &["solve", "--young", "-1", "--out", "x"], &["--young"]);
    refused(d, &["slide", "--x-max", "-1", "--out", "x"], &["--x-max"]);
    refused(d, &["slide", "--law", "slip-weakening", "--dc", "-1", "--out", "x"], &["--dc"]);
    refused(d, &["sweep", "--friction", "0.5,0.6", "--out", "x"], &["--friction"]);
    refused(d, &["check", "--grading", "0.5", "--out", "x"], &["--grading"]);
}

#[test]
fn bench_writes_finite_numbers_only() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    ok(d, &["bench", "--case", "square1", "--dgemm", "0", "--out", "be"]);
    let csv = std::fs::read_to_string(d.join("be/bench.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let row: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(header.len(), row.len());
    for (h, v) in header.iter().zip(&row) {
        if let Ok(x) = v.parse::<f64>() {
            assert!(x.is_finite(), "bench.csv {h} = {v}");
        }
    }
    let col = |name: &str| row[header.iter().position(|h| *h == name).unwrap()].parse::<f64>().unwrap();
    // 4 unknowns in a positive measured time: a finite positive rate, dofs / total.
    assert!(col("total_s") > 0.0);
    let rate = col("dofs") / col("total_s");
    assert!((col("dofs_per_s") - rate).abs() <= 0.5 + 1e-3 * rate, "{} vs {rate}", col("dofs_per_s"));
}

#[test]
fn flags_that_cannot_act_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let sweep = |extra: &[&'static str]| {
        let mut a = vec!["sweep", "--length", "0.05", "--thickness", "0.002,0.004", "--out", "x"];
        a.extend_from_slice(extra);
        a
    };
    refused(d, &sweep(&["--tension-fn", "nan"]), &["--tension-fn"]);
    let mesh = concat!(env!("CARGO_MANIFEST_DIR"), "/meshes/block_regular_v22_ascii.msh");
    refused(d, &sweep(&["--mesh", mesh]), &["--mesh"]);
    refused(d, &sweep(&["--rule", "overdamped"]), &["--rule", "--friction"]);
    refused(d, &sweep(&["--cycles", "5"]), &["--cycles", "--friction"]);
    refused(d, &sweep(&["--h", "0.001"]), &["--h", "--as-meshed"]);
    for flag in ["--plate-thickness", "--plate-modulus", "--plate-poisson"] {
        refused(d, &["check", "--plate", "rigid", flag, "0.3", "--out", "x"], &[flag, "rigid"]);
    }
    std::fs::write(d.join("rigid.toml"), "[plate]\nmodel = \"rigid\"\nthickness = 0.01\n").unwrap();
    refused(d, &["check", "--scene", "rigid.toml", "--out", "x"], &["plate.thickness", "rigid.toml"]);
    // A scene written by --write-scene (every key, the plate's at their defaults) is accepted.
    ok(
        d,
        &[
            "check",
            "--length",
            "0.05",
            "--no-converged",
            "--no-fields",
            "--write-scene",
            "w.toml",
            "--out",
            "w",
        ],
    );
    ok(d, &["check", "--scene", "w.toml", "--no-converged", "--no-fields", "--out", "w"]);
    refused(d, &["precursors", "--length", "0.1", "--out", "x"], &["--length", "--fe"]);
    refused(d, &["precursors", "--fe", "--events", "5", "--out", "x"], &["--events"]);
    refused(d, &["precursors", "--fe", "--max-events", "5", "--out", "x"], &["--max-events"]);
    refused(d, &["stability", "--study", "nu", "--corner-max", "4", "--out", "x"], &["--corner-max"]);
    refused(d, &["slide", "--law", "coulomb", "--rule", "overdamped", "--out", "x"], &["--rule"]);
    refused(d, &["bench", "--case", "square1", "--repeat", "0", "--out", "x"], &["--repeat"]);
    refused(d, &["precursors", "--fe", "--dc", "1e-6", "--cycles", "2", "--out", "x"], &["--cycles", "--dc"]);
    assert!(!d.join("x").exists(), "nothing written by a refused run");
}
