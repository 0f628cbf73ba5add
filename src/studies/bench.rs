//! Benchmarks of the whole pipeline on two ~1e6-DOF problems: the paper's thin strip (aspect
//! 200, rigid plate, `check::run`) and a square (`problem::solve`), with the phase breakdown,
//! sizes, the factorisation's flop rate against the dense DGEMM rate of the machine, and the
//! peak memory. Peak memory is per process, so callers run each case in a fresh process (the
//! binary's `bench` spawns itself; this module spawns nothing and writes nothing).

use crate::error::{Error, Result};
use crate::fem::constraints::{dof, Constraints};
use crate::fem::material::Material;
use crate::fem::mesher::Rectangle;
use crate::fem::problem::{solve, LoadCase, Prepared, Timings};
use crate::linalg::solve::{Ordering, SolverOptions};
use crate::scene::Scene;
use crate::studies::check;
use std::fmt::Write;
use std::time::Instant;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Case {
    /// The paper's scene with h = t / ny (200 ny x ny QUA4).
    Strip(usize),
    /// n x n QUA4 on [0, 1]^2, bottom clamped, uniform traction on top.
    Square(usize),
}

impl Case {
    pub fn name(&self) -> String {
        match self {
            Case::Strip(ny) => format!("strip{ny}"),
            Case::Square(n) => format!("square{n}"),
        }
    }
}

impl std::str::FromStr for Case {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        let num = |p: &str| s.strip_prefix(p).and_then(|v| v.parse::<usize>().ok()).filter(|&v| v > 0);
        num("strip").map(Case::Strip).or_else(|| num("square").map(Case::Square)).ok_or_else(|| {
            Error::input("bench case", format!("'{s}': expected stripNY or squareN, e.g. strip50, square707"))
        })
    }
}

/// Solver settings of one run.
#[derive(Debug, Clone, PartialEq)]
pub struct Config {
    /// faer threads for the factorisation and rayon threads for the assembly.
    pub threads: usize,
    /// None = faer's choice.
    pub supernodal: Option<bool>,
    pub ordering: Ordering,
}

/// One benchmark run. Times in s; `output` is None where the case writes nothing.
#[derive(Debug, Clone)]
pub struct Row {
    pub case: String,
    pub threads: usize,
    pub factor: String,
    pub ordering: String,
    pub dofs: usize,
    pub nnz_k: usize,
    pub nnz_l: usize,
    pub flops: f64,
    pub t: Timings,
    pub output: Option<f64>,
    /// Writing the default field files (`check --fields vtu`: one raw-binary .vtu per load
    /// case and the .pvd), s; None where the case writes none.
    pub fields: Option<f64>,
    /// VmHWM of the process that ran the case (before the refactorisation runs), MiB.
    pub peak_mib: f64,
    /// Core-seconds the numeric factorisation spent in dense kernels (two-domain solver only).
    pub dense_s: Option<f64>,
    /// Numeric factorisation when refactorising with the same analysis (as in a sweep), s.
    pub numeric_warm: f64,
}

impl Row {
    /// Unknowns per second of the whole pipeline; 0 when no time was measured at all (never
    /// infinite: `bench --case square1` once wrote `inf` from times rounded to 0 in the CSV).
    pub fn dofs_per_s(&self) -> f64 {
        let total = self.t.total();
        if total > 0.0 {
            self.dofs as f64 / total
        } else {
            0.0
        }
    }
    pub fn gflops(&self) -> f64 {
        rate(self.flops, self.t.numeric)
    }
    pub fn gflops_warm(&self) -> f64 {
        rate(self.flops, self.numeric_warm)
    }
    /// Rate of the dense kernels alone on this factorisation's fronts, per core, GFLOP/s: the
    /// most any code built on them could reach here.
    pub fn front_gflops_per_core(&self) -> Option<f64> {
        self.dense_s.map(|d| rate(self.flops, d))
    }

