//! Subcommands, one file each. Each parses its flags into library types, calls the library
//! and prints; errors bubble up to `main` as one message and the exit status of
//! [`tribofe::Error::exit_status`].

/// `print!` into the command's standard output, which `main` writes once the command has
/// returned, so its results are on disk before any line is printed ([`write_stdout`]).
macro_rules! out {
    ($($t:tt)*) => { $crate::cli::write_stdout(format_args!($($t)*))? };
}
/// `println!` counterpart of [`out!`].
macro_rules! outln {
    ($($t:tt)*) => { $crate::cli::write_stdout(format_args!("{}\n", format_args!($($t)*)))? };
}

/// `eprint!` that never panics: with standard error closed or full (`2>/dev/full`, a closed
/// pipe) the text is lost, not the run (`eprint!` panics there: exit 101).
macro_rules! err {
    ($($t:tt)*) => {{
        let _ = std::io::Write::write_fmt(&mut std::io::stderr(), format_args!($($t)*));
    }};
}
/// `eprintln!` counterpart of [`err!`].
macro_rules! errln {
    () => { err!("\n") };
    ($($t:tt)*) => { err!("{}\n", format_args!($($t)*)) };
}

mod bench;
mod check;
mod converge;
mod edges;
mod precursors;
mod rupture;
mod scene_args;
mod slide;
mod solve;
mod stability;
mod sweep;

use clap::{Parser, Subcommand};

#[derive(Parser, Debug)]
#[command(
    name = "tribofe",
    version,
    about = "2D plane-strain FE verifier for frictional interfaces (SI units)",
    after_help = "Exit status: 0 success; 2 bad input (parameter, scene key, mesh, unreadable file, size \
above --max-dofs, unusable output folder); 3 numerical refusal (singular or ill-conditioned system, \
failed self-check); 4 failure while writing results, or threads refused by the system; 5 incomplete \
(a cap met mid-run: the results up to there written, the cap named in run.toml); 130 \
interrupted by SIGINT/SIGTERM (temporaries removed, the output folder as before; an interrupt after \
the results were committed lets the run finish with its own status and a note); 141 standard output \
closed before everything was printed (`| head`; the results are on disk, written before anything is \
printed). Inputs are checked before any work starts; results go to a hidden folder and are put in \
place at the end. Every folder holds a run.toml (version, source revision, date, host, command line, \
options, scene, and the size and SHA-256 of every file written). --out refuses an existing folder \
that is not tribofe's by that record unless --force is given; a rerun replaces only the files its \
run.toml lists and keeps everything else, and never writes over a user's file of the same name \
(docs/outputs-and-provenance.md)."
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

// Negative numbers are values, not flags, so a value like `--h -1` reaches the range checks.
#[derive(Subcommand, Debug)]
pub enum Command {
    /// A rectangle with one condition per side (clamped, roller, displaced, traction, free), any element.
    #[command(allow_negative_numbers = true)]
    Solve(solve::Args),
    /// The paper's check: interface pressure and shear under the plate against the model (fig. 2).
    #[command(allow_negative_numbers = true)]
    Check(check::Args),
    /// Mesh convergence of the check: errors per zone, orders, edge widths, accuracy against time.
    #[command(allow_negative_numbers = true)]
    Converge(converge::Args),
    /// Precursors to sliding (Scheibert & Dysthe model): the paper's iteration, its n(r, g) map, and the FE studies; one subcommand each.
    #[command(allow_negative_numbers = true)]
    Precursors(precursors::Args),
    /// Frictional interface (coulomb, static-kinetic, slip-weakening): N then X at height H, solved event by event.
    #[command(allow_negative_numbers = true)]
    Slide(Box<slide::Args>),
    /// Dynamic rupture on a rigid flat with slip-weakening friction (explicit elastodynamics; the cross-check scene).
    #[command(allow_negative_numbers = true)]
    Rupture(rupture::Args),
    /// The block's ends on the frictional interface: pre-slip under N vs refinement, trailing-end opening vs the first precursor.
    ///
    /// Cost of the defaults (4 pre-slip meshes, 16 opening runs, meshes graded to the ends):
    /// about 6 s of CPU, 4 s wall on 2 cores (15 s under a load of 10), 0.45 GB peak resident
    /// memory (`/usr/bin/time -v tribofe edges`). Uniform meshes (--end-grading 1)
    /// cost far more on the paper's 0.4 m block: the former defaults (uniform, the opening at
    /// t/h = 2) took 56 s and 10 GB.
    #[command(allow_negative_numbers = true)]
    Edges(edges::Args),
    /// Pipeline benchmark: phase times, sizes, GFLOP/s and peak memory on ~1e6-DOF problems.
    #[command(allow_negative_numbers = true)]
    Bench(bench::Args),
    /// Numerical stability: stiff elastic plate, near-incompressibility, element shape, thin layers, singular corners.
    #[command(allow_negative_numbers = true)]
    Stability(stability::Args),
    /// The check over a grid of scene parameters: model, corrected model and FE, verdicts, CSV and maps.
    #[command(allow_negative_numbers = true)]
    Sweep(sweep::Args),
}

