//! Running the built `tribofe` as a user does, bounded: a run that outlives its allowance is
//! killed and reported as a hang (exit 124, as `timeout` does) instead of stalling the suite.
#![allow(dead_code)]

use std::io::Read;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Exit status (124: killed after `limit`), stdout and stderr.
pub struct Ran {
    pub code: i32,
    pub stdout: String,
    pub stderr: String,
}

/// Runs `tribofe args` for at most `limit`, with `setup` applied to the command first.
pub fn run_with(args: &[&str], limit: Duration, setup: impl FnOnce(&mut Command)) -> Ran {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_tribofe"));
    cmd.args(args).stdout(Stdio::piped()).stderr(Stdio::piped());
    setup(&mut cmd);
    let mut child = cmd.spawn().unwrap();
    let (mut out, mut err) = (child.stdout.take().unwrap(), child.stderr.take().unwrap());
    let reader = std::thread::spawn(move || {
        let mut s = String::new();
        out.read_to_string(&mut s).ok();
        s
    });
    let ereader = std::thread::spawn(move || {
        let mut s = String::new();
        err.read_to_string(&mut s).ok();
        s
    });
    let start = Instant::now();
    let code = loop {
        if let Some(st) = child.try_wait().unwrap() {
            break st.code().unwrap_or(-1);
        }
        if start.elapsed() > limit {
            child.kill().ok();
            child.wait().ok();
            break 124;
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    Ran { code, stdout: reader.join().unwrap(), stderr: ereader.join().unwrap() }
}

/// [`run_with`] with nothing to set up.
pub fn run(args: &[&str], limit: Duration) -> Ran {
    run_with(args, limit, |_| {})
}