    pub const CSV_HEADER: &'static str = "case,threads,factor,ordering,dofs,nnz_k,nnz_l,gflop,mesh_s,pattern_s,assembly_s,symbolic_s,numeric_s,solve_s,recovery_s,other_s,total_s,output_s,dofs_per_s,gflops,peak_mib,dense_core_s,numeric_warm_s,fields_s";

    pub fn to_csv(&self) -> String {
        let t = &self.t;
        let out = self.output.map_or(String::new(), |v| format!("{v:.4}"));
        let dense = self.dense_s.map_or(String::new(), |v| format!("{v:.4}"));
        // Empty when the system does not report the peak (not NaN).
        let peak = if self.peak_mib.is_finite() { format!("{:.1}", self.peak_mib) } else { String::new() };
        let fields = self.fields.map_or(String::new(), |v| format!("{v:.4}"));
        format!(
            "{},{},{},{},{},{},{},{:.4},{:.4e},{:.4e},{:.4e},{:.4e},{:.4e},{:.4e},{:.4e},{:.4e},{:.4e},{out},{:.0},{:.3},{peak},{dense},{:.4e},{fields}",
            self.case, self.threads, self.factor, self.ordering, self.dofs, self.nnz_k, self.nnz_l, self.flops / 1e9, t.mesh, t.pattern, t.assembly, t.symbolic, t.numeric, t.solve, t.recovery,
            t.other, t.total(), self.dofs_per_s(), self.gflops(), self.numeric_warm
        )
    }

    /// Parses a line written by [`Row::to_csv`] (derived columns are recomputed).
    pub fn from_csv(line: &str) -> Result<Self> {
        let f: Vec<&str> = line.trim().split(',').collect();
        let bad = || Error::input("bench row", format!("cannot parse '{}'", line.trim()));
        if f.len() != Self::CSV_HEADER.split(',').count() {
            return Err(bad());
        }
        let num = |i: usize| f[i].parse::<f64>().map_err(|_| bad());
        let int = |i: usize| f[i].parse::<usize>().map_err(|_| bad());
        let t = Timings {
            mesh: num(8)?,
            pattern: num(9)?,
            assembly: num(10)?,
            symbolic: num(11)?,
            numeric: num(12)?,
            solve: num(13)?,
            recovery: num(14)?,
            other: num(15)?,
        };
        Ok(Row {
            case: f[0].into(),
            threads: int(1)?,
            factor: f[2].into(),
            ordering: f[3].into(),
            dofs: int(4)?,
            nnz_k: int(5)?,
            nnz_l: int(6)?,
            flops: num(7)? * 1e9,
            t,
            output: if f[17].is_empty() { None } else { Some(num(17)?) },
            peak_mib: if f[20].is_empty() { f64::NAN } else { num(20)? },
            dense_s: if f[21].is_empty() { None } else { Some(num(21)?) },
            numeric_warm: num(22)?,
            fields: if f[23].is_empty() { None } else { Some(num(23)?) },
        })
    }
}

pub fn ordering_name(o: &Ordering) -> &'static str {
    match o {
        Ordering::Auto => "auto",
        Ordering::Amd => "amd",
        Ordering::NestedDissection => "nd",
        Ordering::Custom(_) => "custom",
        Ordering::TwoDomain(_) => "2dom",
    }
}

/// Writes a strip case's outputs (the CSVs and figure, then the field files) and returns
/// their two wall times, s: given by the caller, so that this study imports no report code.
pub type Outputs<'a> =
    &'a (dyn Fn(&check::CheckResult, &crate::scene::SceneModel) -> Result<(f64, f64)> + Sync);

