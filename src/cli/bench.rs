//! `tribofe bench`: the pipeline's phase times on the thin strip and a square of ~1e6 DOFs,
//! each run in a fresh process so that its peak memory is its own.

use clap::Args as ClapArgs;
use std::path::{Path, PathBuf};
use tribofe::linalg::solve::Ordering;
use tribofe::studies::bench::{self, Case, Config, Row};

#[derive(ClapArgs, Debug)]
pub struct Args {
    /// Cases to run (stripNY = the paper's scene with h = t/NY; squareN = N x N QUA4).
    #[arg(long, value_delimiter = ',', default_value = "strip50,square707")]
    pub case: Vec<Case>,
    /// Also run the strip family with these NY (no value: 5,16,50; 100 = 4e6 DOFs).
    #[arg(long, value_delimiter = ',', num_args = 0..)]
    pub sizes: Option<Vec<usize>>,
    /// Threads (rayon pool: assembly, the two halves of the factorisation, faer's dense
    /// kernels); a list runs each [default: all cores].
    #[arg(long, value_delimiter = ',')]
    pub threads: Vec<usize>,
    /// Factorisation: auto (faer's choice), supernodal, simplicial; a list runs each.
    #[arg(long, value_delimiter = ',', default_value = "auto")]
    pub factor: Vec<String>,
    /// Ordering: auto (two-domain nested dissection on large grids), nd (nested dissection, one factorisation), amd; a list runs each.
    #[arg(long, value_delimiter = ',', default_value = "auto")]
    pub ordering: Vec<String>,
    /// Runs per setting; the best (smallest in-process time) is reported.
    #[arg(long, default_value_t = 1)]
    pub repeat: usize,
    /// Size of the DGEMM that measures the machine's dense rate (0 = skip).
    #[arg(long, default_value_t = 2000)]
    pub dgemm: usize,
    /// Writes bench.csv and dgemm.csv here.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Write into the --out folder even if it is not tribofe's by its run.toml; only files of
    /// this run's names are replaced (regular files only), nothing else is deleted.
    #[arg(long)]
    #[arg(requires = "out")]
    pub force: bool,
    /// Runs the cases in this process (peak memory is then cumulative).
    #[arg(long)]
    pub in_process: bool,
    /// Internal: run the single case here and print its CSV row only.
    #[arg(long, hide = true)]
    pub row: bool,
}

fn parse_factor(s: &str) -> tribofe::Result<Option<bool>> {
    match s {
        "auto" => Ok(None),
        "supernodal" => Ok(Some(true)),
        "simplicial" => Ok(Some(false)),
        _ => {
            Err(tribofe::Error::input("--factor", format!("'{s}': expected auto, supernodal or simplicial")))
        }
    }
}

fn parse_ordering(s: &str) -> tribofe::Result<Ordering> {
    match s {
        "auto" => Ok(Ordering::Auto),
        "amd" => Ok(Ordering::Amd),
        "nd" => Ok(Ordering::NestedDissection),
        _ => Err(tribofe::Error::input("--ordering", format!("'{s}': expected auto (two domains on large grids), nd (one factorisation, nested dissection) or amd"))),
    }
}

