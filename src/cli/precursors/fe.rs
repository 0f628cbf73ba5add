//! `precursors fe` and `precursors fe-map`: the paper's figs. 4 and 5 from the frictional FE
//! on the scene, next to the model.

use super::{fe_scene, run_file, spinner, write_whole, OutArgs, RgArgs, CONVERGED, MAX_DEFAULT_EVENTS};
use tribofe::precursors::{self, Params};
use tribofe::report::precursors as report;
use tribofe::Error;

#[derive(clap::Args, Debug)]
pub struct FeArgs {
    #[command(flatten)]
    pub rg: RgArgs,
    /// Stick-slip cycles per run, each ending when the slip has crossed the interface (a
    /// whole slip, or a front crossing over several events).
    #[arg(long, default_value_t = tribofe::studies::precursors_fe::DEFAULT_FIG4_CYCLES)]
    pub cycles: usize,
    /// The paper rule's residual shear mu_d p at the `relaxed` equilibrium or `pre-event`
    /// (the paper's mu_d p(x, F_i)); as `slide --residual`.
    #[arg(long, default_value = "relaxed")]
    pub residual: tribofe::law::Residual,
    /// The paper rule's back-slip: `allowed` or `forbidden`; as `slide --backslip`.
    #[arg(long, default_value = "allowed", value_parser = ["allowed", "forbidden"])]
    pub backslip: String,
    #[command(flatten)]
    pub scene: super::super::check::SceneArgs,
    #[command(flatten)]
    pub out: OutArgs,
}

#[derive(clap::Args, Debug)]
pub struct FeMapArgs {
    /// Grid points per axis (cell centres), 2..=400.
    #[arg(long, default_value_t = tribofe::studies::precursors_fe::DEFAULT_FIG5_RESOLUTION)]
    pub resolution: usize,
    /// Event rules to run in every cell, comma separated: paper, overdamped (about 10 s for
    /// 20 x 20 on the paper's scene; overdamped adds about 4 minutes, and 164 of its 400 cells
    /// exceed the event cap).
    #[arg(long, value_delimiter = ',', default_value = tribofe::studies::precursors_fe::DEFAULT_FIG5_RULES[0].name())]
    pub rules: Vec<tribofe::law::Rule>,
    /// Events per cell before the cell is reported as capped (grey).
    #[arg(long, default_value_t = tribofe::studies::precursors_fe::DEFAULT_FIG5_MAX_EVENTS)]
    pub max_events: usize,
    #[command(flatten)]
    pub scene: super::super::check::SceneArgs,
    #[command(flatten)]
    pub out: OutArgs,
}