/// Runs one case in this process, with a rayon pool of `cfg.threads` threads; a strip case's
/// outputs are timed by `outputs` (None: not timed).
pub fn run_case(case: Case, cfg: &Config, outputs: Option<Outputs>) -> Result<Row> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(cfg.threads)
        .build()
        .map_err(|e| Error::input("threads", e.to_string()))?;
    let opts = SolverOptions {
        ordering: cfg.ordering.clone(),
        threads: cfg.threads,
        supernodal: cfg.supernodal,
        ..Default::default()
    };
    // Ignored errors: a closed or full standard error must not end the run (eprintln! panics).
    use std::io::Write;
    let _ = writeln!(
        std::io::stderr(),
        "bench: {} ({} thread(s), {}, {}) ...",
        case.name(),
        cfg.threads,
        cfg.supernodal.map_or("auto", |s| if s { "supernodal" } else { "simplicial" }),
        ordering_name(&cfg.ordering)
    );
    let clock = Instant::now();
    let mut row = pool.install(|| match case {
        Case::Strip(ny) => strip(ny, &opts, outputs),
        Case::Square(n) => square(n, &opts),
    })?;
    row.ordering = ordering_name(&cfg.ordering).into();
    let _ =
        writeln!(std::io::stderr(), "bench: {} done in {:.1} s", case.name(), clock.elapsed().as_secs_f64());
    Ok(row)
}

fn strip(ny: usize, opts: &SolverOptions, outputs: Option<Outputs>) -> Result<Row> {
    let mut scene = Scene::default();
    scene.mesh.h = scene.block.thickness / ny as f64;
    scene.mesh.n_thick = Some(ny);
    let (res, sm) = check::run(&scene, opts)?;
    let peak_mib = peak_memory_mib().unwrap_or(f64::NAN);
    let prepared = check::prepare(&scene, opts)?;
    let numeric_warm = refactorisation_time(|| {
        Ok(check::run_model(&scene, scene.build()?, 0.0, opts, Some(&prepared))?.0.stats.timings.numeric)
    })?;
    let (output, fields_s) = match outputs {
        Some(f) => f(&res, &sm).map(|(o, f)| (Some(o), Some(f)))?,
        None => (None, None),
    };
    Ok(Row {
        case: Case::Strip(ny).name(),
        threads: opts.threads,
        factor: factor_name(res.stats.supernodal),
        ordering: String::new(),
        dofs: res.stats.n_unknowns,
        nnz_k: res.stats.matrix_nnz,
        nnz_l: res.stats.factor_nnz,
        flops: res.stats.factor_flops,
        t: res.stats.timings,
        output,
        fields: fields_s,
        peak_mib,
        dense_s: res.stats.dense_seconds,
        numeric_warm,
    })
}

fn square(n: usize, opts: &SolverOptions) -> Result<Row> {
    let clock = Instant::now();
    let mesh = Rectangle::new(0.0, 1.0, 0.0, 1.0, n, n).build()?;
    let mut c = Constraints::new(mesh.n_nodes());
    for k in mesh.set_nodes("bottom")? {
        c.fix(dof(k, 0));
        c.fix(dof(k, 1));
    }
    let mut f = vec![0.0; 2 * mesh.n_nodes()];
    crate::fem::loads::add_edge_traction(&mesh, "top", &|_| [1e3, -1e3], &mut f)?;
    let case = LoadCase { prescribed: vec![0.0; c.n_fixed()], forces: f };
    let model = crate::fem::assembly::Model::new(&mesh, Material::plane_strain(1e6, 0.3)?);
    let mesh_time = clock.elapsed().as_secs_f64();
    let hint = "check the square benchmark";
    let sol = solve(&model, &c, std::slice::from_ref(&case), opts, hint)?;
    let peak_mib = peak_memory_mib().unwrap_or(f64::NAN);
    let prepared = Prepared::new(&mesh, &c, opts)?;
    let numeric_warm = refactorisation_time(|| {
        Ok(prepared.solve(&model, &c, std::slice::from_ref(&case), opts, hint)?.stats.timings.numeric)
    })?;
    let clock = Instant::now();
    let stresses = crate::fem::recovery::nodal_stresses(&model, &sol.u[0]);
    std::hint::black_box(stresses);
    let t = Timings { mesh: mesh_time, recovery: clock.elapsed().as_secs_f64(), ..sol.stats.timings };
    Ok(Row {
        case: Case::Square(n).name(),
        threads: opts.threads,
        factor: factor_name(sol.stats.supernodal),
        ordering: String::new(),
        dofs: sol.stats.n_unknowns,
        nnz_k: sol.stats.matrix_nnz,
        nnz_l: sol.stats.factor_nnz,
        flops: sol.stats.factor_flops,
        t,
        output: None,
        fields: None,
        peak_mib,
        dense_s: sol.stats.dense_seconds,
        numeric_warm,
    })
}

