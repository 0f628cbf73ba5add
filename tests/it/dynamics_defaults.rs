//! `slide --dynamics` tried as a new user would (issue 43): physical defaults that never
//! follow the mesh, the first run working with its defaults, the paper's control case H = 0,
//! a capped run that keeps what it computed, and the one summary table.

use crate::common::process::{run, Ran};
use std::collections::HashMap;
use std::path::Path;
use std::time::Duration;

/// summary.csv's one row by column name (empty cells left out).
fn summary(dir: &Path) -> HashMap<String, f64> {
    let text = std::fs::read_to_string(dir.join("summary.csv")).unwrap();
    let mut lines = text.lines();
    let head: Vec<&str> = lines.next().unwrap().split(',').collect();
    let row: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(head.len(), row.len(), "{text}");
    assert!(lines.next().is_none(), "one row: {text}");
    head.iter()
        .zip(row)
        .filter(|(_, v)| !v.is_empty())
        .map(|(k, v)| (k.to_string(), v.parse::<f64>().unwrap_or_else(|_| panic!("{k} = {v}"))))
        .collect()
}

fn tribofe(args: &[&str], out: &Path, limit_s: u64) -> Ran {
    let mut a = args.to_vec();
    let o = out.to_str().unwrap();
    a.extend(["--out", o]);
    run(&a, Duration::from_secs(limit_s))
}

/// The short block of the dynamic tests: L = 0.1 m, the paper's t, E, nu, H.
const SHORT: &[&str] = &["slide", "--dynamics", "--law", "slip-weakening", "--length", "0.1"];

#[test]
fn the_default_dc_is_the_same_for_any_h_and_the_mesh_resolves_it() {
    // kappa = G D_c / ((mu_s - mu_d) (N/L) t) = 0.5093 fixes D_c: on the L = 0.1 m block N/L
    // is 4 times the paper's and mu_s - mu_d (from (r, g) at its H/L) 4 times smaller, so D_c
    // is the paper's 2.3107e-7 m again; the cohesive zone is 1.4726 t kappa = 1.5000 mm, so
    // t/4 is the largest whole fraction of t with 3 elements in it.
    let dir = tempfile::tempdir().unwrap();
    let mut dcs = vec![];
    for (name, h) in [("auto", None), ("h25", Some("0.00025"))] {
        let out = dir.path().join(name);
        let mut args = SHORT.to_vec();
        args.extend(["--x-max", "1e-7"]);
        if let Some(h) = h {
            args.extend(["--h", h]);
        }
        let r = tribofe(&args, &out, 120);
        assert_eq!(r.code, 0, "{name}: {}", r.stderr);
        let s = summary(&out);
        dcs.push(s["dc_m"]);
        assert!((s["kappa"] - 0.5093).abs() < 5e-5, "{name}: kappa {}", s["kappa"]);
        assert!((s["lambda0_m"] - 1.5e-3).abs() < 1e-8, "{name}: {}", s["lambda0_m"]);
        let want_h = h.map_or(5e-4, |h| h.parse().unwrap());
        assert_eq!(s["h_m"], want_h, "{name}");
        if h.is_none() {
            assert!(r.stderr.contains("--h not given: h = 5.0000e-4 m (t/4)"), "{}", r.stderr);
        }
    }
    assert!(dcs.iter().all(|&d| d == dcs[0]), "{dcs:?}");
    assert!((dcs[0] / 2.3107e-7 - 1.0).abs() < 1e-12, "{}", dcs[0]);
    // A given h that does not resolve the zone is refused before any work, naming the --h
    // that would (t/4) and the D_c this mesh resolves.
    let out = dir.path().join("coarse");
    let mut args = SHORT.to_vec();
    args.extend(["--h", "0.001"]);
    let r = tribofe(&args, &out, 60);
    assert_eq!(r.code, 2, "{}", r.stderr);
    assert!(r.stderr.contains("invalid --h") && r.stderr.contains("--h 5.0000e-4"), "{}", r.stderr);
    assert!(!out.exists());
}

#[test]
fn the_default_first_run_completes_the_papers_first_cycle_with_precursors() {
    // `tribofe slide --dynamics --law slip-weakening`, nothing else: the paper's scene at
    // D_c = 2.3107e-7 m on the t/4 mesh to the front crossing. Its F_1 and x_1 are the
    // convergence study's (validation/dynamics/converge/table.csv: 0.7350 and -0.4612 at all
    // three meshes; here to 1e-4 of mu_s N and one element, h/L = 1.25e-3).
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("first");
    let r = tribofe(&["slide", "--dynamics", "--law", "slip-weakening"], &out, 900);
    assert_eq!(r.code, 0, "{}", r.stderr);
    let s = summary(&out);
    assert_eq!(s["complete"], 1.0);
    assert_eq!(s["dc_m"], 2.3107e-7);
    assert_eq!(s["h_m"], 5e-4);
    assert!((s["first_advance_F_over_mu_s_N"] - 0.7350).abs() < 1e-4, "{s:?}");
    assert!((s["first_advance_front_over_L"] + 0.4612).abs() < 1.25e-3, "{s:?}");
    assert!(s["front_advances"] >= 5.0 && s["edge_precursors"] >= 1.0, "{s:?}");
    assert_eq!(s["nucleation_at_leading_edge"], 0.0);
    // The largest force before the crossing: 0.951 +- 0.005 over the study's meshes.
    assert!((s["largest_F_before_crossing_over_mu_s_N"] - 0.951).abs() < 0.01, "{s:?}");
    assert!(s["crossing_F_over_mu_s_N"] <= s["largest_F_before_crossing_over_mu_s_N"]);
    let toml = std::fs::read_to_string(out.join("run.toml")).unwrap();
    assert!(toml.contains("first_advance_F_over_mu_s_N") && !toml.contains("incomplete"), "{toml}");
    assert!(!out.join("states.csv").exists(), "--states none is the dynamic default");
}

