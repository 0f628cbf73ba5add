//! `slide --dynamics` tried as a new user would (issue 43): physical defaults that never
//! follow the mesh, the first run working with its defaults, the paper's control case H = 0,
//! a capped run that keeps what it computed, and the one summary table.

use crate::common::process::{run, Ran};
use std::collections::HashMap;
use std::path::Path;
use std::time::Duration;

/// summary.csv's one row by column name (empty cells left out).
fn summary(dir: &Path) -> HashMap<String, f64> {
    let text = std::fs::read_to_string(dir.join("summary.csv")).unwrap();
    let mut lines = text.lines();
    let head: Vec<&str> = lines.next().unwrap().split(',').collect();
    let row: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(head.len(), row.len(), "{text}");
    assert!(lines.next().is_none(), "one row: {text}");
    head.iter()
        .zip(row)
        .filter(|(_, v)| !v.is_empty())
        .map(|(k, v)| (k.to_string(), v.parse::<f64>().unwrap_or_else(|_| panic!("{k} = {v}"))))
        .collect()
}

fn tribofe(args: &[&str], out: &Path, limit_s: u64) -> Ran {
    let mut a = args.to_vec();
    let o = out.to_str().unwrap();
    a.extend(["--out", o]);
    run(&a, Duration::from_secs(limit_s))
}

/// The short block of the dynamic tests: L = 0.1 m, the paper's t, E, nu, H.
const SHORT: &[&str] = &["slide", "--dynamics", "--law", "slip-weakening", "--length", "0.1"];

#[test]
fn the_default_dc_is_the_same_for_any_h_and_the_mesh_resolves_it() {
    // kappa = G D_c / ((mu_s - mu_d) (N/L) t) = 0.5093 fixes D_c: on the L = 0.1 m block N/L
    // is 4 times the paper's and mu_s - mu_d (from (r, g) at its H/L) 4 times smaller, so D_c
    // is the paper's 2.3107e-7 m again; the cohesive zone is 1.4726 t kappa = 1.5000 mm, so
    // t/4 is the largest whole fraction of t with 3 elements in it.
    let dir = tempfile::tempdir().unwrap();
    let mut dcs = vec![];
    for (name, h) in [("auto", None), ("h25", Some("0.00025"))] {
        let out = dir.path().join(name);
        let mut args = SHORT.to_vec();
        args.extend(["--x-max", "1e-7"]);
        if let Some(h) = h {
            args.extend(["--h", h]);
        }
        let r = tribofe(&args, &out, 120);
        assert_eq!(r.code, 0, "{name}: {}", r.stderr);
        let s = summary(&out);
        dcs.push(s["dc_m"]);
        assert!((s["kappa"] - 0.5093).abs() < 5e-5, "{name}: kappa {}", s["kappa"]);
        assert!((s["lambda0_m"] - 1.5e-3).abs() < 1e-8, "{name}: {}", s["lambda0_m"]);
        let want_h = h.map_or(5e-4, |h| h.parse().unwrap());
        assert_eq!(s["h_m"], want_h, "{name}");
        if h.is_none() {
            assert!(r.stderr.contains("--h not given: h = 5.0000e-4 m (t/4)"), "{}", r.stderr);
        }
    }
    assert!(dcs.iter().all(|&d| d == dcs[0]), "{dcs:?}");
    assert!((dcs[0] / 2.3107e-7 - 1.0).abs() < 1e-12, "{}", dcs[0]);
    // A given h that does not resolve the zone is refused before any work, naming the --h
    // that would (t/4) and the D_c this mesh resolves.
    let out = dir.path().join("coarse");
    let mut args = SHORT.to_vec();
    args.extend(["--h", "0.001"]);
    let r = tribofe(&args, &out, 60);
    assert_eq!(r.code, 2, "{}", r.stderr);
    assert!(r.stderr.contains("invalid --h") && r.stderr.contains("--h 5.0000e-4"), "{}", r.stderr);
    assert!(!out.exists());
}

