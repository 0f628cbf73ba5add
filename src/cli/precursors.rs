//! `tribofe precursors`: the paper's event iteration for one (r, g), or the n(r, g) map.

use std::path::{Path, PathBuf};
use tribofe::linalg::solve::SolverOptions;
use tribofe::precursors::{self, Event, Params};
use tribofe::report::precursors as report;
use tribofe::Error;

/// Events are iterated until |F - F_max| < this (or MAX_DEFAULT_EVENTS) unless --events is given.
const CONVERGED: f64 = 1e-6;
const MAX_DEFAULT_EVENTS: usize = 200;

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
    /// Number of events [default: until |F - F_max| < 1e-6, at most 200].
    #[arg(long)]
    events: Option<usize>,
    /// Compute the number of precursors n over the (r, g) square instead (fig. 5).
    #[arg(long, conflicts_with_all = ["r", "g", "events"])]
    map: bool,
    /// Feed the model with the FE interface fields of the scene (options as for `check`).
    #[arg(long, conflicts_with = "map")]
    fe: bool,
    /// With --fe: also sweep H/L and t/L around the scene (writes fe_sweep.csv).
    #[arg(long, requires = "fe")]
    sweep: bool,
    #[command(flatten)]
    scene: super::check::SceneArgs,
    /// Grid points per axis for --map (cell centres), 2..=400.
    #[arg(long, default_value_t = 40, requires = "map")]
    resolution: usize,
}

pub fn run(args: Args) -> tribofe::Result<()> {
    if args.map {
        let map = precursors::n_map(args.resolution)?;
        let n_max = map.iter().map(|m| m.n).max().unwrap_or(0);
        outln!("n(r, g) on a {0} x {0} grid: n from 0 to {n_max}", args.resolution);
        return print_written(&report::write_map(&args.out, &map, args.resolution)?);
    }
    if args.fe {
        return fe(&args);
    }
    let p = Params::new(args.r, args.g)?;
    let events = match args.events {
        Some(0) => return Err(Error::input("--events 0", "need at least one event")),
        Some(n) => precursors::simulate(&p, n),
        None => precursors::simulate_to_convergence(&p, CONVERGED, MAX_DEFAULT_EVENTS),
    };
    print_table(&events)?;
    let n = precursors::n_precursors(&p)?;
    outln!("r = {}, g = {} (dimensionless; forces in units of mu_s N, x in units of L)", p.r(), p.g());
    outln!("F_1 = {:.6}   n = {n} precursors   F_max = {:.6}", p.f1(), p.f_max());
    print_written(&report::write_events(&args.out, &p, &events)?)
}

fn print_table(events: &[Event]) -> tribofe::Result<()> {
    outln!("{:>4} {:>10} {:>10} {:>10} {:>10}  regime", "i", "F", "F^c", "x", "F^*");
    for e in events {
        let regime = if e.stick_slip { "stick-slip" } else { "precursor" };
        outln!("{:>4} {:>10.6} {:>10.6} {:>10.6} {:>10.6}  {regime}", e.i, e.f, e.fc, e.x, e.fstar);
    }
    Ok(())
}

fn print_written(paths: &[impl AsRef<Path>]) -> tribofe::Result<()> {
    for p in paths {
        outln!("wrote {}", p.as_ref().display());
    }
    Ok(())
}

/// FE-fed precursors: the scene's unit interface fields drive the discrete model, next to the
/// paper's linear fields on the same cells.
fn fe(args: &Args) -> tribofe::Result<()> {
    let scene = super::check::scene(&args.scene)?;
    let n_events = args.events.unwrap_or(MAX_DEFAULT_EVENTS);
    let fields = |s: &tribofe::scene::Scene| {
        tribofe::studies::check::run(s, &SolverOptions::default()).map(|r| r.0.unit)
    };
    let c = tribofe::precursors::fe::compare(&fields(&scene)?, args.r, args.g, n_events)?;
    print_comparison(&c)?;
    let mut written = report::write_comparison(&args.out, &c)?;
    if args.sweep {
        let (l, h0, t0) = (
            scene.block.length,
            scene.loading.height / scene.block.length,
            scene.block.thickness / scene.block.length,
        );
        let hs = [0.25 * h0, 0.5 * h0, h0, 2.0 * h0];
        let ts = [0.5 * t0, t0, 2.0 * t0, 4.0 * t0];
        let path = args.out.join("fe_sweep.csv");
        report::sweep_table(&path, &hs, &ts, args.r, args.g, n_events, |h, t| {
            let mut s = scene.clone();
            s.loading.height = h * l;
            s.block.thickness = t * l;
            s.mesh.h = s.mesh.h.min(s.block.thickness / 2.0);
            eprintln!("sweep: H/L = {h}, t/L = {t}");
            let mut f = fields(&s)?;
            (f.h_over_l, f.t_over_l) = (h, t); // exact keys for the table
            Ok(f)
        })?;
        written.push(path);
    }
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
