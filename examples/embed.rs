//! A host program that embeds tribofe with an allocator of its own: the library installs no
//! global allocator, starts no process-wide state, and runs the paper's check through its
//! API. CI builds and runs it (`cargo run --release --example embed`).

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};
use tribofe::linalg::solve::SolverOptions;
use tribofe::scene::Scene;
use tribofe::studies::check;

/// The host's own allocator: counts calls, as a profiler or a Python extension's might.
struct HostAlloc;
static CALLS: AtomicUsize = AtomicUsize::new(0);

// SAFETY: forwards to the system allocator unchanged.
unsafe impl GlobalAlloc for HostAlloc {
    unsafe fn alloc(&self, l: Layout) -> *mut u8 {
        CALLS.fetch_add(1, Relaxed);
        System.alloc(l)
    }
    unsafe fn dealloc(&self, p: *mut u8, l: Layout) {
        System.dealloc(p, l)
    }
}

#[global_allocator]
static HOST: HostAlloc = HostAlloc;

fn main() -> Result<(), tribofe::Error> {
    let (r, _) = check::run(&Scene::default(), &SolverOptions::default())?;
    let c = &r.cases[2];
    println!(
        "F/N = {}: interior pressure slope {:.5} (model {:.5}), {} unknowns; host allocator: {} calls; tribofe's counters: {:?}",
        c.fn_ratio,
        c.metrics.slope_interior,
        c.metrics.slope_model,
        r.stats.n_unknowns,
        CALLS.load(Relaxed),
        tribofe::memory::peak_bytes()
    );
    assert!(tribofe::memory::peak_bytes().is_none() && CALLS.load(Relaxed) > 0);
    Ok(())
}
