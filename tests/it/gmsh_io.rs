//! Gmsh reader: every committed mesh in every format (MSH 4.1/2.2, ASCII/binary), the
//! paper's regular block against the structured mesher, and hand-made files for the corners
//! of the format (sparse tags, parametric nodes, skipped sections, big-endian, bad input).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use tribofe::fem::element::ElementKind;
use tribofe::fem::mesh::Mesh;
use tribofe::io::gmsh;
use tribofe::Error;

const FORMATS: [&str; 4] = ["v41_ascii", "v41_bin", "v22_ascii", "v22_bin"];
const L: f64 = 0.2;
const H: f64 = 0.002;

fn meshes_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("meshes")
}

fn read_all(dir: &Path, base: &str) -> Vec<(String, Mesh)> {
    FORMATS
        .iter()
        .map(|f| {
            let path = dir.join(format!("{base}_{f}.msh"));
            (f.to_string(), gmsh::read(&path).unwrap_or_else(|e| panic!("{e}")))
        })
        .collect()
}

/// The mesh in terms of node tags, so files that order nodes or number elements differently compare equal.
#[derive(Debug, PartialEq)]
struct Canonical {
    nodes: BTreeMap<u64, [f64; 2]>,
    elements: Vec<(ElementKind, Vec<u64>)>,
    node_sets: BTreeMap<String, Vec<u64>>,
    edge_sets: BTreeMap<String, Vec<Vec<u64>>>,
    element_set_sizes: BTreeMap<String, usize>,
}

fn canonical(m: &Mesh) -> Canonical {
    let tag = |n: usize| m.node_tag(n);
    let mut elements: Vec<_> = m.elements().map(|(k, v)| (k, v.iter().map(|&n| tag(n)).collect())).collect();
    elements.sort();
    let edge_sets = m
        .edge_sets
        .iter()
        .map(|(k, v)| {
            let mut edges: Vec<Vec<u64>> = v.iter().map(|e| e.nodes().map(tag).collect()).collect();
            edges.sort();
            (k.clone(), edges)
        })
        .collect();
    Canonical {
        nodes: (0..m.n_nodes()).map(|n| (tag(n), m.nodes[n])).collect(),
        elements,
        node_sets: m
            .node_sets
            .iter()
            .map(|(k, v)| (k.clone(), v.iter().map(|&n| tag(n)).collect()))
            .collect(),
        edge_sets,
        element_set_sizes: m.element_sets.iter().map(|(k, v)| (k.clone(), v.len())).collect(),
    }
}

/// All formats hold the same mesh; coordinates agree to the 16 digits Gmsh prints in ASCII.
fn assert_same_across_formats(meshes: &[(String, Mesh)]) {
    let (f0, m0) = &meshes[0];
    let c0 = canonical(m0);
    for (f, m) in &meshes[1..] {
        let c = canonical(m);
        assert_eq!(c.elements, c0.elements, "{f} vs {f0}");
        assert_eq!(c.node_sets, c0.node_sets, "{f} vs {f0}");
        assert_eq!(c.edge_sets, c0.edge_sets, "{f} vs {f0}");
        assert_eq!(c.element_set_sizes, c0.element_set_sizes, "{f} vs {f0}");
        assert_eq!(c.nodes.len(), c0.nodes.len());
        for ((t, p), (t0, p0)) in c.nodes.iter().zip(&c0.nodes) {
            assert_eq!(t, t0);
            assert!(
                (p[0] - p0[0]).abs() < 1e-15 && (p[1] - p0[1]).abs() < 1e-15,
                "{f}: node {t} at {p:?} vs {p0:?}"
            );
        }
    }
}

