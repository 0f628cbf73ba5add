//! Explicit elastodynamics throughput (`cargo bench --bench dynamics`): one central-difference
//! step (internal force K u element by element, velocity and displacement update) on regular
//! QUA4 meshes, in DOF-updates per second, beside a STREAM-like triad over the same number of
//! doubles to set the memory-bandwidth limit against.
//!
//! Bytes per DOF-update of the step, counted at their minimum (each array streamed once):
//! K u: u read 8 B, f zeroed then read-modify-write 24 B; update: u, v read and written
//! 32 B, f read 8 B, mass read 4 B (one per two DOFs): about 76 B. The triad
//! a = b + s c moves 24 B per element, so limit = triad elements/s x 24 / 76.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::hint::black_box;
use tribofe::dynamics::explicit::Elastodynamic;
use tribofe::fem::material::Material;
use tribofe::fem::mesher::Rectangle;

fn step(c: &mut Criterion) {
    let mut g = c.benchmark_group("explicit step");
    for (nx, ny) in [(200, 100), (800, 400)] {
        let mesh = Rectangle::new(-0.1, 0.1, 0.0, 0.1, nx, ny).build().unwrap();
        let model = Elastodynamic::new(&mesh, Material::plane_strain(2e3, 0.4).unwrap(), 1000.0).unwrap();
        let n = model.n_dofs();
        let dt = 0.5 * model.critical_dt(0.0);
        let (mut u, mut v, mut f) = (vec![1e-9; n], vec![0.0; n], vec![0.0; n]);
        g.throughput(Throughput::Elements(n as u64));
        g.bench_function(format!("{nx}x{ny} QUA4, {n} DOFs"), |b| {
            b.iter(|| {
                model.apply_k(black_box(&u), &mut f);
                for i in 0..n {
                    v[i] -= dt * f[i] / model.mass[i / 2];
                    u[i] += dt * v[i];
                }
            })
        });
        let (mut a, bb, cc) = (vec![0.0; n], vec![1.0; n], vec![2.0; n]);
        g.bench_function(format!("triad over {n} doubles (bandwidth reference)"), |b| {
            b.iter(|| {
                for i in 0..n {
                    a[i] = bb[i] + 0.5 * cc[i];
                }
                black_box(&mut a);
            })
        });
    }
    g.finish();
}

criterion_group!(benches, step);
criterion_main!(benches);
