//! `tribofe precursors`: the paper's event iteration for one (r, g), or the n(r, g) map.
//! Over 600 lines: one flag set drives eight modes (model, map, FE fig. 4, FE map, thin layer,
//! heights, D_c, bonded fields), each a short function printing its own table; they share the
//! argument checks and the folder writing here.

use std::path::{Path, PathBuf};
use tribofe::linalg::solve::SolverOptions;
use tribofe::precursors::{self, Event, Params};
use tribofe::report::precursors as report;
use tribofe::report::run_file::Invocation;
use tribofe::Error;

/// Events are iterated until |F - F_max| < this (or MAX_DEFAULT_EVENTS) unless --events is given.
const CONVERGED: f64 = 1e-6;
const MAX_DEFAULT_EVENTS: usize = 200;
/// Largest --events: the iteration reaches its stick-slip limit cycle within ~200 events, and
/// each event printed and written costs ~100 bytes (10 MB at the cap).
const MAX_EVENTS: usize = 100_000;

#[derive(clap::Args, Debug)]
pub struct Args {
    /// r = mu_d/mu_s, in (0, 1). Default: the paper's fig. 4 case.
    #[arg(long, default_value_t = 0.9)]
    r: f64,
    /// g = 6 mu_d H/L, in (0, 1). Default: the paper's fig. 4 case.
    #[arg(long, default_value_t = 0.35)]
    g: f64,
    /// Output directory (created if needed).
    #[arg(long, default_value = "out/precursors")]
    out: PathBuf,
    /// Replace the --out folder even if it holds files tribofe did not write (they are deleted).
    #[arg(long)]
    force: bool,
    /// Number of events [default: until |F - F_max| < 1e-6, at most 200].
    #[arg(long)]
    events: Option<usize>,
    /// Compute the number of precursors n over the (r, g) square instead (fig. 5); with --fe,
    /// from the frictional FE next to the model.
    #[arg(long, conflicts_with_all = ["r", "g", "events"])]
    map: bool,
    /// The paper's fig. 4 from the frictional FE on the scene (rigid plate, QUA4): one run per
    /// event rule (paper, overdamped) next to the analytic iteration; writes summary.csv and
    /// a folder per rule and one for the model. With --map, the FE fig. 5.
    #[arg(long)]
    fe: bool,
    /// With --fe: stick-slip cycles per run, each ending when the slip has crossed the
    /// interface (a whole slip, or a front crossing over several events) [default: 2].
    #[arg(long, requires = "fe", conflicts_with = "map")]
    cycles: Option<usize>,
    /// With --fe: the thin-layer study instead, the `paper` rule at (r, g) on blocks of these
    /// t/L (comma separated, e.g. 0.02,0.01,0.005,0.0025,0.00125) at the scene's L and H/L, h
    /// = t with 2 elements through t; writes thin_layer.csv and thin_layer.svg.
    #[arg(long, value_delimiter = ',', requires = "fe", conflicts_with_all = ["map", "cycles"])]
    thin_layer: Option<Vec<f64>>,
    /// With --fe: the height-of-drive study instead, the `paper` rule with the coefficients of
    /// (r, g) at the scene's H kept fixed, at these H/L (comma separated; g = 6 mu_d H/L must
    /// stay below 1); writes heights.csv and heights.svg.
    #[arg(long, value_delimiter = ',', requires = "fe", conflicts_with_all = ["map", "cycles", "thin_layer"])]
    heights: Option<Vec<f64>>,
    /// With --fe: the event-rule study instead, the `paper` rule and slip-weakening with each
    /// of these D_c (m, comma separated) at (r, g) on the scene, one cycle; writes dc.csv,
    /// dc.svg and each run's fig. 4 in its own folder. Resolved when the nucleation length G D_c/((mu_s - mu_d) N/L) spans h.
    #[arg(long, value_delimiter = ',', requires = "fe", conflicts_with_all = ["map", "cycles", "thin_layer", "heights"])]
    dc: Option<Vec<f64>>,
    /// With --fe --map: event rules to run in every cell, comma separated: paper, overdamped
    /// (about 10 s for 20 x 20 on the paper's scene; overdamped adds about 4 minutes, and 164
    /// of its 400 cells exceed the event cap).
    #[arg(long, value_delimiter = ',', default_value = "paper", requires = "fe")]
    rules: Vec<tribofe::interface::law::Rule>,
    /// With --fe --map: events per cell before the cell is reported as capped (grey); with
    /// --dc, per run before the run is refused.
    #[arg(long, default_value_t = 2000, requires = "fe")]
    max_events: usize,
    /// The earlier comparison: the 1D model fed with the bonded FE interface fields (ill-posed
    /// at the singular corners, validation/precursors/README.md).
    #[arg(long, conflicts_with_all = ["map", "fe"])]
    bonded_fields: bool,
    /// With --bonded-fields: also sweep H/L and t/L around the scene (writes fe_sweep.csv).
    #[arg(long, requires = "bonded_fields")]
    sweep: bool,
    #[command(flatten)]
    scene: super::check::SceneArgs,
    /// Grid points per axis for --map (cell centres), 2..=400 [default: 40, with --fe 20].
    #[arg(long, requires = "map")]
    resolution: Option<usize>,
}

