//! Every run bounded, and no panic or abort (issue 45): a rupture above its step cap refused
//! at once, special files as inputs refused without blocking, a cancel seen within a beat of
//! wall time, stderr full or closed and a tight address space ending with a documented status.

use crate::common;

use common::process::{run, run_with, Ran};
use std::path::PathBuf;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Far above any of these runs' cost (under 5 s each), far below a hang.
const LIMIT: Duration = Duration::from_secs(60);

fn out(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("tribofe_run_bounds_{}_{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

/// `args` with a fresh --out, refused with status 2 within `within`, naming each of `says`,
/// writing nothing.
fn refused_within(args: &[&str], within: Duration, says: &[&str]) -> Ran {
    let dir = out(&args.join("_").replace(['/', ' '], "_"));
    let d = dir.to_str().unwrap().to_string();
    let mut a = args.to_vec();
    a.extend(["--out", &d]);
    let t0 = Instant::now();
    let r = run(&a, LIMIT);
    let took = t0.elapsed();
    assert_eq!(r.code, 2, "{args:?}: exit {}, stderr {}", r.code, r.stderr);
    assert!(took < within, "{args:?} took {took:?}");
    for s in says {
        assert!(r.stderr.contains(s), "{args:?} must say {s:?}: {}", r.stderr);
    }
    assert!(!dir.exists(), "{args:?}: the refusal left {}", dir.display());
    r
}

#[test]
fn a_rupture_above_its_step_cap_is_refused_at_once() {
    let fast = Duration::from_secs(2);
    // 4.1e15 steps of the default dt = 2.4e-4 s.
    refused_within(
        &["rupture", "--t-end", "1e12"],
        fast,
        &["--t-end", "--max-steps", "4.140e15 explicit steps"],
    );
    // Fast waves make dt tiny: the same cap, naming what sets dt.
    // (D_c scaled with E so that the cohesive zone stays resolved and only the step count fails.)
    refused_within(&["rupture", "--young", "1e30", "--dc", "1e-33"], fast, &["--young", "--max-steps"]);
    refused_within(&["rupture", "--density", "1e-30"], fast, &["--density", "--max-steps"]);
    // (A courant below 0.01 is refused as such first: inputs_dynamic.)
    refused_within(&["rupture", "--courant", "1e-9"], fast, &["--courant"]);
    // The cap is the user's: the default run (414 steps) under a cap of 100 is refused too.
    refused_within(&["rupture", "--max-steps", "100"], fast, &["4.140e2 explicit steps", "--max-steps 100"]);
}

/// A long rupture (4e5 steps, minutes) cancelled from another thread returns within 0.5 s.
#[test]
fn a_cancel_stops_a_long_rupture_within_half_a_second() {
    use tribofe::dynamics::rupture::{run, RuptureSpec};
    let spec = RuptureSpec { t_end: 100.0, ..Default::default() };
    let cancel = tribofe::Cancel::new();
    let host = cancel.clone();
    let worker = std::thread::spawn(move || {
        let r = run(&spec, &cancel, tribofe::Progress::none());
        (r.map(|_| ()), Instant::now())
    });
    std::thread::sleep(Duration::from_millis(300));
    let asked = Instant::now();
    host.cancel();
    let (r, ended) = worker.join().unwrap();
    assert!(matches!(r, Err(tribofe::Error::Interrupted)), "{r:?}");
    let late = ended.duration_since(asked);
    assert!(late < Duration::from_millis(500), "stopped {late:?} after the cancel");
}

#[test]
fn special_files_as_inputs_are_refused_without_blocking() {
    let d = tempfile::tempdir().unwrap();
    let fifo = d.path().join("fifo");
    let c = std::ffi::CString::new(fifo.to_str().unwrap()).unwrap();
    // SAFETY: a valid NUL-terminated path.
    assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
    let f = fifo.to_str().unwrap();
    let now = Duration::from_secs(1);
    refused_within(&["check", "--mesh", f], now, &["--mesh", "is a FIFO; give a regular file"]);
    refused_within(&["slide", "--scene", f], now, &["--scene", "is a FIFO; give a regular file"]);
    refused_within(&["slide", "--scene", "/dev/zero"], now, &["--scene", "is a character device"]);
    refused_within(&["precursors", "fe", "--mesh", "/dev/zero"], now, &["--mesh", "is a character device"]);
    // A scene naming a FIFO as its mesh.
    let scene = d.path().join("scene.toml");
    std::fs::write(&scene, format!("[mesh]\nfile = \"{f}\"\n")).unwrap();
    refused_within(&["check", "--scene", scene.to_str().unwrap()], now, &["--mesh", "is a FIFO"]);
    refused_within(&["sweep", "--merge", f], now, &["--merge"]);
}

/// Standard error that cannot be written (a full device, a closed pipe) loses the text, not
/// the run: the status is the run's own, never 101 (a panic in eprintln!).
#[test]
fn stderr_full_or_closed_is_not_a_panic() {
    for closed in [false, true] {
        let dir = out(&format!("stderr_{closed}"));
        let mut cmd = Command::new(env!("CARGO_BIN_EXE_tribofe"));
        cmd.args(["slide", "--dynamics", "--out", dir.to_str().unwrap()]).stdout(Stdio::null());
        if closed {
            cmd.stderr(Stdio::piped());
        } else {
            cmd.stderr(std::fs::File::create("/dev/full").unwrap());
        }
        let mut child = cmd.spawn().unwrap();
        drop(child.stderr.take()); // the reader goes away: writes fail with EPIPE
        let t0 = Instant::now();
        let code = loop {
            if let Some(st) = child.try_wait().unwrap() {
                break st.code().unwrap_or(-1);
            }
            if t0.elapsed() > LIMIT {
                child.kill().ok();
                break 124;
            }
            std::thread::sleep(Duration::from_millis(20));
        };
        assert_eq!(code, 0, "stderr {}: exit {code}", if closed { "closed" } else { "/dev/full" });
        assert!(dir.join("run.toml").is_file());
        let _ = std::fs::remove_dir_all(&dir);
    }
}

/// Under a tight address space a run ends with 0 or a refusal (2), never an abort in the
/// allocator (134) or a panic spawning a thread (101): the worker threads' fixed reserves
/// (64 MiB each) are sized to the limit and counted by the memory guard.
#[test]
fn a_tight_address_space_is_a_refusal_not_an_abort() {
    use std::os::unix::process::CommandExt;
    for kib in [150_000u64, 250_000] {
        let dir = out(&format!("as_{kib}"));
        let r = run_with(&["precursors", "fe", "--out", dir.to_str().unwrap()], LIMIT, |c| {
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
        assert!(r.code == 0 || r.code == 2, "ulimit -v {kib}: exit {}: {}", r.code, r.stderr);
        assert!(!r.stderr.contains("panicked") && !r.stderr.contains("memory allocation"), "{}", r.stderr);
        if r.code == 2 {
            assert!(r.stderr.contains("RLIMIT_AS") && !dir.exists(), "{}", r.stderr);
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
}

/// A damping whose event cap is above 200 000 steps is refused at once, naming --damping and
/// the range the scene accepts (it ran past 30 s; the default takes 0.5 s). That range is the
/// one rule of --damping: too light and too heavy are refused by it alike.
#[test]
fn slide_dynamics_damping_outside_its_range_is_refused_at_once() {
    let fast = Duration::from_secs(3);
    let mut ranges = Vec::new();
    for eta in ["1e-7", "1e-2", "2e-2"] {
        let r = refused_within(
            &["slide", "--dynamics", "--damping", eta],
            fast,
            &["--damping", "give --damping between"],
        );
        // The range printed holds the default and excludes what was refused.
        let tail = r.stderr.split("between ").nth(1).unwrap();
        let lo: f64 = tail.split_whitespace().next().unwrap().parse().unwrap();
        let hi: f64 = tail.split(" and ").nth(1).unwrap().split_whitespace().next().unwrap().parse().unwrap();
        let eta: f64 = eta.parse().unwrap();
        ranges.push((lo, hi));
        assert!(lo < 3.013e-4 && 3.013e-4 < hi && !(lo..=hi).contains(&eta), "{lo} {hi}: {}", r.stderr);
    }
    // One range whatever the refused value: on the paper's scene about 1.9e-6 to 6.1e-3 s,
    // reaching below the old second rule's floor (0.001 of critical, 3.0e-6 s).
    assert!(ranges.iter().all(|r| *r == ranges[0]), "{ranges:?}");
    let (lo, hi) = ranges[0];
    assert!((1.5e-6..3.0e-6).contains(&lo) && (5e-3..7e-3).contains(&hi), "{lo} {hi}");
}