/// What the command prints, held until it returns: its output folder is committed before
/// the first line reaches a pipe that may close (`tribofe precursors | head -1`).
static STDOUT: std::sync::Mutex<String> = std::sync::Mutex::new(String::new());

/// Appends to the held standard output ([`flush_stdout`] writes it). Returns a Result so the
/// `out!` call sites keep their `?`.
pub fn write_stdout(args: std::fmt::Arguments) -> tribofe::Result<()> {
    use std::fmt::Write;
    let _ = STDOUT.lock().unwrap_or_else(|e| e.into_inner()).write_fmt(args);
    Ok(())
}

/// Writes the held standard output, control bytes quoted ([`tribofe::error::quote_lines`]).
pub fn flush_stdout() -> std::io::Result<()> {
    use std::io::Write;
    let text = std::mem::take(&mut *STDOUT.lock().unwrap_or_else(|e| e.into_inner()));
    let mut o = std::io::stdout().lock();
    // Line by line, as a filter writes: a reader that stops early (`| head -1`) is seen as a
    // closed pipe on the next line, not hidden in one large write into the pipe's buffer.
    for line in tribofe::error::quote_lines(&text).split_inclusive('\n') {
        o.write_all(line.as_bytes()).and_then(|_| o.flush())?;
    }
    Ok(())
}

/// The command line and every option's value, for the run.toml of every command.
static INVOCATION: std::sync::OnceLock<tribofe::report::run_file::Invocation> = std::sync::OnceLock::new();

/// The options typed on the command line (clap ids: `n_ref`, `max_events`), not defaulted.
static GIVEN: std::sync::OnceLock<std::collections::BTreeSet<String>> = std::sync::OnceLock::new();

/// Whether option `id` (its field name) was typed, rather than left at its default.
pub fn given(id: &str) -> bool {
    GIVEN.get().is_some_and(|g| g.contains(id))
}

/// The invocation recorded by [`parse`] (empty when the command was built otherwise).
pub fn invocation() -> &'static tribofe::report::run_file::Invocation {
    INVOCATION.get_or_init(Default::default)
}

