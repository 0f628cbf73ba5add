//! Issue 48's refinement cost (`cargo bench --bench dynamic_refine`): the paper's scene's
//! first cycle in dynamics, `tribofe slide --dynamics --law slip-weakening` with the built-in
//! defaults (D_c = 2.3107e-7 m, to the front crossing, `--states none`), at h = 0.5 and
//! 0.25 mm, and 0.125 mm with `TRIBOFE_BENCH_FINE=1` (about an hour in 2026-11).
//!
//! Whole process, one run per mesh: wall and CPU time (user + sys of the child, the less
//! load-sensitive figure on a shared machine), and the run's own phase split from its
//! run.toml (setup: mesh, operator and condensation; static loading; dynamic events; writing
//! and the rest is the wall time left). The last columns are each phase's ratio to the
//! previous mesh's: the cost of a halving of h, phase by phase.

use std::process::Command;
use std::time::Instant;

mod common;
use common::children_cpu;

/// A number of run.toml's `[results]`.
fn result(toml: &toml::Table, key: &str) -> f64 {
    let v = &toml["results"][key];
    v.as_float().or_else(|| v.as_integer().map(|i| i as f64)).unwrap_or_else(|| panic!("run.toml: {key}"))
}

fn main() {
    let mut meshes = vec![0.0005, 0.00025];
    if std::env::var_os("TRIBOFE_BENCH_FINE").is_some() {
        meshes.push(0.000125);
    }
    let tmp = tempfile::tempdir().expect("a temporary folder");
    println!(
        "| h mm | wall s | CPU s | setup s | static s | dynamic s | writing and rest s | static LU | dynamic steps | \
         instabilities | static x | dynamic x |"
    );
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    let mut previous: Option<(f64, f64)> = None;
    for h in meshes {
        let out = tmp.path().join(format!("h{h}"));
        let (c0, t) = (children_cpu(), Instant::now());
        let st = Command::new(env!("CARGO_BIN_EXE_tribofe"))
            .args(["slide", "--dynamics", "--law", "slip-weakening", "--h", &h.to_string(), "--out"])
            .arg(&out)
            .output()
            .expect("tribofe runs");
        let (wall, cpu) = (t.elapsed().as_secs_f64(), children_cpu() - c0);
        assert!(st.status.success(), "h = {h}: {}", String::from_utf8_lossy(&st.stderr));
        let toml: toml::Table = std::fs::read_to_string(out.join("run.toml"))
            .expect("run.toml")
            .parse()
            .expect("run.toml parses");
        let [setup, stat, dynamic] =
            ["setup_wall_s", "static_wall_s", "dynamic_wall_s"].map(|k| result(&toml, k));
        let events = std::fs::read_to_string(out.join("dyn_events.csv")).expect("dyn_events.csv");
        let column = events.lines().next().and_then(|h| h.split(',').position(|c| c == "instability"));
        let instabilities = column.map_or(0, |c| {
            events.lines().skip(1).filter(|l| l.split(',').nth(c).is_some_and(|v| v == "1")).count()
        });
        let ratio =
            |now: f64, before: Option<f64>| before.map_or("-".to_string(), |b| format!("{:.1}", now / b));
        println!(
            "| {} | {wall:.1} | {cpu:.1} | {setup:.2} | {stat:.1} | {dynamic:.1} | {:.1} | {} | {} | {instabilities} | {} | {} |",
            h * 1e3,
            wall - setup - stat - dynamic,
            result(&toml, "static_factorisations"),
            result(&toml, "dynamic_steps"),
            ratio(stat, previous.map(|p| p.0)),
            ratio(dynamic, previous.map(|p| p.1)),
        );
        previous = Some((stat, dynamic));
    }
}