#[test]
fn the_control_case_h_0_runs_and_its_slip_nucleates_at_the_leading_edge() {
    // The paper's control case: the drive in the interface plane, no torque. The model says
    // no precursors (F_1 = F_max = 1). The block's own shear couple remains: the interior
    // pressure slope goes like (H - t/2) (docs/check.md), negative at H = 0, so the pressure
    // is lowest at the leading edge and slip nucleates there: counted from there, and said.
    let dir = tempfile::tempdir().unwrap();
    // The paper's block (7 s): the model's F_1 = 1 is not reached, slip starts below it.
    let out = dir.path().join("h0");
    let r = tribofe(&["slide", "--dynamics", "--law", "slip-weakening", "--height", "0"], &out, 300);
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert!(r.stdout.contains("g = 0.0000): n = 0, F_1 = 1.0000"), "{}", r.stdout);
    assert!(r.stdout.contains("counted from the leading edge"), "{}", r.stdout);
    let s = summary(&out);
    assert_eq!(s["nucleation_at_leading_edge"], 1.0);
    assert_eq!(s["complete"], 1.0);
    assert!(s["front_advances"] >= 1.0 && s["first_advance_front_over_L"] > 0.0, "{s:?}");
    assert!(s["first_advance_F_over_mu_s_N"] < 0.99, "{s:?}");
    // (r, g) cannot set the coefficients at H = 0; g = 0 at H > 0 points to --height 0.
    for (extra, want) in [
        (&["--height", "0", "--r", "0.9", "--g", "0.35"][..], "--height 0"),
        (&["--r", "0.9", "--g", "0"][..], "--height 0"),
    ] {
        let mut a = SHORT.to_vec();
        a.extend(extra);
        let r = tribofe(&a, &dir.path().join("refused"), 60);
        assert_eq!(r.code, 2, "{extra:?}: {}", r.stderr);
        assert!(r.stderr.contains("invalid --g") && r.stderr.contains(want), "{}", r.stderr);
    }
}

#[test]
fn a_run_that_meets_a_cap_writes_what_it_computed_and_exits_incomplete() {
    // The event cap met midway: exit 5, the tables up to there, the cap in run.toml and on
    // stderr; the summary says complete = 0.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("capped");
    let mut args = SHORT.to_vec();
    args.extend(["--max-events", "40"]);
    let r = tribofe(&args, &out, 300);
    assert_eq!(r.code, 5, "{}", r.stderr);
    assert!(r.stderr.contains("incomplete: --max-events = 40 met"), "{}", r.stderr);
    let s = summary(&out);
    assert_eq!(s["complete"], 0.0);
    let events = std::fs::read_to_string(out.join("events.csv")).unwrap();
    assert_eq!(events.lines().count(), 1 + 40, "{events}");
    let toml = std::fs::read_to_string(out.join("run.toml")).unwrap();
    assert!(toml.contains("incomplete = \"--max-events = 40 met"), "{toml}");
}

#[test]
fn rupture_regularises_the_normal_stress_by_default_and_warns_without_it() {
    // The default is the normal-stress lag T = 1 ms (run.toml's scene records it); the spec's
    // instantaneous normal stress (--normal-lag 0) on a rigid flat is warned about, on the
    // symmetric fault (normal stress constant) not. Refused: a negative T.
    let dir = tempfile::tempdir().unwrap();
    let short = ["rupture", "--t-end", "0.01"];
    let with = |extra: &[&str], name: &str| {
        let mut a = short.to_vec();
        a.extend(extra);
        tribofe(&a, &dir.path().join(name), 120)
    };
    let d = with(&[], "default");
    assert_eq!(d.code, 0, "{}", d.stderr);
    assert!(!d.stderr.contains("warning"), "{}", d.stderr);
    let i = with(&["--normal-lag", "0"], "instantaneous");
    assert_eq!(i.code, 0, "{}", i.stderr);
    assert!(i.stderr.contains("warning: the instantaneous normal stress on a rigid flat"), "{}", i.stderr);
    let s = with(&["--normal-lag", "0", "--contact", "symmetric"], "symmetric");
    assert!(s.code == 0 && !s.stderr.contains("warning"), "{}", s.stderr);
    let n = with(&["--normal-lag", "-1e-3"], "negative");
    assert_eq!(n.code, 2, "{}", n.stderr);
    assert!(n.stderr.contains("--normal-lag"), "{}", n.stderr);
    // The default's force drop differs from the instantaneous run's: the lag acts.
    let drop = |name: &str| -> String {
        let s = std::fs::read_to_string(dir.path().join(name).join("summary.csv")).unwrap();
        s.lines().nth(1).unwrap().split(',').next().unwrap().to_string()
    };
    assert_ne!(drop("default"), drop("instantaneous"));
}