/// `--flag -1,2` as `--flag=-1,2`: clap reads a lone negative number after a flag as its value
/// (allow_negative_numbers) but a negative list or range (`-1,2`, `-1:1:5`) as an unknown
/// flag. A word after a long flag that takes a value is joined to it when it starts with `-`
/// and a digit or `.`, or is a negative number as Rust reads one (`-inf`), which no flag is.
fn join_negative_values(cmd: &clap::Command, args: Vec<std::ffi::OsString>) -> Vec<std::ffi::OsString> {
    let sub = args.iter().skip(1).find_map(|a| a.to_str().and_then(|a| cmd.find_subcommand(a)));
    let Some(mut sub) = sub else { return args };
    // A subcommand's own subcommand (`precursors fe-map`) holds the flags.
    if let Some(inner) = args.iter().skip(2).find_map(|a| a.to_str().and_then(|a| sub.find_subcommand(a))) {
        sub = inner;
    }
    let takes_value = |long: &str| {
        sub.get_arguments().any(|a| {
            a.get_action().takes_values()
                && (a.get_long() == Some(long) || a.get_all_aliases().is_some_and(|al| al.contains(&long)))
        })
    };
    let mut out = Vec::with_capacity(args.len());
    let mut it = args.into_iter().peekable();
    while let Some(a) = it.next() {
        let flag =
            a.to_str().and_then(|s| s.strip_prefix("--")).filter(|f| !f.contains('=') && !f.is_empty());
        // `-inf`, `-nan` and `-infinity` too (clap takes them for flags): they reach the
        // range checks and are refused there, naming the flag.
        let next_negative = it.peek().and_then(|n| n.to_str()).is_some_and(|n| {
            let mut c = n.chars();
            c.next() == Some('-')
                && (c.next().is_some_and(|c| c.is_ascii_digit() || c == '.') || n.parse::<f64>().is_ok())
        });
        match flag {
            Some(f) if next_negative && takes_value(f) => {
                let mut joined = a.clone();
                joined.push("=");
                joined.push(it.next().unwrap_or_default());
                out.push(joined);
            }
            _ => out.push(a),
        }
    }
    out
}

/// The command-line parser: [`Cli`] with the earlier flag forms of `precursors` hidden.
fn command() -> clap::Command {
    use clap::CommandFactory;
    Cli::command().mut_subcommand("precursors", precursors::hide_old_flags)
}

/// Parses the command line and records it with every option's effective value (given or
/// default) for run.toml.
pub fn parse() -> Result<Cli, clap::Error> {
    use clap::FromArgMatches;
    let typed: Vec<std::ffi::OsString> = std::env::args_os().collect();
    let args = join_negative_values(&command(), typed.clone());
    // Plain styles: the rendered error then holds no escape codes of clap's own, and the
    // user's bytes are kept (not stripped) for `main` to quote.
    let cmd = command().styles(clap::builder::Styles::plain());
    let m = cmd.clone().try_get_matches_from(&args)?;
    let cli = Cli::from_arg_matches(&m)?;
    let mut options = toml::Table::new();
    if let (Some((name, mut sub)), Some(mut sc)) =
        (m.subcommand(), m.subcommand_name().and_then(|n| cmd.find_subcommand(n)))
    {
        let mut name = name.to_string();
        // A nested subcommand (`precursors fe-map`): its options are the ones typed.
        if let Some((inner, m2)) = sub.subcommand() {
            if let Some(c2) = sc.find_subcommand(inner) {
                name = format!("{name} {inner}");
                (sub, sc) = (m2, c2);
            }
        }
        options.insert("subcommand".into(), toml::Value::String(name));
        let mut given = std::collections::BTreeSet::new();
        for arg in sc.get_arguments() {
            let id = arg.get_id().as_str();
            if sub.value_source(id) == Some(clap::parser::ValueSource::CommandLine) {
                given.insert(id.to_string());
            }
            let Ok(Some(raw)) = sub.try_get_raw(id) else { continue };
            let switch = !arg.get_action().takes_values();
            let vals: Vec<toml::Value> = raw
                .map(|v| {
                    let v = v.to_string_lossy().into_owned();
                    match (switch, v.as_str()) {
                        (true, "true") => toml::Value::Boolean(true),
                        (true, "false") => toml::Value::Boolean(false),
                        _ => toml::Value::String(v),
                    }
                })
                .collect();
            let key = arg.get_long().unwrap_or(id).to_string();
            let v = match &vals[..] {
                [one] => one.clone(),
                _ => toml::Value::Array(vals),
            };
            options.insert(key, v);
        }
        let _ = GIVEN.set(given);
    }
    let inv = tribofe::report::run_file::Invocation {
        args: typed.iter().map(|a| a.to_string_lossy().into_owned()).collect(),
        options,
    };
    let _ = INVOCATION.set(inv);
    Ok(cli)
}

/// Writes the folder's run.toml ([`tribofe::report::run_file`]) with this invocation.
pub fn write_run_file(
    dir: &std::path::Path,
    scene: Option<&tribofe::scene::Scene>,
    results: &impl serde::Serialize,
) -> tribofe::Result<()> {
    tribofe::report::run_file::write(dir, invocation(), scene, results)
}