/// FE fig. 4: the frictional FE for each event rule next to the analytic iteration.
pub fn fe(args: FeArgs) -> tribofe::Result<()> {
    let cycles = args.cycles;
    let p = Params::new(args.rg.r, args.rg.g)?;
    let scene = fe_scene(&args.scene, &args.out)?;
    let bar = spinner("precursors fe: one run per event rule");
    let cancel = tribofe::Cancel::new();
    let paper = tribofe::law::PaperOptions { residual: args.residual, backslip: args.backslip == "allowed" };
    let runs = tribofe::studies::precursors_fe::fig4_with(
        &scene,
        p.r(),
        p.g(),
        cycles,
        paper,
        &cancel,
        tribofe::Progress::none(),
    )?;
    bar.finish_and_clear();
    if runs.iter().all(|r| r.is_err()) {
        return runs.into_iter().find_map(|r| r.err()).map_or(Ok(()), Err);
    }
    let n = precursors::n_precursors(&p)?;
    let model = precursors::simulate_to_convergence(&p, CONVERGED, MAX_DEFAULT_EVENTS);
    outln!(
        "r = {}, g = {} (dimensionless; F in units of mu_s N, x in units of L), H/L = {:.4}, t/L = {:.4}",
        p.r(),
        p.g(),
        scene.loading.height / scene.block.length,
        scene.block.thickness / scene.block.length
    );
    let f = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.4}"));
    outln!(
        "{:>12} {:>6} {:>8} {:>10} {:>9} {:>9} {:>9} {:>10}",
        "",
        "n",
        "n > 5t",
        "n advance",
        "F_1",
        "x_1",
        "F_max",
        "violation"
    );
    outln!(
        "{:>12} {n:>6} {n:>8} {n:>10} {:>9.4} {:>9.4} {:>9.4} {:>10}",
        "model",
        p.f1(),
        model[0].x,
        p.f_max(),
        "-"
    );
    for (rule, run) in tribofe::studies::precursors_fe::RULES.iter().zip(&runs) {
        match run {
            Ok(r) => {
                let c = &r.cmp;
                outln!(
                    "{:>12} {:>6} {:>8} {:>10} {:>9} {:>9} {:>9} {:>10.1e}",
                    rule.name(),
                    c.n_fe,
                    c.n_fe_long,
                    c.n_fe_advancing,
                    f(c.f1_fe),
                    f(c.x1_fe),
                    f(c.f_max_fe),
                    r.worst_violation
                );
            }
            Err(e) => outln!("{:>12} refused: {e}", rule.name()),
        }
    }
    if paper != tribofe::law::PaperOptions::default() {
        outln!(
            "rule paper with residual {} and back-slip {} (docs/precursors.md)",
            paper.residual.name(),
            if paper.backslip { "allowed" } else { "forbidden" }
        );
    }
    outln!("n: every precursor; > 5t: the long ones; n advance: the count to compare with the model's n (the least sensitive to the mesh); F_1, x_1: its first");
    outln!("{}", tribofe::precursors::definition::DEFINITION);
    outln!("\nthe model's field assumptions measured on each run (states before the end of the first cycle; interior: > 5 t from the ends):");
    outln!(
        "{:>12} {:>11} {:>11} {:>11} {:>11} {:>11}",
        "",
        "1: shear",
        "1: tip",
        "2: pressure",
        "3: F_corner",
        "3: x_nucl"
    );
    for (rule, run) in tribofe::studies::precursors_fe::RULES.iter().zip(&runs) {
        if let Ok(r) = run {
            let e = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.2e}"));
            let fc = &r.fields;
            outln!(
                "{:>12} {:>11} {:>11} {:>11} {:>11} {:>11}",
                rule.name(),
                e(fc.shear_far),
                e(fc.shear_tip),
                e(fc.pressure),
                f(fc.f_corner),
                f(fc.x_nucleation)
            );
        }
    }
    outln!("1: largest |tau - F^c/L|/(F^c/L) on never-slipped nodes > 5 t ahead of the front; tip: tau/(F^c/L) - 1 just ahead of it");
    outln!("2: largest |p - (N/L + 12 F H x/L^3)|/(N/L); 3: F/(mu_s N) when the trailing node opens or creeps, x/L where the first counted precursor nucleated");
    let results = [
        ("r", toml::Value::from(p.r())),
        ("g", toml::Value::from(p.g())),
        ("cycles", toml::Value::from(cycles as i64)),
        ("model_precursors", toml::Value::from(n as i64)),
    ];
    write_whole(&args.out.out, args.out.force, |dir, inv| {
        let mut w = report::write_fe_fig4(dir, &p, &model, &runs, inv, &scene)?;
        w.push(run_file(dir, inv, Some(&scene), &results)?);
        Ok(w)
    })?;
    outln!("wrote {}/{{summary.csv, run.toml, model/, paper/, overdamped/}}", args.out.out.display());
    Ok(())
}

