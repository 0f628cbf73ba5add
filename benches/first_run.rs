//! The first dynamic run a new user makes, whole process (`cargo bench --bench first_run`):
//! `tribofe slide --dynamics --law slip-weakening` with its defaults, the paper's scene's
//! first cycle to the front crossing (issue 43's target: 60 s on the project's 2-core
//! machine). Wall and CPU time (user + sys of the child) of each of `REPEAT` runs.

use std::process::Command;
use std::time::Instant;

const REPEAT: usize = 2;
const TARGET_S: f64 = 60.0;

fn children_cpu() -> f64 {
    let mut u: libc::rusage = unsafe { std::mem::zeroed() };
    // SAFETY: getrusage writes into the struct we own.
    unsafe { libc::getrusage(libc::RUSAGE_CHILDREN, &mut u) };
    let tv = |t: libc::timeval| t.tv_sec as f64 + t.tv_usec as f64 * 1e-6;
    tv(u.ru_utime) + tv(u.ru_stime)
}

fn main() {
    let tmp = tempfile::tempdir().expect("a temporary folder");
    println!("| run | wall s | CPU s | target s |");
    println!("|---|---:|---:|---:|");
    for k in 0..REPEAT {
        let (t, c0) = (Instant::now(), children_cpu());
        let st = Command::new(env!("CARGO_BIN_EXE_tribofe"))
            .args(["slide", "--dynamics", "--law", "slip-weakening", "--out"])
            .arg(tmp.path().join(format!("run{k}")))
            .output()
            .expect("tribofe runs");
        assert!(st.status.success(), "{}", String::from_utf8_lossy(&st.stderr));
        println!(
            "| slide --dynamics --law slip-weakening (defaults), run {} | {:.1} | {:.1} | {TARGET_S} |",
            k + 1,
            t.elapsed().as_secs_f64(),
            children_cpu() - c0
        );
    }
}
