//! The reused factor against a factorisation per solve.

use super::*;
use crate::interface::events::operator::{ActiveSet, Operator};
use crate::interface::events::{NodeState, Phase};
use crate::scene::Scene;

/// Largest difference of two affine solutions relative to each vector's largest entry.
fn diff(a: &Affine, b: &crate::interface::banded::Solution) -> f64 {
    let mut w = 0.0f64;
    for (x, y) in [(&a.b0, &b.b0), (&a.b1, &b.b1), (&a.f0, &b.f0), (&a.f1, &b.f1)] {
        let big = y.iter().fold(1e-300f64, |s, v| s.max(v.abs()));
        for (p, q) in x.iter().zip(y.iter()) {
            w = w.max((p - q).abs() / big);
        }
    }
    w
}

/// A walk of one- and two-node changes (stick, slip both ways, open; anchors moved; the
/// phase switched; a Newton spring) on the coarse paper scene (101 nodes): the reused
/// factor with a rank cap of 3 (refactored every few solves) and with the default cap
/// agree with a factorisation per solve. Both are backward stable to 32 ulps a row on
/// systems of condition ~1e6, so they agree to ~1e-10 of the largest entry.
#[test]
fn reused_factor_matches_a_fresh_factorisation_through_many_updates() {
    let mut scene = Scene::default();
    scene.mesh.h = 0.004;
    scene.mesh.n_thick = Some(2);
    let op = BandedOperator::new(&scene, scene.loading.height).unwrap();
    let n = op.n;
    let mut set = ActiveSet {
        n,
        states: vec![NodeState::Stick; n],
        anchor: vec![0.0; n],
        mu_slip: vec![0.45; n],
        spring: vec![0.0; n],
        spring_u: vec![0.0; n],
        phase: Phase::Normal,
        n_force: 40.0,
        border: crate::interface::events::TOP_PLATE.to_vec(),
    };
    let mut small = Solving::with_rank_cap(&op, 3);
    let mut large = Solving::new(&op);
    let mut ws = op.workspace();
    let mut seed = 5u64;
    let mut rnd = || {
        seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut worst = 0.0f64;
    for step in 0..120 {
        let changes = if rnd() < 0.8 { 1 } else { 2 };
        for _ in 0..changes {
            let i = ((rnd() * n as f64) as usize).min(n - 1);
            let q = rnd();
            set.states[i] = if q < 0.5 {
                set.anchor[i] = 1e-7 * (rnd() - 0.5);
                set.spring[i] = 0.0;
                NodeState::Stick
            } else if q < 0.9 {
                NodeState::Slip(if q < 0.7 { 1.0 } else { -1.0 })
            } else {
                NodeState::Open
            };
        }
        if step == 60 {
            set.phase = Phase::Drive;
        }
        if step % 25 == 7 {
            if let Some(i) = (0..n).find(|&i| matches!(set.states[i], NodeState::Slip(_))) {
                set.spring[i] = 1e9;
                set.spring_u[i] = 1e-8;
            }
        }
        let bufs = RowBufs::new(&set, true);
        let rows = Solving::rows_of(&set, &bufs, &[], true);
        let want = op.solve(&rows, &mut ws).unwrap();
        for s in [&mut small, &mut large] {
            let got = s.solve(&set).unwrap();
            worst = worst.max(diff(&got, &want));
        }
    }
    eprintln!("reused vs fresh: {worst:.2e}; cap 3: {} factorisations", small.factorisations);
    assert!(worst < 1e-10, "reused vs fresh factorisation: {worst:.2e}");
    assert!(small.factorisations > 15, "the cap of 3 was crossed: {}", small.factorisations);
    assert!(small.row_updates > 50 && large.row_updates > 50);
    // The inverse block (slip weakening's stability test) through the reused factor.
    let dofs: Vec<usize> = (0..n).filter(|&i| set.is_free(i)).take(3).collect();
    let a = small.inverse_block(&set, &dofs).unwrap();
    let mut fresh = Solving::with_rank_cap(&op, 0);
    let b = fresh.inverse_block(&set, &dofs).unwrap();
    let big = b.iter().fold(0.0f64, |s, v| s.max(v.abs()));
    for (x, y) in a.iter().zip(&b) {
        assert!((x - y).abs() < 1e-10 * big, "inverse block {x} vs {y}");
    }
}

/// Slip weakening's iterates (the exact path's Newton corrector): a process zone of 20
/// slipping nodes (within this band's rank cap, 24) whose coefficients and tangent springs
/// all change at every solve, 40 times. Their rows enter R once (one band solve each) and
/// then change as low-rank updates of the same factor: one factorisation for the whole
/// walk (only the cap refactors: it grows with the band, ~200 rows at the paper's scene's
/// h = 0.125 mm, where the cap of 24 refactored at every iterate of a wider zone). Each solve agrees with a factorisation of its own to
/// 1e-10 of the largest entry (both backward stable to 32 ulps a row, condition ~1e6), and
/// the determinant's sign (the path's stability test) with the fresh LU's.
#[test]
fn coefficient_iterates_are_low_rank_updates_of_one_factor() {
    let mut scene = Scene::default();
    scene.mesh.h = 0.004;
    scene.mesh.n_thick = Some(2);
    let op = BandedOperator::new(&scene, scene.loading.height).unwrap();
    let n = op.n;
    let zone = 20..40;
    let mut set = ActiveSet {
        n,
        states: (0..n)
            .map(|i| if zone.contains(&i) { NodeState::Slip(1.0) } else { NodeState::Stick })
            .collect(),
        anchor: vec![0.0; n],
        mu_slip: vec![0.45; n],
        spring: vec![0.0; n],
        spring_u: vec![0.0; n],
        phase: Phase::Drive,
        n_force: 40.0,
        border: crate::interface::events::TOP_PLATE.to_vec(),
    };
    let mut reused = Solving::new(&op);
    assert!(reused.rank_cap >= zone.len(), "rank cap {}", reused.rank_cap);
    let mut ws = op.workspace();
    let mut worst = 0.0f64;
    let kt = op.scale;
    for it in 0..40 {
        for (k, i) in zone.clone().enumerate() {
            let phase = (it * 7 + k) as f64;
            set.mu_slip[i] = 0.45 - 0.1 * (0.5 + 0.5 * phase.sin());
            // Softening springs up to a tenth of the interface's own stiffness.
            set.spring[i] = -0.1 * kt * (0.5 + 0.5 * phase.cos());
            set.spring_u[i] = 1e-8 * phase.sin();
        }
        let bufs = RowBufs::new(&set, true);
        let rows = Solving::rows_of(&set, &bufs, &[], true);
        let want = op.solve(&rows, &mut ws).unwrap();
        let got = reused.solve(&set).unwrap();
        worst = worst.max(diff(&got, &want));
        let mut fresh = Solving::with_rank_cap(&op, 0);
        assert_eq!(reused.det_sign(&set).unwrap(), fresh.det_sign(&set).unwrap(), "iterate {it}");
    }
    assert!(worst < 1e-10, "low-rank vs fresh factorisation: {worst:.2e}");
    assert_eq!(reused.factorisations, 1, "{} factorisations for 40 iterates", reused.factorisations);
    assert_eq!(reused.row_updates, zone.len(), "each zone row enters R once");
}