/// FE fig. 5: n over the (r, g) grid from the frictional FE for each rule asked for, next to
/// the model's map.
pub fn fe_map(args: FeMapArgs) -> tribofe::Result<()> {
    use tribofe::studies::precursors_fe::{self as pfe, RULES};
    let resolution = args.resolution;
    if args.max_events == 0 {
        return Err(Error::input("--max-events", "need at least one event per cell"));
    }
    let rules: Vec<_> = RULES.iter().copied().filter(|r| args.rules.contains(r)).collect();
    let scene = fe_scene(&args.scene, &args.out)?;
    let bar = indicatif::ProgressBar::new((resolution * resolution) as u64).with_style(
        indicatif::ProgressStyle::with_template("{bar:40} {pos}/{len} cells, {elapsed} (eta {eta})").unwrap(),
    );
    let tick = |_: &tribofe::Tick| bar.inc(1);
    let clock = std::time::Instant::now();
    let cells = pfe::fig5(
        &scene,
        resolution,
        &rules,
        args.max_events,
        &tribofe::Cancel::new(),
        tribofe::Progress::new(&tick),
    )?;
    bar.finish_and_clear();
    let wall = clock.elapsed().as_secs_f64();
    outln!(
        "FE fig. 5 on a {0} x {0} grid (H/L = {1:.4}, t/L = {2:.4}), {3:.1} s wall on {4} threads; per cell at most {5} events",
        resolution,
        scene.loading.height / scene.block.length,
        scene.block.thickness / scene.block.length,
        wall,
        rayon::current_num_threads(),
        args.max_events
    );
    for (k, rule) in RULES.iter().enumerate().filter(|(_, r)| rules.contains(r)) {
        let runs: Vec<_> = cells.iter().filter_map(|c| c.runs[k]).collect();
        let count = |s: &str| runs.iter().filter(|r| r.status() == s).count();
        let seconds: f64 = runs.iter().map(|r| r.seconds()).sum();
        let st = pfe::fig5_stats(&cells, k, resolution);
        outln!(
            "{:>12}: {} done ({} ended by a front crossing), {} capped, {} refused; {:.1} s in cells; precursors or none as the model in {}/{} finished cells",
            rule.name(),
            count("done"),
            st.crossings,
            count("capped"),
            count("refused"),
            seconds,
            st.agree,
            st.done
        );
        let pc = |v: Option<[f64; 3]>| {
            v.map_or("-".to_string(), |[m, a, b]| {
                format!("median {:+.1} %, from {:+.1} to {:+.1} %", 100.0 * m, 100.0 * a, 100.0 * b)
            })
        };
        outln!("{:>12}  first-cycle peak against the model's F_max: {}", "", pc(st.f_max_dev));
        outln!(
            "{:>12}  n advancing over the model's n (cells with n >= 3): {}",
            "",
            st.n_ratio.map_or("-".to_string(), |[m, a, b]| format!("median {m:.2}, from {a:.2} to {b:.2}"))
        );
        outln!(
            "{:>12}  first g with a precursor minus (1 - r)/2: {}; steps up in g where n falls: {}",
            "",
            st.boundary_offset.map_or("-".to_string(), |[a, b]| format!("from {a:+.3} to {b:+.3}")),
            st.decreases_in_g
        );
        if let Some([m, a, b]) = st.capped_precursors {
            outln!(
                "{:>12}  capped cells: {m:.0} precursors at the cap (median, from {a:.0} to {b:.0}); {} of {} past the model's F_max",
                "",
                st.capped_above_f_max,
                st.capped
            );
        }
    }
    let what = [
        ("resolution", resolution.to_string()),
        ("max_events_per_cell", args.max_events.to_string()),
        ("rules", rules.iter().map(|r| r.name()).collect::<Vec<_>>().join(",")),
        ("wall_seconds", format!("{wall:.1}")),
    ];
    write_whole(&args.out.out, args.out.force, |dir, inv| {
        report::write_fe_fig5(dir, &cells, resolution, &what, inv, &scene)
    })?;
    outln!(
        "counts: n, the advancing precursors before the first whole slip or front crossing (the slipped nodes joining edge to edge); capped: over --max-events, its count every precursor among the recorded events (the cascade the cap cut left out; a lower bound)"
    );
    outln!("{}", tribofe::precursors::definition::DEFINITION);
    outln!("wrote {}/{{fig5_fe.csv, boundary_fe.csv, fig5_fe.svg, run.toml}}", args.out.out.display());
    Ok(())
}
