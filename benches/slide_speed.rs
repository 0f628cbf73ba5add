//! Issue 32's speed targets, whole process and by phase (`cargo bench --bench slide_speed`):
//! coulomb mu = 0.5 at h = 0.5 mm (801 interface nodes) on the dense and the banded operator,
//! the banded one again without states.csv (`--states none`: the loading curve, the events and
//! the figures only), and the thin block t/L = 1/1600 (3,201 nodes, rule paper, first cycle) on
//! the banded one.
//!
//! In process (best of `REPEAT`): mesh (the block's mesh and constraints alone), setup (mesh
//! and operator: the banded operator's assembly, or the dense condensation), events (the
//! event solver), output (every file of `tribofe slide`, states.csv included), and the CPU
//! time (user + sys, all threads) of the run (setup + events) and of the output. Whole
//! process: the `tribofe slide` command itself, wall time and CPU time (user + sys; on this
//! shared machine the CPU time is the less load-sensitive of the two).

use std::process::Command;
use std::time::Instant;
use tribofe::interface::events::Operator;
use tribofe::law::{Law, Rule};
use tribofe::scene::Scene;
use tribofe::studies::slide::{coefficients_from_rg, run, SlideOptions};

const REPEAT: usize = 3;

mod common;
use common::{children_cpu, cpu};

struct Case {
    name: &'static str,
    scene: Scene,
    options: SlideOptions,
    args: Vec<&'static str>,
    /// Whether states.csv is written.
    states: bool,
}

fn cases() -> Vec<Case> {
    let mut fine = Scene::default();
    fine.mesh.h = 0.0005;
    let mut out = vec![];
    for (op, flag) in [(Operator::Dense, "dense"), (Operator::Banded, "banded")] {
        out.push(Case {
            name: if op == Operator::Dense {
                "coulomb h = 0.5 mm (801 nodes), dense"
            } else {
                "coulomb h = 0.5 mm (801 nodes), banded"
            },
            scene: fine.clone(),
            options: SlideOptions { law: Law::coulomb(0.5).unwrap(), operator: op, ..Default::default() },
            args: vec!["--mu", "0.5", "--h", "0.0005", "--operator", flag],
            states: true,
        });
    }
    out.push(Case {
        name: "coulomb h = 0.5 mm (801 nodes), banded, --states none",
        scene: fine.clone(),
        options: SlideOptions {
            law: Law::coulomb(0.5).unwrap(),
            operator: Operator::Banded,
            ..Default::default()
        },
        args: vec!["--mu", "0.5", "--h", "0.0005", "--operator", "banded", "--states", "none"],
        states: false,
    });
    let mut thin = Scene::default();
    thin.block.thickness = 0.00025;
    thin.mesh.h = 0.000125;
    thin.mesh.n_thick = Some(2);
    let (ms, md) = coefficients_from_rg(&thin, 0.9, 0.35).unwrap();
    out.push(Case {
        name: "thin block t/L = 1/1600 (3201 nodes), rule paper, 1 cycle, banded",
        scene: thin,
        options: SlideOptions {
            law: Law::static_kinetic(ms, md, Rule::Paper).unwrap(),
            cycles: 1,
            operator: Operator::Banded,
            ..Default::default()
        },
        args: vec![
            "--thickness",
            "0.00025",
            "--h",
            "0.000125",
            "--n-thick",
            "2",
            "--law",
            "static-kinetic",
            "--r",
            "0.9",
            "--g",
            "0.35",
            "--rule",
            "paper",
            "--cycles",
            "1",
            "--operator",
            "banded",
        ],
        states: true,
    });
    out
}

fn main() {
    // `cargo bench` passes --bench; a name filter selects cases.
    let filter: Vec<String> = std::env::args().skip(1).filter(|a| !a.starts_with("--")).collect();
    let tmp = tempfile::tempdir().expect("a temporary folder");
    println!(
        "| run | mesh s | setup s | events s | output s | in-process s | run CPU s | output CPU s | whole process wall s | CPU s |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for c in cases() {
        if !filter.is_empty() && !filter.iter().any(|f| c.name.contains(f.as_str())) {
            continue;
        }
        let mut best = [f64::INFINITY; 7];
        for k in 0..REPEAT {
            let t = Instant::now();
            tribofe::interface::condense::boundary_model(&c.scene).expect("mesh");
            let mesh = t.elapsed().as_secs_f64();
            let (t, c0) = (Instant::now(), cpu(libc::RUSAGE_SELF));
            let res = run(&c.scene, &c.options, tribofe::Progress::none()).expect("run");
            let (total_run, run_cpu) = (t.elapsed().as_secs_f64(), cpu(libc::RUSAGE_SELF) - c0);
            let dir = tmp.path().join(format!("inproc{k}"));
            std::fs::create_dir_all(&dir).expect("folder");
            let (t, c0) = (Instant::now(), cpu(libc::RUSAGE_SELF));
            tribofe::report::slide::write(&res, &dir, "# bench\n", c.states).expect("output");
            let (output, output_cpu) = (t.elapsed().as_secs_f64(), cpu(libc::RUSAGE_SELF) - c0);
            let row = [mesh, res.condense_s, res.events_s, output, total_run + output, run_cpu, output_cpu];
            for (b, v) in best.iter_mut().zip(row) {
                *b = b.min(v);
            }
        }
        let (mut wall, mut cpu_best) = (f64::INFINITY, f64::INFINITY);
        for k in 0..REPEAT {
            let out = tmp.path().join(format!("whole{k}"));
            let c0 = children_cpu();
            let t = Instant::now();
            let st = Command::new(env!("CARGO_BIN_EXE_tribofe"))
                .arg("slide")
                .args(&c.args)
                .arg("--out")
                .arg(&out)
                .output()
                .expect("tribofe runs");
            assert!(st.status.success(), "{}: {}", c.name, String::from_utf8_lossy(&st.stderr));
            wall = wall.min(t.elapsed().as_secs_f64());
            cpu_best = cpu_best.min(children_cpu() - c0);
        }
        println!(
            "| {} | {:.3} | {:.3} | {:.3} | {:.3} | {:.3} | {:.3} | {:.3} | {:.3} | {:.3} |",
            c.name, best[0], best[1], best[2], best[3], best[4], best[5], best[6], wall, cpu_best
        );
    }
}
