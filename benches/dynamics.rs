//! Explicit elastodynamics throughput (`cargo bench --bench dynamics`; a plain timing harness
//! that prints one table, not criterion, so the fractions of the bandwidth limit come out).
//!
//! For square regular QUA4 meshes of about 1e4, 1e5 and 1e6 DOFs, on 1 and 2 threads, it
//! times:
//! - `elements+upd`: K u element by element (gather, 8x8 product, scatter), then the update
//!   v -= dt K u / m, u += dt v in a second pass: the kernel before the grid stencil;
//! - `K u alone`: the grid's 9-point stencil (`Elastodynamic::apply_k`);
//! - `stencil+upd`: the stencil, then the same update;
//! - `step`, `step damped`: a whole `Explicit::step` (fixed base, external-force hook,
//!   energy ledger), fused into one pass on a grid;
//! - `rupture`: the command's own stepping (`tribofe rupture`, the spec scene at the element
//!   size giving about as many DOFs, its base as the stepper's boundary hook): a run of 201
//!   steps less one of 1 step, over 200, so the set-up is left out;
//! - `step general`: `Explicit::step` on the same mesh with its nodes moved by 10 % of h (so
//!   not a grid: the element-by-element path every graded or Gmsh mesh takes).
//!
//! The reference is a STREAM-like triad a = b + s c over as many doubles as the mesh has DOFs,
//! on as many threads (contiguous shares), plus one out of cache. Each time is the median of
//! 9 batches after a warm-up, as wall time and as CPU time / threads (the machine is shared).
//!
//! Bytes per DOF-update are counted at their minimum, each array streamed once, stores
//! counted once (as STREAM counts: the triad moves 24 B per element); the limit is the
//! triad's bandwidth over those bytes.

use std::hint::black_box;
use std::time::{Duration, Instant};
use tribofe::dynamics::explicit::{Elastodynamic, Explicit};
use tribofe::dynamics::rupture::{self, RuptureSpec};
use tribofe::fem::material::Material;
use tribofe::fem::mesher::Rectangle;
use tribofe::law::Law;

/// Process CPU seconds (all threads).
fn cpu_seconds() -> f64 {
    let mut ts = libc::timespec { tv_sec: 0, tv_nsec: 0 };
    // SAFETY: clock_gettime writes the timespec it is given.
    unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut ts) };
    ts.tv_sec as f64 + 1e-9 * ts.tv_nsec as f64
}

/// Seconds per call of `f`: (wall, CPU of all threads), medians of 9 batches of at least
/// 50 ms each after a warm-up. On a shared machine the wall time includes waiting for a core;
/// CPU time / threads is what the call would take with its cores to itself.
fn time(mut f: impl FnMut()) -> (f64, f64) {
    f();
    let t0 = Instant::now();
    let mut calls = 0usize;
    while t0.elapsed() < Duration::from_millis(50) {
        f();
        calls += 1;
    }
    let per_batch = calls.max(1);
    let mut wall = Vec::new();
    let mut cpu = Vec::new();
    for _ in 0..9 {
        let (t, c) = (Instant::now(), cpu_seconds());
        for _ in 0..per_batch {
            f();
        }
        wall.push(t.elapsed().as_secs_f64() / per_batch as f64);
        cpu.push((cpu_seconds() - c) / per_batch as f64);
    }
    wall.sort_by(f64::total_cmp);
    cpu.sort_by(f64::total_cmp);
    (wall[4], cpu[4])
}

/// a = b + 0.5 c over n doubles on `threads` threads (contiguous shares): bytes/s (STREAM's
/// count, 24 B per element), wall and CPU.
fn triad(n: usize, threads: usize) -> (f64, f64) {
    let (mut a, b, c) = (vec![0.0f64; n], vec![1.0f64; n], vec![2.0f64; n]);
    let (w, cpu) = time(|| {
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
    });
    (24.0 * n as f64 / w, 24.0 * n as f64 / (cpu / threads as f64))
}

/// Minimum bytes per DOF-update of each kernel (see the module comment):
/// - elements: K u reads u 8, zeroes f 8 and accumulates into it 16, reads conn 8 B and the
///   matrix index 2 B per node (2 DOFs) ~ 5; the update reads and writes u, v 32, reads f 8
///   and the mass 4 (one per node): 77;
/// - stencil: K u reads u 8, writes f 8; the update as above 44: 60;
/// - K u alone (the stencil): u read 8, f written 8: 16;
/// - step: see `STEP_BYTES`.
const ELEMENT_BYTES: f64 = 77.0;
const STENCIL_BYTES: f64 = 60.0;
/// `Explicit::step`, fused on a grid: u read 8, u_prev read and written (u^{n+1} replaces
/// u^{n-1}) 16, v read and written 16, f_ext read and zeroed 16, mass 4, fixed flag 1: 61
/// (with damping v^{n+1/2} goes to another array: the same count). Before the fusion the
/// step made separate passes (K u, zeroing f_ext, the kinetic energy, u_prev . K u twice, the
/// update): 129.
const STEP_BYTES: f64 = 61.0;
/// The commands' step (`Explicit::step_boundary`: no external forces, so f_ext is neither read
/// nor zeroed): 61 - 16 = 45. The boundary rows' own work (the base's split-node rule, a
/// row in about sqrt(DOFs)) is not counted.
const BOUNDARY_STEP_BYTES: f64 = 45.0;

