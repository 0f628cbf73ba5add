//! Explicit elastodynamics throughput (`cargo bench --bench dynamics`; a plain timing harness
//! that prints one table, not criterion, so the fractions of the bandwidth limit come out).
//!
//! For regular QUA4 meshes of about 1e4, 1e5 and 1e6 DOFs and 1 and 2 threads it times:
//! - `elements`: K u element by element (gather, 8x8 product, scatter) then the update
//!   v -= dt K u / m, u += dt v in a second pass: the kernel before the grid stencil;
//! - `stencil`: the same with K u as the grid's 9-point stencil (`Elastodynamic::apply_k`);
//! - `step`: a whole `Explicit::step` (fixed base, external-force hook, energy ledger);
//! and a STREAM-like triad a = b + s c over as many doubles as the mesh has DOFs (on 1 and 2
//! threads, each its half) to set the memory-bandwidth limit against. Each time is the
//! median of repeated runs after a warm-up.
//!
//! Bytes per DOF-update are counted at their minimum, each array streamed once, stores
//! counted once (as STREAM counts: the triad moves 24 B per element); the limit is the
//! triad's bandwidth over those bytes.

use std::hint::black_box;
use std::time::{Duration, Instant};
use tribofe::dynamics::explicit::{Elastodynamic, Explicit};
use tribofe::fem::material::Material;
use tribofe::fem::mesher::Rectangle;

/// Median seconds per call of `f`, over at least 0.5 s of calls in 9 batches.
fn time(mut f: impl FnMut()) -> f64 {
    f();
    let t0 = Instant::now();
    let mut calls = 0usize;
    while t0.elapsed() < Duration::from_millis(50) {
        f();
        calls += 1;
    }
    let per_batch = (calls * 10 / 9).max(1);
    let mut batches: Vec<f64> = (0..9)
        .map(|_| {
            let t = Instant::now();
            for _ in 0..per_batch {
                f();
            }
            t.elapsed().as_secs_f64() / per_batch as f64
        })
        .collect();
    batches.sort_by(f64::total_cmp);
    batches[4]
}

/// a = b + 0.5 c on `threads` threads (contiguous halves), seconds per sweep.
fn triad(n: usize, threads: usize) -> f64 {
    let (mut a, b, c) = (vec![0.0f64; n], vec![1.0f64; n], vec![2.0f64; n]);
    time(|| {
        let per = n.div_ceil(threads);
        std::thread::scope(|s| {
            for ((a, b), c) in a.chunks_mut(per).zip(b.chunks(per)).zip(c.chunks(per)) {
                if threads == 1 {
                    a.iter_mut().zip(b).zip(c).for_each(|((a, b), c)| *a = b + 0.5 * c);
                } else {
                    s.spawn(move || a.iter_mut().zip(b).zip(c).for_each(|((a, b), c)| *a = b + 0.5 * c));
                }
            }
        });
        black_box(&mut a);
    })
}

/// Minimum bytes per DOF-update of each kernel (see the module comment):
/// - elements: K u reads u 8, zeroes f 8 and accumulates into it 16, reads conn 8 B and the
///   matrix index 2 B per node (2 DOFs) ~ 5; the update reads and writes u, v 32, reads f 8
///   and the mass 4 (one per node): 77;
/// - stencil: K u reads u 8, writes f 8; the update as above 44: 60;
/// - step: see `STEP_BYTES`.
const ELEMENT_BYTES: f64 = 77.0;
const STENCIL_BYTES: f64 = 60.0;
/// `Explicit::step` in separate passes: K u (u 8, f 8), f_ext zeroed 8, kinetic energy (v 8,
/// m 4), u_prev . K u twice (16 + 16), the update (u, v read and written 32, u_prev written 8,
/// f_ext and K u 16, m 4, fixed 1): 129.
const STEP_BYTES: f64 = 129.0;

fn main() {
    let mat = Material::plane_strain(2e3, 0.4).unwrap();
    println!("explicit step throughput, DOF-updates/s (median), this machine, {} hardware threads", {
        std::thread::available_parallelism().map_or(1, |n| n.get())
    });
    println!(
        "{:>9} {:>8} {:>3} {:>9} {:>10} {:>6} {:>9} {:>9} {:>6}",
        "kernel", "DOFs", "thr", "step s", "DOF-upd/s", "B/DOF", "triad GB/s", "limit", "frac"
    );
    for side in [70usize, 223, 706] {
        let (nx, ny) = (side, side);
        let mesh = Rectangle::new(0.0, 0.1, 0.0, 0.1, nx, ny).build().unwrap();
        let mut model = Elastodynamic::new(&mesh, mat, 1000.0).unwrap();
        assert!(model.is_grid());
        let n = model.n_dofs();
        let dt = 0.5 * model.critical_dt(0.0);
        for threads in [1usize, 2] {
            model.set_threads(threads);
            let bw = 24.0 * n as f64 / triad(n, threads);
            let report = |name: &str, bytes: f64, secs: f64| {
                let rate = n as f64 / secs;
                let limit = bw / bytes;
                println!(
                    "{name:>9} {n:>8} {threads:>3} {secs:>9.3e} {rate:>10.3e} {bytes:>6.0} {:>9.2} {limit:>9.3e} {:>6.2}",
                    bw / 1e9,
                    rate / limit
                );
            };
            let (mut u, mut v, mut f) = (vec![1e-9; n], vec![0.0; n], vec![0.0; n]);
            if threads == 1 {
                let s = time(|| {
                    model.apply_k_by_elements(black_box(&u), &mut f);
                    for i in 0..n {
                        v[i] -= dt * f[i] / model.mass[i / 2];
                        u[i] += dt * v[i];
                    }
                });
                report("elements", ELEMENT_BYTES, s);
            }
            let s = time(|| {
                model.apply_k(black_box(&u), &mut f);
                for i in 0..n {
                    v[i] -= dt * f[i] / model.mass[i / 2];
                    u[i] += dt * v[i];
                }
            });
            report("stencil", STENCIL_BYTES, s);
            let fixed: Vec<bool> = (0..n).map(|i| mesh.nodes[i / 2][1] == 0.0).collect();
            let mut run = Explicit::new(&model, dt, 0.0, fixed).unwrap();
            run.set_displacement(&vec![1e-9; n]);
            let s = time(|| run.step(|_, _| {}));
            report("step", STEP_BYTES, s);
        }
    }
}
