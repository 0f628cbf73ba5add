//! Issue 45: every numeric input of `slide --dynamics`, `rupture` and the thin-layer and
//! height series refused before any work, naming the flag the user typed and what to change;
//! `--write-scene` reproducing a dynamic run. Each refusal is instant.

use std::process::{Command, Output};

fn tribofe(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_tribofe")).args(args).output().unwrap()
}

/// The flags (`--word`) a message names.
fn flags_named(msg: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = msg;
    while let Some(at) = rest.find("--") {
        let tail = &rest[at + 2..];
        let len = tail.find(|c: char| !(c.is_ascii_alphanumeric() || c == '-')).unwrap_or(tail.len());
        if len > 0 && tail.starts_with(|c: char| c.is_ascii_lowercase()) {
            out.push(format!("--{}", &tail[..len]));
        }
        rest = &tail[len..];
    }
    out
}

/// Runs `args` (the subcommand's words first, `sub` of them) into a fresh --out: status 2,
/// the error names `flag` and each of `words`, every flag it names is one of the subcommand's
/// (its --help), and nothing is written.
fn refused(sub: usize, args: &[&str], flag: &str, words: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let mut a = args.to_vec();
    a.extend(["--out", out.to_str().unwrap()]);
    let r = tribofe(&a);
    let err = String::from_utf8_lossy(&r.stderr);
    let last = err.lines().last().unwrap_or("");
    assert!(r.status.code() == Some(2), "{a:?}: status {:?}: {err}", r.status.code());
    assert!(last.starts_with("error: invalid") && last.contains(flag), "{a:?}: names not {flag}: {last}");
    for w in words {
        assert!(last.contains(w), "{a:?}: no '{w}': {last}");
    }
    assert!(!out.exists(), "{a:?}: wrote its --out");
    let mut h = args[..sub].to_vec();
    h.push("--help");
    let help = String::from_utf8_lossy(&tribofe(&h).stdout).into_owned();
    for f in flags_named(last) {
        assert!(
            help.contains(&format!("{f} ")) || help.contains(&format!("{f}\n")),
            "{a:?}: names {f}, not a flag of {h:?}: {last}"
        );
    }
}

/// The drive's end and the cycle count go through the quasi-static checks: X_max <= 0 and
/// --cycles 0 are refused with --dynamics as without.
#[test]
fn dynamic_slide_refuses_the_quasi_static_ends() {
    for d in [&["slide", "--dynamics"][..], &["slide"]] {
        for (extra, flag) in [
            (&["--law", "coulomb", "--x-max", "-1"][..], "--x-max"),
            (&["--law", "coulomb", "--x-max", "0"], "--x-max"),
            (&["--cycles", "0"], "--cycles"),
            (&["--law", "slip-weakening", "--dc", "1e-6", "--cycles", "0"], "--cycles"),
            (&["--law", "slip-weakening", "--dc", "1e-6", "--n-force", "0"], "--n-force"),
            (&["--n-force", "0"], "--n-force"),
        ] {
            refused(1, &[d, extra].concat(), flag, &[]);
        }
    }
    // The default D_c and h come from N: N = 0 is refused as N, not as the D_c it gives.
    refused(1, &["slide", "--dynamics", "--law", "slip-weakening", "--n-force", "0"], "--n-force", &[]);
}

/// A drive faster than 1 % of the shear-wave speed, damping outside the range its event's step
/// cap allows (the one rule of --damping, in both drive modes, printing the range), a step
/// below 1 % of the stable one, a plate heavier than 1e100.
#[test]
fn dynamic_slide_refuses_numeric_extremes() {
    let dynamic = ["slide", "--dynamics"];
    let cases: &[(&[&str], &str, &[&str])] = &[
        (&["--drive-velocity", "10", "--x-max", "1e-6"], "--drive-velocity", &["c_s", "V <="]),
        (&["--drive-velocity", "10"], "--drive-velocity", &["c_s"]),
        (&["--damping", "1"], "--damping", &["give --damping between"]),
        (&["--damping", "1e308"], "--damping", &["give --damping between"]),
        (&["--damping", "1e-308"], "--damping", &["give --damping between"]),
        (&["--damping", "0"], "--damping", &["eta > 0"]),
        (&["--damping", "nan"], "--damping", &["eta > 0"]),
        // Heavy damping shrinks dt below any V's step cap: named as --damping, not as an
        // impossible --drive-velocity.
        (
            &["--drive-velocity", "4e-6", "--x-max", "1e-6", "--damping", "1e308"],
            "--damping",
            &["give --damping between"],
        ),
        (
            &["--drive-velocity", "4e-6", "--x-max", "1e-6", "--damping", "1e-308"],
            "--damping",
            &["give --damping between"],
        ),
        (&["--courant", "1e-308"], "--courant", &["[0.01, 1]"]),
        (&["--plate-mass", "1e308"], "--plate-mass", &["1e100"]),
        (&["--plate-inertia", "-1"], "--plate-inertia", &[]),
        (&["--density", "-inf"], "--density", &[]),
        (&["--weakening-steps", "1e308"], "--weakening-steps", &[]),
    ];
    for (extra, flag, words) in cases {
        refused(1, &[&dynamic[..], extra].concat(), flag, words);
    }
}