fn main() {
    let mat = Material::plane_strain(2e3, 0.4).unwrap();
    let hw = std::thread::available_parallelism().map_or(1, |n| n.get());
    println!("explicit step throughput (cargo bench --bench dynamics), {hw} hardware threads");
    let big = 20_000_000;
    for threads in [1, 2] {
        let (w, c) = triad(big, threads);
        println!(
            "triad over 3 x {big} doubles ({} MB, out of cache), {threads} thread(s): {:.2} GB/s wall, {:.2} GB/s CPU",
            24 * big / 1_000_000,
            w / 1e9,
            c / 1e9
        );
    }
    println!("rate = DOFs / step time; 'cpu' columns use CPU time / threads (the machine is shared);");
    println!(
        "limit = triad bandwidth over as many doubles as DOFs / bytes per DOF-update; frac = rate / limit"
    );
    println!(
        "{:>13} {:>8} {:>3} {:>10} {:>10} {:>10} {:>5} {:>8} {:>8} {:>10} {:>5} {:>5}",
        "kernel",
        "DOFs",
        "thr",
        "step s",
        "rate",
        "rate cpu",
        "B/DOF",
        "triad",
        "GB/s cpu",
        "limit cpu",
        "frac",
        "f cpu"
    );
    for side in [70usize, 223, 706] {
        let mesh = Rectangle::new(0.0, 0.1, 0.0, 0.1, side, side).build().unwrap();
        let mut model = Elastodynamic::new(&mesh, mat, 1000.0).unwrap();
        assert!(model.is_grid());
        let n = model.n_dofs();
        let dt = 0.5 * model.critical_dt(0.0);
        for threads in [1usize, 2] {
            model.set_threads(threads);
            let (bw, bw_cpu) = triad(n, threads);
            let report = |name: &str, bytes: f64, (wall, cpu): (f64, f64)| {
                let (rate, rate_cpu) = (n as f64 / wall, n as f64 / (cpu / threads as f64));
                println!(
                    "{name:>13} {n:>8} {threads:>3} {wall:>10.3e} {rate:>10.3e} {rate_cpu:>10.3e} {bytes:>5.0} {:>8.2} {:>8.2} {:>10.3e} {:>5.2} {:>5.2}",
                    bw / 1e9,
                    bw_cpu / 1e9,
                    bw_cpu / bytes,
                    rate / (bw / bytes),
                    rate_cpu / (bw_cpu / bytes)
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
                report("elements+upd", ELEMENT_BYTES, s);
            }
            report("K u alone", 16.0, time(|| model.apply_k(black_box(&u), &mut f)));
            let s = time(|| {
                model.apply_k(black_box(&u), &mut f);
                for i in 0..n {
                    v[i] -= dt * f[i] / model.mass[i / 2];
                    u[i] += dt * v[i];
                }
            });
            report("stencil+upd", STENCIL_BYTES, s);
            for (name, eta) in [("step", 0.0), ("step damped", 0.2 / model.lambda_bound.sqrt())] {
                let fixed: Vec<bool> = (0..n).map(|i| mesh.nodes[i / 2][1] == 0.0).collect();
                let dt = 0.5 * model.critical_dt(eta);
                let mut run = Explicit::new(&model, dt, eta, fixed).unwrap();
                run.set_displacement(&vec![1e-9; n]);
                report(name, STEP_BYTES, time(|| run.step(|_, _| {})));
            }
            // The spec scene (2:1) with about n DOFs: h = 0.2 / nx, 2 (nx + 1)(nx / 2 + 1) ~ n.
            let nx = 2 * ((n as f64 / 2.0).sqrt() / 2.0).round() as usize;
            // D_c scaled with h so that the cohesive zone spans the spec's 5 elements (the cost of a
            // step does not depend on it).
            let h = 0.2 / nx as f64;
            let d = RuptureSpec::default();
            let spec = RuptureSpec {
                h,
                friction: Law::SlipWeakening {
                    mu_s: d.friction.mu_s(),
                    mu_d: d.friction.mu_d(),
                    dc: d.dc() * h / d.h,
                },
                ..d
            };
            let dt = spec.dt().unwrap();
            let pool = &rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            let steps = |k: f64| {
                let s = RuptureSpec { t_end: k * dt, ..spec.clone() };
                move || {
                    pool.install(|| {
                        rupture::run(&s, &tribofe::Cancel::new(), tribofe::Progress::none()).unwrap()
                    });
                }
            };
            let (long, short) = (time(steps(201.0)), time(steps(1.0)));
            let per = ((long.0 - short.0) / 200.0, (long.1 - short.1) / 200.0);
            let nr = 2 * (nx + 1) * (nx / 2 + 1);
            let (rate, rate_cpu) = (nr as f64 / per.0, nr as f64 / (per.1 / threads as f64));
            println!(
                "{:>13} {nr:>8} {threads:>3} {:>10.3e} {rate:>10.3e} {rate_cpu:>10.3e} {:>5.0} {:>8.2} {:>8.2} {:>10.3e} {:>5.2} {:>5.2}",
                "rupture",
                per.0,
                BOUNDARY_STEP_BYTES,
                bw / 1e9,
                bw_cpu / 1e9,
                bw_cpu / BOUNDARY_STEP_BYTES,
                rate / (bw / BOUNDARY_STEP_BYTES),
                rate_cpu / (bw_cpu / BOUNDARY_STEP_BYTES)
            );
            if threads == 1 {
                let mut moved = mesh.clone();
                moved.distort(0.1 * 0.1 / side as f64, 3).unwrap();
                let general = Elastodynamic::new(&moved, mat, 1000.0).unwrap();
                assert!(!general.is_grid());
                let fixed: Vec<bool> = (0..n).map(|i| mesh.nodes[i / 2][1] == 0.0).collect();
                let mut run = Explicit::new(&general, 0.5 * general.critical_dt(0.0), 0.0, fixed).unwrap();
                run.set_displacement(&vec![1e-9; n]);
                report("step general", ELEMENT_BYTES, time(|| run.step(|_, _| {})));
            }
        }
    }
}