/// Checks a mesh of the paper's block: area, and each boundary set on its side, end to end.
fn assert_block(m: &Mesh, what: &str) {
    assert!((m.total_area() - 2.0 * L * H).abs() < 1e-12 * L * H, "{what}: area {}", m.total_area());
    assert_eq!(m.element_set("block").unwrap().len(), m.n_elements(), "{what}");
    for (set, on_side) in [
        ("interface", (|p: [f64; 2]| p[1].abs() < 1e-15) as fn([f64; 2]) -> bool),
        ("top", |p| (p[1] - H).abs() < 1e-15),
        ("left", |p| (p[0] + L).abs() < 1e-15),
        ("right", |p| (p[0] - L).abs() < 1e-15),
    ] {
        let nodes = m.set_nodes(set).unwrap();
        assert!(nodes.iter().all(|&n| on_side(m.nodes[n])), "{what}: a node of '{set}' is off its side");
        // The edges cover the side exactly once: their lengths add up to its length.
        let length: f64 = m
            .edges(set)
            .unwrap()
            .iter()
            .map(|e| {
                (m.nodes[e.ends[0]][0] - m.nodes[e.ends[1]][0])
                    .hypot(m.nodes[e.ends[0]][1] - m.nodes[e.ends[1]][1])
            })
            .sum();
        let expected = if matches!(set, "interface" | "top") { 2.0 * L } else { H };
        assert!(
            (length - expected).abs() < 1e-12,
            "{what}: '{set}' edges add up to {length}, not {expected}"
        );
    }
    let xs: Vec<f64> = m.set_nodes("interface").unwrap().iter().map(|&n| m.nodes[n][0]).collect();
    let (lo, hi) = xs.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &x| (lo.min(x), hi.max(x)));
    assert!((lo + L).abs() < 1e-15 && (hi - L).abs() < 1e-15, "{what}: interface spans [{lo}, {hi}]");
}

#[test]
fn regular_block_in_every_format() {
    let meshes = read_all(&meshes_dir(), "block_regular");
    assert_same_across_formats(&meshes);
    for (f, m) in &meshes {
        assert_eq!((m.n_nodes(), m.n_elements()), (401 * 3, 400 * 2), "{f}");
        assert_eq!(m.kinds_present(), [ElementKind::Qua4]);
        assert_eq!(m.set_nodes("interface").unwrap().len(), 401);
        assert_block(m, f);
    }
}

#[test]
fn graded_block_in_every_format() {
    let meshes = read_all(&meshes_dir(), "block_graded");
    assert_same_across_formats(&meshes);
    for (f, m) in &meshes {
        assert_eq!((m.n_nodes(), m.n_elements()), (631 * 5, 630 * 4), "{f}");
        assert_block(m, f);
        let sizes: Vec<f64> = m
            .edges("interface")
            .unwrap()
            .iter()
            .map(|e| (m.nodes[e.ends[0]][0] - m.nodes[e.ends[1]][0]).abs())
            .collect();
        let (min, max) = sizes.iter().fold((f64::INFINITY, 0.0f64), |(a, b), &h| (a.min(h), b.max(h)));
        assert!(
            (0.9e-4..1.1e-4).contains(&min) && (1.8e-3..2.2e-3).contains(&max),
            "{f}: sizes {min}..{max}"
        );
    }
}

#[test]
fn unstructured_block_in_every_format() {
    let meshes = read_all(&meshes_dir(), "block_unstructured");
    assert_same_across_formats(&meshes);
    for (f, m) in &meshes {
        assert_eq!(m.kinds_present(), [ElementKind::Tri3, ElementKind::Qua4], "{f}: quad-dominant, mixed");
        assert_eq!((m.n_nodes(), m.n_elements()), (4671, 1198 + 3323), "{f}");
        assert_block(m, f);
    }
}

/// Nodes sorted by (y, x) (y to 1 nm: Gmsh's rows are not exactly level), elements as corner lists rotated to start at their smallest node, sorted.
fn sorted_grid(m: &Mesh) -> (Vec<[f64; 2]>, Vec<Vec<usize>>) {
    let mut order: Vec<usize> = (0..m.n_nodes()).collect();
    let row = |n: usize| (m.nodes[n][1] * 1e9).round() as i64;
    order.sort_by(|&a, &b| row(a).cmp(&row(b)).then(m.nodes[a][0].total_cmp(&m.nodes[b][0])));
    let mut rank = vec![0; m.n_nodes()];
    order.iter().enumerate().for_each(|(r, &n)| rank[n] = r);
    let mut elements: Vec<Vec<usize>> = m
        .elements()
        .map(|(_, v)| {
            let mut v: Vec<usize> = v.iter().map(|&n| rank[n]).collect();
            let first = (0..v.len()).min_by_key(|&i| v[i]).unwrap();
            v.rotate_left(first);
            v
        })
        .collect();
    elements.sort();
    (order.iter().map(|&n| m.nodes[n]).collect(), elements)
}

