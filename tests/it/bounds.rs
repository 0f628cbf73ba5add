//! Every run bounded (issue 31): degenerate frictional inputs and count or size flags refused
//! with exit 2 and the flag named before any work, runs that were unbounded finishing, the
//! memory guard reading the process limit, the meshes that gave wrong numbers with exit 0
//! (a crack, an interface given as one line) refused naming the group and the place, and the
//! `edges` opening study printing no length its mesh cannot resolve.

use crate::common;

use common::process::{run, run_with, Ran};
use std::path::{Path, PathBuf};
use std::time::Duration;

/// Far above any of these runs' cost (all well under 5 s), far below a hang.
const LIMIT: Duration = Duration::from_secs(120);

fn out(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("tribofe_bounds_{}_{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

fn refused(args: &[&str], flag: &str, also: &[&str]) -> Ran {
    let dir = out(&args.join("_").replace(['/', ' '], "_"));
    let mut a = args.to_vec();
    let d = dir.to_str().unwrap().to_string();
    a.extend(["--out", &d]);
    let r = run(&a, LIMIT);
    assert_eq!(r.code, 2, "{args:?}: exit {}, stderr {}", r.code, r.stderr);
    assert!(r.stderr.contains(flag), "{args:?} must name {flag}: {}", r.stderr);
    for s in also {
        assert!(r.stderr.contains(s), "{args:?} must say {s:?}: {}", r.stderr);
    }
    assert!(!r.stderr.contains("panicked"), "{}", r.stderr);
    assert!(!dir.exists(), "{args:?}: the refusal left {}", dir.display());
    r
}

#[test]
fn degenerate_frictional_inputs_are_refused_with_the_reason() {
    refused(&["slide", "--law", "coulomb", "--mu", "0"], "--mu", &["slides as soon as it is loaded"]);
    // With an end too: every result is in units of mu_s N, which mu = 0 makes 0 (Python's
    // curve_F_over_mu_s_N was infinite; the command once hung drawing fig. 4 from it).
    for mode in [&[][..], &["--dynamics"][..]] {
        let args = [&["slide", "--law", "coulomb", "--mu", "0", "--x-max", "1e-6"][..], mode].concat();
        refused(&args, "--mu", &["units of mu_s N", "give mu > 0"]);
    }
    refused(&["slide", "--law", "coulomb", "--mu", "1e7"], "mu", &["above 1000000"]);
    refused(&["slide", "--x-max", "1e308"], "--x-max", &["block's length"]);
    // N/L against [1e-100 N/m / L, E]: subnormal displacements, or strains of order one.
    refused(&["slide", "--n-force", "1e-308"], "--n-force", &["2.5e-308 Pa"]);
    refused(&["slide", "--n-force", "18446744073709551615"], "--n-force", &["E = 2e3 Pa"]);
    // The paper's block: tau t/G = mu_s (N/L) t / (E/(2(1 + nu))) with mu_s = 0.35/(0.6 x 0.9),
    // N/L = 2.5 Pa, t = 2 mm, E = 2 kPa, nu = 0.4: 4.537e-6 m; the floor is 1e-6 of it.
    let slip: f64 = 0.35 / 0.6 / 0.9 * 2.5 * 0.002 / (2e3 / 2.8);
    assert!((slip - 4.537e-6).abs() < 1e-9);
    refused(&["slide", "--law", "slip-weakening", "--dc", "1e-300"], "--dc", &["4.537e-12 m", "tau t/G"]);
    // The ceiling: nucleation length G D_c/((mu_s - mu_d) N/L) = 100 L = 40 m.
    let (ms, md) = (0.35 / 0.6 / 0.9, 0.35 / 0.6);
    let hi = 100.0 * 0.4 * (ms - md) * 2.5 / (2e3 / 2.8);
    let r = refused(&["slide", "--law", "slip-weakening", "--dc", "1e300"], "--dc", &["100 block lengths"]);
    assert!(r.stderr.contains(&format!("{hi:.3e}")), "ceiling {hi:.3e} m: {}", r.stderr);
    refused(&["slide", "--law", "static-kinetic", "--cycles", "1000000000"], "--cycles", &["--max-events"]);
    refused(&["slide", "--law", "static-kinetic", "--cycles", "1e9"], "--cycles", &[]);
    refused(&["precursors", "--fe", "--cycles", "1000000000"], "--cycles", &[]);
    refused(&["precursors", "--fe", "--dc", "1e-300"], "--dc", &[]);
}

#[test]
fn count_and_size_flags_are_bounded_before_allocation() {
    refused(&["slide", "--fields", "18446744073709551615"], "--fields", &["--max-events"]);
    refused(&["slide", "--max-events", "18446744073709551615"], "--max-events", &["GiB"]);
    refused(&["precursors", "--events", "18446744073709551615"], "--events", &["100000"]);
    refused(&["sweep", "--length", "0.1:1:1000000000"], "--length", &["at most 100000"]);
    // Two axes whose product is above the cap, each below it.
    refused(
        &["sweep", "--length", "0.1:1:1000", "--thickness", "0.001:0.002:1000"],
        "sweep",
        &["100000 points"],
    );
}

#[test]
fn a_relaxation_capped_at_one_event_finishes() {
    // Ran past a minute before: with every run refused the D_c figure looped on an empty range.
    let dir = out("dc_cap");
    let r = run(
        &["precursors", "--fe", "--dc", "1e-6", "--max-events", "1", "--out", dir.to_str().unwrap()],
        LIMIT,
    );
    assert_eq!(r.code, 2, "{}", r.stderr);
    assert!(r.stderr.contains("more than 1 events") && r.stderr.contains("--max-events"), "{}", r.stderr);
    assert!(!dir.exists());
}

#[test]
fn the_memory_guard_reads_the_process_limit() {
    // Under ulimit -v 8000000 (KiB) the condensation of a 1 m thick block (8e5 unknowns, its
    // 805 right-hand sides held twice: 10.7 GiB) aborted in the allocator.
    let r = under_limit(&["slide", "--thickness", "1"], 8_000_000);
    // 7.6 GiB less the three threads' reserves of 64 MiB (scene::limits::THREAD_RESERVE_BYTES).
    for s in ["--thickness", "RLIMIT_AS", "7.4 GiB"] {
        assert!(r.stderr.contains(s), "{s}: {}", r.stderr);
    }
}

/// A limit below 1 GiB is printed in MiB: it read "(0.0 GiB)". The paper's slide under
/// `ulimit -v 150000`: its dense condensed system, 5 x 805^2 doubles = 24.7 MiB, above half of
/// what is left of 146.5 MiB once the threads' reserves (64 MiB each) are taken.
#[test]
fn the_memory_guard_prints_a_small_limit_in_mib() {
    let r = under_limit(&["slide"], 150_000);
    assert!(r.stderr.contains("--h") && r.stderr.contains("RLIMIT_AS"), "{}", r.stderr);
    assert!(r.stderr.contains("needs about 24.7 MiB") && !r.stderr.contains("GiB"), "{}", r.stderr);
    let tail = r.stderr.split(" reserves) (").nth(1).expect("the limit in parentheses");
    let (num, unit) = tail.split_once(' ').unwrap();
    let mib: f64 = num.parse().unwrap();
    assert!(unit.starts_with("MiB)") && mib > 0.0 && mib < 0.5 * 146.5, "{}", r.stderr);
}

/// `args` under `ulimit -v KIB`: refused (2), nothing written.
fn under_limit(args: &[&str], kib: u64) -> Ran {
    use std::os::unix::process::CommandExt;
    let dir = out(&format!("limit_{kib}"));
    let d = dir.to_str().unwrap().to_string();
    let a = [args, &["--out", &d]].concat();
    let r = run_with(&a, LIMIT, |c| {
        // SAFETY: setrlimit only, between fork and exec.
        unsafe {
            c.pre_exec(move || {
                let lim = libc::rlimit { rlim_cur: kib * 1024, rlim_max: kib * 1024 };
                if libc::setrlimit(libc::RLIMIT_AS, &lim) != 0 {
                    return Err(std::io::Error::last_os_error());
                }
                Ok(())
            });
        }
    });
    assert_eq!(r.code, 2, "{}", r.stderr);
    assert!(!dir.exists(), "the refusal left {}", dir.display());
    r
}

fn data(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data").join(name).to_str().unwrap().to_string()
}

#[test]
fn inconsistent_meshes_are_refused_by_every_command() {
    let geo = ["--length", "0.02", "--thickness", "0.002"];
    // The control: the consistent block is accepted.
    let dir = out("good");
    let mut a = vec!["check", "--mesh"];
    let good = data("good.msh");
    a.push(&good);
    a.extend(geo);
    a.extend(["--out", dir.to_str().unwrap()]);
    let r = run(&a, LIMIT);
    assert_eq!(r.code, 0, "{}", r.stderr);
    for (file, says) in [
        ("crack.msh", vec!["block 'block' is 2 separate pieces", "element 51"]),
        ("crack_partial.msh", vec!["two nodes at the same point", "(0.000000e0, 0.000000e0) m", "node 64"]),
        (
            "diagonal_interface.msh",
            vec![
                "group 'interface'",
                "(-1.000000e-2, 0.000000e0) m",
                "(1.000000e-2, 0.000000e0) m",
                "not the side of any block element",
            ],
        ),
    ] {
        let path = data(file);
        for cmd in [&["check"][..], &["slide"], &["precursors", "--fe"]] {
            let mut a = cmd.to_vec();
            a.extend(["--mesh", &path]);
            a.extend(geo);
            let r = refused(&a, file, &says);
            assert!(r.stderr.starts_with("error: mesh:"), "{}", r.stderr);
        }
    }
}

#[test]
fn edges_prints_no_open_length_below_its_mesh() {
    let dir = out("edges");
    let r = run(
        &[
            "edges",
            "--mu",
            "0.3",
            "--refine",
            "4",
            "--t-over-l",
            "0.02",
            "--h-over-l",
            "0.1",
            "--out",
            dir.to_str().unwrap(),
        ],
        LIMIT,
    );
    assert_eq!(r.code, 0, "{}", r.stderr);
    let csv = std::fs::read_to_string(dir.join("opening.csv")).unwrap();
    let head: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let col = |name: &str| head.iter().position(|h| *h == name).unwrap();
    let row: Vec<&str> = csv.lines().nth(1).unwrap().split(',').collect();
    let end_h: f64 = row[col("end_element_over_t")].parse().unwrap();
    // Graded from h = t/8 at the ends (default --open-refine 8, --end-grading 1.05).
    assert!((end_h - 0.125).abs() < 0.01, "{end_h}");
    let line = r.stdout.lines().find(|l| l.trim_start().starts_with("0.02")).unwrap();
    if row[col("open_nodes")] == "1" {
        assert!(line.contains("below h"), "{line}");
        // The midpoint rule's h/2 is not printed as a result.
        assert!(!line.contains(&format!("{:.3}", end_h / 2.0)), "{line}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