pub fn run(args: Args) -> tribofe::Result<()> {
    // The model's iteration and map are dimensionless in r and g: no scene can act on them.
    if !args.fe && !args.bonded_fields && args.scene.any() {
        let flag = super::scene_args::FLAG_KEYS
            .iter()
            .map(|(f, _)| *f)
            .chain(["--scene", "--write-scene"])
            .find(|f| args.scene.has(f))
            .unwrap_or("--scene");
        return Err(Error::input(
            flag,
            "cannot act without --fe (or --bonded-fields): the model's precursors depend on r and g only",
        ));
    }
    if args.fe {
        if args.events.is_some() {
            return Err(Error::input(
                "--events",
                "cannot act with --fe, whose runs end at whole-interface slips (--cycles); its cap is --max-events",
            ));
        }
        if super::given("max_events") && !args.map && args.dc.is_none() {
            return Err(Error::input(
                "--max-events",
                "cannot act here: it caps --fe --map cells and --fe --dc runs",
            ));
        }
        if args.cycles.is_some() && args.dc.is_some() {
            return Err(Error::input("--cycles", "cannot act with --dc, whose runs stop after one cycle"));
        }
        if super::given("rules") && !args.map {
            return Err(Error::input("--rules", "cannot act without --map: --fe runs every rule for fig. 4"));
        }
    }
    if args.map && args.fe {
        return fe_map(&args);
    }
    if args.map {
        let resolution = args.resolution.unwrap_or(40);
        let map = precursors::n_map(resolution)?;
        let n_max = map.iter().map(|m| m.n).max().unwrap_or(0);
        tribofe::io::outdir::check(&args.out, args.force)?;
        let results = [("resolution", resolution as i64), ("n_max", n_max as i64)];
        let written = write_whole(&args.out, args.force, |dir, inv| {
            let mut w = report::write_map(dir, &map, resolution)?;
            w.push(run_file(dir, inv, None, &results)?);
            Ok(w)
        })?;
        outln!("n(r, g) on a {0} x {0} grid: n from 0 to {n_max}", resolution);
        return print_written(&written);
    }
    if args.fe && args.thin_layer.is_some() {
        return thin_layer(&args);
    }
    if args.fe && args.heights.is_some() {
        return heights(&args);
    }
    if args.fe && args.dc.is_some() {
        return dc(&args);
    }
    if args.fe {
        return fe(&args);
    }
    if args.bonded_fields {
        return bonded_fields(&args);
    }
    let p = Params::new(args.r, args.g)?;
    tribofe::io::outdir::check(&args.out, args.force)?;
    let events = match args.events {
        Some(0) => return Err(Error::input("--events 0", "need at least one event")),
        Some(n) if n > MAX_EVENTS => return Err(too_many_events(n)),
        Some(n) => precursors::simulate(&p, n),
        None => precursors::simulate_to_convergence(&p, CONVERGED, MAX_DEFAULT_EVENTS),
    };
    let n = precursors::n_precursors(&p)?;
    let results = [
        ("r", toml::Value::from(p.r())),
        ("g", toml::Value::from(p.g())),
        ("precursors", toml::Value::from(n as i64)),
        ("F_1_over_mu_s_N", toml::Value::from(p.f1())),
        ("F_max_over_mu_s_N", toml::Value::from(p.f_max())),
        ("events", toml::Value::from(events.len() as i64)),
    ];
    let written = write_whole(&args.out, args.force, |dir, inv| {
        let mut w = report::write_events(dir, &p, &events)?;
        w.push(run_file(dir, inv, None, &results)?);
        Ok(w)
    })?;
    print_table(&events)?;
    outln!("r = {}, g = {} (dimensionless; forces in units of mu_s N, x in units of L)", p.r(), p.g());
    outln!("F_1 = {:.6}   n = {n} precursors   F_max = {:.6}", p.f1(), p.f_max());
    print_written(&written)
}

