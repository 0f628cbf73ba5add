//! Records the source revision for run.toml when built from a git checkout: the commit
//! (TRIBOFE_GIT_REVISION) and whether tracked files differ from it (TRIBOFE_GIT_DIRTY).
//! Without git or outside a checkout (a tarball, crates.io) nothing is set and the build goes on.

use std::process::Command;

fn git(args: &[&str]) -> Option<String> {
    let o = Command::new("git").args(args).output().ok()?;
    o.status.success().then(|| String::from_utf8_lossy(&o.stdout).trim().to_string())
}

fn main() {
    // Rerun on commits and staging (the git files) and on edits of the sources.
    for p in ["src", "tests", "benches", "examples", "Cargo.toml", "Cargo.lock", "build.rs"] {
        println!("cargo:rerun-if-changed={p}");
    }
    // Only a checkout whose top level is this package (not a tarball unpacked inside another repository).
    let here = std::env::var("CARGO_MANIFEST_DIR").unwrap_or_default();
    let top = git(&["rev-parse", "--show-toplevel"]);
    let same = |t: &str| {
        std::fs::canonicalize(t).ok().zip(std::fs::canonicalize(&here).ok()).is_some_and(|(a, b)| a == b)
    };
    if !top.as_deref().is_some_and(same) {
        return;
    }
    for p in ["HEAD", "index", "logs/HEAD"] {
        if let Some(path) = git(&["rev-parse", "--git-path", p]) {
            println!("cargo:rerun-if-changed={path}");
        }
    }
    let Some(rev) = git(&["rev-parse", "HEAD"]) else { return };
    println!("cargo:rustc-env=TRIBOFE_GIT_REVISION={rev}");
    // Untracked files do not count: only changes to what the commit holds.
    if let Some(status) = git(&["status", "--porcelain", "--untracked-files=no"]) {
        println!("cargo:rustc-env=TRIBOFE_GIT_DIRTY={}", !status.is_empty());
    }
}