/// `-inf`, `-nan`, `-Infinity` after a flag are values (clap took them for flags), refused by
/// our checks with the flag named.
#[test]
fn negative_looking_values_reach_the_checks() {
    refused(1, &["slide", "--mu", "-inf"], "--mu", &[]);
    refused(1, &["slide", "--mu", "-nan"], "--mu", &[]);
    refused(1, &["slide", "--n-force", "-Infinity"], "--n-force", &[]);
    refused(1, &["rupture", "--damping", "-inf"], "--damping", &[]);
    refused(
        1,
        &["slide", "--dynamics", "--drive-velocity", "-inf", "--x-max", "1e-6"],
        "--drive-velocity",
        &[],
    );
}

/// `rupture`: damping whose stable step overflowed (1e200 ran undamped) or is below dt names
/// --damping and its largest accepted value; a too-large --courant a possible bound; the patch
/// must lie inside the interface and the speed window reach into the block; D_c whose zone exceeds the half block; moduli out of
/// range; a run shorter than one step.
#[test]
fn rupture_refuses_what_cannot_run() {
    let cases: &[(&[&str], &str, &[&str])] = &[
        (&["--damping", "1e200"], "--damping", &["--damping <= 1.69"]),
        (&["--damping", "1e-3"], "--damping", &["--damping <= 1.69", "--courant <= 0.14"]),
        (&["--courant", "2"], "--courant", &["--courant <= 0.77"]),
        (&["--courant", "1e-308"], "--courant", &["0.01"]),
        (&["--length", "0.02"], "--length", &["patch", "--length > 0.02"]),
        (&["--length", "0.05"], "--length", &["front speed", "--length > 0.06"]),
        (&["--dc", "1e308"], "--dc", &["Lambda_0"]),
        (&["--young", "1e308"], "--young", &[]),
        (&["--poisson", "-inf"], "--poisson", &[]),
        (&["--density", "1e308"], "--density", &[]),
        (&["--density", "1e90"], "--t-end", &["one step"]),
    ];
    for (extra, flag, words) in cases {
        refused(1, &[&["rupture"][..], extra].concat(), flag, words);
    }
    // No "<= 0.000": the advice is a value one can give.
    let r = tribofe(&["rupture", "--damping", "1e-3", "--out", "/nonexistent/x"]);
    assert!(!String::from_utf8_lossy(&r.stderr).contains("0.000 "));
}

/// The thin-layer series is the t/L -> 0 limit: t/L above 0.1 is refused with the reason; the
/// series name their own flags (not the earlier --thin-layer, --heights).
#[test]
fn series_refuse_with_their_own_flags() {
    refused(2, &["precursors", "thin-layer", "--t-over-l", "0.5"], "--t-over-l", &["0.1", "thin layer"]);
    refused(2, &["precursors", "thin-layer", "--t-over-l", "0.01,-inf"], "--t-over-l", &[]);
    refused(2, &["precursors", "thin-layer", "--t-over-l", "0.01", "--h", "0.001"], "--h", &["thin-layer"]);
    refused(2, &["precursors", "heights", "--h-over-l", "0.1,0.3"], "--h-over-l", &[]);
    refused(2, &["precursors", "heights", "--h-over-l", "0.1", "--tol", "0.1"], "--tol", &[]);
}

/// Control bytes from an input (a scene string, a file name) are escaped in every error's
/// text, for the terminal and the Python layer alike.
#[test]
fn error_text_escapes_control_bytes() {
    let e =
        tribofe::Error::input("mesh.element (\u{1b}[31m)", "'\u{1b}]0;x\u{7}': not an element\nnext line");
    let s = e.to_string();
    assert!(!s.chars().any(|c| c.is_control() && c != '\n'), "{s:?}");
    assert!(s.contains("\\x1b[31m") && s.contains("\\x07") && s.contains("\nnext line"), "{s:?}");
    let e = tribofe::Error::read("/tmp/a\u{1b}b", std::io::Error::from(std::io::ErrorKind::NotFound));
    assert!(e.to_string().contains("a\\x1bb"), "{e}");
}

/// `--write-scene` writes the scene the run used: the --density given and the h that
/// --dynamics chose without --h.
#[test]
fn write_scene_reproduces_a_dynamic_run() {
    let dir = tempfile::tempdir().unwrap();
    let (out, scene) = (dir.path().join("out"), dir.path().join("s.toml"));
    let args = [
        "slide",
        "--dynamics",
        "--law",
        "slip-weakening",
        "--length",
        "0.05",
        "--x-max",
        "1e-7",
        "--density",
        "1200",
        "--write-scene",
        scene.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ];
    let r = tribofe(&args);
    let err = String::from_utf8_lossy(&r.stderr);
    assert!(r.status.success(), "{err}");
    // "--h not given: h = 5.0000e-4 m (t/4), ..."
    let h: f64 = err
        .lines()
        .find_map(|l| l.strip_prefix("--h not given: h = "))
        .and_then(|l| l.split_whitespace().next())
        .and_then(|v| v.parse().ok())
        .unwrap_or_else(|| panic!("no chosen h: {err}"));
    let t: toml::Value = toml::from_str(&std::fs::read_to_string(&scene).unwrap()).unwrap();
    assert_eq!(t["block"]["density"].as_float(), Some(1200.0), "{t}");
    let written = t["mesh"]["h"].as_float().unwrap();
    assert!((written / h - 1.0).abs() < 1e-4 && written < 1e-3, "h {written} against the run's {h}");
}