fn too_many_events(n: usize) -> Error {
    Error::input(
        "--events",
        format!(
            "{n}: at most {MAX_EVENTS} (the iteration settles on its stick-slip cycle within ~200 events)"
        ),
    )
}

fn print_table(events: &[Event]) -> tribofe::Result<()> {
    outln!("{:>4} {:>10} {:>10} {:>10} {:>10}  regime", "i", "F", "F^c", "x", "F^*");
    for e in events {
        let regime = if e.stick_slip { "stick-slip" } else { "precursor" };
        outln!("{:>4} {:>10.6} {:>10.6} {:>10.6} {:>10.6}  {regime}", e.i, e.f, e.fc, e.x, e.fstar);
    }
    Ok(())
}

/// A progress bar over `len` items called `what`.
fn counter(len: usize, what: &str) -> indicatif::ProgressBar {
    let style = format!("{{bar:40}} {{pos}}/{{len}} {what}, {{elapsed}}");
    indicatif::ProgressBar::new(len as u64)
        .with_style(indicatif::ProgressStyle::with_template(&style).unwrap())
}

/// A spinner with elapsed time for a step that reports no fraction.
fn spinner(what: &str) -> indicatif::ProgressBar {
    let bar = indicatif::ProgressBar::new_spinner().with_style(
        indicatif::ProgressStyle::with_template("{spinner} {msg}, {elapsed}")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_spinner()),
    );
    bar.set_message(what.to_string());
    bar.enable_steady_tick(std::time::Duration::from_millis(200));
    bar
}

/// Writes a study's folder whole: `write` fills a temporary sibling of `out` (given the
/// invocation for its run.toml), which replaces `out` only once everything is written.
/// Returns the files written, as paths under `out`.
fn write_whole(
    out: &Path,
    force: bool,
    write: impl FnOnce(&Path, &Invocation) -> tribofe::Result<Vec<PathBuf>>,
) -> tribofe::Result<Vec<PathBuf>> {
    let dir = super::begin_out(out, force)?;
    let tmp = dir.path().to_path_buf();
    let files = write(&tmp, super::invocation())?;
    dir.commit()?;
    Ok(files.into_iter().map(|p| p.strip_prefix(&tmp).map_or(p.clone(), |r| out.join(r))).collect())
}

