//! `tribofe sweep`: the check over a grid of scene parameters (lists and ranges on the scene
//! flags), with a progress bar, one CSV and SVG maps.

use super::scene_args::{scene, SceneArgs};
use clap::Args as ClapArgs;
use indicatif::{ProgressBar, ProgressStyle};
use std::path::PathBuf;
use tribofe::studies::sweep::{Axis, FrictionSweep, Param, SweepOptions, VerdictOptions};

#[derive(ClapArgs, Debug)]
pub struct Args {
    /// Scene flags; --length, --thickness, --height, --young, --poisson take a list `a,b,c` or a
    /// range `a:b:n` (n points, ends included, linear) or `a:b:ng` (geometric). The grid is the
    /// product, first flag given in this order slowest: length, thickness, height, young, poisson.
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Solve each point on the scene's own mesh settings instead of the converged model
    /// (graded QUA8, t/16 at the ends).
    #[arg(long)]
    pub as_meshed: bool,
    /// Run only part I of N (1-based), a contiguous block of points, written as
    /// OUT/sweep_IofN.csv with the header (each shard reads alone); join them with --merge.
    #[arg(long, value_name = "I/N")]
    pub shard: Option<String>,
    /// Verdict: largest interior |p - model| and |tau - model|, in units of N/L.
    #[arg(long, default_value_t = 0.02)]
    pub interior_tol: f64,
    /// Verdict: largest edge zone as a fraction of L (dimensionless).
    #[arg(long, default_value_t = 0.05)]
    pub edge_fraction: f64,
    /// Verdict: no tension one t inside the trailing end up to this F/N (default: the largest ratio).
    #[arg(long)]
    pub tension_fn: Option<f64>,
    /// Also run the frictional interface at each point with these static and kinetic
    /// coefficients `MU_S,MU_D` (g = 6 mu_d H/L follows the geometry): FE precursors, F_1,
    /// x_1 and the stick-slip peak against the paper's iteration, in the CSV and two maps.
    #[arg(long, value_name = "MU_S,MU_D")]
    pub friction: Option<String>,
    /// Event rule of the frictional run: paper or overdamped.
    #[arg(long, default_value = tribofe::studies::slide::DEFAULT_RULE)]
    pub rule: String,
    /// Whole-interface slips of the frictional run (the last one's peak is F_max).
    #[arg(long, default_value_t = tribofe::studies::sweep::DEFAULT_FRICTION_CYCLES)]
    pub cycles: usize,
    /// Join shard tables instead of sweeping: folders holding sweep_IofN.csv files (or the
    /// files), written as OUT/sweep.csv (every shard 1..N required, one header).
    #[arg(long, value_name = "DIR", num_args = 1..)]
    pub merge: Vec<PathBuf>,
    #[arg(long, default_value = "out/sweep")]
    pub out: PathBuf,
    /// Write into the --out folder even if it is not tribofe's by its run.toml; only files of
    /// this run's names are replaced (regular files only), nothing else is deleted.
    #[arg(long)]
    pub force: bool,
}

