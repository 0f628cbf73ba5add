//! Results must not depend on the number of threads, nor (beyond round-off) on the ordering.
//!
//! Assembly: elements of one colour write disjoint node entries and colours run in order, so
//! every node entry is summed in the same order whatever the thread count; the rigid plate's
//! extra-DOF entries are summed over fixed chunks merged in order. Hence bitwise equality.
//! The factorisation with 2 faer threads may reorder dense kernel sums: 1e-14 relative.
//! The two-domain solver does the same work on any thread count: bitwise again.

use tribofe::fem::assembly::Assembler;
use tribofe::fem::ordering::{bisection, nested_dissection};
use tribofe::linalg::solve::{Ordering, SolverOptions};
use tribofe::scene::Scene;
use tribofe::studies::check::{self, CheckResult};

fn pool(k: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new().num_threads(k).build().unwrap()
}

/// The paper's strip with h = t / ny (200 ny x ny elements).
fn strip(ny: usize, element: &str) -> Scene {
    let mut s = Scene::default();
    s.mesh.h = s.block.thickness / ny as f64;
    s.mesh.element = element.into();
    s
}

/// max |a - b| / max |a| over all displacements and interface profiles.
fn rel_diff(a: &CheckResult, b: &CheckResult) -> f64 {
    let fields = |r: &CheckResult| -> Vec<f64> {
        let mut v: Vec<f64> = r.displacements.concat();
        r.cases.iter().for_each(|c| v.extend(c.p.iter().chain(&c.tau)));
        v
    };
    let (fa, fb) = (fields(a), fields(b));
    assert_eq!(fa.len(), fb.len());
    let scale = fa.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    fa.iter().zip(&fb).fold(0.0f64, |m, (x, y)| m.max((x - y).abs())) / scale
}

#[test]
fn assembly_is_bitwise_identical_on_1_and_2_threads() {
    let sm = strip(8, "qua4").build().unwrap();
    let model = sm.model();
    let red = sm.constraints.reduce().unwrap();
    let asm = Assembler::new(&sm.mesh, &red).unwrap();
    // Arbitrary prescribed values and loads so that every rhs path is exercised.
    let g: Vec<Vec<f64>> =
        (0..2).map(|c| (0..red.n_fixed()).map(|j| ((j * 7 + c * 3) % 5) as f64 - 2.0).collect()).collect();
    let f: Vec<Vec<f64>> =
        (0..2).map(|c| (0..red.n_full).map(|d| ((d * 3 + c) % 7) as f64).collect()).collect();
    let run = |k: usize| pool(k).install(|| asm.assemble(&model, &red, &f, &g).unwrap());
    let (v1, r1) = run(1);
    for _ in 0..3 {
        let (v2, r2) = run(2);
        assert!(v1.iter().zip(&v2).all(|(a, b)| a.to_bits() == b.to_bits()), "matrix values differ");
        assert!(r1.iter().zip(&r2).all(|(a, b)| a.to_bits() == b.to_bits()), "right-hand sides differ");
    }
}

#[test]
fn check_results_agree_on_1_and_2_threads() {
    let scene = strip(8, "qua4");
    let run = |k: usize| {
        let opts = SolverOptions { threads: k, supernodal: Some(true), ..Default::default() };
        pool(k).install(|| check::run(&scene, &opts).unwrap().0)
    };
    let (a, b) = (run(1), run(2));
    let d = rel_diff(&a, &b);
    assert!(d <= 1e-14, "relative difference {d:.2e}");
}

#[test]
fn nested_dissection_is_a_permutation_and_matches_amd() {
    for element in ["qua4", "qua8", "tri3"] {
        let scene = strip(4, element);
        let sm = scene.build().unwrap();
        let red = sm.constraints.reduce().unwrap();
        let p = nested_dissection(&sm.mesh, &red).expect("structured mesh");
        let mut seen = vec![false; red.n_free()];
        p.iter().for_each(|&k| seen[k] = true);
        assert!(p.len() == red.n_free() && seen.iter().all(|&s| s), "{element}: not a permutation");
        let run = |ordering: Ordering| {
            check::run(&scene, &SolverOptions { ordering, ..Default::default() }).unwrap().0
        };
        let d = rel_diff(&run(Ordering::Amd), &run(Ordering::Custom(p)));
        assert!(d <= 1e-10, "{element}: relative difference {d:.2e}");
    }
}