pub fn run(mut args: Args) -> tribofe::Result<()> {
    if args.threads.is_empty() {
        args.threads.push(std::thread::available_parallelism().map_or(1, |n| n.get()));
    }
    if args.repeat == 0 {
        return Err(tribofe::Error::input("--repeat", "0: a setting needs at least one run"));
    }
    if args.threads.contains(&0) {
        return Err(tribofe::Error::input("--threads", "0: a run needs at least one thread"));
    }
    if let Some(dir) = &args.out {
        tribofe::io::outdir::check(dir, args.force)?;
    }
    // Three n x n matrices of f64 must fit in half the memory.
    let dgemm_bytes = 24.0 * (args.dgemm as f64).powi(2);
    if dgemm_bytes > 0.5 * tribofe::scene::limits::memory_bytes().0 {
        return Err(tribofe::Error::input(
            "--dgemm",
            format!(
                "{}: three {0} x {0} matrices need {}, more than half the memory this process may use (machine, ulimit or cgroup)",
                args.dgemm,
                tribofe::scene::limits::bytes_text(dgemm_bytes)
            ),
        ));
    }
    let mut configs = Vec::new();
    for &threads in &args.threads {
        for f in &args.factor {
            for o in &args.ordering {
                configs.push(Config { threads, supernodal: parse_factor(f)?, ordering: parse_ordering(o)? });
            }
        }
    }
    if args.row {
        let row = bench::run_case(args.case[0], &configs[0], Some(&time_outputs))?;
        outln!("{}", row.to_csv());
        return Ok(());
    }
    let mut cases = args.case.clone();
    if let Some(sizes) = &args.sizes {
        let ny = if sizes.is_empty() { vec![5, 16, 50] } else { sizes.clone() };
        cases.retain(|c| !matches!(c, Case::Strip(_)));
        cases.splice(0..0, ny.into_iter().map(Case::Strip));
    }
    let exe = std::env::current_exe().map_err(|e| tribofe::Error::io("current executable", e))?;
    let mut rows: Vec<Row> = Vec::new();
    for &case in &cases {
        for cfg in &configs {
            let runs = (0..args.repeat.max(1))
                .map(|_| {
                    if args.in_process {
                        bench::run_case(case, cfg, Some(&time_outputs))
                    } else {
                        run_isolated(&exe, case, cfg)
                    }
                })
                .collect::<tribofe::Result<Vec<_>>>()?;
            rows.extend(bench::best(runs));
        }
    }
    let mut dgemm = Vec::new();
    if args.dgemm > 0 {
        for &t in &args.threads {
            errln!("bench: dense {n} x {n} matmul on {t} thread(s) ...", n = args.dgemm);
            dgemm.push((t, bench::dgemm_gflops(args.dgemm, t)));
        }
    }
    out!("{}", bench::table(&rows, &dgemm));
    if let Some(dir) = &args.out {
        let d = super::begin_out(dir, args.force)?;
        write_csv(&rows, &dgemm, d.path())?;
        super::write_run_file(d.path(), None, &tribofe::report::run_file::NoResults {})?;
        d.commit()?;
        outln!("wrote {}/{{bench.csv, dgemm.csv, run.toml}}", dir.display());
    }
    Ok(())
}

/// Times a strip case's outputs (CSVs and figure, then the VTU field files) written to a
/// private temporary folder, removed afterwards: (outputs, fields), s.
fn time_outputs(
    res: &tribofe::studies::check::CheckResult,
    sm: &tribofe::scene::SceneModel,
) -> tribofe::Result<(f64, f64)> {
    use std::time::Instant;
    let dir = std::env::temp_dir().join(format!("tribofe-bench-{}", std::process::id()));
    let clock = Instant::now();
    let written = tribofe::report::check::write(res, None, &dir);
    let output = clock.elapsed().as_secs_f64();
    let clock = Instant::now();
    let fields = written
        .and_then(|_| tribofe::report::check::write_fields(res, sm, &dir, tribofe::io::FieldFormat::Vtu));
    let fields_s = clock.elapsed().as_secs_f64();
    let _ = std::fs::remove_dir_all(&dir);
    fields.map(|_| (output, fields_s))
}

/// Runs `exe bench --row` for one case in a fresh process (so its peak memory is its own)
/// and parses the row it prints.
fn run_isolated(exe: &Path, case: Case, cfg: &Config) -> tribofe::Result<Row> {
    let factor = cfg.supernodal.map_or("auto", |s| if s { "supernodal" } else { "simplicial" });
    let out = std::process::Command::new(exe)
        .args([
            "bench",
            "--row",
            "--case",
            &case.name(),
            "--threads",
            &cfg.threads.to_string(),
            "--factor",
            factor,
            "--ordering",
            bench::ordering_name(&cfg.ordering),
        ])
        .stderr(std::process::Stdio::inherit())
        .output()
        .map_err(|e| tribofe::Error::io(exe, e))?;
    let text = String::from_utf8_lossy(&out.stdout);
    if !out.status.success() {
        return Err(tribofe::Error::input(
            format!("bench case {}", case.name()),
            format!("child process failed ({}): {}", out.status, text.trim()),
        ));
    }
    Row::from_csv(text.lines().last().unwrap_or(""))
}

/// Writes `bench.csv` (one line per run) and `dgemm.csv` into `dir`.
fn write_csv(rows: &[Row], dgemm: &[(usize, f64)], dir: &Path) -> tribofe::Result<()> {
    let mut s = format!("{}\n", Row::CSV_HEADER);
    rows.iter().for_each(|r| s.push_str(&(r.to_csv() + "\n")));
    tribofe::report::write_atomic(&dir.join("bench.csv"), s.as_bytes())?;
    let mut d = String::from("threads,gflops\n");
    dgemm.iter().for_each(|(t, g)| d.push_str(&format!("{t},{g:.2}\n")));
    tribofe::report::write_atomic(&dir.join("dgemm.csv"), d.as_bytes())
}