pub fn run(args: Args) -> tribofe::Result<()> {
    if !args.merge.is_empty() {
        return merge(&args);
    }
    let mut flat = args.scene.clone();
    let mut axes = Vec::new();
    for p in Param::ALL {
        let slot = match p {
            Param::Length => &mut flat.length,
            Param::Thickness => &mut flat.thickness,
            Param::Height => &mut flat.height,
            Param::Young => &mut flat.young,
            Param::Poisson => &mut flat.poisson,
        };
        if let Some(v) = slot.take() {
            axes.push(Axis { param: p, values: v.0 });
        }
    }
    super::scene_args::refuse_inapplicable(
        &args.scene,
        &["--mesh", "--geometry"],
        "the sweep varies the block's geometry, which a mesh file fixes",
    )?;
    if !args.as_meshed {
        super::scene_args::refuse_inapplicable(
            &args.scene,
            &["--h", "--grading", "--h-max", "--n-thick", "--element"],
            "each point is solved on the converged model (graded QUA8, t/16 at the ends); add --as-meshed to use the scene's mesh settings",
        )?;
    }
    tribofe::studies::sweep::check_friction_settings(
        args.friction.is_some(),
        &[("--rule", super::given("rule")), ("--cycles", super::given("cycles"))],
    )?;
    if let Some(v) = args.tension_fn {
        if !(v.is_finite() && v > 0.0) {
            return Err(tribofe::Error::input(
                "--tension-fn",
                format!("{v}: give the F/N ratio (> 0, dimensionless) up to which no tension is allowed"),
            ));
        }
    }
    let base = scene(&flat)?;
    tribofe::io::outdir::check(&args.out, args.force)?;
    let shard = match &args.shard {
        None => None,
        Some(s) => {
            let parsed =
                s.split_once('/').and_then(|(i, n)| Some((i.trim().parse().ok()?, n.trim().parse().ok()?)));
            Some(
                parsed
                    .ok_or_else(|| tribofe::Error::input("--shard", format!("'{s}' is not I/N, e.g. 3/8")))?,
            )
        }
    };
    for (what, v) in [("--interior-tol", args.interior_tol), ("--edge-fraction", args.edge_fraction)] {
        tribofe::error::positive(what, v)?;
    }
    let friction = match &args.friction {
        None => None,
        Some(v) => {
            let mu: Vec<f64> = tribofe::studies::sweep::parse_values(v)?;
            let [mu_s, mu_d] = mu[..] else {
                return Err(tribofe::Error::input(
                    "--friction",
                    format!("'{v}' is not MU_S,MU_D, e.g. 0.65,0.58"),
                ));
            };
            Some(FrictionSweep { mu_s, mu_d, rule: args.rule.parse()?, cycles: args.cycles })
        }
    };
    let o = SweepOptions {
        friction,
        converged: !args.as_meshed,
        shard,
        verdict: VerdictOptions {
            interior_tol: args.interior_tol,
            edge_fraction: args.edge_fraction,
            tension_fn: args.tension_fn,
        },
        ..Default::default()
    };
    let total = tribofe::studies::sweep::grid_size(&axes)?;
    let range = tribofe::studies::sweep::shard_range(total, shard)?;
    let bar = ProgressBar::new(range.len() as u64).with_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} points, {elapsed} ({per_sec})").unwrap(),
    );
    let clock = std::time::Instant::now();
    let tick = |_: &tribofe::Tick<'_, tribofe::studies::sweep::Point>| bar.inc(1);
    let points = tribofe::studies::sweep::run(&base, &axes, &o, tribofe::Progress::new(&tick))?;
    bar.finish_and_clear();
    let wall = clock.elapsed().as_secs_f64();
    let name = match shard {
        Some((i, n)) => format!("sweep_{i}of{n}.csv"),
        None => "sweep.csv".to_string(),
    };
    let results: toml::Table = [
        ("points", toml::Value::from(points.len() as i64)),
        ("grid_points", toml::Value::from(total as i64)),
        ("wall_seconds", toml::Value::from(wall)),
        // What --merge compares across shards: one sweep's grid and options.
        ("sweep", toml::Value::Table(tribofe::studies::sweep::identity(&axes, &o))),
    ]
    .into_iter()
    .map(|(k, v)| (k.to_string(), v))
    .collect();
    // Every shard's table carries the header, so each reads alone (sweep --merge joins them).
    let table = tribofe::report::sweep::csv(&points, true)?;
    let maps = if shard.is_some() {
        // Shards of one sweep share the folder (a Slurm array): each writes its own file, whole.
        // Each shard's provenance in its own run file, whole, next to its table.
        // The run file lists the table (size, SHA-256): what --merge and later runs go by.
        let (i, n) = shard.unwrap_or((1, 1));
        let text = tribofe::report::run_file::run_toml(super::invocation(), Some(&base), &results)?;
        let record = format!("run_{i}of{n}.toml");
        tribofe::io::outdir::write_in_place(
            &args.out,
            args.force,
            &record,
            &text,
            &[(name.as_str(), table.as_bytes())],
            tribofe::report::write_atomic,
        )?;
        vec![]
    } else {
        let dir = super::begin_out(&args.out, args.force)?;
        tribofe::report::write_atomic(&dir.path().join(&name), table.as_bytes())?;
        super::write_run_file(dir.path(), Some(&base), &results)?;
        let maps = tribofe::report::sweep::write_maps(&points, &axes, dir.path())?;
        dir.commit()?;
        maps
    };
    let cases: usize = points.iter().map(|p| p.result.cases.len()).sum();
    let holds = points.iter().flat_map(|p| &p.verdicts).filter(|v| v.holds()).count();
    outln!(
        "{} points x load cases = {cases} rows in {wall:.2} s ({:.1} points/s, {} threads); model holds in {holds} of {cases}",
        points.len(),
        points.len() as f64 / wall,
        rayon::current_num_threads()
    );
    outln!(
        "wrote {}/{name}{}",
        args.out.display(),
        if maps.is_empty() { String::new() } else { format!(", {}", maps.join(", ")) }
    );
    Ok(())
}