#[test]
fn two_domains_match_one_factorisation_bitwise_on_any_thread_count() {
    for element in ["qua4", "qua8", "tri3"] {
        let scene = strip(6, element);
        let sm = scene.build().unwrap();
        let red = sm.constraints.reduce().unwrap();
        let split = bisection(&sm.mesh, &red).expect("structured mesh");
        // The separator: one grid line (x and y of each node but the fixed bottom and the
        // tied top one) and the plate's free DOFs.
        let line = 6 * if element == "qua8" { 2 } else { 1 };
        assert_eq!(split.separator.len(), 2 * (line - 1) + red.n_free() - red.n_free_nodes, "{element}");
        let run = |ordering: Ordering, k: usize| {
            pool(k)
                .install(|| check::run(&scene, &SolverOptions { ordering, ..Default::default() }).unwrap().0)
        };
        let one = run(Ordering::TwoDomain(split.clone()), 1);
        let two = run(Ordering::TwoDomain(split), 2);
        let bits = |r: &CheckResult| r.displacements.concat().iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&one), bits(&two), "{element}: thread count changed the result");
        // Same system, another elimination order: agreement to round-off (cond ~1e6 here).
        let d = rel_diff(&run(Ordering::Amd, 1), &one);
        assert!(d <= 1e-10, "{element}: relative difference {d:.2e}");
    }
}

/// Our multifrontal factorisation of the halves and faer's left-looking one on the same
/// structure, and our substitutions and faer's on that factor: the same factor and the same
/// solutions to round-off (relative to the largest value; measured <= 3e-15).
#[test]
fn multifrontal_halves_and_their_solves_equal_faer() {
    use tribofe::linalg::substructure::TwoDomain;
    for element in ["qua4", "qua8"] {
        let sm = strip(8, element).build().unwrap();
        let red = sm.constraints.reduce().unwrap();
        let asm = Assembler::new(&sm.mesh, &red).unwrap();
        let g = vec![vec![1e-6; sm.constraints.n_fixed()]];
        let (values, _) = asm.assemble(&sm.model(), &red, &[vec![]], &g).unwrap();
        let two = TwoDomain::analyse(&asm.pattern, &bisection(&sm.mesh, &red).unwrap()).unwrap();
        let (mut ours, mut faer) = (Default::default(), Default::default());
        two.factor_halves(&values, false, &mut ours).unwrap();
        two.factor_halves(&values, true, &mut faer).unwrap();
        let d = relative_difference(&ours, &faer);
        assert!(d < 1e-12, "{element}: factors differ by {d:.2e}");
        // Our substitutions against faer's supernodal ones on that factor, 3 right-hand sides.
        let (mut x_ours, mut x_faer) = (Default::default(), Default::default());
        two.solve_halves(&ours, &mut x_ours, 3, false);
        two.solve_halves(&ours, &mut x_faer, 3, true);
        let d = relative_difference(&x_ours, &x_faer);
        assert!(d < 1e-12, "{element}: solutions differ by {d:.2e}");
    }
}

/// A split that is not a partition, or whose halves touch, is refused with the reason.
#[test]
fn a_bad_two_domain_split_is_refused() {
    use tribofe::linalg::substructure::TwoDomain;
    let sm = strip(6, "qua4").build().unwrap();
    let red = sm.constraints.reduce().unwrap();
    let asm = Assembler::new(&sm.mesh, &red).unwrap();
    let good = bisection(&sm.mesh, &red).unwrap();
    assert!(TwoDomain::analyse(&asm.pattern, &good).is_ok());
    let refused = |split: &tribofe::fem::ordering::Bisection, why: &str| {
        let e = TwoDomain::analyse(&asm.pattern, split).err().expect("refused").to_string();
        assert!(e.contains(why), "{e}");
    };
    // A separator unknown moved into one half touches the other half.
    let mut touching = good.clone();
    let k = touching.separator.remove(0);
    touching.parts[0].push(k);
    refused(&touching, "couple the two halves directly");
    let mut twice = good.clone();
    twice.parts[1].push(twice.parts[0][0]);
    refused(&twice, "listed twice");
    let mut missing = good.clone();
    missing.parts[1].pop();
    refused(&missing, "is in no part");
}

/// Largest difference of the two halves' values, relative to the largest value.
fn relative_difference(a: &[Vec<f64>; 2], b: &[Vec<f64>; 2]) -> f64 {
    let (a, b) = (a.concat(), b.concat());
    let scale = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    a.iter().zip(&b).fold(0.0f64, |m, (x, y)| m.max((x - y).abs())) / scale
}