#[test]
fn regular_block_matches_the_structured_mesher() {
    let reference = tribofe::fem::mesher::Rectangle::new(-L, L, 0.0, H, 400, 2).build().unwrap();
    let (ref_nodes, ref_elements) = sorted_grid(&reference);
    for (f, m) in read_all(&meshes_dir(), "block_regular") {
        let (nodes, elements) = sorted_grid(&m);
        assert_eq!(nodes.len(), ref_nodes.len());
        for (p, q) in nodes.iter().zip(&ref_nodes) {
            // Gmsh's transfinite interpolation strays ~1e-13 m from i * 1 mm.
            assert!((p[0] - q[0]).abs() < 1e-12 && (p[1] - q[1]).abs() < 1e-12, "{f}: {p:?} vs {q:?}");
        }
        assert_eq!(elements, ref_elements, "{f}");
    }
}

/// Mid nodes of every element edge sit halfway between its corners (straight-sided meshes):
/// checks that Gmsh's local numbering of quadratic elements is read as ours.
fn assert_mid_nodes_halfway(m: &Mesh, what: &str) {
    for e in 0..m.n_elements() {
        let (kind, v) = (m.kind(e), m.element_nodes(e));
        for edge in kind.edges() {
            let (a, b, mid) = (m.nodes[v[edge[0]]], m.nodes[v[edge[1]]], m.nodes[v[edge[2]]]);
            assert!(
                (mid[0] - 0.5 * (a[0] + b[0])).abs() < 1e-12 && (mid[1] - 0.5 * (a[1] + b[1])).abs() < 1e-12,
                "{what}: {}",
                m.describe_element(e)
            );
        }
        if kind == ElementKind::Qua9 {
            let c: [f64; 2] = [0, 1].map(|i| v[..4].iter().map(|&n| m.nodes[n][i]).sum::<f64>() / 4.0);
            assert!(
                (m.nodes[v[8]][0] - c[0]).abs() < 1e-12 && (m.nodes[v[8]][1] - c[1]).abs() < 1e-12,
                "{what}"
            );
        }
    }
}

#[test]
fn tiny_meshes_in_every_format() {
    let dir = meshes_dir().join("tiny");
    let mixed = read_all(&dir, "tiny_mixed");
    assert_same_across_formats(&mixed);
    for (f, m) in &mixed {
        assert_eq!(m.kinds_present(), [ElementKind::Tri3, ElementKind::Qua4], "{f}");
        assert!((m.total_area() - 0.004 * 0.002).abs() < 1e-18, "{f}");
        assert_eq!(m.node_sets["corner"].len(), 1);
        assert_eq!(m.nodes[m.node_sets["corner"][0]], [0.0, 0.0], "{f}");
        assert!(m.edge_sets.contains_key("physical_1_7"), "{f}: unnamed group");
        let left = m.element_set("left_part").unwrap();
        assert!(!left.is_empty() && left.len() < m.element_set("block").unwrap().len());
        assert!(left.iter().all(|&e| m.element_coords(e).iter().all(|p| p[0] <= 0.002 + 1e-15)), "{f}");
    }
    for (base, kinds) in [
        ("tiny_quadratic", [ElementKind::Tri6, ElementKind::Qua9]),
        ("tiny_serendipity", [ElementKind::Tri6, ElementKind::Qua8]),
    ] {
        let meshes = read_all(&dir, base);
        assert_same_across_formats(&meshes);
        for (f, m) in &meshes {
            assert_eq!(m.kinds_present(), kinds, "{base} {f}");
            assert!((m.total_area() - 0.004 * 0.002).abs() < 1e-18);
            assert_mid_nodes_halfway(m, f);
            let edges = m.edges("interface").unwrap();
            assert!(!edges.is_empty());
            for e in edges {
                // Gmsh line3: end, end, mid.
                let (a, b, c) =
                    (m.nodes[e.ends[0]], m.nodes[e.ends[1]], m.nodes[e.mid.expect("line3 has a mid node")]);
                assert!(
                    a[1] == 0.0 && b[1] == 0.0 && (c[0] - 0.5 * (a[0] + b[0])).abs() < 1e-12,
                    "{base} {f}: {a:?} {b:?} {c:?}"
                );
            }
        }
    }
}

