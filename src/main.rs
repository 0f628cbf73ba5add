//! The `tribofe` command: parses arguments, calls the library, prints. No FE logic lives here.

#[macro_use]
mod cli;

use clap::Parser;

// The studies report their own peak heap (converge's peak_heap_mib) through this allocator.
#[cfg(feature = "count-alloc")]
#[global_allocator]
static ALLOCATOR: tribofe::memory::CountingAlloc = tribofe::memory::CountingAlloc;
use std::io::Write;
use tribofe::error::exit;

fn main() {
    let args = cli::Cli::parse();
    let status = match cli::run(args) {
        Ok(()) => exit::OK,
        // A closed pipe (`tribofe check | head`) is a normal end for a Unix filter: the reader
        // has what it wanted. Rust ignores SIGPIPE, so the write returns EPIPE and lands here.
        Err(tribofe::Error::Io { source, .. }) if source.kind() == std::io::ErrorKind::BrokenPipe => exit::OK,
        Err(e) => {
            let _ = writeln!(std::io::stderr(), "error: {e}");
            e.exit_status()
        }
    };
    std::process::exit(status);
}