/// Writes `dir/run.toml`; returns its path.
fn run_file(
    dir: &Path,
    inv: &Invocation,
    scene: Option<&tribofe::scene::Scene>,
    results: &impl serde::Serialize,
) -> tribofe::Result<PathBuf> {
    let results = toml::Value::try_from(results).map_err(|e| Error::input("run.toml", e.to_string()))?;
    let results = match results {
        toml::Value::Array(a) => a
            .into_iter()
            .filter_map(|kv| match kv.as_array().map(|a| &a[..]) {
                Some([toml::Value::String(k), v]) => Some((k.clone(), v.clone())),
                _ => None,
            })
            .collect::<toml::Table>(),
        toml::Value::Table(t) => t,
        _ => toml::Table::new(),
    };
    tribofe::report::run_file::write(dir, inv, scene, &results)?;
    Ok(dir.join(tribofe::io::outdir::RUN_FILE))
}

fn print_written(paths: &[impl AsRef<Path>]) -> tribofe::Result<()> {
    for p in paths {
        outln!("wrote {}", p.as_ref().display());
    }
    Ok(())
}

/// The scene of `precursors --fe`, refusing the scene flags that cannot act there.
fn fe_scene(args: &Args) -> tribofe::Result<tribofe::scene::Scene> {
    for (flag, given) in
        [("--fn-ratios", args.scene.fn_ratios.is_some()), ("--tol", args.scene.tol.is_some())]
    {
        if given {
            return Err(Error::input(
                flag,
                "cannot act in `precursors --fe`, which loads N then X until the interface slides",
            ));
        }
    }
    let scene = super::check::scene(&args.scene)?;
    tribofe::io::outdir::check(&args.out, args.force)?;
    Ok(scene)
}

