//! The real-contact-area proxy of a multicontact interface under Amontons friction (issue 49):
//! A(x)/A_0 = p(x)/p_mean, p_mean = N/L with N the state's normal force.

use tribofe::law::Law;
use tribofe::scene::Scene;
use tribofe::studies::slide::{self, SlideOptions, StateField};

#[test]
fn contact_area_is_p_over_p_mean_and_averages_to_one() {
    // Coulomb on the paper's scene to whole sliding: the interface stays closed.
    let o = SlideOptions { law: Law::Coulomb { mu: 0.5 }, ..Default::default() };
    let r = slide::run(&Scene::default(), &o, tribofe::Progress::none()).unwrap();
    let c = &r.condensed;
    let (area, [rows, n]) = r.field(StateField::ContactAreaOverA0);
    assert_eq!(n, c.n);
    assert!(rows > 2);
    let csv = tribofe::report::slide::states_csv(&r).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = header.iter().position(|h| *h == "contact_area_over_A0").expect("the column");
    assert_eq!(col, header.len() - 1, "appended last: the earlier columns keep their places");
    for (k, st) in r.run.states.iter().enumerate() {
        let n_state: f64 = st.p_force.iter().sum();
        let p_mean = n_state / c.l;
        let row = &area[k * n..(k + 1) * n];
        for (i, (a, (f, w))) in row.iter().zip(st.p_force.iter().zip(&c.w)).enumerate() {
            let want = f / w / p_mean;
            assert!((a - want).abs() <= 1e-12 * want.abs().max(1.0), "state {k} node {i}");
        }
        let mean: f64 = row.iter().zip(&c.w).map(|(a, w)| a * w).sum::<f64>() / c.l;
        assert!((mean - 1.0).abs() <= 1e-12, "state {k}: mean A/A0 = {mean}");
        // The states.csv column is the same number to its 13 digits.
        for (i, a) in row.iter().enumerate() {
            let line = lines.next().unwrap();
            let v: f64 = line.rsplit(',').next().unwrap().parse().unwrap();
            assert!((v - a).abs() <= 1e-12 * a.abs().max(1.0), "states.csv state {k} node {i}");
        }
    }
    // The drive holds N: there the column is states.csv's p_over_pmean (p over the target N/L).
    let last = r.run.states.last().unwrap();
    let n_last: f64 = last.p_force.iter().sum();
    assert!((n_last - o.n_force).abs() <= 1e-10 * o.n_force, "N held in the drive: {n_last}");
}

#[test]
fn a_state_without_normal_force_has_no_contact_area() {
    let a = slide::contact_area_over_a0(&[0.0, 0.0, 0.0], &[0.5, 1.0, 0.5], 2.0);
    assert_eq!(a, vec![0.0; 3]);
    let a = slide::contact_area_over_a0(&[1.0, 4.0, 1.0], &[0.5, 1.0, 0.5], 2.0);
    // N = 6 over L = 2: p_mean 3; p = 2, 4, 2.
    assert_eq!(a, vec![2.0 / 3.0, 4.0 / 3.0, 2.0 / 3.0]);
}
