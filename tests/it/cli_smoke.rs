//! One small run of every subcommand as a user starts it: exit status 0, the files it names
//! written and non-empty, nothing else left in the working folder (no temporaries).

use crate::common;

use common::commands::{DC_QUICK, EDGES_QUICK};
use std::path::Path;
use std::process::Command;

fn run(dir: &Path, args: &[&str]) -> String {
    let o = Command::new(env!("CARGO_BIN_EXE_tribofe")).current_dir(dir).args(args).output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "{args:?}: {err}");
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn assert_files(dir: &Path, files: &[&str]) {
    for f in files {
        let len = std::fs::metadata(dir.join(f)).map(|m| m.len()).unwrap_or(0);
        assert!(len > 0, "{} missing or empty", dir.join(f).display());
    }
}

#[test]
fn every_subcommand_runs_and_writes_what_it_names() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let cases: &[(&[&str], &str, &[&str])] = &[
        (
            &["check", "--length", "0.05", "--out", "ck"],
            "ck",
            &["summary.csv", "profile_FN0.82.csv", "fig2.svg", "run.toml"],
        ),
        (&["solve", "--nx", "8", "--ny", "2", "--out", "so"], "so", &["fields.vtu", "fields.msh"]),
        (
            &["converge", "--length", "0.05", "--families", "uniform", "--n-thick", "1,2", "--out", "cv"],
            "cv",
            &["convergence.csv", "error_vs_dofs.svg", "summary.txt"],
        ),
        (
            &["stability", "--study", "corners", "--corner-max", "4", "--length", "0.05", "--out", "st"],
            "st",
            &["corners.csv", "corners.svg", "summary.txt"],
        ),
        (
            &[
                "slide", "--length", "0.05", "--h", "0.001", "--law", "coulomb", "--mu", "0.5", "--fields",
                "1", "--out", "sl",
            ],
            "sl",
            &[
                "loading.csv",
                "events.csv",
                "states.csv",
                "fig4_fe.svg",
                "fronts.svg",
                "run.toml",
                "fields.pvd",
            ],
        ),
        (EDGES_QUICK, "ed", &["preslip.csv", "preslip.svg", "opening.csv", "run.toml"]),
        (&["sweep", "--length", "0.05", "--thickness", "0.002,0.004", "--out", "sw"], "sw", &["sweep.csv"]),
        (&["precursors", "--out", "pr"], "pr", &["events.csv", "loading.csv", "fig4.svg"]),
        (
            &["precursors", "--fe", "--length", "0.05", "--out", "pf"],
            "pf",
            &[
                "summary.csv",
                "model/fig4.svg",
                "paper/events.csv",
                "overdamped/fig4_fe.svg",
                "paper/run.toml",
            ],
        ),
        (
            &[
                "precursors",
                "--fe",
                "--map",
                "--resolution",
                "3",
                "--rules",
                "paper,overdamped",
                "--length",
                "0.05",
                "--out",
                "pm",
            ],
            "pm",
            &["fig5_fe.csv", "boundary_fe.csv", "fig5_fe.svg", "run.toml"],
        ),
        (
            &["precursors", "--fe", "--thin-layer", "0.04,0.02", "--length", "0.05", "--out", "pt"],
            "pt",
            &["thin_layer.csv", "thin_layer.svg", "run.toml"],
        ),
        (
            &["precursors", "--fe", "--heights", "0.05,0.1", "--length", "0.05", "--out", "ph"],
            "ph",
            &["heights.csv", "heights.svg", "run.toml"],
        ),
        (DC_QUICK, "pd", &["dc.csv", "dc.svg", "run.toml", "paper/fig4_fe.svg", "dc_1e-6/events.csv"]),
        (&["bench", "--case", "strip2", "--dgemm", "0", "--out", "be"], "be", &["bench.csv"]),
    ];
    for (args, out, files) in cases {
        run(d, args);
        assert_files(&d.join(out), files);
    }
    let mut left: Vec<String> = std::fs::read_dir(d)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    left.sort();
    let mut want: Vec<String> = cases.iter().map(|c| c.1.to_string()).collect();
    want.sort();
    assert_eq!(left, want, "only the named output folders");
    assert!(run(d, &["--help"]).contains("Exit status"));
}
