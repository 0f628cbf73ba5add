//! `tribofe precursors`: the paper's event iteration for one (r, g), or the n(r, g) map.

use std::path::{Path, PathBuf};
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
    /// Grid points per axis for --map (cell centres), 2..=400.
    #[arg(long, default_value_t = 40, requires = "map")]
    resolution: usize,
}

pub fn run(args: Args) -> tribofe::Result<()> {
    if args.map {
        let map = precursors::n_map(args.resolution)?;
        let n_max = map.iter().map(|m| m.n).max().unwrap_or(0);
        println!("n(r, g) on a {0} x {0} grid: n from 0 to {n_max}", args.resolution);
        return print_written(&report::write_map(&args.out, &map, args.resolution)?);
    }
    let p = Params::new(args.r, args.g)?;
    let events = match args.events {
        Some(0) => return Err(Error::input("--events 0", "need at least one event")),
        Some(n) => precursors::simulate(&p, n),
        None => precursors::simulate_to_convergence(&p, CONVERGED, MAX_DEFAULT_EVENTS),
    };
    print_table(&events);
    let n = precursors::n_precursors(&p)?;
    println!("r = {}, g = {} (dimensionless; forces in units of mu_s N, x in units of L)", p.r(), p.g());
    println!("F_1 = {:.6}   n = {n} precursors   F_max = {:.6}", p.f1(), p.f_max());
    print_written(&report::write_events(&args.out, &p, &events)?)
}

fn print_table(events: &[Event]) {
    println!("{:>4} {:>10} {:>10} {:>10} {:>10}  regime", "i", "F", "F^c", "x", "F^*");
    for e in events {
        let regime = if e.stick_slip { "stick-slip" } else { "precursor" };
        println!("{:>4} {:>10.6} {:>10.6} {:>10.6} {:>10.6}  {regime}", e.i, e.f, e.fc, e.x, e.fstar);
    }
}

fn print_written(paths: &[impl AsRef<Path>]) -> tribofe::Result<()> {
    for p in paths {
        println!("wrote {}", p.as_ref().display());
    }
    Ok(())
}