/// The output folders this process has under way or committed, for the interrupt handler:
/// the binary's own state (the library has no process-wide switch; each folder has its own
/// [`Cleanup`](tribofe::io::outdir::Cleanup)).
static UNDER_WAY: std::sync::Mutex<Vec<tribofe::io::outdir::Cleanup>> = std::sync::Mutex::new(Vec::new());

/// Set when SIGINT/SIGTERM arrived after a folder was committed and none was left under way:
/// the run finishes with its own status, and [`run`] says so on stderr.
static LATE_INTERRUPT: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// [`tribofe::io::outdir::OutDir::begin`], the folder registered for removal on SIGINT/SIGTERM.
pub fn begin_out(out: &std::path::Path, force: bool) -> tribofe::Result<tribofe::io::outdir::OutDir> {
    // Locked first: once the handler holds the list, no new temporary folder is made.
    let mut list = UNDER_WAY.lock().unwrap_or_else(|e| e.into_inner());
    // An interrupt already taken (after an earlier folder's commit) ends the run here.
    if LATE_INTERRUPT.load(std::sync::atomic::Ordering::SeqCst) {
        return Err(tribofe::Error::Interrupted);
    }
    let dir = tribofe::io::outdir::OutDir::begin(out, force)?;
    list.retain(|c| c.is_open() || c.is_committed());
    list.push(dir.cleanup());
    Ok(dir)
}

/// SIGINT and SIGTERM are taken by one thread (blocked in all others, so this runs before any
/// thread starts). It removes the temporary output folders; when that leaves every `--out` as
/// it was, it exits with status 130. When a folder was already committed (the interrupt landed
/// after the commit point) and none is left under way, the run goes on to its end and exits
/// with its own status, a note on stderr ([`LATE_INTERRUPT`]). Not for `bench`, whose child
/// processes would inherit the mask.
fn catch_interrupts() {
    // SAFETY: plain libc signal-set calls on a local set; the mask is set before any thread
    // is spawned, so every later thread inherits it.
    let set = unsafe {
        let mut set: libc::sigset_t = std::mem::zeroed();
        libc::sigemptyset(&mut set);
        libc::sigaddset(&mut set, libc::SIGINT);
        libc::sigaddset(&mut set, libc::SIGTERM);
        if libc::pthread_sigmask(libc::SIG_BLOCK, &set, std::ptr::null_mut()) != 0 {
            return;
        }
        set
    };
    let waiter = std::thread::Builder::new().name("tribofe-signals".into()).spawn(move || loop {
        let mut sig = 0;
        // SAFETY: `set` is an initialised signal set; sigwait only writes `sig`.
        if unsafe { libc::sigwait(&set, &mut sig) } != 0 {
            return;
        }
        let list = UNDER_WAY.lock().unwrap_or_else(|e| e.into_inner());
        // remove() waits for a commit in progress: each folder ends removed or committed.
        let removed = list.iter().filter(|c| c.remove()).count();
        let committed: Vec<String> =
            list.iter().filter(|c| c.is_committed()).map(|c| c.out().display().to_string()).collect();
        use std::io::Write;
        if committed.is_empty() || removed > 0 {
            // Held until exit: no folder is registered after the cleanup.
            let mut e = std::io::stderr();
            if !committed.is_empty() {
                let _ = writeln!(
                    e,
                    "note: {} already hold(s) this run's complete results (committed before the interrupt)",
                    tribofe::error::quote(&committed.join(", "))
                );
            }
            let _ = writeln!(e, "error: {}", tribofe::Error::Interrupted);
            std::process::exit(tribofe::error::exit::INTERRUPTED);
        }
        // After the commit point: the results stand; the run ends on its own.
        LATE_INTERRUPT.store(true, std::sync::atomic::Ordering::SeqCst);
    });
    if waiter.is_err() {
        // No thread for it: restore the default action rather than ignore interrupts.
        // SAFETY: as above.
        unsafe { libc::pthread_sigmask(libc::SIG_UNBLOCK, &set, std::ptr::null_mut()) };
    }
}

