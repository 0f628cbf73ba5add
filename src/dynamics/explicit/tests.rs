//! Tests of the explicit solver: element matrices and mass, the stable step, and the grid
//! stencil and fused step against the general path and across thread counts.

use super::*;
use crate::fem::mesher::Rectangle;

#[test]
fn regular_mesh_shares_one_matrix_and_the_mass_is_the_body_mass() {
    let mesh = Rectangle::new(-0.1, 0.1, 0.0, 0.05, 40, 10).build().unwrap();
    let m = Elastodynamic::new(&mesh, Material::plane_strain(2e3, 0.4).unwrap(), 1000.0).unwrap();
    assert_eq!(m.n_element_matrices(), 1);
    let total: f64 = m.mass.iter().sum();
    assert!((total - 1000.0 * 0.2 * 0.05).abs() < 1e-12 * total, "{total}");
    // Corner node of a square element: a quarter of its mass.
    assert!((m.mass[0] - 1000.0 * 0.005 * 0.005 / 4.0).abs() < 1e-15);
}

#[test]
fn element_bound_holds_and_is_close() {
    let mesh = Rectangle::new(0.0, 0.04, 0.0, 0.02, 20, 10).build().unwrap();
    let m = Elastodynamic::new(&mesh, Material::plane_strain(2e3, 0.4).unwrap(), 1000.0).unwrap();
    let est = m.power_iteration(3000);
    // The power estimate is a Rayleigh quotient (a lower bound on the true largest
    // eigenvalue), and the element bound an upper one. On square nu = 0.4 elements the
    // bound is 6.67 c_p^2 / h^2 and the estimate 4.31 c_p^2 / h^2 (0.647 of it): the
    // element's highest mode does not fit the assembled mesh, so the bound's step
    // 0.775 h / c_p is 0.80 of the true one.
    assert!(est <= m.lambda_bound * (1.0 + 1e-12), "{est} > {}", m.lambda_bound);
    assert!(est >= 0.6 * m.lambda_bound, "{est} vs {}", m.lambda_bound);
    let cp2_h2 = (m.material.lambda() + 2.0 * m.material.shear_modulus()) / 1000.0 / 4e-6;
    assert!((m.lambda_bound / cp2_h2 - 20.0 / 3.0).abs() < 1e-9, "{}", m.lambda_bound / cp2_h2);
}

/// Deterministic pseudo-random values in (-0.5, 0.5).
fn noise(n: usize, mut seed: u64) -> Vec<f64> {
    (0..n)
        .map(|_| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        })
        .collect()
}

#[test]
fn grid_stencil_is_the_element_product_and_the_same_bits_on_any_thread_count() {
    // Elements 2:1 (non-square) so every tap of the stencil differs from its mirror.
    let mesh = Rectangle::new(-0.26, 0.26, 0.0, 0.13, 260, 130).build().unwrap();
    let mut m = Elastodynamic::new(&mesh, Material::plane_strain(2e3, 0.4).unwrap(), 1000.0).unwrap();
    assert!(m.is_grid());
    let u = noise(m.n_dofs(), 7);
    let (mut by_el, mut one, mut two, mut three) =
        (vec![0.0; m.n_dofs()], vec![1.0; m.n_dofs()], vec![2.0; m.n_dofs()], vec![3.0; m.n_dofs()]);
    m.apply_k_by_elements(&u, &mut by_el);
    m.set_threads(1);
    m.apply_k(&u, &mut one);
    m.set_threads(2);
    m.apply_k(&u, &mut two);
    m.set_threads(3);
    m.apply_k(&u, &mut three);
    // 34 191 nodes: above two bands' threshold, so two threads really ran.
    assert!(mesh.n_nodes() >= 2 * stencil::MIN_NODES_PER_THREAD);
    assert!(one.iter().zip(&two).all(|(a, b)| a.to_bits() == b.to_bits()), "1 vs 2 threads");
    assert!(one.iter().zip(&three).all(|(a, b)| a.to_bits() == b.to_bits()), "1 vs 3 threads");
    // Both sum at most 4 x 8 products of |K_ij| |u_j| per DOF, the stencil in another
    // order: they differ by a few ulps of that sum (32 eps of it, generously).
    let kmax = m.kmats[0].iter().fold(0.0f64, |a, &k| a.max(k.abs()));
    let scale = 32.0 * kmax * 0.5;
    let worst = one.iter().zip(&by_el).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
    assert!(worst <= 32.0 * f64::EPSILON * scale, "{worst:e} vs {scale:e}");
    assert!(worst > 0.0 || one == by_el);
    // The AVX build of the row loop (taken here if the CPU has it) against the plain one.
    let g = m.grid.as_ref().unwrap();
    let (mut a, mut b) = (vec![0.0; g.row_len()], vec![1.0; g.row_len()]);
    for j in 0..=130 {
        g.row(&u, j, &mut a);
        g.row_any(&u, j, &mut b);
        assert!(a.iter().zip(&b).all(|(x, y)| x.to_bits() == y.to_bits()), "row {j}");
    }
    // A rigid translation has no force (to round-off) on the edges and corners too.
    let t: Vec<f64> = (0..m.n_dofs()).map(|i| [1.0, -2.0][i % 2]).collect();
    m.apply_k(&t, &mut one);
    assert!(one.iter().all(|f| f.abs() <= 64.0 * f64::EPSILON * kmax * 2.0), "translation");
}

