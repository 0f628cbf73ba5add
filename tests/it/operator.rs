//! The banded operator (issue 32) against the dense condensed S: the same affine solution of
//! random state sets, and the same event histories through the event solver.

use tribofe::interface::banded::{BandedOperator, Rows, Solution, RANK_CAP};
use tribofe::interface::condense::condense;
use tribofe::interface::events::Operator;
use tribofe::law::{Law, Rule};
use tribofe::linalg::solve::SolverOptions;
use tribofe::scene::Scene;
use tribofe::studies::slide::{coefficients_from_rg, run, run_condensed, SlideOptions};

/// Deterministic uniform numbers in [0, 1).
struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The dense reference: the free system of S (rows as in the event solver) by a dense LU.
fn dense(s: &[f64], n: usize, r: &Rows) -> Solution {
    let nd = 2 * n + 3;
    let free: Vec<usize> = (0..nd).filter(|&d| r.free[d]).collect();
    let coef = |d: usize| if d < n { r.coef[d] } else { 0.0 };
    let entry = |a: usize, b: usize| {
        let mut v = s[a * nd + b];
        if coef(a) != 0.0 {
            v += coef(a) * s[(a + n) * nd + b];
        }
        if a == b && a < n {
            v += r.spring[a];
        }
        v
    };
    let m = free.len();
    let a = faer::Mat::<f64>::from_fn(m, m, |i, j| entry(free[i], free[j]));
    let rhs = faer::Mat::<f64>::from_fn(m, 2, |i, k| {
        let d = free[i];
        let bc = if k == 0 { r.b0 } else { r.b1 };
        let mut v = if d == 2 * n + 1 { [r.fk.0, r.fk.1][k] } else { 0.0 };
        for j in (0..nd).filter(|&j| !r.free[j]) {
            v -= entry(d, j) * bc[j];
        }
        if k == 0 && d < n {
            v += r.spring[d] * r.spring_u[d];
        }
        v
    });
    let x = faer::linalg::solvers::Solve::solve(&a.partial_piv_lu(), &rhs);
    let mut out = Solution { b0: r.b0.to_vec(), b1: r.b1.to_vec(), f0: vec![0.0; nd], f1: vec![0.0; nd] };
    for (i, &d) in free.iter().enumerate() {
        out.b0[d] = x[(i, 0)];
        out.b1[d] = x[(i, 1)];
    }
    for i in 0..nd {
        out.f0[i] = (0..nd).map(|j| s[i * nd + j] * out.b0[j]).sum();
        out.f1[i] = (0..nd).map(|j| s[i * nd + j] * out.b1[j]).sum();
    }
    out
}

/// Largest difference relative to the largest entry, over the four vectors.
fn rel_diff(a: &Solution, b: &Solution) -> f64 {
    let mut worst = 0.0f64;
    for (x, y) in [(&a.b0, &b.b0), (&a.b1, &b.b1), (&a.f0, &b.f0), (&a.f1, &b.f1)] {
        let big = y.iter().fold(1e-300f64, |s, v| s.max(v.abs()));
        for (p, q) in x.iter().zip(y) {
            worst = worst.max((p - q).abs() / big);
        }
    }
    worst
}

fn compare(scene: &Scene, cases: usize, seed: u64) -> f64 {
    let c = condense(scene, &SolverOptions::default()).unwrap();
    let h = scene.loading.height;
    let s = c.at_height(h);
    let op = BandedOperator::new(scene, h).unwrap();
    let (n, nd) = (c.n, c.dim());
    assert_eq!(op.n, n);
    let mut ws = op.workspace();
    let mut rng = Lcg(seed);
    let nf = 40.0;
    // Displacement scale N t/(E* L): anchors of that order.
    let us = nf * c.t / (c.e_star * c.l);
    let mut worst = 0.0f64;
    for case in 0..cases {
        let (mut free, mut b0, mut b1) = (vec![false; nd], vec![0.0; nd], vec![0.0; nd]);
        let (mut coef, mut spring, mut spring_u) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        // Mostly stuck (the block must be held), then slip both ways and open patches.
        for i in 0..n {
            let q = rng.next();
            if q < 0.55 {
                b0[i] = us * (rng.next() - 0.5);
            } else if q < 0.9 {
                free[i] = true;
                coef[i] = if q < 0.725 { 0.45 } else { -0.45 };
            } else {
                free[i] = true;
                free[n + i] = true;
            }
        }
        // A Newton spring on one slipping node.
        if let Some(i) = (0..n).find(|&i| free[i] && !free[n + i]) {
            spring[i] = 0.3 * c.e_star;
            spring_u[i] = us;
        }
        free[2 * n + 1] = true;
        free[2 * n + 2] = true;
        let drive = case % 2 == 1;
        let fk = if drive {
            b1[2 * n] = 1.0;
            (-nf, 0.0)
        } else {
            (0.0, -nf)
        };
        let rows = Rows {
            free: &free,
            b0: &b0,
            b1: &b1,
            coef: &coef,
            spring: &spring,
            spring_u: &spring_u,
            fk,
            load: &[],
        };
        let got = op.solve(&rows, &mut ws).unwrap();
        let want = dense(&s, n, &rows);
        worst = worst.max(rel_diff(&got, &want));
    }
    worst
}