/// Regenerates every mesh with the installed gmsh and reads the fresh files.
#[test]
fn regenerated_meshes_read() {
    if std::process::Command::new("gmsh").arg("--version").output().is_err() {
        eprintln!("skipped: gmsh is not on PATH (apt-get install -y gmsh to run this test)");
        return;
    }
    let out = tempfile::tempdir().unwrap();
    let status = std::process::Command::new("bash")
        .arg(meshes_dir().join("regenerate.sh"))
        .arg(out.path())
        .status()
        .unwrap();
    assert!(status.success());
    for (base, counts) in [
        ("block_regular", Some((1203, 800))),
        ("block_graded", Some((3155, 2520))),
        ("block_unstructured", None),
    ] {
        let meshes = read_all(out.path(), base);
        assert_same_across_formats(&meshes);
        for (f, m) in &meshes {
            assert_block(m, &format!("fresh {base} {f}"));
            if let Some(c) = counts {
                assert_eq!((m.n_nodes(), m.n_elements()), c, "fresh {base} {f}");
            }
        }
    }
    for base in ["tiny_mixed", "tiny_quadratic", "tiny_serendipity"] {
        assert_same_across_formats(&read_all(out.path(), base));
    }
}

// ---- hand-made files -------------------------------------------------------------------

fn parse(text: &str) -> tribofe::Result<Mesh> {
    gmsh::parse(text.as_bytes(), Path::new("hand.msh"))
}

fn parse_err(text: &str) -> String {
    match parse(text) {
        Err(e @ Error::Parse { .. }) | Err(e @ Error::Mesh(_)) => e.to_string(),
        other => panic!("expected a parse or mesh error, got {other:?}"),
    }
}

/// Two QUA4 side by side with sparse node tags (from 100), one unused node (tag 7, on a
/// parametric curve block), sections to skip, a 1D group on y = 0 and an unnamed 0D group.
const SPARSE_41: &str = r#"$MeshFormat
4.1 0 8
$EndMeshFormat
$Comments
anything $Nodes here is ignored
$EndComments
$PhysicalNames
2
1 5 "bottom"
2 9 "solid"
$EndPhysicalNames
$Entities
1 1 1 0
3 0 0 0 1 4
11 0 0 0 2 0 0 1 5 0
21 0 0 0 2 1 0 1 9 0
$EndEntities
$Nodes
3 7 7 500
0 3 0 1
100
0 0 0
1 11 1 2
300
7
1 0 0 0.5
5 5 0 1
2 21 0 4
200
400
350
500
2 0 0
0 1 0
1 1 0
2 1 0
$EndNodes
$Elements
3 5 1 60
1 11 1 2
10 100 300
11 300 200
2 21 3 2
50 100 300 350 400
60 300 200 500 350
0 3 15 1
1 100
$EndElements
$NodeData
1
"u"
$EndNodeData
$Unknown
stuff
$EndUnknown
"#;

#[test]
fn sparse_tags_parametric_nodes_and_skipped_sections() {
    let m = parse(SPARSE_41).unwrap();
    assert_eq!(m.n_nodes(), 6, "node 7 (not in any 2D element) is dropped");
    assert_eq!(m.n_elements(), 2);
    let tags = m.node_tags.as_ref().unwrap();
    assert_eq!(tags, &[100, 300, 200, 400, 350, 500]);
    assert_eq!(m.element_tags.as_deref(), Some(&[50, 60][..]));
    assert_eq!(m.nodes[1], [1.0, 0.0], "parametric value skipped");
    assert_eq!(m.nodes[5], [2.0, 1.0]);
    assert_eq!(m.element_set("solid").unwrap(), &[0, 1]);
    let bottom: Vec<u64> = m.set_nodes("bottom").unwrap().iter().map(|&n| m.node_tag(n)).collect();
    assert_eq!(bottom, [100, 300, 200]);
    assert_eq!(m.node_sets["physical_0_4"].iter().map(|&n| m.node_tag(n)).collect::<Vec<_>>(), [100]);
    assert!((m.total_area() - 2.0).abs() < 1e-15);
}

#[test]
fn clockwise_elements_are_reoriented() {
    let text = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n$EndNodes\n$Elements\n1\n1 3 2 0 1 1 4 3 2\n$EndElements\n";
    let m = parse(text).unwrap();
    assert!((m.total_area() - 1.0).abs() < 1e-15);
    assert!(m.min_jacobian(0) > 0.0);
}

#[test]
fn msh22_element_in_two_groups_is_one_element() {
    let text = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n$EndNodes\n$Elements\n2\n1 2 2 4 1 1 2 3\n2 2 2 6 1 1 2 3\n$EndElements\n";
    let m = parse(text).unwrap();
    assert_eq!(m.n_elements(), 1);
    assert_eq!(m.element_set("physical_2_4").unwrap(), &[0]);
    assert_eq!(m.element_set("physical_2_6").unwrap(), &[0]);
}

