//! The `tribofe` command: parses arguments, calls the library, prints. No FE logic lives here.

#[macro_use]
mod cli;

// The studies report their own peak heap (converge's peak_heap_mib) through this allocator.
#[cfg(feature = "count-alloc")]
#[global_allocator]
static ALLOCATOR: tribofe::memory::CountingAlloc = tribofe::memory::CountingAlloc;
use std::io::Write;
use tribofe::error::exit;

fn main() {
    // Before any thread starts: arenas that fit RLIMIT_AS (scene::limits::fit_malloc_arenas).
    tribofe::scene::limits::fit_malloc_arenas();
    let args = match cli::parse() {
        Ok(a) => a,
        Err(e) => {
            // clap's own messages echo the arguments: control bytes quoted as everywhere else.
            let text = tribofe::error::quote_lines(&e.render().ansi().to_string());
            let _ = if e.use_stderr() {
                write!(std::io::stderr(), "{text}")
            } else {
                write!(std::io::stdout(), "{text}")
            };
            std::process::exit(e.exit_code());
        }
    };
    let result = cli::run(args);
    // Results are on disk by now: a closed pipe only loses the printed copy.
    let printed = cli::flush_stdout();
    let status = match (result, printed) {
        (Err(e), _) => {
            let _ = writeln!(std::io::stderr(), "error: {}", tribofe::error::quote_lines(&e.to_string()));
            e.exit_status()
        }
        (Ok(()), Ok(())) => exit::OK,
        // Rust ignores SIGPIPE, so a closed pipe is an EPIPE error here; the shell's status for
        // a process killed by SIGPIPE tells a script the output was cut.
        (Ok(()), Err(e)) if e.kind() == std::io::ErrorKind::BrokenPipe => exit::BROKEN_PIPE,
        (Ok(()), Err(e)) => {
            let e = tribofe::Error::io("standard output", e);
            let _ = writeln!(std::io::stderr(), "error: {e}");
            e.exit_status()
        }
    };
    std::process::exit(status);
}
