//! Subcommands, one file each. Each parses its flags into library types, calls the library
//! and prints; errors bubble up to `main` as one message and the exit status of
//! [`tribofe::Error::exit_status`].

/// `print!` that returns a write failure (closed pipe, full disk) to the caller with `?`
/// instead of panicking; `main` ends quietly on a closed pipe.
macro_rules! out {
    ($($t:tt)*) => { $crate::cli::write_stdout(format_args!($($t)*))? };
}
/// `println!` counterpart of [`out!`].
macro_rules! outln {
    ($($t:tt)*) => { $crate::cli::write_stdout(format_args!("{}\n", format_args!($($t)*)))? };
}

mod bench;
mod check;
mod converge;
mod edges;
mod precursors;
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
failed self-check); 4 failure while writing results, or threads refused by the system; 130 \
interrupted by SIGINT/SIGTERM (temporaries removed, the output folder as before). Inputs are checked \
before any work starts; results go to a fresh folder renamed into place at the end (all but sweep and \
precursors; README, \"Inputs and failures\")."
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
    /// Precursors to sliding (Scheibert & Dysthe model): event table, fig. 4, or the n(r, g) map (fig. 5).
    #[command(allow_negative_numbers = true)]
    Precursors(precursors::Args),
    /// Frictional interface (coulomb, static-kinetic, slip-weakening): N then X at height H, solved event by event.
    #[command(allow_negative_numbers = true)]
    Slide(slide::Args),
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

/// Writes to standard output and flushes, so a closed pipe is seen here, not at exit.
pub fn write_stdout(args: std::fmt::Arguments) -> tribofe::Result<()> {
    use std::io::Write;
    let mut o = std::io::stdout().lock();
    o.write_fmt(args).and_then(|_| o.flush()).map_err(|e| tribofe::Error::io("standard output", e))
}

/// SIGINT and SIGTERM are taken by one thread (blocked in all others, so this runs before any
/// thread starts): it removes the temporary output folders and exits with status 130, leaving
/// every `--out` as it was. Not for `bench`, whose child processes would inherit the mask.
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
    let waiter = std::thread::Builder::new().name("tribofe-signals".into()).spawn(move || {
        let mut sig = 0;
        // SAFETY: `set` is an initialised signal set; sigwait only writes `sig`.
        if unsafe { libc::sigwait(&set, &mut sig) } == 0 {
            tribofe::io::outdir::remove_temporaries();
            use std::io::Write;
            let _ = writeln!(std::io::stderr(), "error: {}", tribofe::Error::Interrupted);
            std::process::exit(tribofe::error::exit::INTERRUPTED);
        }
    });
    if waiter.is_err() {
        // No thread for it: restore the default action rather than ignore interrupts.
        // SAFETY: as above.
        unsafe { libc::pthread_sigmask(libc::SIG_UNBLOCK, &set, std::ptr::null_mut()) };
    }
}

pub fn run(cli: Cli) -> tribofe::Result<()> {
    if !matches!(cli.command, Command::Bench(_)) {
        catch_interrupts();
    }
    // Built here so that threads the system refuses are an error, not a panic at first use.
    rayon::ThreadPoolBuilder::new().build_global().map_err(|e| tribofe::Error::Resource {
        what: "the worker threads (rayon pool; RAYON_NUM_THREADS sets their number)".into(),
        why: e.to_string(),
    })?;
    match cli.command {
        Command::Solve(a) => solve::run(a),
        Command::Check(a) => check::run(a),
        Command::Converge(a) => converge::run(a),
        Command::Precursors(args) => precursors::run(args),
        Command::Slide(a) => slide::run(a),
        Command::Edges(a) => edges::run(a),
        Command::Bench(a) => bench::run(a),
        Command::Stability(a) => stability::run(a),
        Command::Sweep(a) => sweep::run(a),
    }
}
