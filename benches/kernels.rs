//! Kernel benchmarks (`cargo bench`): element matrices, assembly, symbolic and numeric
//! Cholesky, and the solve (one factorisation and two domains), on a strip of the paper's
//! scene small enough to repeat; and the two halves' numeric factorisation of the 1e6-DOF strip,
//! ours against faer's left-looking one. The whole pipeline at 1e6 DOFs is `tribofe bench`.

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use tribofe::fem::assembly::Assembler;
use tribofe::fem::element::stiffness::{stiffness, MAX_DOFS};
use tribofe::fem::element::ElementKind;
use tribofe::fem::material::Material;
use tribofe::fem::ordering::bisection;
use tribofe::fem::problem::LoadCase;
use tribofe::linalg::solve::{Ordering, Solver, SolverOptions};
use tribofe::linalg::substructure::TwoDomain;
use tribofe::scene::Scene;

fn kernels(c: &mut Criterion) {
    let d = Material::plane_strain(2e3, 0.4).unwrap().d_matrix();
    let mut k = [0.0; MAX_DOFS * MAX_DOFS];
    for kind in [ElementKind::Qua4, ElementKind::Qua8, ElementKind::Tri6] {
        let x: Vec<[f64; 2]> = kind
            .reference_nodes()
            .iter()
            .map(|&[a, b]| [1e-3 * (1.0 + a + 0.1 * b), 1e-3 * (0.5 + b)])
            .collect();
        c.bench_function(&format!("element stiffness {}", kind.name()), |b| {
            b.iter(|| stiffness(kind, black_box(&x), &d, &mut k))
        });
    }

    // The paper's scene at h = t/8: 3200 x 8 QUA4, ~2.9e4 unknowns, rigid plate.
    let mut scene = Scene::default();
    scene.mesh.h = scene.block.thickness / 8.0;
    let sm = scene.build().unwrap();
    let model = sm.model();
    let red = sm.constraints.reduce().unwrap();
    let nf = sm.constraints.n_fixed();
    let cases = [LoadCase { prescribed: vec![1e-6; nf], forces: vec![] }];
    let g: Vec<Vec<f64>> = cases.iter().map(|c| c.prescribed.clone()).collect();
    let f = vec![vec![]];
    let mut group = c.benchmark_group("strip t/8");
    group.sample_size(10);
    group.bench_function("pattern", |b| b.iter(|| Assembler::new(&sm.mesh, &red).unwrap()));
    let asm = Assembler::new(&sm.mesh, &red).unwrap();
    group.bench_function("assembly", |b| b.iter(|| asm.assemble(&model, &red, &f, &g).unwrap()));
    let (values, rhs) = asm.assemble(&model, &red, &f, &g).unwrap();
    group.bench_function("ordering + symbolic (AMD)", |b| {
        b.iter(|| Solver::analyse(&asm.pattern, SolverOptions::default()).unwrap())
    });
    let solver = Solver::analyse(&asm.pattern, SolverOptions::default()).unwrap();
    group.bench_function("numeric factorisation", |b| {
        b.iter(|| solver.factorize(&asm.pattern, &values).ok().unwrap())
    });
    let factor = solver.factorize(&asm.pattern, &values).ok().unwrap();
    let rhs3: Vec<f64> = rhs.iter().chain(&rhs).chain(&rhs).copied().collect();
    group.bench_function("solve, 3 right-hand sides", |b| {
        b.iter(|| {
            let mut x = rhs3.clone();
            factor.solve_in_place(&mut x, 3);
            x
        })
    });
    // The same system as two domains (both halves at once on the rayon pool).
    let two = SolverOptions {
        ordering: Ordering::TwoDomain(bisection(&sm.mesh, &red).unwrap()),
        ..Default::default()
    };
    group.bench_function("two domains: symbolic", |b| {
        b.iter(|| Solver::analyse(&asm.pattern, two.clone()).unwrap())
    });
    let solver = Solver::analyse(&asm.pattern, two).unwrap();
    group.bench_function("two domains: numeric factorisation", |b| {
        b.iter(|| solver.factorize(&asm.pattern, &values).ok().unwrap())
    });
    let factor = solver.factorize(&asm.pattern, &values).ok().unwrap();
    group.bench_function("two domains: solve, 3 right-hand sides", |b| {
        b.iter(|| {
            let mut x = rhs3.clone();
            factor.solve_in_place(&mut x, 3);
            x
        })
    });
    group.finish();
}

/// The numeric factorisation of both halves of strip t/50 (980k unknowns), one per core, into
/// the same memory every iteration: our multifrontal code against faer's left-looking one on
/// the same symbolic structure.
fn halves(c: &mut Criterion) {
    let mut scene = Scene::default();
    scene.mesh.h = scene.block.thickness / 50.0;
    let sm = scene.build().unwrap();
    let red = sm.constraints.reduce().unwrap();
    let asm = Assembler::new(&sm.mesh, &red).unwrap();
    let g = vec![vec![1e-6; sm.constraints.n_fixed()]];
    let (values, _) = asm.assemble(&sm.model(), &red, &[vec![]], &g).unwrap();
    let two = TwoDomain::analyse(&asm.pattern, &bisection(&sm.mesh, &red).unwrap()).unwrap();
    let mut l = Default::default();
    let mut group = c.benchmark_group("strip t/50, numeric factorisation of the two halves");
    group.sample_size(10);
    group.bench_function("multifrontal (ours)", |b| {
        b.iter(|| two.factor_halves(&values, false, &mut l).unwrap())
    });
    group.bench_function("left-looking (faer)", |b| {
        b.iter(|| two.factor_halves(&values, true, &mut l).unwrap())
    });
    group.finish();
    // Forward and backward solves of both halves for 3 right-hand sides, on that factor.
    two.factor_halves(&values, false, &mut l).unwrap();
    let mut y: [Vec<f64>; 2] = Default::default();
    let mut group = c.benchmark_group("strip t/50, solves of the two halves, 3 right-hand sides");
    group.sample_size(10);
    let mut run = |faer: bool| {
        y.iter_mut().for_each(Vec::clear); // fresh right-hand sides: repeated solves would overflow
        two.solve_halves(&l, &mut y, 3, faer)
    };
    group.bench_function("ours", |b| b.iter(|| run(false)));
    group.bench_function("faer", |b| b.iter(|| run(true)));
    group.finish();
}

criterion_group!(benches, kernels, halves);
criterion_main!(benches);