pub fn run(cli: Cli) -> tribofe::Result<()> {
    // A file past RLIMIT_FSIZE is then a write error (EFBIG), cleaned up like any other,
    // instead of a signal that kills the process with its temporaries on disk.
    // SAFETY: setting a signal's disposition to ignore has no handler to run.
    unsafe { libc::signal(libc::SIGXFSZ, libc::SIG_IGN) };
    if !matches!(cli.command, Command::Bench(_)) {
        catch_interrupts();
    }
    // Built here so that threads the system refuses are an error, not a panic at first use.
    // Under a process limit, only the workers whose fixed reserves fit (scene::limits).
    let mut pool = rayon::ThreadPoolBuilder::new();
    if std::env::var_os("RAYON_NUM_THREADS").is_none() {
        if let Some(n) = tribofe::scene::limits::worker_threads() {
            pool = pool.num_threads(n);
        }
    }
    pool.build_global().map_err(|e| tribofe::Error::Resource {
        what: "the worker threads (rayon pool; RAYON_NUM_THREADS sets their number)".into(),
        why: e.to_string(),
    })?;
    // The library names its parameters (mu, N, Poisson's ratio); the user typed flags.
    const LAW: &[(&str, &str)] = &[
        ("mu", "--mu"),
        ("mu-s", "--mu-s"),
        ("mu-d", "--mu-d"),
        ("mu-s/mu-d", "--mu-s/--mu-d"),
        ("dc", "--dc"),
        ("N", "--n-force"),
        ("x-max", "--x-max"),
        ("cycles", "--cycles"),
        ("law", "--law"),
        ("newton", "--newton"),
        ("r", "--r"),
        ("g", "--g"),
        ("r, g", "--r, --g"),
    ];
    let draws = !matches!(cli.command, Command::Solve(_) | Command::Bench(_) | Command::Rupture(_));
    let done = match cli.command {
        Command::Solve(a) => solve::run(a).map_err(|e| {
            typed_flag(
                e,
                &[("Poisson's ratio", "--poisson"), ("Young's modulus", "--young"), ("mesh", "--nx/--ny")],
            )
        }),
        Command::Check(a) => check::run(a),
        Command::Converge(a) => converge::run(a),
        Command::Precursors(args) => precursors::run(args).map_err(|e| typed_flag(e, LAW)),
        Command::Slide(a) => slide::run(*a).map_err(|e| typed_flag(e, LAW)),
        Command::Edges(a) => edges::run(a).map_err(|e| typed_flag(e, LAW)),
        Command::Rupture(a) => rupture::run(a),
        Command::Bench(a) => bench::run(a),
        Command::Stability(a) => stability::run(a),
        Command::Sweep(a) => sweep::run(a).map_err(|e| {
            typed_flag(e, &[("mu-s", "--friction"), ("mu-d", "--friction"), ("cycles", "--cycles")])
        }),
    };
    // --write-scene: only once the run was accepted and has finished.
    let done = done.and_then(|_| scene_args::write_pending_scene());
    if LATE_INTERRUPT.load(std::sync::atomic::Ordering::SeqCst) {
        use std::io::Write;
        let _ = writeln!(
            std::io::stderr(),
            "note: interrupted (SIGINT/SIGTERM) after the results were committed; the run finished and its status stands"
        );
    }
    if done.is_ok() && draws && !tribofe::report::FIGURES {
        outln!("note: no figures (SVG) drawn: this tribofe was built without the `plots` feature; the tables are complete");
    }
    done
}

/// A refusal naming a library parameter (`what` equal to, or starting with, a name of `names`
/// and a space) renamed to the flag the user typed.
fn typed_flag(e: tribofe::Error, names: &[(&str, &str)]) -> tribofe::Error {
    match e {
        tribofe::Error::Input { what, why } => {
            let hit = names.iter().find_map(|(name, flag)| {
                if what == *name {
                    Some(flag.to_string())
                } else {
                    what.strip_prefix(name).filter(|r| r.starts_with(' ')).map(|r| format!("{flag}{r}"))
                }
            });
            tribofe::Error::Input { what: hit.unwrap_or(what), why }
        }
        e => e,
    }
}