/// FE fig. 4: the frictional FE for each event rule next to the analytic iteration.
fn fe(args: &Args) -> tribofe::Result<()> {
    let cycles = args.cycles.unwrap_or(2);
    if cycles == 0 {
        return Err(Error::input("--cycles", "need at least one whole-interface slip"));
    }
    let cap = tribofe::studies::slide::SlideOptions::default().max_events;
    if cycles > cap {
        return Err(Error::input(
            "--cycles",
            format!("{cycles}: above the event cap of {cap} (each cycle takes at least one event)"),
        ));
    }
    let p = Params::new(args.r, args.g)?;
    let scene = fe_scene(args)?;
    let bar = spinner("precursors --fe: one run per event rule");
    let cancel = tribofe::Cancel::new();
    let runs = tribofe::studies::precursors_fe::fig4(
        &scene,
        p.r(),
        p.g(),
        cycles,
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
    outln!("n: precursors before the first whole slip or front crossing; > 5t: longer than 5 t; advance: moving the front by > 5 t (the count least sensitive to the mesh)");
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
    outln!("2: largest |p - (N/L + 12 F H x/L^3)|/(N/L); 3: F/(mu_s N) when the trailing node opens or creeps, x/L where the first long precursor began");
    let results = [
        ("r", toml::Value::from(p.r())),
        ("g", toml::Value::from(p.g())),
        ("cycles", toml::Value::from(cycles as i64)),
        ("model_precursors", toml::Value::from(n as i64)),
    ];
    write_whole(&args.out, args.force, |dir, inv| {
        let mut w = report::write_fe_fig4(dir, &p, &model, &runs, inv, &scene)?;
        w.push(run_file(dir, inv, Some(&scene), &results)?);
        Ok(w)
    })?;
    outln!("wrote {}/{{summary.csv, run.toml, model/, paper/, overdamped/}}", args.out.display());
    Ok(())
}

/// The thin-layer limit: the `paper` rule at (r, g) over t/L against the model.
fn thin_layer(args: &Args) -> tribofe::Result<()> {
    use tribofe::studies::precursors_fe as pfe;
    let ts = args.thin_layer.clone().unwrap_or_default();
    let a = &args.scene;
    for (flag, given) in [
        ("--thickness", a.thickness.is_some()),
        ("--h", a.h.is_some()),
        ("--n-thick", a.n_thick.is_some()),
        ("--grading", a.grading.is_some()),
        ("--h-max", a.h_max.is_some()),
    ] {
        if given {
            return Err(Error::input(flag, "cannot act with --thin-layer, which sets t = (t/L) L, h = t and 2 elements through t per run"));
        }
    }
    let p = Params::new(args.r, args.g)?;
    let scene = fe_scene(args)?;
    let bar = counter(ts.len(), "thicknesses");
    let tick = |_: &tribofe::Tick| bar.inc(1);
    let rows =
        pfe::thin_layer(&scene, p.r(), p.g(), &ts, &tribofe::Cancel::new(), tribofe::Progress::new(&tick))?;
    bar.finish_and_clear();
    let n = precursors::n_precursors(&p)?;
    outln!(
        "thin-layer limit, rule paper, (r, g) = ({}, {}), H/L = {:.4}; F in units of mu_s N, x in units of L",
        p.r(),
        p.g(),
        scene.loading.height / scene.block.length
    );
    outln!(
        "{:>9} {:>6} {:>9} {:>9} {:>9} {:>10} {:>11} {:>9}",
        "t/L",
        "n adv",
        "F_1",
        "x_1",
        "F_max",
        "F_corner",
        "violation",
        "time, s"
    );
    let x1 = precursors::simulate(&p, 1)[0].x;
    outln!(
        "{:>9} {n:>6} {:>9.4} {:>9.4} {:>9.4} {:>10} {:>11} {:>9}",
        "model",
        p.f1(),
        x1,
        p.f_max(),
        "-",
        "-",
        "-"
    );
    let f = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.4}"));
    for row in &rows {
        match &row.fig4 {
            Ok(r) => outln!(
                "{:>9} {:>6} {:>9} {:>9} {:>9} {:>10} {:>11.1e} {:>9.1}",
                row.value,
                r.cmp.n_fe_advancing,
                f(r.cmp.f1_fe),
                f(r.cmp.x1_fe),
                f(r.cmp.f_max_fe),
                f(r.fields.f_corner),
                r.worst_violation,
                row.seconds
            ),
            Err(e) => outln!("{:>9} refused: {e}", row.value),
        }
    }
    for lim in pfe::thin_layer_limits(&rows) {
        let (name, model) = (lim.name, lim.model);
        let offset = |v: f64| {
            if name == "x_1" {
                format!("{:+.4} L", v - model)
            } else {
                format!("{:+.2} %", 100.0 * (v / model - 1.0))
            }
        };
        match (lim.order_limit, lim.finest) {
            (Some((p, v)), _) => outln!(
                "{name}: observed order {p:.2} in t/L, limit {v:.4}, offset from the model {}",
                offset(v)
            ),
            (None, Some(v)) => outln!(
                "{name}: no asymptotic range in the last three t/L; finest {v:.4}, offset from the model {}",
                offset(v)
            ),
            (None, None) => outln!("{name}: -"),
        }
    }
    write_whole(&args.out, args.force, |dir, inv| report::write_thin_layer(dir, &p, &rows, inv, &scene))?;
    outln!("wrote {}/{{thin_layer.csv, thin_layer.svg, run.toml}}", args.out.display());
    Ok(())
}

