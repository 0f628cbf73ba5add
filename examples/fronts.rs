//! Where the numeric factorisation of the strip's two halves spends its dense-kernel time, by
//! supernode width, on warm memory (best of N refactorisations into the same factor), against
//! this machine's DGEMM per core: the ceiling that issue 8's ">= 50 % of DGEMM" meets on a
//! strip, whose fronts are at most ~100 columns wide.
//! `cargo run --release --example fronts -- [ny] [repeat]`
use std::time::Instant;
use tribofe::fem::assembly::Assembler;
use tribofe::fem::ordering::bisection;
use tribofe::linalg::multifrontal::{DenseWork, WIDTH_CLASSES};
use tribofe::linalg::substructure::TwoDomain;
use tribofe::scene::Scene;
use tribofe::studies::bench::dgemm_gflops;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let ny: usize = args.get(1).map_or(50, |s| s.parse().unwrap());
    let rep: usize = args.get(2).map_or(5, |s| s.parse().unwrap());
    let mut scene = Scene::default();
    scene.mesh.h = scene.block.thickness / ny as f64;
    let sm = scene.build().unwrap();
    let red = sm.constraints.reduce().unwrap();
    let asm = Assembler::new(&sm.mesh, &red).unwrap();
    let g = vec![vec![1e-6; sm.constraints.n_fixed()]];
    let (values, _) = asm.assemble(&sm.model(), &red, &[vec![]], &g).unwrap();
    let two = TwoDomain::analyse(&asm.pattern, &bisection(&sm.mesh, &red).unwrap()).unwrap();
    let mut l = Default::default();
    two.factor_halves(&values, false, &mut l).unwrap(); // first touch of the factor's memory
    let (mut best, mut work) = (f64::INFINITY, DenseWork::default());
    for _ in 0..rep {
        let clock = Instant::now();
        let w = two.factor_halves(&values, false, &mut l).unwrap();
        let t = clock.elapsed().as_secs_f64();
        if t < best {
            (best, work) = (t, w);
        }
    }
    let (d1, d2) = (dgemm_gflops(2000, 1), dgemm_gflops(2000, 2));
    println!("strip t/{ny}: two halves, one per core, warm memory, best of {rep}; DGEMM {d1:.1} GFLOP/s on 1 core, {d2:.1} on 2");
    println!(
        "{:>12} {:>11} {:>7} {:>10} {:>12} {:>14}",
        "width", "supernodes", "GFLOP", "core-s", "GFLOP/s/core", "% DGEMM/core"
    );
    let mut lower = 0;
    for (&upper, &(n, f, s)) in WIDTH_CLASSES.iter().zip(&work.by_width) {
        let label = if upper == usize::MAX { format!("> {lower}") } else { format!("{}-{upper}", lower + 1) };
        println!(
            "{label:>12} {n:>11} {:>7.3} {s:>10.4} {:>12.1} {:>14.1}",
            f / 1e9,
            f / 1e9 / s,
            100.0 * f / 1e9 / s / d1
        );
        lower = upper;
    }
    let (flops, seconds): (f64, f64) = work.by_width.iter().fold((0.0, 0.0), |a, c| (a.0 + c.1, a.1 + c.2));
    println!(
        "{:>12} {:>11} {:>7.3} {seconds:>10.4} {:>12.1} {:>14.1}",
        "all",
        work.by_width.iter().map(|c| c.0).sum::<usize>(),
        flops / 1e9,
        flops / 1e9 / seconds,
        100.0 * flops / 1e9 / seconds / d1
    );
    println!("numeric phase of the halves: {best:.4} s wall = {:.1} GFLOP/s = {:.1} % of DGEMM on 2 cores; the dense kernels alone: {:.4} s per core", flops / 1e9 / best, 100.0 * flops / 1e9 / best / d2, seconds / 2.0);
    println!(
        "50 % of DGEMM on 2 cores would be {:.4} s for these {:.2} GFLOP",
        flops / 1e9 / (0.5 * d2),
        flops / 1e9
    );
}
