//! `precursors bonded`: the 1D model fed with the scene's bonded unit interface fields, next
//! to the paper's linear fields on the same cells.

use super::MAX_DEFAULT_EVENTS;
use super::{print_written, run_file, write_whole, OutArgs, RgArgs};
use tribofe::report::precursors as report;

#[derive(clap::Args, Debug)]
pub struct BondedArgs {
    #[command(flatten)]
    pub rg: RgArgs,
    /// Number of events of each discrete run.
    #[arg(long, default_value_t = MAX_DEFAULT_EVENTS)]
    pub events: usize,
    /// Also sweep H/L and t/L around the scene (writes fe_sweep.csv).
    #[arg(long)]
    pub sweep: bool,
    #[command(flatten)]
    pub scene: super::super::check::SceneArgs,
    #[command(flatten)]
    pub out: OutArgs,
}

/// The 1D model fed with the scene's bonded unit interface fields, next to the paper's linear
/// fields on the same cells.
pub fn bonded(args: BondedArgs) -> tribofe::Result<()> {
    let scene = super::super::check::scene(&args.scene)?;
    let cancel = tribofe::Cancel::new();
    let c = tribofe::studies::precursors_fe::bonded(&scene, args.rg.r, args.rg.g, args.events, &cancel)?;
    print_comparison(&c)?;
    tribofe::io::outdir::check(&args.out.out, args.out.force)?;
    let rows = if args.sweep {
        let tick = |t: &tribofe::Tick| errln!("{}", t.message);
        let (p, progress) = (&args.rg, tribofe::Progress::new(&tick));
        Some(tribofe::studies::precursors_fe::bonded_sweep(&scene, p.r, p.g, args.events, &cancel, progress)?)
    } else {
        None
    };
    let written = write_whole(&args.out.out, args.out.force, |dir, inv| {
        let mut w = report::write_comparison(dir, &c)?;
        if let Some(rows) = &rows {
            let path = dir.join("fe_sweep.csv");
            report::write_sweep(&path, rows)?;
            w.push(path);
        }
        w.push(run_file(dir, inv, Some(&scene), &[("r", args.rg.r), ("g", args.rg.g)])?);
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