/// `--merge`: reads the shard files, checks by their run files that they are tribofe's, whole
/// and of one sweep, joins them (tribofe::report::sweep::merge) and writes OUT/sweep.csv and
/// its run.toml as every command writes its folder (a user's sweep.csv is never replaced).
fn merge(args: &Args) -> tribofe::Result<()> {
    use tribofe::error::quote;
    use tribofe::Error;
    let s = &args.scene;
    let swept = [&s.length, &s.thickness, &s.height, &s.young, &s.poisson].iter().any(|v| v.is_some());
    if args.shard.is_some() || args.friction.is_some() || swept {
        return Err(Error::input(
            "--merge",
            "joins finished shards and computes nothing: give it without --shard, --friction or swept values",
        ));
    }
    let shown = |p: &std::path::Path| quote(&p.display().to_string());
    let mut files = Vec::new();
    for p in &args.merge {
        let meta = std::fs::metadata(p);
        if meta.as_ref().is_ok_and(|m| m.is_dir()) {
            let entries = std::fs::read_dir(p).map_err(|e| Error::read(p, e))?;
            for e in entries {
                let path = e.map_err(|e| Error::read(p, e))?.path();
                let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
                if tribofe::report::sweep::shard_of(&name).is_some() {
                    files.push((name, path));
                }
            }
        } else if meta.as_ref().is_ok_and(|m| m.is_file()) {
            let name = p.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
            files.push((name, p.clone()));
        } else {
            return Err(Error::input(
                "--merge",
                format!("'{}' is neither a folder nor a regular file", shown(p)),
            ));
        }
    }
    tribofe::io::outdir::check(&args.out, args.force)?;
    // Each table by its shard's run file: listed there with this size and hash, and the
    // sweep it records (grid, options, scene) the same for all.
    let mut first: Option<(String, toml::Value)> = None;
    let mut parts = Vec::with_capacity(files.len());
    for (name, path) in &files {
        let (i, n) = tribofe::report::sweep::shard_of(name).unwrap_or_default();
        let dir = path.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(std::path::Path::new("."));
        let record = dir.join(format!("run_{i}of{n}.toml"));
        let refuse = |why: &str| Error::input("--merge", format!("'{}' {why}", shown(path)));
        if !record.is_file() {
            return Err(refuse(&format!(
                "has no run file beside it ('{}'): give the folder the shard wrote, or run the shard again",
                shown(&record)
            )));
        }
        let text = read_bounded(&record)?;
        let manifest = tribofe::io::outdir::Manifest::of_run_file(&text, &format!("run_{i}of{n}.toml"))
            .ok_or_else(|| {
                refuse(&format!(
                    "has no run file of tribofe with a manifest beside it ('{}'): run the shard again with this tribofe",
                    shown(&record)
                ))
            })?;
        let table = read_bounded(path)?;
        let listed = manifest.files.iter().find(|l| l.path == *name);
        if !listed.is_some_and(|l| {
            l.size == table.len() as u64 && l.sha256 == tribofe::io::outdir::sha256_hex(table.as_bytes())
        }) {
            return Err(refuse(&format!(
                "is not the table its run file '{}' records (edited, or from another run): run the shard again",
                shown(&record)
            )));
        }
        let run: toml::Table = text.parse().map_err(|_| refuse("has an unreadable run file"))?;
        let sweep = run.get("results").and_then(|r| r.get("sweep")).cloned();
        let Some(sweep) = sweep else {
            return Err(refuse(
                "has a run file that does not record its sweep: run the shard again with this tribofe",
            ));
        };
        let id = toml::Value::Table(
            [
                ("sweep".to_string(), sweep),
                ("scene".to_string(), run.get("scene").cloned().unwrap_or(toml::Value::Boolean(false))),
            ]
            .into_iter()
            .collect(),
        );
        match &first {
            None => first = Some((name.clone(), id)),
            Some((other, v)) if *v != id => {
                return Err(Error::input(
                    "--merge",
                    format!(
                        "'{}' and '{}' are shards of different sweeps (their run files record other grids, options or scenes): merge the shards of one sweep",
                        quote(other),
                        quote(name)
                    ),
                ))
            }
            Some(_) => {}
        }
        parts.push((name.clone(), table));
    }
    let table = tribofe::report::sweep::merge(&parts)?;
    let dir = super::begin_out(&args.out, args.force)?;
    tribofe::report::write_atomic(&dir.path().join("sweep.csv"), table.as_bytes())?;
    let results: toml::Table = [
        ("shards", toml::Value::from(parts.len() as i64)),
        ("rows", toml::Value::from(table.lines().count().saturating_sub(1) as i64)),
        (
            "sweep",
            first.and_then(|f| f.1.get("sweep").cloned()).unwrap_or(toml::Value::Table(Default::default())),
        ),
    ]
    .into_iter()
    .map(|(k, v)| (k.to_string(), v))
    .collect();
    super::write_run_file(dir.path(), None, &results)?;
    dir.commit()?;
    outln!(
        "joined {} shards, {} rows, into {}",
        parts.len(),
        table.lines().count() - 1,
        quote(&args.out.join("sweep.csv").display().to_string())
    );
    Ok(())
}

/// A shard's table (1 GiB at most: ~1 kB a point) or run file (a TOML file), read whole.
fn read_bounded(path: &std::path::Path) -> tribofe::Result<String> {
    use tribofe::io::input::{read_text, TABLE_MAX_BYTES, TOML_MAX_BYTES};
    let toml = path.extension().is_some_and(|e| e == "toml");
    read_text(path, "--merge", if toml { TOML_MAX_BYTES } else { TABLE_MAX_BYTES })
}