/// The height of the drive: the `paper` rule at fixed coefficients over H/L against the model.
fn heights(args: &Args) -> tribofe::Result<()> {
    let hs = args.heights.clone().unwrap_or_default();
    let p = Params::new(args.r, args.g)?;
    let scene = fe_scene(args)?;
    let mu = tribofe::studies::slide::coefficients_from_rg(&scene, p.r(), p.g())?;
    let bar = counter(hs.len(), "heights");
    let tick = |_: &tribofe::Tick| bar.inc(1);
    let rows = tribofe::studies::precursors_fe::heights(
        &scene,
        p.r(),
        p.g(),
        &hs,
        &tribofe::Cancel::new(),
        tribofe::Progress::new(&tick),
    )?;
    bar.finish_and_clear();
    outln!(
        "height of the drive, rule paper, mu_s = {:.4}, mu_d = {:.4} (r = {}), t/L = {:.4}; F in units of mu_s N, x in units of L",
        mu.0,
        mu.1,
        p.r(),
        scene.block.thickness / scene.block.length
    );
    outln!(
        "{:>7} {:>6} {:>13} {:>17} {:>17} {:>17} {:>9}",
        "H/L",
        "g",
        "n model/FE",
        "F_1 model/FE",
        "x_1 model/FE",
        "F_max model/FE",
        "violation"
    );
    let f = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.4}"));
    for row in &rows {
        match &row.fig4 {
            Ok(r) => {
                let c = &r.cmp;
                outln!(
                    "{:>7.4} {:>6.4} {:>6}/{:<6} {:>8.4}/{:<8} {:>8.4}/{:<8} {:>8.4}/{:<8} {:>9.1e}",
                    row.value,
                    c.g,
                    c.n,
                    c.n_fe_advancing,
                    c.f1,
                    f(c.f1_fe),
                    c.x1,
                    f(c.x1_fe),
                    c.f_max,
                    f(c.f_max_fe),
                    r.worst_violation
                );
            }
            Err(e) => outln!("{:>7.4} refused: {e}", row.value),
        }
    }
    write_whole(&args.out, args.force, |dir, inv| report::write_heights(dir, mu, &rows, inv, &scene))?;
    outln!("wrote {}/{{heights.csv, heights.svg, run.toml}}", args.out.display());
    Ok(())
}

/// Event rule and D_c: the `paper` rule and slip-weakening with each D_c at (r, g).
fn dc(args: &Args) -> tribofe::Result<()> {
    let dcs = args.dc.clone().unwrap_or_default();
    let p = Params::new(args.r, args.g)?;
    let scene = fe_scene(args)?;
    let (ms, md) = tribofe::studies::slide::coefficients_from_rg(&scene, p.r(), p.g())?;
    // Every D_c and the cap checked before the condensation, as the runs will see them.
    for &d in &dcs {
        let o = tribofe::studies::slide::SlideOptions {
            law: tribofe::interface::law::Law::slip_weakening(ms, md, d)?,
            cycles: 1,
            max_events: args.max_events,
            ..Default::default()
        };
        tribofe::studies::slide::check_options(&scene, &o)?;
    }
    if args.max_events == 0 {
        return Err(Error::input("--max-events", "0: need at least one event per run"));
    }
    let bar = counter(dcs.len() + 1, "runs");
    let tick = |_: &tribofe::Tick| bar.inc(1);
    let rows = tribofe::studies::precursors_fe::dc_series(
        &scene,
        p.r(),
        p.g(),
        &dcs,
        args.max_events,
        &tribofe::Cancel::new(),
        tribofe::Progress::new(&tick),
    )?;
    bar.finish_and_clear();
    if rows.iter().all(|r| r.fig4.is_err()) {
        // Nothing to tabulate or draw: the first refusal says why.
        return rows.into_iter().find_map(|r| r.fig4.err()).map_or(Ok(()), Err);
    }
    let b = &scene.block;
    // dc_series runs at the default normal force.
    let n_force = tribofe::studies::slide::SlideOptions::default().n_force;
    outln!(
        "event rule and D_c at (r, g) = ({}, {}): mu_s = {ms:.4}, mu_d = {md:.4}, t/L = {:.4}, h = {:e} m; F in units of mu_s N, x in units of L",
        p.r(),
        p.g(),
        b.thickness / b.length,
        scene.mesh.h
    );
    outln!(
        "{:>9} {:>8} {:>7} {:>10} {:>6} {:>8} {:>8} {:>8} {:>8} {:>8}",
        "D_c, m",
        "kappa",
        "L_c/h",
        "Appendix",
        "n adv",
        "F_1",
        "x_1",
        "F_max",
        "events",
        "time, s"
    );
    let x1 = precursors::simulate(&p, 1)[0].x;
    outln!(
        "{:>9} {:>8} {:>7} {:>10} {:>6} {:>8.4} {:>8.4} {:>8.4} {:>8} {:>8}",
        "model",
        "-",
        "-",
        "-",
        precursors::n_precursors(&p)?,
        p.f1(),
        x1,
        p.f_max(),
        "-",
        "-"
    );
    let f = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.4}"));
    for row in &rows {
        let d = row.value;
        let (name, kappa, lch, appendix) = if d == 0.0 {
            ("paper".to_string(), "-".to_string(), "-".to_string(), "-".to_string())
        } else {
            let (kappa, lch, appendix) =
                tribofe::studies::precursors_fe::dc_scales(&scene, ms, md, n_force, d);
            (format!("{d:.1e}"), format!("{kappa:.3}"), format!("{lch:.2}"), format!("{appendix:.2e}"))
        };
        match &row.fig4 {
            Ok(r) => outln!(
                "{name:>9} {kappa:>8} {lch:>7} {appendix:>10} {:>6} {:>8} {:>8} {:>8} {:>8} {:>8.1}",
                r.cmp.n_fe_advancing,
                f(r.cmp.f1_fe),
                f(r.cmp.x1_fe),
                f(r.cmp.f_max_fe),
                r.run.run.events.len(),
                row.seconds
            ),
            Err(e) => outln!("{name:>9} {kappa:>8} {lch:>7} {appendix:>10} refused: {e}"),
        }
    }
    outln!("kappa = G D_c/((mu_s - mu_d) p t) (stable above 1); L_c = kappa t, the nucleation length; Appendix: (E/p)(D_c/t)(mu_s - mu_d)/(2 mu_d), the excess mu(x) - mu_d below which the Appendix's Griffith argument lets a front arrest");
    write_whole(&args.out, args.force, |dir, inv| report::write_dc(dir, &rows, inv, &scene))?;
    outln!("wrote {}/{{dc.csv, dc.svg, run.toml, paper/, dc_<D_c>/}}", args.out.display());
    Ok(())
}

