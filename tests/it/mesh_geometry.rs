//! Meshes that passed the consistency checks but are not the block (issue 45): a hole (tau(0)
//! ~ 0 instead of 0.409), an internal slit, hanging nodes (tau(0) 0.377 and -0.036 at
//! F/N = 0). The hole is refused unless `--geometry file` (or `[mesh] geometry = "file"`)
//! declares it intended, and then every verdict says the paper's model does not describe it;
//! slits and hanging nodes are refused always, naming the place. The committed meshes pass.

use crate::common;

use common::process::{run, Ran};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Duration;
use tribofe::fem::mesh_check::{check_block, check_coincident, check_connected, check_shape, sides};

/// Far above these runs' cost (well under a second each), far below a hang.
const LIMIT: Duration = Duration::from_secs(120);

/// The blocks here: 20 mm x 2 mm (`--length 0.02 --thickness 0.002`).
const L: f64 = 0.02;
const T: f64 = 0.002;
const GEO: [&str; 4] = ["--length", "0.02", "--thickness", "0.002"];

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("tribofe_mesh_geometry_{}_{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Nodes as (tag, x, y).
type Nodes = Vec<(usize, f64, f64)>;

/// A QUA4 block as MSH 2.2 ASCII: nodes (tag, x, y) (only those of elements are written),
/// quads by node tag, groups `interface` (the quad sides on y = 0), `top` (on y = t), `block`.
fn write_msh(path: &Path, nodes: &[(usize, f64, f64)], quads: &[[usize; 4]]) {
    let pos = |tag: usize| nodes.iter().find(|n| n.0 == tag).map(|n| (n.1, n.2)).unwrap();
    let mut used: Vec<usize> = quads.iter().flatten().copied().collect();
    used.sort_unstable();
    used.dedup();
    let mut lines = Vec::new();
    for (phys, y) in [(1, 0.0), (2, T)] {
        for q in quads {
            for k in 0..4 {
                let (a, b) = (q[k], q[(k + 1) % 4]);
                if pos(a).1 == y && pos(b).1 == y {
                    lines.push((phys, a, b));
                }
            }
        }
    }
    let mut s = String::from("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n");
    s += "$PhysicalNames\n3\n1 1 \"interface\"\n1 2 \"top\"\n2 3 \"block\"\n$EndPhysicalNames\n";
    let _ = writeln!(s, "$Nodes\n{}", used.len());
    for &n in &used {
        let (x, y) = pos(n);
        let _ = writeln!(s, "{n} {x:e} {y:e} 0");
    }
    let _ = writeln!(s, "$EndNodes\n$Elements\n{}", lines.len() + quads.len());
    let mut k = 0;
    for (phys, a, b) in &lines {
        k += 1;
        let _ = writeln!(s, "{k} 1 2 {phys} {phys} {a} {b}");
    }
    for q in quads {
        k += 1;
        let _ = writeln!(s, "{k} 3 2 3 3 {} {} {} {}", q[0], q[1], q[2], q[3]);
    }
    s += "$EndElements\n";
    std::fs::write(path, s).unwrap();
}

/// The regular nx x ny grid on [x0, x0 + w] x [0, t], node tags from `first` row by row.
fn grid(x0: f64, w: f64, nx: usize, ny: usize, first: usize) -> Nodes {
    let mut v = Vec::new();
    for j in 0..=ny {
        for i in 0..=nx {
            v.push((first + j * (nx + 1) + i, x0 + w * i as f64 / nx as f64, T * j as f64 / ny as f64));
        }
    }
    v
}

/// 20 x 4 QUA4 (1 mm x 0.5 mm), node (i, j) tagged j 21 + i + 1; `skip` leaves out elements.
fn block_20x4(skip: impl Fn(usize, usize) -> bool) -> (Nodes, Vec<[usize; 4]>) {
    let nodes = grid(-L / 2.0, L, 20, 4, 1);
    let n = |i: usize, j: usize| 1 + j * 21 + i;
    let quads = (0..4)
        .flat_map(|j| (0..20).map(move |i| (i, j)))
        .filter(|&(i, j)| !skip(i, j))
        .map(|(i, j)| [n(i, j), n(i + 1, j), n(i + 1, j + 1), n(i, j + 1)])
        .collect();
    (nodes, quads)
}

/// A 2 mm x 1 mm hole in the middle of the thickness: elements i = 9, 10 of rows j = 1, 2
/// (5 % of L t).
fn hole(path: &Path) {
    let (nodes, quads) = block_20x4(|i, j| (9..=10).contains(&i) && (1..=2).contains(&j));
    write_msh(path, &nodes, &quads);
}

/// A slit (delamination) at y = t/2 from x = -5 mm to 5 mm, inside the block: the elements
/// below it use their own copies (tags 1000 + i) of the nodes strictly between its tips.
fn slit(path: &Path) {
    let (mut nodes, mut quads) = block_20x4(|_, _| false);
    for i in 6..=14 {
        nodes.push((1000 + i, -L / 2.0 + L * i as f64 / 20.0, T / 2.0));
    }
    // Row j = 1 (elements 20..40) lies below the slit: its top corners (2, 3) take the copies.
    for q in quads[20..40].iter_mut() {
        for k in [2, 3] {
            let i = (q[k] - 1) % 21;
            if (6..=14).contains(&i) {
                q[k] = 1000 + i;
            }
        }
    }
    write_msh(path, &nodes, &quads);
}

/// Non-conforming halves: x < 0 in 10 x 4 elements (1 mm x 0.5 mm), x > 0 in 5 x 2 (2 mm x
/// 1 mm), sharing the nodes at x = 0, y = 0, t/2, t; the left's nodes at y = t/4, 3t/4 hang on
/// the right's sides.
fn hanging(path: &Path) {
    let left = grid(-L / 2.0, L / 2.0, 10, 4, 1); // tags 1..=55, (i, j) -> 1 + 11 j + i
    let mut right = grid(0.0, L / 2.0, 5, 2, 100); // tags 100..=117, (i, j) -> 100 + 6 j + i
    let shared = |j: usize| 1 + 11 * (2 * j) + 10; // the left's node at x = 0, y = j t/2
    right.retain(|n| (n.0 - 100) % 6 != 0);
    let r = |i: usize, j: usize| if i == 0 { shared(j) } else { 100 + 6 * j + i };
    let l = |i: usize, j: usize| 1 + 11 * j + i;
    let mut quads = Vec::new();
    for j in 0..4 {
        for i in 0..10 {
            quads.push([l(i, j), l(i + 1, j), l(i + 1, j + 1), l(i, j + 1)]);
        }
    }
    for j in 0..2 {
        for i in 0..5 {
            quads.push([r(i, j), r(i + 1, j), r(i + 1, j + 1), r(i, j + 1)]);
        }
    }
    let nodes: Vec<_> = left.into_iter().chain(right).collect();
    write_msh(path, &nodes, &quads);
}

fn check(args: &[&str], out: &Path) -> Ran {
    let mut a = vec!["check"];
    a.extend(args);
    a.extend(GEO);
    a.extend(["--no-fields", "--out", out.to_str().unwrap()]);
    run(&a, LIMIT)
}

fn refused(r: &Ran, says: &[&str]) {
    assert_eq!(r.code, 2, "exit {}, stderr {}", r.code, r.stderr);
    // After the warning of --geometry file, if given.
    assert!(r.stderr.lines().any(|l| l.starts_with("error: mesh:")), "{}", r.stderr);
    for s in says {
        assert!(r.stderr.contains(s), "must say {s}: {}", r.stderr);
    }
}

#[test]
fn a_hole_is_refused_unless_the_geometry_is_the_files() {
    let d = dir("hole");
    let msh = d.join("hole.msh");
    hole(&msh);
    let m = msh.to_str().unwrap();
    // Refused by default, with the area and the missing share, a side of the hole, and the way out.
    let r = check(&["--mesh", m], &d.join("out"));
    refused(
        &r,
        &[
            "hole.msh",
            "not the scene's L x t rectangle",
            "3.800000e-5 m^2",
            "5.0000 % less",
            "lies inside the block",
            "--geometry file",
            "[mesh] geometry = \"file\"",
        ],
    );
    assert!(!d.join("out").exists(), "a refused run writes nothing");
    // Declared: accepted, and the verdict and run.toml say the paper's model does not describe it.
    let out = d.join("file");
    let r = check(&["--mesh", m, "--geometry", "file"], &out);
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert!(r.stdout.contains("geometry: the mesh file's own"), "{}", r.stdout);
    assert!(r.stdout.contains("its elements cover 0.950000 of L t"), "{}", r.stdout);
    assert!(r.stdout.contains("the paper's model does not describe it"), "{}", r.stdout);
    assert!(r.stderr.contains("warning: geometry: the mesh file's own"), "{}", r.stderr);
    let toml = std::fs::read_to_string(out.join("run.toml")).unwrap();
    assert!(
        toml.contains("geometry = \"the mesh file's own (mesh.geometry = file), not the L x t block"),
        "{toml}"
    );
    assert!(toml.contains("geometry = \"file\""), "the scene key: {toml}");
    // The scene key does the same.
    let scene = d.join("scene.toml");
    std::fs::write(&scene, format!("[mesh]\nfile = {m:?}\ngeometry = \"file\"\n")).unwrap();
    let r = check(&["--scene", scene.to_str().unwrap()], &d.join("key"));
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert!(r.stdout.contains("geometry: the mesh file's own"), "{}", r.stdout);
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn geometry_file_needs_a_mesh_file() {
    let d = dir("nofile");
    let r = check(&["--geometry", "file"], &d.join("out"));
    assert_eq!(r.code, 2, "{}", r.stderr);
    assert!(r.stderr.contains("mesh.geometry (--geometry)") && r.stderr.contains("--mesh"), "{}", r.stderr);
    let r = check(&["--geometry", "hole"], &d.join("out"));
    assert_eq!(r.code, 2, "{}", r.stderr);
    assert!(r.stderr.contains("use block or file"), "{}", r.stderr);
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_slit_is_refused_naming_its_place_whatever_the_geometry() {
    let d = dir("slit");
    let msh = d.join("slit.msh");
    slit(&msh);
    for extra in [&[][..], &["--geometry", "file"]] {
        let mut a = vec!["--mesh", msh.to_str().unwrap()];
        a.extend(extra);
        let r = check(&a, &d.join("out"));
        // The first face node of the slit, at x = -4 mm, y = t/2, and its copy.
        refused(
            &r,
            &["two nodes at the same point", "slit", "node 49 at (-4.000000e-3, 1.000000e-3) m", "node 1006"],
        );
    }
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn hanging_nodes_are_refused_naming_the_node_whatever_the_geometry() {
    let d = dir("hanging");
    let msh = d.join("hanging.msh");
    hanging(&msh);
    for extra in [&[][..], &["--geometry", "file"]] {
        let mut a = vec!["--mesh", msh.to_str().unwrap()];
        a.extend(extra);
        let r = check(&a, &d.join("out"));
        // The left's node at (0, t/4) on the first right element's side from (0, 0) to (0, t/2).
        refused(
            &r,
            &[
                "not conforming",
                "node 22 at (0.000000e0, 5.000000e-4) m",
                "hanging node",
                "element 71 (qua4, nodes 11, 101, 107, 33)",
            ],
        );
    }
    let _ = std::fs::remove_dir_all(&d);
}

/// Every committed mesh (meshes/, meshes/tiny/, four encodings each) and the control of
/// tests/data pass every consistency check, the shape's included, as the L x t block (those
/// without a `top` group, two of the tiny ones, all but the groups').
#[test]
fn committed_meshes_are_the_block() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files: Vec<PathBuf> = ["meshes", "meshes/tiny"]
        .iter()
        .flat_map(|d| std::fs::read_dir(root.join(d)).unwrap().map(|e| e.unwrap().path()))
        .filter(|p| p.extension().is_some_and(|e| e == "msh"))
        .collect();
    files.push(root.join("tests/data/good.msh"));
    files.sort();
    assert_eq!(files.len(), 25, "{files:?}");
    for f in &files {
        let m = tribofe::io::gmsh::read(f).unwrap().restrict_to("block").unwrap();
        let t = m.nodes.iter().fold(0.0f64, |a, p| a.max(p[1]));
        let checked = if m.edge_sets.contains_key("top") {
            check_block(&m, "block", "interface", "top", t, false)
        } else {
            check_connected(&m, "block")
                .and_then(|_| check_coincident(&m, "block"))
                .and_then(|_| check_shape(&m, &sides(&m), "block", t, 1e-6 * t, false))
        };
        checked.unwrap_or_else(|e| panic!("{}: {e}", f.display()));
    }
}