/// Numeric time of the second of two solves with one analysis: as in a sweep, the first leaves
/// the factor's memory to the second.
fn refactorisation_time(mut numeric: impl FnMut() -> Result<f64>) -> Result<f64> {
    numeric()?;
    numeric()
}

/// GFLOP/s; 0 for a time too short to be stored (the CSV keeps 0.1 ms), never NaN.
fn rate(flops: f64, seconds: f64) -> f64 {
    if seconds > 0.0 {
        flops / seconds / 1e9
    } else {
        0.0
    }
}

fn factor_name(supernodal: bool) -> String {
    if supernodal { "supernodal" } else { "simplicial" }.into()
}

/// Peak resident memory of this process so far (VmHWM), MiB; None off Linux.
pub fn peak_memory_mib() -> Option<f64> {
    let s = std::fs::read_to_string("/proc/self/status").ok()?;
    let kb: f64 = s
        .lines()
        .find_map(|l| l.strip_prefix("VmHWM:"))?
        .trim()
        .trim_end_matches("kB")
        .trim()
        .parse()
        .ok()?;
    Some(kb / 1024.0)
}

/// Dense matrix product rate of faer on n x n f64 matrices, GFLOP/s (best of 3).
pub fn dgemm_gflops(n: usize, threads: usize) -> f64 {
    let a = faer::Mat::<f64>::from_fn(n, n, |i, j| ((i * 7 + j * 13) % 17) as f64 - 8.0);
    let b = faer::Mat::<f64>::from_fn(n, n, |i, j| ((i * 5 + j * 3) % 11) as f64 - 5.0);
    let mut c = faer::Mat::<f64>::zeros(n, n);
    let par = if threads > 1 { faer::Par::rayon(threads) } else { faer::Par::Seq };
    let best = (0..3)
        .map(|_| {
            let clock = Instant::now();
            faer::linalg::matmul::matmul(c.as_mut(), faer::Accum::Replace, a.as_ref(), b.as_ref(), 1.0, par);
            clock.elapsed().as_secs_f64()
        })
        .fold(f64::INFINITY, f64::min);
    std::hint::black_box(&c);
    2.0 * (n as f64).powi(3) / best / 1e9
}

/// Of several runs of the same case and settings, the one with the smallest in-process time.
pub fn best(rows: Vec<Row>) -> Option<Row> {
    rows.into_iter().min_by(|a, b| a.t.total().total_cmp(&b.t.total()))
}