/// FE fig. 5: n over the (r, g) grid from the frictional FE for each rule asked for, next to
/// the model's map.
fn fe_map(args: &Args) -> tribofe::Result<()> {
    use tribofe::studies::precursors_fe::{self as pfe, RULES};
    let resolution = args.resolution.unwrap_or(20);
    if args.max_events == 0 {
        return Err(Error::input("--max-events", "need at least one event per cell"));
    }
    let rules: Vec<_> = RULES.iter().copied().filter(|r| args.rules.contains(r)).collect();
    let scene = fe_scene(args)?;
    let bar = indicatif::ProgressBar::new((resolution * resolution) as u64).with_style(
        indicatif::ProgressStyle::with_template("{bar:40} {pos}/{len} cells, {elapsed} (eta {eta})").unwrap(),
    );
    let clock = std::time::Instant::now();
    let tick = |_: &tribofe::Tick| bar.inc(1);
    let cancel = tribofe::Cancel::new();
    let cells =
        pfe::fig5(&scene, resolution, &rules, args.max_events, &cancel, tribofe::Progress::new(&tick))?;
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
    write_whole(&args.out, args.force, |dir, inv| {
        report::write_fe_fig5(dir, &cells, resolution, &what, inv, &scene)
    })?;
    outln!(
        "counts: front-advancing precursors (> 5 t) before the first whole slip or front crossing (the slipped nodes joining edge to edge); capped: over --max-events"
    );
    outln!("wrote {}/{{fig5_fe.csv, boundary_fe.csv, fig5_fe.svg, run.toml}}", args.out.display());
    Ok(())
}

