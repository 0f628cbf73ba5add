//! The frictional interface (issue 17): condensation and whole loading histories on the
//! paper's mesh (401 interface nodes), per-event cost at ~1000 nodes, and slip weakening.
//! `cargo bench --bench friction`; the figures quoted in validation/friction/README.md.

use criterion::{criterion_group, criterion_main, Criterion};
use tribofe::interface::condense::condense;
use tribofe::interface::events::Operator;
use tribofe::law::{Law, Rule};
use tribofe::linalg::solve::SolverOptions;
use tribofe::scene::Scene;
use tribofe::studies::slide::{coefficients_from_rg, run, run_condensed, SlideOptions};

fn friction(c: &mut Criterion) {
    let mut g = c.benchmark_group("friction");
    g.sample_size(10);
    let paper = Scene::default();
    g.bench_function("condensation, paper mesh (401 nodes)", |b| {
        b.iter(|| condense(&paper, &SolverOptions::default()).unwrap())
    });
    let cond = condense(&paper, &SolverOptions::default()).unwrap();
    let (ms, md) = coefficients_from_rg(&paper, 0.9, 0.35).unwrap();
    let (p, cd) = (&paper, &cond);
    let history = |law: Law, cycles: usize| {
        let o = SlideOptions { law, cycles, ..Default::default() };
        move || run_condensed(p, cd.clone(), 0.0, &o, tribofe::Progress::none()).unwrap()
    };
    let run = history(Law::coulomb(0.5).unwrap(), 1);
    g.bench_function("coulomb to 5 % past sliding, paper mesh (404 events)", |b| b.iter(&run));
    let run = history(Law::static_kinetic(ms, md, Rule::Paper).unwrap(), 10);
    g.bench_function("static-kinetic paper rule, 10 cycles, paper mesh", |b| b.iter(&run));
    // ~1000 interface nodes: the per-event cost of coulomb (one node per event).
    let mut fine = Scene::default();
    fine.mesh.h = 0.0004;
    fine.mesh.n_thick = Some(2);
    g.bench_function("condensation, 1001 interface nodes", |b| {
        b.iter(|| condense(&fine, &SolverOptions::default()).unwrap())
    });
    let cf = condense(&fine, &SolverOptions::default()).unwrap();
    let o = SlideOptions { law: Law::coulomb(0.5).unwrap(), ..Default::default() };
    let events =
        run_condensed(&fine, cf.clone(), 0.0, &o, tribofe::Progress::none()).unwrap().run.events.len();
    g.bench_function(format!("coulomb, 1001 nodes ({events} events)"), |b| {
        b.iter(|| run_condensed(&fine, cf.clone(), 0.0, &o, tribofe::Progress::none()).unwrap())
    });
    // Slip weakening, D_c = 0.3 um on L = 10 cm, t = 4 mm, h = 2 mm (validation sw_nt4).
    let mut sw = Scene::default();
    sw.block.length = 0.1;
    sw.block.thickness = 0.004;
    sw.mesh.h = 0.002;
    sw.mesh.n_thick = Some(4);
    let (ms, md) = coefficients_from_rg(&sw, 0.9, 0.35).unwrap();
    let cs = condense(&sw, &SolverOptions::default()).unwrap();
    let o = SlideOptions { law: Law::slip_weakening(ms, md, 3e-7).unwrap(), cycles: 1, ..Default::default() };
    g.bench_function("slip-weakening to the first whole slip, 51 nodes", |b| {
        b.iter(|| run_condensed(&sw, cs.clone(), 0.0, &o, tribofe::Progress::none()).unwrap())
    });
    g.finish();
}

/// Issue 32's speed targets through `studies::slide::run` (operator built or S condensed, then
/// the events; no output files): coulomb at h = 0.5 mm (801 nodes) on both operators, and
/// the thin block t/L = 1/1600 (3,201 nodes, rule paper, first cycle) on the banded one (the
/// dense one takes ~50 s a run there; `tribofe slide --operator dense` times it once).
fn operators(c: &mut Criterion) {
    let mut g = c.benchmark_group("operators");
    g.sample_size(10);
    let mut fine = Scene::default();
    fine.mesh.h = 0.0005;
    for op in [Operator::Dense, Operator::Banded] {
        let o = SlideOptions {
            law: Law::coulomb(0.5).unwrap(),
            n_force: 40.0,
            operator: op,
            keep_states: false,
            ..Default::default()
        };
        g.bench_function(format!("coulomb h = 0.5 mm (801 nodes), {}", op.name()), |b| {
            b.iter(|| run(&fine, &o, tribofe::Progress::none()).unwrap())
        });
    }
    let mut thin = Scene::default();
    thin.block.thickness = 0.00025;
    thin.mesh.h = 0.000125;
    thin.mesh.n_thick = Some(2);
    let (ms, md) = coefficients_from_rg(&thin, 0.9, 0.35).unwrap();
    let o = SlideOptions {
        law: Law::static_kinetic(ms, md, Rule::Paper).unwrap(),
        cycles: 1,
        operator: Operator::Banded,
        keep_states: false,
        ..Default::default()
    };
    g.bench_function("thin block t/L = 1/1600 (3201 nodes), paper rule, 1 cycle, banded", |b| {
        b.iter(|| run(&thin, &o, tribofe::Progress::none()).unwrap())
    });
    g.finish();
}

criterion_group!(benches, friction, operators);
criterion_main!(benches);
