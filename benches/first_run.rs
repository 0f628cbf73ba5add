//! Whole-process runs against their targets on the project's 2-core machine
//! (`cargo bench --bench first_run`): the first dynamic run a new user makes,
//! `tribofe slide --dynamics --law slip-weakening` with its defaults (the paper's scene's first
//! cycle to the front crossing; issue 43: 60 s), and the field's benchmark TPV205-2D at
//! h = 100 m (`tribofe rupture --scene validation/dynamics/tpv205_2d/tpv205_2d.toml --h 100`;
//! issue 47: 30 s). Wall and CPU time (user + sys of the child) of each of `REPEAT` runs.

use std::process::Command;
use std::time::Instant;

const REPEAT: usize = 2;

/// (what, arguments, target wall time in s).
const RUNS: [(&str, &[&str], f64); 2] = [
    (
        "slide --dynamics --law slip-weakening (defaults)",
        &["slide", "--dynamics", "--law", "slip-weakening"],
        60.0,
    ),
    (
        "rupture --scene tpv205_2d.toml --h 100",
        &[
            "rupture",
            "--scene",
            concat!(env!("CARGO_MANIFEST_DIR"), "/validation/dynamics/tpv205_2d/tpv205_2d.toml"),
            "--h",
            "100",
        ],
        30.0,
    ),
];

mod common;
use common::children_cpu;

fn main() {
    let tmp = tempfile::tempdir().expect("a temporary folder");
    println!("| run | wall s | CPU s | target s |");
    println!("|---|---:|---:|---:|");
    for (what, args, target) in RUNS {
        for k in 0..REPEAT {
            let (t, c0) = (Instant::now(), children_cpu());
            let st = Command::new(env!("CARGO_BIN_EXE_tribofe"))
                .args(args)
                .arg("--out")
                .arg(tmp.path().join(format!("{}{k}", args[0])))
                .output()
                .expect("tribofe runs");
            assert!(st.status.success(), "{}", String::from_utf8_lossy(&st.stderr));
            println!(
                "| {what}, run {} | {:.1} | {:.1} | {target} |",
                k + 1,
                t.elapsed().as_secs_f64(),
                children_cpu() - c0
            );
        }
    }
}