#[test]
fn the_default_first_run_completes_the_papers_first_cycle_with_precursors() {
    // `tribofe slide --dynamics --law slip-weakening`, nothing else: the paper's scene at
    // D_c = 2.3107e-7 m on the t/4 mesh to the front crossing. Its F_1 and x_1 are the
    // convergence study's (validation/dynamics/converge/table.csv: 0.7350 and -0.4612 at all
    // three meshes; here to 1e-4 of mu_s N and one element, h/L = 1.25e-3).
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("first");
    let r = tribofe(&["slide", "--dynamics", "--law", "slip-weakening"], &out, 900);
    assert_eq!(r.code, 0, "{}", r.stderr);
    let s = summary(&out);
    assert_eq!(s["complete"], 1.0);
    assert_eq!(s["dc_m"], 2.3107e-7);
    assert_eq!(s["h_m"], 5e-4);
    assert!((s["first_advance_F_over_mu_s_N"] - 0.7350).abs() < 1e-4, "{s:?}");
    assert!((s["first_advance_front_over_L"] + 0.4612).abs() < 1.25e-3, "{s:?}");
    assert!(s["front_advances"] >= 5.0 && s["edge_precursors"] >= 1.0, "{s:?}");
    assert_eq!(s["nucleation_at_leading_edge"], 0.0);
    // The largest force before the crossing: 0.951 +- 0.005 over the study's meshes.
    assert!((s["largest_F_before_crossing_over_mu_s_N"] - 0.951).abs() < 0.01, "{s:?}");
    assert!(s["crossing_F_over_mu_s_N"] <= s["largest_F_before_crossing_over_mu_s_N"]);
    let toml = std::fs::read_to_string(out.join("run.toml")).unwrap();
    assert!(toml.contains("first_advance_F_over_mu_s_N") && !toml.contains("incomplete"), "{toml}");
    assert!(!out.join("states.csv").exists(), "--states none is the dynamic default");
    // fronts_t.csv: no front speed above c_p without its cause. The paper's material
    // (E = 2 kPa, nu = 0.4, rho = 1000 kg/m^3): c_p = sqrt(E (1 - nu) / (rho (1 + nu)
    // (1 - 2 nu))) = 2.0702 m/s, c_s = sqrt(E / (2 rho (1 + nu))) = 0.84515 m/s.
    let (e, nu, rho) = (2000.0f64, 0.4f64, 1000.0f64);
    let c_p = (e * (1.0 - nu) / (rho * (1.0 + nu) * (1.0 - 2.0 * nu))).sqrt();
    let c_s = (e / (2.0 * rho * (1.0 + nu))).sqrt();
    let fronts = std::fs::read_to_string(out.join("fronts_t.csv")).unwrap();
    let mut lines = fronts.lines();
    assert_eq!(
        lines.next().unwrap(),
        "event,side,x_over_L,arrival_s,front_time_s,front_speed_m_per_s,front_speed_over_c_s,flag"
    );
    let (mut fast, mut unflagged) = (vec![], vec![]);
    for l in lines {
        let f: Vec<&str> = l.split(',').collect();
        if f[5].is_empty() {
            // The first node reached, or a window reached at once (an infinite speed).
            assert!(f[1] == "0" || !f[7].is_empty(), "a jump without its cause: {l}");
            continue;
        }
        let (v, over) = (f[5].parse::<f64>().unwrap(), f[6].parse::<f64>().unwrap());
        assert!((over * c_s / v - 1.0).abs() < 1e-6, "{l}");
        if v > c_p && f[7].is_empty() {
            fast.push(l.to_string());
        }
        if f[7].is_empty() {
            unflagged.push(v);
        }
    }
    assert!(
        fast.is_empty(),
        "{} front speeds above c_p = {c_p} m/s without a cause: {:?}",
        fast.len(),
        &fast[..fast.len().min(5)]
    );
    // Above c_p with neither preslip nor join in the window (`above_c_p`): rare and near c_p
    // (at most 1.3 c_p). Their count follows the event sequence, which round-off moves after
    // a few dozen events (the precursor count is not converged): 40 of 5 143 rows before the
    // one integrator, 89 of 5 424 after it (its inverse-mass products), so the bound is 3 %
    // and the sharp check the speed; the unflagged fronts run between c_s and c_p (median
    // 1.31 c_s).
    let rows = fronts.lines().count() - 1;
    let above: Vec<f64> = fronts
        .lines()
        .filter(|l| l.ends_with(",above_c_p"))
        .map(|l| l.split(',').nth(5).unwrap().parse().unwrap())
        .collect();
    assert!(above.len() * 100 <= 3 * rows && above.iter().all(|&v| v < 1.5 * c_p), "{above:?} of {rows}");
    unflagged.sort_by(f64::total_cmp);
    let median = unflagged[unflagged.len() / 2];
    assert!(
        unflagged.len() > 300 && median > 0.5 * c_s && median < c_p,
        "{} speeds, median {median}",
        unflagged.len()
    );
    // cycle.svg: one bar per instability (dyn_events.csv's instability = 1); no per-event
    // picture unless asked (--spacetime).
    let dyn_events = std::fs::read_to_string(out.join("dyn_events.csv")).unwrap();
    // (An instability with a slipped region: its columns 8, 9 filled.)
    let inst = dyn_events
        .lines()
        .skip(1)
        .filter(|l| {
            let c: Vec<&str> = l.split(',').collect();
            c[2] == "1" && !c[8].is_empty()
        })
        .count();
    let cycle = std::fs::read_to_string(out.join("cycle.svg")).unwrap();
    assert!(inst > 10, "{inst} instabilities");
    assert_eq!(cycle.matches("class=\"instability\"").count(), inst);
    assert_eq!(cycle.matches(">cycle end").count(), 1, "one crossing marked");
    let pictures = std::fs::read_dir(&out)
        .unwrap()
        .filter(|f| f.as_ref().unwrap().file_name().to_string_lossy().starts_with("spacetime_"));
    assert_eq!(pictures.count(), 0);
    fracture_arrest(&dyn_events, &s);
}

