//! `precursors model` and `precursors map`: the paper's iteration and its n(r, g), which
//! depend on r and g alone (no scene).

use super::{print_written, run_file, write_whole, OutArgs, RgArgs};
use super::{CONVERGED, MAX_DEFAULT_EVENTS};
use tribofe::precursors::{self, Event, Params};
use tribofe::report::precursors as report;
use tribofe::Error;

#[derive(clap::Args, Debug)]
pub struct ModelArgs {
    #[command(flatten)]
    pub rg: RgArgs,
    /// Number of events [default: until |F - F_max| < 1e-6, at most 200].
    #[arg(long)]
    pub events: Option<usize>,
    #[command(flatten)]
    pub out: OutArgs,
}

#[derive(clap::Args, Debug)]
pub struct MapArgs {
    /// Grid points per axis (cell centres), 2..=400.
    #[arg(long, default_value_t = precursors::DEFAULT_MAP_RESOLUTION)]
    pub resolution: usize,
    #[command(flatten)]
    pub out: OutArgs,
}

/// The model's n(r, g) on a grid.
pub fn map(args: MapArgs) -> tribofe::Result<()> {
    let resolution = args.resolution;
    let out = &args.out;
    let map = precursors::n_map(resolution, &tribofe::Cancel::new())?;
    let n_max = map.iter().map(|m| m.n).max().unwrap_or(0);
    tribofe::io::outdir::check(&out.out, out.force)?;
    let results = [("resolution", resolution as i64), ("n_max", n_max as i64)];
    let written = write_whole(&out.out, out.force, |dir, inv| {
        let mut w = report::write_map(dir, &map, resolution)?;
        w.push(run_file(dir, inv, None, &results)?);
        Ok(w)
    })?;
    outln!("n(r, g) on a {0} x {0} grid: n from 0 to {n_max}", resolution);
    print_written(&written)
}

/// The paper's event iteration for one (r, g).
pub fn model(args: ModelArgs) -> tribofe::Result<()> {
    let out = &args.out;
    let p = Params::new(args.rg.r, args.rg.g)?;
    tribofe::io::outdir::check(&out.out, out.force)?;
    let events = match args.events {
        Some(0) => return Err(Error::input("--events 0", "need at least one event")),
        Some(n) => {
            precursors::check_events(n)?;
            precursors::simulate(&p, n)
        }
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
    let written = write_whole(&out.out, out.force, |dir, inv| {
        let mut w = report::write_events(dir, &p, &events)?;
        w.push(run_file(dir, inv, None, &results)?);
        Ok(w)
    })?;
    print_table(&events)?;
    outln!("r = {}, g = {} (dimensionless; forces in units of mu_s N, x in units of L)", p.r(), p.g());
    outln!("F_1 = {:.6}   n = {n} precursors   F_max = {:.6}", p.f1(), p.f_max());
    print_written(&written)
}

fn print_table(events: &[Event]) -> tribofe::Result<()> {
    outln!("{:>4} {:>10} {:>10} {:>10} {:>10}  regime", "i", "F", "F^c", "x", "F^*");
    for e in events {
        let regime = if e.stick_slip { "stick-slip" } else { "precursor" };
        outln!("{:>4} {:>10.6} {:>10.6} {:>10.6} {:>10.6}  {regime}", e.i, e.f, e.fc, e.x, e.fstar);
    }
    Ok(())
}
