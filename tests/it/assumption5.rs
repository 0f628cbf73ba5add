//! The paper's assumption 5 measured as the model needs it
//! (src/studies/dynamic_slide/assumption5.rs): on the short slip-weakening scene, each
//! instability's measures against values recomputed here, by separate loops, from what the
//! run exposes (the pre-event contact forces, the samples, the slips).

use tribofe::interface::events::Operator;
use tribofe::studies::dynamic_slide::{self as ds, DynamicOptions};

#[test]
fn assumption5_measures_match_an_independent_recomputation() {
    let (scene, o) = crate::dynamics::short_weakening(Operator::Dense, 6.0e-6);
    let r = ds::run(&scene, &o, &DynamicOptions::default(), tribofe::Progress::none()).unwrap();
    let c = &r.slide.condensed;
    let (mu_s, mu_d) = (o.law.mu_s(), o.law.mu_d());
    let dc = match o.law {
        tribofe::law::Law::SlipWeakening { dc, .. } => dc,
        _ => unreachable!(),
    };
    let b = &scene.block;
    let (g, t, h) = (b.young / (2.0 * (1.0 + b.poisson)), b.thickness, scene.mesh.h);
    let n = c.n;
    let inst: Vec<_> = r.events.iter().filter(|e| e.record.weakened).collect();
    assert!(inst.len() >= 2, "{} instabilities", inst.len());
    let mut griffith_err = Vec::new();
    let mut fracture_err = Vec::new();
    let mut mu_d_err = Vec::new();
    let mut concentration = Vec::new();
    for e in inst {
        let rec = &e.record;
        let a = e.assumption5.unwrap_or_else(|| panic!("event {}: no measures", e.event));
        let xn = rec.nucleation.expect("nucleated");

        // The pre-event field is the static state at the onset: the base carries N and the
        // drive's F (sum T = -F: the flat resists the drive). The full field is a separate
        // FE solve of the condensed solver's boundary values, so both agree to its round-off
        // (~1e-12 of the load, amplified by the condensation's conditioning): 1e-8.
        let (sp, st) = (rec.p_pre.iter().sum::<f64>(), rec.t_pre.iter().sum::<f64>());
        eprintln!(
            "event {}: sum P - N {:.3e} N, sum T + F {:.3e} mu_s N; arrest {:+.4} L, Griffith {:+.4}, mu_d {:+.4}; dp/p ahead {:.3e} (2.5 t: {:.3e}), dtau/drop ahead {:.3e} (2.5 t: {:.3e}); drop at arrest {:?}",
            e.event,
            (sp - o.n_force) / o.n_force,
            (st + e.f_onset) / (mu_s * o.n_force),
            a.arrest / c.l,
            a.predicted_griffith / c.l,
            a.predicted_mu_d / c.l,
            a.dp_ahead,
            a.dp_far,
            a.dtau_ahead,
            a.dtau_far,
            e.force_drop_at_arrest
        );
        assert!((sp - o.n_force).abs() < 1e-8 * o.n_force, "event {}: sum P {sp} vs N", e.event);
        assert!((st + e.f_onset).abs() < 1e-8 * mu_s * o.n_force, "event {}: sum T {st} vs -F", e.event);

        // The dynamic arrest: the far end of the final run of nodes slipped past D_c/100
        // around the nucleation node, which is events.csv's region on that side.
        let went = |i: usize| rec.slip[i] > dc / 100.0;
        let (mut lo, mut hi) = (xn, xn);
        while lo > 0 && went(lo - 1) {
            lo -= 1;
        }
        while hi + 1 < n && went(hi + 1) {
            hi += 1;
        }
        let far = if c.x[hi] - c.x[xn] >= c.x[xn] - c.x[lo] { hi } else { lo };
        assert!(
            (a.arrest - c.x[far]).abs() < 0.5 * h,
            "event {}: arrest {} vs {}",
            e.event,
            a.arrest,
            c.x[far]
        );
        let region = r.slide.run.events[e.event].region.expect("region");
        assert!(region.0 == far || region.1 == far, "event {}: region {region:?}, tip node {far}", e.event);
        let dir: i64 = if far >= xn { 1 } else { -1 };
        assert_eq!(a.direction, dir as f64, "event {}", e.event);

        // The predictions, by regime.py's form of the rule: walk from the nucleation node
        // toward the tip to the first contact node where tau - mu_d p falls below
        // (mu_s - mu_d) p sqrt(kappa(x)) (Griffith) or below 0 (zero fracture energy); stresses
        // are the nodal forces over the tributary widths, tau > 0 against the drive.
        // The walk starts past the nucleating patch: the nodes around the nucleation node
        // whose slip since the last healing passed D_c/100 at the onset.
        let mut edge = xn as i64;
        while rec.d_pre[edge as usize] > dc / 100.0 && edge + dir >= 0 && edge + dir < n as i64 {
            edge += dir;
        }
        let predict = |griffith: bool| -> f64 {
            let mut i = edge;
            loop {
                let k = i as usize;
                let (p, tau) = (rec.p_pre[k] / c.w[k], -rec.t_pre[k] / c.w[k]);
                if p > 0.0 {
                    let kappa = g * dc / ((mu_s - mu_d) * p * t);
                    let need = if griffith { (mu_s - mu_d) * p * kappa.sqrt() } else { 0.0 };
                    if tau - mu_d * p < need {
                        return c.x[k];
                    }
                }
                if i + dir < 0 || i + dir >= n as i64 {
                    return c.x[k];
                }
                i += dir;
            }
        };
        // The energy and the stress forms of the rule are the same inequality; they could
        // differ only at a node on the threshold to round-off: one node at most.
        let (p0, pg) = (predict(false), predict(true));
        assert!(
            (a.predicted_mu_d - p0).abs() <= h * (1.0 + 1e-9),
            "event {}: {} vs {p0}",
            e.event,
            a.predicted_mu_d
        );
        assert!(
            (a.predicted_griffith - pg).abs() <= h * (1.0 + 1e-9),
            "event {}: {} vs {pg}",
            e.event,
            a.predicted_griffith
        );
        // A finite fracture energy stops a front no later than tau = mu_d p does.
        let d = dir as f64;
        assert!(d * (a.predicted_mu_d - a.predicted_griffith) >= -1e-12, "event {}: {a:?}", e.event);
        assert!(d * (a.predicted_griffith - c.x[edge as usize]) >= -1e-12, "event {}: {a:?}", e.event);
        // The whole body's G (the dense S here) walks the same rule: it ends no later than
        // tau = mu_d p and not before the patch's edge.
        assert!(a.predicted_fracture.is_finite(), "event {}: {a:?}", e.event);
        assert!(d * (a.predicted_mu_d - a.predicted_fracture) >= -1e-12, "event {}: {a:?}", e.event);
        assert!(d * (a.predicted_fracture - c.x[edge as usize]) >= -1e-12, "event {}: {a:?}", e.event);
        fracture_err.push((a.arrest - a.predicted_fracture).abs());
        griffith_err.push((a.arrest - a.predicted_griffith).abs());
        mu_d_err.push((a.arrest - a.predicted_mu_d).abs());

        // The change ahead of the running tip, from the samples up to the arrest (the first
        // sample with the tip at its final place; the record keeps no later one).
        let last = *rec.tip.iter().rev().find(|v| v.is_finite()).unwrap();
        let k_arrest = rec.tip.iter().position(|&v| v == last).unwrap();
        assert_eq!(rec.p_samples.len(), k_arrest + 1, "event {}", e.event);
        let [mut dp_all, mut dtau_all, mut dp_far, mut dtau_far] = [0.0f64; 4];
        for j in 0..=k_arrest {
            let tip = rec.tip[j];
            if tip.is_nan() {
                continue;
            }
            let side = if tip > c.x[xn] {
                1.0
            } else if tip < c.x[xn] {
                -1.0
            } else {
                d
            };
            for i in 0..n {
                let ahead = side * (c.x[i] - tip);
                let p0 = rec.p_pre[i];
                if p0 <= 0.0 || ahead < 0.5 * h {
                    continue;
                }
                let dp = (f64::from(rec.p_samples[j][i]) - p0).abs() / p0;
                let dtau = (f64::from(rec.t_samples[j][i]) - rec.t_pre[i]).abs() / ((mu_s - mu_d) * p0);
                dp_all = dp_all.max(dp);
                dtau_all = dtau_all.max(dtau);
                if ahead > 2.5 * t - 0.5 * h {
                    dp_far = dp_far.max(dp);
                    dtau_far = dtau_far.max(dtau);
                }
            }
        }
        // The same numbers from the same f32 samples: equal to the last bits of f64.
        for (what, ours, theirs) in [
            ("dp ahead", dp_all, a.dp_ahead),
            ("dtau ahead", dtau_all, a.dtau_ahead),
            ("dp 2.5 t ahead", dp_far, a.dp_far),
            ("dtau 2.5 t ahead", dtau_far, a.dtau_far),
        ] {
            assert!(
                (ours - theirs).abs() <= 1e-12 * ours.max(1e-300),
                "event {}: {what} {ours} vs {theirs}",
                e.event
            );
        }
        // The force drop made by the arrest, recomputed.
        let want = (e.f_onset - rec.force[k_arrest]) / (e.f_onset - e.f_after);
        let got = e.force_drop_at_arrest.expect("drop");
        assert!((got - want).abs() <= 1e-12 * want.abs(), "event {}: {got} vs {want}", e.event);
        concentration.push((dtau_all, dtau_far));
    }
    let median = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    let (mg, m0, mf) = (median(&mut griffith_err), median(&mut mu_d_err), median(&mut fracture_err));
    eprintln!(
        "median |arrest - Griffith| {:.2} h, |arrest - whole-body Griffith| {:.2} h, |arrest - (tau = mu_d p)| {:.2} h",
        mg / h,
        mf / h,
        m0 / h
    );
    // The tip moves the field ahead of it (its stress concentration): a measure that reads
    // the pre-event field back as the samples would give 0 in every instability.
    assert!(concentration.iter().all(|(all, _)| *all > 0.0), "{concentration:?}");
    // The Griffith balance is a long-front estimate: it leaves out the cohesive zone
    // (Lambda_0 = 3 h here) and the tip is read to a node, so the median arrest lies within
    // Lambda_0 + h of it (measured: 1 h); the zero-fracture-energy rule, which kappa = 0.51
    // makes wrong by a fair part of the run, is farther (measured: 18 h).
    let zone = tribofe::law::Law::slip_weakening(mu_s, mu_d, dc).unwrap().cohesive_zone(
        g,
        b.poisson,
        o.n_force / b.length,
    );
    assert!(mg <= zone + h, "median |arrest - Griffith| {mg} m, Lambda_0 + h = {} m", zone + h);
    // The whole body's G (measured: 1 h, as the thin-layer rule) by the same bound.
    assert!(mf <= zone + h, "median |arrest - whole-body Griffith| {mf} m, Lambda_0 + h = {} m", zone + h);
    assert!(m0 > zone + h, "median |arrest - (tau = mu_d p)| {m0} m within Lambda_0 + h");
}
