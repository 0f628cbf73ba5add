//! The block's ends on the frictional interface (`tribofe edges`). Under N alone the problem
//! is symmetric, so both ends pre-slip equally (to round-off); a pre-slip zone of finite
//! length is a converged quantity, so refinement may move its front by at most the coarser
//! element; above the corner's own traction ratio the ends stay stuck. Under the drive the
//! trailing end opens before the first precursor, at a force that converges with refinement.

use tribofe::law::Rule;
use tribofe::scene::Scene;
use tribofe::studies::edges::{opening, preslip};

fn short() -> Scene {
    let mut s = Scene::default();
    s.block.length = 0.05;
    s
}

#[test]
fn preslip_converges_and_vanishes_above_the_corner_ratio() {
    let rows = preslip(&short(), &[0.1, 0.3, 0.65], &[8, 16]).unwrap();
    let at = |mu: f64, k: f64| rows.iter().find(|r| r.mu == mu && r.t_over_h == k).unwrap();
    for r in &rows {
        assert!((r.extent_t[0] - r.extent_t[1]).abs() < 1e-12, "{r:?}");
    }
    for mu in [0.1, 0.3] {
        let (a, b) = (at(mu, 8.0).extent_t[0], at(mu, 16.0).extent_t[0]);
        // Finite (several elements at t/h = 16) and moved by less than one coarse element.
        assert!(b > 0.5 && (a - b).abs() <= 1.0 / 8.0 + 1e-12, "mu = {mu}: {a} -> {b}");
    }
    assert!(at(0.1, 16.0).extent_t[0] > at(0.3, 16.0).extent_t[0]);
    assert_eq!(at(0.65, 8.0).extent_t, [0.0, 0.0]);
    assert_eq!(at(0.65, 16.0).extent_t, [0.0, 0.0]);
}

#[test]
fn trailing_end_opens_before_the_first_precursor() {
    let (mu_d, r) = (0.35 / 0.6, 0.9);
    let rows = opening(&short(), mu_d / r, mu_d, Rule::Paper, &[0.02], &[4, 8], &[0.1]).unwrap();
    let (a, b) = (&rows[0], &rows[1]);
    for o in &rows {
        assert!(o.opens_first(), "{o:?}");
        // The first long precursor near the paper's F_1 = 0.72 (thin-layer offsets of a few %).
        assert!((o.f1_fe.unwrap() - o.f1_model).abs() < 0.06, "{o:?}");
    }
    // The opening force converges (0.5354 -> 0.5207 -> 0.5207 at t/h = 4, 8, 16), well below
    // the first precursor's.
    let (fa, fb) = (a.f_open.unwrap(), b.f_open.unwrap());
    assert!((fa - fb).abs() < 0.03 && fb < 0.8 * b.f1_model, "{fa} {fb}");
}
