//! Sweep throughput (issue 19): the `t_H` sweep of validation/sweeps/README.md (4 thicknesses
//! x 16 heights x 4 Poisson ratios, 3 load cases, converged model) through the library, no
//! output written; and the same 256 points with one factorisation per point (H given as a
//! list of single-point sweeps) to show what sharing the factorisation across H saves.
//! `cargo bench --bench sweep`; the figures quoted in README.md, "Sweeps".

use criterion::{criterion_group, criterion_main, Criterion};
use tribofe::scene::Scene;
use tribofe::studies::sweep::{self, parse_values, Axis, Param, SweepOptions};

fn axes(height: Vec<f64>) -> Vec<Axis> {
    let v = |s: &str| parse_values(s).unwrap();
    vec![
        Axis { param: Param::Thickness, values: v("0.001:0.008:4g") },
        Axis { param: Param::Height, values: height },
        Axis { param: Param::Poisson, values: v("0.3,0.4,0.45,0.49") },
    ]
}

fn sweeps(c: &mut Criterion) {
    let mut g = c.benchmark_group("sweep");
    g.sample_size(10);
    let (base, o) = (Scene::default(), SweepOptions::default());
    let heights = parse_values("0.01:0.16:16g").unwrap();
    let all = axes(heights.clone());
    g.bench_function("t_H, 256 points x 3 F/N (shared factorisation across H)", |b| {
        b.iter(|| sweep::run(&base, &all, &o, tribofe::Progress::none()).unwrap())
    });
    g.bench_function("t_H, 256 points x 3 F/N (one factorisation per point)", |b| {
        b.iter(|| {
            for &h in &heights {
                sweep::run(&base, &axes(vec![h]), &o, tribofe::Progress::none()).unwrap();
            }
        })
    });
    g.finish();
}

criterion_group!(benches, sweeps);
criterion_main!(benches);