/// Readable table of the runs; `dgemm` (threads, GFLOP/s) sets the ceiling each
/// factorisation's rate is compared with.
pub fn table(rows: &[Row], dgemm: &[(usize, f64)]) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "{:<11} {:>2} {:<10} {:<4} {:>9} {:>9} {:>10} {:>6} | {:>6} {:>6} {:>6} {:>6} {:>6} {:>6} {:>6} {:>6} | {:>6} {:>6} {:>6} | {:>8} {:>6} {:>5} | {:>6} {:>5} {:>6} | {:>7}",
        "case", "th", "factor", "ord", "DOFs", "nnz(K)", "nnz(L)", "GFLOP", "mesh", "patt", "asm", "symb", "numer", "solve", "recov", "other", "total", "output", "fields", "DOF/s", "GF/s", "%peak", "refact", "%peak", "%front", "MiB");
    for r in rows {
        let t = &r.t;
        let dgemm_rate = dgemm.iter().find(|d| d.0 == r.threads).map(|d| d.1);
        let percent = |rate: f64| dgemm_rate.map_or("-".to_string(), |g| format!("{:.1}", 100.0 * rate / g));
        let front = dgemm_rate
            .zip(r.front_gflops_per_core())
            .map_or("-".to_string(), |(g, f)| format!("{:.1}", 100.0 * f * r.threads as f64 / g));
        let _ = writeln!(
            s,
            "{:<11} {:>2} {:<10} {:<4} {:>9} {:>9} {:>10} {:>6.2} | {:>6.3} {:>6.3} {:>6.3} {:>6.3} {:>6.3} {:>6.3} {:>6.3} {:>6.3} | {:>6.2} {:>6} {:>6} | {:>8.2e} {:>6.2} {:>5} | {:>6.3} {:>5} {:>6} | {:>7.0}",
            r.case, r.threads, r.factor, r.ordering, r.dofs, r.nnz_k, r.nnz_l, r.flops / 1e9, t.mesh, t.pattern, t.assembly, t.symbolic, t.numeric, t.solve, t.recovery, t.other, t.total(),
            r.output.map_or("-".into(), |v| format!("{v:.3}")), r.fields.map_or("-".into(), |v| format!("{v:.3}")), r.dofs_per_s(), r.gflops(), percent(r.gflops()), r.numeric_warm, percent(r.gflops_warm()), front, r.peak_mib
        );
    }
    let _ = writeln!(s, "times in s; symb = ordering + symbolic analysis; solve = all load cases + condition probe + residual check; other = the rest of the run's wall time (total = wall time, mesh to recovery); output = CSVs and fig2.svg; fields = the default field files (check --fields vtu); %peak = numeric GFLOP/s / DGEMM GFLOP/s at the same thread count");
    let _ = writeln!(s, "refact = numeric factorisation again with the same analysis and, with two domains, the factor's memory reused (as in a sweep); first-touch page faults of fresh memory make up most of the difference");
    let _ = writeln!(s, "%front = the dense kernels' own rate on this factorisation's fronts, per core, / DGEMM per core: the ceiling of %peak for any code using them (two-domain solver only)");
    for (th, g) in dgemm {
        let _ = writeln!(s, "dense DGEMM (faer matmul): {th} thread(s) {g:.1} GFLOP/s");
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The parent process reads back what the child printed: every stored field survives.
    #[test]
    fn row_round_trips_through_csv() {
        let t = Timings {
            mesh: 0.01,
            pattern: 0.02,
            assembly: 0.03,
            symbolic: 0.04,
            numeric: 0.5,
            solve: 0.06,
            recovery: 0.07,
            other: 0.005,
        };
        let row = Row {
            case: "strip50".into(),
            threads: 2,
            factor: "supernodal".into(),
            ordering: "auto".into(),
            dofs: 980099,
            nnz_k: 9210342,
            nnz_l: 71550638,
            flops: 7.141e9,
            t,
            output: Some(0.08),
            fields: Some(1.5),
            peak_mib: 1036.0,
            dense_s: Some(0.4088),
            numeric_warm: 0.3563,
        };
        for (output, dense_s, fields) in [(Some(0.08), Some(0.4088), Some(1.5)), (None, None, None)] {
            let r = Row { output, dense_s, fields, ..row.clone() };
            let back = Row::from_csv(&r.to_csv()).unwrap();
            assert_eq!(
                (back.case.as_str(), back.threads, back.dofs, back.nnz_l),
                ("strip50", 2, 980099, 71550638)
            );
            assert_eq!(
                (back.output, back.dense_s, back.numeric_warm, back.t.numeric, back.t.other),
                (output, dense_s, 0.3563, 0.5, 0.005)
            );
            assert_eq!(back.fields, fields);
            assert!((back.flops - 7.141e9).abs() < 1e5 && back.peak_mib == 1036.0);
        }
        assert!(Row::from_csv("strip50,2").is_err());
        // A tiny case's times round to 0 in the CSV: rates are 0, not NaN.
        let tiny = Row {
            flops: 0.0,
            numeric_warm: 0.0,
            dense_s: Some(0.0),
            t: Timings { numeric: 0.0, ..t },
            ..row
        };
        assert_eq!((tiny.gflops(), tiny.gflops_warm(), tiny.front_gflops_per_core()), (0.0, 0.0, Some(0.0)));
    }
}
