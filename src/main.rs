//! The `tribofe` command: parses arguments, calls the library, prints. No FE logic lives here.

mod cli;

use clap::Parser;

fn main() {
    // Die quietly on a closed pipe (`tribofe check | head`) like other Unix tools, instead of
    // panicking in println!.
    #[cfg(unix)]
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    let args = cli::Cli::parse();
    if let Err(e) = cli::run(args) {
        eprintln!("error: {e}");
        std::process::exit(2);
    }
}