/// The paper's scene on a coarse mesh (h = 4 mm, 101 interface nodes): the dense S comes from
/// a sparse Cholesky and 2n + 3 solves, the banded one from a banded LU; both are backward
/// stable on systems of condition ~1e6, so they agree to ~1e-10 of the largest entry.
#[test]
fn banded_matches_dense_paper_scene() {
    let mut s = Scene::default();
    s.mesh.h = 0.004;
    s.mesh.n_thick = Some(2);
    let d = compare(&s, 8, 1);
    eprintln!("paper scene: banded vs dense {d:.2e}");
    assert!(d < 1e-10, "banded vs dense: {d:.2e}");
}

/// A thin block (t/L = 1/100, h = t, 2 elements through t) and a thicker mesh through t.
#[test]
fn banded_matches_dense_thin_block() {
    let mut s = Scene::default();
    s.block.length = 0.05;
    s.block.thickness = 0.0005;
    s.loading.height = 0.005;
    s.mesh.h = 0.0005;
    s.mesh.n_thick = Some(2);
    let d = compare(&s, 8, 2);
    eprintln!("thin block: banded vs dense {d:.2e}");
    assert!(d < 1e-10, "banded vs dense, thin block: {d:.2e}");
    s.mesh.h = 0.00025;
    s.mesh.n_thick = Some(4);
    let d = compare(&s, 4, 3);
    eprintln!("4 through t: banded vs dense {d:.2e}");
    assert!(d < 1e-10, "banded vs dense, 4 elements through t: {d:.2e}");
}

/// Runs `scene` through both operators and asserts the same events (kinds, nodes, regions) and
/// X, F, F relaxed to 1e-9 of the run's largest value (round-off is ~1e-12; event sequences
/// amplify it only where two events nearly coincide, which these scenes do not have).
/// Returns the event count and the banded run's (low-rank row updates, factorisations).
fn same_history(scene: &Scene, law: Law, cycles: usize) -> (usize, usize, usize) {
    same_prefix(scene, law, cycles, None, 1e-9)
}

/// [`same_history`] over the first `prefix` events (all: None) to `tol` of the largest X, F.
fn same_prefix(
    scene: &Scene,
    law: Law,
    cycles: usize,
    prefix: Option<usize>,
    tol: f64,
) -> (usize, usize, usize) {
    let o = SlideOptions { law, cycles, keep_states: false, ..Default::default() };
    let dense = run(scene, &o, tribofe::Progress::none()).unwrap();
    let banded =
        run(scene, &SlideOptions { operator: Operator::Banded, ..o }, tribofe::Progress::none()).unwrap();
    let (a, b) = (&dense.run.events, &banded.run.events);
    if prefix.is_none() {
        assert_eq!(a.len(), b.len(), "event counts");
    }
    let k = prefix.unwrap_or(a.len());
    assert!(a.len() >= k && b.len() >= k, "fewer than {k} events: {} and {}", a.len(), b.len());
    let (a, b) = (&a[..k], &b[..k]);
    let xs = a.iter().fold(0.0f64, |s, e| s.max(e.x.abs()));
    let fs = a.iter().fold(0.0f64, |s, e| s.max(e.f.abs()));
    for (k, (p, q)) in a.iter().zip(b).enumerate() {
        assert_eq!((p.kind, p.node, p.region), (q.kind, q.node, q.region), "event {k}");
        assert!((p.x - q.x).abs() <= tol * xs, "event {k}: X {} vs {}", p.x, q.x);
        assert!((p.f - q.f).abs() <= tol * fs, "event {k}: F {} vs {}", p.f, q.f);
        assert!((p.f_relaxed - q.f_relaxed).abs() <= tol * fs, "event {k}: F relaxed");
    }
    // The banded run is as consistent as the dense one (violations relative to N/n).
    assert!(
        banded.run.max_violation <= 2.0 * dense.run.max_violation.max(1e-10),
        "banded violation {:.1e}, dense {:.1e}",
        banded.run.max_violation,
        dense.run.max_violation
    );
    assert_eq!(banded.condensed.n, dense.condensed.n);
    assert_eq!(banded.condensed.x, dense.condensed.x);
    (a.len(), banded.run.updates, banded.run.refreshes)
}