/// `steps` damped, forced steps from a smooth displacement with the base fixed.
fn run_steps(m: &Elastodynamic, mesh: &crate::fem::mesh::Mesh, steps: usize) -> (Vec<f64>, Vec<f64>, Ledger) {
    let eta = 0.2 / m.lambda_bound.sqrt();
    let dt = 0.9 * m.critical_dt(eta);
    let fixed: Vec<bool> = (0..m.n_dofs()).map(|i| mesh.nodes[i / 2][1] == 0.0).collect();
    let mut run = Explicit::new(m, dt, eta, fixed).unwrap();
    let u0: Vec<f64> = (0..m.n_dofs()).map(|i| 1e-4 * (40.0 * mesh.nodes[i / 2][i % 2]).sin()).collect();
    run.set_displacement(&u0);
    let top = m.n_dofs() - 1;
    for _ in 0..steps {
        run.step(|t, f| f[top] -= 1e-3 * t);
    }
    (run.u, run.v, run.ledger)
}

#[test]
fn fused_grid_step_is_the_general_step_and_the_same_bits_on_any_thread_count() {
    let mesh = Rectangle::new(0.0, 0.2, 0.0, 0.17, 200, 170).build().unwrap();
    let mut m = Elastodynamic::new(&mesh, Material::plane_strain(2e3, 0.4).unwrap(), 1000.0).unwrap();
    assert!(m.is_grid() && mesh.n_nodes() >= 2 * stencil::MIN_NODES_PER_THREAD);
    m.set_threads(1);
    let one = run_steps(&m, &mesh, 40);
    m.set_threads(2);
    let two = run_steps(&m, &mesh, 40);
    let bits = |a: &[f64], b: &[f64]| a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits());
    assert!(bits(&one.0, &two.0) && bits(&one.1, &two.1), "u, v: 1 vs 2 threads");
    assert_eq!(one.2, two.2, "ledger: 1 vs 2 threads");
    // The general path (element by element, separate passes) on the same mesh: K u summed
    // in another order, so u differs at round-off, amplified at most by the stable
    // scheme's growth over 40 steps (a few hundred ulps of max |u|, generously 1e-12).
    let mut general = m.clone();
    general.grid = None;
    let gen = run_steps(&general, &mesh, 40);
    let umax = gen.0.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    let du = one.0.iter().zip(&gen.0).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
    assert!(du <= 1e-12 * umax && umax > 0.0, "{du:e} vs {umax:e}");
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-11 * a.abs().max(b.abs());
    let (l, g) = (one.2, gen.2);
    for (a, b) in [
        (l.shadow_half, g.shadow_half),
        (l.strain, g.strain),
        (l.kinetic, g.kinetic),
        (l.work, g.work),
        (l.damping, g.damping),
    ] {
        assert!(close(a, b), "ledger {a:e} vs {b:e}");
    }
}

