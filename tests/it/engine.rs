//! Verification of the core engine (issue 2) against closed forms.
//!
//! Reference: standard FE verification (patch test: Irons & Razzaque 1972; manufactured
//! solutions: Roache 2002). Tolerances follow from the theory: fields a mesh can represent
//! exactly are reproduced to round-off (1e-10 relative); convergence rates of QUA4 are 2
//! (L2) and 1 (energy) asymptotically, asserted to +-0.1.

use tribofe::fem::assembly::Model;
use tribofe::fem::constraints::{dof, Constraints};
use tribofe::fem::element::ElementKind;
use tribofe::fem::material::Material;
use tribofe::fem::mesh::Mesh;
use tribofe::fem::mesher::Rectangle;
use tribofe::fem::problem::{solve, LoadCase};
use tribofe::fem::recovery::{elements_touching, error_norms, nodal_stresses};
use tribofe::linalg::solve::SolverOptions;

use crate::common;
use common::boundary;

fn mat() -> Material {
    Material::plane_strain(2e3, 0.4).unwrap()
}

/// Moves interior nodes by a deterministic pseudo-random amount (up to 20 % of h).
fn distort(m: &mut Mesh, h: f64) {
    let fixed = boundary(m);
    let mut s = 12345u64;
    for n in 0..m.n_nodes() {
        s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        if fixed.binary_search(&n).is_err() {
            let r1 = (s >> 33) as f64 / (1u64 << 31) as f64 - 0.5;
            let r2 = ((s >> 13) & 0xFFFFF) as f64 / (1u64 << 20) as f64 - 0.5;
            m.nodes[n][0] += 0.4 * h * r1;
            m.nodes[n][1] += 0.4 * h * r2;
        }
    }
    m.validate().unwrap();
}

/// Constant strain on strongly distorted QUA4 and TRI3 meshes (any straight-sided quadrilateral
/// or triangle passes).
#[test]
fn patch_test_distorted_qua4_and_tri3() {
    for kind in [ElementKind::Qua4, ElementKind::Tri3] {
        let mut mesh = Rectangle::new(0.0, 1.0, 0.0, 1.0, 5, 5).kind(kind).build().unwrap();
        distort(&mut mesh, 0.2);
        common::assert_patch_test(&Model::new(&mesh, mat()), &format!("{kind:?}"));
    }
}

/// Layer [0, w] x [0, t] bonded at y = 0, top displaced by `top`; sides tied periodically
/// (right node = left node at the same height) or on rollers (u = 0).
fn layer(kind: ElementKind, top: [f64; 2], periodic: bool) -> (Mesh, Vec<f64>) {
    let (w, t) = (0.3, 0.02);
    let mut mesh = Rectangle::new(0.0, w, 0.0, t, 7, 3).kind(kind).build().unwrap();
    distort_keep_sides(&mut mesh);
    let mut c = Constraints::new(mesh.n_nodes());
    let mut g = Vec::new();
    for n in mesh.set_nodes("bottom").unwrap() {
        for k in 0..2 {
            c.fix(dof(n, k));
            g.push(0.0);
        }
    }
    for n in mesh.set_nodes("top").unwrap() {
        for k in 0..2 {
            c.fix(dof(n, k));
            g.push(top[k]);
        }
    }
    let (left, right) = (mesh.set_nodes("left").unwrap(), mesh.set_nodes("right").unwrap());
    for (&l, &r) in left.iter().zip(&right) {
        if c.fixed_slot(dof(l, 0)).is_some() {
            continue;
        }
        if periodic {
            c.tie(dof(r, 0), &[(dof(l, 0), 1.0)]);
            c.tie(dof(r, 1), &[(dof(l, 1), 1.0)]);
        } else {
            for n in [l, r] {
                c.fix(dof(n, 0));
                g.push(0.0);
            }
        }
    }
    let model = Model::new(&mesh, mat());
    let sol = solve(&model, &c, &[LoadCase { prescribed: g, forces: vec![] }], &SolverOptions::default(), "")
        .unwrap();
    let u = sol.u[0].clone();
    (mesh, u)
}

/// Interior distortion that keeps the sides straight and at matching heights.
fn distort_keep_sides(m: &mut Mesh) {
    let fixed = boundary(m);
    for n in 0..m.n_nodes() {
        if fixed.binary_search(&n).is_err() {
            m.nodes[n][0] += 0.01 * (7.0 * m.nodes[n][1] / 0.02).sin();
        }
    }
    m.validate().unwrap();
}

