//! Times the mesh, pattern and assembly phases of the strip benchmark alone (best of N) and
//! prints a hash of the assembled values so changes can be checked for bitwise equality.
//! `cargo run --release --example asm_phases -- [ny] [repeat]`
use std::time::Instant;
use tribofe::fem::assembly::Assembler;
use tribofe::scene::Scene;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let ny: usize = args.get(1).map_or(50, |s| s.parse().unwrap());
    let rep: usize = args.get(2).map_or(5, |s| s.parse().unwrap());
    let mut scene = Scene::default();
    scene.mesh.h = scene.block.thickness / ny as f64;
    let best = |f: &mut dyn FnMut() -> f64| (0..rep).map(|_| f()).fold(f64::INFINITY, f64::min);
    let t_mesh = best(&mut || {
        let c = Instant::now();
        std::hint::black_box(scene.build().unwrap());
        c.elapsed().as_secs_f64()
    });
    let t_rect = best(&mut || {
        let c = Instant::now();
        std::hint::black_box(
            tribofe::fem::mesher::Rectangle::new(-0.2, 0.2, 0.0, 0.002, 200 * ny, ny).build().unwrap(),
        );
        c.elapsed().as_secs_f64()
    });
    let sm = scene.build().unwrap();
    let t_patt = best(&mut || {
        let c = Instant::now();
        let red = sm.constraints.reduce().unwrap();
        std::hint::black_box(Assembler::new(&sm.mesh, &red).unwrap());
        c.elapsed().as_secs_f64()
    });
    let t_red = best(&mut || {
        let c = Instant::now();
        std::hint::black_box(sm.constraints.reduce().unwrap());
        c.elapsed().as_secs_f64()
    });
    if args.get(3).is_some_and(|a| a == "patt") {
        return; // profile the pattern phase alone
    }
    let red = sm.constraints.reduce().unwrap();
    let asm = Assembler::new(&sm.mesh, &red).unwrap();
    let model = sm.model();
    let g: Vec<Vec<f64>> =
        (0..2).map(|c| (0..red.n_fixed()).map(|j| ((j * 7 + c * 3) % 5) as f64 - 2.0).collect()).collect();
    let f: Vec<Vec<f64>> = vec![vec![], vec![]];
    let mut line = format!("ny={ny} n={} nnz={} colours={} | mesh {t_mesh:.4} (rectangle {t_rect:.4}) patt {t_patt:.4} (reduce {t_red:.4})", asm.pattern.n, asm.pattern.nnz(), asm.n_colors());
    let mut hash = 0u64;
    for th in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(th).build().unwrap();
        let t = best(&mut || {
            let c = Instant::now();
            std::hint::black_box(pool.install(|| asm.assemble(&model, &red, &f, &g).unwrap()));
            c.elapsed().as_secs_f64()
        });
        let (v, r) = pool.install(|| asm.assemble(&model, &red, &f, &g).unwrap());
        let h = v
            .iter()
            .chain(&r)
            .fold(0xcbf29ce484222325u64, |h, x| (h ^ x.to_bits()).wrapping_mul(0x100000001b3));
        let hp = asm
            .pattern
            .row_idx
            .iter()
            .chain(&asm.pattern.col_ptr)
            .fold(0xcbf29ce484222325u64, |h, &x| (h ^ x as u64).wrapping_mul(0x100000001b3));
        if th == 1 {
            hash = h
        } else {
            assert_eq!(h, hash, "thread counts differ")
        }
        line += &format!(" asm{th} {t:.4}");
        if th == 2 {
            line += &format!(" | values {h:016x} pattern {hp:016x}");
        }
    }
    println!("{line}");
}