#[test]
fn only_regular_grids_take_the_stencil() {
    let mat = Material::plane_strain(2e3, 0.4).unwrap();
    let mut mesh = Rectangle::new(0.0, 0.04, 0.0, 0.02, 20, 10).build().unwrap();
    assert!(Elastodynamic::new(&mesh, mat, 1000.0).unwrap().is_grid());
    mesh.distort(0.2 * 2e-3, 3).unwrap(); // 0.2 h
    let m = Elastodynamic::new(&mesh, mat, 1000.0).unwrap();
    assert!(!m.is_grid() && m.n_element_matrices() > 1);
    // One element in a row and one row of elements: every node is an edge node.
    for (nx, ny) in [(1, 5), (5, 1), (1, 1)] {
        let mesh = Rectangle::new(0.0, 0.01 * nx as f64, 0.0, 0.01 * ny as f64, nx, ny).build().unwrap();
        let m = Elastodynamic::new(&mesh, mat, 1000.0).unwrap();
        assert!(m.is_grid());
        let u = noise(m.n_dofs(), 11);
        let (mut a, mut b) = (vec![0.0; m.n_dofs()], vec![0.0; m.n_dofs()]);
        m.apply_k(&u, &mut a);
        m.apply_k_by_elements(&u, &mut b);
        let worst = a.iter().zip(&b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max);
        assert!(worst < 1e-12 * 2e3, "{nx} x {ny}: {worst:e}");
    }
}

#[test]
fn refuses_other_elements_and_bad_density() {
    let mesh = Rectangle::new(0.0, 1.0, 0.0, 1.0, 2, 2).kind(ElementKind::Tri3).build().unwrap();
    let mat = Material::plane_strain(1.0, 0.3).unwrap();
    let e = Elastodynamic::new(&mesh, mat, 1.0).unwrap_err().to_string();
    assert!(e.contains("qua4") && e.contains("tri3"), "{e}");
    let mesh = Rectangle::new(0.0, 1.0, 0.0, 1.0, 2, 2).build().unwrap();
    let e = Elastodynamic::new(&mesh, mat, -1.0).unwrap_err().to_string();
    assert!(e.contains("density"), "{e}");
}

#[test]
fn damped_critical_step() {
    assert!((critical_dt(4.0, 0.0) - 1.0).abs() < 1e-15);
    // dt_c solves lambda dt^2 + 2 eta lambda dt = 4.
    let (l, eta) = (9.0, 0.1);
    let dt = critical_dt(l, eta);
    assert!((l * dt * dt + 2.0 * eta * l * dt - 4.0).abs() < 1e-12);
    // Heavy damping: the step falls like 1/eta (2 / (eta lambda)), never 0 or inf by
    // cancellation or overflow, and largest_damping inverts it.
    for eta in [1e10, 1e100, 1e200] {
        let dt = critical_dt(l, eta);
        assert!(dt > 0.0 && (dt * eta * l / 2.0 - 1.0).abs() < 1e-9, "{eta}: {dt}");
        assert!((super::largest_damping(l, dt) / eta - 1.0).abs() < 1e-6, "{eta}");
    }
    assert!((super::largest_damping(l, critical_dt(l, 0.1)) - 0.1).abs() < 1e-12);
}

/// The base nodes held by a boundary hook (u, v = 0 there), and a dashpot on the top nodes
/// (force -c v, dissipating c v^2): the hook path against the `fixed` flags.
struct HeldBaseDashpotTop {
    nodes: Vec<usize>,
    base: usize,
    c: f64,
    dissipated: f64,
}