#[test]
fn bonded_layer_closed_forms() {
    let m = mat();
    let (g, l) = (m.shear_modulus(), m.lambda());
    let t = 0.02;
    for kind in [ElementKind::Qua4, ElementKind::Tri3] {
        // Shear: tau = G u0 / t everywhere.
        let u0 = 1e-4;
        let (mesh, u) = layer(kind, [u0, 0.0], true);
        let model = Model::new(&mesh, m);
        for s in nodal_stresses(&model, &u) {
            assert!((s[2] - g * u0 / t).abs() < 1e-10 * g * u0 / t, "{kind:?} shear {}", s[2]);
            assert!(s[0].abs() < 1e-10 * g * u0 / t && s[1].abs() < 1e-10 * g * u0 / t);
        }
        // Compression: sigma_yy = -(lambda + 2G) v0 / t, sigma_xx = -lambda v0 / t.
        let v0 = 1e-4;
        let (mesh, u) = layer(kind, [0.0, -v0], false);
        let model = Model::new(&mesh, m);
        let syy = -(l + 2.0 * g) * v0 / t;
        for s in nodal_stresses(&model, &u) {
            assert!((s[1] - syy).abs() < 1e-10 * syy.abs(), "{kind:?} syy {}", s[1]);
            assert!((s[0] + l * v0 / t).abs() < 1e-10 * syy.abs());
            assert!((s[3] + l * v0 / t).abs() < 1e-10 * syy.abs(), "sigma_zz = lambda tr(eps)");
        }
    }
}

#[test]
fn manufactured_solution_rates_qua4() {
    // u = v = sin(pi x) sin(pi y) on the unit square, u = 0 on the boundary, body force b = -div sigma.
    let m = Material::plane_strain(1.0, 0.3).unwrap();
    let sol = tribofe::analytical::manufactured::SineSolution::new(&m);
    let body = move |p: [f64; 2]| sol.body_force(p);
    let exact = move |p: [f64; 2]| sol.exact(p);
    let mut errs = Vec::new();
    for n in [4, 8, 16, 32, 64] {
        let mut mesh = Rectangle::new(0.0, 1.0, 0.0, 1.0, n, n).build().unwrap();
        distort(&mut mesh, 1.0 / n as f64 * 0.25);
        let mut c = Constraints::new(mesh.n_nodes());
        for b in boundary(&mesh) {
            c.fix(dof(b, 0));
            c.fix(dof(b, 1));
        }
        let mut f = vec![0.0; 2 * mesh.n_nodes()];
        tribofe::fem::loads::add_body_force(&mesh, &body, &mut f);
        let model = Model::new(&mesh, m);
        let case = LoadCase { prescribed: vec![0.0; c.n_fixed()], forces: f };
        let sol = solve(&model, &c, &[case], &SolverOptions::default(), "").unwrap();
        errs.push(error_norms(&model, &sol.u[0], &exact));
    }
    let rate = |a: f64, b: f64| (a / b).log2();
    let k = errs.len();
    let (rl2, ren) = (rate(errs[k - 2].0, errs[k - 1].0), rate(errs[k - 2].1, errs[k - 1].1));
    assert!((rl2 - 2.0).abs() < 0.1, "L2 rate {rl2}, errors {errs:?}");
    assert!((ren - 1.0).abs() < 0.1, "energy rate {ren}, errors {errs:?}");
}

#[test]
fn reactions_balance_loads_forces_and_moment() {
    // Cantilever [0, 2] x [0, 0.5] clamped at x = 0, tractions on top and right, one point force.
    let mesh = Rectangle::new(0.0, 2.0, 0.0, 0.5, 20, 5).kind(ElementKind::Qua8).build().unwrap();
    let mut c = Constraints::new(mesh.n_nodes());
    let left = mesh.set_nodes("left").unwrap();
    for &n in &left {
        c.fix(dof(n, 0));
        c.fix(dof(n, 1));
    }
    let mut f = vec![0.0; 2 * mesh.n_nodes()];
    tribofe::fem::loads::add_edge_traction(&mesh, "top", &|p| [0.0, -1e3 * p[0]], &mut f).unwrap();
    tribofe::fem::loads::add_edge_traction(&mesh, "right", &|p| [500.0, 200.0 * p[1]], &mut f).unwrap();
    let corner =
        mesh.nodes.iter().position(|p| (p[0] - 2.0).abs() < 1e-12 && (p[1] - 0.5).abs() < 1e-12).unwrap();
    f[dof(corner, 0)] += 77.0;
    let model = Model::new(&mesh, mat());
    let case = LoadCase { prescribed: vec![0.0; c.n_fixed()], forces: f.clone() };
    let sol = solve(&model, &c, std::slice::from_ref(&case), &SolverOptions::default(), "").unwrap();
    let r = sol.residual_forces(&model, &case, 0, &elements_touching(&model, &left)).unwrap();
    let (mut fx, mut fy, mut mz, mut scale) = (0.0, 0.0, 0.0, 0.0f64);
    for n in 0..mesh.n_nodes() {
        let [x, y] = mesh.nodes[n];
        let (px, py) = if left.contains(&n) { (r[2 * n], r[2 * n + 1]) } else { (f[2 * n], f[2 * n + 1]) };
        fx += px;
        fy += py;
        mz += x * py - y * px;
        scale = scale.max(px.abs()).max(py.abs());
    }
    for (what, v) in [("Fx", fx), ("Fy", fy), ("Mz", mz)] {
        assert!(v.abs() < 1e-10 * scale * mesh.n_nodes() as f64, "{what} = {v}");
    }
}