/// A prepared solver keeps the factor's memory for the next factorisation (a sweep); the
/// stale values in it must not leak: a material change gives bitwise the answer of a fresh
/// solver.
#[test]
fn two_domain_refactorisation_in_reused_memory_is_bitwise_fresh() {
    let scene = strip(6, "qua4");
    let red = scene.build().unwrap().constraints.reduce().unwrap();
    let split = bisection(&scene.build().unwrap().mesh, &red).unwrap();
    let opts = SolverOptions { ordering: Ordering::TwoDomain(split), ..Default::default() };
    let prepared = check::prepare(&scene, &opts).unwrap();
    let mut other = scene.clone();
    other.block.poisson = 0.3;
    check::run_model(&scene, scene.build().unwrap(), 0.0, &opts, Some(&prepared)).unwrap();
    let reused = check::run_model(&other, other.build().unwrap(), 0.0, &opts, Some(&prepared)).unwrap().0;
    let fresh = check::run(&other, &opts).unwrap().0;
    let bits = |r: &CheckResult| r.displacements.concat().iter().map(|v| v.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&reused), bits(&fresh));
    assert!(rel_diff(&reused, &check::run(&scene, &opts).unwrap().0) > 1e-3, "nu must change the answer");
}

#[test]
fn two_domains_name_a_free_body() {
    use tribofe::fem::assembly::Model;
    use tribofe::fem::constraints::{dof, Constraints};
    use tribofe::fem::material::Material;
    use tribofe::fem::problem::{solve, LoadCase};
    let mesh = tribofe::fem::mesher::Rectangle::new(0.0, 2.0, 0.0, 0.1, 40, 2).build().unwrap();
    let mut c = Constraints::new(mesh.n_nodes());
    for n in mesh.set_nodes("bottom").unwrap() {
        c.fix(dof(n, 1)); // free to slide in x
    }
    let split = bisection(&mesh, &c.reduce().unwrap()).unwrap();
    let mut f = vec![0.0; 2 * mesh.n_nodes()];
    f[0] = 1.0;
    let model = Model::new(&mesh, Material::plane_strain(2e3, 0.4).unwrap());
    let opts = SolverOptions { ordering: Ordering::TwoDomain(split), ..Default::default() };
    let err = solve(&model, &c, &[LoadCase { prescribed: vec![0.0; c.n_fixed()], forces: f }], &opts, "")
        .unwrap_err()
        .to_string();
    assert!(err.contains("free to move"), "{err}");
}

/// Separator edge cases on a path graph (tridiagonal, diagonal 3, off-diagonal -1): one
/// unknown between the halves, and no separator at all for two disconnected paths. The
/// solution against A x = b to round-off (cond(A) < 5: ||r||_inf < 1e-14), and a matrix that
/// is not positive definite names its unknown.
#[test]
fn two_domains_with_a_one_unknown_or_empty_separator() {
    use tribofe::linalg::pattern::{Bisection, Pattern};
    use tribofe::linalg::substructure::TwoDomain;
    use tribofe::linalg::NonPositivePivot;
    let n = 9;
    // Lower CSC: column j holds (j, j) and (j + 1, j) unless the link is cut.
    let path = |cut: Option<usize>, bad: Option<usize>| {
        let (mut col_ptr, mut row_idx, mut values) = (vec![0u32], Vec::new(), Vec::new());
        for j in 0..n {
            row_idx.push(j as u32);
            values.push(if Some(j) == bad { -1.0 } else { 3.0 });
            if j + 1 < n && Some(j) != cut {
                row_idx.push(j as u32 + 1);
                values.push(-1.0);
            }
            col_ptr.push(row_idx.len() as u32);
        }
        (Pattern { n, col_ptr, row_idx }, values)
    };
    let one = Bisection { parts: [(0..4).collect(), (5..9).collect()], separator: vec![4] };
    let none = Bisection { parts: [(0..4).collect(), (4..9).collect()], separator: vec![] };
    for (split, cut) in [(one.clone(), None), (none, Some(3))] {
        let (pattern, values) = path(cut, None);
        let two = TwoDomain::analyse(&pattern, &split).unwrap();
        let f = two.factorize(&values).unwrap();
        let b: Vec<f64> = (0..n).map(|i| i as f64 - 4.0).collect();
        let mut x = b.clone();
        two.solve_in_place(&f, &mut x, 1);
        let ax = |i: usize| {
            let left = if i > 0 && Some(i - 1) != cut { -x[i - 1] } else { 0.0 };
            let right = if i + 1 < n && Some(i) != cut { -x[i + 1] } else { 0.0 };
            3.0 * x[i] + left + right
        };
        let r = (0..n).map(|i| (ax(i) - b[i]).abs()).fold(0.0, f64::max);
        assert!(r < 1e-14, "separator {:?}: residual {r:e}", split.separator);
    }
    let (pattern, values) = path(None, Some(6));
    let two = TwoDomain::analyse(&pattern, &one).unwrap();
    assert_eq!(two.factorize(&values).err(), Some(NonPositivePivot { unknown: 6 }));
}