impl Boundary for HeldBaseDashpotTop {
    fn nodes(&self) -> &[usize] {
        &self.nodes
    }
    fn apply(&mut self, s: BoundaryStep<'_>) -> f64 {
        let mut net = 0.0;
        for (j, &k) in self.nodes.iter().enumerate() {
            for i in [2 * k, 2 * k + 1] {
                if j < self.base {
                    s.v[i] = 0.0;
                    s.u_next[i] = 0.0;
                    continue;
                }
                // Implicit in the dashpot, so any c is stable: v+ = (v- + dt f / m (1 - a)) / (1 + a)
                // with a = c dt / (2 m) (c = 0: the stepper's own arithmetic); its work is -c vbar^2 dt.
                let (m, vm) = (s.mass[k], s.v[i]);
                let a = self.c * s.dt / (2.0 * m);
                let vp = ((1.0 - a) * vm + s.dt * s.force(i) * (1.0 / m)) / (1.0 + a);
                let vbar = 0.5 * (vm + vp);
                net -= self.c * vbar * vbar * s.dt;
                s.v[i] = vp;
                s.u_next[i] = s.u[i] + s.dt * vp;
            }
        }
        self.dissipated -= net;
        net
    }
}

#[test]
fn a_boundary_hook_is_the_fixed_flags_bit_for_bit_and_its_work_closes_the_ledger() {
    let mesh = Rectangle::new(0.0, 0.2, 0.0, 0.17, 200, 170).build().unwrap();
    let mut m = Elastodynamic::new(&mesh, Material::plane_strain(2e3, 0.4).unwrap(), 1000.0).unwrap();
    let base: Vec<usize> = (0..mesh.n_nodes()).filter(|&k| mesh.nodes[k][1] == 0.0).collect();
    let top: Vec<usize> = (0..mesh.n_nodes()).filter(|&k| mesh.nodes[k][1] > 0.17 - 1e-9).collect();
    let run = |m: &Elastodynamic, c: f64, threads: usize| {
        let mut m = m.clone();
        m.set_threads(threads);
        let eta = 0.2 / m.lambda_bound.sqrt();
        let dt = 0.9 * m.critical_dt(eta);
        let nodes: Vec<usize> = base.iter().chain(&top).copied().collect();
        let mut hook = HeldBaseDashpotTop { nodes: nodes.clone(), base: base.len(), c, dissipated: 0.0 };
        let mut run = Explicit::new(&m, dt, eta, vec![false; m.n_dofs()]).unwrap().with_boundary(&nodes);
        let u0: Vec<f64> = (0..m.n_dofs())
            .map(|i| {
                if mesh.nodes[i / 2][1] == 0.0 {
                    0.0
                } else {
                    1e-4 * (40.0 * mesh.nodes[i / 2][i % 2]).sin()
                }
            })
            .collect();
        run.set_displacement(&u0);
        let top_dof = m.n_dofs() - 1;
        let mut balance = vec![];
        for _ in 0..40 {
            run.step_with(&mut hook, |t, f| f[top_dof] -= 1e-3 * t);
            balance.push(run.shadow_balance());
        }
        (run.u.clone(), run.v.clone(), run.ledger, balance, hook.dissipated)
    };
    let bits = |a: &[f64], b: &[f64]| a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits());
    // No dashpot: the hook holds the base as the fixed flags do, and every other DOF is the
    // stepper's own update: the same bits, on the fused grid path and the general one, on
    // one thread and two.
    let flags = run_steps(&m, &mesh, 40);
    for threads in [1, 2] {
        let hooked = run(&m, 0.0, threads);
        assert!(bits(&flags.0, &hooked.0) && bits(&flags.1, &hooked.1), "grid, {threads} thread(s)");
        assert_eq!(flags.2.work, hooked.2.work);
    }
    m.grid = None;
    let (flags, hooked) = (run_steps(&m, &mesh, 40), run(&m, 0.0, 1));
    assert!(bits(&flags.0, &hooked.0) && bits(&flags.1, &hooked.1), "general path");
    // With the dashpot: the ledger closes with the hook's reported work (E + D - W - B
    // constant to round-off of the energies), and the dashpot dissipated.
    let (_, _, l, balance, dissipated) = run(&m, 50.0, 1);
    let scale = l.shadow_half.abs() + l.damping + l.work.abs() + dissipated;
    let drift = balance.iter().map(|b| (b - balance[0]).abs()).fold(0.0, f64::max);
    assert!(dissipated > 1e-3 * scale, "{dissipated:e} of {scale:e}");
    assert!(drift <= 1e-12 * scale, "{drift:e} vs {scale:e}");
}