/// The paper's scene (h = 2 mm): coulomb to 5 % past sliding and the paper rule, one cycle.
/// The banded operator reuses one factorisation through low-rank row updates and refactors
/// past [`RANK_CAP`] changed rows: coulomb changes a node an event, so its ~200 events cross
/// the cap several times (each crossing a factorisation), and the paper rule's relaxations
/// (whole regions at once) refactor at once.
#[test]
fn same_events_paper_scene() {
    let mut s = Scene::default();
    s.mesh.h = 0.002;
    s.mesh.n_thick = Some(2);
    let (e, updates, factors) = same_history(&s, Law::coulomb(0.5).unwrap(), 1);
    assert!(e > 100, "coulomb: {e} events");
    assert!(updates > 3 * RANK_CAP, "coulomb: {updates} low-rank row updates");
    assert!(factors > 3 && factors < e / 4, "coulomb: {factors} factorisations for {e} events");
    let (ms, md) = coefficients_from_rg(&s, 0.9, 0.35).unwrap();
    let law = Law::static_kinetic(ms, md, Rule::Paper).unwrap();
    let (e, _, factors) = same_history(&s, law, 1);
    assert!(e > 5, "paper rule: {e} events");
    assert!(factors > 1, "paper rule: {factors} factorisations");
    // run_condensed (the studies' entry, S condensed once) honours the operator too.
    let o =
        SlideOptions { law, cycles: 1, operator: Operator::Banded, keep_states: false, ..Default::default() };
    let c = condense(&s, &SolverOptions::default()).unwrap();
    let a = run_condensed(&s, c, 0.0, &o, tribofe::Progress::none()).unwrap();
    let b = run(&s, &o, tribofe::Progress::none()).unwrap();
    assert_eq!((a.run.updates, a.run.refreshes), (b.run.updates, b.run.refreshes), "banded counts");
    let fx = |r: &tribofe::studies::slide::SlideResult| {
        r.run.events.iter().map(|e| (e.x, e.f)).collect::<Vec<_>>()
    };
    assert_eq!(fx(&a), fx(&b), "same operator, same arithmetic");
}

/// The paper's scene on its own mesh (401 interface nodes), coulomb mu = 0.5: 404 events on
/// the reused banded factor (hundreds of low-rank updates, a dozen factorisations) against
/// the dense reference, events equal and X, F to 1e-9 of the largest (measured ~1e-13).
#[test]
fn same_events_paper_mesh_coulomb_reused_factor() {
    let s = Scene::default();
    let (e, updates, factors) = same_history(&s, Law::coulomb(0.5).unwrap(), 1);
    assert!(e > 400, "coulomb: {e} events");
    assert!(updates > 10 * RANK_CAP && factors > 10, "{updates} updates, {factors} factorisations");
}

/// A thin block (t/L = 1/200, h = t/2) with the paper rule, and slip weakening (its
/// coefficient updates go through the same operator) on the coarse t = 4 mm block. Slip
/// weakening's relaxations are fixed-point iterations stopped at a tolerance, so the two
/// paths agree to ~1e-7 (measured 1.4e-7), and its event sequence amplifies that difference
/// after ~200 events (validation/friction/README.md): the first 150 are compared to 1e-6.
#[test]
fn same_events_thin_block_and_weakening() {
    let mut s = Scene::default();
    s.block.length = 0.1;
    s.block.thickness = 0.0005;
    s.loading.height = 0.01;
    s.mesh.h = 0.00025;
    s.mesh.n_thick = Some(2);
    let (ms, md) = coefficients_from_rg(&s, 0.9, 0.35).unwrap();
    let (e, _, _) = same_history(&s, Law::static_kinetic(ms, md, Rule::Paper).unwrap(), 1);
    assert!(e > 5, "thin block: {e} events");
    let mut w = Scene::default();
    w.block.length = 0.1;
    w.block.thickness = 0.004;
    w.mesh.h = 0.004;
    w.mesh.n_thick = Some(2);
    let (ms, md) = coefficients_from_rg(&w, 0.9, 0.35).unwrap();
    let (e, _, _) = same_prefix(&w, Law::slip_weakening(ms, md, 3e-7).unwrap(), 1, Some(150), 1e-6);
    assert_eq!(e, 150, "slip weakening");
}

#[test]
fn the_default_operator_is_dense_on_thick_blocks_and_banded_on_thin_long_ones() {
    // The size rule (Operator::for_interface): banded above 200 nodes while rows^2 <= n / 2.
    // Measured (docs/speed.md): 401 nodes, 20 rows, static-kinetic: dense 1.1 s, banded 2.4 s;
    // 10 rows: 0.65 s, 0.23 s. The default must pick the faster of each pair.
    let mut s = Scene::default();
    s.block.length = 0.1;
    s.mesh.h = 0.00025;
    s.block.thickness = 0.005;
    assert_eq!(Operator::for_scene(&s), Operator::Dense);
    s.block.thickness = 0.0025;
    assert_eq!(Operator::for_scene(&s), Operator::Banded);
    // The top plate at t/L = 0.5 on 201 nodes (100 rows): banded took 465 s, dense 2.9 s.
    s.mesh.h = 0.0005;
    s.block.thickness = 0.05;
    assert_eq!(Operator::for_scene(&s), Operator::Dense);
}