/// The arrests predicted from the pre-event field (dyn_events.csv) on the paper's scene
/// against the dynamic arrest: the thin-layer Griffith rule and the whole body's G(l)
/// (src/studies/dynamic_slide/fracture.rs).
fn fracture_arrest(dyn_events: &str, s: &HashMap<String, f64>) {
    let mut lines = dyn_events.lines();
    let head: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |name: &str| head.iter().position(|&h| h == name).unwrap_or_else(|| panic!("{name}"));
    let (arrest, griffith, fracture, mu_d) = (
        col("arrest_over_L"),
        col("predicted_arrest_griffith_over_L"),
        col("predicted_arrest_fracture_over_L"),
        col("predicted_arrest_mu_d_over_L"),
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').collect::<Vec<&str>>())
        .filter(|c| c[2] == "1" && !c[arrest].is_empty())
        .map(|c| [arrest, griffith, fracture, mu_d].iter().map(|&k| c[k].parse::<f64>().unwrap()).collect())
        .collect();
    assert!(rows.len() > 10, "{} instabilities with an arrest", rows.len());
    let (l, h) = (0.4, s["h_m"]);
    let t = 0.002 / l;
    let first = &rows[0];
    eprintln!(
        "first instability: arrest {:+.5}, Griffith {:+.5}, fracture {:+.5}, mu_d {:+.5} (x/L)",
        first[0], first[1], first[2], first[3]
    );
    // Measured: arrest -0.46125, Griffith -0.45125, fracture -0.4475, tau = mu_d p -0.32875.
    // The fracture prediction is 0.01375 L from the dynamic arrest, not within 0.01 L: the
    // front stops short of both static balances (by 8 and 11 h), on the side of the patch.
    // What holds: the whole body's G and the thin-layer one differ only through the tip's
    // end zone (the body averages the drop over it), so the two predictions lie within the
    // zone's 2.18 t (its decay to 5 %, docs/convergence.md); both are beyond the arrest; and
    // the whole body's prediction is nearer the arrest than the zero-fracture-energy one by
    // far (the paper's rule: 0.13 L off).
    let d = (first[3] - first[0]).signum();
    assert!((first[2] - first[1]).abs() <= 2.18 * t, "{first:?}");
    assert!(d * (first[1] - first[0]) > 0.0 && d * (first[2] - first[0]) > 0.0, "{first:?}");
    assert!((first[2] - first[0]).abs() < 0.25 * (first[3] - first[0]).abs(), "{first:?}");
    // Over every instability the median |arrest - prediction| is within the cohesive zone and
    // a node (Lambda_0 + h), as the thin-layer rule's (tests/it/assumption5.rs).
    let median = |k: usize| {
        let mut e: Vec<f64> = rows.iter().map(|r| (r[0] - r[k]).abs()).collect();
        e.sort_by(f64::total_cmp);
        e[e.len() / 2]
    };
    let zone = (s["lambda0_m"] + h) / l;
    eprintln!(
        "median |arrest - Griffith| {:.5} L, |arrest - fracture| {:.5} L, Lambda_0 + h = {zone:.5} L",
        median(1),
        median(2)
    );
    assert!(median(1) <= zone && median(2) <= zone, "{} {} vs {zone}", median(1), median(2));
}

#[test]
fn the_control_case_h_0_runs_and_its_slip_nucleates_at_the_leading_edge() {
    // The paper's control case: the drive in the interface plane, no torque. The model says
    // no precursors (F_1 = F_max = 1). The block's own shear couple remains: the interior
    // pressure slope goes like (H - t/2) (docs/check.md), negative at H = 0, so the pressure
    // is lowest at the leading edge and slip nucleates there: counted from there, and said.
    let dir = tempfile::tempdir().unwrap();
    // The paper's block (7 s): the model's F_1 = 1 is not reached, slip starts below it.
    let out = dir.path().join("h0");
    let r = tribofe(&["slide", "--dynamics", "--law", "slip-weakening", "--height", "0"], &out, 300);
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert!(r.stdout.contains("g = 0.0000): n = 0, F_1 = 1.0000"), "{}", r.stdout);
    assert!(r.stdout.contains("counted from the leading edge"), "{}", r.stdout);
    let s = summary(&out);
    assert_eq!(s["nucleation_at_leading_edge"], 1.0);
    assert_eq!(s["complete"], 1.0);
    assert!(s["front_advances"] >= 1.0 && s["first_advance_front_over_L"] > 0.0, "{s:?}");
    assert!(s["first_advance_F_over_mu_s_N"] < 0.99, "{s:?}");
    // (r, g) cannot set the coefficients at H = 0; g = 0 at H > 0 points to --height 0.
    for (extra, want) in [
        (&["--height", "0", "--r", "0.9", "--g", "0.35"][..], "--height 0"),
        (&["--r", "0.9", "--g", "0"][..], "--height 0"),
    ] {
        let mut a = SHORT.to_vec();
        a.extend(extra);
        let r = tribofe(&a, &dir.path().join("refused"), 60);
        assert_eq!(r.code, 2, "{extra:?}: {}", r.stderr);
        assert!(r.stderr.contains("invalid --g") && r.stderr.contains(want), "{}", r.stderr);
    }
}

#[test]
fn the_weakening_path_is_in_run_toml_and_summary_csv() {
    // The stepped path by default (weakening_steps = 20), --exact-weakening the exact one
    // (weakening_steps = 0); the small scene to just past its first instability (4.8e-6 m).
    let dir = tempfile::tempdir().unwrap();
    for (extra, path, steps) in [(None, "steps", 20.0), (Some("--exact-weakening"), "exact", 0.0)] {
        let out = dir.path().join(path);
        let mut args = SHORT.to_vec();
        args.extend(["--h", "0.0005", "--x-max", "4.9e-6"]);
        args.extend(extra);
        let r = tribofe(&args, &out, 300);
        assert_eq!(r.code, 0, "{}", r.stderr);
        assert_eq!(summary(&out)["weakening_steps"], steps);
        let toml = std::fs::read_to_string(out.join("run.toml")).unwrap();
        assert!(toml.contains(&format!("weakening_path = \"{path}\"")), "{toml}");
        let said =
            if extra.is_some() { "followed exactly (--exact-weakening)" } else { "in steps of D_c/20" };
        assert!(r.stderr.contains(said), "{}", r.stderr);
    }
    // Refused where it cannot act, naming the flags.
    let mut args = SHORT.to_vec();
    args.extend(["--exact-weakening", "--weakening-steps", "40"]);
    let r = tribofe(&args, &dir.path().join("both"), 60);
    assert_eq!(r.code, 2);
    assert!(r.stderr.contains("--exact-weakening") && r.stderr.contains("--weakening-steps"), "{}", r.stderr);
    let mut args = SHORT.to_vec();
    args.extend(["--exact-weakening", "--drive-velocity", "1e-5", "--x-max", "1e-6"]);
    let r = tribofe(&args, &dir.path().join("velocity"), 60);
    assert_eq!(r.code, 2);
    assert!(r.stderr.contains("--exact-weakening") && r.stderr.contains("--drive-velocity"), "{}", r.stderr);
}

#[test]
fn the_event_end_rule_is_in_run_toml_and_the_header() {
    // energy by default, slip when asked; refused where no event ends by it.
    let dir = tempfile::tempdir().unwrap();
    for (extra, name, said) in [
        (None, "energy", "ends at rest (kinetic energy 1e-6 of its dissipation, --event-end energy)"),
        (Some("slip"), "slip", "the thickness period (--event-end slip)"),
    ] {
        let out = dir.path().join(name);
        let mut args = SHORT.to_vec();
        args.extend(["--h", "0.0005", "--x-max", "4.9e-6"]);
        if let Some(e) = extra {
            args.extend(["--event-end", e]);
        }
        let r = tribofe(&args, &out, 300);
        assert_eq!(r.code, 0, "{}", r.stderr);
        let toml = std::fs::read_to_string(out.join("run.toml")).unwrap();
        assert!(toml.contains(&format!("event_end = \"{name}\"")), "{toml}");
        assert!(r.stderr.contains(said), "{}", r.stderr);
    }
    let mut args = SHORT.to_vec();
    args.extend(["--event-end", "slip", "--drive-velocity", "1e-5", "--x-max", "1e-6"]);
    let r = tribofe(&args, &dir.path().join("velocity"), 60);
    assert_eq!(r.code, 2);
    assert!(r.stderr.contains("--event-end") && r.stderr.contains("--drive-velocity"), "{}", r.stderr);
}

#[test]
fn a_run_that_meets_a_cap_writes_what_it_computed_and_exits_incomplete() {
    // The event cap met midway: exit 5, the tables up to there, the cap in run.toml and on
    // stderr; the summary says complete = 0.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("capped");
    let mut args = SHORT.to_vec();
    args.extend(["--max-events", "40"]);
    let r = tribofe(&args, &out, 300);
    assert_eq!(r.code, 5, "{}", r.stderr);
    assert!(r.stderr.contains("incomplete: --max-events = 40 met"), "{}", r.stderr);
    let s = summary(&out);
    assert_eq!(s["complete"], 0.0);
    let events = std::fs::read_to_string(out.join("events.csv")).unwrap();
    assert_eq!(events.lines().count(), 1 + 40, "{events}");
    let toml = std::fs::read_to_string(out.join("run.toml")).unwrap();
    assert!(toml.contains("incomplete = \"--max-events = 40 met"), "{toml}");
}

#[test]
fn rupture_regularises_the_normal_stress_by_default_and_warns_without_it() {
    // The default is the normal-stress lag T = 1 ms (run.toml's scene records it); the spec's
    // instantaneous normal stress (--normal-lag 0) on a rigid flat is warned about, on the
    // symmetric fault (normal stress constant) not. Refused: a negative T.
    let dir = tempfile::tempdir().unwrap();
    let short = ["rupture", "--t-end", "0.01"];
    let with = |extra: &[&str], name: &str| {
        let mut a = short.to_vec();
        a.extend(extra);
        tribofe(&a, &dir.path().join(name), 120)
    };
    let d = with(&[], "default");
    assert_eq!(d.code, 0, "{}", d.stderr);
    assert!(!d.stderr.contains("warning"), "{}", d.stderr);
    let i = with(&["--normal-lag", "0"], "instantaneous");
    assert_eq!(i.code, 0, "{}", i.stderr);
    assert!(i.stderr.contains("warning: the instantaneous normal stress on a rigid flat"), "{}", i.stderr);
    let s = with(&["--normal-lag", "0", "--contact", "symmetric"], "symmetric");
    assert!(s.code == 0 && !s.stderr.contains("warning"), "{}", s.stderr);
    let n = with(&["--normal-lag", "-1e-3"], "negative");
    assert_eq!(n.code, 2, "{}", n.stderr);
    assert!(n.stderr.contains("--normal-lag"), "{}", n.stderr);
    // The default's force drop differs from the instantaneous run's: the lag acts.
    let drop = |name: &str| -> String {
        let s = std::fs::read_to_string(dir.path().join(name).join("summary.csv")).unwrap();
        s.lines().nth(1).unwrap().split(',').next().unwrap().to_string()
    };
    assert_ne!(drop("default"), drop("instantaneous"));
}

#[test]
fn fronts_come_from_arrival_times_and_the_pictures_show_the_activity() {
    // The short scene (L = 0.1 m, h = 0.5 mm, X to 6e-6 m: 2-3 s); its instability whose
    // front runs farthest outside the pre-slipped zone (the first ones lie inside theirs).
    use tribofe::interface::events::Operator;
    use tribofe::report::dynamic_slide::{self as report, Spacetime};
    use tribofe::studies::dynamic_slide::{self as ds, fronts};
    let (scene, o) = crate::dynamics::short_weakening(Operator::Dense, 6e-6);
    let r = ds::run(&scene, &o, &ds::DynamicOptions::default(), tribofe::Progress::none()).unwrap();
    let c = &r.slide.condensed;
    let free = |e: &ds::DynEvent| {
        let arr = fronts::arrivals(&e.record, &c.x, scene.block.thickness, r.speeds.c_p);
        [-1, 1]
            .map(|s| arr.iter().filter(|a| a.side == s && a.cause == fronts::Cause::None).count())
            .into_iter()
            .max()
            .unwrap_or(0)
    };
    let e = r.events.iter().filter(|e| e.record.weakened).max_by_key(|e| free(e)).expect("an instability");
    let rec = &e.record;
    // The threshold is the law's: 1 % of (mu_s - mu_d) (N/L) / (rho c_s).
    let (mu_s, mu_d) = (o.law.mu_s(), o.law.mu_d());
    let want = 0.01 * (mu_s - mu_d) * (o.n_force / scene.block.length) / (scene.block.density * r.speeds.c_s);
    assert!((rec.arrival_rate / want - 1.0).abs() < 1e-12, "{} vs {want}", rec.arrival_rate);
    // Independently, from the samples: a node's arrival is the first sample above the
    // threshold, late by less than one sample interval dts on the per-step arrival. Over the
    // longest unflagged stretch of one side, the mean speed from the samples and from the
    // front times then agree within dts / (time between the two ends) each way.
    let arr = fronts::arrivals(rec, &c.x, scene.block.thickness, r.speeds.c_p);
    let dts = rec.t[1] - rec.t[0];
    let sampled = |i: usize| -> f64 {
        let k = rec.rates.iter().position(|v| f64::from(v[i]) > rec.arrival_rate).unwrap();
        rec.t[k]
    };
    let side = |s: i32| arr.iter().filter(move |a| a.side == s && a.cause == fronts::Cause::None);
    let best = [-1, 1].into_iter().max_by_key(|&s| side(s).count()).unwrap();
    let run: Vec<&fronts::Arrival> = side(best).collect();
    assert!(run.len() >= 9, "{} unflagged nodes on side {best}: {arr:?}", run.len());
    let (a, b) = (run[0], run[run.len() - 1]);
    assert!(run.iter().all(|p| p.own == p.front), "no join inside the stretch");
    let dist = (c.x[b.node] - c.x[a.node]).abs();
    let (t_csv, t_samples) = (b.front - a.front, sampled(b.node) - sampled(a.node));
    assert!(t_csv > 10.0 * dts, "{t_csv} s over {dist} m: too short for the check");
    let (v_csv, v_samples) = (dist / t_csv, dist / t_samples);
    assert!(
        (t_samples - t_csv).abs() < dts,
        "front times {t_csv} s, from the samples {t_samples} s (dts {dts})"
    );
    assert!(v_csv < r.speeds.c_p && v_csv > 0.05 * r.speeds.c_s, "{v_csv} m/s");
    eprintln!(
        "mean front speed {v_csv:.4} m/s (samples {v_samples:.4}) over {dist:.4e} m; c_s {:.4}",
        r.speeds.c_s
    );
    // A windowed speed inside the stretch (its window, 1 t either side, all in it): the
    // least-squares slope of the sampled arrivals against distance over the same nodes. Each
    // sampled time is off by [0, dts) from the per-step one, so the slopes differ by at most
    // dts sum|r - mean r| / sum (r - mean r)^2.
    let t = scene.block.thickness;
    let first = arr[0].node;
    let r_of = |p: &fronts::Arrival| (c.x[p.node] - c.x[first]).abs();
    let around = |m: &fronts::Arrival| -> Vec<&&fronts::Arrival> {
        run.iter().filter(|p| (r_of(p) - r_of(m)).abs() <= t * (1.0 + 1e-9)).collect()
    };
    let full = 2 * (t / scene.mesh.h).round() as usize + 1;
    let m = *run[run.len() / 2..]
        .iter()
        .chain(&run[..run.len() / 2])
        .find(|m| around(m).len() == full)
        .expect("a window in the stretch");
    let win = around(m);
    let n = win.len() as f64;
    let rm = win.iter().map(|p| r_of(p)).sum::<f64>() / n;
    let tm = win.iter().map(|p| sampled(p.node)).sum::<f64>() / n;
    let sxx = win.iter().map(|p| (r_of(p) - rm).powi(2)).sum::<f64>();
    let beta = win.iter().map(|p| (r_of(p) - rm) * (sampled(p.node) - tm)).sum::<f64>() / sxx;
    let bound = dts * win.iter().map(|p| (r_of(p) - rm).abs()).sum::<f64>() / sxx;
    assert!(
        (beta - 1.0 / m.speed).abs() <= bound,
        "windowed speed {} m/s, from the samples {} m/s",
        m.speed,
        1.0 / beta
    );

    // The space-time picture: cropped to the activity, log colour bar with a tick per decade,
    // titles to 4 significant digits.
    let svg = report::spacetime_svg(&r, e);
    let t_end = report::spacetime_end(rec);
    assert!(t_end < 0.8 * rec.duration, "crop {t_end} of {} s (measured 0.73)", rec.duration);
    let active = |k: usize| rec.rates[k].iter().any(|&v| f64::from(v) > rec.arrival_rate);
    let last = (0..rec.rates.len()).rev().find(|&k| active(k)).unwrap();
    assert!(
        rec.t[last] <= t_end && t_end <= 1.05 * rec.t[last] + 1e-12,
        "last active sample {} s, shown to {t_end} s",
        rec.t[last]
    );
    let ticks = svg.matches("class=\"cbar-tick\"").count();
    assert!(ticks >= 3, "{ticks} colour-bar ticks");
    let title = svg.split("class=\"title\"").nth(1).unwrap().split("</text>").next().unwrap();
    for w in title.split(|ch: char| !(ch.is_ascii_digit() || ch == '.' || ch == 'e' || ch == '-')) {
        let mant = w.split('e').next().unwrap().trim_start_matches(['-', '0', '.']);
        if w.parse::<f64>().is_ok() && w.contains('.') {
            assert!(mant.chars().filter(|ch| ch.is_ascii_digit()).count() <= 4, "{w} in {title}");
        }
    }
    assert_eq!(svg.matches("class=\"guide\"").count(), 4, "c_s and c_R both ways");
    // cycle.svg: one bar per instability; per-event pictures only as asked.
    let inst = r.events.iter().filter(|e| e.record.weakened).count();
    assert_eq!(report::cycle_svg(&r).matches("class=\"instability\"").count(), inst);
    let dir = tempfile::tempdir().unwrap();
    let names = |sp: &Spacetime, d: &str| -> Vec<String> {
        let p = dir.path().join(d);
        std::fs::create_dir_all(&p).unwrap();
        report::write(&r, &p, "", false, sp).unwrap();
        let mut v: Vec<String> = std::fs::read_dir(&p)
            .unwrap()
            .map(|f| f.unwrap().file_name().into_string().unwrap())
            .filter(|f| f.ends_with(".svg") && f != "fig4_fe.svg" && f != "fronts.svg")
            .collect();
        v.sort();
        v
    };
    assert_eq!(names(&Spacetime::None, "none"), ["cycle.svg"]);
    // Each space-time picture has its contact-area picture A/A0 = p/p_mean beside it (issue 49).
    assert_eq!(
        names(&Spacetime::Events(vec![e.event]), "one"),
        [
            format!("contact_area_{:06}.svg", e.event),
            "cycle.svg".to_string(),
            format!("spacetime_{:06}.svg", e.event)
        ]
    );
    let all = names(&Spacetime::All, "all");
    assert_eq!(all.iter().filter(|f| f.starts_with("spacetime_")).count(), inst);
    assert_eq!(all.iter().filter(|f| f.starts_with("contact_area_")).count(), inst);
    let area = report::contact_area_svg(&r, e).unwrap();
    assert!(
        area.contains("contact area A(x,t)/A(x,onset)") && area.matches("class=\"cbar-tick\"").count() >= 2
    );
    assert_eq!("3,17".parse::<Spacetime>().unwrap(), Spacetime::Events(vec![3, 17]));
    let err = "3,x".parse::<Spacetime>().unwrap_err().to_string();
    assert!(err.contains("--spacetime"), "{err}");
}

mod fronts_unit {
    use tribofe::dynamics::driven::EventRecord;
    use tribofe::studies::dynamic_slide::fronts::{arrivals, Cause};

    fn record(arrival: Vec<f64>) -> EventRecord {
        let n = arrival.len();
        EventRecord { arrival, d_pre: vec![0.0; n], threshold: 1e-9, ..Default::default() }
    }

    #[test]
    fn a_steady_front_has_its_speed_and_a_patch_ahead_is_a_join() {
        // Nodes 1 mm apart, t = 2 mm: a front from node 3 at 0.5 m/s to the right and
        // 0.25 m/s to the left, exactly; then node 8 arrives early (a patch of its own).
        let x: Vec<f64> = (0..12).map(|i| i as f64 * 1e-3).collect();
        let mut a: Vec<f64> =
            x.iter().map(|&xi| if xi >= 3e-3 { (xi - 3e-3) / 0.5 } else { (3e-3 - xi) / 0.25 }).collect();
        let r = arrivals(&record(a.clone()), &x, 2e-3, 2.0);
        assert_eq!((r[0].node, r[0].side), (3, 0));
        assert_eq!(r.len(), 12);
        for f in &r[1..] {
            let want = if f.side > 0 { 0.5 } else { 0.25 };
            assert!((f.speed / want - 1.0).abs() < 1e-12, "{f:?}");
            assert_eq!(f.cause, Cause::None);
        }
        a[8] = 1e-3; // before the front's 10 ms
        let r = arrivals(&record(a), &x, 2e-3, 2.0);
        let at = |k: usize| r.iter().find(|f| f.node == k).unwrap();
        assert_eq!(at(8).front, 8e-3, "the front reaches 8 when 7 has arrived (8 ms)");
        assert_eq!(at(8).cause, Cause::Join);
        assert_eq!(at(4).cause, Cause::None, "8 is 4 mm = 2 t from 4: outside its window");
        // A node that slipped before the event flags the windows holding it.
        let mut rec = record(vec![0.0, 1.0, 2.0, 3.0]);
        rec.d_pre[0] = 1.0;
        let r = arrivals(&rec, &x[..4], 1e-3, 2.0);
        assert!(
            r[0].cause == Cause::Preslip && r[1].cause == Cause::Preslip && r[3].cause == Cause::None,
            "{r:?}"
        );
        // Above c_p with neither cause: named as such.
        let r = arrivals(&record(x.iter().map(|&xi| xi / 3.0).collect()), &x, 2e-3, 2.0);
        assert!(r[1..].iter().all(|f| f.cause == Cause::AboveCp && (f.speed - 3.0).abs() < 1e-9), "{r:?}");
    }
}