/// The 1D model fed with the scene's bonded unit interface fields, next to the paper's linear
/// fields on the same cells.
fn bonded_fields(args: &Args) -> tribofe::Result<()> {
    let scene = super::check::scene(&args.scene)?;
    let n_events = args.events.unwrap_or(MAX_DEFAULT_EVENTS);
    if n_events > MAX_EVENTS {
        return Err(too_many_events(n_events));
    }
    let fields = |s: &tribofe::scene::Scene| {
        tribofe::studies::check::run(s, &SolverOptions::default()).map(|r| r.0.unit)
    };
    let c = tribofe::precursors::fe::compare(&fields(&scene)?, args.r, args.g, n_events)?;
    print_comparison(&c)?;
    tribofe::io::outdir::check(&args.out, args.force)?;
    let mut sweep_fields = Vec::new();
    if args.sweep {
        let (l, h0, t0) = (
            scene.block.length,
            scene.loading.height / scene.block.length,
            scene.block.thickness / scene.block.length,
        );
        let hs = [0.25 * h0, 0.5 * h0, h0, 2.0 * h0];
        let ts = [0.5 * t0, t0, 2.0 * t0, 4.0 * t0];
        for &h in &hs {
            for &t in &ts {
                let mut s = scene.clone();
                s.loading.height = h * l;
                s.block.thickness = t * l;
                s.mesh.h = s.mesh.h.min(s.block.thickness / 2.0);
                eprintln!("sweep: H/L = {h}, t/L = {t}");
                let mut f = fields(&s)?;
                (f.h_over_l, f.t_over_l) = (h, t); // exact keys for the table
                sweep_fields.push(f);
            }
        }
        let written = write_whole(&args.out, args.force, |dir, inv| {
            let mut w = report::write_comparison(dir, &c)?;
            let path = dir.join("fe_sweep.csv");
            let mut it = sweep_fields.into_iter();
            report::sweep_table(&path, &hs, &ts, args.r, args.g, n_events, |_, _| {
                it.next().ok_or_else(|| Error::input("--sweep", "internal: sweep fields out of order"))
            })?;
            w.push(path);
            w.push(run_file(dir, inv, Some(&scene), &[("r", args.r), ("g", args.g)])?);
            Ok(w)
        })?;
        return print_written(&written);
    }
    let written = write_whole(&args.out, args.force, |dir, inv| {
        let mut w = report::write_comparison(dir, &c)?;
        w.push(run_file(dir, inv, Some(&scene), &[("r", args.r), ("g", args.g)])?);
        Ok(w)
    })?;
    print_written(&written)
}

fn print_comparison(c: &tribofe::precursors::fe::Comparison) -> tribofe::Result<()> {
    let opt = |v: Option<usize>| v.map_or("-".to_string(), |n| n.to_string());
    let optf = |v: Option<f64>| v.map_or("-".to_string(), |f| format!("{f:.6}"));
    outln!(
        "FE-fed precursors: r = {}, g = {} (mu_s = {:.4}, mu_d = {:.4}), H/L = {}, t/L = {} (dimensionless)",
        c.params.r(),
        c.params.g(),
        c.mu_s,
        c.mu_d,
        c.h_over_l,
        c.t_over_l
    );
    outln!("{:>22} {:>12} {:>12}", "", "linear model", "FE fields");
    let first = |r: &tribofe::precursors::discrete::Run| r.events.first().map_or(f64::NAN, |e| e.f);
    outln!("{:>22} {:>12.6} {:>12.6}", "F_1", first(&c.linear), first(&c.fe));
    outln!("{:>22} {:>12} {:>12}", "precursors n", opt(c.linear.n_precursors()), opt(c.fe.n_precursors()));
    outln!("{:>22} {:>12} {:>12}", "stick-slip F_max", optf(c.linear.f_limit()), optf(c.fe.f_limit()));
    outln!("{:>4} {:>14} {:>14}   (precursor length x_i + 1/2, in units of L)", "i", "linear", "FE");
    let (a, b) = (c.linear.precursors(), c.fe.precursors());
    for i in 0..a.len().max(b.len()) {
        let len = |v: &[tribofe::precursors::discrete::CellEvent]| {
            v.get(i).map_or("-".to_string(), |e| format!("{:.5}", e.x + 0.5))
        };
        outln!("{:>4} {:>14} {:>14}", i + 1, len(a), len(b));
    }
    Ok(())
}