/// A binary MSH 4.1 file (size_t = 8) of two QUA4 in the given byte order, tags sparse.
fn binary_41(big: bool) -> Vec<u8> {
    let mut b = b"$MeshFormat\n4.1 1 8\n".to_vec();
    let i32_ = |b: &mut Vec<u8>, v: i32| b.extend(if big { v.to_be_bytes() } else { v.to_le_bytes() });
    let u64_ = |b: &mut Vec<u8>, v: u64| b.extend(if big { v.to_be_bytes() } else { v.to_le_bytes() });
    let f64_ = |b: &mut Vec<u8>, v: f64| b.extend(if big { v.to_be_bytes() } else { v.to_le_bytes() });
    i32_(&mut b, 1);
    b.extend(b"\n$EndMeshFormat\n$PhysicalNames\n1\n2 3 \"solid\"\n$EndPhysicalNames\n$Entities\n");
    [0, 0, 1, 0].iter().for_each(|&n| u64_(&mut b, n));
    i32_(&mut b, 8);
    [0.0, 0.0, 0.0, 2.0, 1.0, 0.0].iter().for_each(|&x| f64_(&mut b, x));
    u64_(&mut b, 1);
    i32_(&mut b, 3);
    u64_(&mut b, 0);
    b.extend(b"\n$EndEntities\n$Nodes\n");
    [1, 6, 10, 60].iter().for_each(|&n| u64_(&mut b, n));
    i32_(&mut b, 2);
    i32_(&mut b, 8);
    i32_(&mut b, 1); // parametric: u, v follow each node
    u64_(&mut b, 6);
    [10, 20, 30, 40, 50, 60].iter().for_each(|&t| u64_(&mut b, t));
    for p in [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [0.0, 1.0], [1.0, 1.0], [2.0, 1.0]] {
        [p[0], p[1], 0.0, 0.25, 0.75].iter().for_each(|&x| f64_(&mut b, x));
    }
    b.extend(b"\n$EndNodes\n$Elements\n");
    [1, 2, 7, 8].iter().for_each(|&n| u64_(&mut b, n));
    i32_(&mut b, 2);
    i32_(&mut b, 8);
    i32_(&mut b, 3);
    u64_(&mut b, 2);
    [7, 10, 20, 50, 40, 8, 20, 30, 60, 50].iter().for_each(|&n| u64_(&mut b, n));
    b.extend(b"\n$EndElements\n");
    b
}

/// The same mesh as binary MSH 2.2 in the given byte order.
fn binary_22(big: bool) -> Vec<u8> {
    let mut b = b"$MeshFormat\n2.2 1 8\n".to_vec();
    let i32_ = |b: &mut Vec<u8>, v: i32| b.extend(if big { v.to_be_bytes() } else { v.to_le_bytes() });
    let f64_ = |b: &mut Vec<u8>, v: f64| b.extend(if big { v.to_be_bytes() } else { v.to_le_bytes() });
    i32_(&mut b, 1);
    b.extend(b"\n$EndMeshFormat\n$PhysicalNames\n1\n2 3 \"solid\"\n$EndPhysicalNames\n$Nodes\n6\n");
    for (t, p) in [10, 20, 30, 40, 50, 60].iter().zip([
        [0.0, 0.0],
        [1.0, 0.0],
        [2.0, 0.0],
        [0.0, 1.0],
        [1.0, 1.0],
        [2.0, 1.0],
    ]) {
        i32_(&mut b, *t);
        [p[0], p[1], 0.0].iter().for_each(|&x| f64_(&mut b, x));
    }
    b.extend(b"\n$EndNodes\n$Elements\n2\n");
    [3, 2, 2].iter().for_each(|&n| i32_(&mut b, n)); // type, count, tags per element
    [7, 3, 8, 10, 20, 50, 40, 8, 3, 8, 20, 30, 60, 50].iter().for_each(|&n| i32_(&mut b, n));
    b.extend(b"\n$EndElements\n");
    b
}