#[test]
fn free_floating_body_is_a_clear_error() {
    let mesh = Rectangle::new(0.0, 1.0, 0.0, 0.1, 10, 2).build().unwrap();
    let mut f = vec![0.0; 2 * mesh.n_nodes()];
    f[0] = 1.0;
    // Only v fixed along the bottom: free to slide in x.
    let mut c = Constraints::new(mesh.n_nodes());
    for n in mesh.set_nodes("bottom").unwrap() {
        c.fix(dof(n, 1));
    }
    let model = Model::new(&mesh, mat());
    let case = LoadCase { prescribed: vec![0.0; c.n_fixed()], forces: f.clone() };
    let err = solve(&model, &c, &[case], &SolverOptions::default(), "").unwrap_err().to_string();
    assert!(err.contains("free to move"), "{err}");
    // Nothing fixed at all.
    let c = Constraints::new(mesh.n_nodes());
    let err = solve(&model, &c, &[LoadCase { prescribed: vec![], forces: f }], &SolverOptions::default(), "")
        .unwrap_err()
        .to_string();
    assert!(err.contains("free to move"), "{err}");
}

#[test]
fn stiffness_pattern_and_values_reused_across_materials() {
    // Same pattern, material scaled by 10: displacements under a force scale by 1/10.
    let mesh = Rectangle::new(0.0, 1.0, 0.0, 0.2, 8, 2).build().unwrap();
    let mut c = Constraints::new(mesh.n_nodes());
    for n in mesh.set_nodes("left").unwrap() {
        c.fix(dof(n, 0));
        c.fix(dof(n, 1));
    }
    let mut f = vec![0.0; 2 * mesh.n_nodes()];
    f[2 * mesh.n_nodes() - 1] = -1.0;
    let case = LoadCase { prescribed: vec![0.0; c.n_fixed()], forces: f };
    let red = c.reduce().unwrap();
    let asm = tribofe::fem::assembly::Assembler::new(&mesh, &red).unwrap();
    let m1 = Model::new(&mesh, Material::plane_strain(1e3, 0.3).unwrap());
    let m2 = Model::new(&mesh, Material::plane_strain(1e4, 0.3).unwrap());
    let (v1, _) = asm
        .assemble(&m1, &red, std::slice::from_ref(&case.forces), std::slice::from_ref(&case.prescribed))
        .unwrap();
    let (v2, _) = asm
        .assemble(&m2, &red, std::slice::from_ref(&case.forces), std::slice::from_ref(&case.prescribed))
        .unwrap();
    let scale = v2.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for (a, b) in v1.iter().zip(&v2) {
        assert!((b - 10.0 * a).abs() <= 1e-13 * scale, "{a} {b}");
    }
}

#[test]
fn rectangle_problem_balances_and_rejects_bad_sides() {
    use tribofe::scene::rectangle::{RectangleProblem, Side};
    // Clamped bottom, rollers left and right, uniform pressure on top: the bottom carries it all.
    let p = RectangleProblem {
        rect: Rectangle::new(0.0, 1.0, 0.0, 0.1, 20, 4),
        material: mat(),
        element: "qua9".parse().unwrap(),
        sides: [Side::Clamped, Side::Roller, Side::Traction([0.0, -1e3]), Side::Roller],
    };
    let r = p.solve().unwrap();
    assert!((r.applied[1] + 1e3).abs() < 1e-9);
    assert!((r.total_reaction[1] - 1e3).abs() < 1e-9 && r.total_reaction[0].abs() < 1e-9);
    assert!("u=1".parse::<Side>().is_err() && "glued".parse::<Side>().is_err());
    assert_eq!("t=0,-5".parse::<Side>().unwrap(), Side::Traction([0.0, -5.0]));
}
