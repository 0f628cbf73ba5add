//! Precursor model tests. Tolerances: 1e-12 where the quantity is a short closed-form
//! evaluation in f64 (a few roundings of ~1e-16 on O(1) numbers); discretisation tolerances
//! are derived next to the tests that use them.

use std::path::PathBuf;
use std::process::Command;
use tribofe::precursors::discrete::{self, Interface};
use tribofe::precursors::fe::{compare, UnitFields};
use tribofe::precursors::{
    loading_curve, n_map, n_precursors, simulate, simulate_to_convergence, Event, Params,
};
use tribofe::report::{precursors as report, write_atomic};
use tribofe::Error;

const EXACT: f64 = 1e-12;

fn params(r: f64, g: f64) -> Params {
    Params::new(r, g).expect("valid (r, g)")
}

fn tmp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("tribofe-precursors-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

/// A grid inside the accessible square, with points on both sides of g = (1-r)/2.
fn grid() -> Vec<(f64, f64)> {
    let v = [0.05, 0.2, 0.35, 0.5, 0.65, 0.8, 0.95];
    v.iter().flat_map(|&r| v.iter().map(move |&g| (r, g))).collect()
}

#[test]
fn hand_calculation_r09_g035() {
    // r = 0.9, g = 0.35:
    // F_1   = 1/(1 + 0.35/0.9) = 0.9/1.25 = 0.72                               (eq. F1)
    // F_1^c = F_1 = 0.72                                                       (eq. Fic)
    // x_1   = (0.72 - 0.9)/(2 * 0.72 * 0.35) = -0.18/0.504 = -5/14             (eq. xi)
    // F_1^* = 0.72 - 1/2 (x_1 + 1/2)[0.72 - 0.9 (1 - 0.35*0.72/0.9)]
    //       = 0.72 - 1/2 (1/7)(0.72 - 0.9 + 0.252) = 0.72 - 0.036/7 = 1251/1750  (eq. Fi*)
    // F_2   = (1 - 0.9 + 1251/1750 + 0.35*0.72)/(1 + 0.35/0.9)
    //       = (616/1750 + 1251/1750) * 0.72 = 1867 * 0.72/1750 = 1344.24/1750   (eq. Fi+1)
    // F_2^c = F_2 + (F_1 - F_1^*) = (1344.24 + 9)/1750 = 0.77328               (eq. Fic)
    // x_2   = (0.77328 - 0.9)/(2 * 0.35 * 1344.24/1750) = -0.12672 * 2500/1344.24
    let ev = simulate(&params(0.9, 0.35), 2);
    let (e1, e2) = (ev[0], ev[1]);
    assert!((e1.f - 0.72).abs() < EXACT, "F_1 = {}", e1.f);
    assert!((e1.fc - 0.72).abs() < EXACT, "F_1^c = {}", e1.fc);
    assert!((e1.x - (-5.0 / 14.0)).abs() < EXACT, "x_1 = {}", e1.x);
    assert!((e1.fstar - 1251.0 / 1750.0).abs() < EXACT, "F_1^* = {}", e1.fstar);
    assert!((e2.f - 1344.24 / 1750.0).abs() < EXACT, "F_2 = {}", e2.f);
    assert!((e2.fc - 0.77328).abs() < EXACT, "F_2^c = {}", e2.fc);
    assert!((e2.x - (-0.12672 * 2500.0 / 1344.24)).abs() < EXACT, "x_2 = {}", e2.x);
    assert!(!e1.stick_slip && !e2.stick_slip);
}

#[test]
fn paper_case_r09_g035_has_ten_precursors() {
    // n = 10 and F_max = 1/(1 + 0.35*0.1/0.9) = 0.9/0.935, as quoted in validation/precursors/README.md.
    let p = params(0.9, 0.35);
    assert_eq!(n_precursors(&p).unwrap(), 10);
    assert!((p.f_max() - 0.9 / 0.935).abs() < EXACT);
}

#[test]
fn first_event_is_trailing_edge_static_threshold() {
    // Eq. (F1) is where the uniform shear F meets mu_s p(-1/2, F) = 1 - (g/r) F.
    for (r, g) in grid() {
        let e = simulate(&params(r, g), 1)[0];
        assert!((e.f - 1.0 / (1.0 + g / r)).abs() < EXACT, "(r, g) = ({r}, {g})");
        assert!((e.f - (1.0 - g / r * e.f)).abs() < EXACT, "(r, g) = ({r}, {g})");
        assert_eq!(e.fc, e.f);
    }
}

#[test]
fn no_precursor_line() {
    // x_1 - 1/2 changes sign at g = (1-r)/2 with a slope of order 1, so a relative offset of
    // 1e-6 moves x_1 by ~1e-6 from 1/2, far above rounding (~1e-16).
    for r in [0.1, 0.3, 0.5, 0.7, 0.9] {
        let g0 = Params::no_precursor_g(r);
        assert_eq!(n_precursors(&params(r, g0 * (1.0 - 1e-6))).unwrap(), 0, "r = {r}, just below");
        assert!(n_precursors(&params(r, g0 * (1.0 + 1e-6))).unwrap() >= 1, "r = {r}, just above");
    }
}

#[test]
fn precursors_grow_then_stick_slip() {
    for (r, g) in grid() {
        let p = params(r, g);
        let n = n_precursors(&p).unwrap();
        let ev = simulate(&p, n + 3);
        for w in ev[..n].windows(2) {
            assert!(w[1].x > w[0].x, "(r, g) = ({r}, {g}): x not increasing at event {}", w[1].i);
        }
        assert!(ev[..n].iter().all(|e| !e.stick_slip && e.x <= 0.5 && e.x >= -0.5));
        assert!(ev[n..].iter().all(|e| e.stick_slip && e.x == 0.5 && (e.fstar - r).abs() < EXACT));
    }
}

#[test]
fn stick_slip_converges_to_f_max() {
    // With F^* = r, eq. (Fi+1) gives F_{i+1} - F_max = q (F_i - F_max), q = g/(1 + g/r)
    // = g r/(r + g) < 1: geometric convergence at a known rate. The ratio is checked to 1e-6
    // while |F_i - F_max| > 1e-8, so rounding (~1e-16/1e-8) cannot spoil it.
    for (r, g) in grid() {
        let p = params(r, g);
        let f_max = p.f_max();
        let q = g * r / (r + g);
        let ev = simulate(&p, n_precursors(&p).unwrap() + 200);
        let ss: Vec<f64> = ev.iter().filter(|e| e.stick_slip).map(|e| e.f - f_max).collect();
        for w in ss.windows(2).filter(|w| w[0].abs() > 1e-8) {
            assert!((w[1] / w[0] - q).abs() < 1e-6, "(r, g) = ({r}, {g}): ratio {} vs {q}", w[1] / w[0]);
        }
        assert!(ss.last().unwrap().abs() < EXACT, "(r, g) = ({r}, {g})");
    }
}

#[test]
fn simulate_to_convergence_stops_near_f_max() {
    let p = params(0.9, 0.35);
    let ev = simulate_to_convergence(&p, 1e-6, 200);
    let last = ev.last().unwrap();
    assert!(last.stick_slip && (last.f - p.f_max()).abs() < 1e-6);
    assert!((ev[ev.len() - 2].f - p.f_max()).abs() >= 1e-6, "stopped late");
}

#[test]
fn loading_curve_is_a_sawtooth_of_slope_one() {
    // Between events F and F^c grow together (eq. Fic); relaxations are vertical drops.
    let ev = simulate(&params(0.7, 0.6), 30);
    let c = loading_curve(&ev);
    assert_eq!(c[0], (0.0, 0.0));
    assert_eq!(c.len(), 2 * ev.len() + 1);
    for k in 0..ev.len() {
        let (start, top, bottom) = (c[2 * k], c[2 * k + 1], c[2 * k + 2]);
        assert!(((top.1 - start.1) - (top.0 - start.0)).abs() < EXACT, "reloading slope at event {}", k + 1);
        assert!(top.0 == bottom.0 && bottom.1 < top.1, "drop at event {}", k + 1);
    }
}

#[test]
fn n_map_is_monotone_and_splits_on_the_line() {
    let res = 40;
    let map = n_map(res, &tribofe::Cancel::new()).unwrap();
    assert_eq!(map.len(), res * res);
    let n = |i: usize, j: usize| map[i * res + j].n;
    for i in 0..res {
        for j in 0..res {
            let m = map[i * res + j];
            assert!(m.r > 0.0 && m.r < 1.0 && m.g > 0.0 && m.g < 1.0);
            if i + 1 < res {
                assert!(n(i + 1, j) >= n(i, j), "n decreases with r at ({}, {})", m.r, m.g);
            }
            if j + 1 < res {
                assert!(n(i, j + 1) >= n(i, j), "n decreases with g at ({}, {})", m.r, m.g);
            }
            // No grid centre lies on g = (1-r)/2 (it would need 2j + i = res - 3/2).
            assert_eq!(m.n == 0, m.g < Params::no_precursor_g(m.r), "({}, {})", m.r, m.g);
        }
    }
}

#[test]
fn invalid_params_say_why() {
    let why = |r: f64, g: f64| match Params::new(r, g) {
        Err(e @ Error::Input { .. }) => e.to_string(),
        other => panic!("({r}, {g}) accepted: {other:?}"),
    };
    assert!(why(1.2, 0.3).contains("r = mu_d/mu_s must be < 1 since mu_s > mu_d"));
    assert!(why(1.0, 0.3).contains("< 1"));
    assert!(why(0.0, 0.3).contains("> 0"));
    assert!(why(f64::NAN, 0.3).contains("finite"));
    assert!(why(0.5, f64::INFINITY).contains("finite"));
    assert!(why(0.5, 1.0).contains("g must be < 1 so the trailing-edge pressure stays positive"));
    assert!(why(0.5, -0.1).contains(">= 0"));
    // g = 0 is the control case without torque: accepted, the model's answer is no precursor.
    let p = Params::new(0.9, 0.0).unwrap();
    assert_eq!((p.f1(), p.f_max()), (1.0, 1.0));
    assert_eq!(tribofe::precursors::n_precursors(&p).unwrap(), 0);
    assert!(n_map(1, &tribofe::Cancel::new()).is_err() && n_map(401, &tribofe::Cancel::new()).is_err());
}

fn errors<'a>(run: &'a discrete::Run, an: &'a [Event]) -> impl Iterator<Item = (usize, f64, f64, f64)> + 'a {
    run.events.iter().zip(an).map(|(d, a)| (d.i, (d.f - a.f).abs(), (d.fc - a.fc).abs(), (d.x - a.x).abs()))
}

#[test]
fn discrete_on_fe_like_nodes_reproduces_the_iteration() {
    // Nodes at x = -1/2 + k h, tributary widths (half at the ends). The trailing node sits
    // on the edge, so nucleation is exact, and node sums integrate the linear relaxed field
    // exactly. The only error is the arrest quantisation: the slipped region ends midway
    // between the last node satisfying sigma > mu_d p and the next, so |x_d - x_i| <= h/2,
    // and since dF^*/dx = 2 g F (x - x_i) vanishes at the true arrest point, it shifts F^*
    // by g F (x_d - x_i)^2 <= g h^2/4 per event. Allowing these shifts to accumulate with
    // gain up to 4 over i events: |dF_i|, |dF^c_i| <= i g h^2, and x_i moves by at most
    // dF^c/(2 g F) <= i h^2/(2 F_1) on top of the h/2 quantisation.
    let nodes = 2001;
    let h = 1.0 / (nodes - 1) as f64;
    let (x, w) = discrete::tributary_nodes(nodes);
    for r in [0.5, 0.7, 0.9] {
        for g in [0.3, 0.5, 0.7] {
            let p = params(r, g);
            let run = discrete::simulate(&Interface::linear(&p, 1.0, x.clone(), w.clone()), 500).unwrap();
            let an = simulate(&p, run.events.len());
            assert_eq!(run.n_precursors(), Some(n_precursors(&p).unwrap()), "(r, g) = ({r}, {g})");
            assert!(run.periodic, "(r, g) = ({r}, {g}) did not settle within 500 events");
            for (i, df, dfc, dx) in errors(&run, &an) {
                let tol_f = i as f64 * g * h * h;
                assert!(
                    df <= tol_f && dfc <= tol_f,
                    "(r, g) = ({r}, {g}) event {i}: dF = {df:e}, dF^c = {dfc:e} > {tol_f:e}"
                );
                assert!(
                    dx <= h / 2.0 + i as f64 * h * h / (2.0 * p.f1()) + EXACT,
                    "(r, g) = ({r}, {g}) event {i}: dx = {dx:e}, h = {h:e}"
                );
            }
            assert!((run.f_limit().unwrap() - p.f_max()).abs() < 1e-9, "(r, g) = ({r}, {g})");
            assert!(run.events.iter().all(|e| e.nucleation == 0));
        }
    }
}

#[test]
fn discrete_on_cell_centres_matches_with_shifted_edge() {
    // Cell centres put the trailing threshold at -1/2 + h/2, which turns g into g(1 - h) in
    // the trailing-edge balance behind eqs. (F1) and (Fi+1): F_1 shifts by F_1^2 (g/r) h and
    // the stick-slip limit becomes exactly 1/(1 + g(1-h)(1-r)/r), a shift of at most h/4
    // (a/(1+a)^2 <= 1/4). Allow h/2 on every F_i. Positions: the arrest boundary is within
    // h/2 of the exact crossing of the discrete state's own fields, (F^c - r)/(2 g F).
    let cells = 2000;
    let h = 1.0 / cells as f64;
    let (x, w) = discrete::uniform_cells(cells);
    for r in [0.5, 0.7, 0.9] {
        for g in [0.3, 0.5, 0.7] {
            let p = params(r, g);
            let run = discrete::simulate(&Interface::linear(&p, 1.0, x.clone(), w.clone()), 500).unwrap();
            let an = simulate(&p, run.events.len());
            assert_eq!(run.n_precursors(), Some(n_precursors(&p).unwrap()), "(r, g) = ({r}, {g})");
            for (i, df, _, _) in errors(&run, &an) {
                assert!(df <= h / 2.0, "(r, g) = ({r}, {g}) event {i}: dF = {df:e}");
            }
            for e in run.precursors() {
                let crossing = (e.fc - r) / (2.0 * g * e.f);
                assert!((e.x - crossing).abs() <= h / 2.0 + EXACT, "(r, g) = ({r}, {g}) event {}", e.i);
            }
            let shifted = 1.0 / (1.0 + g * (1.0 - h) * (1.0 - r) / r);
            assert!((run.f_limit().unwrap() - shifted).abs() < 1e-9, "(r, g) = ({r}, {g})");
        }
    }
}

#[test]
fn discrete_rejects_bad_interfaces() {
    let p = params(0.9, 0.35);
    let good = Interface::linear(&p, 1.0, discrete::uniform_cells(10).0, discrete::uniform_cells(10).1);
    let mut short = good.clone();
    short.w[3] *= 0.5;
    assert!(discrete::simulate(&short, 5).unwrap_err().to_string().contains("widths sum"));
    let mut nan = good.clone();
    nan.p0[2] = f64::NAN;
    assert!(discrete::simulate(&nan, 5).unwrap_err().to_string().contains("p0[2]"));
    // Cell 0 unloads in shear (s < 0) while its pressure drops fast: it meets its threshold
    // only at p = -1/19 < 0, i.e. after lifting off (sum w s = 0.1 (-1) + 0.9 (11/9) = 1).
    let mut opening = good.clone();
    opening.dp = vec![0.0; 10];
    opening.dp[0] = -20.0;
    opening.s = vec![11.0 / 9.0; 10];
    opening.s[0] = -1.0;
    assert!(discrete::simulate(&opening, 5).unwrap_err().to_string().contains("contact opens"));
}

#[test]
fn compare_on_linear_fields_coincides() {
    // The synthetic "FE" fields are the paper's (p_per_n = 1, p_per_f = 12 (H/L) x/L,
    // tau_per_f = 1): after the conversion mu_d = g/(6 H/L), mu_s = mu_d/r both runs see the
    // same interface up to rounding of 2g/mu_d vs 12 H/L, hence EXACT. 777 nodes so that no
    // arrest point lands on a node (e.g. x_1 = -0.2 exactly at (0.7, 0.5)), where rounding
    // alone would decide whether that node slips.
    for (r, g, hl) in [(0.9, 0.35, 0.1), (0.7, 0.5, 0.05), (0.5, 0.3, 0.2)] {
        let fields = UnitFields::linear(777, hl, 0.01);
        let c = compare(&fields, r, g, 500).unwrap();
        assert!((c.mu_d - g / (6.0 * hl)).abs() < EXACT && (c.mu_s - c.mu_d / r).abs() < EXACT);
        assert_eq!(c.fe.events.len(), c.linear.events.len());
        for (a, b) in c.fe.events.iter().zip(&c.linear.events) {
            assert_eq!(
                (a.nucleation, a.first, a.last, a.stick_slip),
                (b.nucleation, b.first, b.last, b.stick_slip)
            );
            assert!(
                (a.f - b.f).abs() < EXACT && (a.fc - b.fc).abs() < EXACT && (a.fstar - b.fstar).abs() < EXACT
            );
            assert!((a.x - b.x).abs() < EXACT);
        }
        assert_eq!(c.d_n, Some(0));
        assert!(c.d_f1.abs() < EXACT && c.d_f_max.unwrap().abs() < EXACT);
        assert!(c.d_lengths.iter().all(|d| d.abs() < EXACT));
        assert_eq!(c.fe.n_precursors(), Some(n_precursors(&params(r, g)).unwrap()));
    }
}

#[test]
fn compare_sees_a_missing_torque() {
    // FE fields without the torque-induced asymmetry (p_per_f = 0): every node reaches its
    // threshold together, the first event slips the whole contact, so n = 0 against the
    // linear model's n, and F_1 = 1 (the full mu_s N) against 1/(1 + g/r).
    let (r, g) = (0.9, 0.35);
    let mut fields = UnitFields::linear(401, 0.1, 0.01);
    fields.p_per_f = vec![0.0; 401];
    let c = compare(&fields, r, g, 100).unwrap();
    let n_lin = n_precursors(&params(r, g)).unwrap() as i64;
    assert_eq!(c.d_n, Some(-n_lin));
    assert!((c.d_f1 - (1.0 - 1.0 / (1.0 + g / r))).abs() < EXACT);
    assert!(c.d_lengths.is_empty());
}

#[test]
fn compare_rejects_bad_fields() {
    let mut f = UnitFields::linear(101, 0.1, 0.01);
    f.tau_per_f.iter_mut().for_each(|t| *t *= 0.5);
    assert!(compare(&f, 0.9, 0.35, 10).unwrap_err().to_string().contains("tau_per_f integrates"));
    let mut f = UnitFields::linear(101, 0.1, 0.01);
    f.p_per_n.pop();
    assert!(compare(&f, 0.9, 0.35, 10).is_err());
    let f = UnitFields::linear(101, -0.1, 0.01);
    assert!(compare(&f, 0.9, 0.35, 10).is_err());
    assert!(compare(&UnitFields::linear(101, 0.1, 0.01), 1.5, 0.35, 10).is_err());
}

#[test]
fn write_atomic_replaces_whole_files_only() {
    let dir = tmp_dir("atomic");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("a.csv");
    write_atomic(&path, b"old\n").unwrap();
    write_atomic(&path, b"new\n").unwrap();
    assert_eq!(std::fs::read_to_string(&path).unwrap(), "new\n");
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1, "temporary file left behind");

    // Missing directories are created; a parent that is a file is an I/O error.
    write_atomic(&dir.join("sub/b.csv"), b"x").unwrap();
    let under_file = path.join("b.csv");
    assert!(matches!(write_atomic(&under_file, b"x"), Err(Error::Io { .. })));
    assert!(!under_file.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn outputs_have_the_documented_columns_and_no_nan() {
    let p = params(0.9, 0.35);
    let ev = simulate_to_convergence(&p, 1e-6, 200);
    let dir = tmp_dir("outputs");
    let written = report::write_events(&dir, &p, &ev).unwrap();
    assert_eq!(written.len(), 3);
    let events = std::fs::read_to_string(dir.join("events.csv")).unwrap();
    let mut lines = events.lines();
    assert_eq!(
        lines.next(),
        Some("event,F_over_mu_s_N,Fc_over_mu_s_N,x_arrest_over_L,F_relaxed_over_mu_s_N,stick_slip")
    );
    let rows: Vec<Vec<f64>> = lines.map(|l| l.split(',').map(|v| v.parse().unwrap()).collect()).collect();
    assert_eq!(rows.len(), ev.len());
    assert_eq!(rows.iter().filter(|r| r[5] == 0.0).count(), 10);
    assert!(rows.iter().flatten().all(|v| v.is_finite()));
    let loading = std::fs::read_to_string(dir.join("loading.csv")).unwrap();
    assert!(loading.starts_with("Fc_over_mu_s_N,F_over_mu_s_N\n0,0\n"));
    let svg = std::fs::read_to_string(dir.join("fig4.svg")).unwrap();
    assert!(svg.contains("<svg") && svg.contains("dimensionless") && svg.contains("precursor"));
    let mut bad = ev.clone();
    bad[0].x = f64::NAN;
    assert!(report::events_csv(&bad).is_err());

    let map = n_map(8, &tribofe::Cancel::new()).unwrap();
    report::write_map(&dir, &map, 8).unwrap();
    let csv = std::fs::read_to_string(dir.join("n_map.csv")).unwrap();
    assert!(csv.starts_with("r,g,n\n") && csv.lines().count() == 65);
    assert!(std::fs::read_to_string(dir.join("fig5.svg")).unwrap().contains("g = (1 - r)/2"));

    let c = compare(&UnitFields::linear(201, 0.1, 0.01), 0.9, 0.35, 100).unwrap();
    report::write_comparison(&dir, &c).unwrap();
    assert!(std::fs::read_to_string(dir.join("fe_events.csv"))
        .unwrap()
        .starts_with("model,i,F,Fc,x_nucleation,x,Fstar,stick_slip\n"));
    assert!(std::fs::read_to_string(dir.join("fe_extents.svg")).unwrap().contains("FE-fed n = 10"));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn sweep_table_runs_every_geometry() {
    let dir = tmp_dir("sweep");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("sweep.csv");
    let (hs, ts) = ([0.05, 0.1], [0.01, 0.02, 0.05]);
    let rows =
        tribofe::precursors::fe::sweep(&hs, &ts, 0.9, 0.35, 200, |h, t| Ok(UnitFields::linear(201, h, t)))
            .unwrap();
    report::write_sweep(&path, &rows).unwrap();
    assert_eq!(rows.len(), 6);
    assert!(rows.iter().all(|r| r.n_fe == Some(10) && r.n_linear == Some(10) && r.max_abs_d_length < EXACT));
    let csv = std::fs::read_to_string(&path).unwrap();
    assert!(csv.starts_with("H_over_L,t_over_L,n_fe,n_linear,F1_fe,F1_linear,Fmax_fe,Fmax_linear,max_abs_d_length,outside_model\n"));
    assert!(rows.iter().all(|r| r.outside_model.is_none()));
    assert_eq!(csv.lines().count(), 7);
    // A closure returning fields for the wrong geometry is caught.
    let wrong =
        tribofe::precursors::fe::sweep(&hs, &ts, 0.9, 0.35, 200, |_, t| Ok(UnitFields::linear(201, 0.2, t)));
    assert!(wrong.is_err());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn cli_reports_and_rejects() {
    let exe = env!("CARGO_BIN_EXE_tribofe");
    let dir = tmp_dir("cli");
    let ok = Command::new(exe)
        .args(["precursors", "--r", "0.9", "--g", "0.35", "--out"])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(ok.status.success(), "{}", String::from_utf8_lossy(&ok.stderr));
    let stdout = String::from_utf8_lossy(&ok.stdout);
    assert!(stdout.contains("n = 10 precursors") && stdout.contains("F_1 = 0.720000"), "{stdout}");
    assert!(dir.join("events.csv").exists() && dir.join("fig4.svg").exists());
    for bad in [["--r", "1.2"], ["--g", "1.5"], ["--r", "NaN"], ["--g", "abc"]] {
        let out = Command::new(exe).arg("precursors").args(bad).arg("--out").arg(&dir).output().unwrap();
        assert!(!out.status.success(), "{bad:?} accepted");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains("must be") || err.contains("invalid value"), "{bad:?}: {err}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Every CSV under `dir` (relative path, text with the wall-time columns emptied: their
/// headers name seconds).
fn csvs_without_times(dir: &std::path::Path) -> Vec<(PathBuf, String)> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|x| x == "csv") {
                let text = std::fs::read_to_string(&p).unwrap();
                let mut lines = text.lines();
                let header: Vec<&str> = lines.next().unwrap_or("").split(',').collect();
                let timed: Vec<bool> = header.iter().map(|h| h.contains("seconds")).collect();
                let mut kept = header.join(",");
                for l in lines {
                    let cells: Vec<&str> = l
                        .split(',')
                        .enumerate()
                        .map(|(i, c)| if timed.get(i) == Some(&true) { "" } else { c })
                        .collect();
                    kept.push('\n');
                    kept.push_str(&cells.join(","));
                }
                out.push((p.strip_prefix(dir).unwrap().to_path_buf(), kept));
            }
        }
    }
    out.sort();
    out
}

#[test]
fn old_flag_forms_write_the_same_csvs_as_the_subcommands() {
    let exe = env!("CARGO_BIN_EXE_tribofe");
    let scene = ["--length", "0.05"];
    let pairs: [(Vec<&str>, Vec<&str>); 8] = [
        (
            vec!["--events", "7", "--r", "0.8", "--g", "0.5"],
            vec!["model", "--events", "7", "--r", "0.8", "--g", "0.5"],
        ),
        (vec![], vec!["model"]),
        (vec!["--map", "--resolution", "4"], vec!["map", "--resolution", "4"]),
        ([&["--fe"][..], &scene].concat(), [&["fe"][..], &scene].concat()),
        (
            [&["--fe", "--map", "--resolution", "2"][..], &scene].concat(),
            [&["fe-map", "--resolution", "2"][..], &scene].concat(),
        ),
        (
            [&["--fe", "--thin-layer", "0.04"][..], &scene].concat(),
            [&["thin-layer", "--t-over-l", "0.04"][..], &scene].concat(),
        ),
        (
            [&["--fe", "--heights", "0.1"][..], &scene].concat(),
            [&["heights", "--h-over-l", "0.1"][..], &scene].concat(),
        ),
        ([&["--bonded-fields"][..], &scene].concat(), [&["bonded"][..], &scene].concat()),
    ];
    let dir = tmp_dir("forms");
    for (old, new) in pairs {
        let run = |args: &[&str], out: &std::path::Path| {
            let o = Command::new(exe).arg("precursors").args(args).arg("--out").arg(out).output().unwrap();
            assert!(o.status.success(), "{args:?}: {}", String::from_utf8_lossy(&o.stderr));
        };
        let (a, b) = (dir.join("old"), dir.join("new"));
        run(&old, &a);
        run(&new, &b);
        let (ca, cb) = (csvs_without_times(&a), csvs_without_times(&b));
        assert!(!ca.is_empty(), "{old:?} wrote no CSV");
        assert_eq!(ca, cb, "{old:?} and {new:?} differ");
        std::fs::remove_dir_all(&dir).unwrap();
    }
    // The old forms keep their refusals, and are not listed by --help.
    let o =
        Command::new(exe).args(["precursors", "--length", "0.1"]).arg("--out").arg(&dir).output().unwrap();
    assert_eq!(o.status.code(), Some(2));
    let help = Command::new(exe).args(["precursors", "--help"]).output().unwrap();
    let help = String::from_utf8_lossy(&help.stdout);
    assert!(help.contains("fe-map") && !help.contains("--thin-layer <"), "{help}");
}