#[test]
fn binary_files_in_both_byte_orders() {
    for (what, bytes) in [
        ("4.1 LE", binary_41(false)),
        ("4.1 BE", binary_41(true)),
        ("2.2 LE", binary_22(false)),
        ("2.2 BE", binary_22(true)),
    ] {
        let m = gmsh::parse(&bytes, Path::new("b.msh")).unwrap_or_else(|e| panic!("{what}: {e}"));
        assert_eq!((m.n_nodes(), m.n_elements()), (6, 2), "{what}");
        assert_eq!(m.node_tags.as_deref(), Some(&[10, 20, 30, 40, 50, 60][..]), "{what}");
        assert_eq!(m.nodes[5], [2.0, 1.0], "{what}");
        assert_eq!(m.element_tags.as_deref(), Some(&[7, 8][..]), "{what}");
        assert_eq!(m.element_set("solid").unwrap(), &[0, 1], "{what}");
        assert!((m.total_area() - 2.0).abs() < 1e-15, "{what}");
    }
}

#[test]
fn bad_input_is_named_with_its_line_or_byte() {
    let good = SPARSE_41.to_string();
    let line_of = |needle: &str| good[..good.find(needle).unwrap()].matches('\n').count() + 1;
    let cases: Vec<(String, String)> = vec![
        (good.replace("10 100 300", "10 100 999"), format!("line {}: node tag 999 is used by an element but not defined", line_of("10 100 300"))),
        (good.replace("2 21 3 2", "2 21 4 2"), format!("line {}: Gmsh element type 4 is not supported; supported types: 15 (point)", line_of("2 21 3 2"))),
        (good.replace("3 5 1 60", "3 6 1 60"), "the header announces 6 elements but the blocks hold 5".into()),
        (good.replace("0 1 0\n1 1 0", "0 x 0\n1 1 0"), format!("line {}: expected y, found 'x'", line_of("0 1 0\n1 1 0"))),
        (good.replace("0 1 0\n1 1 0", "0 nan 0\n1 1 0"), "y is NaN".into()),
        (good.replace("0 3 15 1\n1 100", "0 3 15 1\n1 7"), "node tag 7 in set 'physical_0_4' is not connected to any 2D element".into()),
        (good.replace("4.1 0 8", "4.0 0 8"), "line 2: MSH version '4.0' is not supported".into()),
        (good[..good.find("$EndNodes").unwrap() - 10].to_string(), "unexpected end of file".into()),
        (good.replace("$EndElements", "$EndElementz"), "expected $EndElements, found '$EndElementz'".into()),
        (good.replace("$Unknown\nstuff\n$EndUnknown\n", "$Unknown\nstuff\n"), "section $Unknown has no $EndUnknown".into()),
        (good.replace("\n300\n7\n", "\n300\n300\n"), "node tag 300 is defined twice".into()),
        ("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n".into(), "the file defines no nodes".into()),
        ("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n2\n1 0 0 0\n2 1 0 0\n$EndNodes\n$Elements\n1\n1 1 2 1 1 1 2\n$EndElements\n".into(), "no 2D elements".into()),
        ("hello".into(), "hand.msh: line 1: not a Gmsh mesh".into()),
        ("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 2 0 0\n$EndNodes\n$Elements\n1\n5 2 0 1 2 3\n$EndElements\n".into(), "hand.msh: element 5 (tri3, nodes 1, 2, 3) is degenerate".into()),
    ];
    for (text, expected) in cases {
        let msg = parse_err(&text);
        assert!(msg.contains(&expected), "expected '{expected}' in: {msg}");
    }
    let mut bin = binary_41(false);
    bin.truncate(bin.len() - 30);
    let msg = gmsh::parse(&bin, Path::new("b.msh")).unwrap_err().to_string();
    assert!(msg.starts_with("b.msh: byte ") && msg.contains("unexpected end of file"), "{msg}");
    let mut marker = binary_41(false);
    marker[20] = 2;
    assert!(gmsh::parse(&marker, Path::new("b.msh"))
        .unwrap_err()
        .to_string()
        .contains("byte 20: bad endianness marker"));
}

#[test]
fn huge_counts_do_not_allocate() {
    // Counts near u64::MAX with no data behind them must fail at the end of the file, fast.
    let text = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 18446744073709551615 1 2\n2 1 0 18446744073709551615\n1\n";
    assert!(parse_err(text).contains("unexpected end of file"));
    let mut b = binary_41(false);
    let at = b.windows(7).position(|w| w == b"$Nodes\n").unwrap() + 7;
    b[at..at + 16].copy_from_slice(&[0xff; 16]);
    assert!(gmsh::parse(&b, Path::new("b.msh")).is_err());
}
